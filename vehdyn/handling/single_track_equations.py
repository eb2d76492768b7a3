"""The equations of :class:`~vehdyn.handling.SingleTrack` as pure functions over an ``xp`` namespace.

One source for every backend: the functions below use only the interface of
:mod:`vehdyn.components.xp` (``xp.cos``, ``xp.sin``, ``xp.atan``, ``xp.atan2``, ``xp.sqrt``,
``xp.abs``, ``xp.tanh``, ``xp.where``, ``xp.minimum``, ``xp.maximum`` and the tire hooks
``xp.tire_law`` / ``xp.tire_law_pair``) and plain arithmetic, and the shared components
(:mod:`~vehdyn.components.tire_slip`, :mod:`~vehdyn.components.tire_forces`,
:mod:`~vehdyn.components.wheel`, :mod:`~vehdyn.components.planar`, :mod:`~vehdyn.components.aero`),
so that they run

* on numpy arrays with a trailing batch axis (:data:`NUMPY`, what ``SingleTrack.rhs`` and
  ``output`` use; a tire law is a :class:`~vehdyn.tire.TireModel`), and
* on floats inside numba-compiled code (:mod:`vehdyn.handling._single_track_numba` registers
  these functions with ``register_jitable`` and runs them with the compiled ``xp`` of
  :mod:`vehdyn.components.compiled`; a tire law is a :class:`vehdyn.tire.compiled.TireLaw`).

Control flow branches only on the model's options (fields of :class:`Constants`), never on a state.
The equations, their signs and references are in the docstring of
:mod:`vehdyn.handling.single_track`. Signals travel in a fixed order (:data:`STATES`,
:data:`INPUTS`); a model's own vectors hold a subset, mapped through an index (-1: absent, 0.0).
"""

from __future__ import annotations

from collections import namedtuple

from vehdyn.components.aero import aero_side_force
from vehdyn.components.planar import position_rates
from vehdyn.components.tire_forces import (contact_loads, demanded_forces, secant_compliance,
                                           wheel_pair_aligning_moments, wheel_pair_tire_loads)
from vehdyn.components.tire_slip import contact_slips, deflection_rate, low_speed_blend
from vehdyn.components.wheel import net_wheel_torque, rolling_resistance_fade
from vehdyn.components.xp import NUMPY
from vehdyn.conventions import planar_tire_forces_iso_w_to_sae, planar_tire_slips_sae_to_iso_w

__all__ = ["STATES", "INPUTS", "Constants", "Evaluation", "NUMPY", "named_states", "named_inputs", "evaluate",
           "derivatives", "outputs", "axle_loads", "wheel_pair_loads", "wheel_load_outputs", "normal_loads",
           "lateral_load_transfer", "roll_acceleration", "deflection_rates", "axle_aligning_moment"]

STATES = ("longitudinal_velocity", "lateral_velocity", "yaw_rate", "x", "y", "yaw_angle", "front_wheel_speed",
          "rear_wheel_speed", "front_lateral_deflection", "rear_lateral_deflection", "front_longitudinal_deflection",
          "rear_longitudinal_deflection", "roll_angle", "roll_rate")
"""Every state a SingleTrack can have, in the order of :func:`evaluate` and :func:`derivatives`."""

INPUTS = ("front_steer_angle", "rear_steer_angle", "front_longitudinal_force", "rear_longitudinal_force",
          "front_drive_torque", "rear_drive_torque", "front_brake_torque", "rear_brake_torque",
          "external_lateral_force", "external_yaw_moment", "wind_velocity_lateral")
"""Every input a SingleTrack can have, in the order of :func:`evaluate`."""

Constants = namedtuple("Constants", (
    "mass", "yaw_inertia", "a", "b", "cg_height", "rolling_radius", "wheel_spin_inertia", "friction_coefficient",
    "front_lateral_relaxation_length", "rear_lateral_relaxation_length", "front_longitudinal_relaxation_length",
    "rear_longitudinal_relaxation_length", "drag_factor", "front_lift_factor", "rear_lift_factor", "gravity",
    "low_speed_damping_speed", "brake_regularization_speed", "front_peak_slip_ratio", "front_peak_tan_slip_angle",
    "rear_peak_slip_ratio", "rear_peak_tan_slip_angle", "wind_side_force_factor", "centre_of_pressure",
    "front_geometric_transfer", "front_elastic_transfer", "rear_geometric_transfer", "rear_elastic_transfer",
    "front_track", "rear_track", "roll_inertia", "roll_arm", "front_roll_transfer_stiffness",
    "rear_roll_transfer_stiffness", "front_roll_transfer_damping", "rear_roll_transfer_damping",
    "front_mirror_right", "rear_mirror_right", "front_ply_steer", "rear_ply_steer", "road_friction",
    "front_lateral_force_compliance", "rear_lateral_force_compliance", "front_aligning_moment_compliance",
    "rear_aligning_moment_compliance", "front_compliance_slope", "rear_compliance_slope", "compliance_steer",
    "front_roll_steer", "rear_roll_steer", "front_camber_per_roll", "rear_camber_per_roll", "quasi_static_roll",
    "roll_terms", "wheel_spin", "tire_lag", "lateral_load_transfer", "friction_scaled"))
