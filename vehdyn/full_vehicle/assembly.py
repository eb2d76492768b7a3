"""The equations of :class:`~vehdyn.full_vehicle.FullVehicle` as pure functions over an ``xp`` namespace.

One source for numpy (with a trailing batch axis) and numba-compiled code
(:mod:`~vehdyn.full_vehicle._full_vehicle_numba`), with the components the single track uses too
(:mod:`vehdyn.components`: the tire step with its slip, relaxation, mirror-image and friction
rules, the wheel torques) and the rigid body of :mod:`vehdyn.mechanics`, unchanged. Besides
arithmetic the equations use the interface of :mod:`vehdyn.components.xp` (``xp.cos``, ``sin``,
``tan``, ``tanh``, ``atan``, ``atan2``, ``sqrt``, ``abs``, ``where``, ``minimum``, ``maximum``,
the tire hooks ``xp.tire_law``, ``xp.tire_law_pair``) and two hooks of their own:

``xp.rotation_body_to_earth(roll, pitch, yaw)``
    R with R[i][j] indexable (numpy: :func:`vehdyn.mechanics.rotation_body_to_earth`; floats
    (:class:`SCALAR`, one state without numpy's per-call overhead) and compiled:
    :func:`vehdyn.mechanics.kinematics.rotation_matrix`, the same source as nested tuples);
``xp.euler_angle_rates(roll, pitch, p, q, r)``
    (numpy and floats: :func:`vehdyn.mechanics.euler_angle_rates`' check of gimbal lock and its
    source; compiled:
    :func:`vehdyn.mechanics.kinematics.euler_rates`, its source without the check: the domain,
    |pitch| <= pi/4, is checked first).

The sprung body's Newton-Euler equations are
:func:`vehdyn.mechanics.equations_of_motion.rigid_body_accelerations` on every backend.

Signals travel in the fixed orders :data:`STATES` and :data:`INPUTS`; a model's vectors hold a
subset (without tire lag, no deflection states), mapped through an index (-1: absent, 0.0).
Everything is in SAE vehicle axes at the sprung CG; signs flip between SAE and ISO-W only inside
the shared tire step :func:`~vehdyn.components.tire_forces.contact_loads` (through
:mod:`vehdyn.conventions`).
"""

from __future__ import annotations

from collections import namedtuple

from vehdyn.components import xp as components_xp
from vehdyn.components.tire_forces import contact_loads, secant_compliance, tire_aligning_moment
from vehdyn.components.tire_slip import deflection_rate
from vehdyn.conventions import planar_tire_slips_sae_to_iso_w
from vehdyn.errors import SimulationError
from vehdyn.mechanics import euler_angle_rates, rotation_body_to_earth
from vehdyn.mechanics.kinematics import check_gimbal_lock, cross_components, euler_rates, rotation_matrix
from vehdyn.full_vehicle import aero, body, corner, driveline, steering
from vehdyn.full_vehicle.corner import CORNERS

__all__ = ["STATES", "INPUTS", "BODY_STATES", "CORNER_STATES", "Constants", "Evaluation", "NUMPY", "gather",
           "ground_point", "DOMAIN_STATES", "DomainError",
           "evaluate", "derivatives", "OUTPUTS", "outputs"]

BODY_STATES = ("longitudinal_velocity", "lateral_velocity", "vertical_velocity", "roll_rate", "pitch_rate",
               "yaw_rate", "roll_angle", "pitch_angle", "yaw_angle", "x", "y", "z")
CORNER_STATES = ("wheel_speed", "unsprung_displacement", "unsprung_velocity", "lateral_deflection",
                 "longitudinal_deflection")
STATES = BODY_STATES + tuple(f"{name}{sfx}" for name in CORNER_STATES for sfx in CORNERS)
"""Every state a FullVehicle can have: the 12 body states, then per kind the four corners."""

INPUTS = (("front_steer_angle", "rear_steer_angle")
          + tuple(f"{name}{sfx}" for name in ("drive_torque", "brake_torque", "road_displacement", "road_velocity")
                  for sfx in CORNERS) + ("wind_velocity_lateral",))
"""Every input of a FullVehicle, in order."""

