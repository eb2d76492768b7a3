"""Stationary random response of any linear ride model to an ISO 8608 road: r.m.s. of every output.

Road inputs are recognized by name: ``road_displacement<suffix>`` [m] and ``road_velocity<suffix>``
[m/s]; a suffix containing ``rear`` is the same track delayed by tau = wheelbase / V, one
containing ``left`` or ``right`` is on that track (e.g. ``road_displacement_front_left``); other
inputs are held at zero. Three routes give the same numbers:

``"lyapunov"`` (exact covariance)
    The road shaping filter (:meth:`RoadSpectrum.shaping_filter`, waviness 2) is appended to the
    model as :func:`vehdyn.connect_in_series` does and the state covariance X solves
    A X + X A^T + B B^T = 0 (unit-intensity white noise); var(y) = C X C^T. Without a cut-on
    (the ISO spectrum itself) the road is an integrated white noise: the integrator states are
    removed exactly by relative coordinates (:func:`stationary_covariance`), and outputs that see
    them (non-zero gain to a uniform lift of the road, such as absolute displacements) have
    infinite variance; outputs with white-noise feedthrough (e.g. a tire load through tire damping)
    also return ``inf``.
    Rear inputs, ``delay="exact"`` (default): no approximation. The state is the sum of one copy
    of the model per road point (front, rear; left, right), each driven as if under the front axle
    by the same undelayed road; the cross-covariance of two copies at lag tau is e^(A tau) P (plus,
    without cut-on, the random-walk increment over tau, int_0^tau e^(A u) du =
    A^-1 (e^(A tau) - I)). It agrees with ``"psd"`` within 1e-8 from 3 to 40 m/s, at about the
    cost of the Pade route.
    ``delay="pade"``: the front road is delayed through the Pade approximant of e^(-s tau)
    (:func:`vehdyn.ride.wheelbase.pade_delay`) of order ``pade_order`` (default 10, at most 12)
    before it reaches the rear inputs; this is then the only approximation of the route. For a
    half car (wheelbase 2.7 m) its r.m.s. error against the exact delay is, at 20 m/s
    (tau = 0.135 s), 3 % at order 4, 4e-5 at order 8 and 3e-7 at order 10; at order 10 it grows as
    the speed falls (omega tau at wheel hop): 4e-8 at 40 m/s, 7e-4 at 10 m/s, 2 % at 5 m/s.
    (Several Pade sections in series delay better but lose more to rounding in outputs such as the
    tire load.) Kept for comparison with the state-space models of
    :func:`vehdyn.ride.with_wheelbase_delay`, which use the same approximant.
    Left and right tracks must be ``"identical"`` or ``"independent"`` in this route (the
    isotropic coherence is not rational).
``"psd"`` (frequency-domain integral with a stated error; exact delay)
    var(y) = int_0^inf sum_{s,t} H_s(f) S_st(f) H_t(f)^* df with the exact delay e^(-j 2 pi f tau),
    the temporal road PSD G_z(f) and the track coherence (isotropic by default), with H from the
    modal form of A (one eigendecomposition; the products with the modal residues taken in blocks
    of frequencies). The integral is taken over ln f on Gauss-Kronrod
    7-15 panels (4 per decade; graded towards every resonance: edges at its damped frequency f_d
    and at f_d +- gamma 2^k, k = 0, 1, ... up to f_d / 2, with gamma = zeta omega_n / (2 pi) the
    half-power half-width, so that a peak of any sharpness is resolved, at about 2 log2(1 / zeta)
    panels per mode; and, with a delay, no wider than 1/tau, one period of the delay's phase, up
    to the frequency f_c beyond which the envelope of the oscillating delay terms integrates to
    less than 1e-6 of the variance) from 1e-3 times the lowest to 1e3 times the
    highest natural frequency; beyond, power-law tails fitted at the ends are added. The reported
    error bound is the sum over the panels of |K15 - G7| (the 15-point Kronrod result is kept; the
    difference from the embedded 7-point Gauss rule bounds its error generously), plus the change
    of each tail when its exponent is fitted a decade further in, plus the envelope of the
    oscillating terms dropped above f_c, plus the rounding of the modal sums (an output whose terms
    cancel to that rounding, such as roll on identical left and right tracks, is reported as 0),
    plus 10 eps / zeta of the variance for the rounding of the frequencies near the sharpest
    resonance (it matters only below zeta ~ 1e-6).
    Tested on part A's QuarterCar, BouncePitch and FullCar (all outputs, three vehicles): the
    routes agree within 2e-9 (exact delay) and 4e-6 (Pade), and agree on which outputs are
    unbounded; and on quarter cars, half and full cars with damping ratios from 1e-4 to 1 (down
    to 2e-10 for the quarter car): the Lyapunov result lies within the PSD route's bound.
``"simulation"`` (time domain, for checking; exact delay)
    A sum-of-cosines profile (:func:`synthesize_profile`) of ``duration`` seconds of road, sampled
    under each axle by :meth:`RoadProfile.road_inputs` (the rear shifted exactly by the wheelbase),
    exact-discretization simulation (:func:`vehdyn.simulate`), r.m.s. after a settling time, and
    its statistical standard error from batch means.
"""

from __future__ import annotations

import re
import time as _time
from dataclasses import dataclass, field

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.road import RoadSpectrum, synthesize_parallel_profiles, synthesize_profile
from vehdyn.interconnect import pade_delay

__all__ = ["RandomResponse", "random_response", "road_channels", "stationary_covariance"]

_ROAD_INPUT = re.compile(r"^road_(displacement|velocity)(.*)$")


@dataclass(frozen=True)
class _Channel:
    index: int  # model input index
    kind: str  # "displacement" | "velocity"
    suffix: str
    delayed: bool  # rear axle
    track: str  # "coherent" (one track), "left" or "right"