Constants.__doc__ = """What the equations read: the model's numbers, options and the two laws' characteristics.

The fields of :class:`~vehdyn.handling.single_track.SingleTrackParameters` are floats, or arrays
across batch variants on numpy; the four flags come last (a compiled batch appends them to a
variant's floats).

Parameters
----------
mass : float
    m [kg].
yaw_inertia : float
    I_z [kg*m^2].
a, b : float
    CG to the front and rear axle [m].
cg_height : float
    h [m].
rolling_radius : float
    R_e [m].
wheel_spin_inertia : float
    I_w of one wheel [kg*m^2].
friction_coefficient : float
    The laws' own mu of the force mode's friction ellipse [-].
front_lateral_relaxation_length, rear_lateral_relaxation_length : float
    sigma_y [m].
front_longitudinal_relaxation_length, rear_longitudinal_relaxation_length : float
    sigma_x [m].
drag_factor : float
    0.5 rho c_x A [kg/m].
front_lift_factor, rear_lift_factor : float
    0.5 rho c_l A of each axle [kg/m].
gravity : float
    g [m/s^2].
low_speed_damping_speed : float
    v_l [m/s].
brake_regularization_speed : float
    omega_b [rad/s].
front_peak_slip_ratio, front_peak_tan_slip_angle, rear_peak_slip_ratio, rear_peak_tan_slip_angle : float
    The slips of the laws' peak forces [-] (the deflections' limits).
wind_side_force_factor : float
    k_w [kg/m].
centre_of_pressure : float
    x_p ahead of the CG [m].
front_geometric_transfer, front_elastic_transfer, rear_geometric_transfer, rear_elastic_transfer : float
    Lateral load transfer coefficients [-] (:func:`lateral_load_transfer`; 0 without the transfer).
front_track, rear_track : float
    The arms of the yaw couple of unequal left and right longitudinal forces [m] (0 without).
roll_inertia : float
    J [kg*m^2] (1 without roll).
roll_arm : float
    h_1 [m] (0 without roll).
front_roll_transfer_stiffness, rear_roll_transfer_stiffness : float
    K_i / t_i [N/rad].
front_roll_transfer_damping, rear_roll_transfer_damping : float
    C_i / t_i [N*s/rad].
front_mirror_right, rear_mirror_right : float
    1.0 where the axle's right wheel is the law's mirror image (a ``.tir`` file with
    ``TYRESIDE = 'LEFT'``), else 0.0 (the left one, or none:
    :func:`vehdyn.components.tire_setup.mirrored_wheel`) [-].
front_ply_steer, rear_ply_steer : float
    1.0 where the law makes a lateral force at zero slip (one tire of the axle is its mirror
    image), else 0.0 [-].
road_friction : float
    The road's friction relative to the laws' own, mu [-] (a constant ratio; 1.0 without).
front_lateral_force_compliance, rear_lateral_force_compliance : float
    c_i [rad/N]: the axle's compliance steer per unit of its lateral force (SAE, positive in the
    sense of the force; the vehicle's ``suspension.*_lateral_force_compliance_steer``).
front_aligning_moment_compliance, rear_aligning_moment_compliance : float
    e_i [rad/(N*m)]: the axle's compliance steer per unit of its aligning moment (SAE yaw;
    ``suspension.*_aligning_moment_compliance_steer``).
front_compliance_slope, rear_compliance_slope : float
    s_i = (c_i - e_i t_i) C_i [-]: the slope of the compliance steer against itself (C_i the law's
    axle cornering stiffness and t_i its pneumatic trail at the static axle load), the Newton step
    of the model without tire lag (:func:`evaluate`).
compliance_steer : float
    1.0 where a compliance is nonzero, else 0.0 [-] (the step is skipped).
front_roll_steer, rear_roll_steer : float
    eps_i [rad/rad]: the axle's road-wheel steer per unit body roll (SAE; ``suspension.*_roll_steer``).
front_camber_per_roll, rear_camber_per_roll : float
    dgamma_i / dphi [-]: the axle's (ISO-W) inclination per unit body roll, 1 + g_i (T_i / 2)
    phi_si / phi with camber gains g_i, 0 without (upright wheels).
quasi_static_roll : float
    -RG [rad/(m/s^2)]: the body's roll per unit lateral acceleration where the model has no roll
    degree of freedom (the steady roll of :func:`vehdyn.handling.steady_roll`, taken at a_y = u r);
    0 with the roll state.
roll_terms : float
    1.0 where roll steer or camber from roll acts (lateral load transfer and a nonzero roll steer
    or camber gains), else 0.0 [-].
wheel_spin, tire_lag, lateral_load_transfer : bool
    The model's options.
friction_scaled : bool
    The road's friction applies (a ratio or a callable was given)."""

Evaluation = namedtuple("Evaluation", (
    "longitudinal_acceleration", "lateral_acceleration", "yaw_acceleration", "front_longitudinal_force",
    "front_lateral_force", "front_slip_angle", "front_slip_ratio", "rear_longitudinal_force", "rear_lateral_force",
    "rear_slip_angle", "rear_slip_ratio", "front_normal_load", "rear_normal_load", "front_vx", "front_vy",
    "rear_vx", "rear_vy", "front_lateral_deflection_rate", "rear_lateral_deflection_rate",
    "front_longitudinal_deflection_rate", "rear_longitudinal_deflection_rate", "front_rolling_moment",
    "rear_rolling_moment", "front_load_transfer", "rear_load_transfer", "roll_acceleration", "front_steer_angle",
    "rear_steer_angle", "front_compliance_steer_angle", "rear_compliance_steer_angle"))
