"""Stationary random response of any linear ride model to an ISO 8608 road: r.m.s. of every output.

Road inputs are recognized by name: ``road_displacement<suffix>`` [m] and ``road_velocity<suffix>``
[m/s]; a suffix containing ``rear`` is the same track delayed by tau = wheelbase / V, one
containing ``left`` or ``right`` is on that track (e.g. ``road_displacement_front_left``); other
inputs are held at zero. Three routes give the same numbers:

``"lyapunov"`` (exact covariance)
    The road shaping filter (:meth:`RoadSpectrum.shaping_filter`, waviness 2) is appended to the
    model with :func:`vehdyn.connect_in_series` and the state covariance X solves
    A X + X A^T + B B^T = 0 (unit-intensity white noise); var(y) = C X C^T. Without a cut-on
    (the ISO spectrum itself) the road is an integrated white noise: the integrator modes are split
    off exactly (projector on the null space of A) and outputs that see them (those with a non-zero
    gain to a uniform lift of the road, such as absolute displacements) have infinite variance;
    outputs with white-noise feedthrough (e.g. accelerations through tire damping) also return
    ``inf``. A rear input is the front one delayed through a Pade approximant of e^(-s tau) of
    order ``pade_order`` (default 10, at most 12) applied to the shaping filter's output; this is
    the only approximation of the route. For a half car at 20 m/s, wheelbase 2.7 m (tau = 0.135 s)
    the r.m.s. error against the exact delay of ``"psd"`` is 3 % at order 4, 4e-5 at order 8 and
    3e-7 at order 10. Left and right tracks must be ``"identical"`` or ``"independent"``
    here (the isotropic coherence is not rational).
``"psd"`` (frequency-domain integral with a stated error)
    var(y) = int_0^inf sum_{s,t} H_s(f) S_st(f) H_t(f)^* df with the exact delay e^(-j 2 pi f tau),
    the temporal road PSD G_z(f) and the track coherence (isotropic by default). The integral is
    taken over log f on Gauss-Legendre panels (20 per decade, more around every mode and, with a
    delay, no wider than 1/(4 tau)) from 1e-4 times the lowest to 1e4 times the highest natural
    frequency; beyond, power-law tails fitted at the ends are added. The reported error is the sum
    of |I_16 - I_8| over the panels (16- against 8-point rule) plus 10 % of the tails.
``"simulation"`` (time domain, for checking)
    A sum-of-cosines profile (:func:`synthesize_profile`) of ``duration`` seconds of road,
    exact-discretization simulation (:func:`vehdyn.simulate`), r.m.s. after a settling time, and
    its statistical standard error from batch means.
"""

from __future__ import annotations

import re
import time as _time
from dataclasses import dataclass, field
from math import factorial

import numpy as np

from ..errors import ParameterError
from .road import RoadSpectrum, synthesize_parallel_profiles, synthesize_profile

__all__ = ["RandomResponse", "random_response", "road_channels", "pade_delay", "stationary_covariance"]

_ROAD_INPUT = re.compile(r"^road_(displacement|velocity)(.*)$")
_TRACKS = ("coherent", "left", "right")


@dataclass(frozen=True)
class _Channel:
    index: int  # model input index
    kind: str  # "displacement" | "velocity"
    suffix: str
    delayed: bool  # rear axle
    track: str  # "coherent" (one track), "left" or "right"


