"""ISO 7401:2011 lateral transient response: the step-steer metrics (sec. 6.2 and 8).

Response time, peak response time, overshoot and the steady-state values of the yaw rate and
lateral acceleration after a step steer (:func:`step_response_metrics`, :func:`step_steer_metrics`).
"""

from __future__ import annotations
from vehdyn.errors import ParameterError
from dataclasses import dataclass
from dataclasses import fields
import numpy as np

__all__ = ["StepResponseMetrics", "step_response_metrics", "step_steer_metrics"]


# --------------------------------------------------------------------------- step metrics
@dataclass(frozen=True)
class StepResponseMetrics:
    """ISO 7401 step-response metrics of one signal (arrays for a batched result).

    Attributes
    ----------
    signal : str
    unit : str
        Unit of the signal.
    step_time : float
        The time origin: 50 % of the steer change [s].
    initial_value, steady_state_value, peak_value : ndarray
        [signal unit].
    response_time : ndarray
        Step time to 90 % of the steady-state change [s].
    rise_time : ndarray
        10 % to 90 % of the steady-state change [s].
    peak_response_time : ndarray
        Step time to the first peak [s] (NaN without an overshoot).
    overshoot : ndarray
        (peak - steady) / (steady - initial) [-] (0 without an overshoot).
    """

    signal: str
    unit: str
    step_time: float
    initial_value: np.ndarray
    steady_state_value: np.ndarray
    response_time: np.ndarray
    rise_time: np.ndarray
    peak_value: np.ndarray
    peak_response_time: np.ndarray
    overshoot: np.ndarray

    def as_dict(self) -> dict:
        """The metrics as a dict.

        Returns
        -------
        dict
            ``{field name: value}`` of every field, in the order of the class (``signal``,
            ``unit``, ``step_time`` [s], then the metrics in their units: floats, or arrays for a
            batch).
        """
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def to_frame(self):
        """The metrics as a table.

        Returns
        -------
        pandas.DataFrame
            One row per batch member (one row for a single run), one column per metric
            (``initial_value``, ``steady_state_value``, ``response_time``, ``rise_time``,
            ``peak_value``, ``peak_response_time``, ``overshoot``); their units in
            ``attrs["units"]``, the signal's name in ``attrs["signal"]``.
        """
        import pandas as pd

        names = ["initial_value", "steady_state_value", "response_time", "rise_time", "peak_value",
                 "peak_response_time", "overshoot"]
        df = pd.DataFrame({n: np.atleast_1d(getattr(self, n)) for n in names})
        df.attrs["units"] = {"initial_value": self.unit, "steady_state_value": self.unit, "response_time": "s",
                             "rise_time": "s", "peak_value": self.unit, "peak_response_time": "s",
                             "overshoot": "-"}
        df.attrs["signal"] = self.signal
        return df