Evaluation.__doc__ = """Everything one evaluation of the equations yields.

Parameters
----------
longitudinal_acceleration, lateral_acceleration : float or ndarray
    du/dt - v r and dv/dt + u r of the CG [m/s^2].
yaw_acceleration : float or ndarray
    dr/dt [rad/s^2].
front_longitudinal_force, front_lateral_force, rear_longitudinal_force, rear_lateral_force : float or ndarray
    Axle forces in SAE wheel axes [N].
front_slip_angle, rear_slip_angle : float or ndarray
    SAE slip angles acting in the laws [rad].
front_slip_ratio, rear_slip_ratio : float or ndarray
    Slip ratios acting in the laws [-].
front_normal_load, rear_normal_load : float or ndarray
    Axle loads [N].
front_vx, front_vy, rear_vx, rear_vy : float or ndarray
    Wheel-centre velocities in wheel axes [m/s].
front_lateral_deflection_rate, rear_lateral_deflection_rate : float or ndarray
    [m/s] (0 without tire lag).
front_longitudinal_deflection_rate, rear_longitudinal_deflection_rate : float or ndarray
    [m/s] (0 without tire lag or wheel spin).
front_rolling_moment, rear_rolling_moment : float or ndarray
    The axles' rolling-resistance moments M_y [N*m] (ISO-W, about the axis of forward spin,
    negative rolling forwards; 0 in force mode).
front_load_transfer, rear_load_transfer : float or ndarray
    Lateral load transfer onto each axle's left wheel [N] (which carries F_z / 2 + dF_z; 0
    without lateral load transfer).
roll_acceleration : float or ndarray
    dp/dt [rad/s^2] (0 without roll).
front_steer_angle, rear_steer_angle : float or ndarray
    The road-wheel steer angles the axles run at: the inputs plus roll steer and compliance steer [rad].
front_compliance_steer_angle, rear_compliance_steer_angle : float or ndarray
    Their compliance steer c_i F_y,i + e_i M_z,i [rad] (0 without compliance)."""


def _at(values, i):
    """values[i], or zero (of values[0]'s shape) for i = -1: a signal the model lacks."""
    return values[i] if i >= 0 else 0.0 * values[0]


def named_states(x, index):
    """The states of a model's vector in the order of :data:`STATES`.

    Parameters
    ----------
    x : ndarray
        The model's state vector (optional batch axis) [SI units].
    index : sequence of int
        Position of each entry of :data:`STATES` in ``x``, -1 where the model lacks it.

    Returns
    -------
    tuple
        14 entries [SI units of :data:`STATES`]; zeros where the model lacks a state.
    """
    return (_at(x, index[0]), _at(x, index[1]), _at(x, index[2]), _at(x, index[3]), _at(x, index[4]),
            _at(x, index[5]), _at(x, index[6]), _at(x, index[7]), _at(x, index[8]), _at(x, index[9]),
            _at(x, index[10]), _at(x, index[11]), _at(x, index[12]), _at(x, index[13]))


def named_inputs(u, index):
    """The inputs of a model's vector in the order of :data:`INPUTS` (see :func:`named_states`).

    Parameters
    ----------
    u : ndarray
        The model's input vector [SI units].
    index : sequence of int
        Position of each entry of :data:`INPUTS` in ``u``, -1 where the model lacks it.

    Returns
    -------
    tuple
        11 entries [SI units of :data:`INPUTS`]; zeros where the model lacks an input.
    """
    return (_at(u, index[0]), _at(u, index[1]), _at(u, index[2]), _at(u, index[3]), _at(u, index[4]),
            _at(u, index[5]), _at(u, index[6]), _at(u, index[7]), _at(u, index[8]), _at(u, index[9]), _at(u, index[10]))


def axle_loads(xp, tires, axle, k, fz, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection,
               lateral_rate, longitudinal_rate, lateral_length, longitudinal_length, peak_slip_ratio,
               peak_tan_slip_angle, force_demand, friction):
    """The tire step of a lumped axle: two tires at half its load each, on the centre line.

    :func:`vehdyn.components.tire_forces.contact_loads` with ``axle=True``: the axle's law, its
    mirror image with ply steer (``k.front_ply_steer``, ``k.rear_ply_steer``), the road's friction
    by similarity.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    tires : tuple
        The (front, rear) laws (``TireModel`` on numpy, ``TireLaw`` compiled).
    axle : int
        0 front, 1 rear.
    k : Constants
        The model's constants.
    fz : float or ndarray
        Axle load [N].
    vx, vy : float or ndarray
        Wheel-centre velocity in wheel axes (SAE) [m/s].
    wheel_speed : float or ndarray
        Spin of the axle's wheels [rad/s].
    lateral_deflection, longitudinal_deflection : float or ndarray
        Tire deflections [m].
    lateral_rate, longitudinal_rate : float or ndarray
        Their rates [m/s].
    lateral_length, longitudinal_length : float or ndarray
        Relaxation lengths [m].
    peak_slip_ratio, peak_tan_slip_angle : float or ndarray
        Peak-force slips on this road [-].
    force_demand : float or ndarray
        Force mode's longitudinal force demand [N].
    friction : float or ndarray
        The road's friction ratio under the axle [-].

    Returns
    -------
    tuple
        (F_x [N], F_y [N]) in SAE wheel axes, alpha SAE [rad], kappa [-], and M_y [N*m] (ISO-W,
        faded at standstill; 0 in force mode).
    """
    ply_steer = (k.front_ply_steer if axle == 0 else k.rear_ply_steer) > 0.5
    return contact_loads(xp, k, tires[axle], fz, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection,
                         lateral_rate, longitudinal_rate, lateral_length, longitudinal_length, peak_slip_ratio,
                         peak_tan_slip_angle, force_demand, 0.0, True, ply_steer, friction)


def normal_loads(xp, k, x_force, front_lift, rear_lift):
    r"""Axle loads with quasi-static longitudinal load transfer (Gillespie 1992, eq. 2-18) and lift.

    .. math::

        F_{zf} = m g b / L - h X / L - L_f,\qquad F_{zr} = m g - L_f - L_r - F_{zf}

    An axle that would lift off carries 0 and the other the whole weight.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : Constants
        The model's constants.
    x_force : float or ndarray
        The body-x tire force X [N].
    front_lift, rear_lift : float or ndarray
        Aerodynamic lift at the axles [N].

    Returns
    -------
    tuple
        (front, rear) [N].
    """
    wheelbase = k.a + k.b
    weight = k.mass * k.gravity
    front = weight * k.b / wheelbase - k.cg_height * x_force / wheelbase - front_lift
    total = weight - front_lift - rear_lift
    front = xp.minimum(xp.maximum(front, 0.0), xp.maximum(total, 0.0))
    return front, xp.maximum(total - front, 0.0)