def road_channels(model) -> list[_Channel]:
    """The road inputs of ``model`` (by name), each with its kind, axle (delayed or not) and track.

    Parameters
    ----------
    model : LinearModel
        With inputs ``road_displacement<suffix>`` [m] / ``road_velocity<suffix>`` [m/s]; a suffix
        with ``rear`` is delayed by the wheelbase, one with ``left`` or ``right`` on that track.

    Returns
    -------
    list
        One record per road input: its index among the model's inputs, ``kind``
        (``"displacement"`` or ``"velocity"``), ``suffix``, ``delayed`` (bool) and ``track``
        (``"coherent"``, ``"left"`` or ``"right"``).

    Raises
    ------
    ParameterError
        When the model has no road input, or mixes one track with left/right tracks.
    """
    channels = []
    for k, name in enumerate(model.input_names):
        m = _ROAD_INPUT.match(name)
        if not m:
            continue
        kind, suffix = m.groups()
        tokens = set(suffix.strip("_").split("_"))
        track = "left" if "left" in tokens else "right" if "right" in tokens else "coherent"
        channels.append(_Channel(k, kind, suffix, "rear" in tokens, track))
    if not channels:
        raise ParameterError(f"{model.name!r} has no road input (road_displacement*, road_velocity*); its inputs are "
                             f"{list(model.input_names)}", key="model", value=model.name)
    sides = {c.track for c in channels}
    if "coherent" in sides and len(sides) > 1:
        raise ParameterError("road inputs mix a single track with left/right tracks", key="model", value=model.name)
    return channels


@dataclass
class RandomResponse:
    """R.m.s. of each output of a ride model on a random road.

    Attributes
    ----------
    outputs : tuple of Signal
    rms : ndarray
        R.m.s. of each output [unit of the output] (``inf`` where the variance is unbounded).
    error : ndarray
        Error of ``rms`` [unit of the output]: 0 for ``"lyapunov"`` (exact up to rounding and the
        Pade delay), the estimated error bound for ``"psd"``, one standard error for
        ``"simulation"``.
    method : str
        ``"lyapunov"``, ``"psd"`` or ``"simulation"``.
    speed : float
        [m/s].
    spectrum : RoadSpectrum
        The road.
    wall_time : float
        [s].
    info : dict
        What the route reports of itself (grid sizes, panels, the delay used, ...).
    """

    outputs: tuple
    rms: np.ndarray
    error: np.ndarray
    method: str
    speed: float
    spectrum: RoadSpectrum
    wall_time: float = 0.0
    info: dict = field(default_factory=dict)

    @property
    def output_names(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.outputs)

    def __getitem__(self, name: str) -> float:
        try:
            return float(self.rms[self.output_names.index(name)])
        except ValueError:
            raise ParameterError(f"no output {name!r}; outputs are {list(self.output_names)}", key="name",
                                 value=name) from None

    def to_frame(self):
        """The r.m.s. values as a table.

        Returns
        -------
        pandas.DataFrame
            Indexed by ``output``: columns ``rms`` and ``error``; units in ``attrs["units"]``.
        """
        import pandas as pd

        df = pd.DataFrame({"rms": self.rms, "error": self.error}, index=pd.Index(self.output_names, name="output"))
        df.attrs["units"] = {s.name: s.unit for s in self.outputs}
        return df


