"""Ride dynamics, from road to seat: models, wheelbase delay, analysis, roads, comfort, random response, active.

Models (each an exact :class:`vehdyn.LinearModel` with named signals)
    :class:`QuarterCar`, :class:`BouncePitch` (4-DOF half car, or the 2-DOF body-only model),
    :class:`FullCar` (7 DOF, anti-roll bars), their parameter sets :class:`QuarterCarParameters`,
    :class:`BouncePitchParameters`, :class:`FullCarParameters`. As every vehdyn model, each is
    built from a vehicle, ``QuarterCar(vehicle, axle="front")``, ``BouncePitch(vehicle)``,
    ``FullCar(vehicle)``, or from a textbook's numbers, ``QuarterCar.from_parameters(...)``.
Wheelbase delay, the road at every wheel (:mod:`~vehdyn.ride.wheelbase`)
    :func:`road_frequency_response` (exact, frequency domain), :func:`road_inputs` (exact, time
    domain, through :meth:`RoadProfile.road_inputs`), :func:`with_wheelbase_delay` (Padé, state
    space, through :func:`~vehdyn.ride.wheelbase.pade_delay`), :func:`wheel_delays`,
    :func:`~vehdyn.ride.wheelbase.wheel_offsets`.
Analysis (:mod:`~vehdyn.ride.analysis`)
    :func:`ride_modes` / :class:`RideModes`, :func:`bounce_pitch_centres` /
    :class:`BouncePitchCentres`, :func:`olley_criteria` / :class:`OlleyCheck`,
    :func:`axle_ride_rates`, :func:`transmissibility`, :func:`suspension_travel_response`,
    :func:`dynamic_tire_load_response` (per unit road elevation; exact delay with a speed).
Roads
    In :mod:`vehdyn.road` (ISO 8608 spectra and synthesis, profiles and events, the IRI).
Comfort (:mod:`~vehdyn.ride.comfort`)
    :func:`weighting` / :data:`WEIGHTINGS` / :class:`Weighting` (ISO 2631-1 Wk, Wd, Wf, Wc, We, Wj:
    frequency domain, digital filter, state space), :func:`weighting_factor`, :func:`weighted_rms`,
    :func:`rms`, :func:`running_rms`, :func:`mtvv`, :func:`vibration_dose_value`,
    :func:`crest_factor`, :func:`vibration_total_value`, :data:`COMFORT_REACTIONS`,
    :func:`comfort_reactions`, :func:`comfort_category`.
Random response (:mod:`~vehdyn.ride.random_vibration`)
    :func:`random_response` -> :class:`RandomResponse`: r.m.s. of every output on an ISO 8608 road
    by the ``"lyapunov"`` route (exact covariance; rear wheels by the exact delay, or a Padé delay
    with ``delay="pade"``), the ``"psd"`` route (frequency integral, exact delay, stated error) or
    the ``"simulation"`` route (time domain, exact delay); :func:`stationary_covariance` (exact
    covariance of any linear model under white noise, random-walk states removed exactly).
Active and semi-active suspension (:mod:`~vehdyn.ride.active`)
    :func:`skyhook`, :func:`groundhook`, :class:`SemiActiveQuarterCar`, :func:`lqr_quarter_car` /
    :class:`LQRDesign`, :func:`relative_quarter_car`, :func:`compare_suspensions` (exact r.m.s.
    on an ISO 8608 road through :func:`random_response`).

Signals and signs: vertical displacements and road elevation are positive up (road-profile
convention), pitch nose up and roll right side down (SAE angles). Suspension travel is positive in
rebound (z_body - z_wheel), tire deflection (z_road - z_wheel) and dynamic tire load positive in
compression; actuator and damper forces positive when they extend the suspension (up on the body).
Road inputs are ``road_displacement<suffix>`` [m] and ``road_velocity<suffix>`` [m/s] with the
corner suffix (``""`` for a quarter car, ``_front``/``_rear``, ``_front_left`` ... for a full car;
one profile per track: ``""`` or ``_left``/``_right``), in every model, shaping filter, profile
and route alike. See :mod:`vehdyn.ride._ride_model`.
"""

from vehdyn.ride.active import (
    LQRDesign,
    SemiActiveQuarterCar,
    compare_suspensions,
    groundhook,
    lqr_quarter_car,
    relative_quarter_car,
    skyhook,
)
from vehdyn.ride.analysis import (
    BouncePitchCentres,
    OlleyCheck,
    RideModes,
    axle_ride_rates,
    bounce_pitch_centres,
    dynamic_tire_load_response,
    olley_criteria,
    ride_modes,
    suspension_travel_response,
    transmissibility,
)
from vehdyn.ride.bounce_pitch import BouncePitch, BouncePitchParameters
from vehdyn.ride.full_car import FullCar, FullCarParameters
from vehdyn.ride.lift_off import LateralSlip, LiftOff, LongitudinalSlip
from vehdyn.ride.quarter_car import QuarterCar, QuarterCarParameters
from vehdyn.ride.wheelbase import road_frequency_response, road_inputs, wheel_delays, with_wheelbase_delay
from vehdyn.ride.comfort import (
    COMFORT_REACTIONS,
    WEIGHTINGS,
    Weighting,
    comfort_category,
    comfort_reactions,
    crest_factor,
    mtvv,
    rms,
    running_rms,
    vibration_dose_value,
    vibration_total_value,
    weighted_rms,
    weighting,
    weighting_factor,
)
from vehdyn.ride.random_vibration import RandomResponse, random_response, stationary_covariance

__all__ = [
    "QuarterCar",
    "QuarterCarParameters",
    "BouncePitch",
    "BouncePitchParameters",
    "FullCar",
    "FullCarParameters",
    "LiftOff",
    "LateralSlip",
    "LongitudinalSlip",
    "road_frequency_response",
    "road_inputs",
    "wheel_delays",
    "with_wheelbase_delay",
    "RideModes",
    "ride_modes",
    "BouncePitchCentres",
    "bounce_pitch_centres",
    "OlleyCheck",
    "olley_criteria",
    "axle_ride_rates",
    "transmissibility",
    "suspension_travel_response",
    "dynamic_tire_load_response",
    "skyhook",
    "groundhook",
    "SemiActiveQuarterCar",
    "LQRDesign",
    "lqr_quarter_car",
    "relative_quarter_car",
    "compare_suspensions",
    # comfort
    "Weighting", "WEIGHTINGS", "weighting", "weighting_factor", "weighted_rms", "rms", "running_rms", "mtvv",
    "vibration_dose_value", "vibration_total_value", "crest_factor", "COMFORT_REACTIONS", "comfort_reactions",
    "comfort_category",
    # random response
    "RandomResponse", "random_response", "stationary_covariance",
]
