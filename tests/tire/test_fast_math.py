"""The branchless math functions of the compiled Magic Formula backend (vehdyn.tire._fast_math)
against the C library's (libm) functions: error in units in the last place (ulp) on dense grids and on
hypothesis-drawn arguments, and the IEEE special values (+-0, +-inf, nan)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vehdyn.tire.magic_formula import numba_available

from . import fast_math_coefficients

pytestmark = pytest.mark.skipif(not numba_available(), reason="numba is not installed")

# The reference is the C library (math's functions compiled by numba: what the rest of the compiled code
# and math call, on every CPU), not numpy's ufuncs: numpy runs SIMD kernels on CPUs with AVX-512 that
# are themselves a few ulps from the C library, and the budgets of MAX_ULP would then measure numpy's
# error as well as ours (on this AVX2 machine numpy's float64 functions are the C library's, bit for bit).
REFERENCE = {name: (lambda *args, name=name: fast(name, library=True)(*args))
             for name in ("sin", "cos", "tan", "atan", "acos", "exp", "log", "log10")}
LIBRARY = {"sin": math.sin, "cos": math.cos, "tan": math.tan, "atan": math.atan, "acos": math.acos, "exp": math.exp,
           "log": math.log, "log10": math.log10, "pow": math.pow}
MAX_ULP = {"sin": 2, "cos": 2, "tan": 4, "atan": 2, "acos": 4, "exp": 2, "log": 2, "log10": 3}
SPECIAL = np.array([0.0, -0.0, np.inf, -np.inf, np.nan, 1.0, -1.0, 5e-324, -5e-324, 1.7976931348623157e308,
                    -1.7976931348623157e308, 2.2250738585072014e-308])
_LOOPS = {}


def fast(name, library=False):
    """The function compiled into a vectorized loop over an array (as the backend uses it); with
    ``library``, the C library's function of that name (the reference)."""
    if (name, library) not in _LOOPS:
        import numba

        from vehdyn.tire import _fast_math

        function = LIBRARY[name] if library else getattr(_fast_math, "fast_" + name)
        if name == "pow":
            def loop(x, y, out):
                for i in range(x.shape[0]):
                    out[i] = function(x[i], y[i])
        else:
            def loop(x, out):
                for i in range(x.shape[0]):
                    out[i] = function(x[i])
        _LOOPS[name, library] = numba.njit(error_model="numpy")(loop)
    loop = _LOOPS[name, library]

    def call(*args):
        arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in args))
        out = np.empty(arrays[0].size)
        loop(*(np.ascontiguousarray(a).ravel() for a in arrays), out)
        return out.reshape(arrays[0].shape)

    return call


def ulp_error(ours, reference):
    """How many doubles lie between ours and the reference (0 where both are equal or nan): the suite's one
    ulp measure (tests/_tolerances.py)."""
    from tests._tolerances import ulp_distance

    return ulp_distance(ours, reference)


def grid(name):
    """Dense arguments over each function's range (and beyond where numpy gives a number)."""
    rng = np.random.default_rng(7)
    if name in ("sin", "cos", "tan"):
        near_quarter_turns = np.arange(-2000, 2001) * (np.pi / 2)
        # halfway between quarter turns, where x*2/pi rounds to either neighbour, up to |x| ~ 2^40
        halfway = (np.floor(np.logspace(0, 11.5, 20_000)) + 0.5) * (np.pi / 2)
        return np.concatenate([halfway, -halfway, np.nextafter(halfway, 0), np.nextafter(halfway, np.inf),np.linspace(-10, 10, 200_001), rng.uniform(-1e6, 1e6, 100_000),
                               np.logspace(-300, 12, 20_000), -np.logspace(-300, 12, 20_000),
                               near_quarter_turns, np.nextafter(near_quarter_turns, np.inf)])
    if name == "atan":
        return np.concatenate([np.linspace(-5, 5, 200_001), np.logspace(-320, 308, 50_000),
                               -np.logspace(-320, 308, 50_000)])
    if name == "acos":
        return np.concatenate([np.linspace(-1, 1, 200_001), 1 - np.logspace(-16, 0, 5000),
                               -1 + np.logspace(-16, 0, 5000)])
    if name == "exp":
        return np.concatenate([np.linspace(-746, 710, 400_001), rng.uniform(-1, 1, 100_000)])
    return np.concatenate([np.logspace(-323, 308, 400_001), rng.uniform(0.5, 2.0, 100_000),
                           10.0 ** np.arange(-300, 301)])


