"""Steer inputs of the standard handling tests, as closed-form signals.

Steer inputs are road-wheel angles [rad] in SAE signs (positive turns right), returned as
vectorized callables ``delta(t)`` for :func:`vehdyn.simulate`'s ``inputs``: closed-form
:class:`~vehdyn.piecewise_signal.PiecewiseSignal` s, which both backends of ``simulate`` evaluate
exactly between samples and whose kinks they step onto (``solve_ivp`` methods, compiled
RK45/DOP853):

* step steer (ISO 7401:2011, clause 10, step input: a fast ramp, 0.15 s here by default);
* ramp steer (the slowly increasing steer of ISO 4138:2021), sine steer (ISO 7401:2011, clause 14,
  continuous sinusoidal input);
* sine with dwell (FMVSS 126, 49 CFR 571.126, S7.9): a 0.7 Hz sine whose second peak dwells 0.5 s.
"""

from __future__ import annotations

from vehdyn.params.checks import finite_number
from vehdyn.errors import ParameterError
from vehdyn.piecewise_signal import PiecewiseSignal
import numpy as np

__all__ = ["step_steer", "ramp_steer", "sine_steer", "sine_with_dwell"]


def step_steer(amplitude: float, start: float = 0.5, rise_time: float = 0.15) -> PiecewiseSignal:
    r"""Step steer: a linear ramp from 0 to ``amplitude`` over ``rise_time``, then held.

    .. math::

        \delta(t) = \begin{cases} 0 & t < t_0 \\
        A\,(t - t_0)/T_r & t_0 \le t < t_0 + T_r \\
        A & t \ge t_0 + T_r \end{cases}

    Parameters
    ----------
    amplitude : float
        Final steer angle :math:`A` [rad] (road wheel, SAE signs: positive turns right); any
        finite value.
    start : float
        Beginning of the ramp :math:`t_0` [s]; finite. Default 0.5 s.
    rise_time : float
        Duration :math:`T_r` of the ramp [s], > 0. Default 0.15 s: ISO 7401 asks the step to be
        applied as fast as possible, and this is the ramp time a driver or a steering robot
        typically achieves.

    Returns
    -------
    PiecewiseSignal
        ``delta(t)`` [rad], vectorized over ``t`` [s]; its breakpoints are ``start`` and
        ``start + rise_time`` (the 50 % point, the time origin of the ISO 7401 metrics, is
        ``start + rise_time / 2``).

    Raises
    ------
    ParameterError
        A non-finite ``amplitude`` or ``start``, or ``rise_time`` <= 0.

    References
    ----------
    ISO 7401:2011, *Road vehicles - Lateral transient response test methods - Open-loop test
    methods*, clause 10 (step input).

    Examples
    --------
    A 0.02 rad step reached by a ramp from 0.5 s to 0.65 s:

    >>> import numpy as np
    >>> from vehdyn.procedures import step_steer
    >>> delta = step_steer(0.02)
    >>> np.round(delta(np.array([0.0, 0.5, 0.575, 0.65, 2.0])), 6)
    array([0.  , 0.  , 0.01, 0.02, 0.02])
    >>> delta.breakpoints
    array([0.5 , 0.65])
    """
    amplitude, start = finite_number(amplitude, "amplitude"), finite_number(start, "start")
    rise_time = finite_number(rise_time, "rise_time", positive=True)
    end = start + rise_time
    return PiecewiseSignal([[start, end, 0.0, amplitude / rise_time, 0.0, 0.0, 0.0],
                            [end, np.inf, amplitude, 0.0, 0.0, 0.0, 0.0]])


def ramp_steer(rate: float, start: float = 0.0) -> PiecewiseSignal:
    r"""Ramp steer: zero until ``start``, then a steer growing at ``rate`` without end.

    .. math::

        \delta(t) = \begin{cases} 0 & t < t_0 \\ \dot\delta\,(t - t_0) & t \ge t_0 \end{cases}

    Parameters
    ----------
    rate : float
        Steer rate :math:`\dot\delta` [rad/s] (road wheel, SAE signs); any finite value (negative
        turns left).
    start : float
        Beginning of the ramp :math:`t_0` [s]; finite. Default 0 s.

    Returns
    -------
    PiecewiseSignal
        ``delta(t)`` [rad], vectorized over ``t`` [s], with one breakpoint at ``start``.

    Raises
    ------
    ParameterError
        A non-finite ``rate`` or ``start``.

    References
    ----------
    ISO 4138:2021, *Passenger cars - Steady-state circular driving behaviour - Open-loop test
    methods* (the steer-angle variant at constant speed: a slowly increasing steer; the rate is the
    caller's choice, slow enough for the vehicle to stay quasi-steady).

    Examples
    --------
    >>> import numpy as np
    >>> from vehdyn.procedures import ramp_steer
    >>> delta = ramp_steer(0.01, start=1.0)       # 0.01 rad/s from t = 1 s
    >>> np.round(delta(np.array([0.0, 1.0, 3.0])), 6)
    array([0.  , 0.  , 0.02])
    """
    rate, start = finite_number(rate, "rate"), finite_number(start, "start")
    return PiecewiseSignal([[start, np.inf, 0.0, rate, 0.0, 0.0, 0.0]])