# --------------------------------------------------------------------------- entry point
def random_response(
    model,
    road,
    speed: float,
    *,
    method: str = "lyapunov",
    wheelbase: float | None = None,
    track_width: float | None = None,
    track_coherence: str = "isotropic",
    outputs=None,
    pade_order: int = 10,
    delay: str = "exact",
    duration: float = 100.0,
    sample_rate: float = 500.0,
    seed=None,
    n_max: float | None = None,
) -> RandomResponse:
    r"""R.m.s. of the outputs of a linear ride ``model`` driven at ``speed`` over the random road ``road``.

    Parameters
    ----------
    model : LinearModel
        Any ride model with road inputs named ``road_displacement<suffix>`` / ``road_velocity<suffix>``.
    road : RoadSpectrum, class letter or Gd(n0) [m^3]
    speed : float
        [m/s].
    method : {"lyapunov", "psd", "simulation"}
        See the module docstring.
    wheelbase : float, optional
        [m]; needed when the model has rear inputs (default: ``model.wheelbase`` where the model
        has one, as :class:`~vehdyn.ride.BouncePitch` and :class:`~vehdyn.ride.FullCar`).
    track_width : float, optional
        [m]; needed for left/right inputs with the isotropic coherence.
    track_coherence : {"isotropic", "identical", "independent"}
        Left-right coherence (isotropic: :func:`vehdyn.road.isotropic_coherence`).
    outputs : sequence of str, optional
        Restrict to these outputs.
    pade_order : int
        Order of the Pade delay (``"lyapunov"`` with ``delay="pade"``).
    delay : {"exact", "pade"}
        How the Lyapunov route delays the rear inputs: exactly, through lagged covariances
        (default), or by a Pade approximant appended to the road filter (see the module docstring).
        The ``"psd"`` and ``"simulation"`` routes always use the exact delay.
    duration, sample_rate, seed, n_max : ``"simulation"`` only
        Seconds of road [s], sampling rate [Hz], random seed, highest spatial frequency of the
        profile [cycles/m] (default: the Nyquist frequency of the time grid).

    Returns
    -------
    RandomResponse
        The r.m.s. of each output [its unit] and its error (``inf`` where the variance is
        unbounded, e.g. absolute displacements on a road without cut-on).

    Notes
    -----
    The Lyapunov route appends the road's shaping filter (waviness 2: the road velocity is white
    noise of one-sided PSD (2 pi n0)^2 G_d(n0) V) to the model, A and B of the whole, and solves
    for the stationary state covariance X; the PSD route integrates the output spectrum with the
    exact delay e^(-j omega tau) of the rear inputs (tau = wheelbase / V):

    .. math::

        A X + X A^T + B B^T = 0, \qquad \sigma_y^2 = C X C^T, \qquad
        \sigma_y^2 = \int_0^\infty \sum_{s,t} H_s(f) \, S_{st}(f) \, H_t(f)^* \, df

    References
    ----------
    .. [1] ISO 8608:2016, *Mechanical vibration -- Road surface profiles -- Reporting of measured
       data* (the road spectra).
    .. [2] D. E. Newland, *An Introduction to Random Vibrations, Spectral and Wavelet Analysis*,
       3rd ed., Longman, 1993, ch. 7 (transmission of random vibration).
    .. [3] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 7.3 (vehicle
       response to random road excitation).

    Examples
    --------
    A quarter car at 20 m/s on an ISO 8608 class-C road, by the exact Lyapunov route and by the
    frequency integral, which states its error bound:

    >>> from vehdyn.ride import QuarterCar, random_response
    >>> qc = QuarterCar.from_parameters(sprung_mass=250.0, unsprung_mass=35.0, spring_rate=16e3,
    ...                                 damping=1000.0, tire_stiffness=160e3)
    >>> r = random_response(qc, "C", 20.0, outputs=["sprung_acceleration", "suspension_travel"])
    >>> r.rms.round(5).tolist()  # [m/s^2, m]
    [1.37242, 0.012]
    >>> psd = random_response(qc, "C", 20.0, method="psd", outputs=["sprung_acceleration"])
    >>> bool(abs(psd["sprung_acceleration"] - r["sprung_acceleration"]) <= psd.error[0])
    True
    """
    from vehdyn.model import LinearModel

    if not isinstance(model, LinearModel):
        raise ParameterError(f"model must be a LinearModel, got {type(model).__name__} (linearize it first)",
                             key="model", value=model)
    if not model.is_stable():
        raise ParameterError(f"{model.name!r} is not asymptotically stable: its response to a random road has no "
                             "stationary variance", key="model", value=model.name)
    spectrum = road if isinstance(road, RoadSpectrum) else RoadSpectrum.from_class(road)
    V = float(speed)
    if not (np.isfinite(V) and V > 0):
        raise ParameterError(f"speed must be positive [m/s], got {speed!r}", key="speed", value=speed)
    if wheelbase is None:  # a BouncePitch or FullCar knows its own
        wheelbase = getattr(model, "wheelbase", None)
    if outputs is not None:
        model = model.select(outputs=outputs)
    channels = road_channels(model)
    tau = 0.0
    if any(c.delayed for c in channels):
        if wheelbase is None or not (np.isfinite(wheelbase) and wheelbase > 0):
            raise ParameterError(f"the model has rear road inputs: give a positive wheelbase [m], got {wheelbase!r}",
                                 key="wheelbase", value=wheelbase)
        tau = float(wheelbase) / V
    two_tracks = any(c.track != "coherent" for c in channels)
    if track_coherence not in ("isotropic", "identical", "independent"):
        raise ParameterError(f"track_coherence must be 'isotropic', 'identical' or 'independent', got "
                             f"{track_coherence!r}", key="track_coherence", value=track_coherence)
    if two_tracks and track_coherence == "isotropic" and (track_width is None or not track_width > 0):
        raise ParameterError(f"left/right road inputs with isotropic coherence need a positive track_width [m], got "
                             f"{track_width!r}", key="track_width", value=track_width)
    if delay not in ("pade", "exact"):
        raise ParameterError(f"delay must be 'exact' or 'pade', got {delay!r}", key="delay", value=delay)
    if not (isinstance(pade_order, (int, np.integer)) and 1 <= pade_order <= 12):
        raise ParameterError(f"pade_order must be an integer from 1 to 12 (higher orders lose accuracy to rounding), "
                             f"got {pade_order!r}", key="pade_order", value=pade_order)
    start = _time.perf_counter()
    if method == "lyapunov" and (delay == "exact" and tau > 0):
        if two_tracks and track_coherence == "isotropic":
            raise ParameterError("the Lyapunov route needs track_coherence 'identical' or 'independent' (the "
                                 "isotropic coherence is not rational); use method='psd' for it",
                                 key="track_coherence", value=track_coherence)
        var, err, info = _lyapunov_exact_delay(model, channels, spectrum, V, tau, two_tracks, track_coherence)
    elif method == "lyapunov":
        var, err, info = _lyapunov(model, channels, spectrum, V, tau, two_tracks, track_coherence, int(pade_order))
    elif method == "psd":
        var, err, info = _psd(model, channels, spectrum, V, tau, two_tracks, track_coherence, track_width)
    elif method == "simulation":
        var, err, info = _simulation(model, channels, spectrum, V, wheelbase, two_tracks, track_coherence,
                                     track_width, duration, sample_rate, seed, n_max)
    else:
        raise ParameterError(f"method must be 'lyapunov', 'psd' or 'simulation', got {method!r}", key="method",
                             value=method)
    wall = _time.perf_counter() - start
    rms = np.sqrt(np.maximum(var, 0.0))  # a variance that cancels to zero may come out at -1e-30
    if method == "psd":  # error of the variance -> error of the r.m.s.
        with np.errstate(divide="ignore", invalid="ignore"):
            rms_err = np.where(np.isfinite(var), np.where(rms > 0, err / (2 * np.where(rms > 0, rms, 1)),
                                                          np.sqrt(err)), np.inf)
    else:
        rms_err = err
    return RandomResponse(model.output_signals, rms, np.asarray(rms_err, float), method, V, spectrum, wall, info)


# --------------------------------------------------------------------------- Lyapunov route
def _road_generator(channels, spectrum, V, tau, sources, pade_order):
    """White noise -> every road input of the model: matrices (A, B, C, D) and the integrator states.

    One shaping-filter state per noise source (the road under the front axle); a rear input is
    that state passed through the Pade delay, its velocity the derivative of the delay's output.
    Rows of C and D follow ``channels``.
    """
    a = 2.0 * np.pi * spectrum.cut_on * V
    sigma = spectrum.white_noise_gain(V)
    n_src = max(sources.values()) + 1
    used = sorted({sources[c.track] for c in channels})
    delayed_src = sorted({sources[c.track] for c in channels if c.delayed})
    pade = pade_delay(tau, pade_order) if delayed_src else None
    npd = pade[0].shape[0] if pade else 0
    n = len(used) + npd * len(delayed_src)
    xi = {k: j for j, k in enumerate(used)}
    xp = {k: len(used) + j * npd for j, k in enumerate(delayed_src)}
    A = np.zeros((n, n))
    B = np.zeros((n, n_src))
    for k in used:
        A[xi[k], xi[k]] = -a
        B[xi[k], k] = sigma
    for k in delayed_src:
        Ap, Bp, _, _ = pade
        o = xp[k]
        A[o:o + npd, o:o + npd] = Ap
        A[o:o + npd, xi[k]] = Bp[:, 0]
    C = np.zeros((len(channels), n))
    D = np.zeros((len(channels), n_src))
    for r, c in enumerate(channels):
        k = sources[c.track]
        Cz = np.zeros(n)  # displacement as a function of the state; velocity = its derivative
        if c.delayed:
            _, _, Cp, Dp = pade
            Cz[xp[k]:xp[k] + npd] = Cp[0]
            Cz[xi[k]] = Dp[0, 0]
        else:
            Cz[xi[k]] = 1.0
        if c.kind == "displacement":
            C[r] = Cz
        else:
            C[r] = Cz @ A
            D[r] = Cz @ B
    return A, B, C, D, [xi[k] for k in used]


