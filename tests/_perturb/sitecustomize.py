"""Simulate another CPU's numpy: move numpy's float64 transcendental results by 1..N ulps.

numpy dispatches its float64 ``sin``, ``cos``, ``exp``, ``log``, ``arctan``, ``power``, ``tanh`` ...
to SIMD implementations on the CPUs that have the instructions (AVX-512: Intel SVML-derived
kernels; AVX2: ``tanh``), and to the C library elsewhere. Their results differ from the C
library's (which ``math`` and numba-compiled code call on every CPU) by a few units in the last
place. A test that compares a numpy result with a compiled one bit for bit therefore passes on one
CPU and fails on another.

With ``VEHDYN_TEST_PERTURB_ULPS=N`` (N >= 1) in the environment, :func:`install` replaces those
ufuncs in the ``numpy`` module by wrappers that move every float64 result by +-1..N ulps, chosen
deterministically from the result's bits (so the same input always gives the same output, as a
real library does: numpy-vs-numpy comparisons stay bitwise). A test session run so sees what a
machine whose numpy differs from the C library by up to N ulps would see. ``tests/conftest.py``
installs it before vehdyn is imported and puts this folder on ``PYTHONPATH``, so that Python
subprocesses the tests start (the CLI, process pools, Dask workers) import this file as their
``sitecustomize`` and run on the same perturbed numpy.

What it reaches: every call that looks the function up in the ``numpy`` module at call time
(``np.sin(x)``, ``xp.sin`` with ``xp = numpy``) or that bound it after installation (the
``staticmethod(np.tan)`` of vehdyn's array namespaces, ``from numpy import exp`` in vehdyn or
scipy, imported later). What it cannot reach: the ``**`` operator on arrays (ndarray's number
protocol calls the power ufunc internally), numpy's own Python functions that bound the ufuncs when
numpy was imported (``np.sinc``, ``np.angle``, ``np.hanning`` ...), compiled code (C, Fortran,
BLAS/LAPACK, numba: numba-compiled functions that call ``np.sin`` still get the original ufunc,
registered here under the wrapper), and ``math``.

Left exact (not moved): infinities, NaN, zeros, and the results whose mathematical value is a
representable number (cos(0) = 1, exp(0) = 1, log(1) = 0, arctan2(0, x > 0) = 0, power(x, 0) = 1,
power(x, 1) = x, power(2, 3) = 8 ...): every implementation accurate to < 1 ulp returns those exactly,
and the shortcuts of the compiled code rely on them. Results that only round to such a number
(cos(pi) = -1 + 1.9e-33, tanh(20) = 1 - 8e-18) are moved, inward where the function is bounded
(sin, cos, tanh within [-1, 1], arctan within [-pi/2, pi/2] ...): a faithful kernel may return
-0.9999999999999999 for cos(pi).
"""

from __future__ import annotations

import importlib.abc
import importlib.util
import os
import sys

import numpy as np

ENV = "VEHDYN_TEST_PERTURB_ULPS"

# float64 ufuncs with SIMD kernels in numpy 2.x (loops_umath_fp, loops_trigonometric,
# loops_exponent_log, loops_hyperbolic dispatch sources): the functions whose results depend on the CPU.
# sqrt, +, -, *, / are correctly rounded (IEEE 754) on every CPU and are not moved.
UFUNCS = ("sin", "cos", "tan", "arcsin", "arccos", "arctan", "arctan2", "sinh", "cosh", "tanh", "arcsinh",
          "arccosh", "arctanh", "exp", "exp2", "expm1", "log", "log2", "log10", "log1p", "cbrt", "power")

_LARGEST_FINITE_BITS = 0x7FEFFFFFFFFFFFFF
_HALF_PI, _PI = 1.5707963267948966, 3.141592653589793
RANGES = {"sin": (-1.0, 1.0), "cos": (-1.0, 1.0), "tanh": (-1.0, 1.0), "arcsin": (-_HALF_PI, _HALF_PI),
          "arctan": (-_HALF_PI, _HALF_PI), "arccos": (0.0, _PI), "arctan2": (-_PI, _PI)}