def sine_steer(amplitude: float, frequency: float, start: float = 0.0, cycles: float | None = None) -> PiecewiseSignal:
    r"""Sine steer from ``start``, for ``cycles`` periods or without end.

    .. math::

        \delta(t) = A \sin\left(2\pi f\,(t - t_0)\right), \qquad
        t_0 \le t < t_0 + n / f \quad (\text{zero outside})

    Parameters
    ----------
    amplitude : float
        Amplitude :math:`A` [rad] (road wheel, SAE signs; the first half period has its sign);
        any finite value.
    frequency : float
        Frequency :math:`f` [Hz], > 0.
    start : float
        Beginning :math:`t_0` [s]; finite. Default 0 s.
    cycles : float, optional
        Number of periods :math:`n` [-], > 0 (need not be whole: 0.5 is a half-sine pulse);
        None (the default): the sine runs forever.

    Returns
    -------
    PiecewiseSignal
        ``delta(t)`` [rad], vectorized over ``t`` [s]; zero before ``start`` and from
        ``start + cycles / frequency`` on.

    Raises
    ------
    ParameterError
        A non-finite ``amplitude`` or ``start``, ``frequency`` <= 0 or ``cycles`` <= 0.

    References
    ----------
    ISO 7401:2011, *Road vehicles - Lateral transient response test methods - Open-loop test
    methods*, clause 14 (continuous sinusoidal input) and clause 11 (sinusoidal input, one
    period: ``cycles=1``).

    Examples
    --------
    Two periods of a 0.5 Hz sine of 0.01 rad:

    >>> import numpy as np
    >>> from vehdyn.procedures import sine_steer
    >>> delta = sine_steer(0.01, 0.5, cycles=2)
    >>> np.round(delta(np.array([0.5, 1.5, 4.0, 4.5])), 6)   # peak, trough, end (4 s), after
    array([ 0.01, -0.01,  0.  ,  0.  ])
    """
    amplitude, start = finite_number(amplitude, "amplitude"), finite_number(start, "start")
    frequency = finite_number(frequency, "frequency", positive=True)
    end = np.inf if cycles is None else start + finite_number(cycles, "cycles", positive=True) / frequency
    return PiecewiseSignal([[start, end, 0.0, 0.0, amplitude, 2 * np.pi * frequency, 0.0]])


def sine_with_dwell(amplitude: float, frequency: float = 0.7, dwell: float = 0.5, start: float = 1.0) -> PiecewiseSignal:
    r"""FMVSS 126 sine with dwell: a ``frequency`` sine whose second peak is held for ``dwell`` [s].

    With :math:`\tau = t - t_0` and :math:`\omega = 2\pi f`:

    .. math::

        \delta(t) = \begin{cases}
        A \sin(\omega\tau) & 0 \le \tau < \tfrac{3}{4f} \\
        -A & \tfrac{3}{4f} \le \tau < \tfrac{3}{4f} + T_d \\
        A \sin\left(\omega(\tau - T_d)\right) & \tfrac{3}{4f} + T_d \le \tau < \tfrac{1}{f} + T_d \\
        0 & \text{otherwise}
        \end{cases}

    The first lobe has the sign of ``amplitude``; the steer ends at the completion of steer
    (COS) :math:`t_0 + 1/f + T_d`, the instant from which FMVSS 126 S5.2 measures the yaw-rate
    ratios.

    Parameters
    ----------
    amplitude : float
        Amplitude :math:`A` [rad] (road wheel, SAE signs: positive, the first lobe turns right);
        any finite value.
    frequency : float
        Frequency :math:`f` of the sine [Hz], > 0. Default 0.7 Hz (FMVSS 126).
    dwell : float
        Hold :math:`T_d` at the second peak [s], >= 0 (0: a plain one-period sine). Default 0.5 s
        (FMVSS 126).
    start : float
        Beginning of steer (BOS) :math:`t_0` [s]; finite. Default 1 s.

    Returns
    -------
    PiecewiseSignal
        ``delta(t)`` [rad], vectorized over ``t`` [s], with two attributes more:
        ``beginning_of_steer`` (``start``) and ``completion_of_steer``
        (``start + 1 / frequency + dwell``) [s].

    Raises
    ------
    ParameterError
        A non-finite ``amplitude`` or ``start``, ``frequency`` <= 0, or a ``dwell`` that is not
        finite or is negative.

    References
    ----------
    NHTSA, FMVSS No. 126, *Electronic stability control systems*, 49 CFR 571.126 (final rule,
    72 FR 17236, 2007), S7.9 (sine with dwell test of oversteer intervention and
    responsiveness: 0.7 Hz, 500 ms dwell beginning at the second peak).

    Examples
    --------
    The 0.7 Hz sine with a 0.5 s dwell, beginning at 1 s:

    >>> import numpy as np
    >>> from vehdyn.procedures import sine_with_dwell
    >>> delta = sine_with_dwell(0.1)
    >>> t = np.array([1.0, 1 + 0.25 / 0.7, 1 + 0.75 / 0.7, 1 + 0.75 / 0.7 + 0.25, 4.0])
    >>> np.round(delta(t), 6)    # start, first peak, second peak, dwelling, after the steer
    array([ 0. ,  0.1, -0.1, -0.1,  0. ])
    >>> round(delta.completion_of_steer, 6)     # 1 + 1 / 0.7 + 0.5
    2.928571
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
