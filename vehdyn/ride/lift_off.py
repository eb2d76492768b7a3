"""Unilateral tire contact for the linear ride models: the wheel lifts off the road and lands again.

:class:`LiftOff` takes a linear ride model (:class:`~vehdyn.ride.FullCar`,
:class:`~vehdyn.ride.BouncePitch`, :class:`~vehdyn.ride.QuarterCar`, each with unsprung masses)
and replaces its bilateral tire spring by a contact that can push but not pull. Everything else
is the linear model's own matrices: the model adds one correction force per wheel, nothing of the
ride model's equations is restated.

Equations
---------
The linear model (:mod:`vehdyn.ride._ride_model`) is M q'' + C q' + K q = F u with the tire of
wheel i a spring k_t and damper c_t on the tire deflection (compression) z_r - z_u, so that its
force on the wheel is the static load plus

    dF_lin = k_t (z_r - z_u) + c_t (z_r' - z_u')           [N, up on the wheel]

with z_r the road under the wheel and z_u the wheel's displacement (both up from static
equilibrium, as in every ride model). A real tire carries no tension: with the static load F_s and
the static deflection delta_0 = F_s / k_t, the tire's total compression is
delta = delta_0 + z_r - z_u and its force

    F = max(F_s + dF_lin, 0)   where delta > 0,   F = 0 where delta <= 0

(the same law as the full vehicle's corners, :func:`vehdyn.full_vehicle.corner.normal_load`: the
wheel is off the road when the tire is uncompressed; while it unloads, the damper cannot pull it
down either). The model is the linear one with the correction f_c = F - (F_s + dF_lin) added as a
force on the wheel:

    x' = A x + B u + e_i f_c / m_u,       y = C x + D u (+ f_c in ``dynamic_tire_load``,
    + f_c / m_u in ``unsprung_acceleration`` of wheel i)

so that with every wheel on the road (f_c = 0) it *is* the linear model, to round-off. While a
wheel is off the road it flies under gravity and its suspension spring and damper only,
m_u z_u'' = F_susp - m_u g in absolute terms (in the model's coordinates about the static
equilibrium the static loads are part of the correction).

Static loads: the static equilibrium of the linear model's springs under gravity, K q_g = f_g with
f_g = -g x (the mass of each translational coordinate: the body's heave, the wheels), F_s,i =
-k_t,i z_u,i(q_g); for the full car of a vehicle the sprung weight splits by the sprung CG's
position (m_s g b / (2 L) at a front wheel) and each wheel adds its own weight.

Signs: as the ride models (up positive, ``dynamic_tire_load`` positive = more load, so a lifted
wheel shows -F_s). Units SI.

Lateral slip (option ``lateral``, a full car only)
--------------------------------------------------
With the sprung CG at the height h above the contact points (``FullCar`` parameter
``sprung_cg_height``), a roll rate p moves the contact points sideways, and the tires answer with
side forces that roll the body back and push the vehicle sideways; the full car alone rolls about
its CG as if the tires could slide freely. The option adds the lateral velocity v of the sprung CG,
the yaw rate r and each tire's lateral deflection y_i (SAE axes: y right, roll right side down)
at the constant speed u:

    V_i = v + x_i r - h p                       (contact point's lateral velocity)
    y_i' = V_i - u y_i / sigma_i,   F_i = -C_i(F_z,i) y_i / sigma_i     (first-order relaxation)
    C_i(F_z) = K_1 sin(2 atan(F_z / K_2))       (0 when the wheel is off the road)
    m (v' + u r) - m_c p' = sum F_i,     I_z r' = sum x_i F_i
    I_x p' - m_c (v' + u r) = M_susp - h sum F_i

with K_1, K_2 such that C and dC/dF_z at the static load are the given ones (the load dependence
of the Magic Formula's cornering stiffness, Pacejka 2012, eq. 4.E25: degressive, so that a wheel
landing with twice its load does not get twice the stiffness), m the whole mass, m_c = sum m_u
(h - h_u) (the wheels move sideways with the body), I_x the
full car's roll inertia (with the wheels' share) and M_susp the suspension's roll moment (the
linear model's roll equation); the lateral force acts at the contact points, through the roll
centres on the ground (Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 7.2: relaxation;
Segel's lateral-yaw-roll model for the coupling, as in :class:`vehdyn.handling.LateralYawRoll`).
Without roll excitation (equal tracks) v, r and y_i stay zero and the model is the one without
the option.

Longitudinal slip (option ``longitudinal``, a full car only)
------------------------------------------------------------
A pitch rate q moves the contact points fore and aft by h q, and a wheel off the road spins up
under its drive torque and lands with slip; the full car alone rolls its wheels without slip. The
option adds the body's fore-aft velocity change du (from the constant speed u), each wheel's spin
change w_i (from its steady spin) and each tire's longitudinal deflection rho_i (from its steady
value rho_0,i), with the same tire law as the full vehicle's relaxation
(:func:`vehdyn.components.tire_slip.deflection_rate`, here about the steady state):

    V_i = du + h q - R_e w_i                        (contact point's slip velocity change)
    rho_i' = -V_i - u rho_i / sigma_i,   F_x,i = C_i(F_z,i) (rho_0,i + rho_i) / sigma_i + e_i F_z,i
    I_w w_i' = T_i - r_i F_z,i - R_e F_x,i          (:mod:`vehdyn.full_vehicle.driveline`)
    m du' + m_c q' = sum (F_x,i - F_x0,i),     I_y q' + m_c du' = M_susp + h sum (F_x,i - F_x0,i)

with C_i(F_z) the degressive law of the lateral slip through the slip stiffness and its load
derivative at the static load, T_i the constant drive torque, r_i the rolling-resistance lever
(M_y = -r F_z), e_i the tire law's force at zero slip per unit load (its shifts S_Hx, S_Vx),
F_x0,i = (T_i - r_i F_s,i) / R_e the steady force and rho_0,i = (F_x0,i - e_i F_s,i) sigma_i /
C_i(F_s,i) (so that the zero state is steady rolling), m, m_c as above, I_y the full car's pitch
inertia without the wheels' spin (FullCar's 4 I_w (h / R_e)^2 for rolling without slip, which the
spin states now carry) and M_susp the linear model's pitch moment; with the lateral slip the yaw
moment -sum y_i F_x,i joins the yaw equation (SAE: y right, pitch nose up +; Pacejka 2012, sec.
7.2; the full vehicle's contact-point slip, :mod:`vehdyn.full_vehicle.assembly`). A wheel off the
road carries no force (C(0) = 0) and spins up at T_i / I_w. Without drive torque, rolling
resistance and pitch (a road that rolls the body only) du, w_i and rho_i stay zero and the model
is the one without the option. Not modelled: the tire law's saturation in slip (a landing wheel's
slip ratio stays within a few per cent at the ride scenes' speeds), the drag's change with du,
anti-pitch and roll-centre heights above the ground, the loaded rolling radius.

References
----------
Gillespie, T. D., *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5 (ride; wheel hop and the
tire's vertical load). Jazar, R. N., *Vehicle Dynamics: Theory and Application*, Springer, 2008,
ch. 14 (vehicle vibrations) and 15 (suspension optimization; full car, sec. 15.5). Wong, J. Y.,
*Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 7.2 (tire lift-off on rough roads).
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from vehdyn.components.xp import NUMPY
from vehdyn.errors import ParameterError
from vehdyn.model import Model
from vehdyn.params.base import ParameterSet, parameter
from vehdyn.units import GRAVITY

__all__ = ["LiftOff", "LateralSlip", "LongitudinalSlip"]


XP = None
"""The compiled namespace :func:`_rhs` calls the equations with (bound by :func:`_compiled_rhs`)."""


# ---- the equations, once over an ``xp`` namespace: per corner (numpy: rows of corners, columns
# of a batch; compiled: one corner's floats, :func:`_rhs`), and the coupled 2 x 2 body equations
def _contact_force(xp, static, stiffness, damping, compression, compression_rate):
    """(F, F_lin) [N]: the unilateral contact force and the linear tire's force, with the static load."""
    linear = static + stiffness * compression + damping * compression_rate
    deflection = static / stiffness + compression
    return xp.where(deflection > 0.0, xp.maximum(linear, 0.0), 0.0), linear


