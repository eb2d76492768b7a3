"""The tire laws' force kernels over an ``xp`` namespace: the public interface for model authors.

A vehicle model that writes its equations once over an ``xp`` namespace (numpy arrays, Python
floats, numba-compiled code and, later, CasADi symbols) calls a tire law through these kernels.
Each kernel uses only ``xp``'s functions and plain arithmetic, so the same source runs on every
backend:

* :data:`NUMPY` -- numpy arrays with any batch shape (what :class:`~vehdyn.tire.MagicFormula` and
  :class:`~vehdyn.tire.LinearTire` use on arrays);
* :data:`SCALAR` -- Python floats, one operating point without numpy's per-call overhead; it
  raises where a float operation has no IEEE result (the caller then repeats the point on numpy);
* the compiled namespace, :func:`compiled_xp` (numba, optional: ``pip install vehdyn[fast]``;
  :mod:`vehdyn.tire.compiled` evaluates a law from compiled code with it).

The kernels: :func:`forces_kernel` (the Magic Formula's forces and moments without turn slip, what
:meth:`MagicFormula.forces` evaluates), :func:`lateral_force_kernel` (its F_y at zero slip ratio
and inclination, a quarter of the cost) and :func:`linear_tire_law` (the linear law).

The namespace's functions are ``sin``, ``cos``, ``tan``, ``atan``, ``acos``, ``sqrt``, ``exp``,
``pow``, ``log10``, ``abs``, ``sign``, ``copysign``, ``where``, ``minimum``, ``maximum``,
``clip``, ``fmax``, ``isnan``, ``any``, ``all``, ``full_broadcast`` and ``div`` (see
:class:`NUMPY`). The kernels take and return the ISO-W (TYDEX) convention of ``.tir`` files and
MFeval: slip ratio kappa, slip angle alpha [rad], inclination gamma [rad], forward speed of the
wheel centre V_x [m/s] (its sign says which way the wheel rolls), forces in the wheel's ISO-W axes.

References
----------
.. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, sec. 4.3
   (the Magic Formula's equations, 4.E1-4.E78).
"""

from __future__ import annotations

from vehdyn.tire._mf_ops import NumpyOps, ScalarOps
from vehdyn.tire.linear import linear_tire_law
from vehdyn.tire.magic_formula import forces_kernel, lateral_force_kernel

# NUMPY and SCALAR are namespaces (numpy's and math's functions under the interface's names), public
# here but not callables to document one by one: the interface is the list in the module docstring
__all__ = ["compiled_xp", "forces_kernel", "lateral_force_kernel", "linear_tire_law"]

NUMPY = NumpyOps
"""``xp`` of the kernels on numpy arrays (any shape; the arguments broadcast together)."""

SCALAR = ScalarOps
"""``xp`` of the kernels on Python floats (one operating point)."""


def compiled_xp():
    """The ``xp`` namespace of the kernels inside numba-compiled code (floats, one point per call).

    Imports numba on first use (and registers the kernels for compiled callers). A compiled
    function calls a kernel with it, e.g. ``forces_kernel(xp, c, fz, kappa, alpha, gamma, vx,
    c.INFLPRES, True, False)`` with ``c`` a coefficient record of
    :func:`vehdyn.tire.compiled.coefficient_records`.

    Returns
    -------
    module
        The compiled namespace (its functions are numba-compiled and inlined into the caller).
    """
    from vehdyn.tire.compiled import XP

    return XP


