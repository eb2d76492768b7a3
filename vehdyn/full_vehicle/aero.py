"""Aerodynamic forces on the sprung body.

With the air-relative velocity V_a = (u, v - v_w) in body axes (v_w the ``wind_velocity_lateral``
input, the wind's velocity over the ground along the vehicle's y axis, SAE: blowing to the right)::

    X = -k_x u |u|,   Y = -k_y (v - v_w) |V_a|,   lift L_f = k_f u^2 at the front axle, L_r = k_r u^2 at the rear

with k_x = rho c_x A / 2, k_y = rho c_y A / 2 (c_y the vehicle's ``aero.lateral_drag_coefficient``,
a cross-flow drag), k_f, k_r = rho c_l A / 2 of each axle (positive lift unloads the axle). Drag and
side force act at the sprung CG (no pitch or yaw moment; a centre of pressure is not in the vehicle
files); the lifts act at the axles. The drag and lift terms are those of
:class:`vehdyn.handling.SingleTrack`.
"""

from __future__ import annotations

__all__ = ["aero_forces"]


def aero_forces(xp, k, u, v, wind):
    """(X, Y, front lift, rear lift) [N] (module docstring)."""
    lateral = v - wind
    speed = xp.sqrt(u * u + lateral * lateral)
    return (-k.drag_factor * u * xp.abs(u), -k.lateral_drag_factor * lateral * speed, k.front_lift_factor * u * u,
            k.rear_lift_factor * u * u)
