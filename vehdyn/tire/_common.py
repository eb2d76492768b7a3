"""Helpers shared by vehdyn's tire laws: input broadcasting, lift-off, rolling direction.

Private: the laws import these; users call the laws.
"""

from __future__ import annotations

import math

import numpy as np

from .base import TireForces


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
