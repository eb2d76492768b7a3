"""The model contract: named states, inputs and outputs, ``rhs(t, x, u)`` and ``output(t, x, u)``.

A vehdyn model is a :class:`Model` subclass that declares its signals and implements the two pure
functions. Nothing else is needed for it to simulate (:func:`vehdyn.simulate`), linearize
(:meth:`Model.linearize`), and export to python-control (:meth:`Model.to_control`)::

    class Pendulum(vehdyn.Model):
        states = ("angle", "angular_rate")
        inputs = ("torque",)
        outputs = ("angle",)

        def rhs(self, t, x, u):
            angle, rate = x
            (torque,) = u
            return np.stack([rate, -9.81 * np.sin(angle) + torque])

        def output(self, t, x, u):
            return x[:1]

Arrays follow one shape rule: ``x`` is ``(n_states,)`` or ``(n_states, n_batch)``, ``u`` likewise
with ``n_inputs`` rows, and ``rhs``/``output`` return arrays with the same trailing batch axis, so
that one call advances many variants of a model (parameters may be arrays that broadcast against
the batch axis).
"""

from __future__ import annotations

from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import numpy as np

from vehdyn.errors import ParameterError, SimulationError
from vehdyn.signals import Signal, as_signals, names_of

if TYPE_CHECKING:  # pragma: no cover
    from vehdyn.model import LinearModel

__all__ = ["Model", "PHENOMENA", "signal_vector", "float_array"]

#: The vocabulary of :attr:`Model.phenomena` (see DESIGN section 6, the fidelity ladder).
PHENOMENA = frozenset(
    {
        "longitudinal",
        "lateral",
        "yaw",
        "roll",
        "pitch",
        "heave",
        "wheel_hop",
        "wheel_lift",
        "wheel_spin",
        "load_transfer",
        "tire_saturation",
        "tire_lag",
        "road_input",
        "aero",
        "steering",
    }
)

_SIGNAL_KINDS = ("states", "inputs", "outputs")


def float_array(value: Any, key: str) -> np.ndarray:
    """``value`` as a float ndarray, or a ParameterError naming ``key`` when it is not numeric.

    Numbers, booleans and arrays of them convert; strings (even numeric ones such as ``"1.5"``, the
    sign of a text column read by mistake), complex numbers, dates, ragged sequences and objects
    without a float value are refused. Finiteness is left to the caller, which knows what to name.

    Parameters
    ----------
    value : object
        A number, or a (nested) sequence or array of numbers [any unit].
    key : str
        The argument's name, for the error message and ``ParameterError.key``.

    Returns
    -------
    ndarray
        ``value`` as float (not copied when it already is a float array).

    Raises
    ------
    ParameterError
        When ``value`` is not numeric.

    Examples
    --------
    >>> from vehdyn.model import float_array
    >>> float_array([1, 2], "x0")
    array([1., 2.])
    >>> float_array("1.5", "rtol")
    Traceback (most recent call last):
    ...
    vehdyn.errors.ParameterError: rtol must be numeric, got <U3 '1.5'
    """
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):  # a ragged sequence
        raise ParameterError(f"{key} must be numeric, got {value!r}", key=key, value=value) from None
    kind = arr.dtype.kind
    if kind in "biuf":
        return arr.astype(float, copy=False)
    if kind == "O":
        try:
            out = arr.astype(float)
        except (TypeError, ValueError):
            pass
        else:
            if not any(isinstance(v, (str, bytes, complex)) for v in arr.flat):
                return out
    raise ParameterError(f"{key} must be numeric, got {arr.dtype} {value!r}", key=key, value=value)


