"""Array namespaces for the Magic Formula equations: numpy for arrays, plain floats for scalars.

The Magic Formula modules write every equation as ``xp.sin(...)``, ``xp.where(...)`` … with no
boolean-mask indexing, so that the same code runs on numpy arrays (vectorized, chunked) and on
Python floats (a single operating point without numpy's per-call overhead, ~10x faster).
:class:`ScalarOps` fails where a float operation has no IEEE result in Python (ZeroDivisionError,
a math domain ValueError, or :class:`ScalarFallback` from ``div``); the caller then repeats the
point with numpy, whose IEEE rules give the inf/nan that MFeval's MATLAB code relies on.

The float functions of :class:`ScalarOps` are also what the optional compiled backend
(:mod:`vehdyn.tire._mf_numba`) runs: numba compiles them, with ``div = div_ieee`` and the
branchless math functions of :mod:`vehdyn.tire._fast_math` in place of :mod:`math`'s, and the
equation modules themselves, into one per-point loop that LLVM vectorizes. Everything an equation
calls through ``xp`` must therefore work on Python floats, numpy arrays and under ``numba.njit``;
``xp.iterate_to_convergence`` and ``xp.radius_iterations`` tell the iterative equations whether
they may loop until convergence (numpy, floats) or must take a fixed number of steps and mark
unfinished points with NaN (a vectorized compiled loop).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["ScalarOps", "ScalarFallback", "NumpyOps", "sign_nonzero", "cos_atan"]


RADIUS_ITERATIONS = 100
"""At most this many fixed-point steps of the rolling radius (MFeval's limit)."""


def _full_broadcast(value, arrays):
    """An array of the broadcast shape of ``arrays`` (a tuple) filled with ``value``."""
    return np.full(np.broadcast_shapes(*(np.shape(a) for a in arrays)), value)


class ScalarFallback(ArithmeticError):
    """A scalar evaluation needs IEEE special values; repeat it with numpy."""


def _sin_half_angle(theta):
    """sin(theta) = 2t/(1 + t^2), t = tan(theta/2): numpy's float64 tan is vectorized (SIMD) and
    sin is not on many builds, so this is ~3x faster; within a few ulps of np.sin."""
    t = np.tan(0.5 * theta)
    return 2.0 * t / (1.0 + t * t)


def _cos_half_angle(theta):
    """cos(theta) = (1 - t^2)/(1 + t^2), t = tan(theta/2) (see :func:`_sin_half_angle`)."""
    t = np.tan(0.5 * theta)
    t2 = t * t
    return (1.0 - t2) / (1.0 + t2)


class NumpyOps:
    """numpy functions under the names the equations use."""

    sin = staticmethod(_sin_half_angle)
    cos = staticmethod(_cos_half_angle)
    tan = staticmethod(np.tan)
    atan = staticmethod(np.arctan)
    acos = staticmethod(np.arccos)
    sqrt = staticmethod(np.sqrt)
    exp = staticmethod(np.exp)
    pow = staticmethod(np.power)
    log10 = staticmethod(np.log10)
    abs = staticmethod(np.abs)
    sign = staticmethod(np.sign)
    where = staticmethod(np.where)
    minimum = staticmethod(np.minimum)
    maximum = staticmethod(np.maximum)
    clip = staticmethod(np.clip)
    copysign = staticmethod(np.copysign)
    # MATLAB max/min ignore NaN: fmax/fmin
    fmax = staticmethod(np.fmax)
    isnan = staticmethod(np.isnan)
    any = staticmethod(np.any)
    all = staticmethod(np.all)
    full_broadcast = staticmethod(_full_broadcast)
    scalar = False
    iterate_to_convergence = True  # iterations run until every point has converged (see _mf_numba.OPS_VECTOR)
    radius_iterations = RADIUS_ITERATIONS

    @staticmethod
    def div(a, b):
        return np.divide(a, b)

    div_ieee = div


def _sign(x):
    if x > 0:
        return 1.0
    if x < 0:
        return -1.0
    if x == 0:
        return 0.0
    return math.nan


class ScalarOps:
    """The same names for Python floats (math module)."""

    sin = staticmethod(math.sin)
    cos = staticmethod(math.cos)
    tan = staticmethod(math.tan)
    atan = staticmethod(math.atan)
    acos = staticmethod(math.acos)
    sqrt = staticmethod(math.sqrt)
    exp = staticmethod(math.exp)
    pow = staticmethod(math.pow)  # ValueError (-> numpy: nan) for a negative base and a fractional power
    log10 = staticmethod(math.log10)
    abs = staticmethod(abs)
    sign = staticmethod(_sign)
    copysign = staticmethod(math.copysign)
    scalar = True
    iterate_to_convergence = True
    radius_iterations = RADIUS_ITERATIONS

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
    def clip(a, low, high):
        """MATLAB's a(a < low) = low; a(a > high) = high (NaN stays NaN)."""
        if a < low:
            a = low
        return high if a > high else a

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
    def all(a):
        return bool(a)

    @staticmethod
    def full_broadcast(value, arrays):
        """``value`` itself: a single point has no shape."""
        return value

    @staticmethod
    def div(a, b):
        if b == 0:
            raise ScalarFallback("division by zero")
        return a / b

    @staticmethod
    def div_ieee(a, b):
        """a/b with IEEE results for b = 0 (nan for 0/0, signed inf otherwise)."""
        if b == 0:
            if a == 0 or a != a:
                return math.nan
            return math.copysign(math.inf, a) * math.copysign(1.0, b)
        return a / b


def sign_nonzero(xp, x):
    """sign(x) with sign(0) = +1: MFeval's guard against 0/0 in the stiffness factors B.

    Computed as copysign(1, x), which differs from MATLAB's form only for x = -0 (-1 instead of
    +1), where the guarded quantity is a zero product and the result the same.
    """
    return xp.copysign(1.0, x)


def cos_atan(xp, x):
    """cos(atan(x)) = 1/sqrt(1 + x^2), exactly in real arithmetic; cheaper than two functions
    (agrees with the composed form to a few units in the last place)."""
    return 1.0 / xp.sqrt(1.0 + x * x)
