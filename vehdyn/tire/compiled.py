"""A tire law evaluated from numba-compiled code: the compiled ``xp`` of vehicle models' tire step.

Imported only when a compiled backend is used (numba is optional: ``pip install vehdyn[fast]``).
A compiled vehicle model describes each of its laws by a :class:`TireLaw` (built once, from
Python, by :func:`tire_law`) and evaluates it one point at a time with :func:`tire_law_loads`,
which calls the kernels of :mod:`vehdyn.tire.kernels` with the compiled namespace :data:`XP`:
the Magic Formula as :meth:`MagicFormula.forces` evaluates it (``limits=True``,
``alpha_star=False``) or the linear law. Nothing here restates an equation. Other laws (brush,
Fiala, Dugoff) have no compiled form: :func:`tire_law` raises and names the law.

What the law's evaluation is shared for (two tires of an axle at half its load, the mirror image
of a law with ply steer, the road's friction by similarity) is written once over ``xp`` in
:mod:`vehdyn.components.tire_forces`.
"""

from __future__ import annotations

import sys
from collections import namedtuple

import numpy as np
from numba.extending import register_jitable

from vehdyn.errors import ParameterError
from vehdyn.simulation.compiled import CALLEE_ONLY, compiled_copy, source_stamp
from vehdyn.tire import _mf_numba, linear
from vehdyn.tire.linear import LinearTire, linear_tire_law
from vehdyn.tire.magic_formula import MagicFormula, MFCoefficients, forces_kernel, lateral_force_kernel

__all__ = ["XP", "MAGIC_FORMULA", "LINEAR", "TireLaw", "tire_law", "coefficient_records", "tire_law_loads",
           "lateral_or_full_loads", "tire_law_aligning", "SOURCE_MODULES"]

_JIT = {"error_model": "numpy", **CALLEE_ONLY}

XP = _mf_numba.OPS
"""The ``xp`` of the kernels in compiled code (floats; numba-compiled, inlined into the caller)."""

MAGIC_FORMULA, LINEAR = 0, 1
"""The kinds of :class:`TireLaw`."""

N_LINEAR = 5
"""The number of the linear law's coefficients (:attr:`LinearTire.coefficients`)."""

TireLaw = namedtuple("TireLaw", ("kind", "records", "record", "linear", "lateral_only"), defaults=(False,))
TireLaw.__doc__ = """One tire law for compiled code.

Parameters
----------
kind : int
    :data:`MAGIC_FORMULA` or :data:`LINEAR`.
records : ndarray
    Magic Formula coefficient records [the .tir units, SI] (:func:`coefficient_records`; one record of zeros for another
    law): an array, not a record, so that a batch can pick a variant's record inside compiled code.
record : int
    Which of ``records`` is this law's.
linear : tuple of float
    The linear law's coefficients (C_alpha [N/rad], C_kappa [N], C_gamma [N/rad], t [m], F_z0 [N]);
    zeros for a Magic Formula.
lateral_only : bool
    The caller takes only F_y at kappa = 0 and gamma = 0 (a single-track model in force mode):
    a Magic Formula then evaluates :func:`~vehdyn.tire.kernels.lateral_force_kernel`, bitwise the
    same F_y at a quarter of the cost, and returns F_x = M_y = 0."""


def coefficient_records(c=None) -> np.ndarray:
    """An array of one Magic Formula coefficient record.

    Parameters
    ----------
    c : MFCoefficients, optional
        The coefficients (a ``MagicFormula``'s); zeros without them.

    Returns
    -------
    ndarray
        Shape (1,), a structured array with the fields of ``MFCoefficients`` [the .tir units, SI].
    """
    dtype = [(name, np.float64) for name in MFCoefficients._fields]
    return np.zeros(1, dtype=dtype) if c is None else np.array([tuple(c)], dtype=dtype)


def tire_law(tire, name: str = "tire", lateral_only: bool = False) -> TireLaw:
    """The compiled description of ``tire``.

    Parameters
    ----------
    tire : MagicFormula or LinearTire
        The law.
    name : str
        What the caller calls it (``"front_tire"``, ...), for the error message.
    lateral_only : bool
        See :class:`TireLaw`.

    Returns
    -------
    TireLaw

    Raises
    ------
    ParameterError
        For a law without a compiled form, naming it.
    """
    if isinstance(tire, MagicFormula):
        return TireLaw(MAGIC_FORMULA, coefficient_records(tire._c), 0, (0.0,) * N_LINEAR, bool(lateral_only))
    if isinstance(tire, LinearTire):
        return TireLaw(LINEAR, coefficient_records(), 0, tuple(float(v) for v in tire.coefficients),
                       bool(lateral_only))
    raise ParameterError(f"compiled code supports the MagicFormula and LinearTire laws; {name} is a "
                         f"{type(tire).__name__}: use backend='numpy'", key=name, value=type(tire).__name__)


