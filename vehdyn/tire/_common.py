"""Helpers shared by vehdyn's tire laws: input checks, broadcasting, lift-off, rolling direction.

Private: the laws import these; users call the laws. The input policy they implement (non-finite
inputs give NaN at exactly those points, bools and non-numbers raise) is stated in
:mod:`vehdyn.tire.base`.
"""

from __future__ import annotations

import math

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.tire.base import TireForces, TireModel

_isfinite = math.isfinite
_finite = np.isfinite
_count_nonzero = np.count_nonzero
_concatenate = np.concatenate
_broadcast = np.broadcast

#: Names of the inputs of every law's ``forces``, in argument order.
TIRE_INPUTS = ("fz", "kappa", "alpha", "gamma", "vx")


def all_scalars(*values) -> bool:
    """True when every value is a Python (or numpy) float or int: the laws then skip numpy."""
    for v in values:
        if type(v) is not float and (not isinstance(v, (float, int)) or isinstance(v, bool)):
            return False
    return True


def finite_scalars(*values) -> bool:
    """Whether every float of ``values`` is finite.

    Hot paths test ``math.isfinite(a + b + ...)`` inline first (one sum: NaN and inf survive it)
    and call this only when that fails, for the exact answer (the sum may overflow).
    """
    return all(map(_isfinite, values))


def float_input(name: str, value) -> np.ndarray:
    """One tire input as a float array (no copy for float arrays).

    Raises
    ------
    ParameterError
        For a bool or bool array (a ``True`` where a load or slip belongs is a mistake, as in the
        parameter sets), and for anything that is not real numbers (strings, complex, None).
    """
    if type(value) is np.ndarray and value.dtype.kind == "f":
        return value
    if isinstance(value, (bool, np.bool_)):
        raise ParameterError(f"{name} must be a number, got the bool {value!r}", key=name, value=value)
    try:
        array = np.asarray(value)
    except (TypeError, ValueError):  # ragged nested sequences
        raise ParameterError(f"{name} must be numeric, got {value!r}", key=name, value=value) from None
    kind = array.dtype.kind
    if kind == "b":
        raise ParameterError(f"{name} must be numeric, got a bool array {value!r}", key=name, value=value)
    if kind in "fiu":
        return array.astype(float, copy=False)
    if kind == "O":
        try:
            return array.astype(float)
        except (TypeError, ValueError):
            pass
    raise ParameterError(f"{name} must be numeric, got {value!r}", key=name, value=value)


def load_input(fz) -> np.ndarray:
    """A normal load [N] as a float array clipped at 0 (lift-off), NaN where it is not finite."""
    fz = float_input("fz", fz)
    return np.where(np.isfinite(fz), np.maximum(fz, 0.0), np.nan)[()]


#: Up to this many values in all, the inputs are tested in one call (on a concatenated copy).
_JOINT_CHECK_SIZE = 16384


def _all_finite(arrays) -> bool:
    """Whether every element of every array is finite.

    Up to :data:`_JOINT_CHECK_SIZE` values in all, one ``isfinite`` call on their concatenation
    (on small arrays a call costs its overhead, so one call instead of one per input); beyond,
    one call per array (one pass over memory each). ``count_nonzero`` is exact (no overflow) and
    half the cost of ``.all()`` on small arrays.
    """
    if sum([a.size for a in arrays]) <= _JOINT_CHECK_SIZE:
        joint = _concatenate(arrays, axis=None)
        return _count_nonzero(_finite(joint)) == joint.size
    for a in arrays:
        if _count_nonzero(_finite(a)) != a.size:
            return False
    return True


def nonfinite_points(arrays, shape):
    """Boolean mask of the points (of the broadcast ``shape``) where any input is not finite.

    None when every input is finite, which is what the check costs on the usual path: one
    vectorized test (:func:`_all_finite`), no mask.
    """
    arrays = [a for a in arrays if a is not None]
    if _all_finite(arrays):
        return None
    bad = np.zeros(shape, dtype=bool)
    for a in arrays:
        bad |= ~_finite(a)
    return bad


def broadcast_shape(arrays, names):
    """The broadcast shape of ``arrays`` (None entries skipped); ParameterError naming the shapes."""
    present = [a for a in arrays if a is not None]
    try:
        return _broadcast(*present).shape  # C-level, a quarter of np.broadcast_shapes' cost
    except ValueError:
        shapes = {n: a.shape for n, a in zip(names, arrays) if a is not None}
        raise ParameterError(f"input shapes do not broadcast: {shapes}", key="shape", value=shapes) from None


def neutralize(arrays, bad, neutral):
    """``arrays`` broadcast to ``bad``'s shape with ``neutral`` values at the bad points.

    The laws then run on finite numbers only (no RuntimeWarnings, no special cases in the
    compiled loops) and :func:`nan_at` overwrites those points afterwards.
    """
    return [None if a is None else np.where(bad, n, a) for a, n in zip(arrays, neutral)]


def nan_at(bad, values):
    """``values`` (arrays of ``bad``'s shape) with NaN where ``bad``."""
    return tuple(np.where(bad, np.nan, v) for v in values)