def lateral_load_transfer(xp, k, front_lateral, rear_lateral, front_load, rear_load, roll_angle, roll_rate):
    r"""Lateral load transfer (front, rear) [N]: the load moved onto each axle's left wheel.

    .. math::

        \Delta F_{z,i} = \frac{z_i}{t_i} F_{y,i} + \frac{h_1 K_i}{(K_f + K_r - m g h_1) t_i}
        (F_{y,f} + F_{y,r}) - \frac{K_i \phi + C_i p}{t_i}

    (Milliken & Milliken 1995, ch. 18; the ``*_geometric_transfer``, ``*_elastic_transfer``,
    ``*_roll_transfer_stiffness`` and ``*_roll_transfer_damping`` coefficients of
    :class:`Constants`): without the roll degree of freedom the last term is absent (the
    quasi-static elastic part), with it the elastic part is the suspension's roll moment; held
    within +-F_z,i / 2 (an inner wheel that would lift carries 0).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : Constants
        The model's constants.
    front_lateral, rear_lateral : float or ndarray
        The axles' lateral forces in body axes [N] (SAE y, positive turning right, so the load
        moves onto the left, outer wheels).
    front_load, rear_load : float or ndarray
        Axle loads [N].
    roll_angle : float or ndarray
        phi [rad] (SAE: positive right side down).
    roll_rate : float or ndarray
        p [rad/s].

    Returns
    -------
    tuple
        (front, rear) [N].
    """
    total = front_lateral + rear_lateral
    front = k.front_geometric_transfer * front_lateral + k.front_elastic_transfer * total \
        - k.front_roll_transfer_stiffness * roll_angle - k.front_roll_transfer_damping * roll_rate
    rear = k.rear_geometric_transfer * rear_lateral + k.rear_elastic_transfer * total \
        - k.rear_roll_transfer_stiffness * roll_angle - k.rear_roll_transfer_damping * roll_rate
    front_half, rear_half = 0.5 * xp.maximum(front_load, 0.0), 0.5 * xp.maximum(rear_load, 0.0)
    return (xp.minimum(xp.maximum(front, -front_half), front_half),
            xp.minimum(xp.maximum(rear, -rear_half), rear_half))


def roll_acceleration(xp, k, lateral_acceleration, roll_angle, roll_rate):
    r"""Roll acceleration of the body (SAE: positive right side down; Segel 1956).

    .. math::

        J \dot p = -m h_1 a_y - (K_f + K_r - m g h_1) \phi - (C_f + C_r) p

    with J the effective roll inertia, h_1 the CG height above the roll axis; K_i = t_i (K_i / t_i)
    and C_i = t_i (C_i / t_i) from :class:`Constants` (0 without roll: then h_1 = 0 and the result
    is 0).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : Constants
        The model's constants.
    lateral_acceleration : float or ndarray
        a_y of the CG [m/s^2] (all lateral forces over the mass).
    roll_angle : float or ndarray
        phi [rad].
    roll_rate : float or ndarray
        p [rad/s].

    Returns
    -------
    float or ndarray
        dp/dt [rad/s^2].
    """
    stiffness = k.front_track * k.front_roll_transfer_stiffness + k.rear_track * k.rear_roll_transfer_stiffness
    damping = k.front_track * k.front_roll_transfer_damping + k.rear_track * k.rear_roll_transfer_damping
    moment = k.roll_arm * k.mass
    return (-moment * lateral_acceleration - (stiffness - moment * k.gravity) * roll_angle
            - damping * roll_rate) / k.roll_inertia


