"""The compiled :class:`~vehdyn.interconnect.ClosedLoop` (numba, optional).

Imported only when a compiled backend is used. A closed loop compiles when its plant and its
controller both have a compiled rhs and the controller a compiled output
(``Model.compiled_rhs``): :func:`compiled_loop` binds the compiled functions into one
``rhs(t, x, u, args, dxdt)`` that evaluates the controller's commands from its states, the
demands and the plant-state feedback, substitutes them for the plant's inputs, reads the
output feedback from the plant's compiled outputs and stacks the two derivatives -- the same
sequence as :meth:`ClosedLoop._split`. Loops nest (ESC around ABS around the car, a driver
around that): an inner loop is a plant with a compiled rhs and output. The drivers and the
chassis controllers are compiled from their one source (:mod:`vehdyn.driver`,
:mod:`vehdyn.chassis`); nothing here knows a control law.
"""

from __future__ import annotations

import functools
import hashlib
import sys

import numpy as np

from vehdyn.interconnect import closed_loop
from vehdyn.simulation.compiled import CompiledModel, compiled_copy, source_stamp

__all__ = ["compiled_loop"]


@functools.lru_cache(maxsize=None)
def _stamp() -> str:
    return source_stamp(closed_loop, sys.modules[__name__])


def _commands(t, x, u, controller_args, n_plant, demand, feedback_state, commanded, passed, uc, command, up):
    """Fill the controller's inputs ``uc`` (demands and state feedback; output feedback zero), its
    commands ``command`` and the plant's inputs ``up`` (the loop's, with the commands substituted).

    Takes the pieces of ``args`` it reads and writes into views of one work array that the caller
    allocates (an allocation and a reference count per array cost more than the loop's own work).
    """
    for k in range(uc.shape[0]):
        uc[k] = 0.0
    for k in range(demand.shape[0]):
        uc[demand[k, 0]] = u[demand[k, 1]]
    for k in range(feedback_state.shape[0]):
        uc[feedback_state[k, 0]] = x[feedback_state[k, 1]]
    _controller_output(t, x[n_plant:], uc, controller_args, command)  # noqa: F821 (bound by compiled_copy)
    for k in range(passed.shape[0]):  # every plant input is passed or commanded
        up[passed[k]] = u[k]
    for k in range(commanded.shape[0]):
        up[commanded[k]] = command[k]


def _loop_rhs(t, x, u, args, dxdt):
    """dx/dt of the closed loop: the plant's, then the controller's."""
    (plant_args, controller_args, n_plant, demand, feedback_state, feedback_output, commanded, n_plant_outputs,
     passed, n_plant_inputs, n_controller_inputs) = args
    n_commands = commanded.shape[0]
    work = np.empty(n_controller_inputs + n_commands + n_plant_inputs)
    uc, command, up = (work[:n_controller_inputs], work[n_controller_inputs:n_controller_inputs + n_commands],
                       work[n_controller_inputs + n_commands:])
    _commands(t, x, u, controller_args, n_plant, demand, feedback_state, commanded, passed, uc, command,  # noqa: F821
              up)
    xp = x[:n_plant]
    if feedback_output.shape[0] > 0:
        yp = np.empty(n_plant_outputs)
        _plant_output(t, xp, up, plant_args, yp)  # noqa: F821
        for k in range(feedback_output.shape[0]):
            uc[feedback_output[k, 0]] = yp[feedback_output[k, 1]]
    _plant_rhs(t, xp, up, plant_args, dxdt[:n_plant])  # noqa: F821
    _controller_rhs(t, x[n_plant:], uc, controller_args, dxdt[n_plant:])  # noqa: F821


def _loop_output(t, x, u, args, y):
    """The plant's outputs, then the commands."""
    (plant_args, controller_args, n_plant, demand, feedback_state, feedback_output, commanded, n_plant_outputs,
     passed, n_plant_inputs, n_controller_inputs) = args
    n_commands = commanded.shape[0]
    work = np.empty(n_controller_inputs + n_commands + n_plant_inputs)
    uc, command, up = (work[:n_controller_inputs], work[n_controller_inputs:n_controller_inputs + n_commands],
                       work[n_controller_inputs + n_commands:])
    _commands(t, x, u, controller_args, n_plant, demand, feedback_state, commanded, passed, uc, command,  # noqa: F821
              up)
    _plant_output(t, x[:n_plant], up, plant_args, y[:n_plant_outputs])  # noqa: F821
    for k in range(n_commands):
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
        plant_output = compiled_copy(_no_output, f"loop_no_output_{_stamp()}")
    bound = dict(_plant_rhs=plant_rhs, _plant_output=plant_output, _controller_rhs=controller_rhs)
    commands = compiled_copy(_commands, f"{key}_commands", _controller_output=controller_output)
    rhs = compiled_copy(_loop_rhs, f"{key}_rhs", _commands=commands, **bound)
    output = compiled_copy(_loop_output, f"{key}_output", _commands=commands, **bound) if has_output else None
    return rhs, output, key


def _pairs(pairs):
    return np.array(pairs, dtype=np.int64).reshape(-1, 2)


def compiled_loop(loop) -> CompiledModel | None:
    """The compiled rhs and outputs of a :class:`~vehdyn.interconnect.ClosedLoop`, or None.

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
            _pairs(loop._fb_output), np.array(loop._command, dtype=np.int64), int(loop.plant.n_outputs),
            np.array(loop._passed, dtype=np.int64), int(loop.plant.n_inputs), int(loop.controller.n_inputs))
    return CompiledModel(rhs, output, key, args)