def signal_vector(values: Any, signals: Sequence[Signal], kind: str, *, default: float = 0.0) -> np.ndarray:
    """Build a vector (or a batch of vectors) over ``signals`` from user input.

    Parameters
    ----------
    values : None, mapping, scalar or array_like
        The entries [each in its signal's unit]: ``None`` gives ``default`` everywhere; a mapping
        ``{name: value}`` sets the named entries (the others take ``default``); an array must have
        ``len(signals)`` rows.
    signals : sequence of Signal
        The signals the vector runs over.
    kind : str
        Used in error messages (``"x0"``, ``"u0"``).
    default : float
        The value of entries not given [each in its signal's unit].

    Returns
    -------
    ndarray
        Shape ``(n,)`` or ``(n, n_batch)``, dtype float.

    Raises
    ------
    ParameterError
        On an unknown name, a wrong length or a non-finite value.
    """
    n = len(signals)
    names = names_of(signals)
    if values is None:
        return np.full(n, float(default))
    if isinstance(values, Mapping):
        unknown = [k for k in values if k not in names]
        if unknown:
            raise ParameterError(
                f"{kind}: unknown name {unknown[0]!r}; the names are {list(names)}",
                key=kind,
                value=unknown[0],
            )
        entries = [float_array(values.get(name, default), f"{kind}.{name}") for name in names]
        try:
            shape = np.broadcast_shapes(*(e.shape for e in entries)) if entries else ()
        except ValueError:
            raise ParameterError(f"{kind}: the values' shapes {[e.shape for e in entries]} (over {list(names)}) "
                                 "do not broadcast to one batch", key=kind, value=[e.shape for e in entries]) from None
        out = np.stack([np.broadcast_to(e, shape) for e in entries]) if entries else np.zeros((0,))
    else:
        out = np.array(float_array(values, kind))
        if out.ndim == 0 and n == 1:
            out = out.reshape(1)
        if out.ndim == 0 or out.shape[0] != n:
            raise ParameterError(
                f"{kind}: expected {n} values (one per {list(names)}), got shape {np.shape(values)}",
                key=kind,
                value=values,
            )
    if not np.all(np.isfinite(out)):
        bad = int(np.argwhere(~np.isfinite(out.reshape(n, -1)))[0, 0])
        raise ParameterError(
            f"{kind}: value of {names[bad]!r} is not finite ({out.reshape(n, -1)[bad]})",
            key=f"{kind}.{names[bad]}",
            value=out.reshape(n, -1)[bad],
        )
    return out