def wheel_pair_loads(xp, tires, axle, k, fz, shift, vx, vy, wheel_speed, lateral_deflection,
                     longitudinal_deflection, lateral_rate, longitudinal_rate, lateral_length, longitudinal_length,
                     peak_slip_ratio, peak_tan_slip_angle, force_demand, friction, gamma):
    """The tire step of an axle whose wheels carry F_z / 2 + ``shift`` (left) and F_z / 2 - ``shift`` (right).

    Each wheel's law at its own load (:func:`vehdyn.components.tire_forces.wheel_pair_tire_loads`;
    the mirror image on the side :func:`vehdyn.components.tire_setup.mirrored_wheel` names). In
    force mode each wheel takes half the demand (an open differential, equal brake pressures),
    clipped at mu times its load, with its own friction ellipse, and its rolling resistance M_y / R_e
    shifts the force between the wheels (the demand stays the axle's net force).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    tires : tuple
        The (front, rear) laws.
    axle : int
        0 front, 1 rear.
    k : Constants
        The model's constants.
    fz : float or ndarray
        Axle load [N].
    shift : float or ndarray
        Lateral load transfer onto the left wheel [N].
    vx, vy : float or ndarray
        Wheel-centre velocity in wheel axes (SAE) [m/s].
    wheel_speed : float or ndarray
        Spin of the axle's wheels [rad/s].
    lateral_deflection, longitudinal_deflection : float or ndarray
        Tire deflections [m].
    lateral_rate, longitudinal_rate : float or ndarray
        Their rates [m/s].
    lateral_length, longitudinal_length : float or ndarray
        Relaxation lengths [m].
    peak_slip_ratio, peak_tan_slip_angle : float or ndarray
        Peak-force slips on this road [-].
    force_demand : float or ndarray
        Force mode's longitudinal force demand of the axle [N].
    friction : float or ndarray
        The road's friction ratio under the axle [-].
    gamma : float or ndarray
        Inclination of both wheels [rad] (ISO-W; 0.0 upright).

    Returns
    -------
    tuple
        The axle's (F_x [N], F_y [N]) in SAE wheel axes, alpha SAE [rad], kappa [-], M_y [N*m] (as
        :func:`axle_loads`), and F_x,left - F_x,right [N].
    """
    alpha, kappa, direction, speed = contact_slips(
        xp, k, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection, lateral_rate, longitudinal_rate,
        lateral_length, longitudinal_length, peak_slip_ratio, peak_tan_slip_angle)
    kappa_iso, alpha_iso = planar_tire_slips_sae_to_iso_w(kappa, alpha)
    left_load, right_load = 0.5 * fz + shift, 0.5 * fz - shift
    ply_steer = (k.front_ply_steer if axle == 0 else k.rear_ply_steer) > 0.5
    right_mirrored = (k.front_mirror_right if axle == 0 else k.rear_mirror_right) > 0.5
    w = wheel_pair_tire_loads(xp, tires[axle], left_load, right_load, kappa_iso, alpha_iso, gamma,
                              direction * xp.maximum(speed, 1e-3), ply_steer and not right_mirrored, right_mirrored,
                              friction, k.friction_scaled)
    fx_left, fy_left = planar_tire_forces_iso_w_to_sae(w[0], w[1])
    fx_right, fy_right = planar_tire_forces_iso_w_to_sae(w[3], w[4])
    my = w[2] + w[5]
    if not k.wheel_spin:
        fx_left, fy_left = demanded_forces(xp, k, left_load, fx_left, fy_left, 0.5 * force_demand, friction)
        fx_right, fy_right = demanded_forces(xp, k, right_load, fx_right, fy_right, 0.5 * force_demand, friction)
        resistance = (w[2] - w[5]) / k.rolling_radius  # ISO-W M_y < 0 rolling forwards: retarding
        # the rolling resistance fades at standstill as in axle_loads
        return (fx_left + fx_right, fy_left + fy_right, alpha, kappa, 0.0 * my,
                fx_left - fx_right + resistance * xp.abs(low_speed_blend(xp, speed, k.low_speed_damping_speed) - 1.0))
    return (fx_left + fx_right, fy_left + fy_right, alpha, kappa, my * rolling_resistance_fade(xp, k, wheel_speed),
            fx_left - fx_right)


def axle_aligning_moment(xp, tires, axle, k, fz, shift, alpha, kappa, gamma, vx, force_demand, friction):
    """The SAE aligning moment M_z [N*m] of an axle's two tires at the slips its forces were taken at.

    :func:`vehdyn.components.tire_forces.wheel_pair_aligning_moments` at the wheels' loads
    F_z / 2 +- ``shift`` (the mirror image where :func:`axle_loads` or :func:`wheel_pair_loads` has
    it), turned to SAE (M_z,SAE = -M_z,ISO-W: z points down); in force mode each wheel's moment is
    reduced by its friction ellipse as its lateral force is
    (:func:`vehdyn.components.tire_forces.demanded_forces`).

    Parameters
    ----------
    xp : namespace
        The equations' namespace (with ``tire_law_aligning``).
    tires : tuple
        The (front, rear) laws.
    axle : int
        0 front, 1 rear.
    k : Constants
        The model's constants.
    fz : float or ndarray
        Axle load [N].
    shift : float or ndarray
        Lateral load transfer onto the left wheel [N] (0 without).
    alpha : float or ndarray
        SAE slip angle acting in the law [rad].
    kappa : float or ndarray
        Slip ratio acting in the law [-].
    gamma : float or ndarray
        Inclination of both wheels [rad] (ISO-W).
    vx : float or ndarray
        Wheel-centre forward velocity (SAE wheel axes) [m/s].
    force_demand : float or ndarray
        Force mode's longitudinal force demand of the axle [N].
    friction : float or ndarray
        The road's friction ratio under the axle [-].

    Returns
    -------
    float or ndarray
        M_z of the axle [N*m], SAE.
    """
    kappa_iso, alpha_iso = planar_tire_slips_sae_to_iso_w(kappa, alpha)
    direction = xp.where(vx < 0.0, -1.0, 1.0)
    ply_steer = (k.front_ply_steer if axle == 0 else k.rear_ply_steer) > 0.5
    if k.lateral_load_transfer:
        right_mirrored = (k.front_mirror_right if axle == 0 else k.rear_mirror_right) > 0.5
        mirror_left = ply_steer and not right_mirrored
    else:  # the lumped axle: the law's tire and, with ply steer, its mirror image
        right_mirrored, mirror_left = ply_steer, False
    left_load, right_load = 0.5 * fz + shift, 0.5 * fz - shift
    left, right = wheel_pair_aligning_moments(xp, tires[axle], left_load, right_load, kappa_iso, alpha_iso, gamma,
                                              direction * xp.maximum(xp.abs(vx), 1e-3), mirror_left, right_mirrored,
                                              friction, k.friction_scaled)
    if not k.wheel_spin:
        left = demanded_forces(xp, k, left_load, 0.0 * left, left, 0.5 * force_demand, friction)[1]
        right = demanded_forces(xp, k, right_load, 0.0 * right, right, 0.5 * force_demand, friction)[1]
    return -(left + right)


