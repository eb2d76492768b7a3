"""What several vehicle models share, written once over an ``xp`` namespace.

* :mod:`~vehdyn.components.tire_forces` -- the tire-law step of a wheel or an axle: two tires at
  half the axle load, the mirror image of a law with ply steer (``TYRESIDE``), the road's friction
  by similarity, the SAE/ISO-W conventions, force mode;
* :mod:`~vehdyn.components.tire_slip` -- slip and relaxation kinematics (the tire deflections, the
  low-speed damping, the sliding limit at the peak slip);
* :mod:`~vehdyn.components.wheel` -- wheel spin: drive and brake torques, rolling resistance;
* :mod:`~vehdyn.components.planar` -- planar kinematics (earth position rates);
* :mod:`~vehdyn.components.aero` -- the aerodynamic side force of a crosswind;
* :mod:`~vehdyn.components.tire_setup` -- what a model reads from its tire laws when it is built,
  and the one ``friction`` argument (a constant ratio or a callable of the earth position);
* :mod:`~vehdyn.components.xp` -- the ``xp`` interface and its numpy namespace;
  :mod:`~vehdyn.components.compiled` its numba namespace (imported on first compiled use).
"""

from vehdyn.components.aero import (
    aero_side_force,
    centre_of_pressure_ahead_of_cg,
    trailer_wind_side_force_factor,
    wind_side_force_factor,
)

__all__ = ["aero_side_force", "wind_side_force_factor", "trailer_wind_side_force_factor", "centre_of_pressure_ahead_of_cg"]