def _sources(two_tracks, coherence):
    if not two_tracks or coherence == "identical":
        return {"coherent": 0, "left": 0, "right": 0}
    return {"left": 0, "right": 1, "coherent": 0}


def _eigen(A, blocks: int = 1, max_cond: float = 1e6):
    """Eigendecomposition (lam, V, V^-1) of A, or None when V is singular or its 1-norm condition exceeds max_cond.

    With ``blocks`` > 1, A is block-diagonal with that many equal blocks (copies of one model):
    one eigendecomposition of the block serves them all.
    """
    n = A.shape[0] // blocks
    lam, V = np.linalg.eig(A[:n, :n])
    try:
        Vi = np.linalg.inv(V)
    except np.linalg.LinAlgError:
        return None
    if np.linalg.norm(V, 1) * np.linalg.norm(Vi, 1) > max_cond:
        return None
    if blocks > 1:
        Vb, Vib = np.zeros((2, n * blocks, n * blocks), dtype=V.dtype)
        for k in range(blocks):
            Vb[k * n:(k + 1) * n, k * n:(k + 1) * n] = V
            Vib[k * n:(k + 1) * n, k * n:(k + 1) * n] = Vi
        lam, V, Vi = np.tile(lam, blocks), Vb, Vib
    return lam, V, Vi


def _lyapunov_solve(A, Q, eigen=None):
    """X with A X + X A^T + Q = 0.

    Up to 10 states (and no eigendecomposition at hand): one dense solve of the Kronecker form
    (I (x) A + A (x) I) vec X = -vec Q. Otherwise the modal solution from ``eigen`` (see
    :func:`_eigen`; computed when not given), checked by its residual; scipy's Bartels-Stewart
    solver if the check fails or the eigenvectors are ill-conditioned.
    """
    n = A.shape[0]
    if n <= 10 and eigen is None:
        eye = np.eye(n)
        K = (eye[:, None, :, None] * A[None, :, None, :] + A[:, None, :, None] * eye[None, :, None, :])
        X = np.linalg.solve(K.reshape(n * n, n * n), -Q.reshape(-1)).reshape(n, n)
        return 0.5 * (X + X.T)
    if eigen is None:
        eigen = _eigen(A, max_cond=np.inf)  # the residual check below judges the result
    if eigen is not None:
        lam, V, Vi = eigen
        W = Vi @ Q @ Vi.conj().T
        X = (V @ (W / -(lam[:, None] + lam.conj()[None, :])) @ V.conj().T).real
        scale = np.abs(Q).max() + np.abs(A).max() * np.abs(X).max()
        if np.abs(A @ X + X @ A.T + Q).max() <= 1e-10 * scale:
            return X
    from scipy.linalg import solve_continuous_lyapunov

    return solve_continuous_lyapunov(A, -Q)


def _drifts(gain, terms, row_sum, A_rest):
    """Outputs that see an integrator (unbounded variance), from their gain to a unit integrator value.

    A true gain is comparable to the terms it sums (``terms`` = |C_r| |R_r| + |C_xi|) and to the
    output's coefficients (``row_sum`` = sum |C|, states moving by O(1) under a unit lift of the
    road); rounding leaves about cond(A_rest) eps of the terms (taken as at most 1e-6: cond is a
    pessimistic bound, and a real gain, such as the warp of a car with unequal tracks on independent
    left and right random-walk tracks, can be a few 1e-4 of its terms).
    """
    g = np.abs(gain).max(axis=1)
    t = np.maximum(np.max(terms, axis=1), 1e-300)
    drift = (g > 1e-9 * t) & (g > 1e-9 * row_sum)
    if drift.any():  # only then is the conditioning worth its SVD
        drift &= g > min(1e-6, max(1e-9, 1e3 * np.finfo(float).eps * np.linalg.cond(A_rest))) * t
    return drift


def stationary_covariance(A, B, C, D=None, integrators=(), output_scale=None):
    """Stationary output covariance of dx/dt = A x + B w, y = C x + D w (unit-intensity white noise w).

    Parameters
    ----------
    A, B, C, D : ndarray
        The state-space matrices, in the units of the states, the noise and the outputs
        [state units/s, state units/(s * noise unit), output/state unit, output/noise unit]; D
        defaults to zeros.
    integrators : sequence of int
        States whose rows of A are zero (random walks, e.g. the ISO 8608 road without cut-on).
    output_scale : array_like, optional
        Typical size of each output per unit change of the states [output unit/state unit]
        (default: the row sums of |C|); a gain to an integrator below 1e-9 of it is taken as
        rounding.

    Returns
    -------
    Y : ndarray, shape (n_outputs, n_outputs)
        Output covariance; ``inf`` on the diagonal (and nan off it) for outputs with unbounded
        variance: those that see an integrator, or white noise through D.

    Notes
    -----
    The integrators xi are removed exactly by relative coordinates: with R_r = -A_rr^-1 A_rxi (the
    other states' equilibrium for a unit value of each integrator), x' = x_r - R_r xi obeys
    dx'/dt = A_rr x' + (B_r - R_r B_xi) w and y = C_r x' + (C_r R_r + C_xi) xi + D w. The
    covariance X of x' solves A_rr X + X A_rr^T + B' B'^T = 0 (one eigendecomposition; scipy's
    Bartels-Stewart solver if the modal solution fails its residual check); an output has a
    stationary variance only where C_r R_r + C_xi = 0.
    """
    A, B, C = (np.asarray(M, dtype=float) for M in (A, B, C))
    D = np.zeros((C.shape[0], B.shape[1])) if D is None else np.asarray(D, dtype=float)
    idx = list(integrators)
    if idx:
        if np.any(A[idx] != 0):
            raise ParameterError("integrator states must have zero rows in A", key="integrators", value=idx)
        rest = [k for k in range(A.shape[0]) if k not in idx]
        Arr = A[np.ix_(rest, rest)]
        Rr = -np.linalg.solve(Arr, A[np.ix_(rest, idx)])
        Bp = B[rest] - Rr @ B[idx]
        drift_gain = C[:, rest] @ Rr + C[:, idx]
        terms = np.abs(C[:, rest]) @ np.abs(Rr) + np.abs(C[:, idx])
        row = np.abs(C).sum(axis=1) if output_scale is None else np.asarray(output_scale, dtype=float)
        drift = _drifts(drift_gain, terms, row, Arr)
        A, B, C = Arr, Bp, C[:, rest]
    else:
        drift = np.zeros(C.shape[0], dtype=bool)
    X = _lyapunov_solve(A, B @ B.T)
    Y = C @ X @ C.T
    bad = drift | (np.abs(D).max(axis=1, initial=0.0) > 0)
    if bad.any():
        Y[bad, :] = np.nan
        Y[:, bad] = np.nan
        Y[bad, bad] = np.inf
    return Y


