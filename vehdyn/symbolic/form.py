"""A model's right-hand side and outputs as CasADi functions (:func:`to_casadi`)."""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.symbolic.namespace import casadi_namespace, require_casadi

__all__ = ["SymbolicModel", "to_casadi"]


class SymbolicModel:
    r"""A model's equations as CasADi functions: what :func:`to_casadi` returns.

    .. math::

        \dot x = f(x, u, p), \qquad y = g(x, u, p)

    built from the model's own equation functions on CasADi ``SX`` symbols.

    Parameters
    ----------
    model : Model
        The model.
    rhs : casadi.Function
        ``rhs(x, u)`` or, with parameters, ``rhs(x, u, p)`` -> dx/dt [SI units per second].
    output : casadi.Function
        ``output(x, u[, p])`` -> y [SI units of the outputs].
    jacobians : casadi.Function
        ``jacobians(x, u[, p])`` -> (df/dx, df/du, dg/dx, dg/du), exact.
    parameter_names : tuple of str
        The names of ``p``'s entries, in order (empty: no ``p``).
    parameter_values : ndarray
        The model's own values of them [their units].

    Attributes
    ----------
    state_names, input_names, output_names : tuple of str
        The model's signal names, in the order of x, u and y.

    References
    ----------
    .. [1] J. A. E. Andersson et al., "CasADi: a software framework for nonlinear optimization and
       optimal control", *Mathematical Programming Computation* 11(1), 1-36, 2019.

    Examples
    --------
    >>> from vehdyn import LinearModel
    >>> from vehdyn.symbolic import to_casadi
    >>> lag = LinearModel([[-1.0]], [[2.0]], [[1.0]], [[0.0]], states=["v"], inputs=["force"], outputs=["v_out"])
    >>> m = to_casadi(lag)
    >>> float(m.rhs([1.0], [0.25])), m.state_names
    (-0.5, ('v',))
    >>> [float(j) for j in m.jacobians([1.0], [0.25])]
    [-1.0, 2.0, 1.0, 0.0]
    """

    def __init__(self, model, rhs, output, jacobians, parameter_names=(), parameter_values=()):
        self.model = model
        self.rhs = rhs
        self.output = output
        self.jacobians = jacobians
        self.parameter_names = tuple(parameter_names)
        self.parameter_values = np.asarray(parameter_values, dtype=float)
        self.state_names = tuple(model.state_names)
        self.input_names = tuple(model.input_names)
        self.output_names = tuple(model.output_names)

    @property
    def n_states(self) -> int:
        """Number of states."""
        return len(self.state_names)

    @property
    def n_inputs(self) -> int:
        """Number of inputs."""
        return len(self.input_names)

    @property
    def n_outputs(self) -> int:
        """Number of outputs."""
        return len(self.output_names)

    def index(self, name: str, kind: str = "states") -> int:
        """Position of a signal (the model's :meth:`~vehdyn.Model.index`).

        Parameters
        ----------
        name : str
            Signal name.
        kind : str
            ``"states"``, ``"inputs"`` or ``"outputs"``.

        Returns
        -------
        int
        """
        return self.model.index(name, kind)

    def arguments(self, x, u, p=None) -> tuple:
        """``(x, u)`` or ``(x, u, p)`` for the functions (``p`` defaults to the model's values).

        Parameters
        ----------
        x : array_like or casadi expression
            States [SI units].
        u : array_like or casadi expression
            Inputs [SI units].
        p : array_like or casadi expression, optional
            Parameters [their units].

        Returns
        -------
        tuple
        """
        if not self.parameter_names:
            return (x, u)
        return (x, u, self.parameter_values if p is None else p)

    def linear_matrices(self, x0, u0, p=None) -> tuple:
        """Exact (A, B, C, D) at a point.

        Parameters
        ----------
        x0 : array_like
            States [SI units].
        u0 : array_like
            Inputs [SI units].
        p : array_like, optional
            Parameters (default: the model's) [their units].

        Returns
        -------
        tuple of ndarray
            df/dx, df/du, dg/dx, dg/du.
        """
        values = self.jacobians(*self.arguments(np.asarray(x0, float), np.asarray(u0, float), p))
        return tuple(np.array(m, dtype=float) for m in values)


