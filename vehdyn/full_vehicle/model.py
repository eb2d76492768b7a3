"""The full vehicle: a sprung body on four corners, assembled from vehdyn's layers.

Layers used (nothing restated): the sprung body's Newton-Euler equations and Euler-angle
kinematics from :mod:`vehdyn.mechanics`; the tire laws of :mod:`vehdyn.tire` (any
:class:`~vehdyn.tire.TireModel` that takes combined slip); the slip, relaxation, low-speed and
wheel-torque functions and the tire step of :mod:`vehdyn.components` (shared with
:class:`~vehdyn.handling.SingleTrack`); the corner layout and signal names of
:class:`vehdyn.ride.FullCar`. The equations are in
:mod:`~vehdyn.full_vehicle.assembly` and the modules it calls (:mod:`~vehdyn.full_vehicle.body`,
:mod:`~vehdyn.full_vehicle.corner`, :mod:`~vehdyn.full_vehicle.steering`,
:mod:`~vehdyn.full_vehicle.driveline`, :mod:`~vehdyn.full_vehicle.aero`).

Modelling choices (where the full vehicle differs from the models below it)
---------------------------------------------------------------------------
* The unsprung masses move with the body in its x-y plane, as points at the wheel centres, and
  vertically on their own (:mod:`~vehdyn.full_vehicle.body`): they roll and pitch with the body,
  where :class:`~vehdyn.handling.LateralYawRoll` keeps them in a non-rolling frame. Their lateral
  inertia reaches the body through the linkage at the roll centre, the share lambda of its moment
  (``suspension.*_unsprung_transfer_fraction``, default 1, the textbook's) taken by the tires
  directly (:mod:`~vehdyn.full_vehicle.corner`; the closed form of the steady roll in
  :class:`FullVehicle`).
* Each wheel carrier slides along the body z axis and keeps the body's orientation (camber follows
  roll, as between parallel wishbones). Tire slip is taken at the contact point (ground level below
  the wheel centre, rigid with the body but for the travel), so that a roll about a roll axis on
  the ground makes no slip; ``wheel_speed`` is the spin relative to the carrier (the tread speed
  omega R_e), and the spin inertia's share of the body's pitch acceleration, I_w dq/dt, is
  neglected (I_w / (m_s h_s^2) ~ 0.5 %).
* Suspension forces act along the body z axis, tire loads along the vertical; the tires'
  longitudinal and lateral forces lie in the road plane (ISO-W: along the wheel heading projected
  on the road and its normal there) and reach the body through the linkage at the contact point on
  the road, whose height below the CG changes with heave, roll, pitch and the road under the wheel.
  So in a steady turn or in braking the four tire loads carry the weight (to second order in the
  angles: 0.27 % at 0.1 rad of roll). Angles are small in the force projections of the unsprung
  masses (their vertical equation uses the tire load itself, not its body-z component).
* The roll centres and anti-pitch lines are fixed in the body (no migration with travel).
* Compliance steer (``suspension.*_lateral_force_compliance_steer`` c_i and
  ``*_aligning_moment_compliance_steer`` e_i, per unit of the axle's force and moment): each wheel
  steers by 2 c_i F_y + 2 e_i M_z of its own lateral force and its law's aligning moment (SAE), the
  axle's c_i F_y,i + e_i M_z,i when its two wheels share them (Gillespie 1992, ch. 6, Table 6.1;
  Milliken & Milliken 1995, ch. 5). Quasi-static: with tire lag the forces come from the
  deflections, so the steer is explicit (the law once at the wheel's steer without it, then every
  force at the full steer); without tire lag a Newton step with the law's slope at the static load
  and a secant step (:func:`vehdyn.components.tire_forces.secant_compliance`). The understeer
  gradient from the trims is then the budget's (:func:`vehdyn.handling.understeer_budget`) to 1e-8
  with linear tires (``tests/full_vehicle/test_compliance_steer.py``).

What it reduces to
------------------
Every coupling the full vehicle adds to the ride model :class:`vehdyn.ride.FullCar` has the sprung
CG's height above the contact points as its lever: gravity's moment on the pitched or rolled body
(m_s g h_s), the unsprung masses' fore-aft and sideways inertia (m_u (h_s - h_u)^2), the wheels'
spin and the tires' longitudinal and lateral slip as the contact points move by h_s theta, h_s phi,
the anti-pitch lines (slope f h / L) and the drag's pitch moment; and the drive force against the
drag, whose lever is the CG's height above the road (so the reduction holds without drag). A vehicle with its CG heights
going to zero (``mass.sprung_cg_height`` and ``mass.cg_height``; roll centres on the ground, no
roll steer or camber gains, linear tires) is FullCar in straight running: its eigenvalues and road
responses converge on FullCar's in proportion to the height (``tests/full_vehicle``). The sizes on
the sedan: 4.0 % of the pitch stiffness (11 % of the roll stiffness), 0.9 % of the pitch inertia
(6.8 % of roll), 1.4 % of the pitch inertia for the wheel spin; heave and pitch eigenvalues 1.5 %,
2.1 % off FullCar's, the roll mode 41 % (it couples with the lateral motion: compared with
:class:`vehdyn.handling.LateralYawRoll`).
"""

from __future__ import annotations


import numpy as np

from vehdyn.components.tire_forces import tire_loads
from vehdyn.components.tire_setup import (longitudinal_relaxation_lengths, mirrored_wheel, road_friction,
                                          tire_characteristics)
from vehdyn.components.xp import stack as _stack
from vehdyn.errors import ParameterError, VehdynError
from vehdyn.params.checks import is_number
from vehdyn.model import Model
from vehdyn.params import Vehicle
from vehdyn.signals import Signal
from vehdyn.units import GRAVITY
from vehdyn.full_vehicle import assembly
from vehdyn.full_vehicle.corner import CORNERS

__all__ = ["FullVehicle"]

_AXLES = ("front", "rear")
_STATE_UNITS = {"wheel_speed": ("rad/s", "spin of the wheel (positive rolling forwards)"),
                "unsprung_displacement": ("m", "vertical displacement of the wheel centre from static (up)"),
                "unsprung_velocity": ("m/s", "vertical velocity of the wheel centre (up)"),
                "lateral_deflection": ("m", "lateral deflection of the tire's contact point (SAE y, relaxation state)"),
                "longitudinal_deflection": ("m", "longitudinal deflection of the tire (relaxation state, + driving)")}