Constants = namedtuple("Constants", (
    # body
    "gravity", "mass", "sprung_mass", "inertia", "inverse_inertia", "projection", "cg_height", "wheelbase",
    "front_track",
    # corners (4-tuples in corner order)
    "corner_x", "corner_y", "spring_z", "wheel_z", "contact_z", "unsprung_mass", "spring_rate", "damping",
    "spring_preload", "antiroll_rate", "tire_stiffness", "tire_damping", "static_tire_deflection",
    "roll_centre_height", "anti_pitch", "camber_on", "camber_gain", "roll_steer", "ackermann_fraction",
    # wheels and tires
    "rolling_radius", "wheel_spin_inertia", "friction_coefficient", "lateral_relaxation_length",
    "longitudinal_relaxation_length", "peak_slip_ratio", "peak_tan_slip_angle", "low_speed_damping_speed",
    "brake_regularization_speed", "mirror_image", "road_friction", "wheel_spin", "tire_lag", "friction_scaled",
    # aero
    "drag_factor", "wind_side_force_factor", "centre_of_pressure", "front_lift_factor", "rear_lift_factor",
    # the unsprung masses' lateral force through the linkage (issue 28)
    "unsprung_jacking",
    # compliance steer (issue 28)
    "compliance_on", "lateral_compliance", "moment_compliance", "compliance_slope"))
Constants.__doc__ = """The numbers the equations read (floats; 4-tuples per corner in corner order; nested tuples).

:meth:`FullVehicle.constants <vehdyn.full_vehicle.FullVehicle.constants>` builds them; a compiled
version takes the same tuple.

Parameters
----------
gravity : float
    g [m/s^2].
mass, sprung_mass : float
    Total and sprung mass [kg].
inertia, inverse_inertia : tuple
    Sprung inertia J about the sprung CG and its inverse, 3x3 nested tuples [kg*m^2], [1/(kg*m^2)].
projection : tuple
    The added-mass projection P (6x6, :func:`~vehdyn.full_vehicle.body.added_mass_projection`) [-].
cg_height : float
    Total CG height [m].
wheelbase, front_track : float
    [m].
corner_x, corner_y : tuple
    Corner positions from the sprung CG, body axes [m].
spring_z, wheel_z, contact_z : float
    Body-z coordinates (from the sprung CG, down +) of the spring seats, wheel centres and contact
    points [m].
unsprung_mass : tuple
    [kg] per corner.
spring_rate, damping : tuple
    Wheel rates [N/m] and damping [N*s/m] per corner.
spring_preload : tuple
    Static spring forces [N].
antiroll_rate : tuple
    (front, rear) anti-roll bar rate at the wheels [N/m].
tire_stiffness, tire_damping : tuple
    Vertical tire stiffness [N/m] and damping [N*s/m].
static_tire_deflection : tuple
    [m].
roll_centre_height : tuple
    [m].
anti_pitch : tuple
    e_i f h / L per corner [-].
camber_on : float
    1.0 with camber gains, else 0.0 [-].
camber_gain : tuple
    [rad/m].
roll_steer : tuple
    [rad/rad].
ackermann_fraction : float
    [-].
rolling_radius : float
    R_e [m].
wheel_spin_inertia : float
    I_w [kg*m^2].
friction_coefficient : float
    The laws' own mu [-].
lateral_relaxation_length, longitudinal_relaxation_length : tuple
    sigma_y, sigma_x per corner [m].
peak_slip_ratio, peak_tan_slip_angle : tuple
    The slips of the laws' peak forces [-].
low_speed_damping_speed : float
    v_l [m/s].
brake_regularization_speed : float
    omega_b [rad/s].
mirror_image : tuple
    1.0 at the corners whose tire is the mirror image of its axle's law
    (:func:`vehdyn.components.tire_setup.mirrored_wheel`), else 0.0 [-].
road_friction : float
    The road's friction relative to the laws' own, a constant ratio [-] (1.0 without).
wheel_spin : bool
    Always True (the shared tire step reads it).
tire_lag : bool
    The relaxation states.
friction_scaled : bool
    The road's friction applies.
drag_factor : float
    0.5 rho c_x A [kg/m].
wind_side_force_factor : float
    k_w [kg/m].
centre_of_pressure : float
    The crosswind's centre of pressure ahead of the sprung CG [m] (:mod:`~vehdyn.full_vehicle.aero`).
front_lift_factor, rear_lift_factor : float
    0.5 rho c_l A [kg/m].
unsprung_jacking : tuple
    kappa_c = (h_rc,i - lambda_i h_u) / y_c per corner: the vertical linkage force on the body per
    unit lateral force W_y of the corner's unsprung mass (:func:`~vehdyn.full_vehicle.corner.unsprung_jacking`)
    [-].
compliance_on : float
    1.0 where a compliance steer is set, else 0.0 (the step is skipped) [-].
lateral_compliance : tuple
    2 c_i per corner [rad/N]: the wheel's steer per unit of its own lateral force (the axle's
    ``suspension.*_lateral_force_compliance_steer`` c_i is per unit of the axle's force, which its
    two wheels share).
moment_compliance : tuple
    2 e_i per corner [rad/(N*m)]: the wheel's steer per unit of its own aligning moment.
compliance_slope : tuple
    (c_i - e_i t_i) C_i per corner [-]: the wheel's compliance steer against itself at the static
    load (C_i, t_i the law's axle cornering stiffness and pneumatic trail), the first step without
    tire lag."""

