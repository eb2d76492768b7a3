"""Planar kinematics: the earth-fixed position rates of a body moving in the road plane.

Shared by every model that integrates its position and heading (the single track, the
articulated single track, the constant-speed lateral models on the fidelity ladder). SAE axes
(J670): earth X along the initial heading, Y to its right; body x forward, y right; heading psi
positive turning right. A body with velocity (u, v) in its own axes moves over the ground at

.. math::

    \\dot X = u \\cos\\psi - v \\sin\\psi,\\qquad \\dot Y = u \\sin\\psi + v \\cos\\psi,\\qquad
    \\dot\\psi = r

Written over an ``xp`` namespace (``xp.cos``, ``xp.sin``; :mod:`vehdyn.components.xp`).

References
----------
.. [1] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, sec. 2.3, eq. 2.43.
.. [2] SAE J670, *Vehicle Dynamics Terminology*, 2008 (axis systems).
"""

from __future__ import annotations

__all__ = ["position_rates", "body_point"]


def position_rates(xp, u, v, yaw):
    """(dX/dt, dY/dt) [m/s] of a point with body-axis velocity (``u``, ``v``) at heading ``yaw``.

    .. math::

        \\dot X = u \\cos\\psi - v \\sin\\psi,\\qquad \\dot Y = u \\sin\\psi + v \\cos\\psi

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    u : float or ndarray
        Forward velocity in body axes [m/s].
    v : float or ndarray
        Lateral velocity in body axes (SAE: right) [m/s].
    yaw : float or ndarray
        Heading psi [rad].

    Returns
    -------
    tuple
        (dX/dt [m/s], dY/dt [m/s]), earth axes (SAE).
    """
    c, s = xp.cos(yaw), xp.sin(yaw)
    return u * c - v * s, u * s + v * c


def body_point(xp, x, y, yaw, forward, right):
    """Earth (X, Y) [m] of the body point (``forward``, ``right``) of a body at (``x``, ``y``, ``yaw``).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    x, y : float or ndarray
        Earth position of the body's reference point [m].
    yaw : float or ndarray
        Heading psi [rad].
    forward : float or ndarray
        The point's body x ahead of the reference point [m].
    right : float or ndarray
        The point's body y (SAE: right) [m].

    Returns
    -------
    tuple
        (X [m], Y [m]).
    """
    c, s = xp.cos(yaw), xp.sin(yaw)
    return x + forward * c - right * s, y + forward * s + right * c