_BODY_SIGNALS = {
    "longitudinal_velocity": ("m/s", "body-frame velocity u of the sprung CG (forward)"),
    "lateral_velocity": ("m/s", "body-frame velocity v of the sprung CG (right, SAE)"),
    "vertical_velocity": ("m/s", "body-frame velocity w of the sprung CG (down, SAE)"),
    "roll_rate": ("rad/s", "body rate p of the sprung mass"),
    "pitch_rate": ("rad/s", "body rate q of the sprung mass"),
    "yaw_rate": ("rad/s", "body rate r of the sprung mass"),
    "roll_angle": ("rad", "Euler roll angle phi (right side down +)"),
    "pitch_angle": ("rad", "Euler pitch angle theta (nose up +)"),
    "yaw_angle": ("rad", "Euler yaw angle psi (heading, turning right +)"),
    "x": ("m", "earth-fixed X of the sprung CG"),
    "y": ("m", "earth-fixed Y of the sprung CG (SAE: right of the initial heading)"),
    "z": ("m", "earth-fixed Z of the sprung CG from its static position (down +)"),
}
_INPUT_SIGNALS = {
    "front_steer_angle": ("rad", "front road-wheel steer angle (bicycle value; split by the Ackermann fraction)"),
    "rear_steer_angle": ("rad", "rear road-wheel steer angle (SAE)"),
    "drive_torque": ("N*m", "drive torque on the wheel"),
    "brake_torque": ("N*m", "brake torque magnitude on the wheel (>= 0; opposes the spin)"),
    "road_displacement": ("m", "road elevation under the wheel (up)"),
    "road_velocity": ("m/s", "rate of change of the road elevation under the wheel"),
    "wind_velocity_lateral": ("m/s", "wind velocity over ground along the vehicle's y axis (SAE, to the right)"),
}


def check_combined_slip(tire, load, name):
    """Raise ParameterError unless ``tire`` takes combined slip: finite forces with F_x responding to
    kappa and F_y to alpha when both act at once (or the law declares ``combined_slip = False``)."""
    from vehdyn.tire import TireModel

    if not isinstance(tire, TireModel):
        raise ParameterError(f"{name} must be a vehdyn.tire.TireModel, got {type(tire).__name__}", key=name,
                             value=tire)
    reason = None
    if getattr(tire, "combined_slip", True) is False:
        reason = "it declares combined_slip = False"
    else:
        try:
            both = tire.forces(float(load), 0.05, 0.05, 0.0, 20.0)
            fx, fy = float(both.fx), float(both.fy)
            if not (np.isfinite(fx) and np.isfinite(fy)):
                reason = f"at kappa = alpha = 0.05 it returns F_x = {fx}, F_y = {fy}"
            elif abs(fx) <= 1e-6 * load or abs(fy) <= 1e-6 * load:
                reason = f"at kappa = alpha = 0.05 it returns F_x = {fx:.6g} N, F_y = {fy:.6g} N (one slip ignored)"
        except Exception as exc:  # noqa: BLE001 - any failure of the law is the reason
            reason = f"it fails at kappa = alpha = 0.05: {type(exc).__name__}: {exc}"
    if reason is not None:
        raise ParameterError(f"{name} ({type(tire).__name__}) cannot take combined slip, which the full vehicle "
                             f"needs (every wheel spins and slips sideways): {reason}", key=name,
                             value=type(tire).__name__)


