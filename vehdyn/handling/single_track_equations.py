"""The equations of :class:`~vehdyn.handling.SingleTrack` as pure functions over an ``xp`` namespace.

One source for both backends (the pattern of :mod:`vehdyn.tire._mf_ops`): the functions below
use only ``xp.cos``, ``xp.sin``, ``xp.atan``, ``xp.sqrt``, ``xp.abs``, ``xp.where``,
``xp.minimum``, ``xp.maximum`` and ``xp.axle_tire_forces`` / ``xp.axle_tire_loads`` (the tire law
of an axle: forces, or forces and rolling-resistance moment), and plain arithmetic, so that they run

* on numpy arrays with a trailing batch axis (:data:`NUMPY`, what ``SingleTrack.rhs`` and
  ``output`` use; the tire law is the model's :class:`~vehdyn.tire.TireModel`), and
* on floats inside numba-compiled code (:mod:`vehdyn.handling._single_track_numba` registers
  these functions with ``register_jitable`` and supplies a compiled ``xp``).

The equations, their signs and references are in the docstring of
:mod:`vehdyn.handling.single_track`. Signals travel in a fixed order (:data:`STATES`,
:data:`INPUTS`); a model's own vectors hold a subset, mapped through an index (-1: absent, 0.0).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from vehdyn.conventions import planar_tire_forces_iso_w_to_sae, planar_tire_slips_sae_to_iso_w
from vehdyn.tire._mf_ops import NumpyOps
from vehdyn.components.aero import aero_side_force

__all__ = ["STATES", "INPUTS", "Constants", "Evaluation", "NUMPY", "named_states", "named_inputs", "evaluate",
           "derivatives", "outputs", "axle_slips", "axle_forces", "axle_loads", "wheel_pair_loads",
           "wheel_load_outputs", "lateral_load_transfer", "roll_acceleration"]

STATES = ("longitudinal_velocity", "lateral_velocity", "yaw_rate", "x", "y", "yaw_angle", "front_wheel_speed",
          "rear_wheel_speed", "front_lateral_deflection", "rear_lateral_deflection", "front_longitudinal_deflection",
          "rear_longitudinal_deflection", "roll_angle", "roll_rate")
"""Every state a SingleTrack can have, in the order of :func:`evaluate` and :func:`derivatives`."""

INPUTS = ("front_steer_angle", "rear_steer_angle", "front_longitudinal_force", "rear_longitudinal_force",
          "front_drive_torque", "rear_drive_torque", "front_brake_torque", "rear_brake_torque",
          "external_lateral_force", "external_yaw_moment", "wind_velocity_lateral")
"""Every input a SingleTrack can have, in the order of :func:`evaluate`."""

REGULARIZATION_SPEED = 0.5  # [m/s], the default v_0 of vehdyn.tire.slip

Constants = namedtuple("Constants", (
    "mass", "yaw_inertia", "a", "b", "cg_height", "rolling_radius", "wheel_spin_inertia", "friction_coefficient",
    "front_lateral_relaxation_length", "rear_lateral_relaxation_length", "front_longitudinal_relaxation_length",
    "rear_longitudinal_relaxation_length", "drag_factor", "front_lift_factor", "rear_lift_factor", "gravity",
    "low_speed_damping_speed", "brake_regularization_speed", "front_peak_slip_ratio", "front_peak_tan_slip_angle",
    "rear_peak_slip_ratio", "rear_peak_tan_slip_angle", "wind_side_force_factor", "centre_of_pressure",
    "front_geometric_transfer", "front_elastic_transfer", "rear_geometric_transfer", "rear_elastic_transfer",
    "front_track", "rear_track", "roll_inertia", "roll_arm", "front_roll_transfer_stiffness",
    "rear_roll_transfer_stiffness", "front_roll_transfer_damping", "rear_roll_transfer_damping",
    "front_mirror_right", "rear_mirror_right", "wheel_spin", "tire_lag", "lateral_load_transfer"))
Constants.__doc__ = """What the equations read: the fields of :class:`SingleTrackParameters` (floats, or arrays
across batch variants on numpy), the model's options and the peak-force slips of the two laws
(the limits of the tire deflections); ``wheel_spin``, ``tire_lag`` and ``lateral_load_transfer`` are
bools, the last three fields (a compiled batch appends them to a variant's floats). The four
``*_transfer`` coefficients [-] give the load moved onto an axle's left wheel by the axles' lateral
forces (:func:`lateral_load_transfer`; zero without lateral load transfer), the tracks [m] the arm
of the yaw couple of unequal left and right longitudinal forces (zero without). ``*_mirror_right``
is 1.0 where the axle's right wheel is the mirror image of the law (a ``.tir`` file with
``TYRESIDE = 'LEFT'``), else 0.0 (the left one, or none: ``SingleTrack._mirrored_wheel``)."""

Evaluation = namedtuple("Evaluation", (
    "longitudinal_acceleration", "lateral_acceleration", "yaw_acceleration", "front_longitudinal_force",
    "front_lateral_force", "front_slip_angle", "front_slip_ratio", "rear_longitudinal_force", "rear_lateral_force",
    "rear_slip_angle", "rear_slip_ratio", "front_normal_load", "rear_normal_load", "front_vx", "front_vy",
    "rear_vx", "rear_vy", "front_lateral_deflection_rate", "rear_lateral_deflection_rate",
    "front_longitudinal_deflection_rate", "rear_longitudinal_deflection_rate", "front_rolling_moment",
    "rear_rolling_moment", "front_load_transfer", "rear_load_transfer", "roll_acceleration"))
Evaluation.__doc__ = """Accelerations of the CG (du/dt - v r, dv/dt + u r [m/s^2], dr/dt [rad/s^2]), axle forces
in SAE wheel axes [N], the slips acting in the laws (SAE slip angle [rad], slip ratio [-]), normal
loads [N], the wheel-centre velocities in wheel axes [m/s], the tire deflection rates [m/s] (0 without
tire lag), the axles' rolling-resistance moments M_y [N*m] (ISO-W: about the axis of forward spin,
negative rolling forwards; 0 in force mode, where no wheel spins) and the lateral load transfer of
each axle [N] (load onto its left wheel, which carries F_z / 2 + dF_z; 0 without lateral load transfer)."""


class NUMPY(NumpyOps):
    """``xp`` of the equations on numpy arrays: the Magic Formula's, with numpy's own sin and cos
    (not the half-angle forms) and the tire law ``tires.axle_law_forces``."""

    cos = staticmethod(np.cos)
    sin = staticmethod(np.sin)
    tanh = staticmethod(np.tanh)
    atan2 = staticmethod(np.arctan2)

    @staticmethod
    def axle_tire_forces(tires, axle, fz, kappa, alpha, vx):
        """ISO-W axle forces (fx, fy) [N] of ``axle`` (0 front, 1 rear) from ISO-W slips."""
        return tires.axle_law_forces(axle, fz, kappa, alpha, vx)

    @staticmethod
    def axle_tire_loads(tires, axle, fz, kappa, alpha, vx):
        """ISO-W axle forces and rolling-resistance moment (fx, fy, my) [N, N, N*m] of ``axle``."""
        return tires.axle_law_loads(axle, fz, kappa, alpha, vx)

    @staticmethod
    def wheel_pair_tire_loads(tires, axle, left_load, right_load, kappa, alpha, vx):
        """ISO-W (fx, fy, my) of the left, then the right tire of ``axle`` at their own loads [N]."""
        return tires.wheel_pair_law_loads(axle, left_load, right_load, kappa, alpha, vx)


def _at(values, i):
    """values[i], or zero (of values[0]'s shape) for i = -1: a signal the model lacks."""
    return values[i] if i >= 0 else 0.0 * values[0]


def named_states(x, index):
    """The states of a model's vector ``x`` in the order of :data:`STATES` (``index``: position of
    each in ``x``, -1 where the model lacks it)."""
    return (_at(x, index[0]), _at(x, index[1]), _at(x, index[2]), _at(x, index[3]), _at(x, index[4]),
            _at(x, index[5]), _at(x, index[6]), _at(x, index[7]), _at(x, index[8]), _at(x, index[9]),
            _at(x, index[10]), _at(x, index[11]), _at(x, index[12]), _at(x, index[13]))


def named_inputs(u, index):
    """The inputs of a model's vector ``u`` in the order of :data:`INPUTS` (see :func:`named_states`)."""
    return (_at(u, index[0]), _at(u, index[1]), _at(u, index[2]), _at(u, index[3]), _at(u, index[4]),
            _at(u, index[5]), _at(u, index[6]), _at(u, index[7]), _at(u, index[8]), _at(u, index[9]), _at(u, index[10]))


def regularized_speed(xp, vx):
    """|vx| above v_0, (vx^2 + v_0^2) / (2 v_0) below (:func:`vehdyn.tire.regularized_speed`)."""
    v0 = REGULARIZATION_SPEED
    return xp.where(xp.abs(vx) >= v0, xp.abs(vx), (vx * vx + v0 * v0) / (2.0 * v0))


def low_speed_blend(xp, speed, damping_speed):
    """w = (1 + cos(pi |V_x| / v_l)) / 2 below v_l, 0 above (Pacejka 2012, eq. 8.126)."""
    return 0.5 * (1.0 + xp.cos(math.pi * xp.minimum(speed / damping_speed, 1.0)))


def sliding_slip(xp, transient, kinematic, peak):
    """The slip that makes the force: the transient (deflection) slip, or the kinematic slip when
    the deflection sits at its peak-force limit and the kinematic slip lies beyond it (sliding)."""
    at_limit = xp.where(xp.abs(transient) >= 0.999 * peak, 1.0, 0.0)
    beyond = xp.where(transient * kinematic > 0, 1.0, 0.0) * xp.where(xp.abs(kinematic) > xp.abs(transient), 1.0, 0.0)
    return xp.where(at_limit * beyond > 0, kinematic, transient)


def limit_deflection_rate(xp, rate, slip, peak):
    """Deflection rate with its outward part faded out over the last 5 % before the peak slip."""
    room = xp.minimum(xp.maximum((peak - xp.abs(slip)) / (0.05 * peak), 0.0), 1.0)
    return xp.where(rate * slip > 0, rate * room, rate)


def axle_slips(xp, k, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection, lateral_rate,
               longitudinal_rate, lateral_length, longitudinal_length, peak_slip_ratio, peak_tan_slip_angle):
    """The slips acting in an axle's law: (alpha SAE [rad], kappa [-], sign of vx, |vx| [m/s]).

    With tire lag the low-speed damping acts on the deflection rates ``lateral_rate``,
    ``longitudinal_rate`` [m/s] (:func:`deflection_rates`): zero in the steady state."""
    speed = xp.abs(vx)
    direction = xp.where(vx < 0.0, -1.0, 1.0)  # sign(vx) with sign(0) = +1
    blend = low_speed_blend(xp, speed, k.low_speed_damping_speed)
    if k.tire_lag:
        tan_alpha = sliding_slip(xp, lateral_deflection / lateral_length, vy / regularized_speed(xp, vx),
                                 peak_tan_slip_angle)
        tan_alpha = tan_alpha + blend * lateral_rate / k.low_speed_damping_speed
    else:
        tan_alpha = vy / regularized_speed(xp, vx)
    alpha = xp.atan(tan_alpha)
    if k.wheel_spin:
        vsx = vx - wheel_speed * k.rolling_radius
        if k.tire_lag:
            slip = sliding_slip(xp, longitudinal_deflection / longitudinal_length, -vsx / regularized_speed(xp, vx),
                                peak_slip_ratio)
            slip = slip + blend * longitudinal_rate / k.low_speed_damping_speed
            kappa = slip * direction
        else:
            kappa = -vsx / (direction * regularized_speed(xp, vx))
    else:
        kappa = 0.0 * alpha
    return alpha, kappa, direction, speed


def demanded_forces(xp, k, fz, fx, fy, force_demand):
    """Force mode (no wheel spin): F_x the demand clipped at mu F_z, F_y of the law reduced by the
    friction ellipse."""
    limit = k.friction_coefficient * xp.maximum(fz, 0.0)
    fx = xp.minimum(xp.maximum(force_demand, -limit), limit)
    safe = xp.where(limit > 0, limit, 1.0)
    return fx, fy * xp.sqrt(xp.maximum(1.0 - (fx / safe) ** 2, 0.0))


def axle_forces(xp, tires, axle, k, fz, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection,
                lateral_rate, longitudinal_rate, lateral_length, longitudinal_length, peak_slip_ratio,
                peak_tan_slip_angle, force_demand):
    """Axle forces (fx, fy) in SAE wheel axes [N] and the slips (alpha SAE [rad], kappa [-]) at load ``fz``
    (slips: :func:`axle_slips`; the law: ``xp.axle_tire_forces``)."""
    alpha, kappa, direction, speed = axle_slips(
        xp, k, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection, lateral_rate, longitudinal_rate,
        lateral_length, longitudinal_length, peak_slip_ratio, peak_tan_slip_angle)
    kappa_iso, alpha_iso = planar_tire_slips_sae_to_iso_w(kappa, alpha)
    fx_iso, fy_iso = xp.axle_tire_forces(tires, axle, fz, kappa_iso, alpha_iso, direction * xp.maximum(speed, 1e-3))
    fx, fy = planar_tire_forces_iso_w_to_sae(fx_iso, fy_iso)
    if not k.wheel_spin:
        fx, fy = demanded_forces(xp, k, fz, fx, fy, force_demand)
    return fx, fy, alpha, kappa


def axle_loads(xp, tires, axle, k, fz, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection,
               lateral_rate, longitudinal_rate, lateral_length, longitudinal_length, peak_slip_ratio,
               peak_tan_slip_angle, force_demand):
    """:func:`axle_forces` and the axle's rolling-resistance moment M_y [N*m] (ISO-W, about the axis
    of forward spin; 0 in force mode), from one evaluation of the law (``xp.axle_tire_loads``)."""
    alpha, kappa, direction, speed = axle_slips(
        xp, k, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection, lateral_rate, longitudinal_rate,
        lateral_length, longitudinal_length, peak_slip_ratio, peak_tan_slip_angle)
    kappa_iso, alpha_iso = planar_tire_slips_sae_to_iso_w(kappa, alpha)
    fx_iso, fy_iso, my = xp.axle_tire_loads(tires, axle, fz, kappa_iso, alpha_iso,
                                            direction * xp.maximum(speed, 1e-3))
    fx, fy = planar_tire_forces_iso_w_to_sae(fx_iso, fy_iso)
    if not k.wheel_spin:
        fx, fy = demanded_forces(xp, k, fz, fx, fy, force_demand)
        my = 0.0 * my
    return fx, fy, alpha, kappa, my * rolling_resistance_fade(xp, k, wheel_speed)


def rolling_resistance_fade(xp, k, wheel_speed):
    """tanh(|omega| / omega_b) [-]: the rolling resistance opposes rolling and fades to 0 at
    standstill (omega_b the brake regularization speed [rad/s]; exactly 1 in floating point above
    about 19 omega_b), else a law's M_y at zero speed would spin a wheel at rest backwards."""
    return xp.tanh(xp.abs(wheel_speed) / k.brake_regularization_speed)


def normal_loads(xp, k, x_force, front_lift, rear_lift):
    """Axle loads (front, rear) [N] with quasi-static load transfer by the body-x tire force
    ``x_force`` [N]; an axle that would lift off carries 0 and the other the whole weight."""
    wheelbase = k.a + k.b
    weight = k.mass * k.gravity
    front = weight * k.b / wheelbase - k.cg_height * x_force / wheelbase - front_lift
    total = weight - front_lift - rear_lift
    front = xp.minimum(xp.maximum(front, 0.0), xp.maximum(total, 0.0))
    return front, xp.maximum(total - front, 0.0)


def lateral_load_transfer(xp, k, front_lateral, rear_lateral, front_load, rear_load, roll_angle, roll_rate):
    """Lateral load transfer (front, rear) [N]: the load moved onto each axle's left wheel.

    ``front_lateral``, ``rear_lateral`` are the axles' lateral forces in body axes [N] (SAE y,
    positive turning right, so the load moves onto the left, outer wheels); ``roll_angle`` phi
    [rad] and ``roll_rate`` p [rad/s] the body's roll (SAE: positive right side down)::

        dF_z,i = (z_i / t_i) F_y,i + h_1 K_i / ((K_f + K_r - m g h_1) t_i) (F_y,f + F_y,r)
                 - (K_i phi + C_i p) / t_i

    (the ``*_geometric_transfer``, ``*_elastic_transfer``, ``*_roll_transfer_stiffness`` and
    ``*_roll_transfer_damping`` coefficients of :class:`Constants`): without the roll degree of
    freedom the last term is absent (the quasi-static elastic part), with it the elastic part is
    the suspension's roll moment; held within +-F_z,i / 2 (an inner wheel that would lift carries 0).
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
    """Roll acceleration of the body [rad/s^2] (SAE: positive right side down)::

        J dp/dt = -m h_1 a_y - (K_f + K_r - m g h_1) phi - (C_f + C_r) p

    with a_y the lateral acceleration of the CG [m/s^2] (all lateral forces over the mass), J the
    effective roll inertia, h_1 the CG height above the roll axis; K_i = t_i (K_i / t_i) and
    C_i = t_i (C_i / t_i) from :class:`Constants` (0 without roll: then h_1 = 0 and the result is 0).
    """
    stiffness = k.front_track * k.front_roll_transfer_stiffness + k.rear_track * k.rear_roll_transfer_stiffness
    damping = k.front_track * k.front_roll_transfer_damping + k.rear_track * k.rear_roll_transfer_damping
    moment = k.roll_arm * k.mass
    return (-moment * lateral_acceleration - (stiffness - moment * k.gravity) * roll_angle
            - damping * roll_rate) / k.roll_inertia


def wheel_pair_loads(xp, tires, axle, k, fz, shift, vx, vy, wheel_speed, lateral_deflection,
                     longitudinal_deflection, lateral_rate, longitudinal_rate, lateral_length, longitudinal_length,
                     peak_slip_ratio, peak_tan_slip_angle, force_demand):
    """:func:`axle_loads` of an axle whose left wheel carries F_z / 2 + ``shift`` and right wheel
    F_z / 2 - ``shift`` [N], and the difference F_x,left - F_x,right [N] of the wheels' longitudinal
    forces: each wheel's law at its own load (``xp.wheel_pair_tire_loads``). In force mode each
    wheel takes half the demand (an open differential, equal brake pressures), clipped at mu times
    its load, with its own friction ellipse, and its rolling resistance M_y / R_e shifts the force
    between the wheels (the demand stays the axle's net force)."""
    alpha, kappa, direction, speed = axle_slips(
        xp, k, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection, lateral_rate, longitudinal_rate,
        lateral_length, longitudinal_length, peak_slip_ratio, peak_tan_slip_angle)
    kappa_iso, alpha_iso = planar_tire_slips_sae_to_iso_w(kappa, alpha)
    left_load, right_load = 0.5 * fz + shift, 0.5 * fz - shift
    # the law's wheel pair mirrors its first wheel: the right one where the law is a left tire (a
    # float per model or variant; both wheels of the axle run at the same slips, so exchanging the
    # loads in and the wheels out is the pair with the right wheel mirrored)
    right_mirrored = (k.front_mirror_right if axle == 0 else k.rear_mirror_right) > 0.5
    first_load, second_load = left_load, right_load
    if right_mirrored:
        first_load, second_load = right_load, left_load
    w = xp.wheel_pair_tire_loads(tires, axle, first_load, second_load, kappa_iso, alpha_iso,
                                 direction * xp.maximum(speed, 1e-3))
    if right_mirrored:
        w = (w[3], w[4], w[5], w[0], w[1], w[2])
    fx_left, fy_left = planar_tire_forces_iso_w_to_sae(w[0], w[1])
    fx_right, fy_right = planar_tire_forces_iso_w_to_sae(w[3], w[4])
    my = w[2] + w[5]
    if not k.wheel_spin:
        fx_left, fy_left = demanded_forces(xp, k, left_load, fx_left, fy_left, 0.5 * force_demand)
        fx_right, fy_right = demanded_forces(xp, k, right_load, fx_right, fy_right, 0.5 * force_demand)
        resistance = (w[2] - w[5]) / k.rolling_radius  # ISO-W M_y < 0 rolling forwards: retarding
        # the rolling resistance fades at standstill as in axle_loads
        return (fx_left + fx_right, fy_left + fy_right, alpha, kappa, 0.0 * my,
                fx_left - fx_right + resistance * xp.abs(low_speed_blend(xp, speed, k.low_speed_damping_speed) - 1.0))
    return (fx_left + fx_right, fy_left + fy_right, alpha, kappa, my * rolling_resistance_fade(xp, k, wheel_speed),
            fx_left - fx_right)


def evaluate(xp, tires, k, states, inputs):
    """Forces, loads and accelerations at ``states``, ``inputs`` (tuples in the order of
    :data:`STATES`, :data:`INPUTS`): an :class:`Evaluation`."""
    (lon, lat, yaw_rate, _x, _y, _yaw, front_wheel_speed, rear_wheel_speed, front_lateral_deflection,
     rear_lateral_deflection, front_longitudinal_deflection, rear_longitudinal_deflection, roll_angle,
     roll_rate) = states
    (front_steer, rear_steer, front_force, rear_force, _fd, _rd, _fb, _rb, external_force, external_moment,
     wind) = inputs
    front_lift, rear_lift = k.front_lift_factor * lon * lon, k.rear_lift_factor * lon * lon
    cf, sf = xp.cos(front_steer), xp.sin(front_steer)
    cr, sr = xp.cos(rear_steer), xp.sin(rear_steer)
    front_body_lateral, rear_body_lateral = lat + k.a * yaw_rate, lat - k.b * yaw_rate
    vxf, vyf = lon * cf + front_body_lateral * sf, -lon * sf + front_body_lateral * cf
    vxr, vyr = lon * cr + rear_body_lateral * sr, -lon * sr + rear_body_lateral * cr
    rates = deflection_rates(xp, k, vxf, vyf, vxr, vyr, states)

    def front_axle(fz):
        return axle_loads(xp, tires, 0, k, fz, vxf, vyf, front_wheel_speed, front_lateral_deflection,
                          front_longitudinal_deflection, rates[0], rates[2], k.front_lateral_relaxation_length,
                          k.front_longitudinal_relaxation_length, k.front_peak_slip_ratio,
                          k.front_peak_tan_slip_angle, front_force)

    def rear_axle(fz):
        return axle_loads(xp, tires, 1, k, fz, vxr, vyr, rear_wheel_speed, rear_lateral_deflection,
                          rear_longitudinal_deflection, rates[1], rates[3], k.rear_lateral_relaxation_length,
                          k.rear_longitudinal_relaxation_length, k.rear_peak_slip_ratio,
                          k.rear_peak_tan_slip_angle, rear_force)

    # with lateral load transfer the left wheel carries fz / 2 + shift, the right fz / 2 - shift
    # (with the difference of the wheels' longitudinal forces, zero without the transfer)
    def front(fz, shift):
        if k.lateral_load_transfer:
            return wheel_pair_loads(xp, tires, 0, k, fz, shift, vxf, vyf, front_wheel_speed, front_lateral_deflection,
                                    front_longitudinal_deflection, rates[0], rates[2],
                                    k.front_lateral_relaxation_length, k.front_longitudinal_relaxation_length,
                                    k.front_peak_slip_ratio, k.front_peak_tan_slip_angle, front_force)
        return front_axle(fz) + (0.0 * fz,)

    def rear(fz, shift):
        if k.lateral_load_transfer:
            return wheel_pair_loads(xp, tires, 1, k, fz, shift, vxr, vyr, rear_wheel_speed, rear_lateral_deflection,
                                    rear_longitudinal_deflection, rates[1], rates[3],
                                    k.rear_lateral_relaxation_length, k.rear_longitudinal_relaxation_length,
                                    k.rear_peak_slip_ratio, k.rear_peak_tan_slip_angle, rear_force)
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
        shift_f, shift_r = lateral_load_transfer(xp, k, turn * k.b, turn * k.a, fz_f, fz_r, roll_angle, roll_rate)
    if k.wheel_spin:
        weight, wheelbase = k.mass * k.gravity, k.a + k.b
        fz_f, fz_r = weight * k.b / wheelbase - front_lift, weight * k.a / wheelbase - rear_lift
        for _ in range(2):
            f, r = front(fz_f, shift_f), rear(fz_r, shift_r)
            fz_f, fz_r = normal_loads(xp, k, f[0] * cf - f[1] * sf + r[0] * cr - r[1] * sr, front_lift, rear_lift)
            if k.lateral_load_transfer:
                shift_f, shift_r = transfer(f, r, fz_f, fz_r)
    else:
        fz_f, fz_r = normal_loads(xp, k, front_force * cf + rear_force * cr, front_lift, rear_lift)
    f, r = front(fz_f, shift_f), rear(fz_r, shift_r)
    if k.lateral_load_transfer:  # the transfer of the final forces (shown in the outputs)
        shift_f, shift_r = transfer(f, r, fz_f, fz_r)
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
                      roll_acceleration(xp, k, lateral_acceleration, roll_angle, roll_rate))


def deflection_rates(xp, k, front_vx, front_vy, rear_vx, rear_vy, states):
    """d/dt of the tire deflections (front lateral, rear lateral, front longitudinal, rear longitudinal)
    [m/s] from the wheel-centre velocities; 0.0 for those the model lacks."""
    zero = 0.0 * front_vx
    if not k.tire_lag:
        return zero, zero, zero, zero
    (_u, _v, _r, _x, _y, _yaw, front_wheel_speed, rear_wheel_speed, front_lateral_deflection,
     rear_lateral_deflection, front_longitudinal_deflection, rear_longitudinal_deflection, _phi, _p) = states
    front_lateral = deflection_rate(xp, front_vy, front_vx, front_lateral_deflection,
                                    k.front_lateral_relaxation_length, k.front_peak_tan_slip_angle)
    rear_lateral = deflection_rate(xp, rear_vy, rear_vx, rear_lateral_deflection, k.rear_lateral_relaxation_length,
                                   k.rear_peak_tan_slip_angle)
    front_longitudinal = rear_longitudinal = zero
    if k.wheel_spin:
        front_longitudinal = deflection_rate(xp, -(front_vx - front_wheel_speed * k.rolling_radius), front_vx,
                                             front_longitudinal_deflection, k.front_longitudinal_relaxation_length,
                                             k.front_peak_slip_ratio)
        rear_longitudinal = deflection_rate(xp, -(rear_vx - rear_wheel_speed * k.rolling_radius), rear_vx,
                                            rear_longitudinal_deflection, k.rear_longitudinal_relaxation_length,
                                            k.rear_peak_slip_ratio)
    return front_lateral, rear_lateral, front_longitudinal, rear_longitudinal


def derivatives(xp, k, e, states, inputs):
    """d/dt of every entry of :data:`STATES` (0.0 for a state the model lacks) from an :class:`Evaluation`."""
    (lon, lat, yaw_rate, _x, _y, yaw, front_wheel_speed, rear_wheel_speed, _fld, _rld, _fxd, _rxd, _phi,
     roll_rate) = states
    (_fs, _rs, _ff, _rf, front_drive, rear_drive, front_brake, rear_brake, _fe, _me, _w) = inputs
    zero = 0.0 * lon
    cpsi, spsi = xp.cos(yaw), xp.sin(yaw)
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
            e.yaw_acceleration, lon * cpsi - lat * spsi, lon * spsi + lat * cpsi, yaw_rate, d_front_wheel,
            d_rear_wheel, e.front_lateral_deflection_rate, e.rear_lateral_deflection_rate,
            e.front_longitudinal_deflection_rate, e.rear_longitudinal_deflection_rate, roll_rate, e.roll_acceleration)


