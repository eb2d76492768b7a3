"""Roads: ISO 8608 spectra and their synthesis (:mod:`~vehdyn.road.iso8608`), road profiles and
discrete events (:mod:`~vehdyn.road.profile`), and the International Roughness Index
(:mod:`~vehdyn.road.roughness`). Elevation is positive up, distance along the track in metres."""

from vehdyn.road.roughness import GOLDEN_CAR, golden_car, iri
from vehdyn.road.iso8608 import (
    ISO8608_CLASSES,
    ISO8608_REFERENCE_FREQUENCY,
    RoadSpectrum,
    estimate_spectrum,
    iso8608_class_of,
    iso8608_class_value,
    iso8608_psd,
    isotropic_coherence,
    synthesize_parallel_profiles,
    synthesize_profile,
)
from vehdyn.road.profile import RoadProfile, bump, pothole, speed_hump, step

__all__ = [
    "ISO8608_CLASSES",
    "ISO8608_REFERENCE_FREQUENCY",
    "iso8608_class_value",
    "iso8608_psd",
    "iso8608_class_of",
    "estimate_spectrum",
    "RoadSpectrum",
    "RoadProfile",
    "synthesize_profile",
    "synthesize_parallel_profiles",
    "isotropic_coherence",
    "bump",
    "pothole",
    "speed_hump",
    "step",
    "GOLDEN_CAR",
    "golden_car",
    "iri",
]