def _lyapunov(model, channels, spectrum, V, tau, two_tracks, coherence, pade_order):
    if two_tracks and coherence == "isotropic":
        raise ParameterError("the Lyapunov route needs track_coherence 'identical' or 'independent' (the isotropic "
                             "coherence is not rational); use method='psd' for it", key="track_coherence",
                             value=coherence)
    Ag, Bg, Cg, Dg, integrators = _road_generator(channels, spectrum, V, tau, _sources(two_tracks, coherence),
                                                  pade_order)
    # the generator appended in series, as vehdyn.connect_in_series(generator, model) does (matrix form)
    idx = [c.index for c in channels]
    Bm, Dm = model.B[:, idx], model.D[:, idx]
    ng = Ag.shape[0]
    A = np.zeros((ng + model.n_states,) * 2)
    A[:ng, :ng] = Ag
    A[ng:, :ng] = Bm @ Cg
    A[ng:, ng:] = model.A
    B = np.vstack([Bg, Bm @ Dg])
    C = np.hstack([Dm @ Cg, model.C])
    D = Dm @ Dg
    # the model's own coefficients give each output's scale (the road generator's may be large: Pade states)
    scale = np.abs(model.C).sum(axis=1) + np.abs(Dm).sum(axis=1)
    Y = stationary_covariance(A, B, C, D, integrators if spectrum.cut_on == 0 else (), output_scale=scale)
    var = np.diag(Y).copy()
    return var, np.zeros_like(var), {"n_states": A.shape[0], "pade_order": pade_order if tau > 0 else 0}


def _expm(A, t, eigen=None):
    """e^(A t) from the eigendecomposition ``eigen`` (:func:`_eigen`) when it is well conditioned, else scipy's expm."""
    if eigen is not None:
        lam, V, Vi = eigen
        return ((V * np.exp(lam * t)) @ Vi).real
    from scipy.linalg import expm

    return expm(A * t)


def _lyapunov_exact_delay(model, channels, spectrum, V, tau, two_tracks, coherence):
    """Exact covariance with the exact delay: lagged covariances through the matrix exponential.

    The model is linear, so its state is x(t) = sum_p x_p(t - tau_p): one copy x_p per road point
    p = (source, axle), driven by that point's inputs as if it were under the front axle. All
    copies and the road states xi share the undelayed noise: z = [xi; x_p ...], covariance P from
    the Lyapunov equation, and Cov(z(t), z(t - tau)) = e^(A tau) P. Without cut-on the road is a
    random walk: z' = z - R xi (relative coordinates, as in :func:`stationary_covariance`) and the
    rear axle sees xi(t - tau) = xi(t) - Delta, whose increment Delta over tau has variance
    tau B_xi B_xi^T and covariance int_0^tau e^(A'u) du B' B_xi^T = A'^-1 (e^(A' tau) - I) B' B_xi^T
    with z'(t).
    """

    sources = _sources(two_tracks, coherence)
    used = sorted({sources[c.track] for c in channels})
    S = len(used)
    col = {k: j for j, k in enumerate(used)}
    a = 2.0 * np.pi * spectrum.cut_on * V
    sigma = spectrum.white_noise_gain(V)
    groups = sorted({(sources[c.track], c.delayed) for c in channels})
    n, p_out = model.n_states, model.n_outputs
    nz = S + n * len(groups)
    A = np.zeros((nz, nz))
    B = np.zeros((nz, S))
    A[:S, :S] = -a * np.eye(S)
    B[:S, :S] = sigma * np.eye(S)
    E = []
    white = np.zeros(p_out, dtype=bool)
    for g, (src, delayed) in enumerate(groups):
        o = S + g * n
        A[o:o + n, o:o + n] = model.A
        Eg = np.zeros((p_out, nz))
        Eg[:, o:o + n] = model.C
        j = col[src]
        for c in channels:
            if (sources[c.track], c.delayed) != (src, delayed):
                continue
            # road displacement = xi, road velocity = -a xi + sigma w
            gain = 1.0 if c.kind == "displacement" else -a
            A[o:o + n, j] += gain * model.B[:, c.index]
            Eg[:, j] += gain * model.D[:, c.index]
            if c.kind == "velocity":
                B[o:o + n, j] += sigma * model.B[:, c.index]
                white |= model.D[:, c.index] != 0
        E.append(Eg)
    front = [g for g, (_, d) in enumerate(groups) if not d]
    rear = [g for g, (_, d) in enumerate(groups) if d]
    if spectrum.cut_on > 0:
        eigen = _eigen(A)  # one eigendecomposition for the Lyapunov equation and the matrix exponential
        P = _lyapunov_solve(A, B @ B.T, eigen)
        lag = _expm(A, tau, eigen) @ P  # Cov(z(t), z(t - tau))
        Ez, var_extra, drift = E, np.zeros(p_out), np.zeros(p_out, dtype=bool)
    else:
        rest = np.arange(S, nz)
        Arr = A[S:, S:]
        Rr = -np.linalg.solve(Arr, A[S:, :S])
        Bp = B[S:] - Rr @ B[:S]
        G = [Eg[:, S:] @ Rr + Eg[:, :S] for Eg in E]
        g_sum = sum(G)
        terms = sum(np.abs(Eg[:, S:]) @ np.abs(Rr) + np.abs(Eg[:, :S]) for Eg in E)
        drift = _drifts(g_sum, terms, np.abs(model.C).sum(axis=1) + np.abs(model.D).sum(axis=1), Arr)
        g_rear = sum(G[g] for g in rear)
        # Arr is block-diagonal, one copy of the model per road point: one eigendecomposition of the model
        # serves the Lyapunov equation and the matrix exponential
        eigen = _eigen(Arr, blocks=len(groups))
        P = _lyapunov_solve(Arr, Bp @ Bp.T, eigen)
        Phi = _expm(Arr, tau, eigen)
        lag = Phi @ P
        psi = np.linalg.solve(Arr, (Phi - np.eye(Arr.shape[0])) @ (Bp @ B[:S].T))  # Cov(z'(t), Delta)
        Ez = [Eg[:, rest] for Eg in E]
        cross = sum(Ez[g] @ psi for g in front)  # Cov(y_z, Delta)
        var_extra = (-2.0 * np.einsum("ij,ij->i", cross, g_rear)
                     + np.einsum("ij,jk,ik->i", g_rear, tau * (B[:S] @ B[:S].T), g_rear))
    var = var_extra.copy()
    for gp in range(len(groups)):
        for gq in range(len(groups)):
            dp, dq = groups[gp][1], groups[gq][1]
            if dp == dq:
                M = P
            elif not dp:  # p front (t), q rear (t - tau)
                M = lag
            else:
                M = lag.T
            var += np.einsum("ij,jk,ik->i", Ez[gp], M, Ez[gq])
    var = np.where(drift | white, np.inf, var)
    return var, np.zeros_like(var), {"n_states": nz, "delay": "exact (matrix exponential)"}


