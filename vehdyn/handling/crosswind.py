"""Crosswind: the aerodynamic side force and yaw moment, and the crosswind-sensitivity test.

A lateral wind w (the air's velocity along the vehicle's y axis, SAE: positive blowing toward the
right, i.e. a wind from the left) meets a vehicle driving at forward speed u. The air flows past
the body at the resultant speed V_r and the aerodynamic sideslip angle beta_w::

    V_r^2 = u^2 + w^2,        beta_w = atan(w / |u|)

and makes a side force at the centre of pressure, a distance x_p ahead of the CG, hence a yaw
moment about the CG (Hucho, *Aerodynamics of Road Vehicles*, 4th ed., 1998, sec. 4.4; Wong,
*Theory of Ground Vehicles*, 4th ed., 2008, sec. 3.2)::

    F_w = 0.5 rho V_r^2 A C_Y' beta_w,        M_w = x_p F_w

with rho the air density, A the frontal (reference) area and C_Y' = dC_Y/d(beta_w) the
side-force coefficient slope (``vehicle.aero.side_force_coefficient_slope``). The centre of
pressure sits ``vehicle.aero.centre_of_pressure_from_front_axle`` times the wheelbase behind the
front axle: x_p = a - f_p L. SAE signs: a wind toward +y pushes the vehicle toward +y, and with
x_p > 0 yaws its nose toward +y, downwind. The force is linear in beta_w, as measured on cars up
to beta_w of about 20 degrees (Hucho 1998, sec. 4.4). The wind is taken in the vehicle's axes;
the aerodynamic sideslip from the vehicle's own lateral velocity and yaw rate is neglected (its
force is 0.5 rho u A C_Y' v, about 1 % of the tires' C v / u at highway speed, so the vehicle's
eigenvalues stay those of the model without wind).

Linearized about w = 0 (every wind-free state):  F_w = 0.5 rho A C_Y' u w = k_w u w, the input
column of :class:`~vehdyn.handling.LinearBicycle`'s ``wind_velocity_lateral``.

Which way the vehicle turns is set by where the centre of pressure lies against the neutral steer
point (NSP, the point where a side force makes no steady yaw rate,
:func:`~vehdyn.handling.neutral_steer_point`), x_n = (a C_f - b C_r) / (C_f + C_r) ahead of the CG.
The steady yaw rate under a side force F at x_p is (:func:`steady_state_crosswind_yaw_rate`)::

    r = F u (C_f + C_r) (x_p - x_n) / (C_f C_r L (L + K u^2))

with K the understeer gradient: a centre of pressure ahead of the NSP (the usual case, Wong 2008,
sec. 3.2) turns the vehicle downwind.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params import Vehicle

__all__ = ["aero_side_force", "wind_side_force_factor", "trailer_wind_side_force_factor",
           "centre_of_pressure_ahead_of_cg", "steady_state_crosswind_yaw_rate", "wind_zone_signal",
           "CrosswindSensitivity", "crosswind_sensitivity", "optional_wind_input"]


def aero_side_force(xp, side_force_factor, speed, wind_velocity_lateral):
    """Aerodynamic side force F_w = k_w (u^2 + w^2) atan(w / |u|) [N] (SAE y).

    Parameters
    ----------
    xp : namespace
        ``numpy`` or the compiled namespace of :mod:`~vehdyn.handling.single_track_equations`
        (needs ``atan2`` and ``abs``).
    side_force_factor : float or ndarray
        k_w = 0.5 rho A C_Y' [kg/m] (:func:`wind_side_force_factor`).
    speed : float or ndarray
        Forward speed u of the vehicle [m/s].
    wind_velocity_lateral : float or ndarray
        w [m/s], the air's velocity along the vehicle's y axis (positive toward the right).
    """
    return side_force_factor * (speed * speed + wind_velocity_lateral * wind_velocity_lateral) * \
        xp.atan2(wind_velocity_lateral, xp.abs(speed))


def _vehicle(vehicle) -> Vehicle:
    if not isinstance(vehicle, Vehicle):
        raise ParameterError(f"vehicle must be a vehdyn Vehicle, got {type(vehicle).__name__}", key="vehicle",
                             value=vehicle)
    return vehicle


def optional_wind_input(crosswind: bool, B, D, inputs, phenomena):
    """A linear model's wind input (the last column of B and D): named and kept, or dropped.

    Returns ``(B, D, inputs, phenomena)`` with ``wind_velocity_lateral`` [m/s] appended to the
    input signals and ``"aero"`` to the phenomena when ``crosswind`` is true.
    """
    from vehdyn.signals import Signal

    if not crosswind:
        return B[:, :-1], D[:, :-1], tuple(inputs), set(phenomena)
    wind = Signal("wind_velocity_lateral", "m/s", "lateral wind: the air's velocity along the vehicle's y axis "
                                                  "(toward +y)")
    return B, D, tuple(inputs) + (wind,), set(phenomena) | {"aero"}


def _side_force_factor(air_density: float, area: float, slope: float) -> float:
    """k_w = 0.5 rho A C_Y' [kg/m]: the one factor of the side-force law for every body."""
    return 0.5 * air_density * area * slope


def wind_side_force_factor(vehicle: Vehicle) -> float:
    """k_w = 0.5 rho A C_Y' [kg/m] of ``vehicle`` (its ``aero`` group)."""
    aero = _vehicle(vehicle).aero
    return _side_force_factor(aero.air_density, aero.frontal_area, aero.side_force_coefficient_slope)