def evaluate(xp, tires, k, states, inputs, friction):
    """Forces, loads and accelerations at ``states``, ``inputs``.

    The axles run at the steer inputs plus roll steer eps_i phi and compliance steer
    delta_c,i = c_i F_y,i + e_i M_z,i (the axle's SAE force and its law's aligning moment). With
    tire lag the forces follow from the deflection states, not from the steer (above the low-speed
    damping's speed and below the sliding limit), so delta_c,i is explicit: the law once at the
    steer without compliance for F_y,i, M_z,i, then every force at the full steer (the longitudinal
    load transfer, which the steer's projection of the forces moves, is then that of the steer
    without compliance in delta_c: a relative error of order 1e-8 at 0.4 g). Without tire lag the
    slip needs the steer: delta_c = g(delta_c) = c F(alpha_0 - delta_c) + e M(alpha_0 - delta_c)
    is solved by a Newton step from 0 with the slope s_i = (c_i - e_i t_i) C_i of
    :class:`Constants` (the law's at the static load), delta_1 = g(0) / (1 - s_i), then a secant
    step through g(0) and g(delta_1) (:func:`vehdyn.components.tire_forces.secant_compliance`): three evaluations of the law per
    axle; exact for g linear in delta_c, else in error by the second order of the step.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    tires : tuple
        The (front, rear) tire laws (``TireModel`` on numpy, ``TireLaw`` compiled).
    k : Constants
        The model's constants.
    states : tuple
        In the order of :data:`STATES` [SI units].
    inputs : tuple
        In the order of :data:`INPUTS` [SI units].
    friction : tuple
        The road's friction ratio under the (front, rear) axle [-] (read where ``k.friction_scaled``).

    Returns
    -------
    Evaluation
    """
    (lon, lat, yaw_rate, _x, _y, _yaw, front_wheel_speed, rear_wheel_speed, front_lateral_deflection,
     rear_lateral_deflection, front_longitudinal_deflection, rear_longitudinal_deflection, roll_angle,
     roll_rate) = states
    (front_steer, rear_steer, front_force, rear_force, _fd, _rd, _fb, _rb, external_force, external_moment,
     wind) = inputs
    front_lift, rear_lift = k.front_lift_factor * lon * lon, k.rear_lift_factor * lon * lon
    # the peak-force slips scale with the road's friction (similarity)
    peaks = (k.front_peak_slip_ratio, k.front_peak_tan_slip_angle, k.rear_peak_slip_ratio, k.rear_peak_tan_slip_angle)
    if k.friction_scaled:
        peaks = (peaks[0] * friction[0], peaks[1] * friction[0], peaks[2] * friction[1], peaks[3] * friction[1])
    front_gamma = rear_gamma = 0.0
    if k.roll_terms > 0.5:  # roll steer and camber: the roll state, or the steady roll at a_y = u r
        roll = roll_angle + k.quasi_static_roll * lon * yaw_rate
        front_steer = front_steer + k.front_roll_steer * roll
        rear_steer = rear_steer + k.rear_roll_steer * roll
        front_gamma, rear_gamma = k.front_camber_per_roll * roll, k.rear_camber_per_roll * roll

    def axles(front_steer, rear_steer):
        """Every force of the two axles at these road-wheel steer angles."""
        cf, sf = xp.cos(front_steer), xp.sin(front_steer)
        cr, sr = xp.cos(rear_steer), xp.sin(rear_steer)
        front_body_lateral, rear_body_lateral = lat + k.a * yaw_rate, lat - k.b * yaw_rate
        vxf, vyf = lon * cf + front_body_lateral * sf, -lon * sf + front_body_lateral * cf
        vxr, vyr = lon * cr + rear_body_lateral * sr, -lon * sr + rear_body_lateral * cr
        rates = deflection_rates(xp, k, vxf, vyf, vxr, vyr, states, peaks)

        def front_axle(fz):
            return axle_loads(xp, tires, 0, k, fz, vxf, vyf, front_wheel_speed, front_lateral_deflection,
                              front_longitudinal_deflection, rates[0], rates[2], k.front_lateral_relaxation_length,
                              k.front_longitudinal_relaxation_length, peaks[0], peaks[1], front_force, friction[0])

        def rear_axle(fz):
            return axle_loads(xp, tires, 1, k, fz, vxr, vyr, rear_wheel_speed, rear_lateral_deflection,
                              rear_longitudinal_deflection, rates[1], rates[3], k.rear_lateral_relaxation_length,
                              k.rear_longitudinal_relaxation_length, peaks[2], peaks[3], rear_force, friction[1])

        # with lateral load transfer the left wheel carries fz / 2 + shift, the right fz / 2 - shift
        # (with the difference of the wheels' longitudinal forces, zero without the transfer)
        def front(fz, shift):
            if k.lateral_load_transfer:
                return wheel_pair_loads(xp, tires, 0, k, fz, shift, vxf, vyf, front_wheel_speed,
                                        front_lateral_deflection, front_longitudinal_deflection, rates[0], rates[2],
                                        k.front_lateral_relaxation_length, k.front_longitudinal_relaxation_length,
                                        peaks[0], peaks[1], front_force, friction[0], front_gamma)
            return front_axle(fz) + (0.0 * fz,)

        def rear(fz, shift):
            if k.lateral_load_transfer:
                return wheel_pair_loads(xp, tires, 1, k, fz, shift, vxr, vyr, rear_wheel_speed,
                                        rear_lateral_deflection, rear_longitudinal_deflection, rates[1], rates[3],
                                        k.rear_lateral_relaxation_length, k.rear_longitudinal_relaxation_length,
                                        peaks[2], peaks[3], rear_force, friction[1], rear_gamma)
            return rear_axle(fz) + (0.0 * fz,)

        def transfer(f, r, fz_f, fz_r):
            return lateral_load_transfer(xp, k, f[0] * sf + f[1] * cf, r[0] * sr + r[1] * cr, fz_f, fz_r, roll_angle,
                                         roll_rate)

        # quasi-static load transfer: the forces depend on the loads and the loads on the forces.
        # Longitudinal: with force inputs the dependence is explicit, with wheel spin two fixed-point
        # passes from the static loads: the iteration contracts by about mu h / L (~0.2), so the load
        # transfer is within (mu h / L)^2 ~ 4 % of its converged value. Lateral: from the transfer of
        # the steady turn at the present yaw rate (side forces m u r b / L and m u r a / L: exact in a
        # steady turn), with wheel spin updated along the two longitudinal passes; in force mode the
        # forces take one evaluation of the law at each wheel's load.
        shift_f = shift_r = 0.0 * lon
        if k.lateral_load_transfer:
            turn = k.mass * lon * yaw_rate / (k.a + k.b)
            fz_f, fz_r = normal_loads(xp, k, front_force * cf + rear_force * cr, front_lift, rear_lift)
            shift_f, shift_r = lateral_load_transfer(xp, k, turn * k.b, turn * k.a, fz_f, fz_r, roll_angle,
                                                     roll_rate)
        if k.wheel_spin:
            weight, wheelbase = k.mass * k.gravity, k.a + k.b
            fz_f, fz_r = weight * k.b / wheelbase - front_lift, weight * k.a / wheelbase - rear_lift
            for _ in range(2):
                f, r = front(fz_f, shift_f), rear(fz_r, shift_r)
                fz_f, fz_r = normal_loads(xp, k, f[0] * cf - f[1] * sf + r[0] * cr - r[1] * sr, front_lift,
                                          rear_lift)
                if k.lateral_load_transfer:
                    shift_f, shift_r = transfer(f, r, fz_f, fz_r)
        else:
            fz_f, fz_r = normal_loads(xp, k, front_force * cf + rear_force * cr, front_lift, rear_lift)
        f, r = front(fz_f, shift_f), rear(fz_r, shift_r)
        if k.lateral_load_transfer:  # the transfer of the final forces (shown in the outputs)
            shift_f, shift_r = transfer(f, r, fz_f, fz_r)
        return cf, sf, cr, sr, vxf, vyf, vxr, vyr, rates, f, r, fz_f, fz_r, shift_f, shift_r

    def compliance(a):
        """c_i F_y,i + e_i M_z,i of each axle from the forces ``a`` of :func:`axles`."""
        f, r = a[9], a[10]
        front, rear = k.front_lateral_force_compliance * f[1], k.rear_lateral_force_compliance * r[1]
        if k.front_aligning_moment_compliance != 0.0:
            front = front + k.front_aligning_moment_compliance * axle_aligning_moment(
                xp, tires, 0, k, a[11], a[13], f[2], f[3], front_gamma, a[4], front_force, friction[0])
        if k.rear_aligning_moment_compliance != 0.0:
            rear = rear + k.rear_aligning_moment_compliance * axle_aligning_moment(
                xp, tires, 1, k, a[12], a[14], r[2], r[3], rear_gamma, a[6], rear_force, friction[1])
        return front, rear

    # the passes of the compliance steer (docstring): the forces at the steer without compliance steer;
    # with it, (without tire lag) at the Newton step, then at the final steer. numba inlines a closure
    # at every call site: two sites of axles, the second in a loop (three sites tripled the compiled
    # model: cold compile 33 -> 52 s; one site in a loop of all passes compiled in 33 s but cost the
    # shipped single track's warm call 10 %, the first pass no longer straight-line code)
    a = axles(front_steer, rear_steer)
    front_compliance = rear_compliance = g_f = g_r = 0.0 * lon
    if k.compliance_steer > 0.5:
        for n in range(1 if k.tire_lag else 2):
            h_f, h_r = compliance(a)
            if n > 0:  # the secant step through g(0) and g(delta_1)
                front_compliance = secant_compliance(xp, g_f, h_f, front_compliance, k.front_compliance_slope)
                rear_compliance = secant_compliance(xp, g_r, h_r, rear_compliance, k.rear_compliance_slope)
            elif k.tire_lag:  # explicit: the forces follow the deflections, not the steer
                front_compliance, rear_compliance = h_f, h_r
            else:  # a Newton step from 0 with the static slope
                g_f, g_r = h_f, h_r
                front_compliance = g_f / (1.0 - k.front_compliance_slope)
                rear_compliance = g_r / (1.0 - k.rear_compliance_slope)
            a = axles(front_steer + front_compliance, rear_steer + rear_compliance)
        front_steer, rear_steer = front_steer + front_compliance, rear_steer + rear_compliance
    cf, sf, cr, sr, vxf, vyf, vxr, vyr, rates, f, r, fz_f, fz_r, shift_f, shift_r = a
    fx_body = f[0] * cf - f[1] * sf + r[0] * cr - r[1] * sr
    front_lateral, rear_lateral = f[0] * sf + f[1] * cf, r[0] * sr + r[1] * cr
    wind_force = aero_side_force(xp, k.wind_side_force_factor, lon, wind)  # crosswind, at the centre of pressure
    external_force = external_force + wind_force
    moment = external_moment + k.centre_of_pressure * wind_force + k.a * front_lateral - k.b * rear_lateral
    if k.lateral_load_transfer:  # the couple of unequal left and right longitudinal forces (SAE: left at -t/2)
        moment = moment + 0.5 * (k.front_track * f[5] * cf + k.rear_track * r[5] * cr)
    drag = k.drag_factor * lon * xp.abs(lon)
    lateral_acceleration = (front_lateral + rear_lateral + external_force) / k.mass
    return Evaluation((fx_body - drag) / k.mass, lateral_acceleration,
                      moment / k.yaw_inertia, f[0], f[1], f[2], f[3], r[0], r[1], r[2], r[3], fz_f, fz_r,
                      vxf, vyf, vxr, vyr, rates[0], rates[1], rates[2], rates[3], f[4], r[4], shift_f, shift_r,
                      roll_acceleration(xp, k, lateral_acceleration, roll_angle, roll_rate), front_steer, rear_steer,
                      front_compliance, rear_compliance)