# --------------------------------------------------------------------------- PSD route
# Gauss-Kronrod 7-15 rule on [-1, 1] (QUADPACK's qk15 constants; Piessens et al. 1983): the 7 Gauss
# nodes are the odd-indexed Kronrod nodes, so one set of 15 evaluations gives both rules.
_XK = np.array([0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                0.207784955007898467600689403773245, 0.0])
_WK = np.array([0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                0.204432940075298892414161999234649, 0.209482141084727828012999174891714])
_WG = np.array([0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                0.381830050505118944950369775488975, 0.417959183673469387755102040816327])
GAUSS_KRONROD_15 = (np.concatenate([-_XK[:-1], _XK[::-1]]), np.concatenate([_WK[:-1], _WK[::-1]]))
GAUSS_7_IN_15 = np.concatenate([np.r_[0, _WG[0], 0, _WG[1], 0, _WG[2], 0], [_WG[3]],
                                np.r_[0, _WG[2], 0, _WG[1], 0, _WG[0], 0]])
"""Weights of the 7-point Gauss rule on the 15 Kronrod nodes (zero on the Kronrod-only nodes)."""


_BLOCK = 256  # frequencies per matrix product in the PSD route


class _Spectra:
    """Output PSD of a model on the road, evaluated through the modal form of A (one eigendecomposition)."""

    def __init__(self, model, channels, spectrum, V, tau, two_tracks, coherence, track_width):
        from vehdyn.road import isotropic_coherence

        self.spectrum, self.V, self.tau = spectrum, V, tau
        self.isotropic = isotropic_coherence
        self.track_width = track_width
        idx = [c.index for c in channels]
        lam, Vm = np.linalg.eig(model.A)
        B = model.B[:, idx]
        self.cond = float(np.linalg.cond(Vm)) if lam.size else 1.0
        ok = self.cond < 1e8
        self.modal = bool(ok)
        if self.modal:
            self.lam, self.CV, self.WB = lam, model.C @ Vm, np.linalg.solve(Vm, B)
            # residues R[k * p + i, j] = CV[i, j] WB[j, k] of input k, output i, mode j
            self.residues = (self.CV[:, :, None] * self.WB[None, :, :]).transpose(2, 0, 1).reshape(-1, lam.size)
            self.abs_residues = (np.abs(self.CV)[:, :, None] * np.abs(self.WB)[None, :, :]).transpose(
                2, 0, 1).reshape(-1, lam.size)
        self.model, self.idx, self.D = model, idx, model.D[:, idx]
        # road points: (track, delayed) -> channels; each point has one transfer function
        self.points = sorted({(c.track, c.delayed) for c in channels})
        self.member = np.array([[1.0 if (c.track, c.delayed) == pt else 0.0 for c in channels] for pt in self.points])
        self.velocity = np.array([c.kind == "velocity" for c in channels])
        self.two_tracks, self.coherence = two_tracks, coherence

    def _transfer(self, omega):
        """Per road point: response per unit road displacement there, shape (points, outputs, f)."""
        s = 1j * omega
        if self.modal:
            G = 1.0 / (s[None, :] - self.lam[:, None])  # (n, f), contiguous for BLAS
            m, p = self.WB.shape[1], self.CV.shape[0]
            # H[k, i, f] = sum_j CV[i, j] WB[j, k] G[j, f]: one product with the residue matrix; and the same in
            # absolute values, the size of the terms, where the modal terms cancel (far below or above the
            # modes) their rounding can exceed |H|: those frequencies are solved directly. The frequency axis is
            # taken in blocks: multithreaded BLAS on one long product of small matrices is several times slower.
            H = np.empty((m * p, s.size), dtype=complex)
            floor = np.empty((m * p, s.size))
            aG = np.abs(G)
            for i in range(0, s.size, _BLOCK):
                H[:, i:i + _BLOCK] = self.residues @ G[:, i:i + _BLOCK]
                floor[:, i:i + _BLOCK] = self.abs_residues @ aG[:, i:i + _BLOCK]
            H = H.reshape(m, p, s.size) + self.D.T[:, :, None]
            floor = floor.reshape(m, p, s.size)
            bad = np.any(np.abs(H) < 1e4 * np.finfo(float).eps * floor, axis=(0, 1))
            if bad.any():
                H[:, :, bad] = np.moveaxis(self.model.frequency_response(omega[bad]).response[:, self.idx, :], 1, 0)
        else:
            H = np.moveaxis(self.model.frequency_response(omega).response[:, self.idx, :], 1, 0)
        H = np.where(self.velocity[:, None, None], H * s[None, None, :], H)
        return np.einsum("km,mpf->kpf", self.member, H)

    def _rho(self, f, tr1, tr2):
        if tr1 == tr2:
            return 1.0
        if self.coherence == "identical":
            return 1.0
        if self.coherence == "independent":
            return 0.0
        return self.isotropic(f / self.V, self.track_width, self.spectrum.waviness)

    def __call__(self, f, oscillating=True):
        """(steady, oscillating, envelope of oscillating) parts of S_y(f) [unit^2/Hz], each (outputs, f)."""
        omega = 2.0 * np.pi * f
        P = self._transfer(omega)
        Gz = self.spectrum.temporal_psd(f, self.V)
        steady = np.zeros(P.shape[1:])
        osc = np.zeros(P.shape[1:])
        env = np.zeros(P.shape[1:])
        for i, (tr1, d1) in enumerate(self.points):
            for j, (tr2, d2) in enumerate(self.points):
                if j < i:
                    continue
                rho = self._rho(f, tr1, tr2)
                mult = 1.0 if i == j else 2.0
                cross = P[i] * np.conj(P[j])
                if d1 == d2:
                    steady += mult * rho * np.real(cross)
                else:
                    env += mult * np.abs(rho) * np.abs(cross)
                    if oscillating:
                        phase = np.exp(-1j * omega * self.tau * (float(d1) - float(d2)))
                        osc += mult * rho * np.real(cross * phase)
        self.auto = np.sum(np.abs(P) ** 2, axis=0) * Gz  # no cross terms: the scale of each output's PSD
        return steady * Gz, osc * Gz, env * Gz