"""The ranges of the bounded functions: a result that a shift would move out of its range is moved the
other way (no library returns |cos| > 1)."""
_ZERO_EXACT = ("sin", "tan", "arcsin", "arctan", "sinh", "tanh", "arcsinh", "arctanh", "expm1", "log1p",
               "cbrt")  # f(0) = 0, and f(x) = x rounded for a tiny x (cbrt: only at 0 and +-1)
_FLAT_AT_ONE = ("cos", "cosh", "exp", "exp2")  # f(0) = 1, and 1 rounded for a tiny x
_ONE_EXACT = ("arccos", "arccosh", "log", "log2", "log10")  # f(1) = 0
_TINY = 2.0**-27  # x^2 / 2 < 2^-55: below half an ulp of 1 and of x's own ulp in sin(x) ~ x - x^3/6
_NO_MASK = np.zeros(0, dtype=bool)
_POWER = getattr(np.power, "_ufunc", np.power)  # the real ones, also if this module is loaded again
_LOG = getattr(np.log, "_ufunc", np.log)
_LONGDOUBLE_IS_WIDER = np.finfo(np.longdouble).nmant > np.finfo(np.float64).nmant


class PerturbedUfunc:
    """A numpy ufunc whose float64 results are moved by +-1..``ulps`` units in the last place."""

    def __init__(self, ufunc, ulps: int):
        self._ufunc = ufunc
        self._ulps = int(ulps)
        self.__name__ = ufunc.__name__
        self.__module__ = "numpy"
        self.__doc__ = ufunc.__doc__

    def __call__(self, *args, **kwargs):
        operands = args[: self._ufunc.nin]
        if kwargs.get("out") is not None:  # in place (np.expm1(a, out=a)): keep the operands for _exact
            operands = tuple(np.array(a, copy=True) if isinstance(a, np.ndarray) else a for a in operands)
        result = self._ufunc(*args, **kwargs)
        if isinstance(result, tuple) or kwargs.get("where", True) is not True:
            return result  # not used with these ufuncs by vehdyn; left alone rather than half-perturbed
        return nudge(self._ufunc.__name__, result, operands, self._ulps)

    def __getattr__(self, name):  # reduce, outer, at, nin, types, ... of the real ufunc (not perturbed)
        return getattr(self._ufunc, name)

    def __repr__(self):
        return f"<ufunc {self._ufunc.__name__!r} perturbed by +-1..{self._ulps} ulps>"

    def __reduce__(self):  # pickled as the global numpy.<name>, as numpy pickles a ufunc
        return self.__name__


def _exact(name, operands, result):
    """Where every library returns the same result, which is not moved: a boolean array of ``result``'s
    shape, or None (nowhere).

    * the mathematical result is a representable number (sin(0) = 0, cos(0) = 1, exp(0) = 1,
      log(1) = 0, power(x, 0) = 1, power(x, 1) = x, power(2, 3) = 8, log2(8) = 3 ...), which every
      library accurate to < 1 ulp returns exactly; arctan2's only such results, +-0, are never moved;
    * the function is flat there to the last bit, and the result is its leading term: f(x) = x for a
      tiny x (sin, tan, arctan, tanh ..., whose x^3 term is far below half an ulp), f(x) = 1 for a tiny
      x (cos, cosh, exp, and power with |y log x| tiny);
    * saturation: tanh(x) = +-1 for |x| > 19.1 (1 - tanh(x) = 2 exp(-2x) < 5.3e-17, less than half the
      gap below 1) and arctan(x) = +-pi/2 rounded for |x| > 2^53.
    """
    x = operands[0]
    if name == "power":
        y = operands[1]
        exact = (x == 1.0) | (x == 0.0) | (y == 0.0) | (y == 1.0)
        integer = (y == np.round(y)) & (np.abs(y) <= 64)
        with np.errstate(all="ignore"):
            if integer.any():  # x**n is exact where it equals the wider (80-bit on x86) power
                wide = _POWER(x.astype(np.longdouble), y.astype(np.longdouble))
                exact = exact | (integer & (wide == result) & _LONGDOUBLE_IS_WIDER)
            if (result == 1.0).any():
                exact = exact | ((result == 1.0) & (np.abs(y * _LOG(x)) < _TINY))
    elif name in _ONE_EXACT:
        exact = x == 1.0
        if name == "log2":
            exact = exact | (np.frexp(x)[0] == 0.5)
        elif name == "log10":
            exact = exact | np.isin(x, 10.0 ** np.arange(23))
    elif name in _ZERO_EXACT or name in _FLAT_AT_ONE:
        exact = result == x if name in _ZERO_EXACT else x == 0.0  # f(0) = 0 among those
        if name in _FLAT_AT_ONE:
            exact = exact | ((result == 1.0) & (np.abs(x) < _TINY))
        if name == "exp2":
            exact = exact | (x == np.round(x))
        elif name == "tanh":
            exact = exact | (np.abs(x) > 19.1)
        elif name == "arctan":
            exact = exact | (np.abs(x) > 2.0**53)
    else:
        return None
    return exact if exact.shape == np.shape(result) else np.broadcast_to(exact, np.shape(result))


