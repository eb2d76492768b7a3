"""Nonlinear single-track model: planar motion with any tire law, from standstill to the limit.

Equations (SAE J670 vehicle axes: x forward, y right, z down; positive steer turns right; the
two tires of an axle are lumped on the centre line, each carrying half the axle load)::

    m (du/dt - v r) = F_xf cos(d_f) - F_yf sin(d_f) + F_xr cos(d_r) - F_yr sin(d_r) - F_drag
    m (dv/dt + u r) = F_xf sin(d_f) + F_yf cos(d_f) + F_xr sin(d_r) + F_yr cos(d_r) + F_ext
    I_z dr/dt       = a (F_xf sin(d_f) + F_yf cos(d_f)) - b (F_xr sin(d_r) + F_yr cos(d_r)) + M_ext
    dX/dt = u cos(psi) - v sin(psi),   dY/dt = u sin(psi) + v cos(psi),   dpsi/dt = r

(Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 1.3, eq. 1.43 with the forces
resolved through the steer angles; Rajamani, *Vehicle Dynamics and Control*, 2nd ed., 2012,
sec. 2.3 and 2.5; X, Y earth-fixed in SAE orientation: Y to the right of the initial heading).
F_x, F_y are the axle forces in wheel axes (SAE), F_drag = 0.5 rho c_x A u|u|, F_ext and M_ext
the external lateral force and yaw moment at the CG: the inputs ``external_lateral_force`` and
``external_yaw_moment`` plus the crosswind's F_w = 0.5 rho A C_Y' (u^2 + w^2) atan(w / |u|) at the
centre of pressure x_p ahead of the CG (moment x_p F_w; input ``wind_velocity_lateral`` w, the law of
:mod:`vehdyn.handling.crosswind` with the numbers of ``vehicle.aero``).

Wheel-centre velocities in the wheel axes (SAE; front: lateral velocity v + a r, rear: v - b r)::

    V_x = u cos(d) + V_y,body sin(d),   V_y = -u sin(d) + V_y,body cos(d)

Normal loads: quasi-static longitudinal load transfer (Gillespie, *Fundamentals of Vehicle
Dynamics*, 1992, eq. 2-18) through the CG height h, plus aerodynamic lift::

    F_zf = m g b / L - h X / L - L_f,    F_zr = m g a / L + h X / L - L_r,
    X = sum of the body-x tire forces (= m (du/dt - v r) + F_drag)

(with wheel spin the forces depend on the loads: two fixed-point passes from the static loads).

Lateral load transfer (``lateral_load_transfer=True``; default off): the two wheels of an axle
carry F_z,i / 2 +- dF_z,i and the axle force is the tire law at each wheel's load, summed, so the
tire's load sensitivity takes side force off the axle as the load moves outward. dF_z,i is the
quasi-static (steady-state) lateral load transfer through the roll centres and the roll
stiffnesses (Milliken & Milliken, *Race Car Vehicle Dynamics*, 1995, ch. 18, "lateral load
transfer": a geometric part through the roll-centre height and an elastic part shared by the roll
stiffnesses; with Gillespie 1992, ch. 6, "Suspension roll", for the gravity term m g h_1 of the
rolled body)::

    dF_z,i = (z_i / t_i) F_y,i + h_1 K_i / ((K_f + K_r - m g h_1) t_i) (F_y,f + F_y,r)

with the axle lateral forces F_y,i in body axes (in a steady turn F_y,f + F_y,r = m a_y and
F_y,f = m a_y b / L), t_i the track, z_i the roll-centre height, K_i the suspension roll stiffness
(springs and anti-roll bar, :attr:`vehdyn.Vehicle.front_roll_stiffness`), h_1 the CG height above
the roll axis (whole mass on the roll axis: the unsprung masses' own transfer is neglected) and
positive dF_z onto the left wheels (SAE: F_y > 0 turns right). The roll moment of a crosswind is
taken as acting at the CG height. The forces take the transfer of the steady turn at the present
yaw rate (side forces m u r b / L and m u r a / L, exact in a steady turn; in a transient it
follows the yaw rate, not the forces); with wheel spin it is then updated with the forces along the
two fixed-point passes of the longitudinal transfer; the outputs show the transfer of the final
forces. One evaluation of the law per wheel (force mode), so the cost is about that without the
transfer. Unequal longitudinal forces of the left and right wheel make a yaw couple
(t_i / 2)(F_x,left - F_x,right) cos(d_i) (SAE: the left wheel at y = -t_i / 2); in force mode each
wheel takes half the axle's demand (open differential, equal brake pressures) and its rolling
resistance M_y / R_e (the law's, at its own load, faded in over the low-speed range like the
damping above) moves force between them, the axle's net force staying the demand: the outer wheel
rolls harder, a couple toward understeer that the full vehicle has too (1 % of the yaw rate in the
sedan's circle to the limit). An inner wheel that would lift carries 0. The
left tire of an axle is the law's mirror image when the law has ply steer, the right one the law's
own, as in :class:`vehdyn.full_vehicle.FullVehicle` (the zero-slip forces cancel at equal loads, not
under the transfer: 2.7 % of the sedan's steady steer at 2 m/s^2, so the side must be the full
vehicle's). Without the roll degree of freedom (below) the transfer follows the forces without the
roll mode's lag; roll steer and camber take the steady roll (below). With wheel spin the axle's two
wheels share one spin state.

Roll degree of freedom (``roll=True``, with ``lateral_load_transfer=True``): the body rolls by phi
(SAE: positive right side down) about the roll axis through the roll centres, and the suspension's
roll moment, not the quasi-static law, sets the elastic part of each axle's transfer (Segel 1956;
Milliken & Milliken 1995, ch. 18; Gillespie 1992, ch. 6)::

    dF_z,i = (z_i / t_i) F_y,i - (K_i phi + C_i p) / t_i
    J dp/dt = -m h_1 a_y - (K_f + K_r - m g h_1) phi - (C_f + C_r) p,     dphi/dt = p
    m (dv/dt + u r) + m h_1 dp/dt = F_y,f + F_y,r + F_ext            (lateral equation above)

with a_y = (F_y,f + F_y,r + F_ext) / m the lateral acceleration of the CG (the output
``lateral_acceleration``), h_1 the CG height above the roll axis and the whole mass on it, as in the
quasi-static law (whose steady state this is: phi = -m h_1 a_y / (K_f + K_r - m g h_1) gives its
dF_z,i exactly, and K -> infinity at a fixed distribution gives its transient), C_i = c_i t_i^2 / 2
the roll damping of the corner dampers c_i, and J = I_x - (m_s h_s)^2 / m the body's roll inertia
with the vehicle free to move sideways (I_x Segel's sprung-mass roll inertia about the roll axis,
:func:`~vehdyn.handling.lateral_yaw_roll_parameters`; eliminating dv/dt from Segel's lateral and
roll equations). v is then the lateral velocity of the non-rolling frame, from which the slips are
taken. The geometric part follows the yaw rate as without roll; the roll-yaw product of inertia is
left out. States ``roll_angle`` and ``roll_rate``, outputs of the same names.
At 2 % on yaw rate and lateral acceleration against :class:`vehdyn.full_vehicle.FullVehicle`, what
the quasi-static transfer misses in transient manoeuvres is the roll's lag (sine with dwell of the
sedan: 12 % without the roll degree of freedom, 3.3 % with it; see the README's fidelity ladder).

Roll steer, camber and compliance steer (the vehicle file's ``suspension`` fields; Gillespie 1992,
ch. 6, Table 6.1; Milliken & Milliken 1995, ch. 5 and 18): each axle runs at its steer input plus::

    delta_i += eps_i phi + delta_c,i,    delta_c,i = c_i F_y,i + e_i M_z,i,    gamma_i = phi + g_i (T_i / 2) phi_si

with eps_i the roll steer, c_i and e_i the lateral-force and aligning-moment compliance steer (SAE:
positive in the sense of the axle's force F_y,i and of its law's aligning moment M_z,i), g_i the
camber gain and gamma_i the inclination of both wheels (ISO-W; the Magic Formula's camber input;
upright without camber gains). The roll phi is the roll state with ``roll=True`` (rigid tires:
phi_si = phi), else, with ``lateral_load_transfer=True``, the steady roll of the full vehicle at
a_y = u r, phi = -RG u r and phi_si = -RG_si u r (:func:`vehdyn.handling.steady_roll`: springs, bars,
roll centres, tire compliance, unsprung masses; the vehicle's, not a variant's). Without the load
transfer there is no roll: roll steer and camber are absent (the fidelity ladder refuses the rung
for them). The compliance steer is quasi-static: with tire lag the forces come from the deflection
states, so delta_c,i is explicit (the law once for F_y,i and M_z,i at the steer without it, then at
the full steer); without tire lag a Newton step with the law's slope at the static load and a
secant step (:func:`~vehdyn.handling.single_track_equations.evaluate`). Then the understeer gradient
from the model's steady turns is the budget's (:func:`vehdyn.handling.understeer_budget`) to 1e-9
with linear tires (tests/handling/test_single_track_understeer_terms.py). Outputs
``front_compliance_steer_angle`` and ``rear_compliance_steer_angle`` where a compliance is set.

An axle whose load would become negative (the vehicle would tip over that axle) is held at zero
and the other axle carries the whole weight; the output ``front_normal_load`` shows it.

Tire relaxation (``tire_lag=True``, the default): each axle has a lateral tire deflection state
rho_y (and, with wheel spin, a longitudinal one rho_x) of the single-contact-point transient model
(Pacejka 2012, sec. 7.2.1 eq. 7.9-7.12 and sec. 8.2)::

    d(rho_y)/dt = V_sy - |V_x| rho_y / sigma_y,     tan(alpha') = rho_y / sigma_y
    d(rho_x)/dt = -V_sx - |V_x| rho_x / sigma_x,    s_x = rho_x / sigma_x

with V_sx = V_x - omega R_e, V_sy = V_y the slip velocities. The tire law sees alpha' and
kappa' = s_x sign(V_x) (MFeval's signed slip ratio; the laws flip F_x with sign(V_x), so the force
is continuous through standstill). No speed appears in a denominator: at standstill the tire is a
spring of stiffness C / sigma. Below ``low_speed_damping_speed`` v_l a damping term fades in
(after Pacejka 2012, sec. 8.7, eq. 8.125-8.126, the "k_Vlow" damping of MF-Tyre)::

    tan(alpha') <- tan(alpha') + w (d rho_y/dt) / v_l,   s_x <- s_x + w (d rho_x/dt) / v_l,
    w = (1 + cos(pi |V_x| / v_l)) / 2 for |V_x| < v_l, else 0

which damps the otherwise undamped tire-spring oscillation of a parked or creeping vehicle (it is
zero, and so changes nothing, at speeds above v_l). The term acts on the deflection rate (the
carcass deflection velocity; the rate above, limited at the peak slip): at standstill that is the
slip velocity, V_sy or -V_sx, as in Pacejka's form, and in the steady state it is zero, so the
tire lag leaves steady-state slips and forces unchanged at every speed. (On the slip velocity
itself, as in eq. 8.126, the steady-state slip would be (1 + w |V_x| / v_l) times the kinematic
one: up to 26 % stiffer, at |V_x| = 0.42 v_l.) Without tire lag the slips are the steady-state
ones, tan(alpha) = V_y / D(V_x) and kappa = -V_sx / (sign(V_x) D(V_x)), with the regularized speed
D of :func:`vehdyn.tire.regularized_speed` (exact above 0.5 m/s): valid at speed only. So the
steady states with and without tire lag coincide for |V_x| >= 0.5 m/s; below, the model with lag
holds the exact kinematic slips V_y / |V_x|, -V_sx / |V_x| and the one without holds D's.

Longitudinal input, two modes:

* ``wheel_spin=False`` (default): the axle longitudinal forces are inputs
  (``front_longitudinal_force``, ``rear_longitudinal_force``, wheel axes, N), clipped at
  mu F_z; the lateral force of the law at zero slip ratio is reduced by the friction ellipse
  sqrt(1 - (F_x / (mu F_z))^2) (Rajamani 2012, sec. 13.7; mu = ``vehicle.tires.friction_coefficient``).
* ``wheel_spin=True``: each axle has a spin state omega (both wheels together, inertia 2 I_w)::

      2 I_w d(omega)/dt = T_drive - T_brake sat(omega / omega_b) - R_e F_x + M_y

  and the tire law computes F_x, F_y and the rolling-resistance moment M_y (ISO-W, negative
  rolling forwards: the Magic Formula's, a soft-soil tire's ``r F_x - T``; 0 for the laws without
  one) from the (transient) slips with its own combined-slip rule. With M_y a free-rolling axle
  settles at F_x = M_y / R_e: the rolling resistance decelerates the vehicle (Pacejka 2012,
  sec. 4.3.5; Wong 2008, sec. 2.7 for a towed wheel on soil). The brake torque opposes the spin; sat(z) = z / sqrt(1 + z^2) regularizes its sign
  within ``brake_regularization_speed`` omega_b so that a locked wheel stops without chatter.

Road friction (``friction``, a constant ratio or a callable of the earth position under each
axle's centre): every tire's law on the road is the similar one, F(kappa, tan alpha) ->
mu F(kappa / mu, tan(alpha) / mu) (Pacejka 2012, sec. 4.3.2), so the peak forces and the slips at
which they occur scale by mu and the slip stiffnesses stay; the deflections' limits (the peak
slips) and the force mode's friction ellipse scale with it. The same step as the full vehicle's
(:mod:`vehdyn.components.tire_forces`).

The equations are written once, as pure functions over an ``xp`` namespace, in
:mod:`~vehdyn.handling.single_track_equations` (with the components the full vehicle shares,
:mod:`vehdyn.components`): :meth:`SingleTrack.rhs` and ``output`` run them on
numpy arrays (with a batch axis), and :meth:`SingleTrack.compiled_rhs` compiles them with numba
(optional: ``pip install vehdyn[fast]``) for ``simulate(model, t, inputs, method="RK45",
"DOP853" or "BDF")``, which uses the compiled backend by default (``backend="auto"``) for one vehicle
with Magic Formula or linear tires (brush, Fiala and Dugoff laws run on numpy). With tire lag at
speed the relaxation modes (-|V_x| / sigma, ~ -55 1/s at 100 km/h) hold the explicit methods at
their stability limit; ``"BDF"`` takes the steps the tolerance asks for (fewer rhs calls at equal
error: ``benchmarks/bench_sweep.py``).
Give steer inputs as the closed-form signals of :mod:`~vehdyn.procedures` to have them
evaluated exactly inside the compiled steps (see :mod:`vehdyn.simulation.compiled`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError, VehdynError
from vehdyn.model import Model
from vehdyn.params import Vehicle
from vehdyn.signals import STEER_INPUTS, Signal
from vehdyn.units import GRAVITY
from vehdyn.handling import single_track_equations as equations
from vehdyn.components.aero import centre_of_pressure_ahead_of_cg, wind_side_force_factor
from vehdyn.components.planar import body_point
from vehdyn.components.tire_forces import axle_tire_loads, wheel_pair_tire_loads
from vehdyn.components.tire_setup import (friction_at, longitudinal_relaxation_lengths, mirrored_wheel, road_friction,
                                          tire_characteristics)
from vehdyn.components.xp import SCALAR
from vehdyn.components.xp import stack as _stack
from vehdyn.components.xp import with_tire_hooks

__all__ = ["SingleTrack", "SingleTrackParameters", "lateral_load_transfer_coefficients", "roll_parameters"]

_AXLES = ("front", "rear")


def _namespace(states):
    """The ``xp`` the states were evaluated on: :data:`~vehdyn.components.xp.SCALAR` for floats, else numpy's."""
    return SCALAR if type(states[0]) is float else equations.NUMPY