def deflection_rates(xp, k, front_vx, front_vy, rear_vx, rear_vy, states, peaks):
    """d/dt of the tire deflections from the wheel-centre velocities
    (:func:`vehdyn.components.tire_slip.deflection_rate`).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : Constants
        The model's constants.
    front_vx, front_vy, rear_vx, rear_vy : float or ndarray
        Wheel-centre velocities in wheel axes (SAE) [m/s].
    states : tuple
        In the order of :data:`STATES`.
    peaks : tuple
        Peak-force slips on this road (front ratio, front tan angle, rear ratio, rear tan angle) [-].

    Returns
    -------
    tuple
        (front lateral, rear lateral, front longitudinal, rear longitudinal) [m/s]; 0.0 for those the
        model lacks.
    """
    zero = 0.0 * front_vx
    if not k.tire_lag:
        return zero, zero, zero, zero
    (_u, _v, _r, _x, _y, _yaw, front_wheel_speed, rear_wheel_speed, front_lateral_deflection,
     rear_lateral_deflection, front_longitudinal_deflection, rear_longitudinal_deflection, _phi, _p) = states
    front_lateral = deflection_rate(xp, front_vy, front_vx, front_lateral_deflection,
                                    k.front_lateral_relaxation_length, peaks[1])
    rear_lateral = deflection_rate(xp, rear_vy, rear_vx, rear_lateral_deflection, k.rear_lateral_relaxation_length,
                                   peaks[3])
    front_longitudinal = rear_longitudinal = zero
    if k.wheel_spin:
        front_longitudinal = deflection_rate(xp, -(front_vx - front_wheel_speed * k.rolling_radius), front_vx,
                                             front_longitudinal_deflection, k.front_longitudinal_relaxation_length,
                                             peaks[0])
        rear_longitudinal = deflection_rate(xp, -(rear_vx - rear_wheel_speed * k.rolling_radius), rear_vx,
                                            rear_longitudinal_deflection, k.rear_longitudinal_relaxation_length,
                                            peaks[2])
    return front_lateral, rear_lateral, front_longitudinal, rear_longitudinal