Evaluation = namedtuple("Evaluation", (
    "velocity_rate", "angular_acceleration", "cg_acceleration", "euler_rates", "position_rates",
    "wheel_acceleration", "unsprung_acceleration", "lateral_deflection_rate", "longitudinal_deflection_rate",
    "normal_load", "slip_angle", "slip_ratio", "longitudinal_force", "lateral_force", "suspension_travel",
    "camber", "steer", "horizontal_acceleration", "sprung_acceleration", "compliance_steer"))
Evaluation.__doc__ = """Everything one evaluation yields.

Parameters
----------
velocity_rate : tuple
    (du, dv, dw) [m/s^2].
angular_acceleration : tuple
    (dp, dq, dr) [rad/s^2].
cg_acceleration : tuple
    The absolute acceleration of the sprung CG in body axes [m/s^2].
euler_rates : tuple
    (dphi, dtheta, dpsi) [rad/s].
position_rates : tuple
    (dX, dY, dZ) [m/s].
wheel_acceleration, unsprung_acceleration : tuple
    Per corner [rad/s^2], [m/s^2].
lateral_deflection_rate, longitudinal_deflection_rate : tuple
    Per corner [m/s].
normal_load : tuple
    Tire loads [N].
slip_angle, slip_ratio : tuple
    SAE slips acting in the laws [rad], [-].
longitudinal_force, lateral_force : tuple
    Wheel-axis tire forces (SAE) [N].
suspension_travel : tuple
    [m].
camber, steer : tuple
    [rad].
horizontal_acceleration : tuple
    The total CG's horizontal acceleration in the intermediate (yaw-only) axes, gravity excluded [m/s^2].
sprung_acceleration : float or ndarray
    The sprung CG's vertical acceleration (up) [m/s^2].
compliance_steer : tuple
    Per corner, the compliance steer 2 c_i F_y + 2 e_i M_z of the wheel [rad] (in ``steer``; 0 without)."""


DOMAIN_STATES = ("roll_angle", "pitch_angle")
"""The states bounded by :attr:`FullVehicle.domain <vehdyn.full_vehicle.FullVehicle.domain>`."""


def trial_bounds(low, high):
    """Bounds beyond which the rhs returns NaN: the domain widened by half its width on each side.

    An accepted step may cross the domain's bound (then :func:`vehdyn.simulate` locates the
    crossing and raises :class:`DomainError`); a wild trial stage of an adaptive solver far
    beyond it (a rejected step) gets NaN and is rejected instead of stopping the run.
    """
    margin = 0.5 * (high - low)
    return low - margin, high + margin


class DomainError(SimulationError):
    """The roll or pitch angle left :attr:`FullVehicle.domain <vehdyn.full_vehicle.FullVehicle.domain>`
    (raised by the numpy and by the compiled rhs, with the same message).

    Parameters
    ----------
    which : int
        Index into :data:`DOMAIN_STATES` (0 roll angle, 1 pitch angle).
    value, time, low, high : float
        The angle [rad], the time [s] and the domain's bounds [rad].
    """

    def __init__(self, which, value, time, low, high):
        name = DOMAIN_STATES[which]
        super().__init__(f"{name} = {value:.4g} rad at t = {time:.6g} s leaves the full vehicle's domain "
                         f"[{low:.4g}, {high:.4g}] rad: the vehicle is {('rolling', 'pitching')[which]} over",
                         time=float(time), signal=name)


