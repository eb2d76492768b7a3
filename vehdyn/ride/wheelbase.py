"""Road input at every wheel: the wheelbase delay, exact or by Padé approximant.

A vehicle at speed V meets, at its rear wheels, the road its front wheels met tau = L / V earlier
(L the wheelbase). vehdyn's ride models keep one road input per wheel; this module ties them to
one profile per track in three ways:

* **Frequency domain, exact**: :func:`road_frequency_response` multiplies the rear wheels'
  responses by exp(-j omega tau) and adds them to the front's (Gillespie, *Fundamentals of Vehicle
  Dynamics*, 1992, ch. 5, "wheelbase filtering"). Used by :mod:`vehdyn.ride.analysis`
  (transmissibility and the other frequency responses) whenever a speed is given.
* **Time domain, exact**: :func:`road_inputs` samples a road profile under each wheel at its own
  position (front at V t, rear at V t - L), for :func:`vehdyn.simulate`.
* **State space, approximate**: :func:`with_wheelbase_delay` appends a Padé approximant of the
  delay so that eigenvalues, Lyapunov covariances and LQR designs can see the whole car driven by
  one profile per track. Its error: the [n/n] Padé approximant P has |P(j omega)| = 1 exactly, and
  |P(j omega) - exp(-j omega tau)| < 1e-3 for omega tau < 1.5 n - 3.5 and < 1e-2 for
  omega tau < 1.6 n - 2.3 (n = 4..10, checked numerically in the tests); above that the delayed
  input is wrong in phase. With the default n = 6 and a 2.6 m wheelbase at 20 m/s (tau = 0.13 s)
  it is good to 1e-2 up to 9 Hz: enough for the body modes, not for wheel hop — use the exact
  routes for those (Franklin, Powell & Emami-Naeini, *Feedback Control of Dynamic Systems*, 6th ed.,
  sec. 5.6.3; Golub & Van Loan, *Matrix Computations*, 4th ed., sec. 9.3.1).
"""

from __future__ import annotations

from math import factorial

import numpy as np

from ..errors import ParameterError
from ..linear import LinearModel, connect_in_series
from ..results import FrequencyResponse
from ..signals import Signal

__all__ = ["wheel_delays", "pade_coefficients", "road_frequency_response", "road_inputs", "with_wheelbase_delay"]


def _check_speed(speed) -> float:
    try:
        v = float(speed)
    except (TypeError, ValueError):
        raise ParameterError(f"speed must be a number [m/s], got {speed!r}", key="speed", value=speed) from None
    if not (np.isfinite(v) and v > 0):
        raise ParameterError(f"speed must be positive and finite [m/s], got {speed!r}", key="speed", value=speed)
    return v


def _track_suffix(track: str) -> str:
    return f"_{track}" if track else ""


def _tracks(model) -> list[str]:
    out = []
    for c in model.corners:
        if c.track not in out:
            out.append(c.track)
    return out


def wheel_delays(model, speed: float) -> np.ndarray:
    """Delay of the road input at each corner behind the front axle [s]: (x_front - x_i) / V."""
    v = _check_speed(speed)
    x = np.array([c.x for c in model.corners])
    return (x.max() - x) / v


def pade_coefficients(order: int) -> np.ndarray:
    """Coefficients c_k of the [n/n] Padé approximant of exp(-p) = sum (-p)^k c_k / sum p^k c_k.

    c_k = (2n - k)! n! / ((2n)! k! (n - k)!), k = 0..n (ascending powers).
    """
    if not (isinstance(order, (int, np.integer)) and order >= 1):
        raise ParameterError(f"order must be a positive integer, got {order!r}", key="order", value=order)
    n = int(order)
    return np.array([factorial(2 * n - k) * factorial(n) / (factorial(2 * n) * factorial(k) * factorial(n - k))
                     for k in range(n + 1)])