@dataclass(frozen=True)
class SingleTrackParameters:
    """Numbers of the single-track model; each may be a float or an array across batch variants.

    Attributes
    ----------
    mass : kg
    yaw_inertia : kg*m^2
    a, b : m
        CG to front and rear axle.
    cg_height : m
    rolling_radius : m
        Effective rolling radius R_e.
    wheel_spin_inertia : kg*m^2
        One wheel.
    friction_coefficient : -
        mu of the friction ellipse (force mode).
    front_lateral_relaxation_length, rear_lateral_relaxation_length : m
    front_longitudinal_relaxation_length, rear_longitudinal_relaxation_length : m
    drag_factor : kg/m
        0.5 rho c_x A, so that F_drag = drag_factor u |u|.
    front_lift_factor, rear_lift_factor : kg/m
        0.5 rho c_l A of each axle (lift = factor u^2).
    gravity : m/s^2
    wind_side_force_factor : kg/m
        k_w = 0.5 rho A C_Y' of the crosswind side force (:mod:`vehdyn.handling.crosswind`).
    centre_of_pressure : m
        Aerodynamic centre of pressure x_p ahead of the CG (negative: behind).
    """

    mass: object
    yaw_inertia: object
    a: object
    b: object
    cg_height: object
    rolling_radius: object
    wheel_spin_inertia: object
    friction_coefficient: object
    front_lateral_relaxation_length: object
    rear_lateral_relaxation_length: object
    front_longitudinal_relaxation_length: object
    rear_longitudinal_relaxation_length: object
    drag_factor: object
    front_lift_factor: object
    rear_lift_factor: object
    gravity: float = GRAVITY
    wind_side_force_factor: object = 0.0
    centre_of_pressure: object = 0.0

    @property
    def wheelbase(self):
        return self.a + self.b

    def static_axle_loads(self):
        """The static axle loads.

        Returns
        -------
        tuple
            (front, rear) [N].
        """
        w = self.mass * self.gravity
        return w * self.b / self.wheelbase, w * self.a / self.wheelbase


