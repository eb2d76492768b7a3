"""Result objects: :class:`SimulationResult` and :class:`FrequencyResponse`.

Both give named access (``result["yaw_rate"]``), units, ``to_frame()`` (pandas, units in
``attrs["units"]``) and ``plot()`` (matplotlib, imported only when called).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.signals import Signal, names_of

__all__ = ["SimulationResult", "FrequencyResponse"]


@dataclass
class SimulationResult:
    """The outcome of :func:`vehdyn.simulate`.

    Attributes
    ----------
    time : ndarray, shape (n_times,)
        Time [s].
    states, inputs, outputs : ndarray, shape (n_signals, n_times) or (n_signals, n_times, n_batch)
        Signal histories [each signal's unit: :meth:`unit`].
    state_signals, input_signals, output_signals : tuple of Signal
        Names and units.
    method : str
        The integration method used (``"exact"``, ``"rk4"``, a ``solve_ivp`` name).
    method_reason : str
        Why ``method="auto"`` chose it (empty otherwise).
    nfev, njev, nlu, n_steps : int
        Solver counters (right-hand-side and Jacobian evaluations, LU decompositions, steps).
    wall_time : float
        Wall-clock time of the integration [s].
    message : str
        The solver's message.
    options : dict
        The options the run used: ``rtol`` [-], ``atol`` [the states' units], ``hold``,
        ``substeps``.
    backend : str
        Where the run integrated: ``"compiled"`` (numba) or ``"numpy"``.
    backend_reason : str
        Why: the ``backend`` argument, why the compiled backend cannot run, or, on ``"auto"``,
        whether the compiled code was in the cache, is building in the background (numpy answering
        sooner) or was waited for (:func:`vehdyn.simulate`, Notes).

    Examples
    --------
    >>> import numpy as np
    >>> import vehdyn
    >>> lag = vehdyn.LinearModel([[-2.0]], [[2.0]], states=["yaw_rate"], inputs=["front_steer_angle"])
    >>> result = vehdyn.simulate(lag, np.linspace(0.0, 1.0, 11), {"front_steer_angle": 0.01})
    >>> result["yaw_rate"].shape, result.unit("yaw_rate")
    ((11,), 'rad/s')
    >>> round(float(result.final_state["yaw_rate"]), 6)     # 0.01 (1 - e^(-2))
    0.008647
    """

    time: np.ndarray
    states: np.ndarray
    inputs: np.ndarray
    outputs: np.ndarray
    state_signals: tuple[Signal, ...]
    input_signals: tuple[Signal, ...]
    output_signals: tuple[Signal, ...]
    method: str
    method_reason: str = ""
    nfev: int = 0
    njev: int = 0
    nlu: int = 0
    n_steps: int = 0
    wall_time: float = 0.0
    message: str = ""
    options: dict = field(default_factory=dict)
    backend: str = "numpy"
    backend_reason: str = ""

    @property
    def state_names(self) -> tuple[str, ...]:
        return names_of(self.state_signals)

    @property
    def input_names(self) -> tuple[str, ...]:
        return names_of(self.input_signals)

    @property
    def output_names(self) -> tuple[str, ...]:
        return names_of(self.output_signals)

    @property
    def batch_size(self) -> int | None:
        """Number of variants simulated together, or ``None`` for a single run."""
        return self.states.shape[2] if self.states.ndim == 3 else None

    def _lookup(self, name: str):
        for arr, sigs in ((self.outputs, self.output_signals), (self.states, self.state_signals),
                          (self.inputs, self.input_signals)):
            names = names_of(sigs)
            if name in names:
                k = names.index(name)
                return arr[k], sigs[k]
        if name == "time":
            return self.time, Signal("time")
        raise KeyError(
            f"no signal named {name!r}; outputs {list(self.output_names)}, states {list(self.state_names)}, "
            f"inputs {list(self.input_names)}"
        )

    def __getitem__(self, name: str) -> np.ndarray:
        """History of the output, state or input ``name`` (outputs are searched first)."""
        return self._lookup(name)[0]

    def __getattr__(self, name: str):
        if name.startswith("_") or name in self.__dataclass_fields__:
            raise AttributeError(name)
        try:
            return self._lookup(name)[0]
        except KeyError as exc:
            raise AttributeError(str(exc)) from None

    def __contains__(self, name: str) -> bool:
        try:
            self._lookup(name)
        except KeyError:
            return False
        return True

    def unit(self, name: str) -> str:
        """Unit of a signal.

        Parameters
        ----------
        name : str
            An output, state or input (or ``"time"``).

        Returns
        -------
        str
            Its SI unit (``""`` when it has none).
        """
        return self._lookup(name)[1].unit

    @property
    def signal_names(self) -> tuple[str, ...]:
        """Every distinct signal name: outputs, then states and inputs not among the outputs."""
        seen: list[str] = []
        for names in (self.output_names, self.state_names, self.input_names):
            seen.extend(n for n in names if n not in seen)
        return tuple(seen)

    @property
    def final_state(self) -> dict[str, float]:
        """States at the last time, by name."""
        return {n: self.states[k, -1] for k, n in enumerate(self.state_names)}

    def to_frame(self, batch: int | None = None):
        """The run as a pandas DataFrame: one column per signal, indexed by time [s].

        Parameters
        ----------
        batch : int, optional
            For a batched run, the variant to return; without it the frame has a (batch, time)
            MultiIndex.

        Returns
        -------
        pandas.DataFrame
            Columns: every output, then the states and inputs that are not outputs
            (:attr:`signal_names`); ``attrs["units"]`` maps each column to its unit and
            ``attrs["method"]`` names the method.

        Examples
        --------
        >>> import numpy as np
        >>> import vehdyn
        >>> lag = vehdyn.LinearModel([[-2.0]], [[2.0]], states=["yaw_rate"], inputs=["front_steer_angle"])
        >>> frame = vehdyn.simulate(lag, np.linspace(0.0, 1.0, 3), {"front_steer_angle": 0.01}).to_frame()
        >>> frame.round(6)  # doctest: +NORMALIZE_WHITESPACE
              yaw_rate  front_steer_angle
        time
        0.0   0.000000               0.01
        0.5   0.006321               0.01
        1.0   0.008647               0.01
        >>> frame.attrs["units"]
        {'yaw_rate': 'rad/s', 'front_steer_angle': 'rad'}
        """
        import pandas as pd

        names = self.signal_names
        units = {n: self.unit(n) for n in names}
        if self.batch_size is None or batch is not None:
            data = {n: (self[n] if batch is None else self[n][:, batch]) for n in names}
            df = pd.DataFrame(data, index=pd.Index(self.time, name="time"))
        else:
            nb = self.batch_size
            index = pd.MultiIndex.from_product([range(nb), self.time], names=["batch", "time"])
            data = {n: np.asarray(self[n]).T.reshape(-1) for n in names}
            df = pd.DataFrame(data, index=index)
        df.attrs["units"] = units
        df.attrs["method"] = self.method
        return df

    def plot(self, signals: Sequence[str] | None = None, *, fig=None, batch: int | None = None):
        """Plot signals against time, one axis per signal, labelled with units.

        Parameters
        ----------
        signals : sequence of str, optional
            The signals (default: every output).
        fig : matplotlib.figure.Figure, optional
            An empty figure to draw into (default: a new one).
        batch : int, optional
            For a batched run, the variant to plot (default: every variant).

        Returns
        -------
        matplotlib.figure.Figure
            The figure (:func:`vehdyn.plotting.plot_time_histories`).
        """
        from vehdyn.plotting import plot_time_histories

        names = list(signals) if signals is not None else list(self.output_names)
        return plot_time_histories(self, names, fig=fig, batch=batch)

    def __repr__(self) -> str:
        return (
            f"<SimulationResult: {self.time.size} samples over {self.time[0]:g}..{self.time[-1]:g} s, "
            f"method {self.method!r}, {self.nfev} rhs evaluations, {self.wall_time * 1e3:.2f} ms>"
        )


@dataclass
class FrequencyResponse:
    """Complex frequency response of a linear model.

    Attributes
    ----------
    omega : ndarray
        Angular frequency [rad/s].
    response : ndarray of complex, shape (n_outputs, n_inputs, n_frequencies)
        Output per unit input [output unit / input unit: :meth:`unit`].
    outputs, inputs : tuple of Signal
        The named channels.

    Examples
    --------
    A first-order lag 2 / (s + 2) from 0.2 to 20 rad/s: -3 dB and -45 deg at its corner, 2 rad/s.

    >>> import numpy as np
    >>> import vehdyn
    >>> lag = vehdyn.LinearModel([[-2.0]], [[2.0]], states=["yaw_rate"], inputs=["front_steer_angle"])
    >>> fr = lag.frequency_response(np.array([0.2, 2.0, 20.0]))
    >>> fr.magnitude_db[0, 0].round(2)
    array([ -0.04,  -3.01, -20.04])
    >>> fr.to_frame()["yaw_rate", "front_steer_angle", "phase_deg"].round(2).tolist()
    [-5.71, -45.0, -84.29]
    >>> fr.unit("yaw_rate", "front_steer_angle")
    '(rad/s)/(rad)'
    """

    omega: np.ndarray
    response: np.ndarray
    outputs: tuple[Signal, ...]
    inputs: tuple[Signal, ...]

    @property
    def frequency_hz(self) -> np.ndarray:
        """omega / (2 pi) [Hz]."""
        return self.omega / (2 * np.pi)

    @property
    def magnitude(self) -> np.ndarray:
        """|response|, shape (n_outputs, n_inputs, n_frequencies)."""
        return np.abs(self.response)

    @property
    def magnitude_db(self) -> np.ndarray:
        """20 log10 |response| [dB]."""
        with np.errstate(divide="ignore"):
            return 20 * np.log10(self.magnitude)

    @property
    def phase(self) -> np.ndarray:
        """Phase [rad], unwrapped along frequency."""
        return np.unwrap(np.angle(self.response), axis=-1)

    @property
    def output_names(self) -> tuple[str, ...]:
        return names_of(self.outputs)

    @property
    def input_names(self) -> tuple[str, ...]:
        return names_of(self.inputs)

    def __getitem__(self, key) -> np.ndarray:
        """``fr["yaw_rate", "front_steer_angle"]``: the complex response of one channel.

        A single name selects an output of a one-input response.
        """
        if isinstance(key, tuple):
            out, inp = key
        else:
            out, inp = key, None
        try:
            i = self.output_names.index(out)
        except ValueError:
            raise KeyError(f"no output {out!r}; outputs are {list(self.output_names)}") from None
        if inp is None:
            if len(self.inputs) != 1:
                raise KeyError(f"name the input too: inputs are {list(self.input_names)}")
            j = 0
        else:
            try:
                j = self.input_names.index(inp)
            except ValueError:
                raise KeyError(f"no input {inp!r}; inputs are {list(self.input_names)}") from None
        return self.response[i, j]

    def unit(self, output: str, input: str) -> str:
        """Unit of the ratio output/input.

        Parameters
        ----------
        output : str
            An output name.
        input : str
            An input name.

        Returns
        -------
        str
            ``"(output unit)/(input unit)"`` (``1`` for a signal without a unit).
        """
        uo = self.outputs[self.output_names.index(output)].unit or "1"
        ui = self.inputs[self.input_names.index(input)].unit or "1"
        return f"({uo})/({ui})"

    def to_frame(self):
        """The response as a pandas DataFrame indexed by omega [rad/s].

        Returns
        -------
        pandas.DataFrame
            Columns (output, input, quantity) with quantities ``magnitude`` [output unit / input
            unit], ``phase_deg`` [deg, unwrapped], ``real`` and ``imag``; ``attrs["units"]`` gives
            the unit of each ``"output/input"`` ratio.
        """
        import pandas as pd

        cols = {}
        units = {}
        for i, o in enumerate(self.output_names):
            for j, n in enumerate(self.input_names):
                h = self.response[i, j]
                cols[(o, n, "magnitude")] = np.abs(h)
                cols[(o, n, "phase_deg")] = np.rad2deg(np.unwrap(np.angle(h)))
                cols[(o, n, "real")] = h.real
                cols[(o, n, "imag")] = h.imag
                units[f"{o}/{n}"] = self.unit(o, n)
        df = pd.DataFrame(cols, index=pd.Index(self.omega, name="omega"))
        df.columns = pd.MultiIndex.from_tuples(df.columns, names=["output", "input", "quantity"])
        df.attrs["units"] = units
        return df

    def plot(self, outputs=None, inputs=None, *, fig=None, hz: bool = True, db: bool = False):
        """Bode plot (magnitude and phase against frequency, log axes) of the chosen channels.

        Parameters
        ----------
        outputs, inputs : sequence of str, optional
            The channels (every output and every input by default).
        fig : matplotlib.figure.Figure, optional
            A figure to draw into (its first two axes, so that responses overlay).
        hz : bool
            Frequency axis in Hz (default) or in rad/s.
        db : bool
            Magnitude in dB instead of a log axis.

        Returns
        -------
        matplotlib.figure.Figure
            The figure (:func:`vehdyn.plotting.bode_plot`).
        """
        from vehdyn.plotting import bode_plot

        return bode_plot(self, outputs=outputs, inputs=inputs, fig=fig, hz=hz, db=db)

    def __post_init__(self):
        if self.response.shape != (len(self.outputs), len(self.inputs), self.omega.size):
            raise ParameterError(
                f"response has shape {self.response.shape}, expected "
                f"{(len(self.outputs), len(self.inputs), self.omega.size)}",
                key="response",
                value=self.response.shape,
            )