def road_frequency_response(model, omega, speed: float | None = None, outputs=None) -> FrequencyResponse:
    """Frequency response of a ride model to road profiles, with the exact wheelbase delay.

    Parameters
    ----------
    model : RideModel
        A :class:`~vehdyn.ride.QuarterCar`, :class:`~vehdyn.ride.BouncePitch` or
        :class:`~vehdyn.ride.FullCar` (actuator inputs, if any, are left open).
    omega : array_like
        Angular frequencies [rad/s] (temporal).
    speed : float, optional
        Forward speed [m/s]. Without it, each wheel has its own input ``road_displacement<sfx>``.
        With it, the wheels of one track share one profile, delayed by their distance behind the
        front axle divided by ``speed``: inputs ``road_displacement`` (single track) or
        ``road_displacement_left``/``_right`` (full car).
    outputs : sequence of str, optional
        Restrict to these outputs.

    Returns
    -------
    FrequencyResponse
        Output per unit road elevation: the displacement and velocity inputs combined as
        H_d + j omega H_v, times exp(-j omega tau_i) per wheel when ``speed`` is given.
    """
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    corner_inputs = [n for pair in model.road_input_names() for n in pair]
    fr = model.frequency_response(omega, outputs=outputs, inputs=corner_inputs)
    jw = 1j * omega
    per_wheel = fr.response[:, 0::2, :] + jw * fr.response[:, 1::2, :]  # (n_out, n_corners, n_w)
    if speed is None:
        inputs = tuple(Signal(d, "m", "road elevation under the wheel") for d, _ in model.road_input_names())
        return FrequencyResponse(omega=omega, response=per_wheel, outputs=fr.outputs, inputs=inputs)
    tau = wheel_delays(model, speed)
    delayed = per_wheel * np.exp(-jw[None, None, :] * tau[None, :, None])
    tracks = _tracks(model)
    response = np.stack([delayed[:, [k for k, c in enumerate(model.corners) if c.track == tr], :].sum(axis=1)
                         for tr in tracks], axis=1)
    inputs = tuple(Signal(f"road_displacement{_track_suffix(tr)}", "m", "road elevation under the front wheel")
                   for tr in tracks)
    return FrequencyResponse(omega=omega, response=response, outputs=fr.outputs, inputs=inputs)


def road_inputs(model, time, speed: float, distance, elevation, elevation_right=None) -> dict[str, np.ndarray]:
    """Road displacement and velocity under each wheel for a time simulation (exact delay).

    Parameters
    ----------
    model : RideModel
    time : array_like
        Time grid [s].
    speed : float
        Forward speed V [m/s] (constant).
    distance : array_like
        Increasing distances along the road [m] at which the profile is given.
    elevation : array_like
        Road elevation [m] at ``distance`` (the left track of a full car, or both tracks when
        ``elevation_right`` is None).
    elevation_right : array_like, optional
        Right-track elevation [m] on the same distances.

    Returns
    -------
    dict
        ``{road_displacement<sfx>: array, road_velocity<sfx>: array}`` for every corner, ready for
        ``vehdyn.simulate(model, time, inputs=...)``. The front wheels are at s = V t, a wheel x_i
        behind them at s = V t - (x_front - x_i); the profile is interpolated linearly and its
        velocity is V dz/ds (slope by central differences); before the profile's start and after its
        end the elevation is held.
    """
    v = _check_speed(speed)
    t = np.asarray(time, dtype=float)
    s = np.asarray(distance, dtype=float)
    if s.ndim != 1 or s.size < 2 or np.any(np.diff(s) <= 0):
        raise ParameterError("distance must be a strictly increasing 1-D array of at least 2 points [m]",
                             key="distance", value=s.shape)
    profiles = {}
    for track, z in (("left", elevation), ("right", elevation if elevation_right is None else elevation_right)):
        z = np.asarray(z, dtype=float)
        if z.shape != s.shape:
            raise ParameterError(f"elevation must have the shape of distance {s.shape}, got {z.shape}",
                                 key="elevation" if track == "left" else "elevation_right", value=z.shape)
        profiles[track] = (z, np.gradient(z, s))
    profiles[""] = profiles["left"]
    x = np.array([c.x for c in model.corners])
    out = {}
    for c, xi in zip(model.corners, x):
        z, slope = profiles[c.track]
        pos = v * t - (x.max() - xi)
        out[f"road_displacement{c.suffix}"] = np.interp(pos, s, z)
        inside = (pos >= s[0]) & (pos <= s[-1])
        out[f"road_velocity{c.suffix}"] = np.where(inside, v * np.interp(pos, s, slope), 0.0)
    return out