def _log_edges(model, spectrum, V, per_decade=4, grading=2.0):
    """Panel edges [Hz]: ``per_decade`` per decade, and graded towards every resonance.

    A complex pole lambda = -sigma + j omega_d puts the peak 1 / ((2 pi f - omega_d)^2 + sigma^2)
    into the integrand, of half-power half-width gamma = sigma / (2 pi) [Hz] about
    f_d = omega_d / (2 pi). Panels edges at f_d and at f_d +- gamma ``grading``^k (k = 0, 1, ...,
    up to f_d / 2) resolve it whatever the damping: on each panel the peak is smooth (its poles
    lie at least about one panel width away), so the 7-15 rule converges and its error estimate
    sees the peak, with about 2 log2(f_d / gamma) panels per lightly damped mode.
    """
    lam = model.poles()
    wn = np.abs(lam)
    fn = wn[wn > 0] / (2 * np.pi)
    if fn.size == 0:
        fn = np.array([1.0])
    f_lo, f_hi = fn.min() * 1e-3, fn.max() * 1e3
    if spectrum.cut_on > 0:
        f_lo = min(f_lo, 1e-2 * spectrum.cut_on * V)
    edges = [np.geomspace(f_lo, f_hi, int(np.ceil(per_decade * np.log10(f_hi / f_lo))) + 1)]
    for lam_k in lam[lam.imag > 0]:
        f_d, gamma = lam_k.imag / (2 * np.pi), -lam_k.real / (2 * np.pi)
        edges.append([f_d, abs(lam_k) / (2 * np.pi)])
        if 0 < gamma <= 0.5 * f_d:
            d = gamma * grading ** np.arange(int(np.floor(np.log(0.5 * f_d / gamma) / np.log(grading))) + 1)
            edges.extend([f_d - d, f_d + d])
    e = np.unique(np.concatenate(edges))
    return e[(e >= f_lo) & (e <= f_hi)]


def _gauss_kronrod(edges):
    """Nodes f [Hz] and weights (Kronrod, Gauss) of the 7-15 rule on panels in ln f (df = f d ln f)."""
    x, wk = GAUSS_KRONROD_15
    a, b = np.log(edges[:-1]), np.log(edges[1:])
    half, mid = 0.5 * (b - a), 0.5 * (b + a)
    f = np.exp((mid[:, None] + half[:, None] * x[None, :]).ravel())
    jac = (half[:, None] * np.ones_like(x)[None, :]).ravel() * f
    return f, jac * np.tile(wk, a.size), jac * np.tile(GAUSS_7_IN_15, a.size)