def derivatives(xp, k, e, states, inputs):
    """d/dt of every entry of :data:`STATES` from an :class:`Evaluation`.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : Constants
        The model's constants.
    e : Evaluation
        :func:`evaluate` at ``states``, ``inputs``.
    states : tuple
        In the order of :data:`STATES`.
    inputs : tuple
        In the order of :data:`INPUTS`.

    Returns
    -------
    tuple
        14 rates [SI units per second]; 0.0 for a state the model lacks.
    """
    (lon, lat, yaw_rate, _x, _y, yaw, front_wheel_speed, rear_wheel_speed, _fld, _rld, _fxd, _rxd, _phi,
     roll_rate) = states
    (_fs, _rs, _ff, _rf, front_drive, rear_drive, front_brake, rear_brake, _fe, _me, _w) = inputs
    zero = 0.0 * lon
    position = position_rates(xp, lon, lat, yaw)
    d_front_wheel = d_rear_wheel = zero
    if k.wheel_spin:
        inertia = 2.0 * k.wheel_spin_inertia
        d_front_wheel = (net_wheel_torque(xp, k, front_wheel_speed, front_drive, front_brake,
                                          e.front_longitudinal_force) + e.front_rolling_moment) / inertia
        d_rear_wheel = (net_wheel_torque(xp, k, rear_wheel_speed, rear_drive, rear_brake,
                                         e.rear_longitudinal_force) + e.rear_rolling_moment) / inertia
    # with roll, v is the lateral velocity of the non-rolling frame: m (dv/dt + u r) + m h_1 dp/dt = F_y
    return (e.longitudinal_acceleration + lat * yaw_rate,
            e.lateral_acceleration - k.roll_arm * e.roll_acceleration - lon * yaw_rate,
            e.yaw_acceleration, position[0], position[1], yaw_rate, d_front_wheel,
            d_rear_wheel, e.front_lateral_deflection_rate, e.rear_lateral_deflection_rate,
            e.front_longitudinal_deflection_rate, e.rear_longitudinal_deflection_rate, roll_rate, e.roll_acceleration)


def outputs(xp, states, e):
    """The outputs of :class:`~vehdyn.handling.SingleTrack`, in the order of its ``outputs``.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    states : tuple
        In the order of :data:`STATES`.
    e : Evaluation
        :func:`evaluate` at the states.

    Returns
    -------
    tuple
        The 21 outputs every SingleTrack has [SI units of its ``outputs``].
    """
    lon, lat, yaw_rate = states[0], states[1], states[2]
    speed_squared = lon * lon + lat * lat
    return (e.lateral_acceleration, xp.atan2(lat, xp.abs(lon)), yaw_rate, lat, e.front_slip_angle,
            e.rear_slip_angle, e.lateral_acceleration / xp.maximum(speed_squared, 0.25), e.front_lateral_force,
            e.rear_lateral_force, e.longitudinal_acceleration, lon, xp.sqrt(speed_squared),
            e.front_longitudinal_force, e.rear_longitudinal_force, e.front_normal_load, e.rear_normal_load,
            e.front_slip_ratio, e.rear_slip_ratio, states[3], states[4], states[5])


def wheel_load_outputs(e):
    """The wheel loads of a model with lateral load transfer (its outputs after those of :func:`outputs`).

    Parameters
    ----------
    e : Evaluation
        :func:`evaluate` at the states.

    Returns
    -------
    tuple
        (front left, front right, rear left, rear right) [N].
    """
    return (0.5 * e.front_normal_load + e.front_load_transfer, 0.5 * e.front_normal_load - e.front_load_transfer,
            0.5 * e.rear_normal_load + e.rear_load_transfer, 0.5 * e.rear_normal_load - e.rear_load_transfer)
