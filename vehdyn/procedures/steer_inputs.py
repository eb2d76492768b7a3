"""Steer inputs of the standard handling tests, as closed-form signals.

Steer inputs are road-wheel angles [rad] in SAE signs (positive turns right), returned as
vectorized callables ``delta(t)`` for :func:`vehdyn.simulate`'s ``inputs``: closed-form
:class:`~vehdyn.piecewise_signal.PiecewiseSignal` s, which both backends of ``simulate`` evaluate
exactly between samples and whose kinks they step onto (``solve_ivp`` methods, compiled
RK45/DOP853):

* step steer (ISO 7401:2011, sec. 6.2: steer ramp completed within 0.15 s);
* ramp steer (ISO 7401 / ISO 4138 slow ramp), sine steer (ISO 7401 continuous sine);
* sine with dwell (FMVSS 126, 49 CFR 571.126, S7.7): a 0.7 Hz sine whose second peak dwells 0.5 s.
"""

from __future__ import annotations

from vehdyn.params.checks import finite_number
from vehdyn.errors import ParameterError
from vehdyn.piecewise_signal import PiecewiseSignal
import numpy as np

__all__ = ["step_steer", "ramp_steer", "sine_steer", "sine_with_dwell"]


def step_steer(amplitude: float, start: float = 0.5, rise_time: float = 0.15) -> PiecewiseSignal:
    """Step steer of ``amplitude`` [rad] beginning at ``start`` [s], a linear ramp over ``rise_time`` [s]."""
    amplitude, start = finite_number(amplitude, "amplitude"), finite_number(start, "start")
    rise_time = finite_number(rise_time, "rise_time", positive=True)
    end = start + rise_time
    return PiecewiseSignal([[start, end, 0.0, amplitude / rise_time, 0.0, 0.0, 0.0],
                            [end, np.inf, amplitude, 0.0, 0.0, 0.0, 0.0]])


def ramp_steer(rate: float, start: float = 0.0) -> PiecewiseSignal:
    """Ramp steer of ``rate`` [rad/s] from ``start`` [s]."""
    rate, start = finite_number(rate, "rate"), finite_number(start, "start")
    return PiecewiseSignal([[start, np.inf, 0.0, rate, 0.0, 0.0, 0.0]])


def sine_steer(amplitude: float, frequency: float, start: float = 0.0, cycles: float | None = None) -> PiecewiseSignal:
    """Sine steer amplitude sin(2 pi f (t - start)) [rad] from ``start``, for ``cycles`` periods (None: forever)."""
    amplitude, start = finite_number(amplitude, "amplitude"), finite_number(start, "start")
    frequency = finite_number(frequency, "frequency", positive=True)
    end = np.inf if cycles is None else start + finite_number(cycles, "cycles", positive=True) / frequency
    return PiecewiseSignal([[start, end, 0.0, 0.0, amplitude, 2 * np.pi * frequency, 0.0]])


def sine_with_dwell(amplitude: float, frequency: float = 0.7, dwell: float = 0.5, start: float = 1.0) -> PiecewiseSignal:
    """FMVSS 126 sine with dwell: a ``frequency`` sine whose second peak is held for ``dwell`` [s].

    delta = A sin(2 pi f tau) for tau = t - start in [0, 3/(4f)], then -A for ``dwell`` s, then
    A sin(2 pi f (tau - dwell)) until tau = 1/f + dwell (completion of steer), then 0.
    The first lobe has the sign of ``amplitude`` [rad].
    """
    amplitude, start = finite_number(amplitude, "amplitude"), finite_number(start, "start")
    frequency = finite_number(frequency, "frequency", positive=True)
    dwell = finite_number(dwell, "dwell")
    if dwell < 0:
        raise ParameterError(f"dwell must be >= 0 [s], got {dwell}", key="dwell", value=dwell)
    omega, quarter3 = 2 * np.pi * frequency, 0.75 / frequency
    pieces = [[start, start + quarter3, 0.0, 0.0, amplitude, omega, 0.0]]
    if dwell > 0:
        pieces.append([start + quarter3, start + quarter3 + dwell, -amplitude, 0.0, 0.0, 0.0, 0.0])
    # the last quarter period continues the sine from its trough: phase 3 pi / 2
    pieces.append([start + quarter3 + dwell, start + 1.0 / frequency + dwell, 0.0, 0.0, amplitude, omega,
                   1.5 * np.pi])
    delta = PiecewiseSignal(pieces)
    delta.completion_of_steer = start + 1.0 / frequency + dwell
    delta.beginning_of_steer = start
    return delta
