"""The ``xp`` namespace of the equations on CasADi symbols.

vehdyn writes its models' equations once, over an ``xp`` namespace (:mod:`vehdyn.components.xp`,
:mod:`vehdyn.tire.kernels`): numpy arrays, Python floats, numba-compiled code. :func:`casadi_namespace`
gives the same interface on CasADi's ``SX`` and ``MX`` symbols, so that calling the very same
equation functions with symbols builds their expression graph, with exact derivatives:

* ``where(c, a, b)`` is ``casadi.if_else`` (``a if c else b`` where ``c`` is a Python or numpy
  boolean, an option of the model);
* ``minimum``, ``maximum``, ``fmax`` and ``clip`` are ``fmin`` / ``fmax``; ``abs`` is ``fabs``;
  ``div`` is ``/``; ``copysign``, ``sign``, ``atan2``, ``tanh``, ... CasADi's own;
* ``any(c)`` is ``True`` for a symbolic ``c`` (the equations then take their ``where`` branch,
  which gives every point the value the numeric path gives it) and ``all(c)`` ``False``;
* the iterative equations take a fixed number of steps (``iterate_to_convergence = False``).

CasADi's ``SX`` and ``MX`` have no ``&``, ``|`` and ``~`` operators; :func:`casadi_namespace`
gives them CasADi's elementwise ``logic_and``, ``logic_or`` and ``logic_not`` (what the equations
mean by them on numpy booleans), where they are absent.

References
----------
.. [1] J. A. E. Andersson, J. Gillis, G. Horn, J. B. Rawlings and M. Diehl, "CasADi: a software
   framework for nonlinear optimization and optimal control", *Mathematical Programming
   Computation* 11(1), 1-36, 2019.
"""

from __future__ import annotations

import functools

import numpy as np

__all__ = ["casadi_namespace", "is_symbolic", "require_casadi"]


def require_casadi():
    """The ``casadi`` module, imported on first use.

    Returns
    -------
    module
        casadi.

    Raises
    ------
    ImportError
        Where casadi is not installed, saying how to install it.
    """
    try:
        import casadi
    except ImportError as error:  # pragma: no cover - the test extra installs casadi
        raise ImportError("vehdyn's symbolic forms and optimal control need casadi: "
                          "pip install 'vehdyn[optimal]'") from error
    return casadi


def is_symbolic(value) -> bool:
    """Whether ``value`` is a CasADi expression that is not a constant.

    Parameters
    ----------
    value : object
        A number, array or CasADi expression.

    Returns
    -------
    bool
    """
    ca = require_casadi()
    return isinstance(value, (ca.SX, ca.MX)) and not value.is_constant()


def _truth(value, symbolic):
    """A condition's truth where it is known (a number, an array, a constant expression), else ``symbolic``."""
    ca = require_casadi()
    if isinstance(value, (ca.SX, ca.MX, ca.DM)):
        if isinstance(value, ca.DM) or value.is_constant():
            values = np.asarray(ca.evalf(value), dtype=float)
            return bool(np.any(values != 0)) if symbolic else bool(np.all(values != 0))
        return symbolic
    return bool(np.any(value)) if symbolic else bool(np.all(value))


@functools.lru_cache(maxsize=None)
def casadi_namespace():
    """The ``xp`` namespace on CasADi symbols (built once, on first use).

    Returns
    -------
    type
        A class whose static methods are the interface of :mod:`vehdyn.components.xp` and
        :mod:`vehdyn.tire.kernels` on CasADi expressions (and on numbers).
    """
    ca = require_casadi()
    for cls in (ca.SX, ca.MX):
        for name, function in (("__and__", ca.logic_and), ("__or__", ca.logic_or)):
            if not hasattr(cls, name):
                setattr(cls, name, function)
                setattr(cls, name.replace("__", "__r", 1), lambda a, b, f=function: f(b, a))
        if not hasattr(cls, "__invert__"):
            cls.__invert__ = ca.logic_not

    def if_else(condition, a, b):
        if isinstance(condition, (bool, np.bool_)):
            return a if condition else b
        return ca.if_else(condition, a, b)

    def fclip(a, low, high):
        return ca.fmin(ca.fmax(a, low), high)

    class CASADI:
        """``xp`` on CasADi expressions."""

        sin = staticmethod(ca.sin)
        cos = staticmethod(ca.cos)
        tan = staticmethod(ca.tan)
        tanh = staticmethod(ca.tanh)
        atan = staticmethod(ca.atan)
        atan2 = staticmethod(ca.atan2)
        acos = staticmethod(ca.acos)
        sqrt = staticmethod(ca.sqrt)
        hypot = staticmethod(ca.hypot)
        exp = staticmethod(ca.exp)
        pow = staticmethod(ca.power)
        log10 = staticmethod(ca.log10)
        abs = staticmethod(ca.fabs)
        sign = staticmethod(ca.sign)
        copysign = staticmethod(ca.copysign)
        minimum = staticmethod(ca.fmin)
        maximum = staticmethod(ca.fmax)
        fmax = staticmethod(ca.fmax)
        mtimes = staticmethod(ca.mtimes)
        where = staticmethod(if_else)
        clip = staticmethod(fclip)
        scalar = False
        symbolic = True
        iterate_to_convergence = False  # a fixed number of steps (the caller says how many)
        radius_iterations = 20

        @staticmethod
        def isnan(a):
            return a != a

        @staticmethod
        def any(a):
            return _truth(a, True)

        @staticmethod
        def all(a):
            return _truth(a, False)

        @staticmethod
        def full_broadcast(value, arrays):
            return value

        @staticmethod
        def div(a, b):
            return a / b

        div_ieee = div

    return CASADI