def trailer_wind_side_force_factor(trailer, air_density: float | None = None) -> float:
    """k_w,t = 0.5 rho A_t C_Y,t' [kg/m] of a :class:`~vehdyn.Trailer` (same law as the towing vehicle's).

    Parameters
    ----------
    trailer : Trailer
        Its ``frontal_area`` and ``side_force_coefficient_slope`` (0: no wind force on the trailer).
    air_density : float, optional
        rho [kg/m^3]; :func:`~vehdyn.handling.car_trailer_parameters` passes the towing vehicle's.
        Default: the vehicle files' standard air (``Aerodynamics.air_density``'s default, 20 degC).
    """
    import dataclasses

    from vehdyn.params import Trailer
    from vehdyn.params.vehicle import Aerodynamics

    if air_density is None:
        air_density = next(f.default for f in dataclasses.fields(Aerodynamics) if f.name == "air_density")

    if not isinstance(trailer, Trailer):
        raise ParameterError(f"trailer must be a vehdyn Trailer, got {type(trailer).__name__}", key="trailer",
                             value=trailer)
    rho = float(air_density)
    if not (np.isfinite(rho) and rho > 0):
        raise ParameterError(f"air_density must be finite and positive [kg/m^3], got {air_density!r}",
                             key="air_density", value=air_density)
    return _side_force_factor(rho, trailer.frontal_area, trailer.side_force_coefficient_slope)


def centre_of_pressure_ahead_of_cg(vehicle: Vehicle) -> float:
    """x_p = a - f_p L [m]: the aerodynamic centre of pressure ahead of the CG (negative: behind)."""
    v = _vehicle(vehicle)
    return v.geometry.cg_to_front_axle - v.aero.centre_of_pressure_from_front_axle * v.geometry.wheelbase


def steady_state_crosswind_yaw_rate(vehicle_or_bicycle, speed, side_force, centre_of_pressure):
    """Steady yaw rate [rad/s] of the linear bicycle under a side force at a point, steer held at 0.

    r = F u (C_f + C_r) (x_p - x_n) / (C_f C_r L (L + K u^2)) (module docstring; solve the bicycle's
    two equilibrium equations with F_y = F at x_p). Positive (turning right, downwind for a wind
    toward +y) when the force acts ahead of the neutral steer point x_n.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
    speed : float
        [m/s].
    side_force : float
        F [N] (SAE y).
    centre_of_pressure : float
        x_p [m] ahead of the CG.
    """
    from vehdyn.handling.bicycle import bicycle_parameters, check_speed
    from vehdyn.handling.steady_state import neutral_steer_point

    p = bicycle_parameters(vehicle_or_bicycle)
    u = check_speed(speed)
    cf, cr, L = p.front_cornering_stiffness, p.rear_cornering_stiffness, p.wheelbase
    x_n = -neutral_steer_point(p).behind_cg
    return side_force * u * (cf + cr) * (centre_of_pressure - x_n) / (cf * cr * L * (L + p.understeer_gradient * u**2))


# --------------------------------------------------------------------------- the crosswind test
def wind_zone_signal(speed: float, wind_speed: float, wind_length: float, wheelbase: float, start: float = 0.5):
    """The lateral wind [m/s] the vehicle feels driving through a wind zone, as a closed-form signal.

    The front axle enters the zone (where the wind blows at ``wind_speed``) at ``start`` [s]; the
    wind on the vehicle rises as a half cosine while the wheelbase passes the zone's edge (L / u),
    holds, and falls the same way when the vehicle leaves (front axle at ``start + wind_length /
    u``). The rise stands for the body entering the wind; the aerodynamic transient is not modelled
    (Hucho 1998, sec. 4.4, for the measured build-up of side force at a gust edge).

    Returns
    -------
    PiecewiseSignal
        ``u(t)`` for :func:`vehdyn.simulate` (evaluated exactly by the compiled backend).
    """
    from vehdyn.piecewise_signal import PiecewiseSignal

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
    and after ``duration``). With ``driver=True`` the :class:`~vehdyn.handling.PreviewDriver`
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
        y = 0; or a PreviewDriver of your own.
    duration : float
        Run length [s] after the front axle enters the zone (the zone starts 0.5 s into the run).
    model : SingleTrack, optional
        Default ``SingleTrack(vehicle)`` (the vehicle's tire law, tire lag). Any model with the
        states ``x``, ``y``, ``yaw_angle``, ``yaw_rate``, the input ``wind_velocity_lateral`` and,
        for the driver, ``front_steer_angle``.
    rtol : float
        Relative tolerance of the RK45 integration.

    Returns
    -------
    CrosswindSensitivity
    """
    from vehdyn.simulate import simulate
    from vehdyn.handling.bicycle import check_speed
    from vehdyn.handling.driver import DriverInTheLoop, PreviewDriver
    from vehdyn.handling.maneuvers import _finite
    from vehdyn.handling.single_track import SingleTrack
    from vehdyn.handling.steady_state import neutral_steer_point

    v = _vehicle(vehicle)
    u = float(check_speed(speed))
    wind_speed, duration = _finite("wind_speed", wind_speed), _finite("duration", duration, positive=True)
    wind_length = _finite("wind_length", wind_length, positive=True)
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
            driver = PreviewDriver(path_x=np.array([-100.0, u * (start + duration) + 1e3]), path_y=np.zeros(2))
        model = DriverInTheLoop(model, driver, wheelbase=L)
        x0 = np.append(x0, 0.0)
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
