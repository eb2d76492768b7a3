"""Derivation of the polynomial coefficients and split constants of :mod:`vehdyn.tire._fast_math`.

Exact rational arithmetic (``fractions``): the Taylor series of each reduced function, truncated
far beyond double precision, is re-expanded in Chebyshev polynomials on the reduced interval
(Chebyshev economization; near-minimax) and cut to the degree used; the coefficients are then
rounded to doubles. pi (Machin's formula) and ln 2 (atanh series) to ~500 bits give the
Cody-Waite splits. ``python tests/tire/fast_math_coefficients.py`` prints the literals;
``test_fast_math.py`` checks that the module's literals are these.
"""

from __future__ import annotations

from fractions import Fraction as F
from math import factorial

TAYLOR_TERMS = 40

# name: (series of the reduced remainder, lower and upper end of its variable, degree kept)
SPECS = {
    "SIN": (lambda k: F((-1) ** k, factorial(2 * k + 1)), 1, (F(0), F(62, 100)), 6),  # (sin r/r - 1)/z, z = r^2
    "COS": (lambda k: F((-1) ** k, factorial(2 * k)), 2, (F(0), F(62, 100)), 5),  # (cos r - 1 + z/2)/z^2
    "EXP": (lambda k: F(1, factorial(k)), 2, (F(-3466, 10000), F(3466, 10000)), 10),  # (e^r - 1 - r)/r^2
    "ATAN": (lambda k: F((-1) ** k, 2 * k + 1), 1, (F(0), F(1717, 10000)), 10),  # (atan r/r - 1)/z
    "LOG": (lambda k: F(2, 2 * k + 1), 1, (F(0), F(2945, 100000)), 6),  # (log((1+s)/(1-s)) - 2s)/(s w)
}


def _multiply(p, q):
    out = [F(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def _substitute(p, offset, scale):
    """p(offset + scale*u) as a polynomial in u (ascending coefficients)."""
    out, power = [F(0)] * len(p), [F(1)]
    for a in p:
        for i, x in enumerate(power):
            out[i] += a * x
        power = _multiply(power, [offset, scale])
    return out


def _chebyshev_basis(n):
    basis = [[F(1)], [F(0), F(1)]]
    for _ in range(2, n + 1):
        doubled = [F(0)] + [2 * x for x in basis[-1]]
        previous = basis[-2] + [F(0)] * (len(doubled) - len(basis[-2]))
        basis.append([x - y for x, y in zip(doubled, previous)])
    return basis


def economize(series, low, high, degree):
    """Coefficients (ascending, exact) of the degree-``degree`` Chebyshev economization of the
    polynomial ``series`` on [low, high], and the bound on what was dropped."""
    middle, half = (low + high) / 2, (high - low) / 2
    in_u = _substitute(series, middle, half)
    basis = _chebyshev_basis(len(in_u) - 1)
    chebyshev, rest = [F(0)] * len(in_u), list(in_u)
    for k in range(len(in_u) - 1, -1, -1):
        chebyshev[k] = rest[k] / basis[k][k]
        for i, t in enumerate(basis[k]):
            rest[i] -= chebyshev[k] * t
    kept = [F(0)] * (degree + 1)
    for k in range(degree + 1):
        for i, t in enumerate(basis[k]):
            kept[i] += chebyshev[k] * t
    return _substitute(kept, -middle / half, 1 / half), sum(abs(x) for x in chebyshev[degree + 1:])


def coefficients():
    """{name: tuple of doubles} for every polynomial of the module."""
    out = {}
    for name, (term, first, (low, high), degree) in SPECS.items():
        series = [term(k) for k in range(first, TAYLOR_TERMS)]
        exact, _ = economize(series, low, high, degree)
        out[name] = tuple(float(x) for x in exact)
    return out


def _arctan_inverse(n, terms):
    """atan(1/n) as a Fraction (alternating series)."""
    x, total, power = F(1, n), F(0), F(1, n)
    for k in range(terms):
        total += F((-1) ** k, 2 * k + 1) * power
        power *= x * x
    return total


def constants():
    """pi/2 as three doubles and ln 2 as two (each the rounded remainder of the ones before)."""
    pi = 16 * _arctan_inverse(5, 120) - 4 * _arctan_inverse(239, 60)
    ln2 = 2 * sum(F(1, (2 * k + 1) * 3 ** (2 * k + 1)) for k in range(160))

    def split(value, parts):
        out = []
        for _ in range(parts):
            out.append(float(value))
            value -= F(out[-1])
        return tuple(out)

    return {"PIO2": split(pi / 2, 3), "LN2": split(ln2, 2)}


if __name__ == "__main__":
    for name, values in {**coefficients(), **constants()}.items():
        print(f"_{name} = ({', '.join(repr(v) for v in values)})")
