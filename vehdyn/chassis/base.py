"""What the chassis controllers share: checks of their gains and vehicle, their channels' signal
names, the smooth switches of their laws, and :class:`ChassisController`, their base class
(a :class:`vehdyn.interconnect.Controller`: ``close(plant)`` wraps a plant in a
:class:`vehdyn.interconnect.ClosedLoop`)."""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.interconnect import Controller
from vehdyn.params.checks import check_gains, check_vehicle

__all__ = ["ChassisController", "check_gains", "check_vehicle", "channel_signals", "sigmoid", "deadband"]


def channel_signals(owner: str, axles, corners: bool, kinds):
    """The channels of a controller and their signal names, in the single track's or the full vehicle's naming.

    One channel per axle named ``<axle>_<kind>`` (SingleTrack: ``front_brake_torque``), or with
    ``corners`` one per wheel named ``<kind>_<axle>_<side>`` (FullVehicle: ``brake_torque_front_left``).

    Parameters
    ----------
    owner : str
        The controller's name, for the error message.
    axles : sequence of str
        Distinct names from ``("front", "rear")``.
    corners : bool
        One channel per wheel instead of per axle.
    kinds : sequence of str
        The signal kinds (``"brake_torque"``, ``"wheel_speed"``, ...).

    Returns
    -------
    channels : tuple of str
        ``("front", "rear")`` or ``("front_left", "front_right", ...)``.
    names : dict
        ``{kind: [signal name per channel]}``.
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
    r"""Smooth step from 0 to 1, :math:`\sigma(z) = (1 + \tanh z) / 2`: the mode switches of the controllers.

    Parameters
    ----------
    z : float or ndarray
        The switch's argument [-].

    Returns
    -------
    float or ndarray
        sigma(z) [-] in (0, 1).
    """
    return 0.5 * (1.0 + np.tanh(z))


def deadband(value, width):
    r"""The deadband :math:`\mathrm{db}(e, d) = e - \mathrm{clip}(e, -d, d)`: zero inside, continuous, slope 1 outside.

    Parameters
    ----------
    value : float or ndarray
        e, in any unit [-].
    width : float or ndarray
        d >= 0, in the unit of ``value`` [-].

    Returns
    -------
    float or ndarray
        db(e, d), in the unit of ``value``.
    """
    return value - np.minimum(np.maximum(value, -width), width)


class ChassisController(Controller):
    r"""Base of the chassis controllers: a :class:`~vehdyn.interconnect.Controller` built from a vehicle.

    Its channels (one per axle, or per wheel with ``corners``) read demands and feedback of the
    plant by name and command its brake or drive torques (or axle forces),

    .. math::

        \dot x_c = f_c(t, x_c, u_c), \qquad u_{p,commanded} = h_c(t, x_c, u_c),

    with smooth mode switches (:func:`sigmoid`, :func:`deadband`) so that the closed loop is an
    ODE. :class:`~vehdyn.chassis.ABS`, :class:`~vehdyn.chassis.TractionControl` and
    :class:`~vehdyn.chassis.ESC` derive from it.

    References
    ----------
    .. [1] Robert Bosch GmbH, *Automotive Handbook*, 10th ed., 2018, "Driving-safety systems"
       (ABS, TCS, ESC).
    .. [2] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, ch. 6 and 8.
    """