_POSITIVE = ("mass", "yaw_inertia", "a", "b", "cg_height", "rolling_radius", "wheel_spin_inertia",
             "friction_coefficient", "front_lateral_relaxation_length", "rear_lateral_relaxation_length",
             "front_longitudinal_relaxation_length", "rear_longitudinal_relaxation_length")


def _check_parameters(p: SingleTrackParameters) -> SingleTrackParameters:
    sizes = set()
    for field in dataclasses.fields(p):
        value = np.asarray(getattr(p, field.name), dtype=float)
        if not np.all(np.isfinite(value)):
            raise ParameterError(f"SingleTrack parameter {field.name} must be finite, got {getattr(p, field.name)!r}",
                                 key=field.name, value=getattr(p, field.name))
        if field.name in _POSITIVE and np.any(value <= 0):
            bad = value[value <= 0].flat[0] if value.ndim else float(value)
            raise ParameterError(f"SingleTrack parameter {field.name} must be > 0, got {bad!r}", key=field.name,
                                 value=bad)
        if value.ndim > 1:
            raise ParameterError(f"SingleTrack parameter {field.name} must be a scalar or a 1-D array across "
                                 f"variants, got shape {value.shape}", key=field.name, value=value.shape)
        if value.ndim == 1:
            sizes.add(value.size)
    if len(sizes) > 1:
        raise ParameterError(f"SingleTrack parameter arrays differ in length: {sorted(sizes)}", key="variants",
                             value=sorted(sizes))
    return p


def lateral_load_transfer_coefficients(vehicle, *, mass=None, cg_height=None, a=None, b=None, gravity=GRAVITY):
    """Quasi-static lateral load transfer coefficients ((front geometric, front elastic), (rear ...)) [-].

    The load moved onto the outer wheel of axle i by the axle lateral forces F_y,f, F_y,r [N]::

        dF_z,i = g_i F_y,i + e_i (F_y,f + F_y,r),
        g_i = z_i / t_i,   e_i = h_1 K_i / ((K_f + K_r - m g h_1) t_i)

    (Milliken & Milliken, *Race Car Vehicle Dynamics*, 1995, ch. 18; the gravity term of the rolled
    body after Gillespie, *Fundamentals of Vehicle Dynamics*, 1992, ch. 6): t_i the track, z_i the
    roll-centre height, K_i the suspension roll stiffness (springs and anti-roll bar, tires
    excluded), h_1 = h - z(a) the CG height above the roll axis. In a steady turn
    F_y,f + F_y,r = m a_y and F_y,i = m a_y l_j / L, which gives the textbook
    dF_z,i = m a_y / t_i (h_1 K_i / (K_f + K_r - m g h_1) + z_i l_j / L).

    Parameters
    ----------
    vehicle : Vehicle
        Tracks, roll centres and roll stiffnesses.
    mass : float or ndarray, optional
        m [kg] (default the vehicle's; arrays across variants).
    cg_height : float or ndarray, optional
        h [m].
    a, b : float or ndarray, optional
        CG to the front and rear axle [m].
    gravity : float
        [m/s^2].

    Returns
    -------
    tuple
        ((front geometric, front elastic), (rear geometric, rear elastic)) [-].

    Raises
    ------
    ParameterError
        When K_f + K_r <= m g h_1 (the body would roll over).
    """
    m, g = vehicle.mass, vehicle.geometry
    mass = m.mass if mass is None else mass
    cg_height = m.cg_height if cg_height is None else cg_height
    a = g.cg_to_front_axle if a is None else a
    b = g.cg_to_rear_axle if b is None else b
    kf, kr = vehicle.front_roll_stiffness, vehicle.rear_roll_stiffness
    zf, zr = g.front_roll_centre_height, g.rear_roll_centre_height
    h1 = cg_height - (zf + (zr - zf) * a / (a + b))
    denominator = kf + kr - mass * gravity * h1
    if np.any(np.asarray(denominator) <= 0):
        raise ParameterError(f"lateral load transfer needs roll stiffness K_f + K_r = {kf + kr!r} N*m/rad above "
                             f"m g h_1 = {np.max(mass * gravity * h1)!r} N*m (the body would roll over)",
                             key="suspension", value=kf + kr)
    elastic = h1 / denominator
    return ((zf / g.front_track, elastic * kf / g.front_track), (zr / g.rear_track, elastic * kr / g.rear_track))


def roll_parameters(vehicle, *, mass=None, cg_height=None, a=None, b=None) -> dict:
    """The numbers of the roll degree of freedom of :class:`SingleTrack` (``roll=True``).

    ``roll_arm`` h_1 = h - z(a) [m], the CG height above the roll axis (as in
    :func:`lateral_load_transfer_coefficients`); ``roll_inertia`` J [kg*m^2], the effective roll
    inertia of the body when the vehicle is free to move sideways: Segel's sprung-mass roll inertia
    about the roll axis I_x = J_s + m_s h_s^2 (:func:`vehdyn.handling.lateral_yaw_roll_parameters`)
    less (m_s h_s)^2 / m, eliminating dv/dt from Segel's lateral and roll equations (positive, as
    m_s < m); ``{axle}_roll_transfer_stiffness`` K_i / t_i [N/rad] with K_i the suspension roll
    stiffness (springs and anti-roll bar, tires excluded), and ``{axle}_roll_transfer_damping``
    C_i / t_i [N*s/rad] with C_i = c_i t_i^2 / 2 from the corner dampers.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle.
    mass : float, optional
        m [kg] (default the vehicle's).
    cg_height : float, optional
        h [m].
    a, b : float, optional
        CG to the front and rear axle [m].

    Returns
    -------
    dict
        The numbers above [their units].
    """
    from vehdyn.handling.lateral_yaw_roll import lateral_yaw_roll_parameters

    m, g, s = vehicle.mass, vehicle.geometry, vehicle.suspension
    mass = m.mass if mass is None else mass
    cg_height = m.cg_height if cg_height is None else cg_height
    a = g.cg_to_front_axle if a is None else a
    b = g.cg_to_rear_axle if b is None else b
    zf, zr = g.front_roll_centre_height, g.rear_roll_centre_height
    segel = lateral_yaw_roll_parameters(vehicle)
    inertia = segel.roll_inertia - (segel.sprung_mass * segel.roll_arm) ** 2 / segel.mass
    return {"roll_arm": cg_height - (zf + (zr - zf) * a / (a + b)), "roll_inertia": float(inertia),
            "front_roll_transfer_stiffness": vehicle.front_roll_stiffness / g.front_track,
            "rear_roll_transfer_stiffness": vehicle.rear_roll_stiffness / g.rear_track,
            "front_roll_transfer_damping": s.front_damping * g.front_track / 2,
            "rear_roll_transfer_damping": s.rear_damping * g.rear_track / 2}


