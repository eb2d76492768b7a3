"""What several vehicle models share: the aerodynamic side force of a crosswind
(:mod:`~vehdyn.components.aero`)."""

from vehdyn.components.aero import (
    aero_side_force,
    centre_of_pressure_ahead_of_cg,
    trailer_wind_side_force_factor,
    wind_side_force_factor,
)

__all__ = ["aero_side_force", "wind_side_force_factor", "trailer_wind_side_force_factor", "centre_of_pressure_ahead_of_cg"]