def road_channels(model) -> list[_Channel]:
    """The road inputs of ``model`` (by name), each with its kind, axle (delayed or not) and track."""
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
        Error of ``rms``: 0 for ``"lyapunov"`` (exact up to rounding and the Pade delay), the
        estimated error bound for ``"psd"``, one standard error for ``"simulation"``.
    method : str
    speed : float
        [m/s].
    spectrum : RoadSpectrum
    wall_time : float
        [s].
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
        """pandas DataFrame indexed by output: ``rms`` and ``error`` (units in ``attrs["units"]``)."""
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
    duration: float = 100.0,
    sample_rate: float = 500.0,
    seed=None,
    n_max: float | None = None,
) -> RandomResponse:
    """R.m.s. of the outputs of a linear ride ``model`` driven at ``speed`` over the random road ``road``.

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
        [m]; needed when the model has rear inputs.
    track_width : float, optional
        [m]; needed for left/right inputs with the isotropic coherence.
    track_coherence : {"isotropic", "identical", "independent"}
        Left-right coherence (isotropic: :func:`vehdyn.ride.road.isotropic_coherence`).
    outputs : sequence of str, optional
        Restrict to these outputs.
    pade_order : int
        Order of the Pade delay (``"lyapunov"`` only).
    duration, sample_rate, seed, n_max : ``"simulation"`` only
        Seconds of road [s], sampling rate [Hz], random seed, highest spatial frequency of the
        profile [cycles/m] (default: the Nyquist frequency of the time grid).
    """
    from ..linear import LinearModel

    if not isinstance(model, LinearModel):
        raise ParameterError(f"model must be a LinearModel, got {type(model).__name__} (linearize it first)",
                             key="model", value=model)
    spectrum = road if isinstance(road, RoadSpectrum) else RoadSpectrum.from_class(road)
    V = float(speed)
    if not (np.isfinite(V) and V > 0):
        raise ParameterError(f"speed must be positive [m/s], got {speed!r}", key="speed", value=speed)
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
    start = _time.perf_counter()
    if method == "lyapunov":
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
    rms = np.sqrt(var)
    with np.errstate(divide="ignore", invalid="ignore"):
        rms_err = np.where(np.isfinite(var), np.where(rms > 0, err / (2 * np.where(rms > 0, rms, 1)), np.sqrt(err)),
                           np.inf) if method != "simulation" else err
    return RandomResponse(model.output_signals, rms, np.asarray(rms_err, float), method, V, spectrum, wall, info)


# --------------------------------------------------------------------------- Lyapunov route
def pade_delay(delay: float, order: int):
    """State-space (A, B, C, D) of the [order/order] Pade approximant of e^(-s delay).

    Built for a unit delay (coefficients c_k = (2m - k)! m! / ((2m)! k! (m - k)!)), balanced by a
    diagonal similarity (the companion form is ill-conditioned beyond order 4) and scaled in time
    (A / delay, B / delay).
    """
    from scipy import signal
    from scipy.linalg import matrix_balance

    if not 1 <= order <= 12:
        raise ParameterError(f"pade_order must be 1 to 12 (higher orders lose accuracy to rounding), got {order}",
                             key="pade_order", value=order)
    if not delay > 0:
        raise ParameterError(f"delay must be positive [s], got {delay}", key="delay", value=delay)
    m = order
    c = np.array([factorial(2 * m - k) * factorial(m) / (factorial(2 * m) * factorial(k) * factorial(m - k))
                  for k in range(m + 1)])
    num = (c * (-1.0) ** np.arange(m + 1))[::-1]
    den = c[::-1]
    A, B, C, D = signal.tf2ss(num, den)
    _, (scale, _) = matrix_balance(A, permute=False, separate=True)
    A = (A / scale[:, None]) * scale[None, :]
    B = B / scale[:, None]
    C = C * scale[None, :]
    return A / delay, B / delay, C, D


def _road_generator(channels, spectrum, V, tau, sources, pade_order):
    """White noise -> every road input of the model, as one LinearModel (shaping filters, Pade delays).

    One shaping-filter state per noise source (the road under the front axle, ``road_elevation_<k>``);
    a rear input is that state passed through the Pade delay, its velocity the derivative of the
    delay's output. Returns the model and the indices of the shaping-filter states.
    """
    from ..linear import LinearModel

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
    states = [f"road_elevation_{k}" for k in used]
    for k in used:
        A[xi[k], xi[k]] = -a
        B[xi[k], k] = sigma
    for k in delayed_src:
        Ap, Bp, _, _ = pade
        o = xp[k]
        A[o:o + npd, o:o + npd] = Ap
        A[o:o + npd, xi[k]] = Bp[:, 0]
        states += [f"road_delay_state_{k}_{j}" for j in range(npd)]
    C = np.zeros((len(channels), n))
    D = np.zeros((len(channels), n_src))
    for r, c in enumerate(channels):
        k = sources[c.track]
        # displacement row (Cz, Dz) as a function of the state; velocity = its derivative
        Cz = np.zeros(n)
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
    outputs = [f"road_{c.kind}{c.suffix}" for c in channels]
    model = LinearModel(A, B, C, D, states=states, inputs=[f"road_noise_{k}" for k in range(n_src)],
                        outputs=outputs, name="road generator", phenomena={"road_input"})
    return model, [xi[k] for k in used]


def _sources(two_tracks, coherence):
    if not two_tracks or coherence == "identical":
        return {"coherent": 0, "left": 0, "right": 0}
    return {"left": 0, "right": 1, "coherent": 0}