class NUMPY(components_xp.NUMPY):
    """``xp`` of the equations on numpy arrays (trailing batch axis): the components' plus the hooks."""

    @staticmethod
    def rotation_body_to_earth(roll, pitch, yaw):
        """:func:`vehdyn.mechanics.rotation_body_to_earth`.

        Parameters
        ----------
        roll, pitch, yaw : float or ndarray
            Euler angles [rad].

        Returns
        -------
        ndarray
            R, shape (3, 3) or (3, 3, n) [-].
        """
        return rotation_body_to_earth(roll, pitch, yaw)

    @staticmethod
    def euler_angle_rates(roll, pitch, p, q, r):
        """:func:`vehdyn.mechanics.euler_angle_rates`.

        Parameters
        ----------
        roll, pitch : float or ndarray
            phi, theta [rad].
        p, q, r : float or ndarray
            Body rates [rad/s].

        Returns
        -------
        tuple
            (dphi/dt, dtheta/dt, dpsi/dt) [rad/s].
        """
        return euler_angle_rates(roll, pitch, p, q, r)


class SCALAR(components_xp.SCALAR):
    """``xp`` of the equations on Python floats (:data:`vehdyn.components.xp.SCALAR`) plus the hooks:
    one state without numpy's per-call overhead, the same numbers as :class:`NUMPY` on it."""

    @staticmethod
    def rotation_body_to_earth(roll, pitch, yaw):
        """:func:`vehdyn.mechanics.kinematics.rotation_matrix` on floats (the source of
        :func:`vehdyn.mechanics.rotation_body_to_earth`).

        Parameters
        ----------
        roll, pitch, yaw : float
            Euler angles [rad].

        Returns
        -------
        tuple
            R, three rows of three floats [-].
        """
        return rotation_matrix(SCALAR, roll, pitch, yaw)

    @staticmethod
    def euler_angle_rates(roll, pitch, p, q, r):
        """:func:`vehdyn.mechanics.euler_angle_rates` on floats: the same gimbal-lock check, then its
        source :func:`vehdyn.mechanics.kinematics.euler_rates`.

        Parameters
        ----------
        roll, pitch : float
            phi, theta [rad].
        p, q, r : float
            Body rates [rad/s].

        Returns
        -------
        tuple
            (dphi/dt, dtheta/dt, dpsi/dt) [rad/s].
        """
        check_gimbal_lock(pitch)
        return euler_rates(SCALAR, roll, pitch, p, q, r)


def gather(values, index):
    """The entries of a model's vector in the order of :data:`STATES`.

    Parameters
    ----------
    values : ndarray
        The model's vector [SI units].
    index : sequence of int
        Position of each entry in ``values``, -1 where the model lacks it.

    Returns
    -------
    list
        ``values[i]`` for each i, zeros (of values[0]'s shape) where i = -1.
    """
    return [values[i] if i >= 0 else 0.0 * values[0] for i in index]


def ground_point(R, k, s, c):
    """Earth position and velocity of corner ``c``'s contact point (body point (x_c, y_c, h_s)).

    Parameters
    ----------
    R : sequence
        The body-to-earth rotation [-].
    k : Constants
        The model's constants (:class:`vehdyn.full_vehicle.assembly.Constants`).
    s : sequence
        The states in the order of :data:`STATES`.
    c : int
        The corner.

    Returns
    -------
    tuple
        (X [m], Y [m], V_X [m/s], V_Y [m/s]).
    """
    xc, yc, zc = k.corner_x[c], k.corner_y[c], k.contact_z
    X = s[9] + R[0][0] * xc + R[0][1] * yc + R[0][2] * zc
    Y = s[10] + R[1][0] * xc + R[1][1] * yc + R[1][2] * zc
    vx, vy, vz = s[0] + s[4] * zc - s[5] * yc, s[1] + s[5] * xc - s[3] * zc, s[2] + s[3] * yc - s[4] * xc
    return X, Y, R[0][0] * vx + R[0][1] * vy + R[0][2] * vz, R[1][0] * vx + R[1][1] * vy + R[1][2] * vz