def _pade_state_space(delay: float, order: int):
    """(A, B, C, D) of the [n/n] Padé approximant of exp(-s delay), in controllable form."""
    from scipy import signal

    c = pade_coefficients(order)
    num = (c * (-1.0) ** np.arange(order + 1))[::-1]  # descending powers of p = s * delay
    den = c[::-1]
    A, B, C, D = signal.tf2ss(num / den[0], den / den[0])
    return A / delay, B / delay, C, D


def with_wheelbase_delay(model, speed: float, order: int = 6) -> LinearModel:
    """The ride model driven by one profile per track, the rear wheels through a Padé delay.

    Parameters
    ----------
    model : RideModel
        :class:`~vehdyn.ride.BouncePitch` or :class:`~vehdyn.ride.FullCar` (a quarter car has no
        delay and is returned as it is).
    speed : float
        Forward speed [m/s].
    order : int
        Order n of the [n/n] Padé approximant (2 n states per delayed wheel: displacement and
        velocity channels). See the module docstring for its accuracy.

    Returns
    -------
    LinearModel
        Inputs ``road_displacement`` and ``road_velocity`` of the front wheel of each track
        (suffixed ``_left``/``_right`` for a full car), then any actuator inputs; outputs the
        model's, then the road input at each wheel. States: the delay's
        (``wheelbase_delay<sfx>_<k>``), then the model's.
    """
    tau = wheel_delays(model, speed)
    if np.all(tau == 0):
        return model
    tracks = _tracks(model)
    in_names = [f"{q}{_track_suffix(tr)}" for tr in tracks for q in ("road_displacement", "road_velocity")]
    out_names = [n for pair in model.road_input_names() for n in pair]
    blocks_A, blocks_B, blocks_C, states = [], [], [], []
    n_in, n_out = len(in_names), len(out_names)
    D = np.zeros((n_out, n_in))
    cols_B, rows_C = [], []
    for k, c in enumerate(model.corners):
        base = 2 * tracks.index(c.track)
        for ch in range(2):  # displacement, velocity
            i_in, i_out = base + ch, 2 * k + ch
            if tau[k] == 0:
                D[i_out, i_in] = 1.0
                continue
            A, B, C, Dp = _pade_state_space(tau[k], order)
            blocks_A.append(A)
            blocks_B.append(B)
            blocks_C.append(C)
            cols_B.append(i_in)
            rows_C.append(i_out)
            D[i_out, i_in] = Dp[0, 0]
            kind = "displacement" if ch == 0 else "velocity"
            states += [Signal(f"wheelbase_delay_{kind}{c.suffix}_{j + 1}", "", "Padé delay state")
                       for j in range(order)]
    import scipy.linalg

    Aall = scipy.linalg.block_diag(*blocks_A)
    Ball = np.zeros((Aall.shape[0], n_in))
    Call = np.zeros((n_out, Aall.shape[0]))
    row = 0
    for B, C, i_in, i_out in zip(blocks_B, blocks_C, cols_B, rows_C):
        Ball[row:row + order, i_in] = B[:, 0]
        Call[i_out, row:row + order] = C[0]
        row += order
    delay = LinearModel(Aall, Ball, Call, D, states=states,
                        inputs=[Signal(n, "m" if "displacement" in n else "m/s", "road input at the front wheel")
                                for n in in_names],
                        outputs=[model.inputs[model.index(n, "inputs")] for n in out_names],
                        name="wheelbase_delay", phenomena={"road_input"})
    return connect_in_series(delay, model, name=f"{model.name}_pade{order}_{float(speed):g}ms")
