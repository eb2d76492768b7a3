"""Linear time-invariant models with named signals.

:class:`LinearModel` is the state-space form dx/dt = A x + B u, y = C x + D u of a vehdyn model. It
is itself a :class:`~vehdyn.Model` (so it simulates, and linearizes to itself exactly), and it adds
what linear analysis needs: export to python-control and scipy, frequency responses vectorized
over frequency, and modal analysis, none of which import python-control.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model.base import Model, signal_vector
from vehdyn.signals import Signal, as_signals

__all__ = ["LinearModel"]


def _matrix(value, name: str, shape: tuple[int, int]) -> np.ndarray:
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a real matrix, got {value!r}", key=name, value=value) from None
    if arr.size == 0 and 0 in shape:
        return np.zeros(shape)
    if arr.ndim == 0 and shape == (1, 1):
        arr = arr.reshape(1, 1)
    if arr.shape != shape:
        raise ParameterError(f"{name} must have shape {shape}, got {arr.shape}", key=name, value=arr.shape)
    if not np.all(np.isfinite(arr)):
        i, j = np.argwhere(~np.isfinite(arr))[0]
        raise ParameterError(f"{name}[{i}, {j}] is not finite ({arr[i, j]})", key=name, value=arr[i, j])
    return arr


def _velocity_name(dof: str) -> str:
    """Name of the rate of a coordinate: ``*_displacement`` -> ``*_velocity``, ``*_angle`` -> ``*_rate``."""
    for suffix, rate in (("_displacement", "_velocity"), ("_angle", "_rate"), ("_position", "_velocity")):
        if dof.endswith(suffix):
            return dof[: -len(suffix)] + rate
    return dof + "_velocity"


class LinearModel(Model):
    r"""Linear time-invariant state-space model with named signals.

    .. math::

        \dot x = A x + B u, \qquad y = C x + D u.

    Parameters
    ----------
    A, B, C, D : array_like
        State (n, n), input (n, m), output (p, n) and feedthrough (p, m) matrices [in the units of
        the signals: A in 1/s, B in state unit per input unit and second, C in output unit per
        state unit, D in output unit per input unit]. ``C`` defaults to the identity (the outputs
        are the states) and ``D`` to zeros.
    states, inputs, outputs : sequence of str or Signal
        Signal names; ``outputs`` defaults to the states.
    x_op, u_op, y_op : array_like, optional
        Operating point of a linearized model (its signals are deviations from it) [each
        signal's unit].
    name : str, optional
        Label used in exports.
    phenomena : iterable of str, optional
        What the model represents (see :data:`vehdyn.model.PHENOMENA`).

    See Also
    --------
    vehdyn.simulate : ``method="exact"`` integrates a LinearModel through the matrix exponential.

    References
    ----------
    .. [1] G. F. Franklin, J. D. Powell and A. Emami-Naeini, *Feedback Control of Dynamic
       Systems*, 7th ed., Pearson, 2015, ch. 7 (state-space design).

    Examples
    --------
    A 1 kg mass on a 4 N/m spring and a 0.4 N*s/m damper, driven by a force: the modes, the
    frequency response at resonance (1 / (c omega) = 1.25 m/N) and the python-control system,
    every signal named.

    >>> import numpy as np
    >>> import vehdyn
    >>> m = vehdyn.LinearModel([[0, 1], [-4, -0.4]], [[0], [1]], states=["sprung_displacement", "sprung_velocity"],
    ...                        inputs=["actuator_force"], outputs=["sprung_displacement"], C=[[1, 0]])
    >>> modes = m.modes()
    >>> round(float(modes.natural_frequency_hz[0]), 4), round(float(modes.damping_ratio[0]), 4)  # sqrt(4) / 2 pi
    (0.3183, 0.1)
    >>> fr = m.frequency_response(np.array([0.0, 2.0]))
    >>> np.abs(fr["sprung_displacement"]).round(4), fr.unit("sprung_displacement", "actuator_force")
    (array([0.25, 1.25]), '(m)/(N)')
    >>> sys = m.to_control()                               # a control.StateSpace
    >>> sys.state_labels, sys.input_labels
    (['sprung_displacement', 'sprung_velocity'], ['actuator_force'])
    """

    def __init__(
        self,
        A,
        B,
        C=None,
        D=None,
        *,
        states: Sequence[str | Signal],
        inputs: Sequence[str | Signal],
        outputs: Sequence[str | Signal] | None = None,
        x_op=None,
        u_op=None,
        y_op=None,
        name: str | None = None,
        phenomena=frozenset(),
    ):
        self.declare(states=states, inputs=inputs)
        if outputs is not None:
            self.declare(outputs=outputs)
        n, m = len(self.states), len(self.inputs)
        p = len(self.outputs) if outputs is not None else n
        self.A = _matrix(A, "A", (n, n))
        self.B = _matrix(B, "B", (n, m))
        if C is None:
            if outputs is not None and p != n:
                raise ParameterError("C is required when the outputs are not the states", key="C", value=None)
            C = np.eye(n)
        self.C = _matrix(C, "C", (p, n))
        self.D = _matrix(np.zeros((p, m)) if D is None else D, "D", (p, m))
        if outputs is None:
            # the outputs are the states, explicitly (so that to_control() names them)
            self.outputs = self.states
        self.x_op = signal_vector(x_op, self.states, "x_op")
        self.u_op = signal_vector(u_op, self.inputs, "u_op")
        self.y_op = np.zeros(p) if y_op is None else np.asarray(y_op, dtype=float).reshape(p)
        self.name = name or "LinearModel"
        self.phenomena = frozenset(phenomena)
        self.second_order = None  # (M, C, K, F, dof names) when built by from_second_order

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_second_order(
        cls,
        M,
        C,
        K,
        F=None,
        *,
        dof: Sequence[str | Signal],
        inputs: Sequence[str | Signal] = (),
        velocities: Sequence[str | Signal] | None = None,
        outputs: Sequence[str | Signal] | None = None,
        output_matrix=None,
        feedthrough=None,
        name: str | None = None,
        phenomena=frozenset(),
    ) -> "LinearModel":
        r"""State-space model of the mass-damper-spring system M q'' + C q' + K q = F u.

        Parameters
        ----------
        M, C, K : array_like, shape (n, n)
            Mass [kg or kg*m^2], damping [N*s/m ...] and stiffness [N/m ...] matrices. M must be
            symmetric positive definite.
        F : array_like, shape (n, m), optional
            Input matrix [generalized force per unit input: N per input unit, or N*m for an angle].
        dof : sequence of str
            Names of the coordinates q (``"sprung_displacement"``, ``"pitch_angle"``).
        inputs : sequence of str
            Input names.
        velocities : sequence of str, optional
            Names of q'. By default ``*_displacement`` becomes ``*_velocity``, ``*_angle``
            becomes ``*_rate`` and any other name gets ``_velocity`` appended.
        outputs, output_matrix, feedthrough : optional
            Outputs and their ``C``, ``D`` matrices over the state ``[q, q']`` [output unit per
            state or input unit]; by default the outputs are the states.
        name : str, optional
            Label used in exports.
        phenomena : iterable of str, optional
            What the model represents (see :data:`vehdyn.model.PHENOMENA`).

        Returns
        -------
        LinearModel
            States ``[q, q']`` with ``A = [[0, I], [-M^-1 K, -M^-1 C]]`` and ``B = [[0], [M^-1 F]]``;
            ``model.second_order`` keeps ``(M, C, K, F)`` for :meth:`modal_analysis`.

        Notes
        -----
        With the state :math:`x = [q, \dot q]`,

        .. math::

            \dot x = \begin{bmatrix} 0 & I \\ -M^{-1} K & -M^{-1} C \end{bmatrix} x
            + \begin{bmatrix} 0 \\ M^{-1} F \end{bmatrix} u.

        Examples
        --------
        A quarter car's body on its suspension (body mass 400 kg, spring 20 kN/m, damper
        1.5 kN*s/m) over a rigid wheel: body bounce at sqrt(k/m) / (2 pi) = 1.13 Hz.

        >>> from vehdyn import LinearModel
        >>> car = LinearModel.from_second_order([[400.0]], [[1500.0]], [[20e3]], [[1.0]],
        ...                                     dof=["sprung_displacement"], inputs=["actuator_force"])
        >>> car.state_names
        ('sprung_displacement', 'sprung_velocity')
        >>> round(float(car.modal_analysis().natural_frequency_hz[0]), 3)
        1.125
        """
        dof_signals = as_signals(dof, "dof")
        n = len(dof_signals)
        M = _matrix(M, "M", (n, n))
        Cm = _matrix(C, "C", (n, n))
        K = _matrix(K, "K", (n, n))
        in_signals = as_signals(inputs, "inputs")
        F = _matrix(np.zeros((n, len(in_signals))) if F is None else F, "F", (n, len(in_signals)))
        if not np.allclose(M, M.T, rtol=1e-12, atol=0.0):
            raise ParameterError("M must be symmetric", key="M", value=M)
        try:
            np.linalg.cholesky(M)
        except np.linalg.LinAlgError:
            raise ParameterError(
                f"M must be positive definite; its eigenvalues are {np.linalg.eigvalsh(M)}", key="M", value=M
            ) from None
        if velocities is None:
            velocities = [_velocity_name(s.name) for s in dof_signals]
        vel_signals = as_signals(velocities, "velocities")
        Minv = np.linalg.inv(M)
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ Cm]])
        B = np.vstack([np.zeros_like(F), Minv @ F])
        model = cls(
            A,
            B,
            output_matrix,
            feedthrough,
            states=dof_signals + vel_signals,
            inputs=in_signals,
            outputs=outputs,
            name=name,
            phenomena=phenomena,
        )
        model.second_order = (M, Cm, K, F, tuple(s.name for s in dof_signals))
        return model

    # ------------------------------------------------------------------ the model contract
    def rhs(self, t, x, u):
        return self.A @ x + self.B @ u

    def output(self, t, x, u):
        return self.C @ x + self.D @ u

    def jacobian(self, t, x, u):
        return self.A, self.B, self.C, self.D

    def symbolic_equations(self, xp, x, u, parameters):
        """dx/dt = A x + B u and y = C x + D u on symbols (:meth:`vehdyn.Model.symbolic_equations`;
        no parameters: ParameterError naming any).

        Parameters
        ----------
        xp : type
            The symbolic namespace (with ``mtimes``).
        x : casadi.SX
            States [each state's unit].
        u : casadi.SX
            Inputs [each input's unit].
        parameters : dict
            Must be empty.

        Returns
        -------
        tuple
            (dx/dt, y, {}).
        """
        if parameters:
            raise ParameterError(f"a LinearModel takes no symbolic parameters (its matrices are numbers), got "
                                 f"{sorted(parameters)}", key="parameters", value=sorted(parameters))
        return xp.mtimes(self.A, x) + xp.mtimes(self.B, u), xp.mtimes(self.C, x) + xp.mtimes(self.D, u), {}

    def linearize(self, x0=None, u0=None, t: float = 0.0, method: str = "auto") -> "LinearModel":
        """A linear model is its own linearization: the same matrices and names.

        Parameters
        ----------
        x0, u0 : mapping, array_like or None
            Operating point [each signal's unit]; ``None`` is zeros.
        t : float
            Time [s].
        method : str
            Accepted for the interface of :meth:`vehdyn.Model.linearize` (every method gives the
            matrices themselves).

        Returns
        -------
        LinearModel
        """
        if method not in ("auto", "finite_difference", "exact"):
            raise ParameterError(f"method must be 'auto', 'finite_difference' or 'exact', got {method!r}",
                                 key="method", value=method)
        x0 = self.state_vector(x0)
        u0 = self.input_vector(u0)
        return LinearModel(
            self.A,
            self.B,
            self.C,
            self.D,
            states=self.states,
            inputs=self.inputs,
            outputs=self.outputs,
            x_op=x0,
            u_op=u0,
            y_op=self.output(t, x0, u0),
            name=self.name,
            phenomena=self.phenomena,
        )

    # ------------------------------------------------------------------ selection and composition
    def select(self, outputs=None, inputs=None) -> "LinearModel":
        """The sub-model from some inputs to some outputs (the same states).

        Parameters
        ----------
        outputs : sequence of str, optional
            Output names to keep, in this order (``None`` keeps all).
        inputs : sequence of str, optional
            Input names to keep, in this order (``None`` keeps all).

        Returns
        -------
        LinearModel
            The rows of C and D and the columns of B and D of the chosen signals.
        """
        out_idx = [self.index(o, "outputs") for o in (outputs or self.output_names)]
        in_idx = [self.index(i, "inputs") for i in (inputs or self.input_names)]
        return LinearModel(
            self.A,
            self.B[:, in_idx],
            self.C[out_idx],
            self.D[np.ix_(out_idx, in_idx)],
            states=self.states,
            inputs=[self.inputs[i] for i in in_idx],
            outputs=[self.outputs[i] for i in out_idx],
            name=self.name,
            phenomena=self.phenomena,
        )

    # ------------------------------------------------------------------ exports
    def to_control(self, name: str | None = None, **kwargs):
        """This model as a ``control.StateSpace`` with every signal name (imports python-control).

        Parameters
        ----------
        name : str, optional
            The system's name (default: the model's, with spaces and dots as underscores, which
            python-control would read as subsystem separators).
        **kwargs
            Passed to ``control.ss``.

        Returns
        -------
        control.StateSpace
            A, B, C, D with the state, input and output labels of the model; connect it by name
            with ``control.interconnect``.

        Examples
        --------
        >>> import vehdyn
        >>> lag = vehdyn.LinearModel([[-2.0]], [[2.0]], states=["yaw_rate"], inputs=["front_steer_angle"])
        >>> sys = lag.to_control()
        >>> sys.state_labels, sys.input_labels, sys.output_labels
        (['yaw_rate'], ['front_steer_angle'], ['yaw_rate'])
        >>> vehdyn.LinearModel.from_control(sys).state_names       # and back
        ('yaw_rate',)
        """
        import control as ct

        return ct.ss(
            self.A,
            self.B,
            self.C,
            self.D,
            states=list(self.state_names),
            inputs=list(self.input_names),
            outputs=list(self.output_names),
            name=name or self.name.replace(" ", "_").replace(".", "_"),
            **kwargs,
        )

    @classmethod
    def from_control(cls, sys, **kwargs) -> "LinearModel":
        """A :class:`LinearModel` from a ``control.StateSpace``, keeping its signal names.

        Parameters
        ----------
        sys : control.StateSpace
            A continuous-time state-space system.
        **kwargs
            Keyword arguments of :class:`LinearModel` (``states``, ``inputs``, ``outputs`` override
            the system's labels; ``name``, ``phenomena``, ...).

        Returns
        -------
        LinearModel
            The same matrices and names.
        """
        return cls(
            sys.A,
            sys.B,
            sys.C,
            sys.D,
            states=kwargs.pop("states", sys.state_labels),
            inputs=kwargs.pop("inputs", sys.input_labels),
            outputs=kwargs.pop("outputs", sys.output_labels),
            **kwargs,
        )

    def to_scipy(self):
        """This model as a ``scipy.signal.StateSpace`` (scipy keeps no names).

        Returns
        -------
        scipy.signal.StateSpace
            The continuous-time system (A, B, C, D).
        """
        from scipy import signal

        return signal.StateSpace(self.A, self.B, self.C, self.D)

    # ------------------------------------------------------------------ analysis
    def poles(self) -> np.ndarray:
        """The poles: eigenvalues of A.

        Returns
        -------
        ndarray of complex
            Eigenvalues [1/s], unsorted (see :meth:`modes` for sorted, named ones).
        """
        return np.linalg.eigvals(self.A)

    def is_stable(self) -> bool:
        """Whether the model is asymptotically stable.

        Returns
        -------
        bool
            True when every eigenvalue of A has a negative real part.
        """
        return bool(np.all(self.poles().real < 0))

    def dc_gain(self) -> np.ndarray:
        """Steady-state gain H(0) = D - C A^-1 B.

        With integrators -- eigenvalues of A at 0, such as a yaw angle or a position among the
        states -- an output that an input drives through them has no steady state: its entry is
        ``inf`` with the sign of lim H(s) for s -> 0+ (the sign in which the output grows under a
        positive step), as MATLAB's ``dcgain`` does. Entries the integrators do not reach keep their
        finite gain. (``control.StateSpace.dcgain`` returns ``inf`` for every entry of such a
        system, ``nan`` where 0 is also a transmission zero.) Eigenvalues with
        |lambda| <= sqrt(eps) ||A||_1 count as integrators.

        Returns
        -------
        ndarray
            Shape (n_outputs, n_inputs) [output unit per input unit]; ``+inf`` or ``-inf`` where an
            integrator is reached.

        Notes
        -----
        The integrating modes are split off by an ordered real Schur form A = Z T Z^T and a Sylvester
        equation that block-diagonalizes T = [[N, T12], [0, T22]] (Golub & Van Loan, *Matrix
        Computations*, 4th ed., sec. 7.6.3); then H(s) = sum_j C1 N^j B1 / s^(j+1) + C2 (sI - T22)^-1 B2
        + D with N nilpotent, and an entry is infinite when one of its C1 N^j B1 is not zero.
        """
        A, B, C, D = self.A, self.B, self.C, self.D
        n = A.shape[0]
        if n == 0:
            return D.copy()
        lam = np.linalg.eigvals(A)
        tol = np.sqrt(np.finfo(float).eps) * np.linalg.norm(A, 1)
        if np.min(np.abs(lam)) > tol:
            try:
                return D - C @ np.linalg.solve(A, B)
            except np.linalg.LinAlgError:  # pragma: no cover - singular to rounding but not by the test above
                tol = float(np.min(np.abs(lam)))
        return _dc_gain_with_integrators(A, B, C, D, tol)

    def frequency_response(self, omega, outputs=None, inputs=None):
        r"""Complex frequency response.

        .. math::

            H(j\omega) = C\,(j\omega I - A)^{-1} B + D.

        Parameters
        ----------
        omega : array_like
            Angular frequencies [rad/s].
        outputs, inputs : sequence of str, optional
            Restrict to these signals.

        Returns
        -------
        FrequencyResponse
            ``response[output, input, frequency]`` [output unit per input unit]; all frequencies
            are solved in one batched linear solve, without python-control.

        Examples
        --------
        A first-order lag 2 / (s + 2) at its corner frequency: magnitude 1/sqrt(2), phase -45 deg.

        >>> import numpy as np
        >>> import vehdyn
        >>> lag = vehdyn.LinearModel([[-2.0]], [[2.0]], states=["yaw_rate"], inputs=["front_steer_angle"])
        >>> fr = lag.frequency_response(np.array([2.0]))
        >>> h = fr["yaw_rate", "front_steer_angle"][0]
        >>> round(float(abs(h)), 6), round(float(np.degrees(np.angle(h))), 6)
        (0.707107, -45.0)
        """
        from vehdyn.results import FrequencyResponse

        model = self if outputs is None and inputs is None else self.select(outputs, inputs)
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
        if omega.ndim != 1 or not np.all(np.isfinite(omega)):
            raise ParameterError("omega must be a finite 1-D array of angular frequencies [rad/s]", key="omega", value=omega)
        n = model.A.shape[0]
        s = 1j * omega
        if n == 0:
            H = np.broadcast_to(model.D[:, :, None], model.D.shape + (omega.size,)).astype(complex)
        else:
            Z = s[:, None, None] * np.eye(n) - model.A
            try:
                X = np.linalg.solve(Z, np.broadcast_to(model.B.astype(complex), (omega.size,) + model.B.shape))
            except np.linalg.LinAlgError:
                X = np.empty((omega.size,) + model.B.shape, dtype=complex)
                for k in range(omega.size):  # only at a pole on the imaginary axis
                    try:
                        X[k] = np.linalg.solve(Z[k], model.B)
                    except np.linalg.LinAlgError:
                        X[k] = np.inf
            H = np.einsum("pn,wnm->pmw", model.C, X) + model.D[:, :, None]
        return FrequencyResponse(
            omega=omega,
            response=H,
            outputs=model.outputs,
            inputs=model.inputs,
        )

    def modes(self):
        """Eigenvalues, natural frequencies, damping ratios and mode shapes of A.

        Returns
        -------
        Modes
            One entry per real eigenvalue and per complex-conjugate pair (the member with positive
            imaginary part), sorted by natural frequency; shapes are labelled by state name and
            scaled so that their largest entry is 1 (see :func:`vehdyn.model.state_space_modes`).

        Examples
        --------
        >>> import vehdyn
        >>> m = vehdyn.LinearModel([[0, 1], [-4, -0.4]], [[0], [1]], states=["pitch_angle", "pitch_rate"],
        ...                        inputs=["pitch_moment"])
        >>> modes = m.modes()
        >>> round(float(modes.natural_frequency[0]), 6), round(float(modes.damping_ratio[0]), 6)
        (2.0, 0.1)
        >>> modes.dominant_state(0)
        'pitch_rate'
        """
        from vehdyn.model.modal import state_space_modes

        return state_space_modes(self.A, self.states)

    def modal_analysis(self):
        """Undamped modal analysis in mass-normalized coordinates (models from :meth:`from_second_order`).

        Returns
        -------
        SecondOrderModes
            See :func:`vehdyn.model.modal.modal_analysis`.
        """
        from vehdyn.model.modal import modal_analysis

        if self.second_order is None:
            raise ParameterError(
                "modal_analysis needs a model built by LinearModel.from_second_order", key="second_order", value=None
            )
        M, C, K, _, dof = self.second_order
        return modal_analysis(M, K, C, dof=dof)

    def __repr__(self) -> str:
        return (
            f"<LinearModel {self.name!r}: states {list(self.state_names)}, inputs {list(self.input_names)}, "
            f"outputs {list(self.output_names)}>"
        )


def _dc_gain_with_integrators(A, B, C, D, tol):
    """H(0) of a state space whose A has eigenvalues within ``tol`` of 0 (see LinearModel.dc_gain)."""
    from scipy.linalg import schur, solve_sylvester

    T, Z, k = schur(A, output="real", sort=lambda re, im: np.hypot(re, im) <= tol)
    N, T12, T22 = T[:k, :k], T[:k, k:], T[k:, k:]
    Bz, Cz = Z.T @ B, C @ Z
    X = solve_sylvester(N, -T22, -T12) if k < A.shape[0] else np.zeros((k, 0))
    B1 = Bz[:k] - X @ Bz[k:]
    C1, C2, B2 = Cz[:, :k], Cz[:, :k] @ X + Cz[:, k:], Bz[k:]
    gain = D - C2 @ np.linalg.solve(T22, B2) if k < A.shape[0] else D.astype(float)
    # the integrating part sum_j C1 N^j B1 / s^(j+1): the highest power with a nonzero coefficient wins
    sign = np.zeros(D.shape)
    term = B1
    # "nonzero" against the size of the terms B1 is the difference of (not of B1 itself)
    size_b = np.linalg.norm(Bz[:k], 1) + np.linalg.norm(X, 1) * np.linalg.norm(Bz[k:], 1)
    scale = np.sqrt(np.finfo(float).eps) * np.linalg.norm(C1, 1) * size_b
    for _ in range(k):
        coefficient = C1 @ term
        scale *= max(1.0, np.linalg.norm(N, 1))
        nonzero = np.abs(coefficient) > scale
        sign[nonzero] = np.sign(coefficient[nonzero])
        term = N @ term
    out = np.array(gain, dtype=float)
    out[sign != 0] = np.copysign(np.inf, sign[sign != 0])
    return out
