"""Crosswind procedures: a crosswind gust and the crosswind-sensitivity test (ISO 12021).

A gust is a 1 - cos pulse on the aerodynamic side force and yaw moment (:func:`crosswind_gust`);
the sensitivity test drives the vehicle straight through a zone of steady side wind
(:func:`wind_zone_signal`) with the steering wheel held, and reports the yaw rate, lateral
acceleration and lateral offset it causes (:func:`crosswind_sensitivity`; ISO 12021:2010, *Road
vehicles -- Sensitivity to lateral wind -- Open-loop test method using wind generator input*).
"""

from __future__ import annotations

from vehdyn.params.checks import MAX_RUN_SAMPLES, check_sample_count, check_vehicle, finite_number
from vehdyn.errors import ParameterError
from vehdyn.components.aero import centre_of_pressure_ahead_of_cg
from dataclasses import dataclass
import math
import numpy as np

__all__ = ["crosswind_gust", "wind_zone_signal", "CrosswindSensitivity", "crosswind_sensitivity"]


def crosswind_gust(vehicle, speed: float, gust_speed: float, *, start: float = 1.0, duration: float = 1.0,
                   side_force_derivative: float = 2.0, yaw_moment_derivative: float = 0.3,
                   side_area: float | None = None):
    """Inputs ``external_lateral_force`` and ``external_yaw_moment`` of a 1 - cos crosswind gust.

    The wind w(t) = w_g (1 - cos(2 pi (t - start)/duration)) / 2 blows toward +y (SAE: from the
    left to the right); with the resultant air speed V_r^2 = u^2 + w^2 and the aerodynamic sideslip
    beta_w = atan(w / u), the linearized aerodynamic side force and yaw moment are (Hucho,
    *Aerodynamics of Road Vehicles*, 4th ed., 1998, sec. 4.4; Wong, *Theory of Ground Vehicles*,
    4th ed., 2008, sec. 3.2)::

        F_y = 0.5 rho V_r^2 A C_Y,beta beta_w,      M_z = 0.5 rho V_r^2 A L C_N,beta beta_w

    with A the side (reference) area and L the wheelbase. The defaults C_Y,beta = 2.0 /rad and
    C_N,beta = 0.3 /rad (referred to the frontal area) are typical of passenger cars in Hucho's
    data, not measured values of the shipped vehicles; positive C_N,beta turns the nose downwind.
    (The same law acts inside :class:`~vehdyn.handling.SingleTrack` through its input
    ``wind_velocity_lateral``, with the coefficients of the vehicle file; see
    :mod:`vehdyn.handling.crosswind`.)

    Parameters
    ----------
    vehicle : Vehicle
    speed : float
        Forward speed u [m/s] at which the gust is met.
    gust_speed : float
        Peak crosswind w_g [m/s] (positive toward the right).
    start, duration : float
        [s].
    side_force_derivative, yaw_moment_derivative : float
        C_Y,beta and C_N,beta [1/rad].
    side_area : float, optional
        Reference area [m^2] (default the frontal area).

    Returns
    -------
    dict
        ``{"external_lateral_force": f(t), "external_yaw_moment": g(t)}`` for ``simulate``.
    """
    check_vehicle("crosswind_gust", vehicle)
    speed, gust_speed = finite_number(speed, "speed", positive=True), finite_number(gust_speed, "gust_speed")
    start, duration = finite_number(start, "start"), finite_number(duration, "duration", positive=True)
    area = vehicle.aero.frontal_area if side_area is None else finite_number(side_area, "side_area", positive=True)
    rho, length = vehicle.aero.air_density, vehicle.geometry.wheelbase

    def wind(t):
        tau = (np.asarray(t, dtype=float) - start) / duration
        return np.where((tau >= 0) & (tau <= 1), 0.5 * gust_speed * (1 - np.cos(2 * np.pi * tau)), 0.0)

    def pressure_angle(t):  # 0.5 rho V_r^2 A beta_w: the side-force law of vehdyn.handling.crosswind per C_Y'
        from vehdyn.components.aero import aero_side_force

        return aero_side_force(np, 0.5 * rho * area, speed, wind(t))

    return {"external_lateral_force": lambda t: side_force_derivative * pressure_angle(t),
            "external_yaw_moment": lambda t: yaw_moment_derivative * length * pressure_angle(t)}


