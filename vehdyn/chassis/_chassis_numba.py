"""Compiled chassis controllers (numba, optional): ABS, traction control and ESC.

Imported only when a compiled backend is used. Nothing here restates a control law: the law
functions of :mod:`~vehdyn.chassis.abs`, :mod:`~vehdyn.chassis.traction_control` and
:mod:`~vehdyn.chassis.esc` (written once for numpy arrays and floats) are registered with
``register_jitable`` and called once per channel with floats. The loop around a plant is
:mod:`vehdyn.interconnect._compiled_loop`.
"""

from __future__ import annotations

import functools
import sys

from numba.extending import register_jitable

from vehdyn.simulation.compiled import CALLEE_ONLY, CompiledModel, compiled_copy, source_stamp
from vehdyn.chassis import abs as abs_law
from vehdyn.chassis import base, esc, traction_control

__all__ = ["compiled_abs", "compiled_traction_control", "compiled_esc"]

_JIT = {"error_model": "numpy", **CALLEE_ONLY}

for _module, _names in ((base, ("sigmoid", "deadband")), (abs_law, ("braking_slip", "torque_rate")),
                        (traction_control, ("drive_slip", "reduction_rate", "brake_rate", "applied_torques")),
                        (esc, ("reference_yaw_rate", "yaw_moment_demand", "wheel_torque_commands", "axle_commands"))):
    for _name in _names:
        register_jitable(**_JIT)(getattr(_module, _name))


@functools.lru_cache(maxsize=None)
def _stamp() -> str:
    return source_stamp(base, abs_law, traction_control, esc, sys.modules[__name__])


@functools.lru_cache(maxsize=None)
def _compile_pair(rhs, output, name):
    key = f"{name}_{_stamp()}"
    return compiled_copy(rhs, f"{key}_rhs"), compiled_copy(output, f"{key}_output"), key


def _controller(rhs, output, name, controller, extra) -> CompiledModel:
    """The CompiledModel of a controller law: args (its gains with plain floats, ``extra``)."""
    rhs, output, key = _compile_pair(rhs, output, name)
    return CompiledModel(rhs, output, key, (_floats(controller.gains), extra))


# ------------------------------------------------------------------------------------ ABS
def _abs_rhs(t, x, u, args, dxdt):
    """dT/dt of every ABS channel; u = (demands, wheel speeds, speed)."""
    p, n = args
    for i in range(n):
        dxdt[i] = abs_law.torque_rate(p, x[i], u[i], u[n + i], u[2 * n])


def _abs_output(t, x, u, args, y):
    _, n = args
    for i in range(n):
        y[i] = max(x[i], 0.0)


def compiled_abs(controller) -> CompiledModel:
    """The compiled :class:`~vehdyn.chassis.ABS` (one channel per axle or wheel)."""
    return _controller(_abs_rhs, _abs_output, "chassis_abs", controller, len(controller.channels))


# ------------------------------------------------------------------------------------ traction control
def _tcs_rhs(t, x, u, args, dxdt):
    """Engine reduction and brake interventions; u = (drive demands, brake demands, wheel speeds, speed)."""
    p, n = args
    speed = u[3 * n]
    mean = 0.0
    for i in range(n):
        slip = traction_control.drive_slip(p, u[2 * n + i], speed)
        mean += slip
        dxdt[1 + i] = traction_control.brake_rate(p, x[1 + i], u[i], slip)
    dxdt[0] = traction_control.reduction_rate(p, x[0], mean / n)


def _tcs_output(t, x, u, args, y):
    p, n = args
    for i in range(n):
        drive, brake = traction_control.applied_torques(p, x[0], x[1 + i], u[i], u[n + i])
        y[i] = drive
        y[n + i] = brake


def compiled_traction_control(controller) -> CompiledModel:
    """The compiled :class:`~vehdyn.chassis.TractionControl`."""
    return _controller(_tcs_rhs, _tcs_output, "chassis_tcs", controller, len(controller.channels))


# ------------------------------------------------------------------------------------ ESC
_FORCE, _WHEEL_SPIN, _CORNERS = 0, 1, 2


def _esc_rhs(t, x, u, args, dxdt):
    """The four hydraulic channels; u = (steer, commanded demands, u, v, r)."""
    p, mode = args
    k = 5 if mode == _CORNERS else 4
    moment = esc.yaw_moment_demand(p, u[0], u[k], u[k + 1], u[k + 2])
    commands = esc.wheel_torque_commands(p, moment, u[k + 2])
    for j in range(4):
        dxdt[j] = (commands[j] - x[j]) / p.hydraulic_time_constant


def _esc_output(t, x, u, args, y):
    p, mode = args
    if mode == _CORNERS:
        for j in range(4):
            y[j] = max(u[1 + j], 0.0) + max(x[j], 0.0)
    else:
        front, rear, moment = esc.axle_commands(p, mode == _WHEEL_SPIN, x[0], x[1], x[2], x[3], u[1], u[2], u[3])
        y[0] = front
        y[1] = rear
        y[2] = moment


def compiled_esc(controller) -> CompiledModel:
    """The compiled :class:`~vehdyn.chassis.ESC` (force, wheel-spin or corner mode)."""
    mode = _CORNERS if controller.corners else _WHEEL_SPIN if controller.wheel_spin else _FORCE
    return _controller(_esc_rhs, _esc_output, "chassis_esc", controller, mode)


def _floats(gains):
    """The gains namedtuple with plain floats (tuples of floats kept): one numba type per law."""
    return type(gains)(*(tuple(float(v) for v in g) if isinstance(g, tuple) else float(g) for g in gains))
