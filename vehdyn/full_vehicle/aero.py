"""Aerodynamic forces on the sprung body: drag, lift and the crosswind's side force.

Drag and lift (those of :class:`vehdyn.handling.SingleTrack`), with u the forward velocity::

    X = -k_x u |u|,   lift L_f = k_f u^2 at the front axle, L_r = k_r u^2 at the rear

k_x = rho c_x A / 2, k_f, k_r = rho c_l A / 2 of each axle (positive lift unloads the axle); the
drag acts at the sprung CG.

Crosswind: the side force of the handling models, the same function
(:func:`vehdyn.handling.crosswind.aero_side_force`)::

    Y = k_w (u^2 + w^2) atan(w / |u|),   k_w = rho A C_Y' / 2

with w the ``wind_velocity_lateral`` input (the air's velocity along the vehicle's y axis, SAE:
blowing toward the right) and C_Y' the vehicle's ``aero.side_force_coefficient_slope``. It acts at
the centre of pressure, ``aero.centre_of_pressure_from_front_axle`` times the wheelbase behind the
front axle, at the height of the sprung CG (the vehicle files give no height of the centre of
pressure), so it yaws the body by x_p Y about the sprung CG (x_p the centre of pressure ahead of the
sprung CG) and rolls it about its roll axis. As in the handling models, the aerodynamic sideslip of
the vehicle's own lateral velocity and yaw rate is neglected (Hucho, *Aerodynamics of Road
Vehicles*, 4th ed., 1998, sec. 4.4; :mod:`vehdyn.handling.crosswind`).
"""

from __future__ import annotations

from vehdyn.components.aero import aero_side_force

__all__ = ["aero_forces"]


def aero_forces(xp, k, u, wind):
    """The aerodynamic forces on the sprung body (module docstring).

    Parameters
    ----------
    xp : namespace
        The equations' namespace (:mod:`vehdyn.components.xp`).
    k : Constants
        The model's constants (:class:`vehdyn.full_vehicle.assembly.Constants`).
    u : float or ndarray
        Forward velocity of the sprung CG [m/s].
    wind : float or ndarray
        Lateral wind velocity [m/s] (toward +y).

    Returns
    -------
    tuple
        (X [N], Y [N], yaw moment about the sprung CG [N*m], front lift [N], rear lift [N]).
    """
    side = aero_side_force(xp, k.wind_side_force_factor, u, wind)
    return (-k.drag_factor * u * xp.abs(u), side, k.centre_of_pressure * side, k.front_lift_factor * u * u,
            k.rear_lift_factor * u * u)
