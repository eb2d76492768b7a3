"""Terramechanics: wheels and tires on deformable soil (sand, loam, clay, snow).

API index
---------
Soils
    :class:`Soil`, :func:`load_soil`, :func:`shipped_soils`, :func:`soil_source`
Bekker's closed forms
    :func:`bekker_pressure`, :func:`plate_sinkage`, :func:`rigid_wheel_sinkage`,
    :func:`parabolic_wheel_sinkage`, :func:`compaction_resistance`, :func:`bulldozing_resistance`
Rigid wheel (Wong-Reece stress distribution, side force after Ishigami et al.)
    :class:`RigidWheel` (``solve(load, slip, slip_angle=None)``), :class:`WheelSoilResult`
Flexible tire
    :class:`FlexibleWheel`, :func:`critical_ground_pressure`
Tire law for vehicle models
    :class:`SoftSoilTire`, :class:`SoftSoilTireGeometry`

Slip ``s`` in [-1, 1]: ``1 - V / (r omega)`` driven, ``r omega / V - 1`` braked (skid).
"""

from .bekker import (bekker_pressure, bulldozing_resistance, compaction_resistance, parabolic_wheel_sinkage,
                     plate_sinkage, rigid_wheel_sinkage)
from .flexible import FlexibleWheel, critical_ground_pressure
from .soft_soil_tire import SoftSoilTire, SoftSoilTireGeometry
from .soil import Soil, load_soil, shipped_soils, soil_source
from .wong_reece import RigidWheel, WheelSoilResult

__all__ = [
    "Soil", "load_soil", "shipped_soils", "soil_source",
    "bekker_pressure", "plate_sinkage", "rigid_wheel_sinkage", "parabolic_wheel_sinkage",
    "compaction_resistance", "bulldozing_resistance",
    "RigidWheel", "WheelSoilResult",
    "FlexibleWheel", "critical_ground_pressure",
    "SoftSoilTire", "SoftSoilTireGeometry",
]
