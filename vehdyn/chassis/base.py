"""What the chassis controllers share: checks of their gains and vehicle, their channels' signal
names, the smooth switches of their laws, and :class:`ChassisController`, their base class
(:meth:`ChassisController.close` wraps a plant in a :class:`vehdyn.interconnect.ClosedLoop`)."""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.interconnect import ClosedLoop
from vehdyn.model import Model
from vehdyn.params.checks import check_gains, check_vehicle

__all__ = ["ChassisController", "check_gains", "check_vehicle", "channel_signals", "sigmoid", "deadband"]


def channel_signals(owner: str, axles, corners: bool, kinds):
    """(channels, {kind: [signal name per channel]}) in the single track's or the full vehicle's naming.

    One channel per axle named ``<axle>_<kind>`` (SingleTrack: ``front_brake_torque``), or with
    ``corners`` one per wheel named ``<kind>_<axle>_<side>`` (FullVehicle: ``brake_torque_front_left``).
    """
    axles = tuple(axles)
    if not axles or any(a not in ("front", "rear") for a in axles) or len(set(axles)) != len(axles):
        raise ParameterError(f"{owner} axles must be distinct names from ('front', 'rear'), got {axles!r}",
                             key="axles", value=axles)
    if corners:
        channels = tuple(f"{a}_{side}" for a in axles for side in ("left", "right"))
        return channels, {kind: [f"{kind}_{c}" for c in channels] for kind in kinds}
    return tuple(axles), {kind: [f"{c}_{kind}" for c in axles] for kind in kinds}


def sigmoid(z):
    """Smooth step 0 -> 1, (1 + tanh z) / 2: the mode switches of the controllers."""
    return 0.5 * (1.0 + np.tanh(z))


def deadband(value, width):
    """value - clip(value, -width, width): zero inside the band, continuous, slope 1 outside."""
    return value - np.minimum(np.maximum(value, -width), width)


class ChassisController(Model):
    """Base of the chassis controllers: a ``Model`` whose outputs command a plant's inputs."""

    def close(self, plant: Model) -> "ClosedLoop":
        """The :class:`ClosedLoop` of ``plant`` with this controller."""
        return ClosedLoop(plant, self)