def stationary_covariance(A, B, integrators=()):
    """Stationary covariance of dx/dt = A x + B w (unit-intensity white noise w) with integrated-noise states.

    Parameters
    ----------
    A, B : ndarray
    integrators : sequence of int
        States whose rows of A are zero (random walks, e.g. the ISO 8608 road without cut-on).

    Returns
    -------
    X : ndarray
        Covariance of x_s = x - R xi, the part of the state that is stationary: the solution of
        A_s X + X A_s^T + B_s B_s^T = 0 with B_s = (I - R L) B, A_s = A - R L (L selects the
        integrator states, R = the states' equilibrium for a unit value of each integrator, so that
        A R = 0 and L R = I). Exact: x_s obeys dx_s/dt = A x_s + B_s w on an A-invariant subspace.
    R : ndarray, shape (n, n_integrators)
        An output y = C x has a stationary variance C X C^T only where C R = 0.
    """
    from scipy.linalg import solve_continuous_lyapunov

    n = A.shape[0]
    idx = list(integrators)
    if not idx:
        return solve_continuous_lyapunov(A, -B @ B.T), np.zeros((n, 0))
    if np.any(A[idx] != 0):
        raise ParameterError("integrator states must have zero rows in A", key="integrators", value=idx)
    rest = [k for k in range(n) if k not in idx]
    R = np.zeros((n, len(idx)))
    R[idx, range(len(idx))] = 1.0
    R[rest] = -np.linalg.solve(A[np.ix_(rest, rest)], A[np.ix_(rest, idx)])
    L = np.zeros((len(idx), n))
    L[range(len(idx)), idx] = 1.0
    P = np.eye(n) - R @ L
    scale = max(np.abs(np.linalg.eigvals(A[np.ix_(rest, rest)])).max(initial=0.0), 1.0)
    As = A - scale * (R @ L)
    Bs = P @ B
    X = solve_continuous_lyapunov(As, -Bs @ Bs.T)
    return P @ X @ P.T, R


def _lyapunov(model, channels, spectrum, V, tau, two_tracks, coherence, pade_order):
    from ..linear import connect_in_series

    if two_tracks and coherence == "isotropic":
        raise ParameterError("the Lyapunov route needs track_coherence 'identical' or 'independent' (the isotropic "
                             "coherence is not rational); use method='psd' for it", key="track_coherence",
                             value=coherence)
    gen, integrators = _road_generator(channels, spectrum, V, tau, _sources(two_tracks, coherence), pade_order)
    aug = connect_in_series(gen, model)  # generator states first
    integrators = integrators if spectrum.cut_on == 0 else []
    noise = [aug.index(name, "inputs") for name in gen.input_names]
    B = aug.B[:, noise]
    C = aug.C[: model.n_outputs]
    D = aug.D[: model.n_outputs][:, noise]
    X, R = stationary_covariance(aug.A, B, integrators)
    var = np.einsum("ij,jk,ik->i", C, X, C)
    # unbounded: outputs that see an integrated-noise mode, or white noise directly
    scale_c = np.abs(C) @ np.maximum(np.abs(R), 0.0).sum(axis=1) if R.size else np.zeros(C.shape[0])
    drift = np.abs(C @ R).max(axis=1, initial=0.0) > 1e-9 * np.maximum(scale_c, 1e-300)
    white = np.abs(D).max(axis=1, initial=0.0) > 0
    var = np.where(drift | white, np.inf, var)
    return var, np.zeros_like(var), {"n_states": aug.n_states, "pade_order": pade_order if tau > 0 else 0}


# --------------------------------------------------------------------------- PSD route
_GL8 = np.polynomial.legendre.leggauss(8)
_GL16 = np.polynomial.legendre.leggauss(16)


