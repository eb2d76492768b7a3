"""Four-wheel steering (4WS) of the linear single-track model: rear-steer laws and their effect.

Proportional rear steer delta_r = k delta_f (k > 0: rear wheels steer the same way as the front,
"in phase"; k < 0: opposite phase). The speed-dependent ratio that makes the steady-state sideslip
at the CG zero follows from the bicycle model's equilibrium (see
:mod:`vehdyn.handling.steady_state`)::

    k(u) = -(b - m a u^2 / (L C_r)) / (a + m b u^2 / (L C_f))

k(0) = -b / a (opposite phase: the kinematic turn centre lies level with the CG), k = 0 at the zero-sideslip
speed sqrt(b L C_r / (m a)), and k -> a C_f / (b C_r) at high speed (in phase). References: Sano,
Furukawa & Shiraishi, *Four wheel steering system with rear wheel steer angle controlled as a
function of steering wheel angle*, SAE 860625, 1986; Abe, *Vehicle Handling Dynamics*, 2009,
sec. 9.2 (eq. 9.9); Mitschke & Wallentowitz, *Dynamik der Kraftfahrzeuge*, 2014, sec. 28.

The laws plug into :class:`~vehdyn.handling.LinearBicycle` as static gains in series
(:func:`proportional_rear_steer`) or as rear steer fed back from the yaw rate
(:func:`yaw_rate_feedback_rear_steer`); both return a :class:`~vehdyn.LinearModel` with the
single input ``front_steer_angle`` and the rear steer angle among the outputs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model.linear import LinearModel
from vehdyn.interconnect import connect_in_series
from vehdyn.signals import STEER_INPUTS
from vehdyn.handling.bicycle import LinearBicycle, bicycle_parameters, check_speed, speed_of
from vehdyn.handling.steady_state import steady_state_gains

__all__ = [
    "zero_sideslip_rear_steer_ratio",
    "proportional_rear_steer",
    "yaw_rate_feedback_rear_steer",
    "FourWheelSteerComparison",
    "compare_four_wheel_steering",
]

_FRONT, _REAR = STEER_INPUTS


def zero_sideslip_rear_steer_ratio(vehicle_or_bicycle, speed=None):
    r"""Rear/front road-wheel angle ratio k that gives zero steady-state sideslip at the CG.

    .. math::

        k(u) = -\frac{b - m a u^2 / (L C_r)}{a + m b u^2 / (L C_f)}

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (see :func:`~vehdyn.handling.bicycle_parameters`).
    speed : float or array_like, optional
        Forward speed [m/s] (>= 0); defaults to the bicycle's.

    Returns
    -------
    float or ndarray
        k [-], positive when the rear wheels steer the same way as the front: -b / a at
        standstill, 0 at the zero-sideslip speed, a C_f / (b C_r) in the limit of high speed.

    References
    ----------
    .. [1] M. Abe, *Vehicle Handling Dynamics*, Butterworth-Heinemann, 2009, sec. 9.2 (eq. 9.9).
    .. [2] S. Sano, Y. Furukawa and S. Shiraishi, "Four wheel steering system with rear wheel steer
       angle controlled as a function of steering wheel angle", SAE 860625, 1986.
    """
    p = bicycle_parameters(vehicle_or_bicycle)
    u = speed_of(vehicle_or_bicycle, speed, allow_zero=True)
    L = p.wheelbase
    k = -(p.b - p.mass * p.a * u**2 / (L * p.rear_cornering_stiffness)) / (
        p.a + p.mass * p.b * u**2 / (L * p.front_cornering_stiffness))
    return float(k) if np.ndim(k) == 0 else k


def _check_bicycle(bicycle) -> LinearBicycle:
    if not isinstance(bicycle, LinearBicycle):
        raise ParameterError(f"expected a LinearBicycle, got {type(bicycle).__name__}", key="bicycle", value=bicycle)
    return bicycle


def proportional_rear_steer(bicycle: LinearBicycle, ratio=None) -> LinearModel:
    """The bicycle with rear steer proportional to front steer, delta_r = k delta_f.

    Parameters
    ----------
    bicycle : LinearBicycle
        The vehicle with front and rear steer inputs.
    ratio : float, optional
        k [-], finite; by default :func:`zero_sideslip_rear_steer_ratio` at the bicycle's speed.

    Returns
    -------
    LinearModel
        Input ``front_steer_angle``; the bicycle's outputs followed by ``front_steer_angle`` and
        ``rear_steer_angle``; the bicycle's states.
    """
    bicycle = _check_bicycle(bicycle)
    k = zero_sideslip_rear_steer_ratio(bicycle) if ratio is None else float(ratio)
    if not np.isfinite(k):
        raise ParameterError(f"ratio must be finite, got {ratio!r}", key="ratio", value=ratio)
    law = LinearModel(np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((2, 0)), [[1.0], [k]], states=[],
                      inputs=[_FRONT], outputs=[_FRONT, _REAR], name=f"rear steer k={k:.4g}")
    model = connect_in_series(law, bicycle, name=f"{bicycle.name} with proportional rear steer k={k:.4g}")
    model.rear_steer_ratio = k
    return model


def yaw_rate_feedback_rear_steer(bicycle: LinearBicycle, gain: float) -> LinearModel:
    """The bicycle with rear steer fed back from the yaw rate, delta_r = gain * r.

    A positive ``gain`` steers the rear wheels in the direction of the turn (in phase), which
    adds yaw damping and reduces the yaw gain (Abe 2009, sec. 9.3).

    Parameters
    ----------
    bicycle : LinearBicycle
        The vehicle with front and rear steer inputs.
    gain : float
        delta_r / r [s] (rad of rear road-wheel steer per rad/s of yaw rate), finite.

    Returns
    -------
    LinearModel
        Input ``front_steer_angle``; the bicycle's outputs and ``rear_steer_angle``.
    """
    bicycle = _check_bicycle(bicycle)
    if not np.isfinite(gain):
        raise ParameterError(f"gain must be finite [s], got {gain!r}", key="gain", value=gain)
    n = bicycle.n_states
    feedback = np.zeros(n)
    feedback[bicycle.index("yaw_rate")] = float(gain)  # delta_r = K x
    b_front, b_rear = bicycle.B[:, 0], bicycle.B[:, 1]
    d_front, d_rear = bicycle.D[:, 0], bicycle.D[:, 1]
    A = bicycle.A + np.outer(b_rear, feedback)
    C = np.vstack([bicycle.C + np.outer(d_rear, feedback), feedback])
    D = np.concatenate([d_front, [0.0]])[:, None]
    return LinearModel(A, b_front[:, None], C, D, states=bicycle.states, inputs=[_FRONT],
                       outputs=bicycle.outputs + (_REAR,), name=f"{bicycle.name} with yaw-rate rear steer",
                       phenomena=bicycle.phenomena)


@dataclass(frozen=True)
class FourWheelSteerComparison:
    """Front-steer-only (2WS) against zero-sideslip 4WS, against speed.

    Every attribute is an array over ``speed``.

    Attributes
    ----------
    speed : [m/s]
    rear_steer_ratio : k of the 4WS law [-]
    sideslip_gain_2ws, sideslip_gain_4ws : steady beta / delta_f [rad/rad]
    yaw_rate_gain_2ws, yaw_rate_gain_4ws : steady r / delta_f [1/s]
    frequency_hz : frequency of the dynamic comparison [Hz]
    yaw_rate_magnitude_2ws, yaw_rate_magnitude_4ws : |r / delta_f| at that frequency [1/s]
    yaw_rate_phase_2ws, yaw_rate_phase_4ws : phase of r / delta_f at that frequency [deg]
    lateral_acceleration_phase_2ws, lateral_acceleration_phase_4ws : phase of a_y / delta_f [deg]
    """

    speed: np.ndarray
    rear_steer_ratio: np.ndarray
    sideslip_gain_2ws: np.ndarray
    sideslip_gain_4ws: np.ndarray
    yaw_rate_gain_2ws: np.ndarray
    yaw_rate_gain_4ws: np.ndarray
    frequency_hz: float
    yaw_rate_magnitude_2ws: np.ndarray
    yaw_rate_magnitude_4ws: np.ndarray
    yaw_rate_phase_2ws: np.ndarray
    yaw_rate_phase_4ws: np.ndarray
    lateral_acceleration_phase_2ws: np.ndarray
    lateral_acceleration_phase_4ws: np.ndarray

    def to_frame(self):
        """The comparison as a table.

        Returns
        -------
        pandas.DataFrame
            Indexed by ``speed``, one column per attribute; units in ``attrs["units"]``, the
            frequency of the dynamic comparison in ``attrs["frequency_hz"]``.
        """
        import pandas as pd

        names = [n for n in self.__dataclass_fields__ if n not in ("speed", "frequency_hz")]
        df = pd.DataFrame({n: getattr(self, n) for n in names}, index=pd.Index(self.speed, name="speed"))
        units = {"speed": "m/s", "rear_steer_ratio": "-"}
        for n in names:
            if n.startswith("sideslip"):
                units[n] = "rad/rad"
            elif "phase" in n:
                units[n] = "deg"
            elif n.startswith("yaw_rate"):
                units[n] = "1/s"
        df.attrs["units"] = units
        df.attrs["frequency_hz"] = self.frequency_hz
        return df


def compare_four_wheel_steering(vehicle_or_bicycle, speeds, *, frequency_hz: float = 1.0) -> FourWheelSteerComparison:
    """Front steer only (2WS) against zero-sideslip proportional rear steer (4WS), against speed.

    The steady sideslip and yaw-rate gains (:func:`~vehdyn.handling.steady_state_gains`) and the
    yaw-rate and lateral-acceleration response at ``frequency_hz`` (the linear bicycle's
    frequency response, the rear steer k delta_f added to the front's), with k of
    :func:`zero_sideslip_rear_steer_ratio` at each speed.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (see :func:`~vehdyn.handling.bicycle_parameters`).
    speeds : float or array_like
        Forward speeds [m/s], > 0.
    frequency_hz : float, optional
        Frequency of the dynamic comparison [Hz], > 0 (default 1 Hz).

    Returns
    -------
    FourWheelSteerComparison
        Arrays over ``speeds``.
    """
    p = bicycle_parameters(vehicle_or_bicycle)
    u = np.atleast_1d(check_speed(speeds)).astype(float)
    if not (np.isfinite(frequency_hz) and frequency_hz > 0):
        raise ParameterError(f"frequency_hz must be positive, got {frequency_hz!r}", key="frequency_hz",
                             value=frequency_hz)
    k = np.atleast_1d(zero_sideslip_rear_steer_ratio(p, u))
    two = steady_state_gains(p, u)
    four = steady_state_gains(p, u, rear_steer_ratio=k)
    omega = np.array([2 * np.pi * frequency_hz])
    dyn = {key: [] for key in ("r2", "r4", "a2", "a4")}
    for speed, ratio in zip(u, k):
        bike = LinearBicycle(p, float(speed))
        fr = bike.frequency_response(omega, outputs=["yaw_rate", "lateral_acceleration"])
        h_front = fr.response[:, 0, 0]
        h_4ws = fr.response[:, 0, 0] + ratio * fr.response[:, 1, 0]
        dyn["r2"].append(h_front[0])
        dyn["a2"].append(h_front[1])
        dyn["r4"].append(h_4ws[0])
        dyn["a4"].append(h_4ws[1])
    r2, r4, a2, a4 = (np.array(dyn[key]) for key in ("r2", "r4", "a2", "a4"))
    return FourWheelSteerComparison(
        speed=u, rear_steer_ratio=k,
        sideslip_gain_2ws=two.sideslip_angle, sideslip_gain_4ws=four.sideslip_angle,
        yaw_rate_gain_2ws=two.yaw_rate, yaw_rate_gain_4ws=four.yaw_rate,
        frequency_hz=float(frequency_hz),
        yaw_rate_magnitude_2ws=np.abs(r2), yaw_rate_magnitude_4ws=np.abs(r4),
        yaw_rate_phase_2ws=np.rad2deg(np.angle(r2)), yaw_rate_phase_4ws=np.rad2deg(np.angle(r4)),
        lateral_acceleration_phase_2ws=np.rad2deg(np.angle(a2)),
        lateral_acceleration_phase_4ws=np.rad2deg(np.angle(a4)),
    )
