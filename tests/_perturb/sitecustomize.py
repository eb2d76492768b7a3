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
_ZERO_EXACT = ("sin", "tan", "arcsin", "arctan", "sinh", "tanh", "arcsinh", "arctanh", "expm1", "log1p", "cbrt",
               "cos", "cosh", "exp", "exp2")  # f(0) = 0 or 1
_ONE_EXACT = ("arccos", "arccosh", "log", "log2", "log10")  # f(1) = 0
_NO_MASK = np.zeros(0, dtype=bool)
_NO_FLOAT = np.zeros(0)


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
    """Where the mathematical result of ufunc ``name`` is a representable number, which every library
    accurate to < 1 ulp returns exactly and which is therefore never moved: sin(0) = 0, cos(0) = 1,
    exp(0) = 1, log(1) = 0, log2(8) = 3, power(x, 0) = 1, power(x, 1) = x, and x^n for an integer n
    wherever the bits of x's mantissa allow it to be representable (power(2, 3) = 8). A boolean array
    of ``result``'s shape, or None (nowhere; arctan2's only such results, +-0, are zeros, never moved).

    Everything else is moved, also where the mathematical result only rounds to a simple number
    (cos(pi) = -1 + 1.9e-33, tanh(20) = 1 - 8e-18, tan(1e-10) = 1e-10 + 3e-31): a kernel within numpy's
    specification (1-2 ulps) may return a neighbour there, and a test must not rely on it.
    """
    x = operands[0]
    if name == "power":
        y = operands[1]
        exact = (x == 1.0) | (x == 0.0) | (y == 0.0) | (y == 1.0)
        with np.errstate(all="ignore"):
            integer = (y == np.round(y)) & (np.abs(y) <= 1024) & np.isfinite(x)
            if integer.any():  # x = m 2^e, m odd with b bits: x^n has at least (b - 1) n + 1 bits
                odd = (np.frexp(np.abs(x))[0] * 2.0**53).astype(np.int64)
                b = 53 - np.log2((odd & -odd).astype(np.float64))  # 53 less the trailing zeros
                maybe = np.where(y >= 0, (b - 1) * y + 1 <= 53, b == 1)  # 1 / x^n: x a power of two
                exact = exact | (integer & maybe)  # (where x^n may be representable: never moved)
    elif name in _ONE_EXACT:
        exact = x == 1.0
        if name == "log2":
            exact = exact | (np.frexp(x)[0] == 0.5)
        elif name == "log10":
            exact = exact | np.isin(x, 10.0 ** np.arange(23))
    elif name in _ZERO_EXACT:
        exact = x == 0.0
        if name == "exp2":
            exact = exact | (x == np.round(x))
    else:
        return None
    return exact if exact.shape == np.shape(result) else np.broadcast_to(exact, np.shape(result))


# how the compiled loop judges exactness from the operand x (see _exact); 0: from a mask
_CODES = {**{name: 1 for name in _ZERO_EXACT if name != "exp2"}, **{name: 2 for name in _ONE_EXACT[:3]}}


def _move(bits, values, x, y, exact, code, ulps, low, high):
    """Move the float64 ``values`` (``bits``: their int64 view, 1-D) in place by 1..``ulps`` ulps where
    finite, nonzero and not exact: judged from the operand ``x`` by ``code`` (:func:`_exact`'s rules:
    1 exact at x = 0, 2 at x = 1, 3: power with the one non-integer exponent ``y``, exact at x = 0, 1) or,
    for code 0, by the mask ``exact`` (empty: nowhere); ``low`` <= ``high``: the function's range
    (:data:`RANGES`), else unbounded. Compiled by numba once numba is imported."""
    for i in range(bits.size):
        b = bits[i]
        magnitude = b & 0x7FFFFFFFFFFFFFFF
        if magnitude <= ulps or magnitude >= _LARGEST_FINITE_BITS - ulps:
            continue  # zero, the smallest subnormals, inf, nan
        if code == 0:
            if exact.size and exact[i]:
                continue
        elif (code == 1 and x[i] == 0.0) or (code == 2 and x[i] == 1.0) or (code == 3 and (x[i] == 0.0 or x[i] == 1.0)):
            continue
        k = (magnitude >> 1) % (2 * ulps)  # the low mantissa bits: as good as random for these functions
        shift = k - ulps if k < ulps else k - ulps + 1  # -ulps..-1, 1..ulps, each equally often
        bits[i] = b + shift  # int64 arithmetic on the bit pattern: |shift| doubles away, outward if > 0
        if low <= high and (values[i] < low or values[i] > high):
            bits[i] = b - shift


def _move_numpy(bits, values, x, y, exact, code, ulps, low, high):
    """:func:`_move` in numpy operations (before numba is imported, or without it); ``exact`` a mask."""
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
    find it imported), else None."""
    if _COMPILED:
        return _COMPILED[0]
    if "numba" not in sys.modules:
        return None
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
    if type(result) is np.float64:
        values = np.array(result)
    elif type(result) is np.ndarray and result.dtype == np.float64:
        values = result
    else:
        return result  # a pandas object, complex, float32...: left alone
    try:
        operands = [np.asarray(a, dtype=np.float64) for a in operands]
    except (TypeError, ValueError):  # an operand that is no array of numbers
        return result
    contiguous = values.flags.c_contiguous
    flat = (values if contiguous else np.ascontiguousarray(values)).reshape(-1)
    low, high = RANGES.get(name, (1.0, -1.0))
    loop = _move_loop()
    code = _CODES.get(name, 0)
    y = 0.0
    if name == "power" and operands[1].ndim == 0:  # one exponent: its exact cases judged here
        y = float(operands[1])
        if y == 0.0 or y == 1.0:
            return result
        code = 3 if y != round(y) or abs(y) > 1024 else 0
    if loop is not None and code and operands[0].shape == values.shape:
        x = operands[0] if operands[0].flags.c_contiguous else np.ascontiguousarray(operands[0])
        loop(flat.view(np.int64), flat, x.reshape(-1), y, _NO_MASK, code, ulps, low, high)
    else:
        exact = _exact(name, operands, values)
        mask = _NO_MASK if exact is None else np.ascontiguousarray(exact).reshape(-1)
        (loop or _move_numpy)(flat.view(np.int64), flat, _NO_FLOAT, 0.0, mask, 0, ulps, low, high)
    if not contiguous:
        values[...] = flat.reshape(values.shape)
    return values if values is result else values[()]


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
