"""The sprung body: Newton-Euler about its CG (through :mod:`vehdyn.mechanics`) with the unsprung
masses riding along in the body's x-y plane.

Each unsprung mass is a point at its wheel centre W_i (body axes, from the sprung CG) that moves
with the body in the body's x and y directions and freely along the body's z axis (its own
vertical degree of freedom, :mod:`~vehdyn.full_vehicle.corner`). Its x-y inertia therefore loads
the body: with alpha = (a, omega') the absolute acceleration of the sprung CG and the angular
acceleration (body axes), the x-y part of the wheel-centre acceleration is

    H a_i = H (a + omega' x W_i + omega x (omega x W_i) + 2 omega x (0, 0, s_i')),   H = diag(1, 1, 0)

(s_i' the wheel's rate of travel along body z, the Coriolis term), and the body equations

    m_s a + sum m_i G_i a_i = F,     J omega' + omega x J omega + sum W_i x (m_i G_i a_i) = M

with G_i = H + kappa_i e_z e_y^T: besides its x-y inertia, the unsprung mass's lateral force passes
a vertical linkage force kappa_i (per unit of it) to the body (and the opposite to the wheel), the
part of its moment about the roll centre that the linkage does not pass
(:func:`vehdyn.full_vehicle.corner.unsprung_jacking`; kappa_i = 0: none). The equations
are linear in alpha. Split into the part proportional to alpha (an added-mass matrix M_a, constant
in body axes) and the rest, they read (M_s + M_a) alpha = M_s alpha_0, where alpha_0 is what
:func:`vehdyn.mechanics.equations_of_motion.accelerations` returns for the sprung body alone under F and M
plus the wheels' velocity-dependent x-y forces. So the body is advanced by the mechanics layer's
Newton-Euler equations, followed by the constant projection P = (M_s + M_a)^-1 M_s
(:func:`added_mass_projection`). The total mass then acts in the body's x and y directions, the
sprung mass alone in z; roll, pitch and yaw see the sprung inertia tensor J (with I_xz) plus the
wheels' m_i (y_i^2 + z_i^2), m_i (x_i^2 + z_i^2) ... of their x-y motion.

References: Landau & Lifshitz, *Mechanics*, sec. 36 (Euler's equations, used through
:mod:`vehdyn.mechanics.equations_of_motion`); Kane & Levinson, *Dynamics: Theory and Applications*, 1985,
ch. 6 (generalized forces of points constrained to a body).
"""

from __future__ import annotations

import numpy as np

from vehdyn.mechanics.equations_of_motion import rigid_body_accelerations
from vehdyn.mechanics.kinematics import cross_components as cross

__all__ = ["added_mass_projection", "body_accelerations"]


def added_mass_projection(sprung_mass, inertia, masses, points, jacking=None) -> np.ndarray:
    """P = (M_s + M_a)^-1 M_s (6 x 6) of the module docstring.

    With ``jacking`` the lateral inertia force -m_i (H a_i)_y of each unsprung mass also passes a
    vertical linkage force kappa_i (-m_i (H a_i)_y) (body z) to the body at the wheel
    (:func:`vehdyn.full_vehicle.corner.unsprung_jacking`): its acceleration-proportional part is
    a z column of M_a.

    Parameters
    ----------
    sprung_mass : float
        m_s [kg].
    inertia : ndarray, shape (3, 3)
        Sprung inertia matrix J about the sprung CG, body axes [kg*m^2].
    masses : sequence of float
        Unsprung mass of each corner [kg].
    points : sequence of (x, y, z)
        Wheel centres from the sprung CG, body axes [m].
    jacking : sequence of float, optional
        kappa_i of each corner [-] (None: zeros, the unsprung masses' lateral force passes no
        vertical force).

    Returns
    -------
    ndarray
        P, shape (6, 6) [-].
    """
    body = np.zeros((6, 6))
    body[:3, :3] = sprung_mass * np.eye(3)
    body[3:, 3:] = inertia
    added = np.zeros((6, 6))
    jacking = (0.0,) * len(masses) if jacking is None else jacking
    for mass, (x, y, z), kappa in zip(masses, points, jacking):
        for j in range(6):
            e = np.eye(6)[j]
            acc = np.array(e[:3]) + np.array(cross(*e[3:], x, y, z))
            force = -mass * np.array([acc[0], acc[1], kappa * acc[1]])
            added[:, j] -= np.concatenate([force, cross(x, y, z, *force)])
    return np.linalg.solve(body + added, body)


def _dot6(row, a):
    """sum_j row[j] a[j] over six entries (plain arithmetic)."""
    return row[0] * a[0] + row[1] * a[1] + row[2] * a[2] + row[3] * a[3] + row[4] * a[4] + row[5] * a[5]


def body_accelerations(xp, k, velocity, rates, force, moment):
    """Body-axis velocity rates and angular accelerations of the sprung body with the wheels' x-y inertia.

    The sprung body goes through :func:`~vehdyn.mechanics.equations_of_motion.rigid_body_accelerations`
    (the mechanics layer's Newton-Euler) and the result through the projection ``k.projection``.

    Parameters
    ----------
    xp : namespace
        The equations' namespace (:mod:`vehdyn.components.xp`).
    k : Constants
        The model's constants (:class:`vehdyn.full_vehicle.assembly.Constants`).
    velocity : tuple
        (u, v, w) [m/s].
    rates : tuple
        (p, q, r) [rad/s].
    force : tuple
        Body-axis force at the sprung CG [N]: everything but the wheels' x-y inertia proportional
        to the accelerations (module docstring).
    moment : tuple
        Moment about the sprung CG [N*m].

    Returns
    -------
    tuple
        ((du, dv, dw) [m/s^2], (dp, dq, dr) [rad/s^2], the sprung CG's absolute acceleration [m/s^2]).
    """
    u, v, w = velocity
    p, q, r = rates
    velocity_rate, angular = rigid_body_accelerations(k.sprung_mass, k.inertia, k.inverse_inertia, velocity, rates,
                                                      force, moment)
    # absolute acceleration of the sprung CG: dV/dt + omega x V
    cx, cy, cz = cross(p, q, r, u, v, w)
    alpha0 = (velocity_rate[0] + cx, velocity_rate[1] + cy, velocity_rate[2] + cz, angular[0], angular[1],
              angular[2])
    P = k.projection
    alpha = (_dot6(P[0], alpha0), _dot6(P[1], alpha0), _dot6(P[2], alpha0), _dot6(P[3], alpha0), _dot6(P[4], alpha0),
             _dot6(P[5], alpha0))
    return (alpha[0] - cx, alpha[1] - cy, alpha[2] - cz), (alpha[3], alpha[4], alpha[5]), (alpha[0], alpha[1], alpha[2])