def net_wheel_torque(xp, k, wheel_speed, drive, brake, longitudinal_force):
    """Torque on the two wheels of an axle [N*m]: drive - brake sat(omega / omega_b) - R_e F_x."""
    z = wheel_speed / k.brake_regularization_speed
    return drive - xp.abs(brake) * z / xp.sqrt(1.0 + z * z) - k.rolling_radius * longitudinal_force


def deflection_rate(xp, slip_velocity, vx, deflection, length, peak):
    """d(rho)/dt = V_s - |V_x| rho / sigma, its outward part limited at the peak slip."""
    rate = slip_velocity - xp.abs(vx) * deflection / length
    return limit_deflection_rate(xp, rate, deflection / length, peak)


def outputs(xp, states, e):
    """The outputs of :class:`~vehdyn.handling.SingleTrack` (in the order of its ``outputs``)."""
    lon, lat, yaw_rate = states[0], states[1], states[2]
    speed_squared = lon * lon + lat * lat
    return (e.lateral_acceleration, xp.atan2(lat, xp.abs(lon)), yaw_rate, lat, e.front_slip_angle,
            e.rear_slip_angle, e.lateral_acceleration / xp.maximum(speed_squared, 0.25), e.front_lateral_force,
            e.rear_lateral_force, e.longitudinal_acceleration, lon, xp.sqrt(speed_squared),
            e.front_longitudinal_force, e.rear_longitudinal_force, e.front_normal_load, e.rear_normal_load,
            e.front_slip_ratio, e.rear_slip_ratio, states[3], states[4], states[5])


def wheel_load_outputs(e):
    """The wheel loads (front left, front right, rear left, rear right) [N] of a model with lateral
    load transfer (in the order of its outputs after those of :func:`outputs`)."""
    return (0.5 * e.front_normal_load + e.front_load_transfer, 0.5 * e.front_normal_load - e.front_load_transfer,
            0.5 * e.rear_normal_load + e.rear_load_transfer, 0.5 * e.rear_normal_load - e.rear_load_transfer)
