"""Chassis control: controllers that close loops around the vehicle models.

:class:`ABS` (wheel-slip control by an apply/hold/release pressure modulator),
:class:`TractionControl` (drive-torque reduction and brake intervention on a spinning axle) and
:class:`ESC` (yaw-rate control by one-wheel braking with a sideslip guard) are :class:`~vehdyn.Model`
objects with named states, built from a :class:`~vehdyn.Vehicle` plus keyword gains, closed around a
plant by :class:`vehdyn.interconnect.ClosedLoop` (``controller.close(plant)``; it simulates,
linearizes and nests: ESC around ABS around the car) and, when the plant and the controller have
compiled forms (the SingleTrack and FullVehicle with their compiled tire laws; these three
controllers), compiled with numba for ``simulate(..., backend="compiled"/"auto")``. A road of other
friction is the models' ``friction`` argument (:mod:`vehdyn.components.tire_setup`).
"""

from vehdyn.chassis.abs import ABS
from vehdyn.chassis.base import ChassisController
from vehdyn.chassis.esc import ESC
from vehdyn.chassis.traction_control import TractionControl

__all__ = ["ABS", "TractionControl", "ESC", "ChassisController"]