def _corner(xp, laws, k, c, s, i, R, travel_rate, spring, steer, camber, friction):
    """One corner's share of an evaluation (a tuple of numbers, see :func:`evaluate`)."""
    u, v, p, q, r = s[0], s[1], s[3], s[4], s[5]
    omega, wheel, wheel_rate = s[12 + c], s[16 + c], s[20 + c]
    lateral_deflection, longitudinal_deflection = s[24 + c], s[28 + c]
    x_c, y_c = k.corner_x[c], k.corner_y[c]
    load = corner.normal_load(xp, k, c, wheel, wheel_rate, i[10 + c], i[14 + c])
    # contact-point velocity in body axes (the wheel carrier keeps the body's orientation), then in
    # wheel axes
    h = k.contact_z
    vcx, vcy = u + q * h - r * y_c, v + r * x_c - p * h

    def tire(steer):
        """The tire step at road-wheel angle ``steer``: cos, sin, wheel-axis velocities, deflection
        rates, and contact_loads' forces and slips."""
        cd, sd = xp.cos(steer), xp.sin(steer)
        vx, vy = vcx * cd + vcy * sd, -vcx * sd + vcy * cd
        lat_rate, lon_rate = 0.0 * u, 0.0 * u
        if k.tire_lag:  # the deflection rates: state derivatives and the low-speed damping's input
            lat_rate = deflection_rate(xp, vy, vx, lateral_deflection, k.lateral_relaxation_length[c],
                                       k.peak_tan_slip_angle[c] * friction)
            lon_rate = deflection_rate(xp, -(vx - omega * k.rolling_radius), vx, longitudinal_deflection,
                                       k.longitudinal_relaxation_length[c], k.peak_slip_ratio[c] * friction)
        # the tire step of one wheel (the mirror image of its axle's law where k.mirror_image says so)
        loads = contact_loads(
            xp, k, laws[c // 2], load, vx, vy, omega, lateral_deflection, longitudinal_deflection, lat_rate,
            lon_rate, k.lateral_relaxation_length[c], k.longitudinal_relaxation_length[c],
            k.peak_slip_ratio[c] * friction, k.peak_tan_slip_angle[c] * friction, 0.0 * u, camber, False,
            k.mirror_image[c] > 0.5, friction)
        return cd, sd, vx, lat_rate, lon_rate, loads

    def compliance(step):
        """The wheel's compliance steer 2 c F_y + 2 e M_z (SAE) of a tire step."""
        fy, alpha, kappa = step[5][1], step[5][2], step[5][3]
        out = k.lateral_compliance[c] * fy
        if k.moment_compliance[c] != 0.0:
            kappa_iso, alpha_iso = planar_tire_slips_sae_to_iso_w(kappa, alpha)
            speed = xp.where(step[2] < 0.0, -1.0, 1.0) * xp.maximum(xp.abs(step[2]), 1e-3)
            # SAE M_z = -ISO-W M_z (z down)
            out = out - k.moment_compliance[c] * tire_aligning_moment(
                xp, laws[c // 2], load, kappa_iso, alpha_iso, camber, speed, k.mirror_image[c] > 0.5, friction,
                k.friction_scaled)
        return out

    # compliance steer: explicit with tire lag (the forces come from the deflections: the law once at
    # the steer without it), a Newton step with the static slope and a secant step without
    # (the passes in a loop: one call site of tire and of compliance, which numba inlines at each)
    passes = 1
    if k.compliance_on > 0.5:
        passes = 2 if k.tire_lag else 3
    at = steer
    compliance_steer = first = 0.0 * u
    for n in range(passes):
        step = tire(at)
        if n + 1 < passes:
            g = compliance(step)
            if n > 0:
                compliance_steer = secant_compliance(xp, first, g, compliance_steer, k.compliance_slope[c])
            elif k.tire_lag:
                compliance_steer = g
            else:
                first = g
                compliance_steer = first / (1.0 - k.compliance_slope[c])
            at = steer + compliance_steer
    steer = at
    cd, sd, _vx, lat_rate, lon_rate, (fx, fy, alpha, kappa, rolling_moment) = step
    # the tire's forces lie in the road plane (ISO-W): along the wheel heading projected on the road
    # and its normal there, in body axes; n = R[2] is the earth's z (down) in body axes. Applied
    # along the rolled/pitched body's x-y plane instead, they would lift the car by sum F_y sin(roll)
    tx, ty, tz = _road_plane_force(xp, R, cd, sd, fx, fy)
    # force the contact passes to the body (x, y) and the linkage's vertical force on the body; the
    # linkage passes the road-plane force whole (its body-z part tz too), the spring the load
    link_x, link_y = tx - load * R[2][0], ty - load * R[2][1]
    jack = corner.jacking_force(k, c, link_x, link_y)
    # the wheel's velocity-dependent x-y inertia and its gravity, at the wheel centre
    zw = k.wheel_z
    m_u = k.unsprung_mass[c]
    ox, oy, oz = cross_components(p, q, r, x_c, y_c, zw)
    cx, cy, _cz = cross_components(p, q, r, ox, oy, oz)
    wheel_x = m_u * (k.gravity * R[2][0] - cx - 2.0 * q * travel_rate)
    wheel_y = m_u * (k.gravity * R[2][1] - cy + 2.0 * p * travel_rate)
    # the unsprung mass's lateral force reaches the body through the linkage as the tire's does; the
    # part of its moment the linkage does not pass is taken by the tire load (corner.unsprung_jacking;
    # its acceleration-proportional part is in k.projection and in evaluate)
    jack_u = k.unsprung_jacking[c] * wheel_y
    f_z = jack + jack_u - spring + tz
    # the contact point lies on the road: its body z below the sprung CG changes as the body rolls,
    # pitches and heaves (road height i[10 + c] up, CG displacement s[11] down); the road-plane
    # forces act there, which with tz at the wheel gives their moment the CG's height over the road
    zeta = (h - i[10 + c] - s[11] - R[2][0] * x_c - R[2][1] * y_c) / R[2][2]
    mx1, my1, mz1 = cross_components(x_c, y_c, zeta, link_x, link_y, f_z)
    mx2, my2, mz2 = cross_components(x_c, y_c, zw, wheel_x, wheel_y, 0.0 * u)
    return (load, alpha, kappa, fx, fy,
            driveline.wheel_acceleration(xp, k, omega, i[2 + c], i[6 + c], fx, rolling_moment),
            (load - spring + jack + jack_u) / m_u - k.gravity, lat_rate, lon_rate,
            link_x + wheel_x, link_y + wheel_y, f_z, mx1 + mx2, my1 + my2, mz1 + mz2, link_x, link_y,
            tz - load * R[2][2], steer, compliance_steer)


def _road_plane_force(xp, R, cd, sd, fx, fy):
    """Body-axis components (x, y, z) [N] of a tire's longitudinal and lateral forces ``fx``, ``fy``
    (SAE wheel axes) that lie in the road plane.

    The wheel heading d = (cos delta, sin delta, 0) (body axes, steer angle delta) projected on the
    road plane, h = (d - (d.n) n) / |d - (d.n) n|, and the road-plane lateral axis l = n x h, with
    n = (R20, R21, R22) the earth's z axis (down) in body axes (R body-to-earth). With the body
    level, h = d and l = (-sin delta, cos delta, 0). (Pacejka, *Tire and Vehicle Dynamics*, 3rd ed.,
    2012, sec. 2.2: the tire's force components in the road plane, the normal load along the road
    normal.)
    """
    n0, n1, n2 = R[2][0], R[2][1], R[2][2]
    dn = cd * n0 + sd * n1
    scale = 1.0 / xp.sqrt(1.0 - dn * dn)
    hx, hy, hz = (cd - dn * n0) * scale, (sd - dn * n1) * scale, -dn * n2 * scale
    lx, ly, lz = n1 * hz - n2 * hy, n2 * hx - n0 * hz, n0 * hy - n1 * hx
    return fx * hx + fy * lx, fx * hy + fy * ly, fx * hz + fy * lz


def _column(corners, j):
    """Entry ``j`` of the four corners' tuples."""
    return corners[0][j], corners[1][j], corners[2][j], corners[3][j]


def _total(corners, j):
    """Sum over the corners of entry ``j``."""
    return corners[0][j] + corners[1][j] + corners[2][j] + corners[3][j]


def evaluate(xp, laws, k, s, i, friction):
    """An :class:`Evaluation` at states ``s`` and inputs ``i``.

    Per-corner values are tuples built from one function per corner (:func:`_corner`): no lists,
    so that the same source compiles to allocation-free code.

    Parameters
    ----------
    xp : namespace
        The equations' namespace (module docstring).
    laws : tuple
        The (front, rear) tire laws (``TireModel`` on numpy, ``TireLaw`` compiled).
    k : Constants
        The model's constants.
    s : sequence
        The states in the order of :data:`STATES` [SI units].
    i : sequence
        The inputs in the order of :data:`INPUTS` [SI units].
    friction : tuple
        The road's friction under each corner relative to the tire law's own [-] (FL, FR, RL, RR;
        read where ``k.friction_scaled``, else 1.0).

    Returns
    -------
    Evaluation
    """
    u, v, w, p, q, r, roll, pitch, yaw, z = s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], s[8], s[11]
    R = xp.rotation_body_to_earth(roll, pitch, yaw)
    R20, R21, R22 = R[2][0], R[2][1], R[2][2]

    # suspension
    t0 = corner.suspension_travel(R, z, u, v, w, p, q, r, k.corner_x[0], k.corner_y[0], k.spring_z, s[16], s[20])
    t1 = corner.suspension_travel(R, z, u, v, w, p, q, r, k.corner_x[1], k.corner_y[1], k.spring_z, s[17], s[21])
    t2 = corner.suspension_travel(R, z, u, v, w, p, q, r, k.corner_x[2], k.corner_y[2], k.spring_z, s[18], s[22])
    t3 = corner.suspension_travel(R, z, u, v, w, p, q, r, k.corner_x[3], k.corner_y[3], k.spring_z, s[19], s[23])
    travel, travel_rate = (t0[0], t1[0], t2[0], t3[0]), (t0[1], t1[1], t2[1], t3[1])
    spring = corner.suspension_forces(k, travel, travel_rate)
    steer = steering.corner_steer_angles(xp, k, i[0], i[1], roll)
    camber = (corner.camber(k, 0, roll, travel[0]), corner.camber(k, 1, roll, travel[1]),
              corner.camber(k, 2, roll, travel[2]), corner.camber(k, 3, roll, travel[3]))
    corners = (_corner(xp, laws, k, 0, s, i, R, travel_rate[0], spring[0], steer[0], camber[0], friction[0]),
               _corner(xp, laws, k, 1, s, i, R, travel_rate[1], spring[1], steer[1], camber[1], friction[1]),
               _corner(xp, laws, k, 2, s, i, R, travel_rate[2], spring[2], steer[2], camber[2], friction[2]),
               _corner(xp, laws, k, 3, s, i, R, travel_rate[3], spring[3], steer[3], camber[3], friction[3]))

    drag, side, wind_moment, front_lift, rear_lift = aero.aero_forces(xp, k, u, i[18])
    weight = k.sprung_mass * k.gravity
    fx_body = _total(corners, 9) + drag + weight * R20
    fy_body = _total(corners, 10) + side + weight * R21
    fz_body = _total(corners, 11) - front_lift - rear_lift + weight * R22
    moment_y = _total(corners, 13) + k.corner_x[0] * front_lift + k.corner_x[2] * rear_lift
    velocity_rate, angular, cg_acc = body.body_accelerations(
        xp, k, (u, v, w), (p, q, r), (fx_body, fy_body, fz_body), (_total(corners, 12), moment_y, _total(corners, 14) + wind_moment))

    # the wheels' share of the unsprung masses' acceleration-proportional lateral force through the
    # linkage: -kappa_c (a + omega' x W_c)_y per unit unsprung mass (explicit: the body's accelerations
    # do not depend on the wheels' vertical ones)
    unsprung = (corners[0][6] - k.unsprung_jacking[0] * (cg_acc[1] + angular[2] * k.corner_x[0]
                                                          - angular[0] * k.wheel_z),
                corners[1][6] - k.unsprung_jacking[1] * (cg_acc[1] + angular[2] * k.corner_x[1]
                                                          - angular[0] * k.wheel_z),
                corners[2][6] - k.unsprung_jacking[2] * (cg_acc[1] + angular[2] * k.corner_x[2]
                                                          - angular[0] * k.wheel_z),
                corners[3][6] - k.unsprung_jacking[3] * (cg_acc[1] + angular[2] * k.corner_x[3]
                                                          - angular[0] * k.wheel_z))
    euler = xp.euler_angle_rates(roll, pitch, p, q, r)
    position = (R[0][0] * u + R[0][1] * v + R[0][2] * w, R[1][0] * u + R[1][1] * v + R[1][2] * w,
                R20 * u + R21 * v + R22 * w)
    # horizontal acceleration of the total CG, intermediate axes: non-gravity forces / m
    contact_x, contact_y, contact_z = _total(corners, 15) + drag, _total(corners, 16) + side, \
        _total(corners, 17) - front_lift - rear_lift
    ex = R[0][0] * contact_x + R[0][1] * contact_y + R[0][2] * contact_z
    ey = R[1][0] * contact_x + R[1][1] * contact_y + R[1][2] * contact_z
    cpsi, spsi = xp.cos(yaw), xp.sin(yaw)
    horizontal = ((cpsi * ex + spsi * ey) / k.mass, (-spsi * ex + cpsi * ey) / k.mass)
    vertical = -(R20 * cg_acc[0] + R21 * cg_acc[1] + R22 * cg_acc[2])
    return Evaluation(velocity_rate, angular, cg_acc, (euler[0], euler[1], euler[2]), position, _column(corners, 5),
                      unsprung, _column(corners, 7), _column(corners, 8), _column(corners, 0),
                      _column(corners, 1), _column(corners, 2), _column(corners, 3), _column(corners, 4), travel,
                      camber, _column(corners, 18), horizontal, vertical, _column(corners, 19))


def derivatives(s, e):
    """d/dt of every entry of :data:`STATES` from an :class:`Evaluation`.

    Parameters
    ----------
    s : sequence
        The states in the order of :data:`STATES`.
    e : Evaluation
        :func:`evaluate` at them.

    Returns
    -------
    tuple
        32 rates [SI units per second].
    """
    return (e.velocity_rate + e.angular_acceleration + e.euler_rates + e.position_rates + e.wheel_acceleration
            + (s[20], s[21], s[22], s[23]) + e.unsprung_acceleration + e.lateral_deflection_rate
            + e.longitudinal_deflection_rate)


OUTPUTS = (("longitudinal_acceleration", "m/s^2", "horizontal longitudinal acceleration of the total CG in the "
            "intermediate (yaw-only) axes, gravity excluded"),
           ("lateral_acceleration", "m/s^2", "horizontal lateral acceleration of the total CG in the intermediate "
            "axes (right +, SAE), gravity excluded"),
           ("sideslip_angle", "rad", "vehicle sideslip at the sprung CG, atan2(v, |u|)"),
           ("speed", "m/s", "speed of the sprung CG in its body x-y plane, sqrt(u^2 + v^2)"),
           ("path_curvature", "1/m", "a_y / V^2 (V^2 floored at 0.25 m^2/s^2)"),
           ("yaw_rate", "rad/s", "body yaw rate r"),
           ("roll_angle", "rad", "roll angle phi (right side down +)"),
           ("pitch_angle", "rad", "pitch angle theta (nose up +)"),
           ("sprung_acceleration", "m/s^2", "vertical acceleration of the sprung CG (up +, gravity excluded)"),
           ("longitudinal_velocity", "m/s", "body-frame forward velocity u of the sprung CG"),
           ("lateral_velocity", "m/s", "body-frame lateral velocity v of the sprung CG"),
           ("x", "m", "earth-fixed X of the sprung CG"),
           ("y", "m", "earth-fixed Y of the sprung CG (SAE)"),
           ("yaw_angle", "rad", "heading psi"))
CORNER_OUTPUTS = (("normal_load", "N", "tire normal load (>= 0)"),
                  ("slip_angle", "rad", "slip angle acting in the tire law (SAE)"),
                  ("slip_ratio", "-", "slip ratio acting in the tire law"),
                  ("longitudinal_force", "N", "tire longitudinal force in wheel axes"),
                  ("lateral_force", "N", "tire lateral force in wheel axes (SAE y)"),
                  ("suspension_travel", "m", "suspension extension z_body - z_wheel (rebound +)"),
                  ("camber_angle", "rad", "wheel inclination, rotation about x (SAE = ISO-W)"),
                  ("steer_angle", "rad", "road-wheel steer angle (SAE)"))


def outputs(xp, s, e):
    """The outputs in the order of :data:`OUTPUTS` then :data:`CORNER_OUTPUTS` (each over the corners).

    Parameters
    ----------
    xp : namespace
        The equations' namespace (:mod:`vehdyn.components.xp`).
    s : sequence
        The states in the order of :data:`STATES`.
    e : Evaluation
        :func:`evaluate` at them.

    Returns
    -------
    tuple
        The outputs [SI units of :data:`OUTPUTS`].
    """
    u, v = s[0], s[1]
    speed_squared = u * u + v * v
    ax, ay = e.horizontal_acceleration
    return ((ax, ay, xp.atan2(v, xp.abs(u)), xp.sqrt(speed_squared), ay / xp.maximum(speed_squared, 0.25), s[5],
             s[6], s[7], e.sprung_acceleration, u, v, s[9], s[10], s[8])
            + e.normal_load + e.slip_angle + e.slip_ratio + e.longitudinal_force + e.lateral_force
            + e.suspension_travel + e.camber + e.steer)