class SingleTrack(Model):
    r"""Nonlinear planar single-track model with any tire law (equations in the module docstring).

    Parameters
    ----------
    vehicle : Vehicle
        Masses, geometry, tire data (rolling radius, wheel inertia, mu, relaxation lengths), aero.
    front_tire, rear_tire : TireModel, optional
        The law of ONE tire of each axle (ISO-W, :class:`vehdyn.tire.TireModel`); the axle force
        is twice the tire's at half the axle load. Default: the vehicle's law
        (``vehicle.tires.model``, the Magic Formula from its ``.tir`` file) through
        :func:`vehdyn.tire.tire_for_vehicle`.
    wheel_spin : bool
        Wheel-spin states and torque inputs (True) or axle-force inputs (False, default).
    tire_lag : bool
        Tire deflection (relaxation) states, needed for low speed and standstill (default True).
    longitudinal_relaxation_length : float or (float, float), optional
        sigma_x [m] of the front and rear tires; default: for a Magic Formula tire its own value at
        half the static axle load (:func:`vehdyn.tire.relaxation_lengths`, K_xkappa / C_x), for
        other laws the lateral lengths (the vehicle file's ``tires.*_relaxation_length``).
    low_speed_damping_speed : float
        v_l [m/s] below which the tire-spring damping fades in (default 2 m/s).
    brake_regularization_speed : float
        omega_b [rad/s] of the brake-torque sign regularization (default 1 rad/s).
    gravity : float
        [m/s^2].
    lateral_load_transfer : bool
        Split each axle's load between its left and right wheel by the quasi-static lateral load
        transfer (module docstring; default False: both wheels at half the axle load). Adds the
        outputs ``front_left_normal_load``, ``front_right_normal_load``, ``rear_left_normal_load``
        and ``rear_right_normal_load``.
    roll : bool
        The roll degree of freedom (module docstring; needs ``lateral_load_transfer=True``): the
        roll angle and rate of the body set the elastic part of the lateral load transfer. Adds the
        states and outputs ``roll_angle`` [rad] and ``roll_rate`` [rad/s] (default False).
    friction : float or callable, optional
        The road's friction relative to the tire laws' own [-]: a constant ratio (e.g. 0.5; it
        compiles), or a callable ``friction(X, Y) -> ratio`` of earth positions [m] (arrays),
        evaluated under each axle's centre (numpy backend only; the single track lumps an axle's
        wheels on the centre line, so a split-mu road needs :class:`~vehdyn.full_vehicle.FullVehicle`).
        Applied to every tire by similarity (Pacejka 2012, sec. 4.3.2): the peak forces and their
        slips scale by the ratio, the slip stiffnesses stay (:mod:`vehdyn.components.tire_forces`);
        the force mode's friction ellipse takes the same ratio. Default: the laws as they are.
        :func:`vehdyn.components.tire_setup.friction_ratio` gives the ratio of a road of known peak mu.

    Signals
    -------
    states
        ``longitudinal_velocity`` u, ``lateral_velocity`` v, ``yaw_rate`` r, ``x``, ``y``,
        ``yaw_angle`` psi; with wheel spin ``front_wheel_speed``, ``rear_wheel_speed`` [rad/s];
        with tire lag ``front_lateral_deflection``, ``rear_lateral_deflection`` [m] (and with wheel
        spin ``front_longitudinal_deflection``, ``rear_longitudinal_deflection``).
    inputs
        ``front_steer_angle``, ``rear_steer_angle`` [rad]; ``front_longitudinal_force``,
        ``rear_longitudinal_force`` [N] or ``front_drive_torque``, ``rear_drive_torque``,
        ``front_brake_torque``, ``rear_brake_torque`` [N*m] (per axle, brake torques >= 0);
        ``external_lateral_force`` [N], ``external_yaw_moment`` [N*m];
        ``wind_velocity_lateral`` [m/s] (crosswind toward +y, acting at the centre of pressure).
    outputs
        See :attr:`outputs` (accelerations, sideslip, slips, axle forces and loads, position).

    Notes
    -----
    The planar equations (module docstring; SAE axes, axle forces resolved through the steer
    angles):

    .. math::

        m (\dot u - v r) &= F_{xf} \cos\delta_f - F_{yf} \sin\delta_f + F_{xr} \cos\delta_r
        - F_{yr} \sin\delta_r - F_{drag}\\
        m (\dot v + u r) &= F_{xf} \sin\delta_f + F_{yf} \cos\delta_f + F_{xr} \sin\delta_r
        + F_{yr} \cos\delta_r + F_{ext}\\
        I_z \dot r &= a (F_{xf} \sin\delta_f + F_{yf} \cos\delta_f) - b (F_{xr} \sin\delta_r
        + F_{yr} \cos\delta_r) + M_{ext}\\
        \dot\rho_y &= V_{sy} - |V_x| \rho_y / \sigma_y,\qquad \tan\alpha' = \rho_y / \sigma_y\\
        2 I_w \dot\omega &= T_{drive} - T_{brake}\,\mathrm{sat}(\omega / \omega_b) - R_e F_x + M_y

    with the axle loads F_zf = m g b / L - h X / L - L_f (quasi-static longitudinal transfer) and
    each axle's forces from its tire law at the transient slips (two tires at half the axle load, or
    each wheel at its own load under the lateral load transfer), each axle at the road-wheel steer

    .. math::

        \delta_i = \delta_{i,input} + \varepsilon_i \phi + c_i F_{y,i} + e_i M_{z,i},\qquad
        \gamma_i = \phi + g_i (T_i / 2) \phi_{si}

    (roll steer, compliance steer and camber from roll: module docstring).

    Parameters may vary across a batch: :meth:`variants` returns a model whose mass, inertia,
    axle positions, CG height or relaxation lengths are arrays, and one ``simulate`` call with
    ``x0`` of shape (n_states, n_variants) runs them all.

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, sec. 1.3
       (eq. 1.43, the single-track equations), 4.3.2 (similarity), 7.2.1 (eq. 7.9-7.12, the tire
       deflections), 8.7 (eq. 8.125-8.126, the low-speed damping).
    .. [2] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, sec. 2.3, 2.5 and
       13.7 (the friction ellipse).
    .. [3] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, eq. 2-18 and ch. 6.
    .. [4] W. F. Milliken, D. L. Milliken, *Race Car Vehicle Dynamics*, SAE, 1995, ch. 18 (lateral
       load transfer).
    .. [5] L. Segel, "Theoretical prediction and experimental substantiation of the response of the
       automobile to steering control", *Proc. IMechE Automobile Division*, 1956 (the roll degree
       of freedom).
    """

    def __init__(self, vehicle: Vehicle, front_tire=None, rear_tire=None, *, wheel_spin: bool = False,
                 tire_lag: bool = True, longitudinal_relaxation_length=None, low_speed_damping_speed: float = 2.0,
                 brake_regularization_speed: float = 1.0, gravity: float = GRAVITY,
                 lateral_load_transfer: bool = False, roll: bool = False, friction=None):
        if not isinstance(vehicle, Vehicle):
            raise ParameterError(f"vehicle must be a vehdyn Vehicle, got {type(vehicle).__name__}", key="vehicle",
                                 value=vehicle)
        from vehdyn.tire import TireModel, tire_for_vehicle

        tires = {}
        for axle, tire in zip(_AXLES, (front_tire, rear_tire)):
            if tire is None:
                tire = tire_for_vehicle(vehicle, axle)
            if not isinstance(tire, TireModel):
                raise ParameterError(f"{axle}_tire must be a vehdyn.tire.TireModel, got {type(tire).__name__}",
                                     key=f"{axle}_tire", value=tire)
            tires[axle] = tire
        self.front_tire, self.rear_tire = tires["front"], tires["rear"]
        self.vehicle = vehicle
        self.wheel_spin = bool(wheel_spin)
        self.tire_lag = bool(tire_lag)
        self.lateral_load_transfer = bool(lateral_load_transfer)
        for name, value in (("lateral_load_transfer", lateral_load_transfer), ("roll", roll)):
            if not isinstance(value, (bool, np.bool_)):
                raise ParameterError(f"{name} must be True or False, got {value!r}", key=name, value=value)
        if roll and not lateral_load_transfer:
            raise ParameterError("roll=True needs lateral_load_transfer=True (the roll sets the wheels' loads)",
                                 key="roll", value=roll)
        self.roll = bool(roll)
        self.friction = road_friction(friction)
        for name, value in (("low_speed_damping_speed", low_speed_damping_speed),
                            ("brake_regularization_speed", brake_regularization_speed), ("gravity", gravity)):
            if not (np.isfinite(value) and value > 0):
                raise ParameterError(f"{name} must be a finite number > 0, got {value!r}", key=name, value=value)
        self.low_speed_damping_speed = float(low_speed_damping_speed)
        self.brake_regularization_speed = float(brake_regularization_speed)
        t, g, m, aero = vehicle.tires, vehicle.geometry, vehicle.mass, vehicle.aero
        lateral = (t.front_relaxation_length, t.rear_relaxation_length)
        if self.tire_lag and min(lateral) <= 0:
            raise ParameterError("tire_lag needs positive tires.front_relaxation_length and "
                                 f"tires.rear_relaxation_length, got {lateral}", key="tires.front_relaxation_length",
                                 value=lateral)
        lateral = tuple(s if s > 0 else 1.0 for s in lateral)  # unused without tire lag
        longitudinal = longitudinal_relaxation_lengths(vehicle, tires, longitudinal_relaxation_length, lateral, gravity)
        half_rho_a = 0.5 * aero.air_density * aero.frontal_area
        self.parameters = _check_parameters(SingleTrackParameters(
            mass=m.mass, yaw_inertia=m.yaw_inertia, a=g.cg_to_front_axle, b=g.cg_to_rear_axle, cg_height=m.cg_height,
            rolling_radius=t.rolling_radius, wheel_spin_inertia=t.wheel_spin_inertia,
            friction_coefficient=t.friction_coefficient,
            front_lateral_relaxation_length=lateral[0], rear_lateral_relaxation_length=lateral[1],
            front_longitudinal_relaxation_length=longitudinal[0], rear_longitudinal_relaxation_length=longitudinal[1],
            drag_factor=half_rho_a * aero.drag_coefficient, front_lift_factor=half_rho_a * aero.front_lift_coefficient,
            rear_lift_factor=half_rho_a * aero.rear_lift_coefficient, gravity=float(gravity),
            wind_side_force_factor=wind_side_force_factor(vehicle),
            centre_of_pressure=centre_of_pressure_ahead_of_cg(vehicle)))
        static = self.parameters.static_axle_loads()
        characteristics = {axle: tire_characteristics(tires[axle], 0.5 * load) for axle, load in zip(_AXLES, static)}
        self._mirrored = {axle: value[0] for axle, value in characteristics.items()}
        self._mirrored_wheels = {axle: mirrored_wheel(tires[axle], value[0]) for axle, value in characteristics.items()}
        self._peak_slip = {axle: value[1] for axle, value in characteristics.items()}
        if self.lateral_load_transfer:
            self._transfer_coefficients()  # a vehicle whose body would roll over: error here
        self._understeer_terms = self._understeer_constants()
        self._declare_signals()

    def _understeer_constants(self) -> dict:
        """The constants of roll steer, camber from roll and compliance steer (:class:`Constants`)
        from the vehicle's ``suspension`` fields; all 0 (and the steps skipped) for a vehicle without."""
        from vehdyn.handling.axle_tires import compliance_steer_slope

        s, g = self.vehicle.suspension, self.vehicle.geometry
        out = {}
        compliance = False
        for axle, tire in zip(_AXLES, (self.front_tire, self.rear_tire)):
            c, e, slope = compliance_steer_slope(self.vehicle, axle, tire)
            compliance = compliance or c != 0.0 or e != 0.0
            out.update({f"{axle}_lateral_force_compliance": c, f"{axle}_aligning_moment_compliance": e,
                        f"{axle}_compliance_slope": slope})
        out["compliance_steer"] = float(compliance)
        steer = (float(s.front_roll_steer), float(s.rear_roll_steer))
        gains = (s.front_camber_gain, s.rear_camber_gain)
        roll_terms = self.lateral_load_transfer and (steer != (0.0, 0.0) or gains != (None, None))
        out.update(front_roll_steer=steer[0], rear_roll_steer=steer[1], front_camber_per_roll=0.0,
                   rear_camber_per_roll=0.0, quasi_static_roll=0.0, roll_terms=float(roll_terms))
        if not roll_terms:
            return out
        tracks = (g.front_track, g.rear_track)
        if self.roll:  # rigid tires: the body rolls on the springs alone, phi_s = phi
            ratios = (1.0, 1.0)
        else:
            from vehdyn.handling.roll_balance import steady_roll

            roll = steady_roll(self.vehicle, gravity=float(self.parameters.gravity))
            out["quasi_static_roll"] = -float(roll.roll_gradient)
            ratios = tuple(float(r) / float(roll.roll_gradient) for r in roll.suspension_roll_gradient)
        for axle, gain, track, ratio in zip(_AXLES, gains, tracks, ratios):
            if gain is not None:
                out[f"{axle}_camber_per_roll"] = 1.0 + float(gain) * 0.5 * track * ratio
        return out

    # ------------------------------------------------------------------ construction helpers
    # (for the handling models that share them: vehdyn.components.tire_setup holds them)
    _longitudinal_lengths = staticmethod(longitudinal_relaxation_lengths)
    _mirrored_wheel = staticmethod(mirrored_wheel)
    _tire_characteristics = staticmethod(tire_characteristics)

    @staticmethod
    def _needs_mirror(tire, load) -> bool:
        """True when ``tire`` makes a lateral force at zero slip (at ``load`` [N], 20 m/s): one wheel of
        an axle is then the law's mirror image (:func:`~vehdyn.components.tire_setup.mirrored_wheel`)."""
        return tire_characteristics(tire, load)[0]

    def _declare_signals(self):
        states = [Signal("longitudinal_velocity", "m/s", "body-frame forward velocity u of the CG"),
                  Signal("lateral_velocity", "m/s", "body-frame lateral velocity v of the CG (right, SAE)"),
                  Signal("yaw_rate", "rad/s", "yaw rate r (positive turning right, SAE)"),
                  Signal("x", "m", "earth-fixed X of the CG (initial heading direction)"),
                  Signal("y", "m", "earth-fixed Y of the CG (right of the initial heading, SAE)"),
                  Signal("yaw_angle", "rad", "heading psi (positive turning right, SAE)")]
        if self.wheel_spin:
            states += [Signal(f"{axle}_wheel_speed", "rad/s", f"spin of the {axle} wheels (positive rolling forwards)")
                       for axle in _AXLES]
        if self.roll:
            states += [Signal("roll_angle", "rad", "roll angle phi of the body about the roll axis (right side down)"),
                       Signal("roll_rate", "rad/s", "roll rate p of the body")]
        if self.tire_lag:
            states += [Signal(f"{axle}_lateral_deflection", "m",
                              f"lateral deflection of the {axle} tires' contact point (SAE y, relaxation state)")
                       for axle in _AXLES]
            if self.wheel_spin:
                states += [Signal(f"{axle}_longitudinal_deflection", "m",
                                  f"longitudinal deflection of the {axle} tires (relaxation state, + driving)")
                           for axle in _AXLES]
        inputs = list(STEER_INPUTS)
        if self.wheel_spin:
            inputs += [Signal(f"{axle}_drive_torque", "N*m", f"drive torque on the {axle} axle (both wheels)")
                       for axle in _AXLES]
            inputs += [Signal(f"{axle}_brake_torque", "N*m", f"brake torque magnitude on the {axle} axle (>= 0)")
                       for axle in _AXLES]
        else:
            inputs += [Signal(f"{axle}_longitudinal_force", "N",
                              f"longitudinal force of the {axle} axle in wheel axes (+ driving)") for axle in _AXLES]
        inputs += [Signal("external_lateral_force", "N", "lateral force at the CG, e.g. wind (SAE y, right)"),
                   Signal("external_yaw_moment", "N*m", "yaw moment about the CG, e.g. wind (SAE z)"),
                   Signal("wind_velocity_lateral", "m/s",
                          "lateral wind: the air's velocity along the vehicle's y axis (toward +y)")]
        outputs = [
            Signal("lateral_acceleration", "m/s^2", "lateral acceleration of the CG, dv/dt + u r (right, SAE)"),
            Signal("sideslip_angle", "rad", "vehicle sideslip at the CG, atan2(v, |u|)"),
            Signal("yaw_rate", "rad/s", "yaw rate r"),
            Signal("lateral_velocity", "m/s", "body-frame lateral velocity v"),
            Signal("front_slip_angle", "rad", "front slip angle acting in the tire law (transient with lag, SAE)"),
            Signal("rear_slip_angle", "rad", "rear slip angle acting in the tire law (transient with lag, SAE)"),
            Signal("path_curvature", "1/m", "curvature of the CG path a_y / V^2 (V^2 floored at 0.25 m^2/s^2)"),
            Signal("front_lateral_force", "N", "lateral force of the front axle in wheel axes (SAE y)"),
            Signal("rear_lateral_force", "N", "lateral force of the rear axle in wheel axes (SAE y)"),
            Signal("longitudinal_acceleration", "m/s^2", "longitudinal acceleration of the CG, du/dt - v r"),
            Signal("longitudinal_velocity", "m/s", "body-frame forward velocity u"),
            Signal("speed", "m/s", "speed of the CG sqrt(u^2 + v^2)"),
            Signal("front_longitudinal_force", "N", "longitudinal force of the front axle in wheel axes"),
            Signal("rear_longitudinal_force", "N", "longitudinal force of the rear axle in wheel axes"),
            Signal("front_normal_load", "N", "normal load of the front axle"),
            Signal("rear_normal_load", "N", "normal load of the rear axle"),
            Signal("front_slip_ratio", "-", "front slip ratio acting in the tire law (0 in force mode)"),
            Signal("rear_slip_ratio", "-", "rear slip ratio acting in the tire law (0 in force mode)"),
            Signal("x", "m", "earth-fixed X of the CG"),
            Signal("y", "m", "earth-fixed Y of the CG (SAE)"),
            Signal("yaw_angle", "rad", "heading psi"),
        ]
        if self.lateral_load_transfer:
            outputs += [Signal(f"{axle}_{side}_normal_load", "N", f"normal load of the {axle} {side} wheel")
                        for axle in _AXLES for side in ("left", "right")]
        if self.roll:
            outputs += [Signal("roll_angle", "rad", "roll angle of the body (positive right side down, SAE)"),
                        Signal("roll_rate", "rad/s", "roll rate of the body")]
        if self._understeer_terms["compliance_steer"]:
            outputs += [Signal(f"{axle}_compliance_steer_angle", "rad",
                               f"compliance steer of the {axle} axle, c F_y + e M_z (SAE, positive turning right)")
                        for axle in _AXLES]
        self.declare(states=states, inputs=inputs, outputs=outputs)
        # positions of the model's signals in the equations' fixed order (-1: not a signal of this model)
        self._state_index = np.array([self.state_names.index(n) if n in self.state_names else -1
                                      for n in equations.STATES], dtype=np.int64)
        self._input_index = np.array([self.input_names.index(n) if n in self.input_names else -1
                                      for n in equations.INPUTS], dtype=np.int64)
        self._state_order = [equations.STATES.index(n) for n in self.state_names]
        phenomena = {"longitudinal", "lateral", "yaw", "load_transfer", "tire_saturation", "aero"}
        if self.wheel_spin:
            phenomena.add("wheel_spin")
        if self.tire_lag:
            phenomena.add("tire_lag")
        if self.roll:
            phenomena.add("roll")
        self.phenomena = frozenset(phenomena)

    def variants(self, **arrays) -> "SingleTrack":
        """A copy whose parameters (fields of :class:`SingleTrackParameters`) take the given values.

        Arrays (1-D, one entry per variant) make a batch model: simulate it with ``x0`` of shape
        (n_states, n_variants). Example: ``model.variants(mass=np.linspace(1000, 1600, 1000))``.

        Parameters
        ----------
        **arrays
            Fields of :class:`SingleTrackParameters` and their values [the fields' units].

        Returns
        -------
        SingleTrack
            The copy.

        Raises
        ------
        ParameterError
            For an unknown name, a non-finite or non-positive value, or arrays of different lengths.
        """
        names = {f.name for f in dataclasses.fields(SingleTrackParameters)}
        unknown = sorted(set(arrays) - names)
        if unknown:
            raise ParameterError(f"SingleTrack has no parameter {unknown[0]!r}; the parameters are {sorted(names)}",
                                 key=unknown[0], value=arrays[unknown[0]])
        new = object.__new__(type(self))
        new.__dict__.update(self.__dict__)
        values = {k: (np.asarray(v, dtype=float) if np.ndim(v) else float(v)) for k, v in arrays.items()}
        new.parameters = _check_parameters(dataclasses.replace(self.parameters, **values))
        return new

    @property
    def n_variants(self) -> int | None:
        """Number of batch variants, or None for a model with scalar parameters."""
        for field in dataclasses.fields(self.parameters):
            value = getattr(self.parameters, field.name)
            if np.ndim(value) == 1:
                return int(np.size(value))
        return None

    # ------------------------------------------------------------------ the equations
    # They live in single_track_equations (one source for numpy and the compiled backend); the
    # methods below map the model's vectors onto them and supply the tire laws.
    def _transfer_coefficients(self) -> dict:
        """The coefficients of the lateral load transfer (module docstring) [-]: geometric z_i / t_i
        and elastic h_1 K_i / ((K_f + K_r - m g h_1) t_i) of each axle (from the vehicle's tracks,
        roll centres and roll stiffnesses and the parameters' mass, CG height, a, b and gravity);
        with roll the elastic ones are 0 and the roll's numbers (:func:`roll_parameters`) are set."""
        out = dict.fromkeys(("front_geometric_transfer", "front_elastic_transfer", "rear_geometric_transfer",
                             "rear_elastic_transfer", "front_track", "rear_track", "roll_arm",
                             "front_roll_transfer_stiffness", "rear_roll_transfer_stiffness",
                             "front_roll_transfer_damping", "rear_roll_transfer_damping"), 0.0)
        out["roll_inertia"] = 1.0  # unused without roll (its arm is 0)
        if not self.lateral_load_transfer:
            return out
        p, v = self.parameters, self.vehicle
        transfer = lateral_load_transfer_coefficients(v, mass=p.mass, cg_height=p.cg_height, a=p.a, b=p.b,
                                                      gravity=p.gravity)
        out.update({f"{axle}_{kind}_transfer": value for axle, pair in zip(_AXLES, transfer)
                    for kind, value in zip(("geometric", "elastic"), pair)})
        out["front_track"], out["rear_track"] = v.geometry.front_track, v.geometry.rear_track
        if self.roll:
            out["front_elastic_transfer"] = out["rear_elastic_transfer"] = 0.0
            out.update(roll_parameters(v, mass=p.mass, cg_height=p.cg_height, a=p.a, b=p.b))
        return out

    def _constants(self, overrides=None) -> equations.Constants:
        p = self.parameters
        fields = {f.name: getattr(p, f.name) for f in dataclasses.fields(p)}
        if overrides:  # symbols for some parameters (symbolic_equations: none of the transfer's)
            fields.update(overrides)
        return equations.Constants(
            **fields, **self._transfer_coefficients(), lateral_load_transfer=self.lateral_load_transfer,
            low_speed_damping_speed=self.low_speed_damping_speed,
            brake_regularization_speed=self.brake_regularization_speed,
            front_peak_slip_ratio=self._peak_slip["front"][0], front_peak_tan_slip_angle=self._peak_slip["front"][1],
            rear_peak_slip_ratio=self._peak_slip["rear"][0], rear_peak_tan_slip_angle=self._peak_slip["rear"][1],
            front_mirror_right=float(self._mirrored_wheels["front"] == "right"),
            rear_mirror_right=float(self._mirrored_wheels["rear"] == "right"),
            front_ply_steer=float(self._mirrored["front"]), rear_ply_steer=float(self._mirrored["rear"]),
            road_friction=self.friction if isinstance(self.friction, float) else 1.0, **self._understeer_terms,
            wheel_spin=self.wheel_spin, tire_lag=self.tire_lag, friction_scaled=self.friction is not None)

    def _evaluate(self, x, u, xp=equations.NUMPY, k=None):
        """(named states, named inputs, Evaluation) at x, u (numpy arrays, optional batch axis; or
        sequences of symbols, with a symbolic ``xp`` and constants ``k``).

        On numpy one state (``x`` and ``u`` 1-D) is evaluated on Python floats
        (:data:`vehdyn.components.xp.SCALAR`, the same numbers without numpy's per-call overhead),
        repeated on numpy where a float operation has no IEEE result in Python; the named states
        are then floats.
        """
        if xp is equations.NUMPY:
            x = np.asarray(x, dtype=float)
            u = np.asarray(u, dtype=float)
            if x.ndim == 1 and u.ndim == 1:
                try:
                    return self._evaluate(x.tolist(), u.tolist(), SCALAR, k)
                except VehdynError:
                    raise
                except (ArithmeticError, ValueError):  # no IEEE result in Python: numpy's rules (inf, nan)
                    pass
        states = equations.named_states(x, self._state_index)
        inputs = equations.named_inputs(u, self._input_index)
        k = self._constants() if k is None else k
        friction = (k.road_friction, k.road_friction)
        if callable(self.friction):  # the road under each axle's centre
            p = self.parameters
            friction = tuple(friction_at(self.friction, *body_point(equations.NUMPY, states[3], states[4], states[5],
                                                                      forward, 0.0))
                             for forward in (p.a, -p.b))
        tires = (self.front_tire, self.rear_tire)
        return states, inputs, k, equations.evaluate(xp, tires, k, states, inputs, friction)

    def axle_law_forces(self, axle, fz, kappa, alpha, vx):
        """Axle forces in ISO-W from the law of one tire at half the load: those of :meth:`axle_law_loads`.

        Parameters
        ----------
        axle : int
            0 front, 1 rear.
        fz : float or ndarray
            Axle load [N].
        kappa : float or ndarray
            Slip ratio [-] (ISO-W).
        alpha : float or ndarray
            Slip angle [rad] (ISO-W).
        vx : float or ndarray
            Signed wheel-centre speed [m/s].

        Returns
        -------
        tuple
            (F_x [N], F_y [N]) of the axle, ISO-W.
        """
        fx, fy, _ = SingleTrack.axle_law_loads(self, axle, fz, kappa, alpha, vx)
        return fx, fy

    def axle_law_loads(self, axle, fz, kappa, alpha, vx):
        """Axle forces and rolling-resistance moment in ISO-W from the law of one tire at half the load.

        The two tires of an axle are mirror images: when the law has a lateral force at zero slip
        (ply-steer and conicity shifts of a Magic Formula file), the axle force is the tire's plus
        its mirror image's, F_y = F_y(alpha) - F_y(-alpha), F_x = F_x(alpha) + F_x(-alpha),
        M_y = M_y(alpha) + M_y(-alpha), so that a vehicle with zero steer runs straight; laws
        without such shifts are evaluated once, doubled
        (:func:`vehdyn.components.tire_forces.axle_tire_loads`, on the law's own road).

        Parameters
        ----------
        axle : int
            0 front, 1 rear.
        fz : float or ndarray
            Axle load [N].
        kappa : float or ndarray
            Slip ratio [-] (ISO-W).
        alpha : float or ndarray
            Slip angle [rad] (ISO-W).
        vx : float or ndarray
            Signed wheel-centre speed [m/s].

        Returns
        -------
        tuple
            (F_x [N], F_y [N], M_y [N*m]) of the axle, ISO-W.
        """
        tire = self.front_tire if axle == 0 else self.rear_tire
        return axle_tire_loads(equations.NUMPY, tire, fz, kappa, alpha, vx, self._mirrored[_AXLES[axle]], 1.0, False)

    def wheel_pair_law_loads(self, axle, left_load, right_load, kappa, alpha, vx):
        """ISO-W (F_x, F_y, M_y) of the left, then the right tire of ``axle`` at their own loads.

        The mirror image of the law (:meth:`axle_law_loads`) on the side
        :func:`~vehdyn.components.tire_setup.mirrored_wheel` names: the left tire for a right-side
        law, the right one for a ``TYRESIDE = 'LEFT'`` file
        (:func:`vehdyn.components.tire_forces.wheel_pair_tire_loads`).

        Parameters
        ----------
        axle : int
            0 front, 1 rear.
        left_load, right_load : float or ndarray
            Wheel loads [N].
        kappa : float or ndarray
            Slip ratio [-] (ISO-W).
        alpha : float or ndarray
            Slip angle [rad] (ISO-W).
        vx : float or ndarray
            Signed wheel-centre speed [m/s].

        Returns
        -------
        tuple
            (F_x, F_y, M_y of the left tire, F_x, F_y, M_y of the right one) [N, N, N*m], ISO-W.
        """
        name = _AXLES[axle]
        tire = self.front_tire if axle == 0 else self.rear_tire
        side = self._mirrored_wheels[name]
        return wheel_pair_tire_loads(equations.NUMPY, tire, left_load, right_load, kappa, alpha, 0.0, vx,
                                     side == "left",
                                     side == "right", 1.0, False)

    def compiled_rhs(self):
        """The rhs compiled by numba for ``simulate(..., backend="compiled")`` (see :meth:`vehdyn.Model.compiled_rhs`).

        The same equations (:mod:`~vehdyn.handling.single_track_equations`) with the Magic Formula
        or linear law compiled; every mode (force or wheel spin, with or without tire lag). Raises
        ParameterError for another tire law or a batch model (array parameters).
        """
        cached = self.__dict__.get("_compiled_model")
        if cached is not None and cached[0] is self.parameters:  # variants() get new parameters
            return cached[1]
        from vehdyn.handling import _single_track_numba

        compiled = _single_track_numba.compiled_model(self)
        self._compiled_model = (self.parameters, compiled)
        return compiled

    def compiled_batch(self, n_variants: int | None = None):
        """The compiled rhs of a batch (:func:`vehdyn.simulation.compiled.solve_batch`): this model's
        variants (array parameters, :meth:`variants`), or ``n_variants`` copies of a model with
        scalar parameters (a batch of initial states or inputs). ``simulate`` runs it on the compiled
        backend, each variant with its own step-size control: every variant's states are bitwise
        those of its own compiled run. Raises ParameterError as :meth:`compiled_rhs` does.

        Parameters
        ----------
        n_variants : int, optional
            The number of copies of a model with scalar parameters (default: the variants).

        Returns
        -------
        CompiledBatch
        """
        from vehdyn.handling import _single_track_numba

        return _single_track_numba.compiled_batch(self, n_variants)

    @staticmethod
    def compiled_batch_of(models):
        """The compiled batch of many models with scalar parameters and one :meth:`batch_structure`
        (their parameters and tires may differ): what :func:`vehdyn.simulate.simulate_many` runs.

        Parameters
        ----------
        models : sequence of SingleTrack
            The models.

        Returns
        -------
        CompiledBatch
        """
        from vehdyn.handling import _single_track_numba

        return _single_track_numba.compiled_batch(list(models))

    def batch_structure(self) -> tuple:
        """What models must share to run in one compiled batch (modes, tire laws, friction mode, signals).

        Returns
        -------
        tuple
            A hashable key.
        """
        from vehdyn.handling import _single_track_numba

        return _single_track_numba.batch_structure(self)

    def rhs(self, t, x, u):
        """State derivatives (equations in the module docstring)."""
        states, inputs, k, e = self._evaluate(x, u)
        rates = equations.derivatives(_namespace(states), k, e, states, inputs)
        return _stack([rates[j] for j in self._state_order])

    def output(self, t, x, u):
        """Outputs (see :attr:`outputs`)."""
        states, _, _, e = self._evaluate(x, u)
        return _stack(self._output_values(_namespace(states), states, e))

    def _output_values(self, xp, states, e):
        values = equations.outputs(xp, states, e)
        if self.lateral_load_transfer:
            values = values + equations.wheel_load_outputs(e)
        if self.roll:
            values = values + (states[12], states[13])
        if self._understeer_terms["compliance_steer"]:
            values = values + (e.front_compliance_steer_angle, e.rear_compliance_steer_angle)
        return values

    def symbolic_equations(self, xp, x, u, parameters):
        """These equations on symbols (:meth:`vehdyn.Model.symbolic_equations`, for
        :func:`vehdyn.symbolic.to_casadi`): the same functions of
        :mod:`~vehdyn.handling.single_track_equations` as :meth:`rhs` and :meth:`output`, the tire
        laws through their kernels (Magic Formula or linear).

        Parameters
        ----------
        xp : type
            The symbolic namespace.
        x : casadi.SX
            States [each state's unit].
        u : casadi.SX
            Inputs [each input's unit].
        parameters : dict
            Symbols for fields of :class:`SingleTrackParameters`, by name [their units].

        Returns
        -------
        tuple
            (dx/dt, y, the model's values of the named parameters).

        Raises
        ------
        ParameterError
            For a tire law without a kernel (naming it), a road friction given as a function of
            position, a batch model, or a name that is not a parameter.
        """
        names = [f.name for f in dataclasses.fields(self.parameters)]
        for name in parameters:
            if name not in names:
                raise ParameterError(f"{name!r} is not a SingleTrack parameter (those are {names})", key="parameters",
                                     value=name)
        derived = sorted({"mass", "cg_height", "a", "b", "gravity"} & set(parameters))
        if self.lateral_load_transfer and derived:
            raise ParameterError(f"with lateral load transfer, {derived[0]} sets the transfer coefficients, which are "
                                 "checked on numbers (lateral_load_transfer_coefficients): it cannot be a symbol",
                                 key="parameters", value=derived[0])
        if self.n_variants is not None:
            raise ParameterError("a batch SingleTrack (array parameters) has no symbolic form: take one variant",
                                 key="parameters", value=self.n_variants)
        if callable(self.friction):
            raise ParameterError("a road friction that is a function of position has no symbolic form: give a "
                                 "number", key="friction", value=self.friction)
        xp = with_tire_hooks(xp)
        for axle, tire in zip(_AXLES, (self.front_tire, self.rear_tire)):
            try:
                xp.tire_law(tire, 3000.0, 0.0, 0.0, 0.0, 20.0)
            except ParameterError as error:
                raise ParameterError(f"SingleTrack's {axle}_tire: {error}", key=f"{axle}_tire",
                                     value=type(tire).__name__) from None
        k = self._constants(dict(parameters))
        states, inputs, k, e = self._evaluate([x[i] for i in range(self.n_states)],
                                              [u[i] for i in range(self.n_inputs)], xp, k)
        rates = equations.derivatives(xp, k, e, states, inputs)
        return ([rates[j] for j in self._state_order], self._output_values(xp, states, e),
                {name: float(getattr(self.parameters, name)) for name in parameters})

    # ------------------------------------------------------------------ operating points
    def straight_running(self, speed: float, **states) -> np.ndarray:
        """State vector of straight running at ``speed`` (wheels rolling freely, tires relaxed).

        Parameters
        ----------
        speed : float
            Forward speed [m/s].
        **states
            Other states by name (``x=..., yaw_angle=...``) [their units].

        Returns
        -------
        ndarray
            The state vector [SI units].
        """
        values = {"longitudinal_velocity": speed}
        if self.wheel_spin:
            for axle in _AXLES:
                values[f"{axle}_wheel_speed"] = speed / self.parameters.rolling_radius
        values.update(states)
        return self.state_vector(values)

    def linearize(self, x0=None, u0=None, t: float = 0.0, method: str = "auto", *, speed: float | None = None):
        """Linearize about ``(x0, u0)``, or about straight running at ``speed`` [m/s].

        With ``speed`` given (and no ``x0``), the operating point is :meth:`straight_running`; in
        force mode the rear axle force balances the aerodynamic drag so that the speed is an
        equilibrium. See :meth:`vehdyn.Model.linearize` (``method="exact"``: CasADi's Jacobians of
        these equations); :meth:`lateral_yaw` extracts the lateral-yaw block that the linear
        bicycle model describes.
        """
        if speed is not None:
            if x0 is not None:
                raise ParameterError("give either x0 or speed, not both", key="speed", value=speed)
            x0 = self.straight_running(speed)
            if u0 is None:  # hold the speed: the rear axle balances the drag
                drag = float(np.asarray(self.parameters.drag_factor)) * speed * abs(speed)
                if self.wheel_spin:
                    u0 = {"rear_drive_torque": drag * float(np.asarray(self.parameters.rolling_radius))}
                else:
                    u0 = {"rear_longitudinal_force": drag}
        return super().linearize(x0, u0, t, method)

    def lateral_yaw(self, speed: float, *, crosswind: bool = False):
        """The lateral-yaw linearization at straight running at ``speed`` [m/s].

        States ``lateral_velocity``, ``yaw_rate`` (and the lateral deflections with tire lag), inputs
        ``front_steer_angle``, ``rear_steer_angle`` (and ``wind_velocity_lateral`` with
        ``crosswind=True``), and the first nine outputs (those of
        :class:`~vehdyn.handling.LinearBicycle`): with linear tires and no tire lag its matrices are
        the bicycle model's (evaluated at zero longitudinal force, the constant-speed assumption of
        the bicycle model). In straight running these states decouple from the others exactly
        (every coupling term is proportional to v, r or the steer angle), so the block is exact.

        Parameters
        ----------
        speed : float
            Forward speed [m/s].
        crosswind : bool
            Keep the input ``wind_velocity_lateral``.

        Returns
        -------
        LinearModel
        """
        from vehdyn.model import LinearModel

        full = self.linearize(speed=speed, u0=self.input_vector())
        keep = [self.index("lateral_velocity"), self.index("yaw_rate")]
        if self.tire_lag:
            keep += [self.index(f"{axle}_lateral_deflection") for axle in _AXLES]
        inputs = [self.index(name, "inputs") for name in ("front_steer_angle", "rear_steer_angle")
                  + (("wind_velocity_lateral",) if crosswind else ())]
        outputs = list(range(9))
        return LinearModel(full.A[np.ix_(keep, keep)], full.B[np.ix_(keep, inputs)],
                           full.C[np.ix_(outputs, keep)], full.D[np.ix_(outputs, inputs)],
                           states=[self.states[k] for k in keep], inputs=[self.inputs[k] for k in inputs],
                           outputs=[self.outputs[k] for k in outputs], name=f"SingleTrack lateral-yaw at {speed:g} m/s")

    def peak_slip(self, axle: str) -> tuple:
        """Where the pure-slip force of ``axle``'s tire law peaks, at the static axle load.

        Parameters
        ----------
        axle : str
            ``"front"`` or ``"rear"``.

        Returns
        -------
        tuple of float
            (slip ratio [-], tangent of the slip angle [-]) of the peak longitudinal and lateral
            force (1 and tan 80 deg for a law without a peak).
        """
        if axle not in self._peak_slip:
            raise ParameterError(f"axle must be 'front' or 'rear', got {axle!r}", key="axle", value=axle)
        return self._peak_slip[axle]

    def axle_cornering_stiffness(self, fz=None, eps: float = 1e-6):
        """Cornering stiffnesses (front, rear) of the AXLES [N/rad] at loads ``fz`` (default static).

        -dF_y/d(alpha) at zero slip of two tires, each at half the axle load, by a central
        difference of the tire law (SAE sign: positive).

        Parameters
        ----------
        fz : (float, float), optional
            Axle loads [N] (default: static).
        eps : float
            Slip-angle step of the difference [rad].

        Returns
        -------
        tuple
            (front, rear) [N/rad].
        """
        loads = self.parameters.static_axle_loads() if fz is None else fz
        out = []
        for tire, load in zip((self.front_tire, self.rear_tire), loads):
            plus = tire.forces(0.5 * np.asarray(load, float), 0.0, eps, 0.0, 20.0).fy
            minus = tire.forces(0.5 * np.asarray(load, float), 0.0, -eps, 0.0, 20.0).fy
            # ISO-W: F_y falls with alpha for the usual tire; the SAE stiffness is the same magnitude
            out.append(-2.0 * (np.asarray(plus) - np.asarray(minus)) / (2 * eps))
        return tuple(out)

    def __repr__(self) -> str:
        return (f"<SingleTrack of {self.vehicle.name!r}: tires {type(self.front_tire).__name__}/"
                f"{type(self.rear_tire).__name__}, wheel_spin={self.wheel_spin}, tire_lag={self.tire_lag}, "
                + ("lateral_load_transfer=True, " if self.lateral_load_transfer else "")
                + ("roll=True, " if self.roll else "") +
                f"{self.n_states} states>")