def _degressive_stiffness(xp, stiffness, load_scale, force):
    """C(F_z) = K_1 sin(2 atan(F_z / K_2)) = 2 K_1 l / (1 + l^2), l = F_z / K_2 (0 off the road)."""
    load = xp.maximum(force, 0.0) / load_scale
    return stiffness * 2.0 * load / (1.0 + load * load)


def _lateral_tire(xp, force, deflection, slip_velocity, cornering, load_scale, relaxation, speed):
    """(F_y [N], dy/dt [m/s]) of a tire's first-order lateral relaxation."""
    stiffness = _degressive_stiffness(xp, cornering, load_scale, force)
    return -stiffness * deflection / relaxation, slip_velocity - speed * deflection / relaxation


def _longitudinal_tire(xp, force, deflection, slip_velocity, slip_stiffness, slip_scale, relaxation, deflection0,
                       zero_slip, speed, drive, rolling, radius, spin_inertia):
    """(F_x [N], d(rho)/dt [m/s], dw/dt [rad/s^2]) of a tire's longitudinal relaxation and its wheel's spin."""
    stiffness = _degressive_stiffness(xp, slip_stiffness, slip_scale, force)
    fx = stiffness * (deflection0 + deflection) / relaxation + zero_slip * force
    return fx, -slip_velocity - speed * deflection / relaxation, (drive - rolling * force - radius * fx) / spin_inertia


def _coupled(total, angular, mass, coupling, inertia):
    """The 2 x 2 body equations m a - m_c b' = F, I b' - m_c a = M solved: (a, b') for the total tire
    force F and the moment M (lateral: a = v' + u r, b = roll; longitudinal with m_c -> -m_c)."""
    det = mass * inertia - coupling * coupling
    return (inertia * total + coupling * angular) / det, (coupling * total + mass * angular) / det