def to_casadi(model, parameters=()) -> SymbolicModel:
    """A model's right-hand side and outputs as ``casadi.Function`` objects, from its own equations.

    Parameters
    ----------
    model : Model
        A model with a symbolic form (:meth:`vehdyn.Model.symbolic_equations`): every
        ``LinearModel`` (the bicycle, the lateral-yaw-roll models), the single track and the full
        vehicle with Magic Formula or linear tires (every option but a road or friction that is a
        function of position).
    parameters : sequence of str
        Model parameters to make a third argument ``p`` of the functions (e.g. ``"mass"``,
        ``"yaw_inertia"``), for identification and robust design; empty: none.

    Returns
    -------
    SymbolicModel
        ``rhs``, ``output`` and ``jacobians`` functions and the signal names.

    Raises
    ------
    ParameterError
        For a model without a symbolic form (naming it and the missing method), a piece of it without
        one (e.g. a tire law of the user's own without an ``xp_kernel``, naming it), or a parameter the
        model does not take symbolically.
    ImportError
        Without casadi.
    """
    ca = require_casadi()
    names = (parameters,) if isinstance(parameters, str) else tuple(parameters)
    for name in names:
        if not isinstance(name, str):
            raise ParameterError(f"parameters must be names (str), got {name!r}", key="parameters", value=name)
    if len(set(names)) != len(names):
        raise ParameterError(f"parameters names one twice: {names}", key="parameters", value=names)
    method = getattr(model, "symbolic_equations", None)
    if method is None:
        raise ParameterError(f"{type(model).__name__} has no symbolic form: it does not define "
                             "symbolic_equations(xp, x, u, parameters)", key="model", value=type(model).__name__)
    x = ca.SX.sym("x", model.n_states)
    u = ca.SX.sym("u", model.n_inputs)
    p = ca.SX.sym("p", len(names))
    symbols = {name: p[i] for i, name in enumerate(names)}
    result = method(casadi_namespace(), x, u, symbols)
    if result is NotImplemented:
        raise ParameterError(f"{type(model).__name__} has no symbolic form: it does not define "
                             "symbolic_equations(xp, x, u, parameters)", key="model", value=type(model).__name__)
    rates, outputs, values = result
    f, y = _column(ca, rates), _column(ca, outputs)
    if f.shape != (model.n_states, 1) or y.shape != (model.n_outputs, 1):
        raise ParameterError(f"{type(model).__name__}.symbolic_equations returned {f.shape[0]} rates and "
                             f"{y.shape[0]} outputs for {model.n_states} states and {model.n_outputs} outputs",
                             key="model", value=type(model).__name__)
    args, labels = ([x, u, p], ["x", "u", "p"]) if names else ([x, u], ["x", "u"])
    rhs = ca.Function("rhs", args, [f], labels, ["dxdt"])
    output = ca.Function("output", args, [y], labels, ["y"])
    jacobians = ca.Function("jacobians", args, [ca.jacobian(f, x), ca.jacobian(f, u), ca.jacobian(y, x),
                                                ca.jacobian(y, u)], labels, ["A", "B", "C", "D"])
    return SymbolicModel(model, rhs, output, jacobians, names, [float(values[n]) for n in names])


def _column(ca, rows):
    """Rows (expressions, numbers) or a column as one SX column."""
    if isinstance(rows, (ca.SX, ca.DM)):
        return ca.SX(rows)
    return ca.vertcat(*(ca.SX(r) if not isinstance(r, ca.SX) else r for r in rows)) if len(rows) else ca.SX(0, 1)