def _psd(model, channels, spectrum, V, tau, two_tracks, coherence, track_width, rtol=1e-6, **grid):
    spectra = _Spectra(model, channels, spectrum, V, tau, two_tracks, coherence, track_width)
    edges = _log_edges(model, spectrum, V, **grid)
    dropped = 0.0
    if tau > 0:
        # resolve the delay's oscillation (panels <= 1/tau: one period of e^(-j 2 pi f tau) per 15 nodes) up
        # to f_c, beyond which the oscillating terms' envelope integrates to less than rtol of the steady part:
        # there they are dropped and their envelope is counted in the error
        f0, w0, _ = _gauss_kronrod(edges)
        st, osc, env = spectra(f0)
        env_tail = np.cumsum((env * w0)[:, ::-1], axis=1)[:, ::-1]  # (outputs, f)
        total = np.abs(((st + osc) * w0).sum(axis=1))  # the delay terms may cancel most of it (pitch)
        # outputs that cancel to rounding (roll on identical tracks) do not set f_c
        floor = 1e3 * np.finfo(float).eps * (spectra.cond if spectra.modal else 1.0) * (spectra.auto @ w0)
        ok = env_tail <= rtol * np.where(np.isfinite(total) & (total > floor), total, np.inf)[:, None]
        first = np.where(ok.any(axis=1), np.argmax(ok, axis=1), 0)
        f_c = float(f0[first.max()])
        lin = np.arange(0.0, f_c, 1.0 / tau)[1:]
        edges = np.unique(np.concatenate([edges, lin, [f_c]]))
    nodes, wk, wg = _gauss_kronrod(edges)
    lo, hi = edges[0], edges[-1]
    ends = np.array([lo, 1.01 * lo, 10 * lo, 10.1 * lo, hi / 10.1, hi / 10, hi / 1.01, hi])
    f_all = np.concatenate([nodes, ends])
    st, osc, env = spectra(f_all)
    if tau > 0:
        osc = np.where(f_all > f_c, 0.0, osc)
    S = (st + osc)[:, :nodes.size]
    var = S @ wk
    panels = edges.size - 1
    err = np.abs((S * (wk - wg)).reshape(-1, panels, 15).sum(axis=2)).sum(axis=1)
    if tau > 0:
        dropped = (env[:, :nodes.size] * (nodes > f_c)) @ wk
    # power-law tails beyond the grid: S ~ f^q below lo and f^-p above hi, exponents fitted at the ends; the
    # error of each tail is its change when the exponent is fitted a decade further in. Below lo the delay
    # terms do not oscillate (omega tau << 1) and may cancel (pitch, roll): the integrand itself is used;
    # above hi their envelope bounds them. An end where the PSD is negligible against the output's scale
    # (the integral of its PSD without cross terms, which cancel there) adds nothing but its bound.
    Se = st[:, -8:] + np.concatenate([osc[:, -8:-4], np.zeros((st.shape[0], 4))], axis=1)
    Se = np.maximum(Se, 0.0)
    env_hi = env[:, -1] * hi  # the oscillating terms above hi, bounded by their envelope (~ S f)
    scale = spectra.auto[:, :nodes.size] @ wk
    with np.errstate(divide="ignore", invalid="ignore"):
        q0 = np.log(Se[:, 1] / Se[:, 0]) / np.log(1.01)
        q1 = np.log(Se[:, 3] / Se[:, 2]) / np.log(1.01)
        p1 = -np.log(Se[:, 5] / Se[:, 4]) / np.log(1.01)
        p0 = -np.log(Se[:, 7] / Se[:, 6]) / np.log(1.01)

        def end(S_end, f_end, expo_term):
            est = np.where(expo_term > 0, S_end * f_end / expo_term, np.inf)
            tiny = S_end * f_end <= 1e-12 * scale
            return np.where(S_end == 0, 0.0, np.where(tiny, 0.0, est)), np.where(tiny, S_end * f_end, 0.0)

        head0, tiny_head = end(Se[:, 0], lo, q0 + 1)
        head1, _ = end(Se[:, 0], lo, q1 + 1)
        tail0, tiny_tail = end(Se[:, 7], hi, p0 - 1)
        tail1, _ = end(Se[:, 7], hi, p1 - 1)
        var = var + head0 + tail0
        err = err + np.abs(head0 - head1) + np.abs(tail0 - tail1) + tiny_head + tiny_tail + dropped + env_hi
        # rounding of the modal sums, ~ cond(V) eps of each output's scale; an output whose cross terms
        # cancel its PSD (roll on identical left and right tracks) is zero to that rounding
        rounding = 1e3 * np.finfo(float).eps * (spectra.cond if spectra.modal else 1.0) * scale
        zero = np.abs(var) <= rounding
        var, err = np.where(zero, 0.0, var), err + rounding
        # rounding of the frequencies themselves: near a resonance of half-width gamma a relative error eps
        # of f moves the integrand by eps f_d / gamma of itself (1 / zeta; it matters below zeta ~ 1e-6)
        lam = spectra.lam if spectra.modal else model.poles()
        sharp = lam[(lam.imag > 0) & (lam.real < 0)]
        sharpness = float(np.max(sharp.imag / -sharp.real, initial=1.0))
        err = err + 10 * np.finfo(float).eps * sharpness * np.abs(var)
        err = np.where(np.isfinite(var), np.nan_to_num(err, nan=np.inf), np.inf)
    return var, err, {"n_frequencies": int(f_all.size), "f_range_hz": (float(edges[0]), float(edges[-1]))}


# --------------------------------------------------------------------------- simulation route
def _simulation(model, channels, spectrum, V, wheelbase, two_tracks, coherence, track_width, duration, sample_rate,
                seed, n_max):
    from vehdyn.simulation import simulate

    T = float(duration)
    fs = float(sample_rate)
    if not (T > 0 and fs > 0):
        raise ParameterError("duration and sample_rate must be positive", key="duration", value=duration)
    dx = V / fs
    lam = model.poles()
    decay = np.min(-lam.real[lam.real < 0], initial=np.inf)
    settle = min(0.2 * T, 10.0 / decay) if np.isfinite(decay) else 0.2 * T
    length = V * (T + settle)
    rng = np.random.default_rng(seed)
    if two_tracks:
        if coherence == "isotropic":
            left, right = synthesize_parallel_profiles(spectrum, length, dx, track_width, seed=rng, n_max=n_max)
        else:
            left = synthesize_profile(spectrum, length, dx, seed=rng, n_max=n_max)
            right = left if coherence == "identical" else synthesize_profile(spectrum, length, dx, seed=rng,
                                                                             n_max=n_max)
        profiles = {"left": left, "right": right}
    else:
        profiles = {"coherent": synthesize_profile(spectrum, length, dx, seed=rng, n_max=n_max)}
    inputs = {}
    t = None
    for c in channels:
        prof = profiles[c.track]
        t, u = prof.road_inputs(V, {c.suffix: float(wheelbase) if c.delayed else 0.0})
        inputs[model.input_names[c.index]] = u[f"road_{c.kind}{c.suffix}"]
    res = simulate(model, t, inputs, method="exact", hold="foh")
    keep = t >= settle
    y = res.outputs[:, keep]
    var = np.mean(y**2, axis=1)
    n_batches = 20
    batches = np.array_split(y, n_batches, axis=1)
    bvar = np.array([np.mean(b**2, axis=1) for b in batches])
    se_var = bvar.std(axis=0, ddof=1) / np.sqrt(n_batches)
    rms = np.sqrt(var)
    se_rms = np.where(rms > 0, se_var / (2 * np.where(rms > 0, rms, 1)), 0.0)
    return var, se_rms, {"n_samples": int(keep.sum()), "settle_s": settle, "simulate_wall_time": res.wall_time}

