"""Compiled right-hand side of :class:`~vehdyn.driver.DriverInTheLoop` (numba, optional).

Imported only when the compiled backend is used. The driver's law is not restated: the method
:meth:`PreviewDriver.steer_command` (and every module-level function of :mod:`~vehdyn.driver`
it calls) is registered with ``register_jitable`` and called with a namedtuple :data:`DriverNumbers`
in place of the driver (the same attribute names). The vehicle model runs through its own compiled
rhs and output (:meth:`vehdyn.Model.compiled_rhs`), so a driver steers a compiled
:class:`~vehdyn.handling.SingleTrack`, a :class:`~vehdyn.full_vehicle.FullVehicle` or a compiled
:class:`~vehdyn.interconnect.ClosedLoop` (the car braking under ABS).
"""

from __future__ import annotations

import functools
import hashlib
import sys
import types
from collections import namedtuple

import numpy as np
from numba.extending import register_jitable

from vehdyn.simulation.compiled import CompiledModel, compiled_copy, source_stamp
from vehdyn.driver import base as driver_base
from vehdyn.driver import preview as driver

__all__ = ["DriverNumbers", "compiled_model"]

_JIT = {"error_model": "numpy"}

DriverNumbers = namedtuple("DriverNumbers", ("path_x", "path_y", "preview_time", "lag", "gain",
                                             "minimum_preview_distance", "target_speed", "speed_gain"))
DriverNumbers.__doc__ = "A PreviewDriver's numbers for compiled code (``target_speed`` 0.0 when None)."

_steer_command = driver.PreviewDriver.steer_command
for _name in _steer_command.__code__.co_names:
    if isinstance(getattr(driver, _name, None), types.FunctionType):
        register_jitable(**_JIT)(getattr(driver, _name))
register_jitable(**_JIT)(_steer_command)


@functools.lru_cache(maxsize=None)
def _stamp() -> str:
    return source_stamp(driver, driver_base, sys.modules[__name__])


def _vehicle_inputs(x, u, args, uv):
    """The vehicle model's inputs: the passed ones, the driver's steer (the last state), the speed law."""
    (_vargs, p, passed, i_steer, _i_x, _i_y, _i_yaw, i_speed, i_force, _wheelbase, _max_steer, mass, n_vehicle,
     _n_vehicle_inputs) = args
    for j in range(uv.shape[0]):
        uv[j] = 0.0
    for k in range(passed.shape[0]):
        uv[passed[k]] = u[k]
    uv[i_steer] = x[n_vehicle]
    if i_force >= 0:
        uv[i_force] = mass * p.speed_gain * (p.target_speed - x[i_speed])


def _rhs(t, x, u, args, dxdt):
    """dx/dt of the vehicle model, then the driver's steer rate."""
    (vargs, p, _passed, _i_steer, i_x, i_y, i_yaw, i_speed, _i_force, wheelbase, max_steer, _mass, n_vehicle,
     n_vehicle_inputs) = args
    uv = np.empty(n_vehicle_inputs)
    _vehicle_inputs(x, u, args, uv)
    speed = x[i_speed] if i_speed >= 0 else p.target_speed
    command = _steer_command(p, x[i_x], x[i_y], x[i_yaw], speed, wheelbase)
    command = min(max(command, -max_steer), max_steer)
    _vehicle_rhs(t, x[:n_vehicle], uv, vargs, dxdt[:n_vehicle])
    dxdt[n_vehicle] = (command - x[n_vehicle]) / p.lag


def _output(t, x, u, args, y):
    """The vehicle model's outputs, then the driver's steer angle."""
    vargs, n_vehicle, n_vehicle_inputs = args[0], args[12], args[13]
    uv = np.empty(n_vehicle_inputs)
    _vehicle_inputs(x, u, args, uv)
    _vehicle_output(t, x[:n_vehicle], uv, vargs, y[:y.shape[0] - 1])
    y[y.shape[0] - 1] = x[n_vehicle]


@functools.lru_cache(maxsize=None)
def _functions(vehicle_rhs, vehicle_output, vehicle_key):
    """(rhs, output, key) of the driver around these compiled vehicle functions."""
    key = f"driver_in_the_loop_{hashlib.sha256(vehicle_key.encode()).hexdigest()[:16]}_{_stamp()}"
    bound = dict(_vehicle_rhs=vehicle_rhs, _vehicle_output=vehicle_output)
    common = compiled_copy(_vehicle_inputs, f"driver_vehicle_inputs_{_stamp()}")
    rhs = compiled_copy(_rhs, f"{key}_rhs", _vehicle_inputs=common, **bound)
    output = compiled_copy(_output, f"{key}_output", _vehicle_inputs=common, **bound)
    return rhs, output, key


def compiled_model(loop) -> CompiledModel | None:
    """The compiled DriverInTheLoop, or None when its vehicle model has no compiled rhs and output."""
    vehicle = loop.vehicle_model.compiled_rhs()
    if vehicle is None or vehicle.output is None:
        return None
    d = loop.driver
    p = DriverNumbers(np.ascontiguousarray(d.path_x, dtype=float), np.ascontiguousarray(d.path_y, dtype=float),
                      float(d.preview_time), float(d.lag), float(d.gain), float(d.minimum_preview_distance),
                      float(d.target_speed or 0.0), float(d.speed_gain))
    vm = loop.vehicle_model
    rhs, output, key = _functions(vehicle.rhs, vehicle.output, vehicle.key)
    args = (vehicle.args, p, np.array(loop._passed, dtype=np.int64), int(loop._i_steer), int(loop._ix["x"]),
            int(loop._ix["y"]), int(loop._ix["yaw_angle"]), -1 if loop._iu is None else int(loop._iu),
            -1 if loop._i_force is None else int(loop._i_force), float(loop.wheelbase), float(loop.max_steer_angle),
            float(loop.mass or 0.0), int(vm.n_states), int(vm.n_inputs))
    return CompiledModel(rhs, output, key, args)