def _psd_integrand(model, channels, spectrum, V, tau, two_tracks, coherence, track_width, f, envelope=False):
    """Output PSD S_y(f) [unit^2/Hz], shape (n_outputs, n_f); ``envelope``: an upper bound without the oscillating
    delay and coherence terms (sum of magnitudes), used for the tail estimates."""
    from .road import isotropic_coherence

    omega = 2.0 * np.pi * f
    H = model.frequency_response(omega).response  # (p, m, nf)
    Gz = spectrum.temporal_psd(f, V)
    tracks = ("coherent",) if not two_tracks else ("left", "right")
    Ht = {}
    for tr in tracks:
        acc = np.zeros((H.shape[0], f.size), dtype=complex)
        for c in channels:
            if c.track != tr:
                continue
            g = H[:, c.index, :]
            if c.kind == "velocity":
                g = g * (1j * omega)
            if envelope:
                g = np.abs(g)
            elif c.delayed:
                g = g * np.exp(-1j * omega * tau)
            acc += g
        Ht[tr] = acc
    if envelope:
        return sum(np.abs(h) for h in Ht.values()) ** 2 * Gz
    if not two_tracks:
        return np.abs(Ht["coherent"]) ** 2 * Gz
    if coherence == "identical":
        rho = np.ones_like(f)
    elif coherence == "independent":
        rho = np.zeros_like(f)
    else:
        rho = isotropic_coherence(f / V, track_width, spectrum.waviness)
    hl, hr = Ht["left"], Ht["right"]
    return (np.abs(hl) ** 2 + np.abs(hr) ** 2 + 2.0 * rho * np.real(hl * np.conj(hr))) * Gz


def _panel_edges(model, spectrum, V, tau):
    lam = model.poles()
    wn = np.abs(lam)
    wn = wn[wn > 0]
    fn = wn / (2 * np.pi) if wn.size else np.array([1.0])
    f_lo = min(fn.min(), max(spectrum.cut_on * V, 1e-12)) * 1e-4 if spectrum.cut_on > 0 else fn.min() * 1e-4
    f_hi = fn.max() * 1e4
    edges = [np.geomspace(f_lo, f_hi, int(np.ceil(20 * np.log10(f_hi / f_lo))) + 1)]
    for lam_k in lam:
        w = abs(lam_k)
        if w == 0:
            continue
        zeta = min(max(-lam_k.real / w, 1e-4), 1.0)
        f0 = w / (2 * np.pi)
        edges.append(f0 * (1 + zeta * np.array([-8, -4, -2, -1, -0.5, 0, 0.5, 1, 2, 4, 8])))
    if tau > 0:
        f_osc = min(f_hi, 100 * fn.max())
        edges.append(np.arange(0.0, f_osc, 1.0 / (4 * tau))[1:])
    e = np.unique(np.concatenate(edges))
    return e[(e >= f_lo) & (e <= f_hi)]


def _psd(model, channels, spectrum, V, tau, two_tracks, coherence, track_width):
    edges = _panel_edges(model, spectrum, V, tau)
    u = np.log(edges)
    a, b = u[:-1], u[1:]
    half, mid = 0.5 * (b - a), 0.5 * (b + a)

    def rule(xw):
        x, w = xw
        nodes = (mid[:, None] + half[:, None] * x[None, :]).ravel()
        weights = (half[:, None] * w[None, :]).ravel()
        f = np.exp(nodes)
        S = _psd_integrand(model, channels, spectrum, V, tau, two_tracks, coherence, track_width, f)
        return (S * f * weights).reshape(S.shape[0], a.size, x.size).sum(axis=2)  # per panel

    I16, I8 = rule(_GL16), rule(_GL8)
    var = I16.sum(axis=1)
    err = np.abs(I16 - I8).sum(axis=1)
    # power-law tails beyond the grid (head below f_lo, tail above f_hi)
    f2 = np.array([edges[0], edges[0] * 1.01, edges[-1] / 1.01, edges[-1]])
    S2 = _psd_integrand(model, channels, spectrum, V, tau, two_tracks, coherence, track_width, f2, envelope=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.log(S2[:, 1] / S2[:, 0]) / np.log(1.01)  # S ~ f^q at the low end
        p = -np.log(S2[:, 3] / S2[:, 2]) / np.log(1.01)  # S ~ f^-p at the high end
        head = np.where(q > -1, S2[:, 0] * edges[0] / (q + 1), np.inf)
        tail = np.where(p > 1, S2[:, 3] * edges[-1] / (p - 1), np.inf)
    head = np.where(S2[:, 0] == 0, 0.0, head)
    tail = np.where(S2[:, 3] == 0, 0.0, tail)
    var = var + head + tail
    err = err + 0.1 * (np.abs(head) + np.abs(tail))  # power laws fitted 4 decades beyond every mode
    return var, err, {"n_frequencies": int(a.size * 24 + 4), "f_range_hz": (float(edges[0]), float(edges[-1]))}


# --------------------------------------------------------------------------- simulation route
def _simulation(model, channels, spectrum, V, wheelbase, two_tracks, coherence, track_width, duration, sample_rate,
                seed, n_max):
    from ..simulate import simulate

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

