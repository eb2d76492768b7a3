"""The ``xp`` namespace of the vehicle models' equations on numpy arrays, and its interface.

The equations of the vehicle models (:mod:`vehdyn.handling.single_track_equations`,
:mod:`vehdyn.full_vehicle.assembly`) and of the components they share are written once, as pure
functions of an ``xp`` namespace and plain arithmetic. The interface an ``xp`` offers:

* math on numbers or arrays: ``cos``, ``sin``, ``tan``, ``tanh``, ``atan``, ``atan2``, ``sqrt``,
  ``abs``; ``where(condition, a, b)``, ``minimum(a, b)``, ``maximum(a, b)`` (elementwise);
* the tire hooks ``tire_law(law, fz, kappa, alpha, gamma, vx) -> (fx, fy, my)`` and
  ``tire_law_pair(law, fz_1, fz_2, kappa, alpha_1, alpha_2, gamma_1, gamma_2, vx)`` (a 6-tuple):
  one tire law evaluated at ISO-W slips (:mod:`vehdyn.components.tire_forces`);
  ``tire_law_aligning(law, fz, kappa, alpha, gamma, vx) -> mz``, the ISO-W aligning moment of one
  tire (read only by a model whose compliance steer needs the law's M_z).

A model may add hooks of its own (the full vehicle's rigid-body functions,
:mod:`vehdyn.full_vehicle.assembly`). :data:`NUMPY` runs the equations on numpy arrays with a
trailing batch axis (what the models' ``rhs`` and ``output`` use on a batch), :data:`SCALAR` on
Python floats (one state, without numpy's per-call overhead); the compiled namespace of
:mod:`vehdyn.components.compiled` runs them on floats inside numba-compiled code. Control flow in
the equations branches only on the model's constants (its options), never on a state, so that the
same source also builds a symbolic expression.
"""

from __future__ import annotations

import math

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.tire.kernels import NUMPY as _TIRE_NUMPY
from vehdyn.tire.kernels import SCALAR as _TIRE_SCALAR
from vehdyn.tire.kernels import forces_kernel, linear_tire_law
from vehdyn.tire.linear import LinearTire
from vehdyn.tire.magic_formula import MagicFormula

__all__ = ["NUMPY", "SCALAR", "stack", "with_tire_hooks"]


def _scalars(*values) -> bool:
    return all(np.ndim(v) == 0 for v in values)


class NUMPY(_TIRE_NUMPY):
    """``xp`` of the equations on numpy arrays: numpy's functions (``sin`` and ``cos`` numpy's own,
    not the half-angle forms of the tire kernels) and the tire hooks on a
    :class:`~vehdyn.tire.TireModel`."""

    cos = staticmethod(np.cos)
    sin = staticmethod(np.sin)
    tanh = staticmethod(np.tanh)
    atan2 = staticmethod(np.arctan2)

    @staticmethod
    def tire_law(law, fz, kappa, alpha, gamma, vx):
        """ISO-W (F_x, F_y, M_y) of one tire.

        Parameters
        ----------
        law : TireModel
            The law (``law.forces`` is called once; with every argument a number, on Python floats:
            the laws' fast scalar path).
        fz : float or ndarray
            Normal load [N].
        kappa : float or ndarray
            Slip ratio [-].
        alpha : float or ndarray
            Slip angle [rad].
        gamma : float or ndarray
            Inclination [rad].
        vx : float or ndarray
            Signed forward speed [m/s].

        Returns
        -------
        tuple
            (F_x [N], F_y [N], M_y [N*m]), ISO-W.
        """
        if _scalars(fz, kappa, alpha, gamma, vx):
            fz, kappa, alpha, gamma, vx = float(fz), float(kappa), float(alpha), float(gamma), float(vx)
        f = law.forces(fz, kappa, alpha, gamma, vx)
        return f.fx, f.fy, f.my

    @staticmethod
    def tire_law_aligning(law, fz, kappa, alpha, gamma, vx):
        """ISO-W aligning moment M_z [N*m] of one tire (the arguments of :meth:`tire_law`).

        Parameters
        ----------
        law : TireModel
            The law.
        fz : float or ndarray
            Normal load [N].
        kappa : float or ndarray
            Slip ratio [-].
        alpha : float or ndarray
            Slip angle [rad].
        gamma : float or ndarray
            Inclination [rad].
        vx : float or ndarray
            Signed forward speed [m/s].

        Returns
        -------
        float or ndarray
            M_z [N*m], ISO-W.
        """
        if _scalars(fz, kappa, alpha, gamma, vx):
            fz, kappa, alpha, gamma, vx = float(fz), float(kappa), float(alpha), float(gamma), float(vx)
        return law.forces(fz, kappa, alpha, gamma, vx).mz

    @staticmethod
    def tire_law_pair(law, fz_1, fz_2, kappa, alpha_1, alpha_2, gamma_1, gamma_2, vx):
        """ISO-W (F_x, F_y, M_y) of two tires at the same slip ratio and speed, from one call of the law.

        Parameters
        ----------
        law : TireModel
            The law (one call on stacked arrays; two calls on floats when every argument is a number).
        fz_1, fz_2 : float or ndarray
            Normal loads [N].
        kappa : float or ndarray
            Slip ratio of both [-].
        alpha_1, alpha_2 : float or ndarray
            Slip angles [rad].
        gamma_1, gamma_2 : float or ndarray
            Inclinations [rad] (one number where they are equal numbers).
        vx : float or ndarray
            Signed forward speed of both [m/s].

        Returns
        -------
        tuple
            (F_x, F_y, M_y of the first, F_x, F_y, M_y of the second) [N, N, N*m], ISO-W.
        """
        if _scalars(fz_1, fz_2, kappa, alpha_1, alpha_2, gamma_1, gamma_2, vx):
            f = law.forces(float(fz_1), float(kappa), float(alpha_1), float(gamma_1), float(vx))
            g = law.forces(float(fz_2), float(kappa), float(alpha_2), float(gamma_2), float(vx))
            return f.fx, f.fy, f.my, g.fx, g.fy, g.my
        gamma = gamma_1 if _scalars(gamma_1, gamma_2) and gamma_1 == gamma_2 else \
            np.stack(np.broadcast_arrays(gamma_1, gamma_2, fz_1, fz_2, kappa, alpha_1, alpha_2, vx)[:2])
        both = law.forces(np.stack(np.broadcast_arrays(fz_1, fz_2)), np.stack(np.broadcast_arrays(kappa, kappa)),
                          np.stack(np.broadcast_arrays(alpha_1, alpha_2)), gamma,
                          np.stack(np.broadcast_arrays(vx, vx)))
        return both.fx[0], both.fy[0], both.my[0], both.fx[1], both.fy[1], both.my[1]