@dataclasses.dataclass(frozen=True, kw_only=True)
class LateralSlip(ParameterSet):
    """The tires' lateral slip under a rolling full car (:class:`LiftOff` option ``lateral``).

    The contact points lie ``sprung_cg_height`` below the sprung CG (the full car's parameter), so
    a roll rate p moves them sideways; the tires resist that as side slip, and the body gains a
    lateral velocity v and a yaw rate r (module docstring, "Lateral slip").
    """

    speed: float = parameter("m/s", "forward speed u (constant)", gt=0)
    yaw_inertia: float = parameter("kg*m^2", "yaw inertia of the whole vehicle", gt=0)
    front_cornering_stiffness: float = parameter("N/rad", "cornering stiffness of one front tire at its static "
                                                 "load", gt=0)
    rear_cornering_stiffness: float = parameter("N/rad", "cornering stiffness of one rear tire at its static load",
                                                gt=0)
    front_load_sensitivity: float = parameter("1/rad", "dC/dF_z of a front tire at its static load", ge=0,
                                              default=0.0)
    rear_load_sensitivity: float = parameter("1/rad", "dC/dF_z of a rear tire at its static load", ge=0,
                                             default=0.0)
    front_relaxation_length: float = parameter("m", "lateral relaxation length of a front tire", gt=0)
    rear_relaxation_length: float = parameter("m", "lateral relaxation length of a rear tire", gt=0)


@dataclasses.dataclass(frozen=True, kw_only=True)
class LongitudinalSlip(ParameterSet):
    """The tires' longitudinal slip, the wheels' spin and the body's fore-aft motion under a full car
    (:class:`LiftOff` option ``longitudinal``; module docstring, "Longitudinal slip").

    The drive torques are those that hold the constant speed (per wheel); a wheel off the road spins
    up under its drive torque and lands with slip.
    """

    speed: float = parameter("m/s", "forward speed u (constant)", gt=0)
    rolling_radius: float = parameter("m", "effective rolling radius R_e", gt=0)
    wheel_spin_inertia: float = parameter("kg*m^2", "spin inertia of one wheel", gt=0)
    front_slip_stiffness: float = parameter("N", "longitudinal slip stiffness dF_x/dkappa of one front tire at its "
                                            "static load", gt=0)
    rear_slip_stiffness: float = parameter("N", "longitudinal slip stiffness of one rear tire at its static load",
                                           gt=0)
    front_load_sensitivity: float = parameter("-", "dC_kappa/dF_z of a front tire at its static load", ge=0,
                                              default=0.0)
    rear_load_sensitivity: float = parameter("-", "dC_kappa/dF_z of a rear tire at its static load", ge=0,
                                             default=0.0)
    front_relaxation_length: float = parameter("m", "longitudinal relaxation length of a front tire", gt=0)
    rear_relaxation_length: float = parameter("m", "longitudinal relaxation length of a rear tire", gt=0)
    front_drive_torque: float = parameter("N*m", "drive torque on one front wheel (constant)", default=0.0)
    rear_drive_torque: float = parameter("N*m", "drive torque on one rear wheel (constant)", default=0.0)
    front_zero_slip_force: float = parameter("-", "F_x / F_z of a front tire at zero slip (the tire law's shifts, "
                                             "Pacejka's S_Hx, S_Vx)", default=0.0)
    rear_zero_slip_force: float = parameter("-", "F_x / F_z of a rear tire at zero slip", default=0.0)
    front_rolling_resistance: float = parameter("m", "rolling-resistance lever r of a front tire: M_y = -r F_z "
                                                "against the spin", ge=0, default=0.0)
    rear_rolling_resistance: float = parameter("m", "rolling-resistance lever of a rear tire", ge=0, default=0.0)


def _degressive(static_load, stiffness, sensitivity):
    """(K_1, K_2) of C(F_z) = K_1 sin(2 atan(F_z / K_2)) = K_1 2 l / (1 + l^2), l = F_z / K_2, with
    C and dC/dF_z at the static load the given ones (module docstring; a sensitivity above
    C / F_s, which this law cannot reach, gives C proportional to the load)."""
    # with zeta = F_s / K_2, F_s C'/C = (1 - zeta^2) / (1 + zeta^2)
    ratio = np.minimum(sensitivity * static_load / stiffness, 1.0 - 2e-6)
    zeta = np.sqrt((1.0 - ratio) / (1.0 + ratio))
    return stiffness * (1.0 + zeta**2) / (2.0 * zeta), static_load / zeta


