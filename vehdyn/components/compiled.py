"""The ``xp`` namespace of the vehicle models' equations in numba-compiled code.

Imported only when a compiled backend is used (numba is optional: ``pip install vehdyn[fast]``).
Nothing here restates an equation: the functions of the components
(:mod:`~vehdyn.components.tire_slip`, :mod:`~vehdyn.components.tire_forces`,
:mod:`~vehdyn.components.wheel`, :mod:`~vehdyn.components.planar`,
:mod:`~vehdyn.components.aero`) and of :mod:`vehdyn.conventions` are registered with
``register_jitable`` (so that compiled code can call them) and :data:`XP` supplies the interface
of :mod:`vehdyn.components.xp` on floats: the math functions and the tire hooks
(:func:`vehdyn.tire.compiled.tire_law_loads` on a :class:`~vehdyn.tire.compiled.TireLaw`).

The library calls that have an exact answer on the usual path are skipped (``cos`` at 0 and pi,
``sin`` and ``tanh`` at 0, ``atan2`` at y = 0 and x > 0: an absent rear steer, the low-speed
blend above its speed, a wheel that does not spin, no crosswind), bitwise the library's results
(tested).
"""

from __future__ import annotations

import math
import sys
import types

from numba.extending import register_jitable

from vehdyn import conventions
from vehdyn.components import aero, planar, tire_forces, tire_slip, wheel
from vehdyn.simulation.compiled import CALLEE_ONLY
from vehdyn.tire import compiled as tire_compiled
from vehdyn.tire.compiled import lateral_or_full_loads, tire_law_loads

__all__ = ["XP", "XP_WITHOUT_ALIGNING", "FULL_FORCES", "WITHOUT_ALIGNING", "namespace", "SOURCE_MODULES",
           "JIT_OPTIONS"]

JIT_OPTIONS = {"error_model": "numpy", **CALLEE_ONLY}
"""numba options of the equations: x/0 = inf and 0/0 = nan as numpy, no exceptions; called from
compiled code only (:data:`vehdyn.simulation.compiled.CALLEE_ONLY`)."""

for _module, _names in ((conventions, ("planar_tire_slips_sae_to_iso_w", "planar_tire_forces_iso_w_to_sae")),
                        (aero, ("aero_side_force",)), (tire_slip, tire_slip.__all__[1:]), (wheel, wheel.__all__),
                        (tire_forces, tire_forces.__all__ + ["_similar", "_scaled_pair"]), (planar, planar.__all__)):
    for _name in _names:
        register_jitable(**JIT_OPTIONS)(getattr(_module, _name))


def _cos(x):
    """cos(x), without the library call at x = 0 and x = pi: exactly 1.0 and -1.0, as the library returns."""
    if x == 0.0:
        return 1.0
    if x == math.pi:
        return -1.0
    return math.cos(x)


def _sin(x):
    """sin(x), without the library call at x = +-0 (sin(+-0) = +-0)."""
    return x if x == 0.0 else math.sin(x)


def _tanh(x):
    """tanh(x), without the library call at x = +-0."""
    return x if x == 0.0 else math.tanh(x)


def _atan2(y, x):
    """atan2(y, x), without the library call at y = +-0, x > 0: +-0."""
    return y if y == 0.0 and x > 0.0 else math.atan2(y, x)


def _tire_law_pair(law, fz_1, fz_2, kappa, alpha_1, alpha_2, gamma_1, gamma_2, vx):
    """Two tires: two calls of :func:`~vehdyn.tire.compiled.lateral_or_full_loads` (a 6-tuple)."""
    fx1, fy1, my1 = lateral_or_full_loads(law, fz_1, kappa, alpha_1, gamma_1, vx)
    fx2, fy2, my2 = lateral_or_full_loads(law, fz_2, kappa, alpha_2, gamma_2, vx)
    return fx1, fy1, my1, fx2, fy2, my2


def _tire_law_pair_full(law, fz_1, fz_2, kappa, alpha_1, alpha_2, gamma_1, gamma_2, vx):
    """Two tires: two calls of :func:`~vehdyn.tire.compiled.tire_law_loads` (a 6-tuple)."""
    fx1, fy1, my1 = tire_law_loads(law, fz_1, kappa, alpha_1, gamma_1, vx)
    fx2, fy2, my2 = tire_law_loads(law, fz_2, kappa, alpha_2, gamma_2, vx)
    return fx1, fy1, my1, fx2, fy2, my2


def _no_aligning_moment(law, fz, kappa, alpha, gamma, vx):
    """The ``tire_law_aligning`` hook of a model whose compliance steer never reads M_z: 0.0."""
    return 0.0


def namespace(name: str, **hooks) -> types.ModuleType:
    """A copy of :data:`XP` with a model's own hooks added (numba reads a namespace's functions as
    compile-time constants, so a model that adds hooks needs a namespace of its own).

    Parameters
    ----------
    name : str
        The namespace's module name.
    **hooks
        Compiled (or ``register_jitable``) functions under the names the model's equations call.

    Returns
    -------
    module
        The namespace.
    """
    ns = types.ModuleType(name)
    ns.__doc__ = XP.__doc__
    vars(ns).update({k: v for k, v in vars(XP).items() if not k.startswith("__")})
    vars(ns).update(hooks)
    return ns


XP = types.ModuleType("vehdyn.components.compiled.XP")
XP.__doc__ = "The ``xp`` of the vehicle equations in compiled code (floats; the tire laws compiled)."
for _name in ("tan", "atan", "sqrt"):
    setattr(XP, _name, getattr(math, _name))
for _function in (_cos, _sin, _tanh, _atan2):
    setattr(XP, _function.__name__[1:], register_jitable(**JIT_OPTIONS, forceinline=True)(_function))
for _name in ("abs", "where", "minimum", "maximum"):
    setattr(XP, _name, getattr(tire_compiled.XP, _name))
XP.tire_law = lateral_or_full_loads
XP.tire_law_pair = register_jitable(**JIT_OPTIONS)(_tire_law_pair)
XP.tire_law_aligning = tire_compiled.tire_law_aligning

WITHOUT_ALIGNING = {"tire_law_aligning": register_jitable(**JIT_OPTIONS)(_no_aligning_moment)}
"""The hook of a model with no aligning-moment compliance (e_i = 0, the shipped cars): its equations
call ``tire_law_aligning`` only where e_i != 0, a branch numba still types and compiles; a namespace
with this hook leaves the Magic Formula's M_z out of the model's compiled code (the single track's
cold compile, CPU: 44 -> 33 s)."""

XP_WITHOUT_ALIGNING = namespace("vehdyn.components.compiled.XP_WITHOUT_ALIGNING", **WITHOUT_ALIGNING)
""":data:`XP` with :data:`WITHOUT_ALIGNING`."""

FULL_FORCES = {"tire_law": tire_law_loads, "tire_law_pair": register_jitable(**JIT_OPTIONS)(_tire_law_pair_full),
               "cos": math.cos, "sin": math.sin, "tanh": math.tanh, "atan2": math.atan2}
"""Hooks for :func:`namespace` of a model that always takes a law's full forces (no ``lateral_only``)
and the library's math functions as they are (no short cuts: less code to compile)."""

SOURCE_MODULES = (*tire_compiled.SOURCE_MODULES, conventions, tire_slip, tire_forces, wheel, planar, aero,
                  sys.modules[__name__])
"""The modules whose source the disk cache of a compiled model built on :data:`XP` is keyed on."""
