"""Terramechanics: wheels and tires on deformable soil (sand, loam, clay, snow).

API index
---------
Soils
    :class:`Soil`, :func:`load_soil`, :func:`shipped_soils`, :func:`soil_source`
Bekker's closed forms
    :func:`bekker_pressure`, :func:`plate_sinkage`, :func:`rigid_wheel_sinkage`,
    :func:`parabolic_wheel_sinkage`, :func:`compaction_resistance`, :func:`bulldozing_resistance`
Rigid wheel (Wong-Reece stress distribution)
    :class:`RigidWheel` (``solve(load, slip, slip_angle=None)``), :class:`WheelSoilResult`;
    ``reference`` (the same equations point by point with adaptive quadrature, slow)
Side force (side shear and sidewall bulldozing, after Ishigami et al. 2007)
    module ``lateral`` (used by the rigid wheel and the flexible tire)
Flexible tire
    :class:`FlexibleWheel`, :func:`critical_ground_pressure`
Tire law for vehicle models
    :class:`SoftSoilTire`, :class:`SoftSoilTireGeometry`
Curves (CLI ``vehdyn tire --soil NAME``, the off-road study)
    module ``curves``: ``soil_curves``, ``describe_soil``, ``plot_soil_curves``

Slip ``s`` in [-1, 1]: ``1 - V / (r omega)`` driven, ``r omega / V - 1`` braked (skid).

Validation
----------
The tests check the Wong-Reece quadrature against adaptive quadrature and against Bekker's closed
forms where their assumptions hold, the Coulomb limit of the drawbar pull, the flexible tire's
elastic mode against its closed forms, a SingleTrack coast-down on soil against the towed tires'
compaction resistance, and the shipped soils against an independent transcription of Wong's table.
Not yet against measured drawbar pull, sinkage or torque: no measured data set together with the
soil parameters of the same test (Wong and Reece 1967; Ding et al. 2011) was at hand.
"""

from vehdyn.tire.terramechanics.bekker import (bekker_pressure, bulldozing_resistance, compaction_resistance, parabolic_wheel_sinkage,
                     plate_sinkage, rigid_wheel_sinkage)
from vehdyn.tire.terramechanics.flexible import FlexibleWheel, critical_ground_pressure
from vehdyn.tire.terramechanics.soft_soil_tire import SoftSoilTire, SoftSoilTireGeometry
from vehdyn.tire.terramechanics.soil import Soil, load_soil, shipped_soils, soil_source
from vehdyn.tire.terramechanics.wong_reece import RigidWheel, WheelSoilResult

__all__ = [
    "Soil", "load_soil", "shipped_soils", "soil_source",
    "bekker_pressure", "plate_sinkage", "rigid_wheel_sinkage", "parabolic_wheel_sinkage",
    "compaction_resistance", "bulldozing_resistance",
    "RigidWheel", "WheelSoilResult",
    "FlexibleWheel", "critical_ground_pressure",
    "SoftSoilTire", "SoftSoilTireGeometry",
]
