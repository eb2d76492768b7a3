"""What a comparison of two computational paths can promise, in units in the last place (ulps).

Three kinds of comparison run through the suite:

(a) both sides run the same code (the same compiled loop, or the same numpy calls): bitwise
    (``np.array_equal``), on every CPU; the test says why in a comment.
(b) one side calls numpy's transcendental ufuncs, the other the C library (numba-compiled code, or
    :mod:`math`), or vehdyn's own branchless functions (``vehdyn.tire._fast_math``): numpy
    dispatches float64 ``sin``, ``cos``, ``exp``, ``log``, ``arctan``, ``power``, ``tanh`` ... to SIMD
    kernels on CPUs that have them (AVX-512, partly AVX2), which differ from the C library by a few
    ulps; so these compare with :func:`assert_close_ulps` within a budget tied to the computation.
(c) exact by construction (integers, copies, file round trips, a shortcut whose exactness is the
    point such as cos(0) = 1): exact.

Budgets of (b), used across the suite:

``ONE_CALL_ULPS`` (4)
    one transcendental call on each side: numpy's accuracy tables
    (``numpy/_core/tests/data/umath-validation-set-*.csv``) hold its float64 kernels to 1 ulp of the
    correctly rounded result (2 for ``tanh`` and ``cbrt``), glibc's libm documents 1-2 ulps for these
    functions: two libraries are at most ~3 ulps apart (measured on the AVX2 development machine:
    ``tanh`` 3, the others 0, ``tests/_perturb/dispatch_differences.py``). A wrong formula, a wrong
    constant or one float32 rounding is millions of ulps away.
``rtol`` fallback
    for a value that is the small difference of larger terms (an ill-conditioned subtraction: a
    lateral force near zero from the sum of a tire and its mirror image, a derivative that balances
    forces), the result's own ulp says nothing: the error is a few ulps *of the terms*. Such tests
    pass ``rtol`` (a multiple of the double epsilon 2.2e-16) and ``scale`` (the size of the terms).
Through an integrator
    a one-ulp difference in the right-hand side can flip one accept/reject decision of the step-size
    control; the trajectories then differ by up to the solver's local error, so those comparisons
    use a relative tolerance of a few times the solver's ``rtol`` (they use ``np.allclose`` with it).

Portability checks: ``VEHDYN_TEST_PERTURB_ULPS=2`` (tests/_perturb/sitecustomize.py) moves numpy's
transcendental results by 1-2 ulps, ``NPY_DISABLE_CPU_FEATURES`` switches numpy's SIMD off; tests of
kind (b) are marked ``compiled_vs_numpy`` and run under both in CI (``.ci/run``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["EPS", "ONE_CALL_ULPS", "ulp_distance", "assert_close_ulps"]

EPS = float(np.finfo(np.float64).eps)
"""The double epsilon, 2.2e-16: one ulp of 1.0."""

ONE_CALL_ULPS = 4
"""Budget of one transcendental call compared across math libraries (numpy SIMD vs C library)."""

_MAGNITUDE = np.int64(0x7FFFFFFFFFFFFFFF)


def ulp_distance(actual, desired) -> np.ndarray:
    """How many float64 numbers lie between ``actual`` and ``desired`` (elementwise, broadcast).

    0 for the same number (+0 and -0 included) and for NaN against NaN; inf for NaN against a number.
    An ulp here is one step between adjacent doubles, so the distance between 1.0 and
    1.0000000000000002 is 1 and between 0.9999999999999999 and 1.0000000000000002 is 2.
    """
    a, d = np.broadcast_arrays(np.asarray(actual, dtype=np.float64), np.asarray(desired, dtype=np.float64))
    a_bits, d_bits = a.view(np.int64), d.view(np.int64)
    # the bit patterns as a monotonic integer scale: -x maps to -(bits of x), both zeros to 0
    a_key = np.where(a_bits < 0, -(a_bits & _MAGNITUDE), a_bits)
    d_key = np.where(d_bits < 0, -(d_bits & _MAGNITUDE), d_bits)
    same_sign = (a_key >= 0) == (d_key >= 0)
    with np.errstate(over="ignore"):
        distance = np.where(same_sign, np.abs(a_key - np.where(same_sign, d_key, 0)).astype(np.float64),
                            np.abs(a_key).astype(np.float64) + np.abs(d_key).astype(np.float64))
    a_nan, d_nan = np.isnan(a), np.isnan(d)
    distance = np.where(a_nan | d_nan, np.inf, distance)
    return np.where(a_nan & d_nan, 0.0, distance)


def assert_close_ulps(actual, desired, *, ulps: int, what: str, rtol: float = 0.0, scale=None):
    """Assert ``actual`` equals ``desired`` within ``ulps`` units in the last place, elementwise.

    Parameters
    ----------
    actual, desired : array_like
        The two paths' results (broadcast against each other); NaN must match NaN.
    ulps : int
        The budget: the largest :func:`ulp_distance` accepted, tied to the computation (say why in
        the test: ``ONE_CALL_ULPS`` for one transcendental call on each side, more for a chain).
    what : str
        What is compared, for the failure message (e.g. ``"compiled vs numpy rhs"``).
    rtol : float, optional
        Also accept an element where ``|actual - desired| <= rtol * scale``: for values that went
        through an ill-conditioned subtraction (a small difference of larger terms), whose own ulp is
        no yardstick. 0 (default): ulps only.
    scale : float or array_like, optional
        The size of the terms of that subtraction [the values' unit]; default the largest
        ``|desired|`` of the comparison.
    """
    a, d = np.broadcast_arrays(np.asarray(actual, dtype=np.float64), np.asarray(desired, dtype=np.float64))
    distance = ulp_distance(a, d)
    ok = distance <= ulps
    if rtol:
        if scale is None:
            finite = np.abs(d[np.isfinite(d)])
            scale = finite.max() if finite.size else 0.0
        with np.errstate(invalid="ignore"):
            ok |= np.abs(a - d) <= rtol * np.asarray(scale, dtype=np.float64)
    if np.all(ok):
        return
    bad = np.flatnonzero(~ok.ravel())
    worst = bad[np.argmax(distance.ravel()[bad])]
    index = np.unravel_index(worst, a.shape) if a.ndim else ()
    budget = f"{ulps} ulps" + (f" or |difference| <= {rtol:.3g} * {np.max(scale):.6g}" if rtol else "")
    raise AssertionError(
        f"{what}: {bad.size} of {a.size} values differ by more than {budget}; the worst, at index "
        f"{tuple(int(i) for i in index)}: {float(a[index])!r} vs {float(d[index])!r} "
        f"({distance[index]:.0f} ulps apart, difference {a[index] - d[index]:.3g})")
