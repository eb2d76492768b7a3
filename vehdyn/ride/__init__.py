"""Ride: ISO 8608 roads, ISO 2631-1 comfort and the random response of linear ride models.

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
