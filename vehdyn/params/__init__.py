"""Parameter sets: frozen, validated dataclasses loaded from TOML, and shipped-data lookup."""

from vehdyn.params.base import ParameterSet, dump_toml, load_toml, parameter, text
from vehdyn.params.vehicle import (
    Aerodynamics,
    Geometry,
    MassAndInertia,
    Steering,
    Driveline,
    Suspension,
    Tires,
    Vehicle,
    data_path,
    load_vehicle,
    shipped_vehicles,
)
from vehdyn.params.trailer import Trailer, load_trailer, shipped_trailers

__all__ = [
    "ParameterSet",
    "parameter",
    "text",
    "load_toml",
    "dump_toml",
    "Vehicle",
    "MassAndInertia",
    "Geometry",
    "Suspension",
    "Tires",
    "Steering",
    "Driveline",
    "Aerodynamics",
    "load_vehicle",
    "shipped_vehicles",
    "data_path",
    "Trailer",
    "load_trailer",
    "shipped_trailers",
]