def _move(bits, values, exact, ulps, low, high):
    """Move the float64 ``values`` (``bits``: their int64 view, 1-D) in place by 1..``ulps`` ulps where
    finite, nonzero and not ``exact`` (a mask of their size, or empty: nowhere); ``low`` <= ``high``: the
    function's range (:data:`RANGES`), else unbounded. Compiled by numba once numba is imported."""
    for i in range(bits.size):
        b = bits[i]
        magnitude = b & 0x7FFFFFFFFFFFFFFF
        if magnitude <= ulps or magnitude >= _LARGEST_FINITE_BITS - ulps or (exact.size and exact[i]):
            continue  # zero, the smallest subnormals, inf, nan, an exact result
        k = (magnitude >> 1) % (2 * ulps)  # the low mantissa bits: as good as random for these functions
        shift = k - ulps if k < ulps else k - ulps + 1  # -ulps..-1, 1..ulps, each equally often
        bits[i] = b + shift  # int64 arithmetic on the bit pattern: |shift| doubles away, outward if > 0
        if low <= high and (values[i] < low or values[i] > high):
            bits[i] = b - shift


def _move_numpy(bits, values, exact, ulps, low, high):
    """:func:`_move` in numpy operations (before numba is imported, or without it)."""
    magnitude = bits & np.int64(0x7FFFFFFFFFFFFFFF)
    movable = (magnitude > ulps) & (magnitude < _LARGEST_FINITE_BITS - ulps)
    if exact.size:
        movable &= ~exact
    k = (magnitude >> 1) % (2 * ulps)
    shift = np.where(k < ulps, k - ulps, k - ulps + 1)
    moved = bits + shift
    if low <= high:
        as_float = moved.view(np.float64)
        moved = np.where((as_float < low) | (as_float > high), bits - shift, moved)
    np.copyto(bits, moved, where=movable)


_COMPILED = []


def _move_loop():
    """:func:`_move` compiled (~1 s, once per process; not cached: the cache would tie it to one module
    name) once numba has been imported by someone else (a subprocess that never imports numba must not
    find it imported), else :func:`_move_numpy`."""
    if _COMPILED:
        return _COMPILED[0]
    if "numba" not in sys.modules:
        return _move_numpy
    import numba

    _COMPILED.append(numba.njit(nogil=True)(_move))
    return _COMPILED[0]


