"""Whole-body vibration comfort after ISO 2631-1:1997: frequency weightings, r.m.s., MTVV, VDV, comfort.

Frequency weightings
--------------------
Each weighting W of ISO 2631-1, Annex A, is the product of four continuous-time stages
(s = j 2 pi f, omega_i = 2 pi f_i; Annex A and its Table A.2 of parameters):

* band limiting, high pass:  H_h(s) = s^2 / (s^2 + omega_1 s / Q_1 + omega_1^2)
* band limiting, low pass:   H_l(s) = omega_2^2 / (s^2 + omega_2 s / Q_2 + omega_2^2), Q_1 = Q_2 = 1/sqrt(2)
* acceleration-velocity transition:
  H_t(s) = (1 + s / omega_3) / (1 + s / (Q_4 omega_4) + s^2 / omega_4^2)
* upward step:  H_s(s) = (s^2 + omega_5 s / Q_5 + omega_5^2) / (s^2 + omega_6 s / Q_6 + omega_6^2)

(H_s tends to 1 at high frequency and to (f_5/f_6)^2 at low frequency: that is what makes the
standard's Table 3 values, e.g. Wk = 0.482 at 1 Hz.) A weighting without a transition or a step
omits that stage. Parameters (Table A.2):

====  ======  =====  =====  =====  ====  =====  ====  =====  ====  ==========================
W     f1 Hz   f2 Hz  f3 Hz  f4 Hz  Q4    f5 Hz  Q5    f6 Hz  Q6    use
====  ======  =====  =====  =====  ====  =====  ====  =====  ====  ==========================
Wk    0.4     100    12.5   12.5   0.63  2.37   0.91  3.35   0.91  seat z, feet z, recumbent
Wd    0.4     100    2.0    2.0    0.63  --     --    --     --    seat x, y; back y, z
Wf    0.08    0.63   inf    0.25   0.86  0.0625 0.80  0.10   0.80  motion sickness (z)
Wc    0.4     100    8.0    8.0    0.63  --     --    --     --    seat back x
We    0.4     100    1.0    1.0    0.63  --     --    --     --    rotational (roll, pitch, yaw)
Wj    0.4     100    --     --     --    3.75   0.91  5.32   0.91  head, recumbent x
====  ======  =====  =====  =====  ====  =====  ====  =====  ====  ==========================

Table 3 of the standard is this filter evaluated at the *nominal* one-third-octave frequencies
(0.1, 0.125, 0.16 ... Hz) rounded to three significant figures (largest deviation 0.3 % for Wk and
Wd, 0.9 % for Wf).

Time domain: :meth:`Weighting.filter` applies the weighting to a sampled signal as a cascade of
second-order sections obtained by the bilinear transform, each stage pre-warped at its own
characteristic frequency (f1, f2, f4, sqrt(f5 f6)), so the digital filter matches the analog one
exactly at those frequencies. :meth:`Weighting.digital_error` states the accuracy: the largest
relative magnitude error against the analog weighting over a band. Measured for Wk (the other
weightings are alike): below 0.02 % up to fs/100, 0.2 % at fs/50, 1.4 % at fs/20 and 10 % at fs/10
(the bilinear transform compresses the frequency axis towards the Nyquist frequency); so sample at
least 20 times the highest frequency of interest (1 kHz for ride up to 50 Hz). For an exact time-domain route use
:meth:`Weighting.to_linear_model` with :func:`vehdyn.simulate` (exact discretization), or in the
frequency domain :func:`weighting_factor`.

Metrics (clause 6 of the standard, basic and additional methods): weighted r.m.s. a_w, running
r.m.s. a_w(t0) with integration time tau and the maximum transient vibration value MTVV (linear
integration), fourth-power vibration dose value VDV, crest factor, and the likely comfort reactions
of Annex C.2.3. (Equation and clause numbers are not cited: they were not re-read.)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError

__all__ = [
    "Weighting",
    "WEIGHTINGS",
    "weighting",
    "weighting_factor",
    "weighted_rms",
    "rms",
    "running_rms",
    "mtvv",
    "vibration_dose_value",
    "crest_factor",
    "vibration_total_value",
    "COMFORT_REACTIONS",
    "comfort_reactions",
    "comfort_category",
]

_Q_BAND = 1.0 / np.sqrt(2.0)


def _frequencies(values, name="frequency_hz") -> np.ndarray:
    """``values`` as a float array of frequencies [Hz], else ParameterError naming the first that is
    not a finite number >= 0 (its value, and its index in an array)."""
    try:
        f = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be numbers [Hz], got {values!r}", key=name, value=values) from None
    bad = ~(np.isfinite(f) & (f >= 0))
    if np.any(bad):
        where = tuple(int(i) for i in np.unravel_index(int(np.argmax(bad)), f.shape)) if f.ndim else ()
        value = float(f[where])
        at = f" at index {where[0] if len(where) == 1 else where}" if f.ndim else ""
        raise ParameterError(f"{name} must be finite and >= 0 [Hz]; got {value!r}{at}", key=name, value=value)
    return f


@dataclass(frozen=True)
class Weighting:
    r"""One ISO 2631-1 frequency weighting defined by its Annex A parameters.

    Parameters
    ----------
    name : str
        ``"Wk"``, ``"Wd"`` ...
    f1, f2 : float
        Band-limiting high-pass and low-pass corner frequencies [Hz].
    f3, f4, q4 : float or None
        Acceleration-velocity transition [Hz, Hz, -]; ``f3=None`` with ``f4`` given means f3 = infinity
        (Wf); ``f4=None`` means no transition stage (Wj).
    f5, q5, f6, q6 : float or None
        Upward step [Hz, -, Hz, -]; ``None`` means no step stage.
    description : str, optional
        What the weighting is for (``"vertical (z) on the seat, ..."``).

    Notes
    -----
    The weighting is the product of four continuous-time stages, s = j 2 pi f,
    omega_i = 2 pi f_i, Q_1 = Q_2 = 1/sqrt(2); a weighting without a transition or a step omits
    that stage:

    .. math::

        H_h(s) &= \frac{s^2}{s^2 + \omega_1 s / Q_1 + \omega_1^2}, \qquad
        H_l(s) = \frac{\omega_2^2}{s^2 + \omega_2 s / Q_2 + \omega_2^2}, \\
        H_t(s) &= \frac{1 + s / \omega_3}{1 + s / (Q_4 \omega_4) + s^2 / \omega_4^2}, \qquad
        H_s(s) = \frac{s^2 + \omega_5 s / Q_5 + \omega_5^2}{s^2 + \omega_6 s / Q_6 + \omega_6^2}, \\
        W(s) &= H_h(s) \, H_l(s) \, H_t(s) \, H_s(s)

    (band limiting high and low pass, acceleration-velocity transition, upward step). Table 3 of
    the standard is |W| at the nominal one-third-octave frequencies rounded to three significant
    figures (e.g. Wk = 0.482 at 1 Hz). :meth:`filter` applies it to samples by the bilinear
    transform, each stage pre-warped at its own characteristic frequency (its accuracy:
    :meth:`digital_error`); :meth:`to_linear_model` gives the exact state space.

    References
    ----------
    .. [1] ISO 2631-1:1997, *Mechanical vibration and shock -- Evaluation of human exposure to
       whole-body vibration -- Part 1: General requirements*, Annex A (Table A.2, the parameters
       of the weightings) and Table 3.

    Examples
    --------
    >>> from vehdyn.ride import weighting
    >>> weighting("Wk").factor([1.0, 8.0]).round(3).tolist()
    [0.482, 1.036]
    """

    name: str
    f1: float
    f2: float
    f3: float | None = None
    f4: float | None = None
    q4: float | None = None
    f5: float | None = None
    q5: float | None = None
    f6: float | None = None
    q6: float | None = None
    description: str = ""

    # ---------------------------------------------------------------- analog stages
    def _stages(self):
        """Analog stages as (numerator, denominator) polynomials in s (highest power first) and prewarp [Hz]."""
        w = lambda f: 2.0 * np.pi * f  # noqa: E731
        stages = [
            (np.array([1.0, 0.0, 0.0]), np.array([1.0, w(self.f1) / _Q_BAND, w(self.f1) ** 2]), self.f1),
            (np.array([0.0, 0.0, w(self.f2) ** 2]), np.array([1.0, w(self.f2) / _Q_BAND, w(self.f2) ** 2]), self.f2),
        ]
        if self.f4 is not None:
            w4 = w(self.f4)
            num = np.array([0.0, 0.0, 1.0]) if self.f3 is None else np.array([0.0, 1.0 / w(self.f3), 1.0])
            stages.append((num, np.array([1.0 / w4**2, 1.0 / (self.q4 * w4), 1.0]), self.f4))
        if self.f5 is not None:
            w5, w6 = w(self.f5), w(self.f6)
            stages.append((np.array([1.0, w5 / self.q5, w5**2]), np.array([1.0, w6 / self.q6, w6**2]),
                           np.sqrt(self.f5 * self.f6)))
        return stages

    def response(self, frequency_hz) -> np.ndarray:
        """Complex analog weighting W(j 2 pi f) (class Notes).

        Parameters
        ----------
        frequency_hz : float or array_like
            Frequencies f [Hz], finite and >= 0.

        Returns
        -------
        ndarray of complex
            W [-]; 0 at 0 Hz (the band-limiting high pass removes a constant acceleration).
        """
        f = _frequencies(frequency_hz)
        s = 2j * np.pi * f
        H = np.ones_like(s)
        for num, den, _ in self._stages():
            H = H * np.polyval(num, s) / np.polyval(den, s)
        return H

    def factor(self, frequency_hz) -> np.ndarray:
        """Weighting factor |W(f)|, the quantity tabulated in ISO 2631-1 Table 3.

        Parameters
        ----------
        frequency_hz : float or array_like
            Frequencies f [Hz], finite and >= 0.

        Returns
        -------
        ndarray
            |W| [-].
        """
        return np.abs(self.response(frequency_hz))

    # ---------------------------------------------------------------- state space
    def to_linear_model(self, input_name: str = "acceleration", output_name: str | None = None):
        """The weighting as a :class:`~vehdyn.LinearModel` (input acceleration, output weighted acceleration).

        A cascade of the stages, each realized in controllable form in the time scale of its own
        characteristic frequency (well conditioned, unlike one 8th-order polynomial). Append it to
        a ride model with :func:`vehdyn.connect_in_series` to get weighted responses exactly
        (frequency response, Lyapunov covariance, exact-discretization simulation); its states are
        named ``<output_name>_<weighting>_state_<k>``, so filters on several outputs can be appended.

        Parameters
        ----------
        input_name : str, optional
            Name of the input (default ``"acceleration"``), e.g. the ride model's output to weight.
        output_name : str, optional
            Name of the output; default ``"weighted_<input_name>"``.

        Returns
        -------
        LinearModel
            One input, one output (the weighted signal, in the input's unit), 2 states per stage.
        """
        from scipy import signal

        from vehdyn.model import LinearModel

        A = np.zeros((0, 0))
        B = np.zeros((0, 1))
        C = np.zeros((1, 0))
        D = np.ones((1, 1))
        for num, den, f_c in self._stages():
            wc = 2.0 * np.pi * f_c
            # the stage in s' = s / wc, then scaled back: A = wc A', B = wc B'
            scale = wc ** np.arange(2, -1, -1)
            b_num = np.trim_zeros(num * scale, "f")
            a_, b_, c_, d_ = signal.tf2ss(b_num, den * scale)
            a_, b_ = a_ * wc, b_ * wc
            n1, n2 = A.shape[0], a_.shape[0]
            A = np.block([[A, np.zeros((n1, n2))], [b_ @ C, a_]])
            B = np.vstack([B, b_ @ D])
            C = np.hstack([d_ @ C, c_])
            D = d_ @ D
        out = output_name or f"weighted_{input_name}"
        # states named after the output, so that several weighted outputs can be appended to one model
        return LinearModel(A, B, C, D, states=[f"{out}_{self.name.lower()}_state_{k}" for k in range(A.shape[0])],
                           inputs=[input_name], outputs=[out], name=f"ISO 2631-1 {self.name}")

    # ---------------------------------------------------------------- digital filter
    def sos(self, sample_rate: float) -> np.ndarray:
        """Second-order sections of the digital weighting at ``sample_rate`` [Hz].

        Bilinear transform of each analog stage, pre-warped at its characteristic frequency
        (f1, f2, f4, sqrt(f5 f6)), so that each stage is exact there. Needs
        ``sample_rate > 2 f2`` (the band-limiting low pass must lie below the Nyquist frequency).

        Parameters
        ----------
        sample_rate : float
            fs [Hz], > 2 f2.

        Returns
        -------
        ndarray, shape (n_stages, 6)
            Second-order sections [b0, b1, b2, a0, a1, a2] (``scipy.signal.sosfilt``'s form).
        """
        from scipy import signal

        fs = _positive(sample_rate, "sample_rate")
        if fs <= 2.0 * self.f2:
            raise ParameterError(
                f"sample_rate = {fs} Hz is too low for {self.name}: its band-limiting low pass at f2 = {self.f2} Hz "
                f"needs sample_rate > {2 * self.f2} Hz (ISO 2631-1 weighting up to f2)", key="sample_rate", value=fs)
        sections = []
        for num, den, f_warp in self._stages():
            b, a = signal.bilinear(np.trim_zeros(num, "f") if np.any(num) else num, den,
                                   fs=_prewarped_rate(fs, f_warp))
            b = np.concatenate([np.zeros(3 - b.size), b]) if b.size < 3 else b
            a = np.concatenate([np.zeros(3 - a.size), a]) if a.size < 3 else a
            sections.append(np.concatenate([b / a[0], a / a[0]]))
        return np.array(sections)

    def digital_response(self, frequency_hz, sample_rate: float) -> np.ndarray:
        """Complex response of the digital weighting (:meth:`sos`).

        Parameters
        ----------
        frequency_hz : float or array_like
            Frequencies [Hz], below sample_rate / 2.
        sample_rate : float
            fs [Hz], > 2 f2.

        Returns
        -------
        ndarray of complex
            The response [-].
        """
        from scipy import signal

        _, h = signal.sosfreqz(self.sos(sample_rate), worN=np.atleast_1d(np.asarray(frequency_hz, float)),
                               fs=sample_rate)
        return h

    def digital_error(self, sample_rate: float, f_low: float | None = None, f_high: float | None = None) -> float:
        """Largest relative error of the digital weighting's magnitude against the analog one.

        Parameters
        ----------
        sample_rate : float
            fs [Hz], > 2 f2.
        f_low : float, optional
            Lower end of the band [Hz] (default 0.1 f1).
        f_high : float, optional
            Upper end of the band [Hz] (default min(f2, sample_rate / 20)).

        Returns
        -------
        float
            max | |W_digital| / |W_analog| - 1 | [-] over 400 log-spaced frequencies of the band;
            e.g. Wk at 1 kHz: 1.4 % (at 50 Hz).
        """
        f_low = 0.1 * self.f1 if f_low is None else f_low
        f_high = min(self.f2, sample_rate / 20.0) if f_high is None else f_high
        f = np.geomspace(f_low, f_high, 400)
        return float(np.max(np.abs(np.abs(self.digital_response(f, sample_rate)) / self.factor(f) - 1.0)))

    def filter(self, signal_values, sample_rate: float, axis: int = -1) -> np.ndarray:
        """Weighted signal: the digital weighting (:meth:`sos`) applied to ``signal_values``.

        Parameters
        ----------
        signal_values : array_like
            Acceleration samples [m/s^2] (or [rad/s^2] for We), uniformly spaced in time.
        sample_rate : float
            Sampling rate [Hz]; must exceed 2 f2.
        axis : int
            Time axis.

        Returns
        -------
        ndarray
            The weighted signal, in the unit of ``signal_values``, same shape.
        """
        from scipy import signal

        x = np.asarray(signal_values, dtype=float)
        return signal.sosfilt(self.sos(sample_rate), x, axis=axis)


def _prewarped_rate(fs: float, f_warp: float) -> float:
    """The 'fs' to give scipy's bilinear() so that frequency ``f_warp`` maps exactly (pre-warping)."""
    wd = np.pi * f_warp / fs
    return fs * np.tan(wd) / wd if wd > 0 else fs


WEIGHTINGS: dict[str, Weighting] = {
    "Wk": Weighting("Wk", 0.4, 100.0, 12.5, 12.5, 0.63, 2.37, 0.91, 3.35, 0.91,
                    "vertical (z) on the seat, the feet and a recumbent person"),
    "Wd": Weighting("Wd", 0.4, 100.0, 2.0, 2.0, 0.63, description="horizontal (x, y) on the seat"),
    "Wf": Weighting("Wf", 0.08, 0.63, None, 0.25, 0.86, 0.0625, 0.80, 0.10, 0.80,
                    "vertical, motion sickness"),
    "Wc": Weighting("Wc", 0.4, 100.0, 8.0, 8.0, 0.63, description="seat back, x"),
    "We": Weighting("We", 0.4, 100.0, 1.0, 1.0, 0.63, description="rotational (roll, pitch, yaw) on the seat"),
    "Wj": Weighting("Wj", 0.4, 100.0, f5=3.75, q5=0.91, f6=5.32, q6=0.91, description="head, recumbent (x)"),
}
"""The ISO 2631-1 weightings by name (Annex A, Table A.2)."""


def weighting(name: str | Weighting) -> Weighting:
    """The ISO 2631-1 weighting called ``name``.

    Parameters
    ----------
    name : str or Weighting
        ``"Wk"``, ``"Wd"``, ``"Wf"``, ``"Wc"``, ``"We"``, ``"Wj"`` (any case); a Weighting passes
        through.

    Returns
    -------
    Weighting
        From :data:`WEIGHTINGS`.
    """
    if isinstance(name, Weighting):
        return name
    key = str(name)
    for k in WEIGHTINGS:
        if k.lower() == key.lower():
            return WEIGHTINGS[k]
    raise ParameterError(f"unknown ISO 2631-1 weighting {name!r}; known: {list(WEIGHTINGS)}", key="name", value=name)


def weighting_factor(name: str | Weighting, frequency_hz) -> np.ndarray:
    """Weighting factor |W(f)| of an ISO 2631-1 weighting (the analog filter of Annex A).

    Parameters
    ----------
    name : str or Weighting
        The weighting (``"Wk"``, ...).
    frequency_hz : float or array_like
        Frequencies [Hz], finite and >= 0 (ParameterError naming the first other value and its
        index).

    Returns
    -------
    ndarray
        |W| [-]; 0 at 0 Hz (the band-limiting high pass).
    """
    return weighting(name).factor(frequency_hz)


# --------------------------------------------------------------------------- metrics
def _positive(value, name):
    v = float(value)
    if not (np.isfinite(v) and v > 0):
        raise ParameterError(f"{name} must be a positive number, got {value!r}", key=name, value=value)
    return v


def _samples(values, name="signal_values"):
    x = np.asarray(values, dtype=float)
    if x.ndim == 0 or x.shape[-1] < 1:
        raise ParameterError(f"{name} must be a non-empty array of samples", key=name, value=x.shape)
    if not np.all(np.isfinite(x)):
        raise ParameterError(f"{name} contains non-finite samples", key=name, value=x[~np.isfinite(x)][0])
    return x


def rms(signal_values) -> np.ndarray:
    """Root mean square over the last axis, sqrt(mean(a^2)) (ISO 2631-1, the basic method).

    Parameters
    ----------
    signal_values : array_like
        Samples [any unit], the last axis time; finite, non-empty.

    Returns
    -------
    ndarray
        The r.m.s. [unit of the signal] over the other axes.
    """
    x = _samples(signal_values)
    return np.sqrt(np.mean(x**2, axis=-1))


def weighted_rms(signal_values, sample_rate: float, name: str | Weighting = "Wk", *, settle: float = 0.0):
    """Frequency-weighted r.m.s. a_w of an acceleration record (ISO 2631-1, the basic method).

    Parameters
    ----------
    signal_values : array_like
        Unweighted acceleration [m/s^2], last axis is time.
    sample_rate : float
        [Hz].
    name : str or Weighting
        Weighting (``"Wk"`` for vertical seat acceleration).
    settle : float
        Leading time [s] discarded after filtering (the filter's start-up transient).

    Returns
    -------
    ndarray
        a_w = sqrt(1/T int a_w(t)^2 dt) [m/s^2] over the other axes.

    References
    ----------
    .. [1] ISO 2631-1:1997, clause 6 (the basic evaluation method) and Annex A (the weightings).

    Examples
    --------
    A 1-Hz sine of amplitude 1 m/s^2: its r.m.s. 1/sqrt(2) times the Wk factor at 1 Hz:

    >>> import numpy as np
    >>> from vehdyn.ride import weighted_rms, weighting_factor
    >>> fs = 500.0
    >>> t = np.arange(0.0, 30.0, 1 / fs)
    >>> round(float(weighted_rms(np.sin(2 * np.pi * t), fs, "Wk", settle=10.0)), 4)
    0.3412
    >>> round(float(weighting_factor("Wk", 1.0) / np.sqrt(2)), 4)
    0.3412
    """
    fs = _positive(sample_rate, "sample_rate")
    aw = weighting(name).filter(_samples(signal_values), fs)
    k = int(round(settle * fs))
    if k >= aw.shape[-1]:
        raise ParameterError(f"settle = {settle} s leaves no samples", key="settle", value=settle)
    return rms(aw[..., k:])


def running_rms(weighted_values, sample_rate: float, integration_time: float = 1.0) -> np.ndarray:
    r"""Running r.m.s. of a weighted record (ISO 2631-1, linear integration).

    .. math::

        a_w(t_0) = \left[\frac{1}{\tau} \int_{t_0 - \tau}^{t_0} a_w^2(t) \, dt\right]^{1/2}

    Parameters
    ----------
    weighted_values : array_like
        Frequency-weighted acceleration a_w [m/s^2], the last axis time.
    sample_rate : float
        [Hz], > 0.
    integration_time : float, optional
        tau [s] (default 1 s, as the standard recommends); at least one sample, at most the record.

    Returns
    -------
    ndarray
        a_w(t_0) [m/s^2] at every sample from the first full window on (``N - n_tau + 1`` values
        along the last axis).
    """
    x = _samples(weighted_values, "weighted_values")
    fs = _positive(sample_rate, "sample_rate")
    n_tau = int(round(_positive(integration_time, "integration_time") * fs))
    if n_tau < 1 or n_tau > x.shape[-1]:
        raise ParameterError(f"integration_time = {integration_time} s is {n_tau} samples; the record has "
                             f"{x.shape[-1]}", key="integration_time", value=integration_time)
    c = np.cumsum(np.concatenate([np.zeros(x.shape[:-1] + (1,)), x**2], axis=-1), axis=-1)
    return np.sqrt(np.maximum(c[..., n_tau:] - c[..., :-n_tau], 0.0) / n_tau)


def mtvv(weighted_values, sample_rate: float, integration_time: float = 1.0) -> np.ndarray:
    """Maximum transient vibration value MTVV: the largest running r.m.s. (ISO 2631-1).

    Parameters
    ----------
    weighted_values : array_like
        Frequency-weighted acceleration a_w [m/s^2], the last axis time.
    sample_rate : float
        [Hz], > 0.
    integration_time : float, optional
        tau [s] of the running r.m.s. (default 1 s).

    Returns
    -------
    ndarray
        MTVV = max a_w(t_0) [m/s^2] over the other axes (:func:`running_rms`).
    """
    return np.max(running_rms(weighted_values, sample_rate, integration_time), axis=-1)


def vibration_dose_value(weighted_values, sample_rate: float) -> np.ndarray:
    r"""Fourth-power vibration dose value (ISO 2631-1), by the rectangle rule.

    .. math::

        VDV = \left[\int_0^T a_w^4(t) \, dt\right]^{1/4}

    Parameters
    ----------
    weighted_values : array_like
        Frequency-weighted acceleration a_w [m/s^2], the last axis time.
    sample_rate : float
        [Hz], > 0.

    Returns
    -------
    ndarray
        VDV [m/s^1.75] over the other axes.
    """
    x = _samples(weighted_values, "weighted_values")
    fs = _positive(sample_rate, "sample_rate")
    return (np.sum(x**4, axis=-1) / fs) ** 0.25


def crest_factor(weighted_values) -> np.ndarray:
    """Crest factor: the peak of the weighted record over its r.m.s. (ISO 2631-1).

    Parameters
    ----------
    weighted_values : array_like
        Frequency-weighted acceleration a_w [m/s^2], the last axis time.

    Returns
    -------
    ndarray
        max |a_w| / a_w,rms [-] over the other axes (the basic method holds up to 9).
    """
    x = _samples(weighted_values, "weighted_values")
    r = rms(x)
    return np.max(np.abs(x), axis=-1) / r


def vibration_total_value(weighted_rms_values, factors=None) -> float:
    """Vibration total value a_v = sqrt(sum_i (k_i a_wi)^2) [m/s^2] of several axes (ISO 2631-1).

    Parameters
    ----------
    weighted_rms_values : array_like
        Frequency-weighted r.m.s. a_wi of each axis [m/s^2].
    factors : array_like, optional
        Multiplying factors k_i [-] (1 by default, the seat-surface translational axes for comfort;
        take the standard's factors for other axes or for health, e.g. 1.4 on x and y).

    Returns
    -------
    float
        a_v [m/s^2].
    """
    a = np.asarray(weighted_rms_values, dtype=float)
    k = np.ones_like(a) if factors is None else np.asarray(factors, dtype=float)
    if a.shape != k.shape or not (np.all(np.isfinite(a)) and np.all(a >= 0)):
        raise ParameterError(f"weighted_rms_values must be non-negative numbers matching factors, got {a!r} and "
                             f"{k!r}", key="weighted_rms_values", value=a)
    return float(np.sqrt(np.sum((k * a) ** 2)))


# --------------------------------------------------------------------------- comfort reactions
COMFORT_REACTIONS: tuple[tuple[str, float, float], ...] = (
    ("not uncomfortable", 0.0, 0.315),
    ("a little uncomfortable", 0.315, 0.63),
    ("fairly uncomfortable", 0.5, 1.0),
    ("uncomfortable", 0.8, 1.6),
    ("very uncomfortable", 1.25, 2.5),
    ("extremely uncomfortable", 2.0, np.inf),
)
"""ISO 2631-1 Annex C.2.3 likely reactions to the overall vibration total value a_v [m/s^2]:
(reaction, lower, upper). The ranges overlap on purpose."""


def comfort_reactions(total_value) -> list[str]:
    """Every likely reaction of ISO 2631-1 Annex C.2.3 whose range holds a vibration total value.

    The standard's ranges overlap, so 0.9 m/s^2 is both "fairly uncomfortable" and "uncomfortable".

    Parameters
    ----------
    total_value : float
        a_v [m/s^2], >= 0 (:func:`vibration_total_value`).

    Returns
    -------
    list of str
        The reactions of :data:`COMFORT_REACTIONS` with lower <= a_v < upper.
    """
    a = float(total_value)
    if not (np.isfinite(a) and a >= 0):
        raise ParameterError(f"total_value must be a non-negative number [m/s^2], got {total_value!r}",
                             key="total_value", value=total_value)
    return [name for name, lo, hi in COMFORT_REACTIONS if lo <= a < hi]


def comfort_category(total_value) -> str:
    """One comfort label: the ISO 2631-1 Annex C.2.3 ranges split at the geometric middle of each overlap.

    Below 0.315 "not uncomfortable"; where two ranges overlap the label changes at the geometric
    mean of the overlap: sqrt(0.5 * 0.63) = 0.561, sqrt(0.8 * 1.0) = 0.894, sqrt(1.25 * 1.6) = 1.414,
    sqrt(2.0 * 2.5) = 2.236 m/s^2. Use :func:`comfort_reactions` for the
    overlapping labels of the standard itself.

    Parameters
    ----------
    total_value : float or array_like
        a_v [m/s^2], >= 0.

    Returns
    -------
    str or ndarray of str
        The label (an array of labels for an array).
    """
    a = np.asarray(total_value, dtype=float)
    if not np.all(np.isfinite(a) & (a >= 0)):
        raise ParameterError(f"total_value must be non-negative numbers [m/s^2], got {total_value!r}",
                             key="total_value", value=total_value)
    edges = _category_edges()
    names = np.array([r[0] for r in COMFORT_REACTIONS], dtype=object)
    index = np.searchsorted(edges, a, side="right")
    return str(names[index]) if np.ndim(index) == 0 else names[index]


def _category_edges() -> np.ndarray:
    """Boundaries between consecutive reactions: the upper limit where they do not overlap, else the geometric mean."""
    edges = []
    for (_, _, hi), (_, lo, _) in zip(COMFORT_REACTIONS[:-1], COMFORT_REACTIONS[1:]):
        edges.append(hi if lo >= hi else np.sqrt(lo * hi))
    return np.array(edges)
