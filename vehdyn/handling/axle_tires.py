"""Small-slip properties of an axle's tire law at the static load: pneumatic trail and camber stiffness.

The linear models and the understeer budget read them where a vehicle file's field needs a tire
property (the aligning-moment compliance steer needs the trail, the camber gain the camber
stiffness); both at zero slip and half the static axle load (one wheel), by central differences of
the law (Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 1.3 and 4.3: the cornering,
aligning and camber stiffnesses at zero slip).
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["pneumatic_trail", "camber_stiffness", "cornering_stiffness", "compliance_steer_slope", "wheel_loads",
           "wheel_slip_ratio"]

_EPS = 1e-4  # [rad]
_SPEED = 20.0  # [m/s]


def _law(vehicle, axle, tire):
    if axle not in ("front", "rear"):
        raise ParameterError(f"axle must be 'front' or 'rear', got {axle!r}", key="axle", value=axle)
    if tire is not None:
        return tire
    from vehdyn.tire import tire_for_vehicle

    return tire_for_vehicle(vehicle, axle)


def _wheel_load(vehicle, axle):
    return 0.5 * vehicle.static_axle_loads()[0 if axle == "front" else 1]


def _axle_lateral_slope(vehicle, axle, tire, variable, load=None, slip_ratio=0.0, speed=_SPEED):
    """-2 dF_y,ISO/d(variable) [N/rad] of one wheel at half the static axle load (or ``load``), zero slip
    and inclination (or the slip ratio ``slip_ratio``): central differences in ``variable`` ("alpha" or
    "gamma"), the other held at 0."""
    law = _law(vehicle, axle, tire)
    load = _wheel_load(vehicle, axle) if load is None else load
    step = {"alpha": (_EPS, 0.0), "gamma": (0.0, _EPS)}[variable]
    plus = law.forces(load, slip_ratio, step[0], step[1], speed)
    minus = law.forces(load, slip_ratio, -step[0] if step[0] else 0.0, -step[1] if step[1] else 0.0, speed)
    return -2.0 * float(np.asarray(plus.fy) - np.asarray(minus.fy)) / (2 * _EPS)


def pneumatic_trail(vehicle, axle: str = "front", tire=None) -> float:
    r"""Pneumatic trail t of an axle's tires: -dM_z/dF_y at zero slip and the static load.

    .. math::

        t = -\frac{\partial M_z / \partial \alpha}{\partial F_y / \partial \alpha}\Big|_{\alpha = 0}

    (the same in SAE and ISO-W: F_y and M_z both change sign between them); t > 0 for a force
    acting behind the contact centre, so that M_z = -t F_y steers the wheel away from the force.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle; the front axle's ``steering.pneumatic_trail`` is used where it is set (and no
        ``tire`` is given).
    axle : {"front", "rear"}
        The axle.
    tire : TireModel, optional
        The law of one wheel (default the vehicle's, :func:`vehdyn.tire.tire_for_vehicle`).

    Returns
    -------
    float
        t [m] (0.0 for a law without an aligning moment).
    """
    if axle == "front" and tire is None and vehicle.steering.pneumatic_trail is not None:
        return float(vehicle.steering.pneumatic_trail)
    law = _law(vehicle, axle, tire)
    load = _wheel_load(vehicle, axle)
    plus, minus = law.forces(load, 0.0, _EPS, 0.0, _SPEED), law.forces(load, 0.0, -_EPS, 0.0, _SPEED)
    dfy = float(np.asarray(plus.fy) - np.asarray(minus.fy))
    mz_plus, mz_minus = getattr(plus, "mz", None), getattr(minus, "mz", None)
    if mz_plus is None or dfy == 0.0:
        return 0.0
    return -float(np.asarray(mz_plus) - np.asarray(mz_minus)) / dfy


def camber_stiffness(vehicle, axle: str = "front", tire=None) -> float:
    r"""Camber stiffness of an axle (both tires, SAE): dF_y/d(gamma) at zero slip and the static load.

    .. math::

        C_{\gamma} = 2 \frac{\partial F_{y,SAE}}{\partial \gamma}\Big|_{\alpha = \gamma = 0}
                   = -2 \frac{\partial F_{y,ISO}}{\partial \gamma}

    gamma the inclination, a rotation about the vehicle's x axis (the same in SAE and ISO-W): with
    the wheels' planes rolled together (both tops toward +y) the two wheels of an axle push the
    same way, a mirror-image tire (:func:`vehdyn.components.tire_setup.mirrored_wheel`) as much as
    the other.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle (its static axle load).
    axle : {"front", "rear"}
        The axle.
    tire : TireModel, optional
        The law of one wheel (default the vehicle's).

    Returns
    -------
    float
        C_gamma [N/rad] (SAE force per SAE inclination).
    """
    return _axle_lateral_slope(vehicle, axle, tire, "gamma")


def cornering_stiffness(vehicle, axle: str = "front", tire=None, *, wheel_load=None, slip_ratio: float = 0.0,
                        speed: float = _SPEED) -> float:
    r"""Cornering stiffness of an axle (both tires, SAE) from its law: -dF_y/d(alpha) at zero slip and the static load.

    .. math::

        C = 2 \frac{\partial F_{y,ISO}}{\partial \alpha}\Big|_{\alpha = 0}\cdot(-1)

    (one wheel at half the static axle load, doubled; positive for the usual tire). The file's
    ``tires.*_cornering_stiffness`` is the linear models' number; this is the law's. ``wheel_load``,
    ``slip_ratio`` and ``speed`` move the point (the understeer budget's load-sensitivity and
    combined-slip rows); the slope is that of the law's own tire (a mirror image has the same).

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle (its static axle load).
    axle : {"front", "rear"}
        The axle.
    tire : TireModel, optional
        The law of one wheel (default the vehicle's).
    wheel_load : float, optional
        Normal load of each wheel [N] (default half the static axle load).
    slip_ratio : float, optional
        Slip ratio at which the slope is taken [-] (ISO-W; default 0).
    speed : float, optional
        Forward speed of the wheel centre [m/s] (default 20).

    Returns
    -------
    float
        C [N/rad].
    """
    return _axle_lateral_slope(vehicle, axle, tire, "alpha", wheel_load, slip_ratio, speed)


def compliance_steer_slope(vehicle, axle: str = "front", tire=None) -> tuple[float, float, float]:
    r"""An axle's compliance steer fields and the slope of the steer against itself with a tire law.

    .. math::

        s = (c - e t) C

    c the ``suspension.<axle>_lateral_force_compliance_steer`` [rad/N], e the
    ``*_aligning_moment_compliance_steer`` [rad/(N*m)], t the law's pneumatic trail and C its axle
    cornering stiffness at the static load (:func:`pneumatic_trail`, :func:`cornering_stiffness`;
    read only where c or e is set): d(delta_c)/d(delta_c) of delta_c = c F_y + e M_z, the first
    step of the nonlinear models without tire lag.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle.
    axle : {"front", "rear"}
        The axle.
    tire : TireModel, optional
        The law of one wheel (default the vehicle's).

    Returns
    -------
    tuple of float
        (c [rad/N], e [rad/(N*m)], s [-]).

    Raises
    ------
    ParameterError
        Naming ``suspension.<axle>_lateral_force_compliance_steer`` where s >= 1 (the axle's force
        would steer it further than its slip: no effective cornering stiffness).
    """
    s = vehicle.suspension
    c = float(getattr(s, f"{axle}_lateral_force_compliance_steer"))
    e = float(getattr(s, f"{axle}_aligning_moment_compliance_steer"))
    if c == 0.0 and e == 0.0:
        return c, e, 0.0
    trail = pneumatic_trail(vehicle, axle, tire) if e != 0.0 else 0.0
    slope = (c - e * trail) * cornering_stiffness(vehicle, axle, tire)
    if not slope < 1.0:
        raise ParameterError(f"suspension.{axle}_lateral_force_compliance_steer = {c:.6g} rad/N and "
                             f"{axle}_aligning_moment_compliance_steer = {e:.6g} rad/(N*m) with the {axle} tire law's "
                             f"cornering stiffness and trail {trail:.4g} m make (c - e t) C = {slope:.6g} >= 1: no "
                             "effective cornering stiffness", key=f"suspension.{axle}_lateral_force_compliance_steer",
                             value=c)
    return c, e, float(slope)


def wheel_loads(vehicle, axle: str, side: str, fz, kappa=0.0, alpha=0.0, gamma=0.0, speed: float = _SPEED,
                tire=None) -> tuple[float, float, float]:
    r"""ISO-W (F_x, F_y, M_y) of one wheel of an axle: the law's own tire or its mirror image.

    .. math::

        (F_x, F_y, M_y) = (F_x^*, \pm F_y^*, M_y^*), \qquad F^* = F(\kappa, \pm\alpha, \pm\gamma)

    (the lower signs on the wheel that is the mirror image of the law's tire: the left one, or the
    right one for a ``.tir`` file with ``TYRESIDE = 'LEFT'``, where the law makes a lateral force at
    zero slip; :func:`vehdyn.components.tire_setup.mirrored_wheel`, MF-Tyre's convention). Under a
    lateral load transfer the ply-steer part of the axle's force at zero slip is the difference of
    the two wheels' (Pacejka 2012, sec. 4.3.2).

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle (its static load decides the law's ply steer).
    axle : {"front", "rear"}
        The axle.
    side : {"left", "right"}
        The wheel.
    fz : float
        Normal load [N].
    kappa : float, optional
        Slip ratio [-] (ISO-W).
    alpha : float, optional
        Slip angle [rad] (ISO-W).
    gamma : float, optional
        Inclination [rad] (ISO-W).
    speed : float, optional
        Forward speed of the wheel centre [m/s].
    tire : TireModel, optional
        The law of one wheel (default the vehicle's).

    Returns
    -------
    tuple of float
        (F_x [N], F_y [N], M_y [N*m]), ISO-W (M_y 0 for a law without rolling resistance).

    Raises
    ------
    ParameterError
        For a side other than "left" or "right".
    """
    from vehdyn.components.tire_forces import tire_loads
    from vehdyn.components.tire_setup import mirrored_wheel, tire_characteristics
    from vehdyn.components.xp import NUMPY

    if side not in ("left", "right"):
        raise ParameterError(f"side must be 'left' or 'right', got {side!r}", key="side", value=side)
    law = _law(vehicle, axle, tire)
    mirror = mirrored_wheel(law, tire_characteristics(law, _wheel_load(vehicle, axle))[0]) == side
    fx, fy, my = tire_loads(NUMPY, law, float(fz), float(kappa), float(alpha), float(gamma), float(speed), mirror,
                            1.0, False)
    return float(fx), float(fy), float(my)


def wheel_slip_ratio(vehicle, axle: str, fz: float, fx: float, speed: float = _SPEED, tire=None) -> float:
    r"""The slip ratio at which one wheel's law makes the longitudinal force ``fx`` at zero slip angle.

    .. math::

        F_x(\kappa, F_z) = F_{x,target}

    solved by Newton's method with the law's slip stiffness by central differences (both wheels of
    an axle alike: F_x does not change sign in the mirror image).

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle.
    axle : {"front", "rear"}
        The axle.
    fz : float
        Normal load of the wheel [N].
    fx : float
        Longitudinal force of the wheel [N] (ISO-W, positive driving).
    speed : float, optional
        Forward speed of the wheel centre [m/s].
    tire : TireModel, optional
        The law of one wheel (default the vehicle's).

    Returns
    -------
    float
        kappa [-].

    Raises
    ------
    ParameterError
        Naming ``fx`` where the law has no longitudinal slip stiffness or does not reach the force.
    """
    law = _law(vehicle, axle, tire)
    kappa, step = 0.0, 1e-6

    def force(k):
        return float(np.asarray(law.forces(fz, k, 0.0, 0.0, speed).fx))

    for _ in range(50):
        residual = force(kappa) - fx
        slope = (force(kappa + step) - force(kappa - step)) / (2 * step)
        if not slope > 0.0 or not np.isfinite(slope):
            break
        change = residual / slope
        kappa -= change
        if abs(change) < 1e-12:
            return float(kappa)
    raise ParameterError(f"the {axle} tire law does not make the longitudinal force fx = {fx:.6g} N at "
                         f"F_z = {fz:.6g} N (no slip stiffness, or beyond its peak)", key="fx", value=fx)