def nudge(name, result, operands, ulps: int):
    """``result`` (ndarray or numpy scalar) of ufunc ``name`` applied to ``operands``, with its float64
    entries moved by 1..``ulps`` ulps (in place for an array) except where every library returns the same
    (:func:`_exact`).

    The shift is a function of the result's magnitude (its low mantissa bits), so that the same input
    always gives the same output and odd and even functions stay exactly odd and even (sin(-x) = -sin(x),
    arctan2(-y, x) = -arctan2(y, x)), as every library keeps them.
    """
    if not isinstance(result, (np.ndarray, np.floating)) or result.dtype != np.float64:
        return result  # a pandas object, complex, float32...: left alone
    scalar = not isinstance(result, np.ndarray)
    values = np.array(result) if scalar else result
    try:
        operands = [np.asarray(a, dtype=np.float64) for a in operands]
    except (TypeError, ValueError):  # an operand that is no array of numbers
        return result
    exact = _exact(name, operands, values)
    flat = values if values.flags.c_contiguous else np.ascontiguousarray(values)
    flat = flat.reshape(-1)
    mask = _NO_MASK if exact is None or not exact.any() else np.ascontiguousarray(exact).reshape(-1)
    low, high = RANGES.get(name, (1.0, -1.0))
    _move_loop()(flat.view(np.int64), flat, mask, ulps, low, high)
    if not values.flags.c_contiguous:
        values[...] = flat.reshape(values.shape)
    return values[()] if scalar else values


def _register_with_numba(pairs):
    """Make numba compile ``np.<name>`` to the original ufunc where it finds the wrapper there."""
    from numba.core.registry import cpu_target
    from numba.core.typing.templates import Registry
    from numba.np import ufunc_db

    typing = cpu_target.typing_context
    typing.refresh()
    registry = Registry()
    for wrapper, ufunc in pairs:
        try:
            registry.register_global(wrapper, typing.resolve_value_type(ufunc))
        except ValueError:  # a ufunc numba does not support: compiled code cannot call it anyway
            pass
    typing.install_registry(registry)
    ufunc_db.get_ufuncs()
    cpu_target.target_context.refresh()


class _AfterNumbaImport(importlib.abc.MetaPathFinder):
    """Runs :func:`_register_with_numba` when numba is first imported (this module must not import
    numba itself: a test checks that vehdyn imports it only on demand)."""

    def __init__(self, pairs):
        self.pairs = pairs

    def find_spec(self, fullname, path=None, target=None):
        if fullname != "numba":
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec("numba")
        if spec is not None and spec.loader is not None:
            execute, pairs = spec.loader.exec_module, self.pairs

            def exec_module(module):
                execute(module)
                _register_with_numba(pairs)

            spec.loader.exec_module = exec_module
        return spec


def installed() -> int:
    """The ulps numpy's ufuncs are perturbed by in this process (0: not perturbed)."""
    return getattr(np, "_vehdyn_perturbed_ulps", 0)


def install(ulps: int) -> list[str]:
    """Replace the ufuncs of :data:`UFUNCS` (under every name numpy exports them) by perturbed ones.

    Returns the numpy attribute names replaced. Idempotent for the same ``ulps``.
    """
    ulps = int(ulps)
    if ulps < 1:
        raise ValueError(f"{ENV} must be an integer >= 1, got {ulps}")
    if installed():
        if installed() != ulps:
            raise RuntimeError(f"numpy is already perturbed by {installed()} ulps, not {ulps}")
        return list(np._vehdyn_perturbed_names)
    wrappers = {getattr(np, name): PerturbedUfunc(getattr(np, name), ulps) for name in UFUNCS}
    replaced = []
    for name in dir(np):  # the array-API aliases too: np.atan, np.atan2, np.pow, np.asin ...
        value = getattr(np, name, None)
        if isinstance(value, np.ufunc) and value in wrappers:
            setattr(np, name, wrappers[value])
            replaced.append(name)
    pairs = [(w, u) for u, w in wrappers.items()]
    if "numba" in sys.modules:
        _register_with_numba(pairs)
    else:
        sys.meta_path.insert(0, _AfterNumbaImport(pairs))
    np._vehdyn_perturbed_ulps = ulps
    np._vehdyn_perturbed_names = tuple(sorted(replaced))
    return sorted(replaced)


def install_from_environment() -> int:
    """Install with the ulps of ``VEHDYN_TEST_PERTURB_ULPS`` if it is set (and not 0); return them."""
    text = os.environ.get(ENV, "").strip()
    if not text or text == "0":
        return 0
    try:
        ulps = int(text)
    except ValueError:
        raise ValueError(f"{ENV} must be an integer >= 1, got {text!r}") from None
    install(ulps)
    return ulps


if __name__ == "sitecustomize":  # a subprocess of a perturbed test session
    install_from_environment()