def _tanh(x):
    """numpy's tanh of a float, as a float.

    numpy's own (SIMD) tanh differs from :func:`math.tanh` by an ulp at some points; this gives
    the number :data:`NUMPY` gives on an array.

    Parameters
    ----------
    x : float
        The argument [-].

    Returns
    -------
    float
        tanh(x) [-].
    """
    return float(np.tanh(x))


class SCALAR(_TIRE_SCALAR):
    """``xp`` of the equations on Python floats: one operating point without numpy's per-call
    overhead (a model's ``rhs`` at one state: the single track's and the full vehicle's numpy runs
    take 25-45 % less CPU so).

    The functions of :data:`vehdyn.tire.kernels.SCALAR` (:mod:`math`'s, ``where`` as a conditional,
    ``minimum``/``maximum`` NaN-propagating as numpy's), ``tanh`` numpy's (:data:`NUMPY`'s) and the
    tire hooks of :data:`NUMPY` without its checks for arrays. Where a float operation has no IEEE
    result in Python (a division by zero, a math domain or range error) it raises
    ``ArithmeticError`` or ``ValueError``: the caller then repeats the point on :data:`NUMPY`,
    whose rules give the inf or NaN. ``cos``, ``sin``, ``tan``, ``atan``, ``atan2`` and ``sqrt`` are
    the C library's, as numpy's float64 loops on a CPU without AVX-512 (there numpy may use SIMD
    forms of its own, within an ulp of them).
    """

    tanh = staticmethod(_tanh)
    atan2 = staticmethod(math.atan2)

    @staticmethod
    def tire_law(law, fz, kappa, alpha, gamma, vx):
        """ISO-W (F_x, F_y, M_y) of one tire at floats (:meth:`NUMPY.tire_law`).

        Parameters
        ----------
        law : TireModel
            The law (``law.forces`` on floats: the laws' scalar path).
        fz : float
            Normal load [N].
        kappa : float
            Slip ratio [-].
        alpha : float
            Slip angle [rad].
        gamma : float
            Inclination [rad].
        vx : float
            Signed forward speed [m/s].

        Returns
        -------
        tuple
            (F_x [N], F_y [N], M_y [N*m]), ISO-W.
        """
        f = law.forces(fz, kappa, alpha, gamma, vx)
        return f.fx, f.fy, f.my

    @staticmethod
    def tire_law_aligning(law, fz, kappa, alpha, gamma, vx):
        """ISO-W aligning moment of one tire at floats (:meth:`NUMPY.tire_law_aligning`).

        Parameters
        ----------
        law : TireModel
            The law.
        fz : float
            Normal load [N].
        kappa : float
            Slip ratio [-].
        alpha : float
            Slip angle [rad].
        gamma : float
            Inclination [rad].
        vx : float
            Signed forward speed [m/s].

        Returns
        -------
        float
            M_z [N*m], ISO-W.
        """
        return law.forces(fz, kappa, alpha, gamma, vx).mz

    @staticmethod
    def tire_law_pair(law, fz_1, fz_2, kappa, alpha_1, alpha_2, gamma_1, gamma_2, vx):
        """Two tires at floats, one call of the law each (:meth:`NUMPY.tire_law_pair`).

        Parameters
        ----------
        law : TireModel
            The law.
        fz_1, fz_2 : float
            Normal loads [N].
        kappa : float
            Slip ratio of both [-].
        alpha_1, alpha_2 : float
            Slip angles [rad].
        gamma_1, gamma_2 : float
            Inclinations [rad].
        vx : float
            Signed forward speed of both [m/s].

        Returns
        -------
        tuple
            (F_x, F_y, M_y of the first, F_x, F_y, M_y of the second) [N, N, N*m], ISO-W.
        """
        return (*SCALAR.tire_law(law, fz_1, kappa, alpha_1, gamma_1, vx),
                *SCALAR.tire_law(law, fz_2, kappa, alpha_2, gamma_2, vx))


