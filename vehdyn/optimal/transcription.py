"""Direct multiple shooting of a model's symbolic form (:class:`Problem`), solved by IPOPT."""

from __future__ import annotations

import tempfile
import time as _time

import numpy as np

from vehdyn.errors import ParameterError, SimulationError
from vehdyn.params.checks import finite_number
from vehdyn.symbolic import require_casadi, to_casadi

__all__ = ["Problem", "Solution", "OptimalControlError"]

_SUCCESS = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
_HESSIANS = ("exact", "gauss-newton", "limited-memory")


class OptimalControlError(SimulationError):
    """IPOPT did not find a solution: its status, the horizon and the constraint violated most.

    Parameters
    ----------
    message : str
        What failed.
    status : str
        IPOPT's return status (e.g. ``"Infeasible_Problem_Detected"``).
    horizon : tuple of float
        The grid's first and last value [s, or the unit of the state it runs along].
    constraint : str
        The constraint violated most at IPOPT's last point (name, node and grid value).
    violation : float
        By how much [the constraint's unit].

    Attributes
    ----------
    status, horizon, constraint, violation
        As given.
    """

    def __init__(self, message, *, status, horizon, constraint, violation):
        super().__init__(message)
        self.status, self.horizon, self.constraint, self.violation = status, horizon, constraint, violation


class Solution:
    """A solved problem: the trajectory at the nodes, and how the solver got there.

    Parameters
    ----------
    problem : Problem
        The problem solved.
    grid : ndarray
        The nodes' independent variable (N + 1,) [s, or the unit of the state the grid runs along].
    time : ndarray
        Time at the nodes (N + 1,) [s].
    states : ndarray
        (n_states, N + 1) [each state's unit].
    inputs : ndarray
        Every input of the model on each interval (n_inputs, N), piecewise constant [each input's unit].
    outputs : ndarray
        (n_outputs, N + 1), at each node with the input of the interval it starts (the last: the last
        interval's) [each output's unit].
    cost : float
        The cost's value [its unit].
    status : str
        IPOPT's return status.
    iterations : int
        IPOPT iterations.
    solve_time : float
        Wall time of the solver call [s].
    raw : dict
        The solver's primal and dual solution (``x``, ``lam_x``, ``lam_g``): a warm start.
    """

    def __init__(self, problem, grid, time, states, inputs, outputs, cost, status, iterations, solve_time, raw):
        self.problem, self.grid, self.time = problem, grid, time
        self.states, self.inputs, self.outputs = states, inputs, outputs
        self.cost, self.status, self.iterations, self.solve_time, self.raw = cost, status, iterations, solve_time, raw

    def __getitem__(self, name: str) -> np.ndarray:
        """A signal by name: a state or output at the nodes, an input on the intervals, or ``"time"``."""
        model = self.problem.model
        if name == "time":
            return self.time
        for names, values in ((model.state_names, self.states), (model.output_names, self.outputs),
                              (model.input_names, self.inputs)):
            if name in names:
                return values[names.index(name)]
        raise ParameterError(f"{name!r} is not a signal of {type(model).__name__}", key="name", value=name)

    def input_signals(self) -> dict:
        """The controls as :class:`~vehdyn.PiecewiseSignal` inputs of ``simulate`` (held after the end): a replay.

        Returns
        -------
        dict
            ``{control name: PiecewiseSignal}`` in time from the solution's start [each input's unit].
        """
        from vehdyn.piecewise_signal import PiecewiseSignal

        ends = np.append(self.time[1:-1], np.inf)
        return {name: PiecewiseSignal(np.column_stack([self.time[:-1], ends, self[name], np.zeros((ends.size, 4))]))
                for name in self.problem.controls}

    def input_at(self, t) -> np.ndarray:
        """Every input at times ``t``: the piecewise-constant inputs of the solution (held after its end).

        Parameters
        ----------
        t : array_like
            Times [s] from the start of the solution.

        Returns
        -------
        ndarray
            (n_inputs, len(t)) [each input's unit].
        """
        k = np.clip(np.searchsorted(self.time, np.asarray(t, dtype=float), side="right") - 1, 0,
                    self.inputs.shape[1] - 1)
        return self.inputs[:, k]


