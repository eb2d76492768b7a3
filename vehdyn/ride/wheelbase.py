"""Road input at every wheel: the wheelbase delay, exact or by Padé approximant.

A vehicle at speed V meets, at its rear wheels, the road its front wheels met tau = L / V earlier
(L the wheelbase). vehdyn's ride models keep one road input per wheel; this module ties them to
one profile per track, and holds the one implementation of each form of the delay:

* **Frequency domain, exact**: :func:`road_frequency_response` multiplies the rear wheels'
  responses by exp(-j omega tau) and adds them to the front's (Gillespie, *Fundamentals of Vehicle
  Dynamics*, 1992, ch. 5, "wheelbase filtering"). Used by :mod:`vehdyn.ride.analysis`
  (transmissibility and the other frequency responses) whenever a speed is given; the ``"psd"``
  route of :func:`vehdyn.ride.random_vibration` applies the same factor to the road spectra.
* **Time domain, exact**: :func:`road_inputs` samples a road profile under each wheel at its own
  position (front at V t, rear at V t - L) through :meth:`vehdyn.ride.RoadProfile.road_inputs`,
  for :func:`vehdyn.simulate`; the ``"simulation"`` route of :func:`vehdyn.ride.random_vibration`
  uses the same method.
* **State space, approximate**: :func:`pade_delay` is the [n/n] Padé approximant of e^(-s tau)
  as a state space (balanced). :func:`with_wheelbase_delay` appends it to a ride model so that
  eigenvalues, time simulations and LQR designs can see the whole car driven by one profile per
  track; the ``delay="pade"`` option of :func:`vehdyn.ride.random_vibration` appends it to the road
  shaping filter (its default, ``delay="exact"``, needs no approximation). Its error: the [n/n]
  Padé approximant P has |P(j omega)| = 1 exactly, and |P(j omega) - exp(-j omega tau)| < 1e-3 for
  omega tau < 1.5 n - 3.5 and < 1e-2 for omega tau < 1.6 n - 2.3 (n = 4..10, checked numerically
  in the tests); above that the delayed input is wrong in phase. The phase error of the [10/10]
  approximant is 4e-11 rad at omega tau = 5, 3e-8 at 7, 4e-6 at 9, 2e-4 at 11 and 3e-2 at 15;
  orders above 10 gain little (rounding grows with the order; at most 12 is accepted). With
  n = 6 and a 2.6 m wheelbase at 20 m/s (tau = 0.13 s) it is good to 1e-2 up to 9 Hz: enough for
  the body modes, not for wheel hop — use the exact routes for those (Franklin, Powell &
  Emami-Naeini, *Feedback Control of Dynamic Systems*, 6th ed., sec. 5.6.3; Golub & Van Loan,
  *Matrix Computations*, 4th ed., sec. 9.3.1).
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.interconnect import connect_in_series, pade_delay
from vehdyn.model import LinearModel
from vehdyn.results import FrequencyResponse
from vehdyn.signals import Signal
from vehdyn.road import RoadProfile

__all__ = ["wheel_offsets", "wheel_delays", "road_frequency_response",
           "road_inputs", "with_wheelbase_delay"]


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


def wheel_offsets(model) -> np.ndarray:
    """Distance of each corner of a ride model behind its front axle: x_front - x_i.

    Parameters
    ----------
    model : QuarterCar, BouncePitch or FullCar
        A ride model of :mod:`vehdyn.ride`.

    Returns
    -------
    ndarray
        One distance per corner, in input order [m] (0 at the front axle).
    """
    x = np.array([c.x for c in model.corners])
    return x.max() - x


def wheel_delays(model, speed: float) -> np.ndarray:
    """Delay of the road input at each corner behind the front axle: (x_front - x_i) / V.

    Parameters
    ----------
    model : QuarterCar, BouncePitch or FullCar
        A ride model of :mod:`vehdyn.ride`.
    speed : float
        Forward speed V [m/s], > 0.

    Returns
    -------
    ndarray
        One delay per corner, in input order [s].
    """
    return wheel_offsets(model) / _check_speed(speed)


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
        Uniformly spaced, increasing distances along the road [m] at which the profile is given.
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
        behind them at s = V t - (x_front - x_i); the profile is sampled by
        :meth:`vehdyn.ride.RoadProfile.road_inputs` (linear interpolation, velocity V dz/ds with
        the slope by central differences; before the profile's start and after its end the
        elevation is held and the velocity is zero).
    """
    v = _check_speed(speed)
    s = np.asarray(distance, dtype=float)
    profiles = {}
    for track, z, key in (("left", elevation, "elevation"),
                          ("right", elevation if elevation_right is None else elevation_right, "elevation_right")):
        z = np.asarray(z, dtype=float)
        if s.ndim != 1 or z.shape != s.shape:
            raise ParameterError(f"{key} must have the shape of distance {s.shape}, got {z.shape}", key=key,
                                 value=z.shape)
        profiles[track] = RoadProfile(s, z)
    profiles[""] = profiles["left"]
    out = {}
    for c, offset in zip(model.corners, wheel_offsets(model)):
        # RoadProfile puts the first axle at distance[0] + V t: shift so that it is at V t
        _, u = profiles[c.track].road_inputs(v, {c.suffix: offset + s[0]}, time=time)
        out.update(u)
    return out


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
            A, B, C, Dp = pade_delay(tau[k], order)
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
