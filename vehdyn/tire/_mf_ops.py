"""Array namespaces for the Magic Formula equations: numpy for arrays, plain floats for scalars.

The Magic Formula modules write every equation as ``xp.sin(...)``, ``xp.where(...)`` … with no
boolean-mask indexing, so that the same code runs on numpy arrays (vectorized, chunked) and on
Python floats (a single operating point without numpy's per-call overhead, ~10x faster).
:class:`ScalarOps` raises :class:`ScalarFallback` where a float operation would fail (division by
zero, a math domain error); the caller then repeats the point with numpy, whose IEEE rules give
the inf/nan that MFeval's MATLAB code relies on.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["ScalarOps", "ScalarFallback", "NumpyOps", "sign_nonzero"]


class ScalarFallback(ArithmeticError):
    """A scalar evaluation needs IEEE special values; repeat it with numpy."""


class NumpyOps:
    """numpy functions under the names the equations use."""

    sin = staticmethod(np.sin)
    cos = staticmethod(np.cos)
    tan = staticmethod(np.tan)
    atan = staticmethod(np.arctan)
    acos = staticmethod(np.arccos)
    sqrt = staticmethod(np.sqrt)
    exp = staticmethod(np.exp)
    log10 = staticmethod(np.log10)
    abs = staticmethod(np.abs)
    sign = staticmethod(np.sign)
    where = staticmethod(np.where)
    minimum = staticmethod(np.minimum)
    maximum = staticmethod(np.maximum)
    # MATLAB max/min ignore NaN: fmax/fmin
    fmax = staticmethod(np.fmax)
    isnan = staticmethod(np.isnan)
    any = staticmethod(np.any)
    scalar = False

    @staticmethod
    def div(a, b):
        return np.divide(a, b)


def _sign(x):
    if x > 0:
        return 1.0
    if x < 0:
        return -1.0
    if x == 0:
        return 0.0
    return math.nan


def _checked(function):
    def wrapped(*args):
        try:
            return function(*args)
        except (ValueError, OverflowError, ZeroDivisionError) as exc:
            raise ScalarFallback(str(exc)) from None

    return staticmethod(wrapped)


class ScalarOps:
    """The same names for Python floats (math module)."""

    sin = _checked(math.sin)
    cos = _checked(math.cos)
    tan = _checked(math.tan)
    atan = staticmethod(math.atan)
    acos = _checked(math.acos)
    sqrt = _checked(math.sqrt)
    exp = _checked(math.exp)
    log10 = _checked(math.log10)
    abs = staticmethod(abs)
    sign = staticmethod(_sign)
    scalar = True

    @staticmethod
    def where(condition, a, b):
        return a if condition else b

    @staticmethod
    def minimum(a, b):
        if a != a or b != b:
            return math.nan
        return a if a <= b else b

    @staticmethod
    def maximum(a, b):
        if a != a or b != b:
            return math.nan
        return a if a >= b else b

    @staticmethod
    def fmax(a, b):
        if a != a:
            return b
        if b != b:
            return a
        return a if a >= b else b

    @staticmethod
    def isnan(a):
        return a != a

    @staticmethod
    def any(a):
        return bool(a)

    @staticmethod
    def div(a, b):
        if b == 0:
            raise ScalarFallback("division by zero")
        return a / b


def sign_nonzero(xp, x):
    """sign(x) with sign(0) = +1 (MFeval's guard against 0/0 in the stiffness factors B)."""
    return xp.where(x == 0, 1.0, xp.sign(x))