class LiftOff(Model):
    r"""A linear ride model with unilateral tire contact (the wheels lift off and land again).

    Parameters
    ----------
    model : RideModel
        A :class:`~vehdyn.ride.QuarterCar`, :class:`~vehdyn.ride.BouncePitch` or
        :class:`~vehdyn.ride.FullCar` whose every corner has an unsprung mass (a wheel that can
        leave the road).
    gravity : float, optional
        Gravitational acceleration [m/s^2] that sets the static tire loads (default
        :data:`vehdyn.units.GRAVITY`).
    lateral : LateralSlip, optional
        The tires' lateral slip under the rolling body (a :class:`~vehdyn.ride.FullCar` only):
        adds the states ``lateral_velocity``, ``yaw_rate`` and ``lateral_deflection_<corner>``
        and the outputs ``lateral_force_<corner>`` (module docstring).
    longitudinal : LongitudinalSlip, optional
        The tires' longitudinal slip, the wheels' spin and the body's fore-aft motion (a
        :class:`~vehdyn.ride.FullCar` only): adds the states ``longitudinal_velocity_change``,
        ``wheel_speed_change_<corner>`` and ``longitudinal_deflection_<corner>`` and the outputs
        ``longitudinal_force_<corner>`` (module docstring).
    name : str, optional

    Attributes
    ----------
    linear : RideModel
        The model with bilateral tires (the same states, inputs and outputs).
    static_tire_load : ndarray
        F_s [N] per corner, in the order of ``linear.corners``.
    static_longitudinal_force : ndarray
        F_x0 [N] per corner (with ``longitudinal`` only): the steady force of the drive torque.

    Notes
    -----
    States, inputs and outputs are the linear model's (module docstring: the equations), with
    ``lateral`` and ``longitudinal`` those above after them (in that order); the phenomena add
    ``wheel_lift`` (and ``lateral``, ``yaw``; ``longitudinal``, ``wheel_spin``). On a road that
    never unloads a wheel the result equals the
    linear model's. ``simulate(model, ..., method="RK45")`` runs a compiled right-hand side when
    numba is installed (:meth:`compiled_rhs`), else the numpy one: both run the same per-corner
    equations (the contact law, the tires' relaxation and the coupled body equations are written
    once, over an ``xp`` namespace).

    .. math::

        \dot x = A x + B u + \sum_i e_i f_{c,i} / m_{u,i},\qquad
        f_{c,i} = F_i - (F_{s,i} + k_t (z_r - z_u) + c_t (\dot z_r - \dot z_u)),\\
        F_i = \max(F_{s,i} + \Delta F_{lin}, 0) \text{ where } \delta_i > 0,\ 0 \text{ elsewhere};\quad
        \dot y_i = V_i - u\, y_i / \sigma_i,\quad F_{y,i} = -C_i(F_i)\, y_i / \sigma_i

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5 (ride; wheel hop and
       the tire's vertical load).
    .. [2] R. N. Jazar, *Vehicle Dynamics: Theory and Application*, Springer, 2008, ch. 14 and 15
       (the full car, sec. 15.5).
    .. [3] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 7.2 (tire lift-off on
       rough roads).
    .. [4] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 7.2 (relaxation) and eq.
       4.E25 (the load dependence of the cornering stiffness).

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.ride import FullCar, LiftOff
    >>> car = LiftOff(FullCar(vehdyn.load_vehicle("sedan")))
    >>> sorted(car.phenomena)[-1]
    'wheel_lift'
    """

    def __init__(self, model, *, gravity: float = GRAVITY, lateral: LateralSlip | None = None,
                 longitudinal: LongitudinalSlip | None = None, name: str | None = None):
        from vehdyn.ride._ride_model import RideModel

        if not isinstance(model, RideModel):
            raise ParameterError(f"LiftOff needs a linear ride model (QuarterCar, BouncePitch, FullCar), got "
                                 f"{type(model).__name__}", key="model", value=type(model).__name__)
        rigid = [c.suffix or "(single corner)" for c in model.corners if not c.has_unsprung_mass]
        if rigid:
            raise ParameterError(f"LiftOff needs an unsprung mass at every corner (a wheel that can leave the road); "
                                 f"corners {rigid} have none", key="model", value=rigid)
        if model.has_actuators:
            raise ParameterError("LiftOff takes a passive ride model (no actuator inputs)", key="model",
                                 value=model.name)
        g = float(gravity) if isinstance(gravity, (int, float, np.floating)) and not isinstance(gravity, bool) \
            else float("nan")
        if not np.isfinite(g) or g <= 0:
            raise ParameterError(f"gravity must be a finite number > 0 [m/s^2], got {gravity!r}", key="gravity",
                                 value=gravity)
        self.linear, self.gravity = model, g
        self.name = name or f"{model.name}_lift_off"
        self.declare(states=model.states, inputs=model.inputs, outputs=model.output_signals)
        self.phenomena = frozenset(model.phenomena) | {"wheel_lift"}

        M, _, K, _, dof = model.second_order
        n, nb, nc = M.shape[0], len(model.body_dof), len(model.corners)
        wheel = nb + np.arange(nc)  # the wheels' coordinates follow the body's, in corner order
        # static equilibrium of the linear model under gravity: the translational coordinates
        # (heave, wheels) carry their mass's weight, the angles none (the origin is the sprung CG)
        translational = np.array([name != "pitch_angle" and name != "roll_angle" for name in dof])
        # (the suspension's and tires' stiffness: gravity's moment on a tilted body, in
        # ``body_stiffness``, is no spring that carries the weight)
        springs = K.copy()
        springs[range(nb), range(nb)] -= model.body_stiffness
        q_g = np.linalg.solve(springs, -g * np.diag(M) * translational)
        self.tire_stiffness = np.array([c.tire_stiffness for c in model.corners])
        self.tire_damping = np.array([c.tire_damping for c in model.corners])
        self.unsprung_mass = np.array([c.unsprung_mass for c in model.corners])
        self.static_tire_load = -self.tire_stiffness * q_g[wheel]
        if np.any(self.static_tire_load <= 0):
            raise ParameterError(f"LiftOff: the static tire loads {self.static_tire_load} [N] must be positive (a "
                                 "wheel that carries no weight is off the road already)", key="model",
                                 value=self.static_tire_load.tolist())
        # the compiled rhs relies on the second-order structure of A and B
        assert np.array_equal(model.A[:n], np.hstack([np.zeros((n, n)), np.eye(n)])) and not np.any(model.B[:n])
        self._wheel = wheel  # states: wheel displacements
        self._wheel_rate = n + wheel  # states: wheel velocities (rows of their accelerations in x')
        self._n = 2 * n  # states of the ride model
        names = model.input_names
        self._road = np.array([names.index(f"road_displacement{c.suffix}") for c in model.corners])
        self._road_rate = np.array([names.index(f"road_velocity{c.suffix}") for c in model.corners])
        out = model.output_names
        self._acc_rows = np.array([out.index(f"unsprung_acceleration{c.suffix}") for c in model.corners])
        self._load_rows = np.array([out.index(f"dynamic_tire_load{c.suffix}") for c in model.corners])
        self.lateral = self.longitudinal = None
        self._o = self._n  # first longitudinal state
        if lateral is not None:
            self._lateral_setup(model, lateral, n, nb)
            self._o = self._n + 2 + nc
        if longitudinal is not None:
            self._longitudinal_setup(model, longitudinal, n)

    def _longitudinal_setup(self, model, lon, n):
        from vehdyn.signals import Signal
        from vehdyn.ride.full_car import FullCar

        if not isinstance(lon, LongitudinalSlip):
            raise ParameterError(f"longitudinal must be a LongitudinalSlip, got {type(lon).__name__}",
                                 key="longitudinal", value=type(lon).__name__)
        if not isinstance(model, FullCar):
            raise ParameterError(f"the longitudinal slip needs a FullCar (pitch and four corners), got "
                                 f"{type(model).__name__}", key="longitudinal", value=type(model).__name__)
        if self.lateral is not None and self.lateral.speed != lon.speed:
            raise ParameterError(f"the longitudinal slip's speed {lon.speed} m/s differs from the lateral slip's "
                                 f"{self.lateral.speed} m/s", key="longitudinal.speed", value=lon.speed)
        p = model.parameters
        self.longitudinal = lon
        self.phenomena = self.phenomena | {"longitudinal", "wheel_spin"}
        front = np.array([c.suffix.startswith("_front") for c in model.corners])
        stiffness = np.where(front, lon.front_slip_stiffness, lon.rear_slip_stiffness)
        sensitivity = np.where(front, lon.front_load_sensitivity, lon.rear_load_sensitivity)
        self._slip_stiffness, self._slip_load_scale = _degressive(self.static_tire_load, stiffness, sensitivity)
        self._lon_relaxation = np.where(front, lon.front_relaxation_length, lon.rear_relaxation_length)
        self._drive = np.where(front, lon.front_drive_torque, lon.rear_drive_torque)
        self._rolling = np.where(front, lon.front_rolling_resistance, lon.rear_rolling_resistance)
        # the steady state: R_e F_x0 = T_d - r F_s, the deflection rho_0 = F_x0 sigma / C(F_s)
        self.static_longitudinal_force = (self._drive - self._rolling * self.static_tire_load) / lon.rolling_radius
        self._zero_slip = np.where(front, lon.front_zero_slip_force, lon.rear_zero_slip_force)
        self._deflection0 = (self.static_longitudinal_force - self._zero_slip * self.static_tire_load) \
            * self._lon_relaxation / stiffness
        self._cx = np.array([c.x for c in model.corners])
        self._cy = np.array([c.y for c in model.corners])
        self._h = p.sprung_cg_height
        self._mass = p.mass + 2.0 * (p.front_unsprung_mass + p.rear_unsprung_mass)
        self._coupling = 2.0 * (p.front_unsprung_mass + p.rear_unsprung_mass) * (p.sprung_cg_height
                                                                                  - p.unsprung_cg_height)
        pitch = model.body_dof.index("pitch")
        # the full car's pitch inertia holds the wheels' spin for rolling without slip (FullCar:
        # 4 I_w (h / R)^2); here the spin is a state of its own
        self._pitch_inertia_full = model.mass_matrix[pitch, pitch]
        self._pitch_inertia = self._pitch_inertia_full - 4.0 * p.wheel_spin_inertia * (p.sprung_cg_height
                                                                                         / p.rolling_radius) ** 2
        self._pitch_rate = n + pitch
        out = model.output_names
        self._pitch_rows = np.array([out.index("pitch_acceleration")]
                                    + [out.index(f"sprung_acceleration{c.suffix}") for c in model.corners])
        self._pitch_gains = np.concatenate([[1.0], self._cx])
        extra = (Signal("longitudinal_velocity_change", "m/s", "forward velocity of the sprung CG less the constant "
                        "speed (SAE: forward +)"),)
        spins = tuple(Signal(f"wheel_speed_change{c.suffix}", "rad/s", "wheel spin less its steady value (rolling "
                             "forwards +)") for c in model.corners)
        deflections = tuple(Signal(f"longitudinal_deflection{c.suffix}", "m", "tire longitudinal deflection less its "
                                   "steady value (driving +)") for c in model.corners)
        forces = tuple(Signal(f"longitudinal_force{c.suffix}", "N", "tire longitudinal force on the vehicle (SAE: "
                              "forward +)") for c in model.corners)
        self.declare(states=tuple(self.states) + extra + spins + deflections,
                     outputs=tuple(self.outputs) + extra + spins + deflections + forces)

    def _lateral_setup(self, model, lateral, n, nb):
        from vehdyn.signals import Signal
        from vehdyn.ride.full_car import FullCar

        if not isinstance(lateral, LateralSlip):
            raise ParameterError(f"lateral must be a LateralSlip, got {type(lateral).__name__}", key="lateral",
                                 value=type(lateral).__name__)
        if not isinstance(model, FullCar):
            raise ParameterError(f"the lateral slip needs a FullCar (roll and four corners), got {type(model).__name__}",
                                 key="lateral", value=type(model).__name__)
        p = model.parameters
        self.lateral = lateral
        self.phenomena = self.phenomena | {"lateral", "yaw"}
        front = np.array([c.suffix.startswith("_front") for c in model.corners])
        self._x = np.array([c.x for c in model.corners])
        self._h = p.sprung_cg_height
        cornering = np.where(front, lateral.front_cornering_stiffness, lateral.rear_cornering_stiffness)
        sensitivity = np.where(front, lateral.front_load_sensitivity, lateral.rear_load_sensitivity)
        self._cornering, self._load_scale = _degressive(self.static_tire_load, cornering, sensitivity)
        self._relaxation = np.where(front, lateral.front_relaxation_length, lateral.rear_relaxation_length)
        self._mass = p.mass + 2.0 * (p.front_unsprung_mass + p.rear_unsprung_mass)
        self._coupling = 2.0 * (p.front_unsprung_mass + p.rear_unsprung_mass) * (p.sprung_cg_height
                                                                                  - p.unsprung_cg_height)
        roll = model.body_dof.index("roll")
        self._roll_inertia = model.mass_matrix[roll, roll]
        self._roll_rate = n + roll
        out = model.output_names
        self._roll_rows = np.array([out.index("roll_acceleration")]
                                   + [out.index(f"sprung_acceleration{c.suffix}") for c in model.corners])
        self._roll_gains = np.concatenate([[1.0], [-c.y for c in model.corners]])
        extra = (Signal("lateral_velocity", "m/s", "lateral velocity v of the sprung CG (SAE: right +)"),
                 Signal("yaw_rate", "rad/s", "yaw rate r (SAE)"))
        deflections = tuple(Signal(f"lateral_deflection{c.suffix}", "m", "tire lateral deflection (SAE: right +)")
                            for c in model.corners)
        forces = tuple(Signal(f"lateral_force{c.suffix}", "N", "tire lateral force on the vehicle (SAE: right +)")
                       for c in model.corners)
        self.declare(states=tuple(model.states) + extra + deflections,
                     outputs=tuple(model.output_signals) + extra + deflections + forces)

    def __repr__(self) -> str:
        return f"<LiftOff {self.name}: {self.n_states} states, static tire loads {np.round(self.static_tire_load)} N>"

    def _contact(self, x, u):
        """(F, F_lin) [N] per corner (rows; columns along any batch axis): the unilateral contact
        force and the linear tire's force, both with the static load."""
        col = (slice(None),) + (None,) * (x.ndim - 1)
        return _contact_force(NUMPY, self.static_tire_load[col], self.tire_stiffness[col], self.tire_damping[col],
                              u[self._road] - x[self._wheel], u[self._road_rate] - x[self._wheel_rate])

    def correction(self, x, u):
        """The unilateral contact force minus the linear tire's (0 while the tire is compressed and pushing).

        Parameters
        ----------
        x : array_like
            States [SI units] (optional batch axis).
        u : array_like
            Inputs [SI units].

        Returns
        -------
        ndarray
            f_c [N] per corner (rows; columns along any batch axis of ``x``, ``u``).
        """
        force, linear = self._contact(np.asarray(x, dtype=float), np.asarray(u, dtype=float))
        return force - linear

    def _ride(self, x, u):
        """(d x_ride / dt, contact force F, correction f_c) with the contact law."""
        col = (slice(None),) + (None,) * (x.ndim - 1)
        force, linear = self._contact(x, u)
        dxdt = self.linear.A @ x[:self._n] + self.linear.B @ u
        dxdt[self._wheel_rate] += (force - linear) / self.unsprung_mass[col]
        return dxdt, force, force - linear

    def _slip(self, x, force, roll_acceleration):
        """Roll acceleration, dv/dt, dr/dt, the tire deflections' rates and the lateral forces."""
        lat = self.lateral
        col = (slice(None),) + (None,) * (x.ndim - 1)
        u = lat.speed
        v, r, deflection = x[self._n], x[self._n + 1], x[self._n + 2:self._n + 6]
        slip_velocity = v + self._x[col] * r - self._h * x[self._roll_rate]
        fy, rates = _lateral_tire(NUMPY, force, deflection, slip_velocity, self._cornering[col], self._load_scale[col],
                                  self._relaxation[col], u)
        total, yaw_moment = np.sum(fy, axis=0), np.sum(self._x[col] * fy, axis=0)
        moment = self._roll_inertia * roll_acceleration - self._h * total
        lateral_acceleration, roll = _coupled(total, moment, self._mass, self._coupling, self._roll_inertia)
        return roll, lateral_acceleration - u * r, yaw_moment / lat.yaw_inertia, rates, fy

    def _spin(self, x, force, pitch_acceleration):
        """Pitch acceleration, du/dt, the wheels' spin accelerations, the deflections' rates, the
        longitudinal forces F_x and their yaw moment (SAE)."""
        lon = self.longitudinal
        col = (slice(None),) + (None,) * (x.ndim - 1)
        o, nc = self._o, self._cx.size
        du, spin, deflection = x[o], x[o + 1:o + 1 + nc], x[o + 1 + nc:]
        slip_velocity = du + self._h * x[self._pitch_rate] - lon.rolling_radius * spin
        fx, rates, spin_acceleration = _longitudinal_tire(
            NUMPY, force, deflection, slip_velocity, self._slip_stiffness[col], self._slip_load_scale[col],
            self._lon_relaxation[col], self._deflection0[col], self._zero_slip[col], lon.speed, self._drive[col],
            self._rolling[col], lon.rolling_radius, lon.wheel_spin_inertia)
        total = np.sum(fx - self.static_longitudinal_force[col], axis=0)
        moment = self._pitch_inertia_full * pitch_acceleration + self._h * total
        acceleration, pitch = _coupled(total, -moment, self._mass, self._coupling, self._pitch_inertia)
        return -pitch, acceleration, spin_acceleration, rates, fx, -np.sum(self._cy[col] * fx, axis=0)

    def rhs(self, t, x, u):
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        dxdt, force, _ = self._ride(x, u)
        parts = [dxdt]
        if self.longitudinal is not None:
            pitch, du, spin, rates, _, yaw_moment = self._spin(x, force, dxdt[self._pitch_rate])
            dxdt[self._pitch_rate] = pitch
        if self.lateral is not None:
            roll, dv, dr, lateral_rates, _ = self._slip(x, force, dxdt[self._roll_rate])
            dxdt[self._roll_rate] = roll
            if self.longitudinal is not None:
                dr = dr + yaw_moment / self.lateral.yaw_inertia
            parts += [dv[None], dr[None], lateral_rates]
        if self.longitudinal is not None:
            parts += [du[None], spin, rates]
        return np.concatenate(parts)

    def output(self, t, x, u):
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        col = (slice(None),) + (None,) * (x.ndim - 1)
        dxdt, force, f = self._ride(x, u)
        y = self.linear.C @ x[:self._n] + self.linear.D @ u
        y[self._acc_rows] += f / self.unsprung_mass[col]
        y[self._load_rows] += f
        parts = [y]
        if self.lateral is not None:
            roll, _, _, _, fy = self._slip(x, force, dxdt[self._roll_rate])
            y[self._roll_rows] += self._roll_gains[col] * (roll - dxdt[self._roll_rate])
            parts += [x[self._n:self._o], fy]
        if self.longitudinal is not None:
            pitch, _, _, _, fx, _ = self._spin(x, force, dxdt[self._pitch_rate])
            y[self._pitch_rows] += self._pitch_gains[col] * (pitch - dxdt[self._pitch_rate])
            parts += [x[self._o:], fx]
        return np.concatenate(parts)

    def compiled_rhs(self):
        """The rhs compiled by numba (see :meth:`vehdyn.Model.compiled_rhs`): the same law, one loop
        over the corners; the outputs come from :meth:`output` (numpy, once on the time grid)."""
        from vehdyn.simulation.compiled import CompiledModel

        rhs, key = _compiled_rhs()
        c = np.ascontiguousarray
        if self.lateral is None:
            lateral = (0.0, 0, 0.0, c(np.zeros(1)), c(np.zeros(1)), c(np.zeros(1)), c(np.ones(1)), 1.0, 0.0, 1.0,
                       1.0)
        else:
            lateral = (self.lateral.speed, self._roll_rate, self._h, c(self._x), c(self._cornering),
                       c(self._load_scale), c(self._relaxation), self._mass, self._coupling, self._roll_inertia,
                       self.lateral.yaw_inertia)
        if self.longitudinal is None:
            one = c(np.ones(1))
            longitudinal = (0.0, 0, 0, 0.0, 1.0, 1.0, one, one, one, one, one, one, one, one, one, 1.0, 0.0, 1.0,
                            1.0)
        else:
            lon = self.longitudinal
            longitudinal = (lon.speed, self._o, self._pitch_rate, self._h, lon.rolling_radius, lon.wheel_spin_inertia,
                            c(self._slip_stiffness), c(self._slip_load_scale), c(self._lon_relaxation),
                            c(self._deflection0), c(self._drive), c(self._rolling), c(self._zero_slip),
                            c(self.static_longitudinal_force), c(self._cy), self._mass, self._coupling,
                            self._pitch_inertia_full, self._pitch_inertia)
        args = (c(self.linear.A), c(self.linear.B), c(self._wheel), c(self._wheel_rate), c(self._road),
                c(self._road_rate), c(self.static_tire_load), c(self.tire_stiffness), c(self.tire_damping),
                c(self.unsprung_mass), lateral, longitudinal)
        return CompiledModel(rhs, None, key, args)


