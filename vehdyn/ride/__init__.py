"""Ride dynamics, from road to seat: models, analysis, roads, comfort, random response, active suspension.

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
Roads (:mod:`vehdyn.ride.road`)
    :func:`iso8608_psd`, :data:`ISO8608_CLASSES`, :func:`iso8608_class_of`,
    :func:`estimate_spectrum` (Gd(n0) and class of a measured profile), :class:`RoadSpectrum` (PSD, band r.m.s., shaping
    filter), :class:`RoadProfile`, :func:`synthesize_profile`, :func:`synthesize_parallel_profiles`,
    :func:`isotropic_coherence`, events :func:`bump`, :func:`pothole`, :func:`speed_hump`,
    :func:`step`, :func:`iri` (ASTM E1926 golden car, :func:`golden_car`).
Comfort (:mod:`vehdyn.ride.comfort`)
    :func:`weighting` / :data:`WEIGHTINGS` (Wk, Wd, Wf, Wc, We, Wj), :func:`weighting_factor`,
    :func:`weighted_rms`, :func:`rms`, :func:`running_rms`, :func:`mtvv`, :func:`vibration_dose_value`,
    :func:`crest_factor`, :func:`vibration_total_value`, :func:`comfort_reactions`,
    :func:`comfort_category`.
Random response (:mod:`vehdyn.ride.random_response`)
    :func:`random_response` (``"lyapunov"`` with a Pade or exact delay, ``"psd"``, ``"simulation"``)
    -> :class:`RandomResponse`; :func:`stationary_covariance`.
"""

from .active import (
    LQRDesign,
    SemiActiveQuarterCar,
    compare_suspensions,
    groundhook,
    lqr_quarter_car,
    relative_quarter_car,
    skyhook,
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
from .comfort import (
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
from .random_response import RandomResponse, random_response, stationary_covariance
from .road import (
    GOLDEN_CAR,
    ISO8608_CLASSES,
    RoadProfile,
    RoadSpectrum,
    bump,
    golden_car,
    iri,
    estimate_spectrum,
    iso8608_class_of,
    iso8608_class_value,
    iso8608_psd,
    isotropic_coherence,
    pothole,
    speed_hump,
    step,
    synthesize_parallel_profiles,
    synthesize_profile,
)

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
    "compare_suspensions",

    # road
    "ISO8608_CLASSES", "iso8608_class_value", "iso8608_class_of", "iso8608_psd", "estimate_spectrum",
    "RoadSpectrum", "RoadProfile", "synthesize_profile", "synthesize_parallel_profiles", "isotropic_coherence",
    "bump", "pothole", "speed_hump", "step", "GOLDEN_CAR", "golden_car", "iri",
    # comfort
    "Weighting", "WEIGHTINGS", "weighting", "weighting_factor", "weighted_rms", "rms", "running_rms", "mtvv",
    "vibration_dose_value", "vibration_total_value", "crest_factor", "COMFORT_REACTIONS", "comfort_reactions",
    "comfort_category",
    # random response
    "RandomResponse", "random_response", "stationary_covariance",
]