def _crossing_time(t, z, level):
    """First time z (shape (n_t, ...)) reaches ``level`` from below, by linear interpolation; NaN if never."""
    above = z >= level
    k = np.argmax(above, axis=0)
    reached = np.take_along_axis(above, k[None], 0)[0]
    k0 = np.maximum(k - 1, 0)
    z0 = np.take_along_axis(z, k0[None], 0)[0]
    z1 = np.take_along_axis(z, k[None], 0)[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(z1 > z0, (level - z0) / (z1 - z0), 1.0)
    w = np.clip(w, 0.0, 1.0)
    tk = np.where(k == 0, t[0], t[k0] + w * (t[k] - t[k0]))
    return np.where(reached, tk, np.nan)


def _step_time(t, steer) -> float:
    """Time at which the steer signal passes 50 % of its change (t[0] for a step at the start)."""
    s0, s1 = steer[0], steer[-1]
    change = s1 - s0
    if abs(change) <= 1e-12 * max(abs(s1), 1e-300) or np.ptp(steer) == 0:
        return float(t[0])  # the steer is already at its final value at t[0]: an ideal step at t[0]
    z = (steer - s0) / change
    return float(_crossing_time(t, z, 0.5))


def step_response_metrics(result, signal: str = "yaw_rate", *, steer: str | None = "front_steer_angle",
                          step_time: float | None = None, steady_window: float = 1.0,
                          initial_value=None) -> StepResponseMetrics:
    """ISO 7401 step-steer metrics of ``signal`` in a :class:`~vehdyn.SimulationResult`.

    Parameters
    ----------
    result : SimulationResult
        Any model's result (batched results give arrays of metrics).
    signal : str
        The response (``"yaw_rate"``, ``"lateral_acceleration"``, ``"roll_angle"`` ...).
    steer : str or None
        The steer signal in the result that defines the time origin (50 % of its change). When it
        is constant over the run (an ideal step applied at ``time[0]`` to a vehicle at rest in its
        straight-running state) the origin is ``time[0]``.
    step_time : float, optional
        The time origin [s], overriding ``steer``.
    steady_window : float
        The steady-state value is the mean over the last ``steady_window`` seconds [s].
    initial_value : float or array_like, optional
        Response before the step; by default the first sample, or 0 (straight running) for an
        ideal step at ``time[0]``.

    Returns
    -------
    StepResponseMetrics

    Raises
    ------
    ParameterError
        A signal or steer the result does not have, a step time or window outside the run, or a
        result sampled too coarsely for the metrics: fewer than :data:`MIN_SAMPLES_PER_RESPONSE`
        samples between the step and the 90 % response.
    """
    t = np.asarray(result.time, dtype=float)
    y = np.asarray(_signal(result, signal, "signal"), dtype=float)
    ideal_step = False
    if step_time is None:
        if steer is None:
            raise ParameterError("give steer (a signal name) or step_time", key="steer", value=None)
        s = np.asarray(_signal(result, steer, "steer"), dtype=float)
        if s.ndim > 1:
            s = s[:, 0]
        step_time = _step_time(t, s)
        ideal_step = np.ptp(s) == 0
    if not (t[0] <= step_time < t[-1]):
        raise ParameterError(f"step_time {step_time} s is outside the run [{t[0]}, {t[-1]}] s",
                             key="step_time", value=step_time)
    if not (0 < steady_window <= t[-1] - step_time):
        raise ParameterError(f"steady_window must be in (0, {t[-1] - step_time}] s, got {steady_window}",
                             key="steady_window", value=steady_window)
    if initial_value is None:
        # straight running before an ideal step at time[0]; otherwise the first sample
        initial_value = np.zeros(y.shape[1:]) if ideal_step else y[0]
    y0 = np.asarray(initial_value, dtype=float)
    ys = y[t >= t[-1] - steady_window].mean(axis=0)
    change = ys - y0
    after = t >= step_time
    ta = t[after]
    with np.errstate(divide="ignore", invalid="ignore"):
        z = (y[after] - y0) / change  # normalized response: 0 before, 1 at steady state
    t90 = _crossing_time(ta, z, 0.9)
    t10 = _crossing_time(ta, z, 0.1)
    # first peak: the first local maximum of z above 1
    interior = (z[1:-1] >= z[:-2]) & (z[1:-1] > z[2:]) & (z[1:-1] > 1.0)
    has_peak = interior.any(axis=0)
    k = np.argmax(interior, axis=0) + 1
    zm1 = np.take_along_axis(z, (k - 1)[None], 0)[0]
    z0 = np.take_along_axis(z, k[None], 0)[0]
    zp1 = np.take_along_axis(z, (k + 1)[None], 0)[0]
    curvature = zm1 - 2 * z0 + zp1
    with np.errstate(divide="ignore", invalid="ignore"):
        shift = np.where(curvature < 0, 0.5 * (zm1 - zp1) / curvature, 0.0)
    shift = np.clip(shift, -1.0, 1.0)
    h = np.where(shift >= 0, ta[np.minimum(k + 1, ta.size - 1)] - ta[k], ta[k] - ta[k - 1])
    t_peak = ta[k] + shift * h
    z_peak = z0 - 0.25 * (zm1 - zp1) * shift
    overshoot = np.where(has_peak, z_peak - 1.0, 0.0)
    peak_value = np.where(has_peak, y0 + z_peak * change, ys)
    _check_resolution(ta, step_time, t90 - step_time)
    unit = result.unit(signal) if hasattr(result, "unit") else ""
    return StepResponseMetrics(
        signal=signal, unit=unit, step_time=float(step_time), initial_value=y0, steady_state_value=ys,
        response_time=t90 - step_time, rise_time=t90 - t10, peak_value=peak_value,
        peak_response_time=np.where(has_peak, t_peak - step_time, np.nan), overshoot=overshoot)


def step_steer_metrics(result, signals=("yaw_rate", "lateral_acceleration"), **kwargs) -> dict:
    """:func:`step_response_metrics` of several signals: ``{signal: StepResponseMetrics}``.

    Parameters
    ----------
    result : SimulationResult
    signals : sequence of str
        The responses.
    **kwargs
        Keyword arguments of :func:`step_response_metrics` (``steer``, ``step_time``,
        ``steady_window``, ``initial_value``).

    Returns
    -------
    dict
    """
    if isinstance(signals, str):
        signals = (signals,)
    return {s: step_response_metrics(result, s, **kwargs) for s in signals}


#: The fewest samples between the step time and the 90 % response the metrics are read from: the
#: crossings are linear interpolations between samples, the peak a parabola through three.
MIN_SAMPLES_PER_RESPONSE = 4


def _signal(result, name, what):
    """``result[name]``; ParameterError naming ``what`` when the result has no such signal."""
    try:
        return result[name]
    except (KeyError, TypeError) as exc:
        raise ParameterError(f"{what} = {name!r}: {exc.args[0] if exc.args else 'not in the result'}", key=what,
                             value=name) from None


def _check_resolution(t_after, step_time, response_time):
    """ParameterError when the samples after the step are too far apart for the response time."""
    response = np.atleast_1d(response_time)
    # 0 (to the rounding of the time values): at 90 % at once -- a direct feedthrough, or a signal whose
    # steady change is ~0 (the sideslip angle near the speed where it changes sign) -- nothing to resolve
    at_once = 1e-9 * max(1.0, abs(float(step_time)), abs(float(t_after[-1])) if t_after.size else 1.0)
    response = response[np.isfinite(response) & (response > at_once)]
    if t_after.size < 2 or not response.size:
        return
    horizon = t_after[t_after <= step_time + float(np.max(response)) + 1e-12]
    step = float(np.max(np.diff(horizon if horizon.size > 1 else t_after[:2])))
    fastest = float(np.min(response))
    if step > fastest / MIN_SAMPLES_PER_RESPONSE:
        raise ParameterError(f"result is sampled {step:.3g} s apart, too coarsely for the response time {fastest:.3g} "
                             f"s it gives: the ISO 7401 metrics need at least {MIN_SAMPLES_PER_RESPONSE} samples "
                             "between the step and the 90 % response (a grid of "
                             f"{fastest / (2 * MIN_SAMPLES_PER_RESPONSE):.2g} s or finer)", key="result", value=step)