def broadcast_inputs(fz, kappa, alpha, gamma, vx):
    """The five tire inputs checked and broadcast to one shape, ``fz`` clipped at 0 (lift-off).

    Returns
    -------
    arrays : tuple of ndarray
        ``(fz, kappa, alpha, gamma, vx)`` as float arrays of the broadcast shape; at non-finite
        points they hold neutral values (0, and 1 m/s for ``vx``).
    bad : ndarray of bool or None
        Where an input is not finite (the points whose outputs must be NaN), None if nowhere.
    """
    arrays = [float_input(n, v) for n, v in zip(TIRE_INPUTS, (fz, kappa, alpha, gamma, vx))]
    shape = broadcast_shape(arrays, TIRE_INPUTS)
    bad = nonfinite_points(arrays, shape)
    if bad is not None:
        fz, kappa, alpha, gamma, vx = neutralize(arrays, bad, (0.0, 0.0, 0.0, 0.0, 1.0))
    else:  # (cheaper than np.broadcast_arrays: most inputs have the shape already, the rest are one value)
        fz, kappa, alpha, gamma, vx = (a if a.shape == shape else np.full(shape, a.item()) if a.size == 1
                                       else np.broadcast_to(a, shape) for a in arrays)
    return (np.maximum(fz, 0.0), kappa, alpha, gamma, vx), bad


def rolling_direction(vx):
    """+1 rolling forwards (and at standstill), -1 in reverse: the side the contact patch is entered from."""
    return np.where(vx < 0.0, -1.0, 1.0)


def scalar_rolling_direction(vx: float) -> float:
    """:func:`rolling_direction` for one float."""
    return -1.0 if vx < 0.0 else 1.0


def planar_forces(fx, fy, fz, mz) -> TireForces:
    """TireForces of a law without overturning and rolling-resistance moments (Mx = My = 0)."""
    if isinstance(fx, float):
        return TireForces(fx, fy, fz, 0.0, 0.0, mz)
    zero = np.zeros_like(fx)
    return TireForces(fx, fy, fz, zero, zero.copy(), mz)


#: What a scalar call returns at a non-finite input.
NAN_FORCES = TireForces(*(6 * (math.nan,)))


def scalar_sign(value: float) -> float:
    """math's sign: -1, 0 or +1."""
    return math.copysign(1.0, value) if value != 0.0 else 0.0


#: Points per block of a vectorized evaluation: the temporaries of one block stay in the CPU cache.
CHUNK_POINTS = 8192


def evaluate_chunked(kernel, fz, kappa, alpha, gamma, vx) -> TireForces:
    """Apply ``kernel(fz, kappa, alpha, gamma, vx) -> (fx, fy, mz)`` block-wise over broadcast inputs.

    ``fz`` is clipped at 0 first. Inputs of more than :data:`CHUNK_POINTS` points are flattened and
    evaluated in blocks of that size, which keeps the law's temporaries in cache (about twice as
    fast at a million points as one pass over whole arrays). Points with a non-finite input come
    out NaN in every field (:func:`broadcast_inputs`).
    """
    (fz, kappa, alpha, gamma, vx), bad = broadcast_inputs(fz, kappa, alpha, gamma, vx)
    n = fz.size
    shape = fz.shape
    if n <= CHUNK_POINTS:
        # kernels work in place on arrays, so 0-d inputs go through as 1-element arrays
        fx, fy, mz = kernel(*(a.reshape(-1) for a in (fz, kappa, alpha, gamma, vx)))
        forces = planar_forces(fx.reshape(shape), fy.reshape(shape), fz, mz.reshape(shape))
    else:
        flat = [np.ascontiguousarray(a).reshape(-1) for a in (fz, kappa, alpha, gamma, vx)]
        out = np.empty((3, n))
        for start in range(0, n, CHUNK_POINTS):
            block = slice(start, start + CHUNK_POINTS)
            out[0, block], out[1, block], out[2, block] = kernel(*(a[block] for a in flat))
        forces = planar_forces(out[0].reshape(shape), out[1].reshape(shape), flat[0].reshape(shape),
                               out[2].reshape(shape))
    return forces if bad is None else TireForces(*nan_at(bad, forces))


class VectorizedTire(TireModel):
    """A tire law written twice: ``_kernel`` on arrays, ``_forces_scalar`` on floats with :mod:`math`.

    :meth:`forces` sends all-scalar calls to the scalar path (no numpy overhead, and the per-point
    baseline of ``benchmarks/bench_tire.py``) and everything else, in cache-sized blocks, to the
    kernel. Subclasses implement ``_kernel(fz, kappa, alpha, gamma, vx) -> (fx, fy, mz)`` for float
    arrays of one shape with ``fz >= 0``, and ``_forces_scalar(fz, kappa, alpha, gamma, vx)`` for
    finite floats. Both paths apply the input policy of :mod:`vehdyn.tire.base` (NaN for a
    non-finite input, ParameterError for a bool) before the law sees a number.
    """

    def forces(self, fz, kappa, alpha, gamma=0.0, vx=10.0) -> TireForces:
        """Steady-state forces and moments (ISO-W); see :meth:`TireModel.forces`."""
        if all_scalars(fz, kappa, alpha, gamma, vx):
            if not (_isfinite(fz + kappa + alpha + gamma + vx) or finite_scalars(fz, kappa, alpha, gamma, vx)):
                return NAN_FORCES
            return self._forces_scalar(float(fz), float(kappa), float(alpha), float(gamma), float(vx))
        return evaluate_chunked(self._kernel, fz, kappa, alpha, gamma, vx)

    def _kernel(self, fz, kappa, alpha, gamma, vx):
        raise NotImplementedError

    def _forces_scalar(self, fz: float, kappa: float, alpha: float, gamma: float, vx: float) -> TireForces:
        raise NotImplementedError
