"""ISO 8608 road spectra: classes, temporal spectra, the shaping filter, synthesis, parallel tracks.

Spectrum (ISO 8608:2016, clause 5 and Annex C)
    Displacement power spectral density (one-sided) against spatial frequency n [cycles/m]:
    Gd(n) = Gd(n0) (n / n0)^-w, n0 = 0.1 cycles/m, waviness w = 2. The classes A to H are the
    *geometric means* of the class bands: Gd(n0) = 16e-6 m^3 (A) ... 262144e-6 m^3 (H), each class
    four times the previous one. (Public code often uses the class upper limits, 32e-6 m^3 for A, or
    the values at Omega0 = 1 rad/m, Gd(Omega0) = 2 pi n0^2 Gd(n0) = Gd(n0) / 15.9 -- not here.)
    :class:`RoadSpectrum` may add a cut-on spatial frequency n_c below which the spectrum levels
    off, Gd(n) = Gd(n0) ((n^2 + n_c^2) / n0^2)^(-w/2), which makes the profile variance finite and
    its shaping filter stable; n_c = 0 (the default) is the standard's spectrum.

Temporal spectra at speed V [m/s]
    f = n V, G_z(f) = Gd(f / V) / V [m^2/Hz]. For w = 2 the road *velocity* spectrum is white:
    G_zdot(f) = (2 pi n0)^2 Gd(n0) V (for n_c = 0).

Shaping filter (w = 2 only)
    road_displacement = sigma / (s + a) w(t), a = 2 pi n_c V, sigma = 2 pi n0 sqrt(Gd(n0) V / 2),
    for unit-intensity white noise w (E[w(t) w(t + tau)] = delta(tau), i.e. one-sided PSD 2 per
    Hz); it reproduces the spectrum above exactly. See :meth:`RoadSpectrum.shaping_filter`.

Synthesis
    Sum of cosines with random phases (Shinozuka & Jan 1972; da Silva 2004):
    z(x) = sum_i A_i cos(2 pi n_i x + phi_i), n_i = i dn, dn = 1 / L, A_i = sqrt(2 Gd(n_i) dn),
    phi_i uniform on [0, 2 pi) from a seeded generator. Over the length L the cosines are
    orthogonal, so the sample variance is sum_i Gd(n_i) dn exactly, whatever the phases (with a
    coarse dn this left-endpoint sum differs from the continuous band integral by tens of percent for
    an n^-2 spectrum). Evaluated on the grid by one inverse FFT.
    Filtered white noise: the shaping filter sampled exactly (an Ornstein-Uhlenbeck recurrence, a
    random walk for n_c = 0).

Parallel tracks
    Left and right profiles with the coherence of a homogeneous isotropic surface (Dodds & Robson,
    J. Sound Vib. 31(2) 1973 175-183; Kamash & Robson, J. Sound Vib. 57(1) 1978 89-100 -- from
    memory): a track spectrum Gd ~ n^-w comes from an isotropic 2-D spectrum ~ k^-(w+1), whose
    cross-spectrum between tracks a distance B apart is real, Gd(n) rho(n) with
    rho(n) = 2^(1 - nu) / Gamma(nu) z^nu K_nu(z), z = 2 pi n B, nu = w / 2 (rho = z K_1(z) for
    w = 2). See :func:`isotropic_coherence`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.checks import MAX_SAMPLES, check_sample_count
from vehdyn.params.checks import positive_number as _positive
from vehdyn.road.profile import RoadProfile

__all__ = [
    "ISO8608_CLASSES",
    "ISO8608_REFERENCE_FREQUENCY",
    "iso8608_class_value",
    "iso8608_psd",
    "iso8608_class_of",
    "estimate_spectrum",
    "RoadSpectrum",
    "synthesize_profile",
    "synthesize_parallel_profiles",
    "isotropic_coherence",
]

ISO8608_REFERENCE_FREQUENCY = 0.1
"""n0 [cycles/m] of ISO 8608."""

ISO8608_CLASSES: dict[str, float] = {c: 16e-6 * 4.0**k for k, c in enumerate("ABCDEFGH")}
"""Geometric-mean displacement PSD Gd(n0) [m^3] of the ISO 8608 classes A-H (n0 = 0.1 cycles/m, w = 2)."""


def iso8608_class_value(road_class) -> float:
    """Gd(n0) of an ISO 8608 class: the geometric mean of the class band.

    Parameters
    ----------
    road_class : str or float
        A class letter ``"A"`` ... ``"H"`` (case and surrounding blanks ignored), or a value
        Gd(n0) [m^3], > 0, returned as it is.

    Returns
    -------
    float
        Gd(n0) [m^3] at n0 = 0.1 cycles/m: 16e-6 m^3 for A, four times more per class.

    Raises
    ------
    ParameterError
        For an unknown letter or a value that is not a finite number > 0 (key ``road_class``).

    References
    ----------
    .. [1] ISO 8608:2016, *Mechanical vibration -- Road surface profiles -- Reporting of measured
       data*, clause 5 and annex C.

    Examples
    --------
    >>> from vehdyn.road import iso8608_class_value
    >>> iso8608_class_value("C")
    0.000256
    """
    if isinstance(road_class, str):
        key = road_class.strip().upper()
        if key not in ISO8608_CLASSES:
            raise ParameterError(f"unknown ISO 8608 road class {road_class!r}; classes are A-H or a value Gd(n0) "
                                 "in m^3", key="road_class", value=road_class)
        return ISO8608_CLASSES[key]
    return _positive(road_class, "road_class")


def iso8608_psd(road_class, n, *, waviness: float = 2.0) -> np.ndarray:
    """ISO 8608 displacement PSD Gd(n) = Gd(n0) (n / n0)^-w [m^3] at spatial frequency ``n`` [cycles/m].

    Parameters
    ----------
    road_class : str or float
        Class letter ``"A"`` to ``"H"`` (geometric mean of the class) or Gd(n0) [m^3].
    n : array_like
        Spatial frequency [cycles/m], > 0.
    waviness : float
        Exponent w [-] (2 in ISO 8608).

    Returns
    -------
    ndarray
        Gd(n) [m^3] (one-sided, of the shape of ``n``).

    References
    ----------
    .. [1] ISO 8608:2016, *Mechanical vibration -- Road surface profiles -- Reporting of measured
       data*, clause 5 and annex C.
    """
    return RoadSpectrum.from_class(road_class, waviness=waviness).psd(n)


@dataclass(frozen=True)
class RoadSpectrum:
    r"""Road displacement spectrum of ISO 8608, with an optional cut-on frequency.

    .. math::

        G_d(n) = G_d(n_0) \left(\frac{n^2 + n_c^2}{n_0^2}\right)^{-w/2}, \qquad
        n_0 = 0.1 \ \text{cycles/m}

    one-sided, against the spatial frequency n [cycles/m]; at the speed V the road seen by a wheel
    has the temporal spectrum :math:`G_z(f) = G_d(f / V) / V` [m^2/Hz], f = n V.

    Parameters
    ----------
    gd0 : float
        Gd(n0) [m^3] at n0 = 0.1 cycles/m (see :func:`iso8608_class_value` for the classes).
    waviness : float
        w [-] (ISO 8608: 2), in (0, 6].
    cut_on : float
        n_c [cycles/m] below which the spectrum levels off (0: the ISO 8608 spectrum itself).

    Raises
    ------
    ParameterError
        If ``gd0`` or ``waviness`` is not a finite number > 0, ``waviness`` exceeds 6 or
        ``cut_on`` is negative.

    Notes
    -----
    With n_c > 0 the profile variance is finite and the shaping filter (:meth:`shaping_filter`,
    waviness 2 only) is stable; n_c = 0 is the standard's spectrum, whose variance diverges at
    low frequencies (integrate over a band: :meth:`variance`).

    References
    ----------
    .. [1] ISO 8608:2016, *Mechanical vibration -- Road surface profiles -- Reporting of measured
       data*, clause 5 and annex C.
    .. [2] C. J. Dodds and J. D. Robson, "The description of road surface roughness", J. Sound
       Vib. 31(2), 175-183, 1973.

    Examples
    --------
    >>> from vehdyn.road import RoadSpectrum
    >>> road = RoadSpectrum.from_class("C")
    >>> road.gd0, float(road.psd(0.2))                    # [m^3]: Gd falls as n^-2
    (0.000256, 6.4e-05)
    >>> round(road.rms(0.011, 2.83) * 1e3, 2)              # r.m.s. over ISO 8608's band [mm]
    15.23
    """

    gd0: float
    waviness: float = 2.0
    cut_on: float = 0.0

    def __post_init__(self):
        _positive(self.gd0, "gd0")
        w = _positive(self.waviness, "waviness")
        if w > 6:
            raise ParameterError(f"waviness = {w} is outside the plausible range (0, 6] of road spectra",
                                 key="waviness", value=w)
        _positive(self.cut_on, "cut_on", allow_zero=True)

    @classmethod
    def from_class(cls, road_class, *, waviness: float = 2.0, cut_on: float = 0.0) -> "RoadSpectrum":
        """The spectrum of an ISO 8608 class.

        Parameters
        ----------
        road_class : str or float
            Class letter ``"A"`` ... ``"H"`` or Gd(n0) [m^3] (see :func:`iso8608_class_value`).
        waviness : float
            w [-].
        cut_on : float
            n_c [cycles/m].

        Returns
        -------
        RoadSpectrum
        """
        return cls(iso8608_class_value(road_class), waviness, cut_on)

    @property
    def n0(self) -> float:
        """The reference spatial frequency n0 = 0.1 cycles/m of ISO 8608 [cycles/m]."""
        return ISO8608_REFERENCE_FREQUENCY

    def psd(self, n) -> np.ndarray:
        """The displacement spectrum at given spatial frequencies.

        Parameters
        ----------
        n : array_like
            Spatial frequency [cycles/m], > 0 (>= 0 with a cut-on).

        Returns
        -------
        ndarray
            Gd(n) [m^3], one-sided.
        """
        n = np.asarray(n, dtype=float)
        if np.any(n < 0) or (self.cut_on == 0 and np.any(n == 0)):
            raise ParameterError("spatial frequency n must be positive [cycles/m]", key="n", value=n)
        return self.gd0 * ((n**2 + self.cut_on**2) / self.n0**2) ** (-self.waviness / 2.0)

    def temporal_psd(self, frequency_hz, speed: float) -> np.ndarray:
        """Road displacement spectrum seen in time by a wheel at a constant speed.

        Parameters
        ----------
        frequency_hz : array_like
            Temporal frequency f [Hz].
        speed : float
            V [m/s], > 0.

        Returns
        -------
        ndarray
            G_z(f) = Gd(f / V) / V [m^2/Hz], one-sided.
        """
        V = _positive(speed, "speed")
        return self.psd(np.asarray(frequency_hz, dtype=float) / V) / V

    def variance(self, n_low: float = 0.0, n_high: float = np.inf) -> float:
        """Profile variance in a band of spatial frequencies.

        Closed form for w = 2 (arctangent, or 1/n without cut-on) and for any w without cut-on;
        otherwise adaptive quadrature.

        Parameters
        ----------
        n_low, n_high : float
            Band [n_low, n_high] [cycles/m], 0 <= n_low < n_high (n_high may be ``inf``).

        Returns
        -------
        float
            The integral of Gd(n) dn over the band [m^2] (``inf`` where it diverges: n_low = 0
            without cut-on, or w <= 1 up to infinity).
        """
        lo, hi = float(n_low), float(n_high)
        if not (0 <= lo < hi):
            raise ParameterError(f"need 0 <= n_low < n_high, got {n_low}, {n_high}", key="n_low", value=n_low)
        w, nc, n0, g = self.waviness, self.cut_on, self.n0, self.gd0
        if nc == 0:
            if lo == 0 or (w <= 1 and np.isinf(hi)):
                return float("inf")
            if w == 1:
                return float(g * n0 * np.log(hi / lo))
            hi_term = 0.0 if np.isinf(hi) else hi ** (1 - w)
            return float(g * n0**w * (hi_term - lo ** (1 - w)) / (1 - w))
        if w == 2:
            return float(g * n0**2 / nc * (np.arctan(hi / nc) - np.arctan(lo / nc)))
        from scipy.integrate import quad

        return float(quad(lambda n: float(self.psd(n)), lo, hi, limit=200)[0])

    def rms(self, n_low: float = 0.0, n_high: float = np.inf) -> float:
        """Profile r.m.s. in a band of spatial frequencies.

        Parameters
        ----------
        n_low, n_high : float
            Band [n_low, n_high] [cycles/m] (see :meth:`variance`).

        Returns
        -------
        float
            sqrt of :meth:`variance` [m].
        """
        return float(np.sqrt(self.variance(n_low, n_high)))

    def white_noise_gain(self, speed: float) -> float:
        """Gain from unit-intensity white noise to the road velocity (waviness 2 only).

        Parameters
        ----------
        speed : float
            V [m/s], > 0.

        Returns
        -------
        float
            sigma = 2 pi n0 sqrt(Gd(n0) V / 2) [m/s^0.5]: road_velocity = sigma w for n_c = 0.

        Raises
        ------
        ParameterError
            If the waviness is not 2.
        """
        self._require_rational()
        return 2.0 * np.pi * self.n0 * np.sqrt(self.gd0 * _positive(speed, "speed") / 2.0)

    def _require_rational(self):
        if self.waviness != 2.0:
            raise ParameterError(f"a rational shaping filter exists only for waviness 2, got {self.waviness}; use "
                                 "the PSD route or sum-of-cosines synthesis", key="waviness", value=self.waviness)

    def shaping_filter(self, speed: float, *, noise_input: str = "road_noise", suffix: str = ""):
        r"""Shaping filter: a :class:`~vehdyn.LinearModel` from white noise to the road at a speed.

        .. math::

            \dot z = -a z + \sigma w, \qquad a = 2 \pi n_c V, \qquad
            \sigma = 2 \pi n_0 \sqrt{G_d(n_0) V / 2}

        for unit-intensity white noise w (E[w(t) w(t + tau)] = delta(tau), one-sided PSD 2 per
        Hz): the output spectrum is :meth:`temporal_psd` exactly. With n_c = 0 the filter is an
        integrator (a marginally stable state, like the road itself);
        :func:`vehdyn.ride.random_vibration` handles that exactly.

        Parameters
        ----------
        speed : float
            V [m/s], > 0.
        noise_input : str
            Name of the white-noise input.
        suffix : str
            Appended to the signal names (``"_front"``), so that
            ``vehdyn.connect_in_series(filter, ride_model)`` drives any ride model with inputs of
            those names.

        Returns
        -------
        LinearModel
            State and output ``road_displacement`` [m], output ``road_velocity`` [m/s].

        Raises
        ------
        ParameterError
            If the waviness is not 2.

        Examples
        --------
        >>> import numpy as np
        >>> from vehdyn.road import RoadSpectrum
        >>> road = RoadSpectrum.from_class("C", cut_on=0.01)
        >>> f = np.array([0.5, 2.0])                                   # [Hz]
        >>> H = road.shaping_filter(20.0).frequency_response(2 * np.pi * f).response[0, 0]
        >>> bool(np.allclose(2 * np.abs(H) ** 2, road.temporal_psd(f, 20.0), rtol=1e-12))
        True
        """
        from vehdyn.model import LinearModel

        V = _positive(speed, "speed")
        sigma = self.white_noise_gain(V)
        a = 2.0 * np.pi * self.cut_on * V
        return LinearModel([[-a]], [[sigma]], [[1.0], [-a]], [[0.0], [sigma]],
                           states=[f"road_displacement{suffix}"], inputs=[noise_input],
                           outputs=[f"road_displacement{suffix}", f"road_velocity{suffix}"],
                           name=f"ISO 8608 road Gd(n0)={self.gd0:.3g} m^3 at {V:g} m/s",
                           phenomena={"road_input"})


def isotropic_coherence(n, track_width: float, waviness: float = 2.0) -> np.ndarray:
    r"""Left-right coherence of a homogeneous isotropic road.

    .. math::

        \rho(n) = \frac{2^{1 - \nu}}{\Gamma(\nu)} z^\nu K_\nu(z), \qquad
        z = 2 \pi n B, \quad \nu = w / 2

    (K_nu the modified Bessel function of the second kind); the cross-spectral density between
    two parallel tracks B apart is rho(n) Gd(n) (real). rho is 1 at n = 0 and falls to 0.5 near
    n B = 0.19 (w = 2). The magnitude-squared coherence is rho^2.

    Parameters
    ----------
    n : array_like
        Spatial frequency [cycles/m].
    track_width : float
        Distance B between the tracks [m], >= 0.
    waviness : float
        w [-] of the track spectrum.

    Returns
    -------
    ndarray
        rho(n) [-].

    References
    ----------
    .. [1] C. J. Dodds and J. D. Robson, "The description of road surface roughness", J. Sound
       Vib. 31(2), 175-183, 1973.
    .. [2] M. K. M. Kamash and J. D. Robson, "The application of isotropy in road surface
       modelling", J. Sound Vib. 57(1), 89-100, 1978.
    """
    from scipy.special import gamma, kv

    B = _positive(track_width, "track_width", allow_zero=True)
    nu = _positive(waviness, "waviness") / 2.0
    z = 2.0 * np.pi * np.abs(np.asarray(n, dtype=float)) * B
    with np.errstate(invalid="ignore", over="ignore"):
        rho = 2.0 ** (1.0 - nu) / gamma(nu) * z**nu * kv(nu, z)
    return np.where(z == 0, 1.0, np.nan_to_num(rho, nan=0.0))


# --------------------------------------------------------------------------- profiles
def _rng(seed):
    return seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)


def _grid(length, spacing):
    L = _positive(length, "length")
    dx = _positive(spacing, "spacing")
    N = int(round(L / dx)) if L / dx <= MAX_SAMPLES else check_sample_count(L / dx, "length", length,
                                                                             f"length / spacing {dx:g} m")
    if N < 4:
        raise ParameterError(f"length / spacing = {L / dx:g} gives fewer than 4 samples", key="spacing", value=dx)
    return N, dx


def _cosine_amplitudes(spectrum: RoadSpectrum, N: int, dx: float, n_min, n_max):
    """Component indices i (n_i = i / L) and amplitudes A_i = sqrt(2 Gd(n_i) dn) in [n_min, n_max]."""
    L = N * dx
    dn = 1.0 / L
    i = np.arange(1, (N - 1) // 2 + 1)  # strictly below the Nyquist frequency
    n = i * dn
    keep = np.ones(i.size, dtype=bool)
    if n_min is not None:
        keep &= n >= float(n_min) * (1 - 1e-12)
    if n_max is not None:
        keep &= n <= float(n_max) * (1 + 1e-12)
    i, n = i[keep], n[keep]
    if i.size == 0:
        raise ParameterError(f"no spatial frequency i/L (L = {L:g} m) lies in [{n_min}, {n_max}] below the Nyquist "
                             f"frequency {0.5 / dx:g} cycles/m", key="n_min", value=n_min)
    return i, np.sqrt(2.0 * spectrum.psd(n) * dn)


def synthesize_profile(
    spectrum: RoadSpectrum | str | float,
    length: float,
    spacing: float,
    *,
    seed=None,
    n_min: float | None = None,
    n_max: float | None = None,
    method: str = "cosines",
) -> RoadProfile:
    r"""A random road profile with the displacement spectrum ``spectrum``.

    Sum of cosines with random phases, evaluated on the grid by one inverse FFT:

    .. math::

        z(x) = \sum_i A_i \cos(2 \pi n_i x + \varphi_i), \qquad n_i = i \, \Delta n, \quad
        \Delta n = 1 / L, \quad A_i = \sqrt{2 G_d(n_i) \Delta n}

    with phases uniform on [0, 2 pi) from a seeded generator. Over the length L the cosines are
    orthogonal, so the sample variance is :math:`\sum_i G_d(n_i) \Delta n` exactly, whatever the
    phases. Or, for waviness 2, the shaping filter (:meth:`RoadSpectrum.shaping_filter`) driven by
    white noise and sampled exactly.

    Parameters
    ----------
    spectrum : RoadSpectrum, str or float
        The spectrum, an ISO 8608 class letter or Gd(n0) [m^3].
    length, spacing : float
        Profile length and sample spacing [m].
    seed : int or numpy Generator, optional
        Random phases (or noise) are reproducible with a seed.
    n_min, n_max : float, optional
        Band of the cosine components [cycles/m]; default from 1 / length up to the Nyquist
        frequency 1 / (2 spacing) (exclusive).
    method : {"cosines", "white_noise"}
        ``"cosines"``: sum of cosines with random phases at n_i = i / length (the profile is
        periodic over ``length``; its variance is sum Gd(n_i) dn exactly). ``"white_noise"``: the
        shaping filter driven by white noise, sampled exactly (waviness 2 only; with cut_on = 0 a
        random walk starting at 0).

    Returns
    -------
    RoadProfile
        round(length / spacing) samples from x = 0; a ``"cosines"`` profile carries its Fourier
        coefficients (exact shifts and slopes).

    Raises
    ------
    ParameterError
        For a bad spectrum, length or spacing (fewer than 4 samples), an empty band, or an
        unknown ``method``.

    References
    ----------
    .. [1] M. Shinozuka and C.-M. Jan, "Digital simulation of random processes and its
       applications", J. Sound Vib. 25(1), 111-128, 1972.
    .. [2] ISO 8608:2016, *Mechanical vibration -- Road surface profiles -- Reporting of measured
       data*, clause 5 and annex C.

    Examples
    --------
    >>> import numpy as np
    >>> from vehdyn.road import RoadSpectrum, synthesize_profile
    >>> profile = synthesize_profile("C", length=200.0, spacing=0.05, seed=1)
    >>> profile.distance.size, profile.length
    (4000, 200.0)
    >>> n = np.arange(1, 2000) / profile.length                  # the components, below Nyquist
    >>> exact = np.sum(RoadSpectrum.from_class("C").psd(n)) / profile.length
    >>> bool(np.isclose(profile.elevation.var(), exact, rtol=1e-12))   # sum Gd(n_i) dn [m^2]
    True
    """
    if not isinstance(spectrum, RoadSpectrum):
        spectrum = RoadSpectrum.from_class(spectrum)
    N, dx = _grid(length, spacing)
    x = np.arange(N) * dx
    rng = _rng(seed)
    if method == "cosines":
        i, A = _cosine_amplitudes(spectrum, N, dx, n_min, n_max)
        c = np.zeros(i[-1] + 1, dtype=complex)
        c[i] = A * np.exp(1j * rng.uniform(0.0, 2.0 * np.pi, i.size))
        profile = RoadProfile(x, np.zeros(N), c)
        return RoadProfile(x, profile._spectral(1.0), c)
    if method == "white_noise":
        from scipy.signal import lfilter

        spectrum._require_rational()
        # in distance: dz/dx = -a z + s w(x), a = 2 pi n_c, s = 2 pi n0 sqrt(Gd0 / 2) (speed 1 m/s)
        a = 2.0 * np.pi * spectrum.cut_on
        s = spectrum.white_noise_gain(1.0)
        if a > 0:
            phi = np.exp(-a * dx)
            q = s**2 * (1.0 - phi**2) / (2.0 * a)
            z0 = rng.normal(0.0, s / np.sqrt(2.0 * a))  # stationary start
        else:
            phi, q, z0 = 1.0, s**2 * dx, 0.0
        e = rng.normal(0.0, np.sqrt(q), N)
        e[0] = z0
        return RoadProfile(x, lfilter([1.0], [1.0, -phi], e))
    raise ParameterError(f"method must be 'cosines' or 'white_noise', got {method!r}", key="method", value=method)


def synthesize_parallel_profiles(
    spectrum: RoadSpectrum | str | float,
    length: float,
    spacing: float,
    track_width: float,
    *,
    seed=None,
    n_min: float | None = None,
    n_max: float | None = None,
) -> tuple[RoadProfile, RoadProfile]:
    r"""Left and right profiles a track apart with the isotropic coherence of :func:`isotropic_coherence`.

    .. math::

        z_l(x) = \sum_i A_i \cos(2 \pi n_i x + \varphi_i), \qquad
        z_r(x) = \sum_i A_i \left[\rho_i \cos(2 \pi n_i x + \varphi_i)
        + \sqrt{1 - \rho_i^2} \cos(2 \pi n_i x + \psi_i)\right]

    with independent phases phi, psi: both tracks have the spectrum Gd, their cross-spectrum is
    rho Gd.

    Parameters
    ----------
    spectrum : RoadSpectrum, str or float
        The spectrum, an ISO 8608 class letter or Gd(n0) [m^3].
    length, spacing : float
        Profile length and sample spacing [m].
    track_width : float
        Distance between the tracks [m].
    seed : int or numpy Generator, optional
        Makes the phases reproducible.
    n_min, n_max : float, optional
        Band of the components [cycles/m] (see :func:`synthesize_profile`).

    Returns
    -------
    left, right : RoadProfile

    References
    ----------
    .. [1] C. J. Dodds and J. D. Robson, "The description of road surface roughness", J. Sound
       Vib. 31(2), 175-183, 1973.
    """
    if not isinstance(spectrum, RoadSpectrum):
        spectrum = RoadSpectrum.from_class(spectrum)
    N, dx = _grid(length, spacing)
    x = np.arange(N) * dx
    rng = _rng(seed)
    i, A = _cosine_amplitudes(spectrum, N, dx, n_min, n_max)
    rho = isotropic_coherence(i / (N * dx), track_width, spectrum.waviness)
    e1 = np.exp(1j * rng.uniform(0.0, 2.0 * np.pi, i.size))
    e2 = np.exp(1j * rng.uniform(0.0, 2.0 * np.pi, i.size))
    cl = np.zeros(i[-1] + 1, dtype=complex)
    cr = np.zeros(i[-1] + 1, dtype=complex)
    cl[i] = A * e1
    cr[i] = A * (rho * e1 + np.sqrt(np.clip(1.0 - rho**2, 0.0, None)) * e2)
    empty = RoadProfile(x, np.zeros(N), cl)
    return RoadProfile(x, empty._spectral(1.0, cl), cl), RoadProfile(x, empty._spectral(1.0, cr), cr)


def iso8608_class_of(gd0: float) -> str:
    """ISO 8608 class letter of a spectrum level: classes are bands a factor 4 wide around the geometric means.

    Parameters
    ----------
    gd0 : float
        Gd(n0) [m^3], > 0.

    Returns
    -------
    str
        ``"A"`` ... ``"H"``: the lower limit of a class is its geometric mean / 2, the upper limit
        its geometric mean * 2 (A has no lower limit, H no upper one).

    References
    ----------
    .. [1] ISO 8608:2016, *Mechanical vibration -- Road surface profiles -- Reporting of measured
       data*, clause 5 and annex C.
    """
    g = _positive(gd0, "gd0")
    k = int(np.floor(np.log(g / 16e-6 * 2.0) / np.log(4.0)))  # 0 for A: [8e-6, 32e-6) and below
    return "ABCDEFGH"[min(max(k, 0), 7)]


def estimate_spectrum(profile: "RoadProfile", n_low: float = 0.011, n_high: float = 2.83):
    """Gd(n0) and ISO 8608 class of a measured profile, for waviness 2.

    The displacement PSD is estimated by Welch's method (Hann windows, segments of at least 1 / n_low
    or a quarter of the profile), compensated by (n / n0)^2 and averaged first within each octave
    band of [n_low, n_high], then geometrically over the octaves.

    Parameters
    ----------
    profile : RoadProfile
        The measured profile.
    n_low, n_high : float
        Band [cycles/m] (default: ISO 8608's range, 0.011 to 2.83 cycles/m); ``n_high`` is
        limited to 0.8 times the Nyquist frequency.

    Returns
    -------
    gd0 : float
        Estimated Gd(n0) [m^3].
    class_letter : str
        Its ISO 8608 class (:func:`iso8608_class_of`).

    References
    ----------
    .. [1] ISO 8608:2016, *Mechanical vibration -- Road surface profiles -- Reporting of measured
       data*, clause 5 and annex C.
    .. [2] P. D. Welch, "The use of fast Fourier transform for the estimation of power spectra",
       IEEE Trans. Audio Electroacoust. 15(2), 70-73, 1967.
    """
    from scipy.signal import welch

    if not isinstance(profile, RoadProfile):
        raise ParameterError("profile must be a RoadProfile", key="profile", value=type(profile).__name__)
    lo, hi = _positive(n_low, "n_low"), _positive(n_high, "n_high")
    nyq = 0.5 / profile.spacing
    hi = min(hi, 0.8 * nyq)
    if lo >= hi:
        raise ParameterError(f"no band left between n_low = {lo} and min(n_high, 0.8 Nyquist) = {hi} cycles/m",
                             key="n_low", value=lo)
    N = profile.elevation.size
    nperseg = int(min(N, max(N // 4, 2 ** np.ceil(np.log2(4.0 / (lo * profile.spacing))))))
    n, G = welch(profile.elevation - profile.elevation.mean(), fs=1.0 / profile.spacing, nperseg=nperseg)
    r = G * (n / ISO8608_REFERENCE_FREQUENCY) ** 2
    edges = lo * 2.0 ** np.arange(0, np.log2(hi / lo) + 1e-9)
    edges = np.append(edges, hi) if edges[-1] < hi else edges
    means = [r[(n >= a) & (n < b)].mean() for a, b in zip(edges[:-1], edges[1:]) if np.any((n >= a) & (n < b))]
    if not means:
        raise ParameterError("the profile is too short for its band: no PSD estimate falls in it", key="profile",
                             value=N * profile.spacing)
    gd0 = float(np.exp(np.mean(np.log(means))))
    return gd0, iso8608_class_of(gd0)


# --------------------------------------------------------------------------- discrete events