def _rhs(t, x, u, args, dxdt):
    """dx/dt of a :class:`LiftOff` into ``dxdt`` (compiled; ``args`` from :meth:`LiftOff.compiled_rhs`;
    ``XP`` bound to the compiled namespace of :mod:`vehdyn.components.compiled` by :func:`_compiled_rhs`)."""
    A, B, wheel, wheel_rate, road, road_rate, static, stiffness, damping, mass, lateral, longitudinal = args
    speed, roll_rate, h, cx, cornering, load_scale, relaxation, total_mass, coupling, inertia, yaw_inertia = lateral
    (lon_speed, o, pitch_rate, lon_h, radius, spin_inertia, slip_stiffness, slip_scale, lon_relaxation, deflection0,
     drive, rolling, zero_slip, static_fx, cy, lon_mass, lon_coupling, pitch_inertia_full, pitch_inertia) = longitudinal
    n, m = A.shape[0], B.shape[1]
    half = n // 2
    for i in range(half):  # A = [[0, I], [-M^-1 K, -M^-1 C]], B = [[0], [M^-1 F]] (from_second_order)
        dxdt[i] = x[half + i]
    for i in range(half, n):
        s = 0.0
        for j in range(n):
            s += A[i, j] * x[j]
        for j in range(m):
            s += B[i, j] * u[j]
        dxdt[i] = s
    total, lateral_yaw, lon_total, lon_yaw = 0.0, 0.0, 0.0, 0.0
    nc = wheel.shape[0]
    for c in range(nc):  # the equations of the numpy methods, one corner at a time
        force, linear = _contact_force(XP, static[c], stiffness[c], damping[c], u[road[c]] - x[wheel[c]],
                                       u[road_rate[c]] - x[wheel_rate[c]])
        dxdt[wheel_rate[c]] += (force - linear) / mass[c]
        if speed > 0.0:
            fy, rate = _lateral_tire(XP, force, x[n + 2 + c], x[n] + cx[c] * x[n + 1] - h * x[roll_rate],
                                     cornering[c], load_scale[c], relaxation[c], speed)
            dxdt[n + 2 + c] = rate
            total += fy
            lateral_yaw += cx[c] * fy
        if lon_speed > 0.0:
            fx, rate, spin = _longitudinal_tire(
                XP, force, x[o + 1 + nc + c], x[o] + lon_h * x[pitch_rate] - radius * x[o + 1 + c], slip_stiffness[c],
                slip_scale[c], lon_relaxation[c], deflection0[c], zero_slip[c], lon_speed, drive[c], rolling[c], radius,
                spin_inertia)
            dxdt[o + 1 + nc + c] = rate
            dxdt[o + 1 + c] = spin
            lon_total += fx - static_fx[c]
            lon_yaw += cy[c] * fx
    if lon_speed > 0.0:
        moment = pitch_inertia_full * dxdt[pitch_rate] + lon_h * lon_total
        acceleration, pitch = _coupled(lon_total, -moment, lon_mass, lon_coupling, pitch_inertia)
        dxdt[pitch_rate] = -pitch
        dxdt[o] = acceleration
    if speed > 0.0:
        moment = inertia * dxdt[roll_rate] - h * total
        lateral_acceleration, roll = _coupled(total, moment, total_mass, coupling, inertia)
        dxdt[roll_rate] = roll
        dxdt[n] = lateral_acceleration - speed * x[n + 1]
        dxdt[n + 1] = lateral_yaw / yaw_inertia
        if lon_speed > 0.0:
            dxdt[n + 1] = dxdt[n + 1] + (-lon_yaw) / yaw_inertia


@functools.lru_cache(maxsize=None)
def _compiled_rhs():
    """(compiled rhs, cache key), compiled on first use and cached on disk per source digest."""
    import sys

    from vehdyn.simulation.compiled import compiled_copy, source_stamp

    from numba.extending import register_jitable

    from vehdyn.components.compiled import JIT_OPTIONS, SOURCE_MODULES, XP

    for function in (_contact_force, _degressive_stiffness, _lateral_tire, _longitudinal_tire, _coupled):
        register_jitable(**JIT_OPTIONS)(function)
    key = "lift_off_" + source_stamp(*SOURCE_MODULES, sys.modules[__name__])
    return compiled_copy(_rhs, f"{key}_rhs", XP=XP), key
