"""Ride dynamics: quarter car, bounce-pitch and full-car models, ride analysis, active suspension.

Models (each an exact :class:`vehdyn.LinearModel` with named signals)
    :class:`QuarterCar`, :class:`BouncePitch`, :class:`FullCar`
Road input at every wheel (wheelbase delay)
    :func:`road_frequency_response` (exact, frequency domain), :func:`road_inputs` (exact, time
    domain), :func:`with_wheelbase_delay` (Padé, state space), :func:`wheel_delays`
Analysis
    :func:`ride_modes`, :func:`bounce_pitch_centres`, :func:`olley_criteria`,
    :func:`axle_ride_rates`, :func:`transmissibility`, :func:`suspension_travel_response`,
    :func:`dynamic_tire_load_response`
Active and semi-active suspension
    :func:`skyhook`, :func:`groundhook`, :class:`SemiActiveQuarterCar`, :func:`lqr_quarter_car`,
    :func:`relative_quarter_car`, :func:`white_noise_rms`, :func:`iso8608_velocity_intensity`,
    :func:`compare_suspensions`

Signs: vertical displacements upward (road-profile convention), pitch nose up, roll right side
down (SAE angles); suspension travel positive in rebound, tire deflection and dynamic tire load
positive in compression. See :mod:`vehdyn.ride._ride_model`.
"""

from .active import (
    LQRDesign,
    SemiActiveQuarterCar,
    compare_suspensions,
    groundhook,
    iso8608_velocity_intensity,
    lqr_quarter_car,
    relative_quarter_car,
    skyhook,
    white_noise_rms,
)
from .analysis import (
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
from .bounce_pitch import BouncePitch, BouncePitchParameters
from .full_car import FullCar, FullCarParameters
from .quarter_car import QuarterCar, QuarterCarParameters
from .wheelbase import road_frequency_response, road_inputs, wheel_delays, with_wheelbase_delay

__all__ = [
    "QuarterCar",
    "QuarterCarParameters",
    "BouncePitch",
    "BouncePitchParameters",
    "FullCar",
    "FullCarParameters",
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
    "white_noise_rms",
    "iso8608_velocity_intensity",
    "compare_suspensions",
]
