"""Compiled drivers (numba, optional): the preview, crossover and optimal preview drivers.

Imported only when a compiled backend is used. Nothing here restates a driver's law: the law
functions of :mod:`~vehdyn.driver.base`, :mod:`~vehdyn.driver.preview`,
:mod:`~vehdyn.driver.crossover` and :mod:`~vehdyn.driver.optimal_preview` (written once for numpy
arrays and floats, the same functions the drivers' ``rhs`` and ``output`` call) are registered
with ``register_jitable`` and called with the driver's numbers (a namedtuple) and floats. The loop
around a plant is :mod:`vehdyn.interconnect._compiled_loop`.
"""

from __future__ import annotations

import functools
import sys

from numba.extending import register_jitable

from vehdyn.driver import base, crossover, optimal_preview, preview
from vehdyn.simulation.compiled import CALLEE_ONLY, CompiledModel, compiled_copy, source_stamp

__all__ = ["compiled_driver"]

_JIT = {"error_model": "numpy", **CALLEE_ONLY}

for _module, _names in ((base, ("preview_offsets", "heading_offsets", "delay_rates", "steer_rates", "steer_output")),
                        (preview, ("pure_pursuit_command", "speed_control_force", "preview_driver_rhs",
                                   "preview_driver_output")),
                        (crossover, ("crossover_command", "crossover_driver_rhs")),
                        (optimal_preview, ("optimal_preview_command", "optimal_preview_driver_rhs"))):
    for _name in _names:
        register_jitable(**_JIT)(getattr(_module, _name))


@functools.lru_cache(maxsize=None)
def _stamp() -> str:
    return source_stamp(base, preview, crossover, optimal_preview, sys.modules[__name__])


def _rhs(t, x, u, args, dxdt):
    """dx/dt of the driver's states; ``args`` its numbers, ``_law_rhs`` bound to its law."""
    _law_rhs(args, x, u, dxdt)  # noqa: F821 (bound by compiled_copy)


def _output(t, x, u, args, y):
    """The driver's outputs; ``_law_output`` bound to its law."""
    _law_output(args, x, u, y)  # noqa: F821 (bound by compiled_copy)


@functools.lru_cache(maxsize=None)
def _functions(law_rhs, law_output):
    key = f"driver_{law_rhs.__name__}_{law_output.__name__}_{_stamp()}"
    return (compiled_copy(_rhs, f"{key}_rhs", _law_rhs=law_rhs),
            compiled_copy(_output, f"{key}_output", _law_output=law_output), key)


def compiled_driver(driver) -> CompiledModel:
    """The compiled rhs and output of a driver of :mod:`vehdyn.driver`, its numbers as their ``args``."""
    cls = type(driver)
    rhs, output, key = _functions(cls._law_rhs, cls._law_output)
    return CompiledModel(rhs, output, key, driver.numbers)