class Model:
    r"""Base class of every vehdyn model.

    Subclasses declare ``states``, ``inputs`` and ``outputs`` (names or :class:`~vehdyn.Signal`
    objects, as class attributes or set in ``__init__`` through :meth:`declare`) and implement
    :meth:`rhs` and, where outputs are declared, :meth:`output`. A model with no declared outputs
    outputs its states.

    Attributes
    ----------
    states, inputs, outputs : tuple of Signal
        The named signals.
    phenomena : frozenset of str
        What the model represents, drawn from :data:`PHENOMENA`.
    domain : mapping of str to (float, float)
        Bounds ``(low, high)`` of states, by name, outside which the model's equations do not hold
        (e.g. a vehicle rolled over). :func:`vehdyn.simulate` checks them on accepted steps only
        and raises :meth:`domain_error` at the first crossing; an adaptive solver's rejected trial
        stage may lie outside (``rhs`` returns NaN there, so that the step is rejected). Empty by
        default.

    Notes
    -----
    A model is the initial-value problem

    .. math::

        \dot x = f(t, x, u), \qquad y = g(t, x, u),

    with :meth:`rhs` = f and :meth:`output` = g, pure functions of numpy arrays that accept a
    trailing batch axis. The model contract is DESIGN section 3; its signal names come from one
    glossary (:data:`vehdyn.signals.GLOSSARY`).

    Examples
    --------
    A 1500 kg car coasting against aerodynamic drag, dv/dt = (F - c v|v|) / m: declare the
    signals, write the equation, and the model simulates, linearizes and exports.

    >>> import numpy as np
    >>> import vehdyn
    >>> class CoastDown(vehdyn.Model):
    ...     states = ("longitudinal_velocity",)
    ...     inputs = ("drive_force",)
    ...     phenomena = frozenset({"longitudinal", "aero"})
    ...
    ...     def __init__(self, mass=1500.0, drag=0.4):
    ...         self.mass, self.drag = mass, drag
    ...
    ...     def rhs(self, t, x, u):
    ...         (v,), (force,) = x, u
    ...         return np.stack([(force - self.drag * v * np.abs(v)) / self.mass])
    >>> car = CoastDown()
    >>> car.state_names, car.inputs[0].unit
    (('longitudinal_velocity',), 'N')
    >>> linear = car.linearize(x0={"longitudinal_velocity": 30.0})   # about 30 m/s
    >>> round(float(linear.A[0, 0]), 6), round(float(linear.B[0, 0]), 9)   # -2 c v / m, 1 / m
    (-0.016, 0.000666667)
    >>> result = vehdyn.simulate(car, np.linspace(0.0, 10.0, 11), x0=[30.0], method="RK45")
    >>> round(float(result["longitudinal_velocity"][-1]), 3)            # 30 / (1 + c 30 t / m)
    27.778
    """

    states: tuple[Signal, ...] = ()
    inputs: tuple[Signal, ...] = ()
    outputs: tuple[Signal, ...] = ()
    phenomena: frozenset[str] = frozenset()
    domain: Mapping[str, tuple[float, float]] = MappingProxyType({})

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        for kind in _SIGNAL_KINDS:
            if kind in cls.__dict__:
                setattr(cls, kind, as_signals(cls.__dict__[kind], kind))
        unknown = set(cls.phenomena) - PHENOMENA
        if unknown:
            raise ParameterError(
                f"{cls.__name__}.phenomena: unknown entries {sorted(unknown)}; "
                f"the vocabulary is {sorted(PHENOMENA)}",
                key="phenomena",
                value=sorted(unknown),
            )

    # ------------------------------------------------------------------ declaration helpers
    def declare(self, *, states=None, inputs=None, outputs=None) -> None:
        """Set the instance's signals (for models whose signals depend on their options).

        Parameters
        ----------
        states, inputs, outputs : sequence of str or Signal, optional
            The signals to set (names get the glossary's units); ``None`` leaves a kind as it is.
        """
        if states is not None:
            self.states = as_signals(states, "states")
        if inputs is not None:
            self.inputs = as_signals(inputs, "inputs")
        if outputs is not None:
            self.outputs = as_signals(outputs, "outputs")

    @property
    def has_declared_outputs(self) -> bool:
        return len(self.outputs) > 0

    @property
    def output_signals(self) -> tuple[Signal, ...]:
        """The outputs, or the states for a model that declares no outputs."""
        return self.outputs if self.outputs else self.states

    @property
    def state_names(self) -> tuple[str, ...]:
        return names_of(self.states)

    @property
    def input_names(self) -> tuple[str, ...]:
        return names_of(self.inputs)

    @property
    def output_names(self) -> tuple[str, ...]:
        return names_of(self.output_signals)

    @property
    def n_states(self) -> int:
        return len(self.states)

    @property
    def n_inputs(self) -> int:
        return len(self.inputs)

    @property
    def n_outputs(self) -> int:
        return len(self.output_signals)

    def index(self, name: str, kind: str = "states") -> int:
        """Position of a signal among the model's states, inputs or outputs.

        Parameters
        ----------
        name : str
            The signal's name.
        kind : {"states", "inputs", "outputs"}
            Where to look.

        Returns
        -------
        int
            The row of the signal in ``x``, ``u`` or ``y``.

        Raises
        ------
        ParameterError
            When the model has no such signal (the message lists those it has).
        """
        names = {"states": self.state_names, "inputs": self.input_names, "outputs": self.output_names}[kind]
        try:
            return names.index(name)
        except ValueError:
            raise ParameterError(
                f"{type(self).__name__} has no {kind[:-1]} named {name!r}; its {kind} are {list(names)}",
                key=kind,
                value=name,
            ) from None

    # ------------------------------------------------------------------ the contract
    def rhs(self, t, x, u):
        """State derivative dx/dt: the model's equations of motion.

        Parameters
        ----------
        t : float or ndarray
            Time [s] (an array of the batch's length where outputs are computed for many instants
            at once).
        x : ndarray
            States, shape (n_states,) or (n_states, n_batch) [each state's unit].
        u : ndarray
            Inputs, shape (n_inputs,) or (n_inputs, n_batch) [each input's unit].

        Returns
        -------
        ndarray
            dx/dt with the shape of ``x`` [each state's unit per second].
        """
        raise NotImplementedError(f"{type(self).__name__} must implement rhs(t, x, u)")

    def output(self, t, x, u):
        """Outputs y = g(t, x, u); the default returns the states (for models without outputs).

        Parameters
        ----------
        t : float or ndarray
            Time [s] (an array of the batch's length when simulate computes every instant in one
            call).
        x : ndarray
            States, shape (n_states,) or (n_states, n_batch) [each state's unit].
        u : ndarray
            Inputs, shape (n_inputs,) or (n_inputs, n_batch) [each input's unit].

        Returns
        -------
        ndarray
            Outputs, shape (n_outputs,) or (n_outputs, n_batch) [each output's unit].
        """
        if self.outputs:
            raise NotImplementedError(
                f"{type(self).__name__} declares outputs and must implement output(t, x, u)"
            )
        return np.asarray(x, dtype=float)

    def domain_error(self, name: str, value: float, time: float) -> SimulationError:
        """The error :func:`vehdyn.simulate` raises when a state leaves :attr:`domain`.

        Override it to say what the crossing means for the model (a vehicle rolled over, a wheel
        lifted off for good).

        Parameters
        ----------
        name : str
            The state that left the domain.
        value : float
            Its value (or the bound it crossed) [the state's unit].
        time : float
            When [s].

        Returns
        -------
        SimulationError
            With ``time`` and ``signal`` set.
        """
        low, high = self.domain[name]
        return SimulationError(f"{name} = {value:.4g} at t = {time:.6g} s leaves {type(self).__name__}'s domain "
                               f"[{low:.4g}, {high:.4g}]", time=float(time), signal=name)

    def jacobian(self, t, x, u):
        """Analytic Jacobians at a point, or ``None`` (the default).

        Override to give :meth:`linearize` exact derivatives (and the implicit ``solve_ivp``
        methods their Jacobian); the default makes it use finite differences.

        Parameters
        ----------
        t : float
            Time [s].
        x : ndarray
            States (n_states,) [each state's unit].
        u : ndarray
            Inputs (n_inputs,) [each input's unit].

        Returns
        -------
        tuple of ndarray or None
            ``(A, B, C, D)`` = (df/dx, df/du, dg/dx, dg/du) at ``(t, x, u)``, or None.
        """
        return None

    def compiled_rhs(self):
        """The right-hand side compiled for ``simulate(..., backend="compiled")``, or ``None`` (default).

        A model that has one returns a :class:`vehdyn.simulation.compiled.CompiledModel` ``(rhs, output,
        key, args)``: numba-compiled ``rhs(t, x, u, args, dxdt)`` writing dx/dt of one vehicle (1-D
        ``x``, ``u``) into ``dxdt`` and ``output(t, x, u, args, y)`` (or None), a short name of their
        source (for the compiled-code cache) and the tuple of numbers they read. It raises
        :class:`~vehdyn.ParameterError` when its present configuration has no compiled form.
        """
        return None

    def symbolic_equations(self, xp, x, u, parameters):
        """The model's equations on symbols, for :func:`vehdyn.symbolic.to_casadi`; ``NotImplemented`` (default).

        A model that has a symbolic form calls the same equation functions as :meth:`rhs` and
        :meth:`output` with the symbolic namespace ``xp``.

        Parameters
        ----------
        xp : type
            The symbolic namespace (:func:`vehdyn.symbolic.casadi_namespace`).
        x : casadi.SX
            The states, a column of symbols [each state's unit].
        u : casadi.SX
            The inputs, a column of symbols [each input's unit].
        parameters : dict
            Model parameters to take as symbols, by name [their units].

        Returns
        -------
        tuple or NotImplemented
            ``(rates, outputs, values)``: dx/dt and y (sequences of expressions, or columns) and the
            model's own numeric value of each parameter named in ``parameters`` (a dict).
        """
        return NotImplemented

    # ------------------------------------------------------------------ services
    def state_vector(self, values=None, **named) -> np.ndarray:
        """A state vector from a mapping or array (``None`` is zeros); keywords set named states.

        Parameters
        ----------
        values : None, mapping or array_like
            The states [each in its signal's unit] (see :func:`signal_vector`).
        **named
            States by name, e.g. ``longitudinal_velocity=20.0``.

        Returns
        -------
        ndarray
            Shape (n_states,) or (n_states, n_batch).
        """
        if named:
            values = {**(values or {}), **named}
        return signal_vector(values, self.states, "x0")

    def input_vector(self, values=None, **named) -> np.ndarray:
        """An input vector from a mapping or array (``None`` is zeros); keywords set named inputs.

        Parameters
        ----------
        values : None, mapping or array_like
            The inputs [each in its signal's unit] (see :func:`signal_vector`).
        **named
            Inputs by name, e.g. ``front_steer_angle=0.01``.

        Returns
        -------
        ndarray
            Shape (n_inputs,) or (n_inputs, n_batch).
        """
        if named:
            values = {**(values or {}), **named}
        return signal_vector(values, self.inputs, "u0")

    def linearize(self, x0=None, u0=None, t: float = 0.0, method: str = "auto") -> "LinearModel":
        r"""Linearize about the operating point ``(x0, u0)`` at time ``t``.

        Parameters
        ----------
        x0, u0 : mapping, array_like or None
            Operating point (by name or as arrays) [each signal's unit]; ``None`` is zeros.
        t : float
            Time [s].
        method : str
            ``"auto"`` (the model's :meth:`jacobian` where it gives one, else finite differences),
            ``"finite_difference"``, or ``"exact"``: the Jacobians of the model's symbolic form
            (:func:`vehdyn.symbolic.to_casadi`, needs casadi), exact to rounding.

        Returns
        -------
        LinearModel
            Matrices of the deviation system dx' = A dx + B du, dy = C dx + D du, with every
            signal name kept and the operating point in ``x_op``, ``u_op``, ``y_op``.

        Notes
        -----
        The deviation system is the first-order Taylor expansion about the operating point,

        .. math::

            A = \frac{\partial f}{\partial x}, \quad B = \frac{\partial f}{\partial u}, \quad
            C = \frac{\partial g}{\partial x}, \quad D = \frac{\partial g}{\partial u}
            \quad \text{at } (t, x_0, u_0).

        With ``method="exact"`` the Jacobians are CasADi's algorithmic derivatives of the model's
        own equations (time-invariant models: ``t`` is not read). Otherwise they come from
        :meth:`jacobian` where a model provides them, else from a fourth-order central difference, all perturbed points evaluated in one batched call,

        .. math::

            f'(z) \approx \frac{f(z - 2h) - 8 f(z - h) + 8 f(z + h) - f(z + 2h)}{12 h}

        (Fornberg 1988). The
        step of each variable z_i is h_i = eps**(1/5) * max(|z_i|, 1), which balances truncation
        (O(h^4)) against rounding (O(eps |f| / h)) for well-scaled variables: the Jacobian is then
        accurate to about 1e-12 relative to the size of f for smooth models, and to 1e-9 of it in
        the worst case of strong cancellation.

        References
        ----------
        .. [1] B. Fornberg, "Generation of finite difference formulas on arbitrarily spaced grids",
           *Mathematics of Computation* 51(184), 699-706, 1988.
        """
        from vehdyn.model import LinearModel

        x0 = self.state_vector(x0)
        u0 = self.input_vector(u0)
        if x0.ndim != 1 or u0.ndim != 1:
            raise ParameterError("linearize: x0 and u0 must be single points, not batches", key="x0", value=x0.shape)
        if method not in ("auto", "finite_difference", "exact"):
            raise ParameterError(f"method must be 'auto', 'finite_difference' or 'exact', got {method!r}",
                                 key="method", value=method)
        y0 = np.asarray(self.output(t, x0, u0), dtype=float)
        jac = self.jacobian(t, x0, u0) if method == "auto" else None
        if method == "exact":
            from vehdyn.symbolic import to_casadi

            A, B, C, D = to_casadi(self).linear_matrices(x0, u0)
        elif jac is None:
            A, B, C, D = self._finite_difference_jacobian(t, x0, u0)
        else:
            A, B, C, D = (np.asarray(m, dtype=float) for m in jac)
        return LinearModel(
            A,
            B,
            C,
            D,
            states=self.states,
            inputs=self.inputs,
            outputs=self.output_signals,
            x_op=x0,
            u_op=u0,
            y_op=y0,
            name=f"{type(self).__name__} linearized",
        )

    def _finite_difference_jacobian(self, t, x0, u0):
        n, m = x0.size, u0.size
        z0 = np.concatenate([x0, u0])
        h = np.finfo(float).eps ** 0.2 * np.maximum(np.abs(z0), 1.0)
        # Four-point central stencil: f'(z) ~ [f(z-2h) - 8 f(z-h) + 8 f(z+h) - f(z+2h)] / (12 h)
        offsets = np.array([-2.0, -1.0, 1.0, 2.0])
        weights = np.array([1.0, -8.0, 8.0, -1.0]) / 12.0
        k = n + m
        Z = np.repeat(z0[:, None], 4 * k, axis=1)
        cols = np.arange(4 * k)
        var = cols // 4
        # Exact representable steps: (z + s h) - z
        Z[var, cols] = z0[var] + offsets[cols % 4] * h[var]
        steps = Z[var, cols] - z0[var]
        X, U = Z[:n], Z[n:]
        F = np.asarray(self.rhs(t, X, U), dtype=float)
        G = np.asarray(self.output(t, X, U), dtype=float)
        if F.shape != (n, 4 * k) or G.shape != (self.n_outputs, 4 * k):
            raise ParameterError(
                f"{type(self).__name__}.rhs/output must accept a trailing batch axis: for x of shape "
                f"{X.shape} they returned {F.shape} and {G.shape}",
                key="rhs",
                value=F.shape,
            )
        # derivative = sum_s w_s f(z + s h) / h, with the exact step sizes per variable
        scale = weights[cols % 4] * offsets[cols % 4] / steps  # w_s / h, with h = step / s exact
        JF = (F * scale).reshape(n, k, 4).sum(axis=2)
        JG = (G * scale).reshape(self.n_outputs, k, 4).sum(axis=2)
        return JF[:, :n], JF[:, n:], JG[:, :n], JG[:, n:]

    def to_control(self, name: str | None = None, **kwargs):
        """This model as a ``control.NonlinearIOSystem`` with every signal name.

        python-control is imported here, not when vehdyn is imported.

        Parameters
        ----------
        name : str, optional
            The system's name (default: the class name).
        **kwargs
            Passed to ``control.NonlinearIOSystem`` (e.g. ``dt``).

        Returns
        -------
        control.NonlinearIOSystem
            Its update function is :meth:`rhs`, its output function :meth:`output`; states,
            inputs and outputs carry the model's names.
        """
        import control as ct

        return ct.NonlinearIOSystem(
            lambda t, x, u, params: np.asarray(self.rhs(t, np.asarray(x, float), np.asarray(u, float))),
            lambda t, x, u, params: np.asarray(self.output(t, np.asarray(x, float), np.asarray(u, float))),
            states=list(self.state_names),
            inputs=list(self.input_names),
            outputs=list(self.output_names),
            name=name or type(self).__name__,
            **kwargs,
        )

    def __repr__(self) -> str:
        return (
            f"<{type(self).__name__}: {self.n_states} states {list(self.state_names)}, "
            f"{self.n_inputs} inputs, {self.n_outputs} outputs>"
        )