class _Signals:
    """The signals at one node, by name, as CasADi expressions (outputs computed on first use)."""

    def __init__(self, problem, k):
        self._problem, self._k, self._outputs = problem, k, None

    def __getitem__(self, name):
        p, k = self._problem, self._k
        interval = min(k, p.intervals - 1)
        if name == "time":
            return p._time(k)
        if name in p.model.state_names:
            return p._X[p.model.state_names.index(name), k]
        if name in p.model.input_names:
            return p._input_vector(interval)[p.model.input_names.index(name)]
        if name in p.model.output_names:
            if self._outputs is None:
                self._outputs = p.form.output(p._X[:p.n_states, k], p._input_vector(interval))
            return self._outputs[p.model.output_names.index(name)]
        if name.endswith("_rate") and name[:-5] in p.controls:
            i = p.controls.index(name[:-5])
            before = p._U[i, interval - 1] if interval > 0 else p._u_initial[i]
            # the step from the previous control: the previous interval, or the first one's length at the start
            step = p._time(interval) - p._time(interval - 1) if interval > 0 else p._time(1) - p._time(0)
            return (p._U[i, interval] - before) / step
        raise ParameterError(f"{name!r} is not a signal of {type(p.model).__name__} (states, inputs, outputs, "
                             "'time', or '<control>_rate')", key="name", value=name)