# --------------------------------------------------------------------------- the crosswind test
def wind_zone_signal(speed: float, wind_speed: float, wind_length: float, wheelbase: float, start: float = 0.5):
    """The lateral wind [m/s] the vehicle feels driving through a wind zone, as a closed-form signal.

    The front axle enters the zone (where the wind blows at ``wind_speed``) at ``start`` [s]; the
    wind on the vehicle rises as a half cosine while the wheelbase passes the zone's edge (L / u),
    holds, and falls the same way when the vehicle leaves (front axle at ``start + wind_length /
    u``). The rise stands for the body entering the wind; the aerodynamic transient is not modelled
    (Hucho 1998, sec. 4.4, for the measured build-up of side force at a gust edge).

    Parameters
    ----------
    speed : float
        Forward speed u [m/s], > 0.
    wind_speed : float
        Lateral wind in the zone [m/s].
    wind_length : float
        Zone length [m], at least ``wheelbase``.
    wheelbase : float
        L [m], > 0.
    start : float
        When the front axle enters the zone [s].

    Returns
    -------
    PiecewiseSignal
        ``u(t)`` for :func:`vehdyn.simulate` (evaluated exactly by the compiled backend).
    """
    from vehdyn.piecewise_signal import PiecewiseSignal

    speed = finite_number(speed, "speed", positive=True)
    wheelbase = finite_number(wheelbase, "wheelbase", positive=True)
    wind_speed, start = finite_number(wind_speed, "wind_speed"), finite_number(start, "start")
    wind_length = finite_number(wind_length, "wind_length", minimum=wheelbase)

    rise = wheelbase / speed
    full, leave = start + rise, start + wind_length / speed
    half, omega = 0.5 * wind_speed, math.pi / rise
    pieces = [[start, full, half, 0.0, half, omega, -0.5 * math.pi]]
    if leave > full:
        pieces.append([full, leave, wind_speed, 0.0, 0.0, 0.0, 0.0])
    pieces.append([leave, leave + rise, half, 0.0, half, omega, 0.5 * math.pi])
    return PiecewiseSignal(pieces)


@dataclass(frozen=True)
class CrosswindSensitivity:
    """The response to a crosswind zone (:func:`crosswind_sensitivity`).

    Attributes
    ----------
    speed, wind_speed : float
        Forward speed u and lateral wind w [m/s] (w > 0 blows toward +y, the right).
    wind_length : float
        Length of the wind zone [m].
    driver : bool
        True when the driver model steered (closed loop), False with the steering held at 0.
    peak_yaw_rate : float
        Yaw rate of largest magnitude, with its sign [rad/s] (SAE: > 0 turning right, downwind).
    peak_lateral_acceleration : float
        Lateral acceleration of largest magnitude, with its sign [m/s^2].
    lateral_deviation_at_exit : float
        Lateral displacement y of the CG [m] when the rear axle leaves the zone (> 0 downwind).
    lateral_deviation : float
        y [m] at the end of the run (``duration`` after the front axle entered the zone).
    max_lateral_deviation : float
        Largest |y| over the run [m].
    yaw_angle_at_exit : float
        Heading psi [rad] when the rear axle leaves the zone.
    centre_of_pressure, neutral_steer_point : float
        x_p and x_n, ahead of the CG [m]: x_p > x_n turns the vehicle downwind.
    result : SimulationResult
        The run (states, the wind input, outputs).
    """

    speed: float
    wind_speed: float
    wind_length: float
    driver: bool
    peak_yaw_rate: float
    peak_lateral_acceleration: float
    lateral_deviation_at_exit: float
    lateral_deviation: float
    max_lateral_deviation: float
    yaw_angle_at_exit: float
    centre_of_pressure: float
    neutral_steer_point: float
    result: object


def _signed_peak(values) -> float:
    values = np.asarray(values, dtype=float)
    return float(values[np.argmax(np.abs(values))])


