"""Compiled chassis controllers and the compiled :class:`~vehdyn.chassis.ClosedLoop` (numba, optional).

Imported only when a compiled backend is used. Nothing here restates a control law: the law
functions of :mod:`~vehdyn.chassis.abs`, :mod:`~vehdyn.chassis.traction_control` and
:mod:`~vehdyn.chassis.esc` (written once for numpy arrays and floats) are registered with
``register_jitable`` and called once per channel with floats.

A closed loop compiles when its plant and its controller both have a compiled rhs and output
(``Model.compiled_rhs``): :func:`compiled_loop` binds the four compiled functions into one
``rhs(t, x, u, args, dxdt)`` that evaluates the controller's commands from its states and the
demands, substitutes them for the plant's inputs, reads the feedback from the plant's states (or
its compiled outputs) and stacks the two derivatives -- the same sequence as
:meth:`ClosedLoop._split`. Loops nest (ESC around ABS around the car): an inner loop is a plant
with a compiled rhs and output.
"""

from __future__ import annotations

import functools
import hashlib
import sys

import numba
import numpy as np
from numba.extending import register_jitable

from vehdyn._compiled_ode import CompiledModel, compiled_copy, source_stamp
from vehdyn.chassis import abs as abs_law
from vehdyn.chassis import closed_loop, esc, traction_control

__all__ = ["compiled_abs", "compiled_traction_control", "compiled_esc", "compiled_loop"]

_JIT = {"error_model": "numpy"}

for _module, _names in ((closed_loop, ("sigmoid", "deadband")), (abs_law, ("braking_slip", "torque_rate")),
                        (traction_control, ("drive_slip", "reduction_rate", "brake_rate", "applied_torques")),
                        (esc, ("reference_yaw_rate", "yaw_moment_demand", "wheel_torque_commands", "axle_commands"))):
    for _name in _names:
        register_jitable(**_JIT)(getattr(_module, _name))


@functools.lru_cache(maxsize=None)
def _stamp() -> str:
    return source_stamp(closed_loop, abs_law, traction_control, esc, sys.modules[__name__])


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


# ------------------------------------------------------------------------------------ the loop
def _commands(t, x, u, args):
    """(controller inputs with the demands, plant inputs with the commands substituted, the commands)."""
    plant_args, controller_args, n_plant, demand, feedback_state, feedback_output, commanded, n_plant_outputs = args
    uc = np.zeros(demand.shape[0] + feedback_state.shape[0] + feedback_output.shape[0])
    up = u.copy()
    command = np.empty(commanded.shape[0])
    for k in range(demand.shape[0]):
        uc[demand[k, 0]] = u[demand[k, 1]]
    _controller_output(t, x[n_plant:], uc, controller_args, command)
    for k in range(commanded.shape[0]):
        up[commanded[k]] = command[k]
    return uc, up, command


def _loop_rhs(t, x, u, args, dxdt):
    """dx/dt of the closed loop: the plant's, then the controller's."""
    plant_args, controller_args, n_plant, demand, feedback_state, feedback_output, commanded, n_plant_outputs = args
    uc, up, command = _commands(t, x, u, args)
    xp = x[:n_plant]
    for k in range(feedback_state.shape[0]):
        uc[feedback_state[k, 0]] = xp[feedback_state[k, 1]]
    if feedback_output.shape[0] > 0:
        yp = np.empty(n_plant_outputs)
        _plant_output(t, xp, up, plant_args, yp)
        for k in range(feedback_output.shape[0]):
            uc[feedback_output[k, 0]] = yp[feedback_output[k, 1]]
    _plant_rhs(t, xp, up, plant_args, dxdt[:n_plant])
    _controller_rhs(t, x[n_plant:], uc, controller_args, dxdt[n_plant:])


def _loop_output(t, x, u, args, y):
    """The plant's outputs, then the commands."""
    plant_args, controller_args, n_plant, demand, feedback_state, feedback_output, commanded, n_plant_outputs = args
    uc, up, command = _commands(t, x, u, args)
    _plant_output(t, x[:n_plant], up, plant_args, y[:n_plant_outputs])
    for k in range(commanded.shape[0]):
        y[n_plant_outputs + k] = command[k]


def _no_output(t, x, u, args, y):
    """Stands for a plant without compiled outputs (never called: the loop then reads no plant output)."""
    for j in range(y.shape[0]):
        y[j] = np.nan


@functools.lru_cache(maxsize=None)
def _loop_functions(plant_rhs, plant_output, controller_rhs, controller_output, plant_key, controller_key):
    """(rhs, output or None, key) of the loop of these compiled plant and controller functions."""
    digest = hashlib.sha256(f"{plant_key}|{controller_key}".encode()).hexdigest()[:16]
    key = f"closed_loop_{digest}_{_stamp()}"
    has_output = plant_output is not None
    if not has_output:
        plant_output = compiled_copy(_no_output, f"chassis_no_output_{_stamp()}")
    bound = dict(_plant_rhs=plant_rhs, _plant_output=plant_output, _controller_rhs=controller_rhs)
    commands = compiled_copy(_commands, f"{key}_commands", _controller_output=controller_output)
    rhs = compiled_copy(_loop_rhs, f"{key}_rhs", _commands=commands, **bound)
    output = compiled_copy(_loop_output, f"{key}_output", _commands=commands, **bound) if has_output else None
    return rhs, output, key


def _pairs(pairs):
    return np.array(pairs, dtype=np.int64).reshape(-1, 2)


def compiled_loop(loop) -> CompiledModel | None:
    """The compiled rhs and outputs of a :class:`~vehdyn.chassis.ClosedLoop`, or None.

    None when the plant or the controller has no compiled rhs (or the controller no compiled
    output), or when the controller reads a plant output and the plant has no compiled outputs;
    a :class:`~vehdyn.ParameterError` of the plant's ``compiled_rhs`` (a configuration without a
    compiled form) passes through.
    """
    plant = loop.plant.compiled_rhs()
    controller = loop.controller.compiled_rhs()
    if plant is None or controller is None or controller.output is None:
        return None
    if loop._fb_output and plant.output is None:
        return None
    rhs, output, key = _loop_functions(plant.rhs, plant.output, controller.rhs, controller.output, plant.key,
                                       controller.key)
    args = (plant.args, controller.args, int(loop._np), _pairs(loop._demand), _pairs(loop._fb_state),
            _pairs(loop._fb_output), np.array(loop._command, dtype=np.int64), int(loop.plant.n_outputs))
    return CompiledModel(rhs, output, key, args)