@pytest.mark.parametrize("name", list(REFERENCE))
def test_dense_grid_within_stated_ulps(name):
    x = grid(name)
    with np.errstate(all="ignore"):
        reference = REFERENCE[name](x)
    error = ulp_error(fast(name)(x), reference)
    assert error.max() <= MAX_ULP[name], (name, x[np.argmax(error)], error.max())


@pytest.mark.parametrize("name", list(REFERENCE))
def test_special_values_as_numpy(name):
    with np.errstate(all="ignore"):
        reference = REFERENCE[name](SPECIAL)
    ours = fast(name)(SPECIAL)
    if name in ("sin", "cos", "tan"):  # the largest doubles: beyond the accurate range, only bounded
        keep = np.abs(SPECIAL) < 1e300
        ours, reference = ours[keep], reference[keep]
    assert (ulp_error(ours, reference) <= MAX_ULP[name]).all(), (name, ours, reference)
    if name in ("sin", "tan", "atan"):  # odd functions keep the sign of zero
        assert math.copysign(1.0, ours[1]) == -1.0 and math.copysign(1.0, ours[0]) == 1.0


@settings(max_examples=300, deadline=None)
@given(x=st.floats(allow_nan=True, allow_infinity=True))
def test_any_double(x):
    """Every double: within the stated ulps where the reduction is exact enough (|x| < 2^40 for
    sin, cos, tan), and bounded beyond."""
    args = np.array([x])
    for name, reference_function in REFERENCE.items():
        with np.errstate(all="ignore"):
            reference = reference_function(args)
        ours = fast(name)(args)
        if name in ("sin", "cos") and abs(x) >= 2.0**40:
            assert np.isnan(ours[0]) == np.isnan(reference[0]) and (np.isnan(ours[0]) or abs(ours[0]) <= 1.0)
            continue
        if name == "tan" and abs(x) >= 2.0**40:
            continue
        assert ulp_error(ours, reference)[0] <= MAX_ULP[name], (name, x, ours[0], reference[0])


def test_pow_against_numpy():
    """x**y as the C library's pow (numpy's power on this machine): relative error 2 ulp + |y*log x|*2^-52,
    and the special cases the equations can meet (0, negative bases with integer and fractional powers,
    inf, nan)."""
    rng = np.random.default_rng(3)
    x = np.concatenate([rng.uniform(0, 10, 200_000), np.logspace(-300, 300, 10_000)])
    y = np.concatenate([rng.uniform(-3, 3, 200_000), rng.uniform(-1, 1, 10_000)])
    reference = fast("pow", library=True)(x, y)
    ours = fast("pow")(x, y)
    allowed = 2 + np.abs(y * np.log(x)) * 2.0
    assert (ulp_error(ours, reference) <= allowed).all()
    specials = np.array([0.0, -0.0, 1.0, -1.0, 2.0, -2.0, 0.5, np.inf, -np.inf, np.nan, 1e-310])
    xs, ys = np.meshgrid(specials, np.array([0.0, 1.0, -1.0, 2.0, 3.0, -3.0, 0.5, -0.5, 1 / 3, np.inf, -np.inf,
                                             np.nan]))
    with np.errstate(all="ignore"):
        reference = fast("pow", library=True)(xs, ys)
        allowed = 2 + np.nan_to_num(np.abs(ys * np.log(np.abs(xs))), posinf=0.0) * 2.0
    ours = fast("pow")(xs, ys)
    bad = ~(ulp_error(ours, reference) <= allowed)
    assert not bad.any(), list(zip(xs[bad], ys[bad], ours[bad], reference[bad]))


def test_coefficients_are_the_economized_series():
    """The literals of the module are the exact derivation rounded to doubles (re-derived here)."""
    from vehdyn.tire import _fast_math

    for name, values in fast_math_coefficients.coefficients().items():
        assert getattr(_fast_math, "_" + name) == values, name
    split = fast_math_coefficients.constants()
    assert (_fast_math._PIO2_1, _fast_math._PIO2_2, _fast_math._PIO2_3) == split["PIO2"]
    assert (_fast_math._LN2_1, _fast_math._LN2_2) == split["LN2"]