class FullVehicle(Model):
    r"""Full vehicle: 6-DOF sprung body, four corners with wheel hop and wheel spin, any tire law.

    Parameters
    ----------
    vehicle : Vehicle
        Masses and inertias (sprung tensor with I_xz; ``mass.sprung_yaw_inertia`` or derived),
        geometry (roll-centre heights), suspension (wheel rates, dampers, anti-roll bars, roll
        steer, optional camber gains and anti-dive/anti-squat, the unsprung transfer fractions,
        lateral-force and aligning-moment compliance steer), tires (vertical stiffness and
        damping, rolling radius, wheel inertia, relaxation lengths, law), steering (Ackermann
        fraction), aero (drag, lift, the crosswind's side-force slope and
        centre of pressure, as the handling models).
    front_tire, rear_tire : TireModel, optional
        The law of one tire of each axle (ISO-W); default the vehicle's (``vehicle.tires.model``,
        through :func:`vehdyn.tire.tire_for_vehicle`). It must take combined slip.
    tire_lag : bool
        Tire deflection (relaxation) states per corner (default True; needed at low speed).
    road : RoadProfile or callable, optional
        A road under the wheels: a :class:`vehdyn.ride.RoadProfile` along the earth X axis (the
        same for both tracks) or a callable ``road(X, Y) -> (elevation, slope_X, slope_Y)`` of
        arrays [m, -, -]. Its elevation and rate are added to the ``road_displacement_*``,
        ``road_velocity_*`` inputs. Default: flat.
    friction : float or callable, optional
        The road's friction relative to the tire law's own [-]: a constant ratio (e.g. 0.5), or a
        callable ``friction(X, Y) -> ratio`` of earth positions [m] (arrays), evaluated at each
        contact point (e.g. 0.2 / 0.9 on the right half of a split-mu road for a law with mu = 0.9;
        numpy backend only). Applied to each tire by similarity, as in
        :class:`~vehdyn.handling.SingleTrack` (:mod:`vehdyn.components.tire_forces`). Default: the
        law as it is.
    longitudinal_relaxation_length : float or (float, float), optional
        sigma_x [m] of the front and rear tires, as :class:`~vehdyn.handling.SingleTrack` (default
        from the Magic Formula, else the lateral).
    low_speed_damping_speed, brake_regularization_speed : float
        v_l [m/s] and omega_b [rad/s] as in :class:`~vehdyn.handling.SingleTrack` (2 m/s, 1 rad/s).
    gravity : float
        [m/s^2].

    Signals
    -------
    states
        ``longitudinal_velocity``, ``lateral_velocity``, ``vertical_velocity``, ``roll_rate``,
        ``pitch_rate``, ``yaw_rate``, ``roll_angle``, ``pitch_angle``, ``yaw_angle``, ``x``, ``y``, ``z``
        (sprung CG, SAE); then for each corner suffix ``_front_left``, ``_front_right``,
        ``_rear_left``, ``_rear_right``: ``wheel_speed_*``, ``unsprung_displacement_*``,
        ``unsprung_velocity_*`` and, with tire lag, ``lateral_deflection_*``,
        ``longitudinal_deflection_*`` (order: :data:`vehdyn.full_vehicle.assembly.STATES`).
    inputs
        ``front_steer_angle``, ``rear_steer_angle``, ``drive_torque_*``, ``brake_torque_*``,
        ``road_displacement_*``, ``road_velocity_*``, ``wind_velocity_lateral``.
    outputs
        Accelerations of the CG (intermediate axes), sideslip, speed, curvature, attitude, sprung
        vertical acceleration, position, and per corner ``normal_load_*``, ``slip_angle_*``,
        ``slip_ratio_*``, ``longitudinal_force_*``, ``lateral_force_*``, ``suspension_travel_*``,
        ``camber_angle_*``, ``steer_angle_*`` (the road-wheel angle, compliance steer included), and
        ``compliance_steer_angle_*`` where the vehicle has a compliance steer.

    Notes
    -----
    The state zero (with any speed set) is the static equilibrium at rest: spring preloads and tire
    deflections carry the static loads. The sprung CG sits where the total CG and the unsprung
    masses (at the axles) put it, so that the static loads split exactly by the total CG, and the
    unsprung masses (points at the "wheel centres") at the height h_u = (m h - m_s h_s) / m_u that
    makes the total CG height the file's ``mass.cg_height`` (0.28 m for the shipped sedan; the
    rolling radius is used for the tread speed only).
    Equations and modelling choices: module docstrings of :mod:`vehdyn.full_vehicle`.

    ``vehdyn.simulate(model, ..., method="RK45" or "DOP853")`` runs the compiled rhs (numba; see
    :meth:`compiled_rhs`), two orders of magnitude faster than the numpy rhs under ``solve_ivp``
    (``benchmarks/bench_full_vehicle.py``); the first call compiles it (about a minute, then cached
    on disk).

    The sprung body's Newton-Euler equations in body axes with the wheels' x-y inertia projected
    (:mod:`~vehdyn.full_vehicle.body`), each corner's wheel hop, spin and tire relaxation
    (:mod:`~vehdyn.full_vehicle.corner`, :mod:`vehdyn.components`):

    .. math::

        m_s (\dot V + \omega \times V) &= \sum_i F_i + F_{aero} + m_s g,\qquad
        J \dot\omega + \omega \times J \omega = \sum_i r_i \times F_i + M_{aero}\\
        m_{u,i} \ddot z_{u,i} &= F_{z,i} - F_{susp,i} - m_{u,i} g,\qquad
        F_{z,i} = \max(F_{s,i} + k_t (z_r - z_{u,i}) + c_t (\dot z_r - \dot z_{u,i}), 0)\\
        I_w \dot\omega_i &= T_{drive,i} - T_{brake,i}\,\mathrm{sat}(\omega_i / \omega_b) - R_e F_{x,i} + M_{y,i},
        \qquad \dot\rho_{y,i} = V_{sy,i} - |V_{x,i}| \rho_{y,i} / \sigma_y

    **Steady roll, derived.** The unsprung masses' lateral force (inertia and the body-y component of
    their weight) reaches the body through the linkage at the roll centre, as the tire's does; the
    share lambda_i (``suspension.*_unsprung_transfer_fraction``) of its moment about the roll
    centre, m_ui h_u A, is taken by the tire loads directly, the rest by the springs
    (:mod:`~vehdyn.full_vehicle.corner`). lambda = 1, the default, is the textbook's treatment
    (Milliken & Milliken 1995, ch. 18; Gillespie 1992, ch. 7) and a beam or swing axle's physics;
    lambda = 0 describes parallel equal-length links or a sliding pillar (the wheel carrier keeps the
    body's orientation and passes the moment to the body as a couple), (T/2)/d an independent
    suspension with a front-view swing arm d long. In a steady turn, linear and small angles, the
    body's roll gradient and each axle's lateral load transfer Delta N_i = (N_outer - N_inner)/2 are
    then (:func:`vehdyn.handling.steady_roll`, where every symbol is defined; A = a_y + g phi)

    .. math::

        \frac{\phi}{a_y} = \frac{M}{K_{ser} - g M},\qquad
        M = \underbrace{\sum_i m_{si} (h_s - h_i)}_{\text{sprung moment}}
          + \underbrace{\sum_i m_{ui} (1 - \lambda_i) h_u}_{\text{unsprung, through the springs}}
          + \underbrace{\sum_i u_i G_i}_{\text{tires' roll}},\qquad
        K_{ser} = \sum_i \frac{K_i K_{ti}}{K_i + K_{ti}}\\
        \Delta N_i T_i = \frac{K_i K_{ti}}{K_i + K_{ti}} \phi + (1 - u_i) G_i A,\qquad
        G_i = m_{si} h_i + m_{ui} \lambda_i h_u,\quad u_i = \frac{K_i}{K_i + K_{ti}}

    (sprung moment about the roll centres, unsprung masses, tire compliance K_ti = k_t T_i^2/2,
    gravity moment g M, roll centres h_i in the geometric transfer m_si h_i). The model reaches it to
    0.01 % with the roll centres on the ground and 0.06 % with them 0.3-0.4 m high (trims at
    +-0.5 m/s^2; the rest is of higher order: the drag's pitch, gyroscopic terms); the sedan
    (CommonRoad's vehicle 2) then rolls 0.01581 rad/(m/s^2), CommonRoad's multi-body model 0.01580
    (``tests/full_vehicle/test_steady_roll.py``).

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, sec. 2.2
       (the tire forces in the road plane), 4.3.2 (similarity), 7.2 and 8.7 (relaxation, low-speed damping).
    .. [2] L. D. Landau, E. M. Lifshitz, *Mechanics*, 3rd ed., 1976, sec. 36 (Euler's equations).
    .. [3] T. R. Kane, D. A. Levinson, *Dynamics: Theory and Applications*, McGraw-Hill, 1985, ch. 6.
    .. [4] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5 and 6 (ride, roll
       centres, anti-pitch geometry).
    .. [5] W. F. Milliken, D. L. Milliken, *Race Car Vehicle Dynamics*, SAE, 1995, ch. 17-18.
    """

    #: Where the equations hold: the body's force projections are those of small roll and pitch angles
    #: (every angle enters through exact rotations, the suspension and tire forces through their
    #: body-axis components). Past these bounds the vehicle is rolling or pitching over; :meth:`rhs`
    #: and the compiled rhs raise :class:`~vehdyn.SimulationError` naming the state and the time.
    #: [rad] (An adaptive solver's trial stage can also land there when its step is far too long for a
    #: sudden input, e.g. a pothole on an otherwise smooth road: give ``max_step`` below the shortest
    #: road feature.)
    domain = {"roll_angle": (-np.pi / 4, np.pi / 4), "pitch_angle": (-np.pi / 4, np.pi / 4)}

    def __init__(self, vehicle: Vehicle, front_tire=None, rear_tire=None, *, tire_lag: bool = True, road=None,
                 friction=None, longitudinal_relaxation_length=None, low_speed_damping_speed: float = 2.0,
                 brake_regularization_speed: float = 1.0, gravity: float = GRAVITY):
        if not isinstance(vehicle, Vehicle):
            raise ParameterError(f"vehicle must be a vehdyn Vehicle, got {type(vehicle).__name__}", key="vehicle",
                                 value=vehicle)
        for name, value in (("low_speed_damping_speed", low_speed_damping_speed),
                            ("brake_regularization_speed", brake_regularization_speed), ("gravity", gravity)):
            if not is_number(value) or not (np.isfinite(value) and value > 0):
                raise ParameterError(f"{name} must be a finite number > 0, got {value!r}", key=name, value=value)
        self.vehicle = vehicle
        self.tire_lag = bool(tire_lag)
        self.gravity = float(gravity)
        self.low_speed_damping_speed = float(low_speed_damping_speed)
        self.brake_regularization_speed = float(brake_regularization_speed)
        self.road = self._check_road(road)
        self.friction = road_friction(friction)
        if callable(self.friction):
            _check_takes_x_y("friction", self.friction, "friction(X, Y) -> ratio")
        self._geometry(vehicle)
        from vehdyn.tire import tire_for_vehicle

        tires = {}
        for axle, tire, load in zip(_AXLES, (front_tire, rear_tire), self.static_tire_loads[::2]):
            tire = tire_for_vehicle(vehicle, axle) if tire is None else tire
            check_combined_slip(tire, load, f"{axle}_tire")
            tires[axle] = tire
        self.front_tire, self.rear_tire = tires["front"], tires["rear"]
        t = vehicle.tires
        lateral = (t.front_relaxation_length, t.rear_relaxation_length)
        if self.tire_lag and min(lateral) <= 0:
            raise ParameterError("tire_lag needs positive tires.front_relaxation_length and "
                                 f"tires.rear_relaxation_length, got {lateral}", key="tires.front_relaxation_length",
                                 value=lateral)
        lateral = tuple(s if s > 0 else 1.0 for s in lateral)
        longitudinal = longitudinal_relaxation_lengths(vehicle, tires, longitudinal_relaxation_length, lateral,
                                                       self.gravity)
        characteristics = [tire_characteristics(tires[axle], load) for axle, load in zip(_AXLES, self.static_tire_loads[::2])]
        self._mirrored = tuple(value[0] for value in characteristics)
        wheels = [mirrored_wheel(tires[axle], value[0]) for axle, value in zip(_AXLES, characteristics)]
        peaks = [value[1] for value in characteristics]
        self._tire_constants = dict(
            mirror_image=tuple(float(wheel == side) for wheel in wheels for side in ("left", "right")),
            lateral_relaxation_length=(lateral[0],) * 2 + (lateral[1],) * 2,
            longitudinal_relaxation_length=(longitudinal[0],) * 2 + (longitudinal[1],) * 2,
            peak_slip_ratio=(peaks[0][0],) * 2 + (peaks[1][0],) * 2,
            peak_tan_slip_angle=(peaks[0][1],) * 2 + (peaks[1][1],) * 2)
        self._compliance = self._compliance_constants()
        self._k = self.constants()
        self._declare_signals()
        phenomena = {"longitudinal", "lateral", "yaw", "roll", "pitch", "heave", "wheel_hop", "wheel_lift",
                     "wheel_spin", "load_transfer", "tire_saturation", "road_input", "aero"}
        if self.tire_lag:
            phenomena.add("tire_lag")
        self.phenomena = frozenset(phenomena)

    # ------------------------------------------------------------------ construction
    def _compliance_constants(self) -> dict:
        """The compliance steer's constants (:class:`~vehdyn.full_vehicle.assembly.Constants`): per
        wheel 2 c_i, 2 e_i and the slope (c_i - e_i t_i) C_i of the law at the static load; ParameterError
        naming the field where the slope is >= 1 (no effective cornering stiffness)."""
        from vehdyn.handling.axle_tires import compliance_steer_slope

        values = {"lateral": [], "moment": [], "slope": []}
        for axle, tire in zip(_AXLES, (self.front_tire, self.rear_tire)):
            c, e, slope = compliance_steer_slope(self.vehicle, axle, tire)
            values["lateral"] += [2.0 * c] * 2
            values["moment"] += [2.0 * e] * 2
            values["slope"] += [slope] * 2
        on = any(v != 0.0 for v in values["lateral"] + values["moment"])
        return dict(compliance_on=float(on), lateral_compliance=tuple(values["lateral"]),
                    moment_compliance=tuple(values["moment"]), compliance_slope=tuple(values["slope"]))

    @staticmethod
    def _check_road(road):
        if road is None:
            return road
        if callable(road):
            _check_takes_x_y("road", road, "road(X, Y) -> (elevation, slope_X, slope_Y)")
            return road
        from vehdyn.road import RoadProfile

        if isinstance(road, RoadProfile):
            return road
        raise ParameterError(f"road must be None, a vehdyn.ride.RoadProfile or a callable road(X, Y) -> (elevation, "
                             f"slope_X, slope_Y), got {type(road).__name__}", key="road", value=road)

    def _geometry(self, vehicle):
        """Corner positions, static loads, sprung inertia; ParameterError naming what does not fit."""
        m, g = vehicle.mass, vehicle.geometry
        unsprung = (0.5 * m.front_unsprung_mass,) * 2 + (0.5 * m.rear_unsprung_mass,) * 2
        if min(unsprung) <= 0:
            key = "mass.front_unsprung_mass" if m.front_unsprung_mass <= 0 else "mass.rear_unsprung_mass"
            raise ParameterError(f"the full vehicle needs unsprung masses > 0 (wheel hop), got {key} = 0", key=key,
                                 value=0.0)
        sprung = m.mass - m.unsprung_mass
        if abs(sprung - m.sprung_mass) > 1e-3 * m.mass:
            raise ParameterError(f"mass.sprung_mass = {m.sprung_mass} kg with unsprung masses {m.unsprung_mass} kg "
                                 f"does not add up to mass.mass = {m.mass} kg (the full vehicle has no other mass)",
                                 key="mass.sprung_mass", value=m.sprung_mass)
        # the unsprung masses sit at the height that makes the total CG height the file's
        unsprung_height = (m.mass * m.cg_height - sprung * m.sprung_cg_height) / m.unsprung_mass
        if not 0.0 < unsprung_height < m.sprung_cg_height:
            raise ParameterError(f"mass.cg_height = {m.cg_height} m puts the unsprung masses at "
                                 f"{unsprung_height:.4g} m "
                                 f"(from m h = m_s h_s + m_u h_u), outside (0, mass.sprung_cg_height = "
                                 f"{m.sprung_cg_height} m)", key="mass.cg_height", value=m.cg_height)
        self.unsprung_cg_height = unsprung_height
        a, b = g.a, g.b
        x_s = (m.rear_unsprung_mass * b - m.front_unsprung_mass * a) / sprung  # sprung CG ahead of the total CG
        a_s, b_s = a - x_s, b + x_s
        L = g.wheelbase
        self.sprung_mass = sprung
        self.sprung_cg_to_front_axle, self.sprung_cg_to_rear_axle = a_s, b_s
        self.corner_x = (a_s, a_s, -b_s, -b_s)
        self.corner_y = (-0.5 * g.front_track, 0.5 * g.front_track, -0.5 * g.rear_track, 0.5 * g.rear_track)
        self.unsprung_masses = unsprung
        weight = sprung * self.gravity
        preload = (0.5 * weight * b_s / L,) * 2 + (0.5 * weight * a_s / L,) * 2
        self.spring_preloads = preload
        self.static_tire_loads = tuple(f + mu * self.gravity for f, mu in zip(preload, unsprung))
        # sprung yaw inertia: given, or what the total leaves (wheels as points at the wheel centres)
        jzz = m.sprung_yaw_inertia
        if jzz is None:
            jzz = m.yaw_inertia - sprung * x_s**2 - sum(mu * ((xc + x_s) ** 2 + yc**2) for mu, xc, yc in
                                                       zip(unsprung, self.corner_x, self.corner_y))
            if jzz <= 0:
                raise ParameterError(f"mass.yaw_inertia = {m.yaw_inertia} kg*m^2 leaves no yaw inertia for the sprung "
                                     f"mass ({jzz:.4g} kg*m^2); give mass.sprung_yaw_inertia", key="mass.yaw_inertia",
                                     value=m.yaw_inertia)
        from vehdyn.mechanics import InertiaTensor

        tensor = InertiaTensor(ixx=m.sprung_roll_inertia, iyy=m.sprung_pitch_inertia, izz=float(jzz),
                               ixz=m.sprung_roll_yaw_product)
        self.sprung_inertia = tensor.matrix

    def constants(self) -> assembly.Constants:
        """The numbers the equations read.

        Returns
        -------
        Constants
            :class:`~vehdyn.full_vehicle.assembly.Constants` (floats and tuples).
        """
        from vehdyn.components.aero import wind_side_force_factor
        from vehdyn.full_vehicle.body import added_mass_projection
        from vehdyn.full_vehicle.corner import unsprung_jacking

        v = self.vehicle
        m, g, s, t, a = v.mass, v.geometry, v.suspension, v.tires, v.aero
        h_s, radius = m.sprung_cg_height, t.rolling_radius
        wheel_z = h_s - self.unsprung_cg_height
        inertia = np.asarray(self.sprung_inertia, dtype=float)
        points = [(x, y, wheel_z) for x, y in zip(self.corner_x, self.corner_y)]
        lam = (s.front_unsprung_transfer_fraction,) * 2 + (s.rear_unsprung_transfer_fraction,) * 2
        hrc = (g.front_roll_centre_height,) * 2 + (g.rear_roll_centre_height,) * 2
        jacking = tuple(float(unsprung_jacking(h, f, self.unsprung_cg_height, y))
                        for h, f, y in zip(hrc, lam, self.corner_y))
        projection = added_mass_projection(self.sprung_mass, inertia, self.unsprung_masses, points, jacking)
        L = g.wheelbase
        gains = (s.front_camber_gain, s.rear_camber_gain)
        half = 0.5 * a.air_density * a.frontal_area
        tup = lambda front, rear: (float(front),) * 2 + (float(rear),) * 2  # noqa: E731
        return assembly.Constants(
            gravity=self.gravity, mass=float(m.mass), sprung_mass=float(self.sprung_mass),
            inertia=tuple(map(tuple, inertia)), inverse_inertia=tuple(map(tuple, np.linalg.inv(inertia))),
            projection=tuple(map(tuple, projection)), cg_height=float(m.cg_height), wheelbase=float(L),
            front_track=float(g.front_track), corner_x=tuple(map(float, self.corner_x)),
            corner_y=tuple(map(float, self.corner_y)), spring_z=float(wheel_z), wheel_z=float(wheel_z),
            contact_z=float(h_s), unsprung_mass=tuple(map(float, self.unsprung_masses)),
            spring_rate=tup(s.front_spring_rate, s.rear_spring_rate), damping=tup(s.front_damping, s.rear_damping),
            spring_preload=tuple(map(float, self.spring_preloads)),
            antiroll_rate=(s.front_antiroll_stiffness / g.front_track**2, s.rear_antiroll_stiffness / g.rear_track**2),
            tire_stiffness=tup(t.vertical_stiffness, t.vertical_stiffness),
            tire_damping=tup(t.vertical_damping, t.vertical_damping),
            static_tire_deflection=tuple(load / t.vertical_stiffness for load in self.static_tire_loads),
            roll_centre_height=tup(g.front_roll_centre_height, g.rear_roll_centre_height),
            anti_pitch=tup(s.front_anti_dive * m.cg_height / L, -s.rear_anti_squat * m.cg_height / L),
            camber_on=0.0 if gains == (None, None) else 1.0,
            camber_gain=tup(gains[0] or 0.0, gains[1] or 0.0),
            roll_steer=tup(s.front_roll_steer, s.rear_roll_steer),
            ackermann_fraction=float(v.steering.ackermann_fraction), rolling_radius=float(radius),
            wheel_spin_inertia=float(t.wheel_spin_inertia), friction_coefficient=float(t.friction_coefficient),
            low_speed_damping_speed=self.low_speed_damping_speed,
            brake_regularization_speed=self.brake_regularization_speed, wheel_spin=True, tire_lag=self.tire_lag,
            road_friction=self.friction if isinstance(self.friction, float) else 1.0,
            friction_scaled=self.friction is not None,
            drag_factor=half * a.drag_coefficient, wind_side_force_factor=wind_side_force_factor(v),
            centre_of_pressure=float(self.corner_x[0] - a.centre_of_pressure_from_front_axle * L),
            front_lift_factor=half * a.front_lift_coefficient, rear_lift_factor=half * a.rear_lift_coefficient,
            unsprung_jacking=jacking,
            **self._tire_constants, **self._compliance)

    def _declare_signals(self):
        states = [Signal(n, *_BODY_SIGNALS[n]) for n in assembly.BODY_STATES]
        kinds = assembly.CORNER_STATES if self.tire_lag else assembly.CORNER_STATES[:3]
        states += [Signal(f"{kind}{sfx}", *_STATE_UNITS[kind]) for kind in kinds for sfx in CORNERS]
        inputs = []
        for name in assembly.INPUTS:
            base = next(b for b in _INPUT_SIGNALS if name.startswith(b))
            inputs.append(Signal(name, *_INPUT_SIGNALS[base]))
        outputs = [Signal(*o) for o in assembly.OUTPUTS]
        outputs += [Signal(f"{name}{sfx}", unit, text) for name, unit, text in assembly.CORNER_OUTPUTS
                    for sfx in CORNERS]
        if self._k.compliance_on:
            outputs += [Signal(f"compliance_steer_angle{sfx}", "rad", "the wheel's compliance steer 2 c F_y + 2 e M_z "
                               "(SAE; in steer_angle)") for sfx in CORNERS]
        self.declare(states=states, inputs=inputs, outputs=outputs)
        self._state_index = [self.state_names.index(n) if n in self.state_names else -1 for n in assembly.STATES]
        self._state_order = [assembly.STATES.index(n) for n in self.state_names]

    # ------------------------------------------------------------------ tire laws
    def corner_law_forces(self, corner, fz, kappa, alpha, gamma, vx, friction=1.0):
        """ISO-W (F_x, F_y) of ``corner``'s tire from ISO-W slips: the forces of :meth:`corner_law_loads`.

        Parameters
        ----------
        corner : int
            0 front left, 1 front right, 2 rear left, 3 rear right.
        fz : float or ndarray
            Normal load [N].
        kappa : float or ndarray
            Slip ratio [-] (ISO-W).
        alpha : float or ndarray
            Slip angle [rad] (ISO-W).
        gamma : float or ndarray
            Inclination angle [rad] (ISO-W).
        vx : float or ndarray
            Signed wheel-centre speed [m/s].
        friction : float or ndarray
            The road's friction relative to the law's own [-] (1: the law as it is).

        Returns
        -------
        tuple
            (F_x [N], F_y [N]), ISO-W.
        """
        fx, fy, _ = self.corner_law_loads(corner, fz, kappa, alpha, gamma, vx, friction)
        return fx, fy

    def corner_law_loads(self, corner, fz, kappa, alpha, gamma, vx, friction=1.0):
        """ISO-W (F_x, F_y, M_y) of ``corner``'s tire from ISO-W slips.

        :func:`vehdyn.components.tire_forces.tire_loads`, the tire step the equations take. ``my``
        is the tire's rolling-resistance moment (ISO-W, about the axis of forward spin; 0 for laws
        without one); it comes from the hysteresis of the tire, not from the road's grip, so the
        friction ratio does not scale it. ``friction`` is the road's friction relative to the law's
        own, applied by similarity (Pacejka 2012, sec. 4.3.2): F(kappa, tan alpha) ->
        mu F(kappa / mu, tan(alpha) / mu), which keeps the slip stiffnesses and scales the peak
        forces and the slips at which they occur. One tire of an axle is the mirror image of the
        law's tire when the law makes a lateral force at zero slip (ply steer, conicity): the left
        one, or the right one where the law is a left tire (a ``.tir`` file with ``TYRESIDE =
        'LEFT'``; :func:`vehdyn.components.tire_setup.mirrored_wheel`). It is evaluated at (-alpha,
        -gamma) and its F_y negated, so that a vehicle with zero steer runs straight.

        Parameters
        ----------
        corner : int
            0 front left, 1 front right, 2 rear left, 3 rear right.
        fz : float or ndarray
            Normal load [N].
        kappa : float or ndarray
            Slip ratio [-] (ISO-W).
        alpha : float or ndarray
            Slip angle [rad] (ISO-W).
        gamma : float or ndarray
            Inclination angle [rad] (ISO-W).
        vx : float or ndarray
            Signed wheel-centre speed [m/s].
        friction : float or ndarray
            The road's friction relative to the law's own [-] (1: the law as it is).

        Returns
        -------
        tuple
            (F_x [N], F_y [N], M_y [N*m]), ISO-W.
        """
        tire = self.front_tire if corner // 2 == 0 else self.rear_tire
        scaled = not (np.ndim(friction) == 0 and friction == 1.0)
        return tire_loads(assembly.NUMPY, tire, fz, kappa, alpha, gamma, vx, self._k.mirror_image[corner] > 0.5,
                          friction, scaled)

    # ------------------------------------------------------------------ the contract
    def _inputs_with_road(self, x, u):
        if self.road is None:
            return u
        u = np.array(u, dtype=float, copy=True)
        # ground points below the wheels: earth X, Y of the body points (x_c, y_c, h_s), their velocity
        for c, (X, Y, VX, VY) in enumerate(self._ground_points(assembly.gather(x, self._state_index))):
            if callable(self.road):
                elevation, slope_x, slope_y = _called("road", self.road, X, Y, ("elevation", "slope_X", "slope_Y"))
            else:
                elevation, slope_x = self.road.sample(X)
                slope_y = 0.0
            u[10 + c] = u[10 + c] + elevation
            u[14 + c] = u[14 + c] + slope_x * VX + slope_y * VY
        return u

    def _ground_points(self, states):
        """Earth (X, Y) of the four contact points and their earth velocities (VX, VY)."""
        R = assembly.NUMPY.rotation_body_to_earth(states[6], states[7], states[8])
        return [assembly.ground_point(R, self._k, states, c) for c in range(4)]

    def _evaluate(self, x, u):
        """(states in the order of :data:`~assembly.STATES`, :class:`~assembly.Evaluation`) at ``x``, ``u``.

        One state (``x`` and ``u`` 1-D) is evaluated on Python floats (:class:`assembly.SCALAR`, ~2.5x
        faster than on numpy scalars, the same numbers), repeated on numpy where a float operation
        has no IEEE result in Python; a batch (trailing axis) on numpy. The states are floats on
        the first path, arrays on the second.
        """
        x = np.asarray(x, dtype=float)
        u = self._inputs_with_road(x, np.asarray(u, dtype=float))
        friction = (self._k.road_friction,) * 4
        one_point = x.ndim == 1 and u.ndim == 1
        if callable(self.friction):  # the road under each contact point
            friction = [_called("friction", self.friction, X, Y, ("ratio",))[0]
                        for X, Y, _, _ in self._ground_points(assembly.gather(x, self._state_index))]
            if not all(np.all(f > 0) for f in friction):
                raise ParameterError("friction(X, Y) must be > 0 under every wheel", key="friction",
                                     value=[float(np.min(f)) for f in friction])
            one_point = one_point and all(np.ndim(f) == 0 for f in friction)
        laws = (self.front_tire, self.rear_tire)
        if one_point:
            point = assembly.gather(x.tolist(), self._state_index)
            try:
                return point, assembly.evaluate(assembly.SCALAR, laws, self._k, point, u.tolist(),
                                                tuple(float(f) for f in friction))
            except VehdynError:
                raise
            except (ArithmeticError, ValueError):  # no IEEE result in Python: numpy's rules (inf, nan)
                pass
        states = assembly.gather(x, self._state_index)
        return states, assembly.evaluate(assembly.NUMPY, laws, self._k, states, list(u), friction)

    def rhs(self, t, x, u):
        """State derivatives (equations in the module docstrings).

        :func:`vehdyn.simulate` raises :meth:`domain_error` when an accepted step leaves
        :attr:`domain` (the vehicle rolls or pitches over); NaN for a state far beyond it
        (:func:`~vehdyn.full_vehicle.assembly.trial_bounds`), so that an adaptive solver's wild
        trial stage is rejected instead of stopping a good run.
        """
        if not np.any(self._outside_domain(x)):
            states, e = self._evaluate(x, u)
            rates = assembly.derivatives(states, e)
            return _stack([rates[j] for j in self._state_order])
        far = self._outside_domain(x, trial=True)
        if np.all(far):
            return np.full(np.shape(x), np.nan)
        with np.errstate(all="ignore"):  # beyond the domain: a crossing about to be located, or discarded
            states, e = self._evaluate(x, u)
            rates = assembly.derivatives(states, e)
            return np.where(far, np.nan, _stack([rates[j] for j in self._state_order]))

    def _outside_domain(self, x, trial=False):
        """True where (per batch member) the roll or pitch angle lies outside :attr:`domain` (with
        ``trial``, outside :func:`~vehdyn.full_vehicle.assembly.trial_bounds`) or is NaN."""
        outside = False
        for name in assembly.DOMAIN_STATES:
            low, high = assembly.trial_bounds(*self.domain[name]) if trial else self.domain[name]
            value = np.asarray(x[self._state_index[assembly.STATES.index(name)]])
            outside = outside | ~((value >= low) & (value <= high))
        return outside

    def domain_error(self, name, value, time):
        """:class:`~vehdyn.full_vehicle.assembly.DomainError`: the vehicle rolls or pitches over."""
        low, high = self.domain[name]
        return assembly.DomainError(assembly.DOMAIN_STATES.index(name), value, time, low, high)

    def compiled_rhs(self):
        """The rhs compiled by numba for ``simulate(..., backend="compiled")`` (see :meth:`vehdyn.Model.compiled_rhs`).

        The same equations (:mod:`~vehdyn.full_vehicle.assembly`) with the Magic Formula or linear
        tire law compiled, with or without tire lag, on a flat road or a
        :class:`~vehdyn.ride.RoadProfile` (its samples interpolated in compiled code as
        :meth:`RoadProfile.sample` does), NaN outside the :attr:`domain` as the numpy rhs. Raises
        :class:`~vehdyn.ParameterError` naming the reason where there is no compiled form: a road
        or friction given as a Python callable, another tire law.
        """
        key = (id(self.road), id(self.friction), tuple((name, tuple(map(float, bounds)))
                                                       for name, bounds in self.domain.items()))
        cached = self.__dict__.get("_compiled_model")
        if cached is not None and cached[0] == key:  # a changed road, friction or domain recompiles args
            return cached[1]
        from vehdyn.full_vehicle import _full_vehicle_numba

        compiled = _full_vehicle_numba.compiled_model(self)
        self._compiled_model = (key, compiled)
        return compiled

    def output(self, t, x, u):
        """Outputs (see :attr:`outputs`)."""
        states, e = self._evaluate(x, u)
        values = assembly.outputs(assembly.SCALAR if type(states[0]) is float else assembly.NUMPY, states, e)
        if self._k.compliance_on:
            values = values + e.compliance_steer
        return _stack(values)

    def symbolic_equations(self, xp, x, u, parameters):
        """These equations on symbols (:meth:`vehdyn.Model.symbolic_equations`, for
        :func:`vehdyn.symbolic.to_casadi`): :func:`~vehdyn.full_vehicle.assembly.evaluate`,
        ``derivatives`` and ``outputs`` with ``xp``, the tire laws through their kernels (Magic
        Formula or linear) and the rigid-body hooks from :mod:`vehdyn.mechanics.kinematics`'s
        ``rotation_matrix`` and ``euler_rates``.

        Parameters
        ----------
        xp : type
            The symbolic namespace.
        x : casadi.SX
            States [each state's unit].
        u : casadi.SX
            Inputs [each input's unit].
        parameters : dict
            Must be empty (the full vehicle's numbers are derived from the vehicle file).

        Returns
        -------
        tuple
            (dx/dt, y, {}).

        Raises
        ------
        ParameterError
            For parameters, a road or a friction that is a function of position, or a tire law without
            a kernel (naming it).
        """
        from vehdyn.components.xp import with_tire_hooks
        from vehdyn.mechanics import kinematics

        if parameters:
            raise ParameterError(f"FullVehicle takes no symbolic parameters, got {sorted(parameters)}",
                                 key="parameters", value=sorted(parameters))
        for name, value in (("road", self.road), ("friction", self.friction if callable(self.friction) else None)):
            if value is not None:
                raise ParameterError(f"FullVehicle with a {name} has no symbolic form (a function of position): "
                                     "build it without", key=name, value=value)
        base = with_tire_hooks(xp)
        for axle, tire in zip(("front", "rear"), (self.front_tire, self.rear_tire)):
            try:
                base.tire_law(tire, 3000.0, 0.0, 0.0, 0.0, 20.0)
            except ParameterError as error:
                raise ParameterError(f"FullVehicle's {axle}_tire: {error}", key=f"{axle}_tire",
                                     value=type(tire).__name__) from None
        hooks = {"rotation_body_to_earth": staticmethod(lambda roll, pitch, yaw:
                                                        kinematics.rotation_matrix(base, roll, pitch, yaw)),
                 "euler_angle_rates": staticmethod(lambda roll, pitch, p, q, r:
                                                   kinematics.euler_rates(base, roll, pitch, p, q, r))}
        xp = type("FULL_VEHICLE_" + base.__name__, (base,), hooks)
        states = assembly.gather([x[j] for j in range(self.n_states)], self._state_index)
        e = assembly.evaluate(xp, (self.front_tire, self.rear_tire), self._k, states,
                              [u[j] for j in range(self.n_inputs)], (self._k.road_friction,) * 4)
        rates = assembly.derivatives(states, e)
        values = assembly.outputs(xp, states, e) + (e.compliance_steer if self._k.compliance_on else ())
        return [rates[j] for j in self._state_order], list(values), {}

    # ------------------------------------------------------------------ operating points
    def static_loads(self) -> dict[str, float]:
        """Tire normal loads at rest on a flat road [N], ``{"normal_load_front_left": ..., ...}``.

        Evaluated by the model's equations at its rest state (which they hold in equilibrium:
        :meth:`rhs` is zero there).

        Returns
        -------
        dict
            ``{"normal_load_front_left": ..., ...}`` [N].
        """
        x0, u0 = self.state_vector(), self.input_vector()
        y = self.output(0.0, x0, u0)
        return {f"normal_load{sfx}": float(y[self.index(f'normal_load{sfx}', 'outputs')]) for sfx in CORNERS}

    def trim(self, speed: float, *, lateral_acceleration: float = 0.0, radius: float | None = None,
             longitudinal_acceleration: float = 0.0, tol: float = 1e-9, guess=None, backend: str = "numpy"):
        """Steady straight running or steady cornering: ``(x0, u0)``.

        Parameters
        ----------
        speed : float
            Speed of the sprung CG in the body's x-y plane [m/s], > 0.
        lateral_acceleration : float
            Steady lateral acceleration [m/s^2] of the total CG in the intermediate axes (the output
            ``lateral_acceleration``; SAE: positive turning right); or give ``radius``.
        radius : float, optional
            Path radius of the sprung CG [m] (positive turning right); overrides
            ``lateral_acceleration`` (a_y = V^2 / R).
        longitudinal_acceleration : float
            Quasi-steady straight braking (< 0) or driving (> 0) [m/s^2] of the total CG: attitude,
            heights, slips and deflections steady, the velocities decreasing in proportion, the
            torques split by the vehicle's ``driveline`` fractions (brake torques when braking).
        tol : float
            Largest derivative allowed [-], relative to g for accelerations and to the speed for
            velocities (every derivative except of x, y and yaw angle).
        guess : (x, u), optional
            A nearby operating point to start from (continuation towards the limit), instead of the
            closed-form start.
        backend : {"numpy", "compiled"}
            The residuals from the numpy equations, or from the model's compiled code (the same
            equations within a few ulps, ~100x less time per evaluation; compiled on first use, or
            loaded from numba's cache): for many trims of a model that also runs compiled.

        Returns
        -------
        x0, u0 : ndarray
            The state (x = y = yaw = 0) and inputs: ``front_steer_angle`` and the drive torques that
            hold the speed (split by the vehicle's ``driveline.front_drive_fraction``), or the brake
            torques of a braking operating point.

        Raises
        ------
        ParameterError
            For a bad speed or acceleration, or when no steady state is found within ``tol`` (e.g.
            beyond the limit lateral acceleration); for a bad ``backend``, or ``"compiled"`` without
            numba or for a model without compiled code (a tire law without one).
        """
        from vehdyn.full_vehicle import operating_points

        return operating_points.trim(self, speed, lateral_acceleration=lateral_acceleration, radius=radius,
                                     longitudinal_acceleration=longitudinal_acceleration, tol=tol, guess=guess,
                                     backend=backend)

    @staticmethod
    def wheel_lift(result) -> dict[str, list[tuple[float, float]]]:
        """The intervals during which each wheel carried no load in a simulation ``result``.

        Parameters
        ----------
        result : SimulationResult
            A run of this model (its ``normal_load_*`` outputs; a wheel is off the ground where its
            load is exactly 0, the model's lift-off).

        Returns
        -------
        dict
            ``{"front_left": [(t_start, t_end), ...], ...}`` [s]; empty lists for wheels that never lifted.
        """
        if not (hasattr(result, "time") and all(f"normal_load{sfx}" in result for sfx in CORNERS)):
            raise ParameterError(f"result must be a FullVehicle SimulationResult (with the normal_load_* outputs), got "
                                 f"{type(result).__name__}", key="result", value=type(result).__name__)
        time = np.asarray(result.time)
        out = {}
        for sfx in CORNERS:
            lifted = np.asarray(result[f"normal_load{sfx}"]) <= 0.0
            edges = np.flatnonzero(np.diff(np.concatenate([[False], lifted, [False]]).astype(int)))
            out[sfx[1:]] = [(float(time[a]), float(time[b - 1])) for a, b in zip(edges[::2], edges[1::2])]
        return out

    def __repr__(self) -> str:
        return (f"<FullVehicle of {self.vehicle.name!r}: tires {type(self.front_tire).__name__}/"
                f"{type(self.rear_tire).__name__}, tire_lag={self.tire_lag}, {self.n_states} states>")


