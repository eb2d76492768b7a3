"""ISO 7975:2019 braking in a turn: from a steady turn, brake at a constant deceleration demand."""

from __future__ import annotations

from vehdyn.params.checks import finite_number
from vehdyn.errors import ParameterError
from dataclasses import dataclass
import numpy as np

__all__ = ["BrakingInTurn", "braking_in_turn"]


@dataclass(frozen=True)
class BrakingInTurn:
    """Braking in a turn (ISO 7975): the result and the metrics 1 s after brake onset.

    Attributes
    ----------
    result : SimulationResult
    initial : SteadyStateCornering
    yaw_rate_ratio : float
        Yaw rate 1 s after brake onset over the initial yaw rate [-].
    sideslip_change : float
        Sideslip change over that second [rad].
    mean_deceleration : float
        Mean longitudinal deceleration over that second [m/s^2] (positive braking).
    """

    result: object
    initial: object
    yaw_rate_ratio: float
    sideslip_change: float
    mean_deceleration: float


def braking_in_turn(model, *, radius: float = 100.0, lateral_acceleration: float = 5.0, deceleration: float = 4.0,
                    brake_front_share: float = 0.65, brake_start: float = 1.0, duration: float = 4.0,
                    method: str = "RK45", rtol: float = 1e-6):
    """ISO 7975 braking in a turn with a force-mode SingleTrack model.

    The vehicle starts in the steady turn (radius [m], a_y [m/s^2]); at ``brake_start`` the drive is
    released and braking forces m * ``deceleration`` split ``brake_front_share`` : rest between the
    axles are applied (clipped by the tire friction in the model); the steer is held. The run is
    sampled every 0.01 s (the metrics' own grid).

    Parameters
    ----------
    model : SingleTrack
        A force-mode SingleTrack (``wheel_spin=False``).
    radius : float
        Radius of the initial turn [m] (positive turning right).
    lateral_acceleration : float
        Lateral acceleration of the initial turn [m/s^2].
    deceleration : float
        Braking demand [m/s^2], > 0.
    brake_front_share : float
        Front axle's share of the braking force [-], in [0, 1].
    brake_start : float
        Brake onset [s], >= 0.
    duration : float
        Run after the brake onset [s], > 0 (at least the 1 s the metrics need).
    method : str
        Integrator of :func:`vehdyn.simulate` (default ``"RK45"``; the inputs are held between
        the 0.01 s samples, ``hold="zoh"``).
    rtol : float
        Relative tolerance of the integration [-] (default 1e-6).

    Returns
    -------
    BrakingInTurn
        The run, the initial steady turn and the metrics 1 s after brake onset: yaw rate over the
        initial yaw rate [-], sideslip change [rad], mean deceleration [m/s^2].

    Raises
    ------
    ParameterError
        ``model`` not a force-mode SingleTrack, ``brake_front_share`` outside [0, 1],
        ``deceleration`` not finite and > 0, ``brake_start`` < 0, ``duration`` < 1 s, too many
        samples, or a radius and lateral acceleration of opposite signs.
    SimulationError
        No steady turn of the model at that radius and lateral acceleration.

    References
    ----------
    ISO 7975:2019, *Passenger cars - Braking in a turn - Open-loop test method* (the manoeuvre:
    brake from a steady turn with the steering held; the metrics here are read 1 s after brake
    onset).
    """
    from vehdyn.simulation import simulate
    from vehdyn.handling.nonlinear_steady_state import steady_state_cornering
    from vehdyn.handling.single_track import SingleTrack
    from vehdyn.params.checks import MAX_RUN_SAMPLES, check_sample_count

    if not isinstance(model, SingleTrack) or model.wheel_spin:
        raise ParameterError(f"braking_in_turn: model must be a force-mode SingleTrack (wheel_spin=False), got "
                             f"{type(model).__name__}", key="model", value=model)
    share = finite_number(brake_front_share, "brake_front_share")
    if not 0 <= share <= 1:
        raise ParameterError(f"brake_front_share must be in [0, 1], got {share}", key="brake_front_share", value=share)
    deceleration = finite_number(deceleration, "deceleration", positive=True)
    brake_start = finite_number(brake_start, "brake_start", minimum=0.0)
    duration = finite_number(duration, "duration", minimum=1.0)
    check_sample_count((brake_start + duration) / 0.01, "duration" if duration > brake_start else "brake_start",
                       duration if duration > brake_start else brake_start, "(brake_start + duration) / 0.01 s",
                       limit=MAX_RUN_SAMPLES)
    initial = steady_state_cornering(model, lateral_acceleration=lateral_acceleration, radius=radius)
    force = float(model.parameters.mass) * deceleration
    drive = initial.drive
    time = np.linspace(0.0, brake_start + duration, int(round((brake_start + duration) / 0.01)) + 1)
    braking = time >= brake_start
    inputs = {"front_steer_angle": np.full(time.size, initial.steer_angle),
              "front_longitudinal_force": np.where(braking, -share * force, 0.0),
              "rear_longitudinal_force": np.where(braking, -(1 - share) * force, drive)}
    result = simulate(model, time, inputs, x0=initial.state, method=method, rtol=rtol, hold="zoh")
    t1 = brake_start + 1.0
    r = result["yaw_rate"]
    beta = result["sideslip_angle"]
    u = result["longitudinal_velocity"]
    return BrakingInTurn(result, initial, float(np.interp(t1, time, r) / initial.yaw_rate),
                         float(np.interp(t1, time, beta) - np.interp(brake_start, time, beta)),
                         float((np.interp(brake_start, time, u) - np.interp(t1, time, u)) / 1.0))