def stack(rows) -> np.ndarray:
    """Rows of numbers or arrays as one array, the batch axis last.

    Parameters
    ----------
    rows : sequence
        Numbers or arrays that broadcast together (one per state or output).

    Returns
    -------
    ndarray
        Shape (len(rows),) for numbers, else (len(rows), *batch shape).
    """
    if all(isinstance(row, float) or np.ndim(row) == 0 for row in rows):
        return np.array(rows, dtype=float)
    shape = np.broadcast_shapes(*(np.shape(row) for row in rows))
    return np.stack([np.broadcast_to(row, shape) for row in rows])


def with_tire_hooks(xp):
    """``xp`` with the tire hooks evaluating a law's kernel on that namespace itself.

    What a symbolic namespace (:func:`vehdyn.symbolic.casadi_namespace`) needs to run the vehicle
    equations: ``tire_law`` calls :func:`vehdyn.tire.kernels.forces_kernel` for a
    :class:`~vehdyn.tire.MagicFormula` (as :meth:`MagicFormula.forces` evaluates it: the file's
    limits, its pressure, no turn slip), :func:`vehdyn.tire.kernels.linear_tire_law` for a
    :class:`~vehdyn.tire.LinearTire` (M_y = 0) and a law's own ``xp_kernel`` (brush, Fiala, Dugoff;
    M_y = 0); ``tire_law_pair`` calls it twice.

    Parameters
    ----------
    xp : type
        A namespace with the kernels' interface (:mod:`vehdyn.tire.kernels`).

    Returns
    -------
    type
        A subclass of ``xp`` with ``tire_law`` and ``tire_law_pair``; their ``law`` raises
        ParameterError, naming the law, for a law without such a kernel.
    """

    def tire_law(law, fz, kappa, alpha, gamma, vx):
        if isinstance(law, MagicFormula):
            c = law.coefficients
            f = forces_kernel(xp, c, fz, kappa, alpha, gamma, vx, c.INFLPRES, True, False)
            return f[0], f[1], f[4]
        if isinstance(law, LinearTire):
            fx, fy, _ = linear_tire_law(xp, law.coefficients, fz, kappa, alpha, gamma, vx)
            return fx, fy, 0.0 * fx
        if hasattr(law, "xp_kernel"):  # the brush, Fiala and Dugoff laws (M_y = 0), the load clipped as forces() does
            fx, fy, _ = law.xp_kernel(xp, xp.maximum(fz, 0.0), kappa, alpha, gamma, vx)
            return fx, fy, 0.0 * fx
        raise ParameterError(f"a {type(law).__name__} tire has no kernel over an xp namespace (only MagicFormula, "
                             "LinearTire and the laws with an xp_kernel have one): it cannot run on symbols",
                             key="tire", value=type(law).__name__)

    def tire_law_pair(law, fz_1, fz_2, kappa, alpha_1, alpha_2, gamma_1, gamma_2, vx):
        return (*tire_law(law, fz_1, kappa, alpha_1, gamma_1, vx), *tire_law(law, fz_2, kappa, alpha_2, gamma_2, vx))

    def tire_law_aligning(law, fz, kappa, alpha, gamma, vx):
        if isinstance(law, MagicFormula):
            c = law.coefficients
            return forces_kernel(xp, c, fz, kappa, alpha, gamma, vx, c.INFLPRES, True, False)[5]
        if isinstance(law, LinearTire):
            return linear_tire_law(xp, law.coefficients, fz, kappa, alpha, gamma, vx)[2]
        return tire_law(law, fz, kappa, alpha, gamma, vx)  # raises, naming the law

    return type(f"{xp.__name__}_VEHICLE", (xp,), {"tire_law": staticmethod(tire_law),
                                                  "tire_law_pair": staticmethod(tire_law_pair),
                                                  "tire_law_aligning": staticmethod(tire_law_aligning)})