def _check_takes_x_y(name: str, function, form: str):
    """ParameterError naming ``name`` when ``function`` cannot be called with the two positions (X, Y)."""
    import inspect

    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):  # a builtin or an extension type without a signature: called as it is
        return
    try:
        signature.bind(0.0, 0.0)
    except TypeError:
        raise ParameterError(f"{name} must be a callable {form} of the earth positions X, Y [m] (arrays), got "
                             f"{getattr(function, '__name__', type(function).__name__)}{signature}", key=name,
                             value=function) from None


def _called(name: str, function, X, Y, parts: tuple) -> list:
    """The arrays ``function(X, Y)`` returns (one per name in ``parts``: a ratio alone, or the three
    road values), each checked numeric, finite and of the shape of X; ParameterError naming
    ``name``, what came back and where."""
    out = function(X, Y)
    values = [out] if len(parts) == 1 else out
    form = ("a number or an array of X's shape" if len(parts) == 1 else
            "(" + ", ".join(parts) + "), each a number or an array of X's shape") + f" {np.shape(X)} (a value per point)"
    try:
        values = list(values)
    except TypeError:
        values = None
    if values is None or len(values) != len(parts):
        raise ParameterError(f"{name}(X, Y) must return {form}; got {type(out).__name__} {out!r:.80}", key=name,
                             value=out)
    checked = []
    for part, value in zip(parts, values):
        a = np.asarray(value)
        try:
            fits = a.dtype.kind in "iuf" and np.broadcast_shapes(a.shape, np.shape(X)) == np.shape(X)
        except ValueError:
            fits = False
        if not fits:
            raise ParameterError(f"{name}(X, Y) must return {form}; its {part} is {type(value).__name__} "
                                 f"{value!r:.80}", key=name, value=value)
        a = a.astype(float, copy=False)
        if not np.all(np.isfinite(a)):
            full = np.broadcast_to(a, np.shape(X))
            bad = ~np.isfinite(full)
            at_x, at_y = (np.broadcast_to(np.asarray(c, dtype=float), bad.shape)[bad].flat[0] for c in (X, Y))
            raise ParameterError(f"{name}(X, Y) returned a non-finite {part} ({full[bad].flat[0]}) at X = {at_x:.6g} m, "
                                 f"Y = {at_y:.6g} m", key=name, value=float(full[bad].flat[0]))
        checked.append(a)
    return checked
