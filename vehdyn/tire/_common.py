"""Helpers shared by vehdyn's tire laws: input broadcasting, lift-off, rolling direction.

Private: the laws import these; users call the laws.
"""

from __future__ import annotations

import math

import numpy as np

from .base import TireForces, TireModel


def all_scalars(*values) -> bool:
    """True when every value is a Python (or numpy) float or int: the laws then skip numpy."""
    return all(isinstance(v, (float, int)) and not isinstance(v, bool) for v in values)


def broadcast_inputs(fz, kappa, alpha, gamma, vx):
    """The five tire inputs as float arrays of one broadcast shape; ``fz`` clipped at 0 (lift-off)."""
    fz, kappa, alpha, gamma, vx = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (fz, kappa, alpha, gamma, vx)))
    return np.maximum(fz, 0.0), kappa, alpha, gamma, vx


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


def scalar_sign(value: float) -> float:
    """math's sign: -1, 0 or +1."""
    return math.copysign(1.0, value) if value != 0.0 else 0.0


#: Points per block of a vectorized evaluation: the temporaries of one block stay in the CPU cache.
CHUNK_POINTS = 8192


def evaluate_chunked(kernel, fz, kappa, alpha, gamma, vx) -> TireForces:
    """Apply ``kernel(fz, kappa, alpha, gamma, vx) -> (fx, fy, mz)`` block-wise over broadcast inputs.

    ``fz`` is clipped at 0 first. Inputs of more than :data:`CHUNK_POINTS` points are flattened and
    evaluated in blocks of that size, which keeps the law's temporaries in cache (about twice as
    fast at a million points as one pass over whole arrays).
    """
    fz, kappa, alpha, gamma, vx = broadcast_inputs(fz, kappa, alpha, gamma, vx)
    n = fz.size
    shape = fz.shape
    if n <= CHUNK_POINTS:
        # kernels work in place on arrays, so 0-d inputs go through as 1-element arrays
        fx, fy, mz = kernel(*(a.reshape(-1) for a in (fz, kappa, alpha, gamma, vx)))
        return planar_forces(fx.reshape(shape), fy.reshape(shape), fz, mz.reshape(shape))
    flat = [np.ascontiguousarray(a).reshape(-1) for a in (fz, kappa, alpha, gamma, vx)]
    out = np.empty((3, n))
    for start in range(0, n, CHUNK_POINTS):
        block = slice(start, start + CHUNK_POINTS)
        out[0, block], out[1, block], out[2, block] = kernel(*(a[block] for a in flat))
    return planar_forces(out[0].reshape(shape), out[1].reshape(shape), flat[0].reshape(shape), out[2].reshape(shape))


class VectorizedTire(TireModel):
    """A tire law written twice: ``_kernel`` on arrays, ``_forces_scalar`` on floats with :mod:`math`.

    :meth:`forces` sends all-scalar calls to the scalar path (no numpy overhead, and the per-point
    baseline of ``benchmarks/bench_tire.py``) and everything else, in cache-sized blocks, to the
    kernel. Subclasses implement ``_kernel(fz, kappa, alpha, gamma, vx) -> (fx, fy, mz)`` for float
    arrays of one shape with ``fz >= 0``, and ``_forces_scalar(fz, kappa, alpha, gamma, vx)`` for floats.
    """

    def forces(self, fz, kappa, alpha, gamma=0.0, vx=10.0) -> TireForces:
        """Steady-state forces and moments (ISO-W); see :meth:`TireModel.forces`."""
        if all_scalars(fz, kappa, alpha, gamma, vx):
            return self._forces_scalar(float(fz), float(kappa), float(alpha), float(gamma), float(vx))
        return evaluate_chunked(self._kernel, fz, kappa, alpha, gamma, vx)

    def _kernel(self, fz, kappa, alpha, gamma, vx):
        raise NotImplementedError

    def _forces_scalar(self, fz: float, kappa: float, alpha: float, gamma: float, vx: float) -> TireForces:
        raise NotImplementedError
