"""The full vehicle: the top rung that ties mechanics, tires, handling and ride together.

:class:`FullVehicle` -- a sprung body (6 DOF, through :mod:`vehdyn.mechanics`) on four corners
(suspension with roll-centre and anti-pitch linkage, wheel hop, wheel spin, any tire law of
:mod:`vehdyn.tire`), steering with Ackermann blend and roll steer, driveline and brakes, aero.

Modules: :mod:`~vehdyn.full_vehicle.body` (sprung body and the wheels' x-y inertia),
:mod:`~vehdyn.full_vehicle.corner` (suspension, linkage, tire load, camber),
:mod:`~vehdyn.full_vehicle.steering`, :mod:`~vehdyn.full_vehicle.driveline`,
:mod:`~vehdyn.full_vehicle.aero`, :mod:`~vehdyn.full_vehicle.assembly` (the shared equations),
:mod:`~vehdyn.full_vehicle.model` (the Model), :mod:`~vehdyn.full_vehicle.operating_points` (trim),
(its rungs on the fidelity ladder are in :mod:`vehdyn.scene.full_vehicle_rungs`).
"""

from vehdyn.full_vehicle.corner import CORNERS
from vehdyn.full_vehicle.model import FullVehicle

__all__ = ["FullVehicle", "CORNERS"]