def tire_law_loads(law, fz, kappa, alpha, gamma, vx):
    """ISO-W (F_x, F_y, M_y) [N, N, N*m] of one tire of ``law`` (compiled code; floats).

    Parameters
    ----------
    law : TireLaw
        The law.
    fz : float
        Normal load [N].
    kappa : float
        Slip ratio [-] (ISO-W).
    alpha : float
        Slip angle [rad] (ISO-W).
    gamma : float
        Inclination angle [rad] (ISO-W).
    vx : float
        Forward speed of the wheel centre [m/s].

    Returns
    -------
    tuple of float
        (F_x [N], F_y [N], M_y [N*m]): the Magic Formula's rolling-resistance moment, 0 for the
        linear law (which has none). ``law.lateral_only`` is not read (see :func:`lateral_or_full_loads`).
    """
    if law.kind == MAGIC_FORMULA:
        c = law.records[law.record]
        f = forces_kernel(XP, c, fz, kappa, alpha, gamma, vx, c.INFLPRES, True, False)
        return f[0], f[1], f[4]
    fx, fy, _ = linear_tire_law(XP, law.linear, fz, kappa, alpha, gamma, vx)
    return fx, fy, 0.0


def lateral_or_full_loads(law, fz, kappa, alpha, gamma, vx):
    """:func:`tire_law_loads`, or with ``law.lateral_only`` a Magic Formula's F_y alone (F_x = M_y = 0).

    The tire hook of a model that can take F_y alone (the single track in force mode): a separate
    function, so that a model that never does (the full vehicle) does not compile the lean kernel.

    Parameters
    ----------
    law : TireLaw
        The law.
    fz : float
        Normal load [N].
    kappa : float
        Slip ratio [-] (ISO-W; 0 with ``law.lateral_only``).
    alpha : float
        Slip angle [rad] (ISO-W).
    gamma : float
        Inclination angle [rad] (ISO-W; 0 with ``law.lateral_only``).
    vx : float
        Forward speed of the wheel centre [m/s].

    Returns
    -------
    tuple of float
        (F_x [N], F_y [N], M_y [N*m]).
    """
    if law.lateral_only and law.kind == MAGIC_FORMULA:
        c = law.records[law.record]
        return 0.0, lateral_force_kernel(XP, c, fz, alpha, vx, c.INFLPRES), 0.0
    return tire_law_loads(law, fz, kappa, alpha, gamma, vx)


def tire_law_aligning(law, fz, kappa, alpha, gamma, vx):
    """ISO-W aligning moment M_z [N*m] of one tire of ``law`` (compiled code; floats).

    The Magic Formula's M_z as :func:`tire_law_loads` evaluates the law
    (:func:`~vehdyn.tire.kernels.forces_kernel` with ``limits=True``, ``alpha_star=False``), or the
    linear law's -t F_y (Pacejka 2012, sec. 1.2: the pneumatic trail t behind the contact centre).

    Parameters
    ----------
    law : TireLaw
        The law.
    fz : float
        Normal load [N].
    kappa : float
        Slip ratio [-] (ISO-W).
    alpha : float
        Slip angle [rad] (ISO-W).
    gamma : float
        Inclination angle [rad] (ISO-W).
    vx : float
        Forward speed of the wheel centre [m/s].

    Returns
    -------
    float
        M_z [N*m], ISO-W.
    """
    if law.kind == MAGIC_FORMULA:
        c = law.records[law.record]
        return forces_kernel(XP, c, fz, kappa, alpha, gamma, vx, c.INFLPRES, True, False)[5]
    return linear_tire_law(XP, law.linear, fz, kappa, alpha, gamma, vx)[2]


register_jitable(**_JIT)(linear_tire_law)

SOURCE_MODULES = (*_mf_numba.SOURCE_MODULES, linear, sys.modules[__name__])
"""The modules whose source a compiled caller's disk cache is keyed on (editing one recompiles)."""

# The three entry points are compiled once and cached on disk (numba dispatchers named by the source of
# every module they draw on), not registered for inlining into each caller: every model family (single
# track, full vehicle, the controllers' loops) then links the same compiled law (numba links a cached
# callee's LLVM module into the caller without retyping it; LLVM may still inline it), instead of typing
# and lowering the Magic Formula again per family. The Python functions stay documented above.
_STAMP = source_stamp(*SOURCE_MODULES)
tire_law_loads = compiled_copy(tire_law_loads, f"tire_law_loads_{_STAMP}")
lateral_or_full_loads = compiled_copy(lateral_or_full_loads, f"lateral_or_full_loads_{_STAMP}",
                                      tire_law_loads=tire_law_loads)
tire_law_aligning = compiled_copy(tire_law_aligning, f"tire_law_aligning_{_STAMP}")