class Problem:
    r"""An optimal-control problem over a model's own equations, transcribed by direct multiple shooting.

    .. math::

        \min_{u}\; \phi(s(T)) + \int_0^T L(s(t))\,dt \quad \text{s.t.}\quad \dot x = f(x, u),\;
        x(0) = x_0,\; s_{\min} \le s(t) \le s_{\max},\; c_{\min} \le c(s(t)) \le c_{\max}

    with s the model's signals (states, inputs, outputs, input rates, time). The grid has ``intervals``
    intervals, in time (``duration``) or along a state (``along``, ``span``: the grid is that state's
    values, the equations divided by its rate, time a further state); each interval is integrated by
    ``substeps`` classical Runge-Kutta steps of the model's symbolic form; the controls are constant
    on an interval; bounds and constraints hold at the nodes. Build, then :meth:`solve` (the program
    is built once, on the first solve: a receding horizon re-solves it from new initial states).

    Parameters
    ----------
    model : Model
        A model with a symbolic form (:func:`vehdyn.symbolic.to_casadi`).
    intervals : int
        N, the number of intervals (>= 1).
    controls : sequence of str
        The inputs the optimizer chooses; the others are held at ``inputs``.
    duration : float, optional
        The horizon T [s] of a grid in time.
    along : str, optional
        The state the grid runs along (its rate must stay positive), with ``span``.
    span : array_like, optional
        ``(start, end)`` of ``along`` (N equal intervals), or its N + 1 nodes [its unit].
    inputs : mapping, optional
        The values of the inputs that are not controls [each input's unit]; default 0.
    substeps : int
        Runge-Kutta steps per interval (>= 1).
    expand : bool
        Expand the program into CasADi's scalar graph (SX) before solving: slower to build, faster
        per iteration (what a receding horizon wants).
    hessian : {"exact", "gauss-newton", "limited-memory"}
        The Hessian of the Lagrangian IPOPT uses: CasADi's exact one; the Gauss-Newton one
        :math:`2 J_r^\top J_r` of a cost in squares (:meth:`minimize` with ``squares=True``: the
        curvature of the model and of the constraints left out -- cheap, and exact at a zero-residual
        optimum; what tracking MPC uses [3]_); or IPOPT's L-BFGS update.
    jit : bool
        Compile the integration of one interval and its derivatives to C with the system C compiler
        (CasADi's ``"shell"`` compiler, ``-O1``) when the solver is built, the program calling them on
        each interval (``expand`` is then left out: inlining would undo it): seconds to build, then
        faster per iteration.

    References
    ----------
    .. [1] H. G. Bock and K. J. Plitt, "A multiple shooting algorithm for direct solution of optimal
       control problems", *IFAC Proceedings Volumes* 17(2), 1603-1608, 1984.
    .. [2] A. Wächter and L. T. Biegler, *Mathematical Programming* 106(1), 25-57, 2006 (IPOPT).
    .. [3] M. Diehl, H. G. Bock and J. P. Schlöder, "A real-time iteration scheme for nonlinear
       optimization in optimal feedback control", *SIAM Journal on Control and Optimization* 43(5),
       1714-1736, 2005 (the Gauss-Newton Hessian of a least-squares tracking cost).

    Examples
    --------
    >>> from vehdyn import LinearModel
    >>> from vehdyn.optimal import Problem
    >>> cart = LinearModel([[0.0, 1.0], [0.0, 0.0]], [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]],
    ...                    states=["position", "velocity"], inputs=["force"], outputs=["y"])
    >>> p = Problem(cart, 20, controls=["force"], duration=2.0)
    >>> p.constrain(lambda s, k: s["position"], 1.0, 1.0, "arrive", nodes=[20])
    >>> p.constrain(lambda s, k: s["velocity"], 0.0, 0.0, "stop", nodes=[20])
    >>> p.minimize(integral=lambda s, k: s["force"] ** 2)
    >>> round(p.solve([0.0, 0.0]).cost, 6)  # rest to rest: 12 d^2 / T^3 N^2 / (N^2 - 1)
    1.503759
    """

    def __init__(self, model, intervals: int, *, controls, duration=None, along=None, span=None, inputs=None,
                 substeps: int = 1, expand: bool = False, hessian: str = "exact", jit: bool = False):
        self.model = model
        self.expand, self.jit = bool(expand), bool(jit)
        if hessian not in _HESSIANS:
            raise ParameterError(f"hessian must be one of {_HESSIANS}, got {hessian!r}", key="hessian", value=hessian)
        self.hessian = hessian
        self.form = to_casadi(model)
        if not isinstance(intervals, (int, np.integer)) or isinstance(intervals, bool) or intervals < 1:
            raise ParameterError(f"intervals must be an integer >= 1, got {intervals!r}", key="intervals",
                                 value=intervals)
        if not isinstance(substeps, (int, np.integer)) or isinstance(substeps, bool) or substeps < 1:
            raise ParameterError(f"substeps must be an integer >= 1, got {substeps!r}", key="substeps", value=substeps)
        self.intervals, self.substeps, self.n_states = int(intervals), int(substeps), model.n_states
        self.controls = (controls,) if isinstance(controls, str) else tuple(controls)
        for name in self.controls:
            if name not in model.input_names:
                raise ParameterError(f"control {name!r} is not an input of {type(model).__name__} "
                                     f"({list(model.input_names)})", key="controls", value=name)
        self.fixed_inputs = model.input_vector(inputs)
        if (duration is None) == (along is None):
            raise ParameterError("give either duration (a grid in time) or along and span (a grid along a state)",
                                 key="duration", value=duration)
        if duration is not None:
            duration = finite_number(duration, "duration", positive=True)
            self.grid, self.along = np.linspace(0.0, duration, self.intervals + 1), None
        else:
            if along not in model.state_names:
                raise ParameterError(f"along must be a state of {type(model).__name__}, got {along!r}", key="along",
                                     value=along)
            try:
                values = np.asarray(span, dtype=float).reshape(-1)
            except (TypeError, ValueError):
                raise ParameterError(f"span must be (start, end) or the N + 1 nodes, got {span!r}", key="span",
                                     value=span) from None
            if values.size == 2:
                values = np.linspace(values[0], values[1], self.intervals + 1)
            if values.size != self.intervals + 1 or not np.all(np.isfinite(values)) or np.any(np.diff(values) <= 0):
                raise ParameterError(f"span must be (start, end) or the N + 1 = {self.intervals + 1} nodes, finite "
                                     f"and increasing, got {span!r}", key="span", value=span)
            self.grid, self.along = values, model.state_names.index(along)
        ca = require_casadi()
        self._ca = ca
        self._X = ca.MX.sym("X", self.n_states + 1, self.intervals + 1)  # the states and time at the nodes
        self._U = ca.MX.sym("U", len(self.controls), self.intervals)
        self._x_initial = ca.MX.sym("x_initial", self.n_states)
        self._u_initial = ca.MX.sym("u_initial", len(self.controls))
        self._parameters, self._free = [], set()
        self._lbx = np.full(self._X.shape, -np.inf)
        self._ubx = np.full(self._X.shape, np.inf)
        self._lbu = np.full(self._U.shape, -np.inf)
        self._ubu = np.full(self._U.shape, np.inf)
        self._constraints = []  # (expression, low, high, label)
        self._final, self._integral, self._squares, self._solver = None, None, False, None
        self._lbx[-1, 0] = self._ubx[-1, 0] = 0.0  # time starts at 0
        if self.along is not None:
            self._lbx[self.along] = self._ubx[self.along] = self.grid

    # ------------------------------------------------------------------ what the user states
    def parameter(self, name: str, rows: int = 1, cols: int = 1):
        """A symbol whose value is given at each :meth:`solve` (a reference path, a weight).

        Parameters
        ----------
        name : str
            Its name (the keyword of :meth:`solve`'s ``parameters``).
        rows, cols : int
            Its shape.

        Returns
        -------
        casadi.SX
            The symbol, for the callables of :meth:`constrain` and :meth:`minimize`.
        """
        self._require_unbuilt()
        symbol = self._ca.MX.sym(name, rows, cols)
        self._parameters.append((name, symbol))
        return symbol

    def free_initial(self, *names):
        """Leave these initial states to the optimizer (within their :meth:`bound`), e.g. the entry speed.

        Parameters
        ----------
        *names : str
            State names.
        """
        self._require_unbuilt()
        for name in names:
            self.model.index(name)
            self._free.add(name)

    def bound(self, name: str, low=-np.inf, high=np.inf, nodes=None):
        """low <= signal <= high at the nodes (a state, control, output, ``"time"`` or ``"<control>_rate"``).

        Parameters
        ----------
        name : str
            The signal.
        low, high : float or array_like
            The bounds, one value or one per node of ``nodes`` [the signal's unit].
        nodes : sequence of int, optional
            Where (default: every node; the intervals 0..N-1 for a control or a rate).
        """
        self._require_unbuilt()
        on_intervals = name in self.controls or (name.endswith("_rate") and name[:-5] in self.controls)
        nodes = np.arange(self.intervals if on_intervals else self.intervals + 1) if nodes is None else \
            np.asarray(nodes, dtype=int)
        low, high = (np.broadcast_to(np.asarray(v, dtype=float), nodes.shape) for v in (low, high))
        if np.any(np.isnan(low)) or np.any(np.isnan(high)) or np.any(low > high):
            raise ParameterError(f"bounds of {name!r} must be numbers with low <= high, got {low}, {high}",
                                 key=name, value=(low, high))
        if name in self.model.state_names or name == "time":
            row = self.n_states if name == "time" else self.model.state_names.index(name)
            self._lbx[row, nodes] = np.maximum(self._lbx[row, nodes], low)
            self._ubx[row, nodes] = np.minimum(self._ubx[row, nodes], high)
        elif name in self.controls:
            row = self.controls.index(name)
            self._lbu[row, nodes] = np.maximum(self._lbu[row, nodes], low)
            self._ubu[row, nodes] = np.minimum(self._ubu[row, nodes], high)
        else:
            self.constrain(lambda s, k: s[name], low, high, f"bound on {name}", nodes=nodes)

    def constrain(self, function, low, high, label: str, nodes=None):
        """low <= function(signals, k) <= high at the nodes: a path constraint written in signal names.

        Parameters
        ----------
        function : callable
            ``function(s, k)`` with ``s[name]`` any signal at node ``k`` (see :meth:`bound`).
        low, high : float or array_like
            Bounds, one or one per node of ``nodes`` [its unit].
        label : str
            Its name, in the error of an infeasible problem.
        nodes : sequence of int, optional
            Where (default: every node 0..N).
        """
        self._require_unbuilt()
        nodes = np.arange(self.intervals + 1) if nodes is None else np.asarray(nodes, dtype=int)
        low, high = (np.broadcast_to(np.asarray(v, dtype=float), nodes.shape) for v in (low, high))
        for k, lo, hi in zip(nodes, low, high):
            self._constraints.append((function(_Signals(self, int(k)), int(k)), lo, hi, f"{label} at node {k}"))

    def minimize(self, final=None, integral=None, squares: bool = False):
        r"""The cost :math:`\phi(s_N) + \sum_k L(s_k)\,(t_{k+1} - t_k)`, written in signal names.

        Parameters
        ----------
        final : callable, optional
            ``final(s, N)``: the cost at the last node, e.g. ``lambda s, k: s["time"]``.
        integral : callable, optional
            ``integral(s, k)``: the integrand, at the start of each interval (rectangle rule in time).
        squares : bool
            The callables return residuals r (an expression or a list of them) and the term is
            :math:`\sum_i r_i^2`: a least-squares cost, which ``hessian="gauss-newton"`` needs.
        """
        self._require_unbuilt()
        if self.hessian == "gauss-newton" and not squares:
            raise ParameterError("hessian='gauss-newton' needs a cost in squares: minimize(..., squares=True) with "
                                 "callables returning the residuals", key="squares", value=squares)
        self._final, self._integral, self._squares = final, integral, bool(squares)

    def signals(self, k: int):
        """The signals at node ``k`` by name (what the callables of :meth:`constrain` and :meth:`minimize` get).

        Parameters
        ----------
        k : int
            The node, 0..N.

        Returns
        -------
        mapping
            ``s[name]``: a CasADi expression.
        """
        return _Signals(self, int(k))

    # ------------------------------------------------------------------ the program
    def _time(self, k):
        """Time at node k: the grid's (a grid in time) or the time state (a grid along a state)."""
        return float(self.grid[k]) if self.along is None else self._X[self.n_states, k]

    def _input_vector(self, k):
        """Every input of interval k: the controls' symbols, the others' values."""
        rows = [self._U[self.controls.index(n), k] if n in self.controls else self.fixed_inputs[i]
                for i, n in enumerate(self.model.input_names)]
        return self._ca.vertcat(*rows)

    def _interval_function(self):
        """z(end of an interval) from z = (x, t) at its start, its controls and its length (RK4 steps)."""
        ca = self._ca
        z = ca.SX.sym("z", self.n_states + 1)
        uc = ca.SX.sym("uc", len(self.controls))
        h = ca.SX.sym("h")
        rows = [uc[self.controls.index(n)] if n in self.controls else self.fixed_inputs[i]
                for i, n in enumerate(self.model.input_names)]
        u = ca.vertcat(*rows)

        def rate(zz):
            f = self.form.rhs(zz[:self.n_states], u)
            if self.along is None:
                return ca.vertcat(f, 1.0)
            speed = f[self.along]
            return ca.vertcat(f / speed, 1.0 / speed)

        step, zz = h / self.substeps, z
        for _ in range(self.substeps):
            k1 = rate(zz)
            k2 = rate(zz + 0.5 * step * k1)
            k3 = rate(zz + 0.5 * step * k2)
            k4 = rate(zz + step * k3)
            zz = zz + step / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        options = {}
        if self.jit:  # the interval compiled once, with its derivatives; the program calls it N times
            jit = {"jit": True, "compiler": "shell", "jit_cleanup": True,
                   "jit_options": {"flags": ["-O1"], "directory": tempfile.gettempdir()}}
            options = {**jit, "jacobian_options": jit, "der_options": jit, "forward_options": jit,
                       "reverse_options": jit}
        try:
            return ca.Function("interval", [z, uc, h], [zz], options)
        except RuntimeError as error:  # no C compiler, or it failed
            raise ParameterError(f"jit=True compiles C code with CasADi's shell compiler (gcc), which failed: "
                                 f"{str(error).strip().splitlines()[-1]}", key="jit", value=True) from None

    def _build(self):
        ca = self._ca
        names = self.model.state_names
        interval = self._interval_function()
        g, labels, lbg, ubg = [], [], [], []
        unit = "s" if self.along is None else f"{names[self.along]}"
        for k in range(self.intervals):
            gap = self._X[:, k + 1] - interval(self._X[:, k], self._U[:, k], self.grid[k + 1] - self.grid[k])
            rows = [i for i in range(self.n_states + 1) if i != self.along]
            g += [gap[i] for i in rows]
            labels += [f"continuity of {(names + ('time',))[i]} over interval {k} (from {self.grid[k]:.4g} {unit})"
                       for i in rows]
        for i, name in enumerate(names):
            if name not in self._free and i != self.along:
                g.append(self._X[i, 0] - self._x_initial[i])
                labels.append(f"initial {name}")
        lbg, ubg = [0.0] * len(g), [0.0] * len(g)
        for expression, lo, hi, label in self._constraints:
            g.append(expression)
            lbg.append(lo)
            ubg.append(hi)
            labels.append(label)
        terms = []  # (value of the callable, its weight)
        if self._integral is not None:
            terms += [(self._integral(_Signals(self, k), k), self._time(k + 1) - self._time(k))
                      for k in range(self.intervals)]
        if self._final is not None:
            terms.append((self._final(_Signals(self, self.intervals), self.intervals), 1.0))
        w = ca.vertcat(ca.vec(self._X), ca.vec(self._U))
        p = ca.vertcat(self._x_initial, self._u_initial, *(ca.vec(symbol) for _, symbol in self._parameters))
        residuals = None
        if self._squares:
            residuals = ca.vertcat(*(ca.sqrt(weight) * ca.vec(ca.vertcat(*value) if isinstance(value, (list, tuple))
                                                                else value) for value, weight in terms))
            cost = ca.sumsqr(residuals)
        else:
            cost = 0.0
            for value, weight in terms:
                cost = cost + value * weight
        self._nlp = {"x": w, "p": p, "f": cost, "g": ca.vertcat(*g)}
        self._hess_lag = None
        if self.hessian == "gauss-newton" and residuals is None:
            raise ParameterError("hessian='gauss-newton' needs a cost in squares: minimize(..., squares=True)",
                                 key="hessian", value=self.hessian)
        if self.hessian == "gauss-newton":  # 2 lam_f J_r' J_r: the curvature of the residuals and of g left out
            lam_f, lam_g = ca.MX.sym("lam_f"), ca.MX.sym("lam_g", self._nlp["g"].shape[0])
            jr = ca.jacobian(residuals, w)
            hessian = ca.triu(2.0 * lam_f * ca.mtimes(jr.T, jr))
            self._hess_lag = ca.Function("nlp_hess_l", [w, p, lam_f, lam_g], [hessian], ["x", "p", "lam_f", "lam_g"],
                                         ["triu_hess_gamma_x_x"])
            if self.expand:
                self._hess_lag = self._hess_lag.expand()
        self._lbg, self._ubg, self._labels = np.array(lbg, dtype=float), np.array(ubg, dtype=float), labels
        self._lbw = np.concatenate([self._lbx.ravel(order="F"), self._lbu.ravel(order="F")])
        self._ubw = np.concatenate([self._ubx.ravel(order="F"), self._ubu.ravel(order="F")])
        self._g_function = ca.Function("g", [w, p], [self._nlp["g"]])

    def _require_unbuilt(self):
        if self._solver is not None:
            raise ParameterError("the problem is built (solved once): state every bound, constraint and cost first",
                                 key="problem", value="built")

    def solve(self, x0, *, u0=None, guess=None, parameters=None, options=None) -> Solution:
        """Solve from the initial states ``x0`` (IPOPT, exact derivatives).

        Parameters
        ----------
        x0 : mapping or array_like
            The initial states [each state's unit] (those of :meth:`free_initial`: a first guess).
        u0 : array_like, optional
            The controls before the start (for the first interval's rates) [their units]; default 0.
        guess : Solution, optional
            A warm start (a previous solution, e.g. shifted by :meth:`shift`); default: ``x0`` held
            over the horizon (time from the rate of ``along``), the controls at ``u0``.
        parameters : mapping, optional
            The values of the :meth:`parameter` symbols, by name.
        options : mapping, optional
            IPOPT options (``{"max_iter": 200}``, ...), on the first solve.

        Returns
        -------
        Solution

        Raises
        ------
        OptimalControlError
            When IPOPT ends without a solution (infeasible, iteration limit, ...): its status, the
            horizon and the constraint violated most.
        """
        ca = self._ca
        if self._solver is None:
            self._build()
            opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes", "ipopt.max_iter": 1000,
                    "expand": self.expand and not self.jit}
            if self.hessian == "gauss-newton":
                opts["hess_lag"] = self._hess_lag
            elif self.hessian == "limited-memory":
                opts["ipopt.hessian_approximation"] = "limited-memory"
            opts.update({f"ipopt.{k}": v for k, v in (options or {}).items()})
            self._solver = ca.nlpsol("solver", "ipopt", self._nlp, opts)
        x0 = self.model.state_vector(x0)
        u0 = np.zeros(len(self.controls)) if u0 is None else np.asarray(u0, dtype=float).reshape(-1)
        values = dict(parameters or {})
        missing = [name for name, _ in self._parameters if name not in values]
        if missing:
            raise ParameterError(f"give the value of parameter {missing[0]!r}", key="parameters", value=missing)
        p = np.concatenate([x0, u0, *(self._parameter_value(n, s.shape, values[n]) for n, s in self._parameters)])
        args = {"p": p, "lbx": self._lbw, "ubx": self._ubw, "lbg": self._lbg, "ubg": self._ubg}
        if guess is not None:
            args.update(x0=guess.raw["x"], lam_x0=guess.raw["lam_x"], lam_g0=guess.raw["lam_g"])
        else:
            args["x0"] = self._cold_guess(x0, u0)
        start = _time.perf_counter()
        result = self._solver(**args)
        elapsed = _time.perf_counter() - start
        stats = self._solver.stats()
        status = stats["return_status"]
        w = np.array(result["x"], dtype=float).ravel()
        if status not in _SUCCESS:
            self._raise(status, w, p, stats.get("iter_count", -1))
        return self._solution(w, result, status, stats.get("iter_count", -1), elapsed)

    @staticmethod
    def _parameter_value(name, shape, value):
        value = np.asarray(value, dtype=float)
        if value.size == shape[0] * shape[1]:
            return value.reshape(shape, order="F").ravel(order="F")
        try:
            return np.broadcast_to(value, shape).ravel(order="F")
        except ValueError:
            raise ParameterError(f"parameter {name!r} has shape {shape}, got {value.shape}", key=name,
                                 value=value.shape) from None

    def _cold_guess(self, x0, u0):
        X = np.repeat(np.concatenate([x0, [0.0]])[:, None], self.intervals + 1, axis=1)
        if self.along is not None:
            speed = float(np.asarray(self.form.rhs(x0, self._fixed_with(u0))).ravel()[self.along])
            X[self.along] = self.grid
            X[-1] = (self.grid - self.grid[0]) / max(speed, 1e-3)
        else:
            X[-1] = self.grid
        U = np.repeat(u0[:, None], self.intervals, axis=1)
        return np.concatenate([np.clip(X, self._lbx, self._ubx).ravel(order="F"),
                               np.clip(U, self._lbu, self._ubu).ravel(order="F")])

    def _fixed_with(self, controls):
        u = self.fixed_inputs.copy()
        for i, name in enumerate(self.controls):
            u[self.model.input_names.index(name)] = controls[i]
        return u

    def _raise(self, status, w, p, iterations):
        g = np.array(self._g_function(w, p), dtype=float).ravel()
        violations = np.maximum(self._lbg - g, g - self._ubg)
        bound = np.maximum(self._lbw - w, w - self._ubw)
        worst, label = -np.inf, "none (the last point is feasible: IPOPT stopped short of optimality)"
        if violations.size and violations.max() > 0:
            worst, label = float(violations.max()), self._labels[int(np.argmax(violations))]
        if bound.size and bound.max() > max(worst, 0.0):
            worst, label = float(bound.max()), self._variable_label(int(np.argmax(bound)))
        unit = "s" if self.along is None else self.model.state_names[self.along]
        raise OptimalControlError(
            f"IPOPT ended with {status} after {iterations} iterations over the horizon {self.grid[0]:.4g} to "
            f"{self.grid[-1]:.4g} ({unit}); the constraint violated most: {label} (by {max(worst, 0.0):.3g})",
            status=status, horizon=(float(self.grid[0]), float(self.grid[-1])), constraint=label,
            violation=max(worst, 0.0))

    def _variable_label(self, i):
        """The name of the program's variable ``i``: a state at a node or a control on an interval."""
        rows = self.n_states + 1
        if i < rows * (self.intervals + 1):
            k, row = divmod(i, rows)
            name = (self.model.state_names + ("time",))[row]
            return f"bound on {name} at node {k} ({self.grid[k]:.4g})"
        k, row = divmod(i - rows * (self.intervals + 1), len(self.controls))
        return f"bound on {self.controls[row]} on interval {k} (from {self.grid[k]:.4g})"

    def _solution(self, w, result, status, iterations, elapsed):
        n_x = (self.n_states + 1) * (self.intervals + 1)
        X = w[:n_x].reshape(self.n_states + 1, self.intervals + 1, order="F")
        U = w[n_x:].reshape(len(self.controls), self.intervals, order="F")
        inputs = np.stack([self._fixed_with(U[:, k]) for k in range(self.intervals)], axis=1)
        outputs = np.stack([np.array(self.form.output(X[:self.n_states, k], inputs[:, min(k, self.intervals - 1)]),
                                     dtype=float).ravel() for k in range(self.intervals + 1)], axis=1)
        raw = {key: np.array(result[key], dtype=float).ravel() for key in ("x", "lam_x", "lam_g")}
        return Solution(self, self.grid.copy(), X[-1].copy(), X[:self.n_states].copy(), inputs, outputs,
                        float(result["f"]), status, int(iterations), elapsed, raw)