def crosswind_sensitivity(vehicle, speed: float = 100 / 3.6, *, wind_speed: float = 20.0, wind_length: float = 20.0,
                          driver=False, duration: float = 3.0, model=None, rtol: float = 1e-7):
    """Response to a zone of steady lateral wind, steering held or steered by the driver model.

    The vehicle drives straight at ``speed`` into a zone ``wind_length`` long where the wind blows
    across the road at ``wind_speed`` (an open-loop test in the style of ISO 12021:2010, *Road
    vehicles -- Sensitivity to lateral wind -- Open-loop test method using wind generator input*,
    whose wind generators blow at about 20 m/s over a stated length of track; the metrics here are
    this package's: peak yaw rate and lateral acceleration, lateral deviation at the zone's exit
    and after ``duration``). With ``driver=True`` the :class:`~vehdyn.driver.PreviewDriver`
    (defaults) holds the straight path y = 0 (closed loop). The sign of the response follows from
    the centre of pressure against the neutral steer point (:mod:`vehdyn.handling.crosswind`).

    Parameters
    ----------
    vehicle : Vehicle
    speed : float
        Forward speed [m/s] (default 100 km/h); held by a rear-axle force equal to the drag.
    wind_speed : float
        Lateral wind w [m/s] in the zone (default 20 m/s; > 0 blows toward +y, the right).
    wind_length : float
        Zone length [m] (default 20 m), at least the wheelbase.
    driver : bool or PreviewDriver
        False: steering held at zero (open loop); True: the default preview driver on the path
        y = 0 (:class:`~vehdyn.driver.PreviewDriver` with the vehicle's wheelbase, defaults
        otherwise); or a driver of your own (any controller of :mod:`vehdyn.driver`), closed
        around the model with ``driver.close(model)``.
    duration : float
        Run length [s] after the front axle enters the zone (the zone starts 0.5 s into the run).
    model : SingleTrack, optional
        Default ``SingleTrack(vehicle)`` (the vehicle's tire law, tire lag). Any model with the
        states ``x``, ``y``, ``yaw_angle``, ``yaw_rate``, the input ``wind_velocity_lateral`` and,
        for the driver, ``front_steer_angle``.
    rtol : float
        Relative tolerance of the RK45 integration [-] (default 1e-7; the absolute tolerance is
        1e-9 max(u, 1 m/s)); the output is sampled every 5 ms.

    Returns
    -------
    CrosswindSensitivity
        The metrics (peak yaw rate and lateral acceleration, the lateral deviation and yaw angle
        when the rear axle leaves the zone, the deviation at the end and its largest magnitude),
        the centre of pressure and neutral steer point, and the run (``result``).

    References
    ----------
    ISO 12021:2010, *Road vehicles - Sensitivity to lateral wind - Open-loop test method using wind
    generator input* (the test set-up; the metrics are this package's, see above).
    """
    from vehdyn.simulation import simulate
    from vehdyn.handling.bicycle import check_speed
    from vehdyn.driver import PreviewDriver
    from vehdyn.handling.single_track import SingleTrack
    from vehdyn.handling.steady_state import neutral_steer_point

    v = check_vehicle("crosswind_sensitivity", vehicle)
    u = float(check_speed(speed))
    wind_speed, duration = finite_number(wind_speed, "wind_speed"), finite_number(duration, "duration", positive=True)
    wind_length = finite_number(wind_length, "wind_length", positive=True)
    check_sample_count((0.5 + duration) * 200, "duration", duration, "samples every 5 ms", limit=MAX_RUN_SAMPLES)
    L = v.geometry.wheelbase
    if wind_length < L:
        raise ParameterError(f"wind_length must be at least the wheelbase {L:.3f} m, got {wind_length!r}",
                             key="wind_length", value=wind_length)
    start = 0.5
    if model is None:
        model = SingleTrack(v)
    needed = ("x", "y", "yaw_angle", "yaw_rate")
    if any(n not in model.state_names for n in needed) or "wind_velocity_lateral" not in model.input_names:
        raise ParameterError(f"model must have states {list(needed)} and the input wind_velocity_lateral; "
                             f"{type(model).__name__} has states {list(model.state_names)}", key="model",
                             value=type(model).__name__)
    inputs = {"wind_velocity_lateral": wind_zone_signal(u, float(wind_speed), float(wind_length), L, start)}
    if "rear_longitudinal_force" in model.input_names:  # hold the speed against the drag
        inputs["rear_longitudinal_force"] = v.aero.drag_force(u).item()
    x0 = model.straight_running(u) if hasattr(model, "straight_running") else \
        model.state_vector({"longitudinal_velocity": u} if "longitudinal_velocity" in model.state_names else {})
    closed = driver is not False and driver is not None
    if closed:
        if driver is True:
            driver = PreviewDriver(np.array([-100.0, u * (start + duration) + 1e3]), np.zeros(2), wheelbase=L)
        model = driver.close(model)
        x0 = np.concatenate([x0, np.zeros(driver.n_states)])
        inputs = {k: v for k, v in inputs.items() if k in model.input_names}  # what the driver commands goes
    t = np.linspace(0.0, start + duration, int(round((start + duration) * 200)) + 1)
    res = simulate(model, t, inputs, x0=x0, method="RK45", rtol=rtol, atol=1e-9 * max(u, 1.0))
    y, psi, r, ay = res["y"], res["yaw_angle"], res["yaw_rate"], res["lateral_acceleration"]
    exit_time = start + (wind_length + L) / u
    k = min(int(np.searchsorted(t, exit_time)), t.size - 1)
    x_n = -neutral_steer_point(v).behind_cg
    return CrosswindSensitivity(
        speed=u, wind_speed=float(wind_speed), wind_length=float(wind_length), driver=closed,
        peak_yaw_rate=_signed_peak(r), peak_lateral_acceleration=_signed_peak(ay),
        lateral_deviation_at_exit=float(y[k]), lateral_deviation=float(y[-1]),
        max_lateral_deviation=float(np.max(np.abs(y))), yaw_angle_at_exit=float(psi[k]),
        centre_of_pressure=centre_of_pressure_ahead_of_cg(v), neutral_steer_point=float(x_n), result=res)
