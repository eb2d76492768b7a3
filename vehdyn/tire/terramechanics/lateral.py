"""Side force of a wheel on soft soil at a slip angle: side shear plus sidewall bulldozing.

After Ishigami, Miwa, Nagatani and Yoshida (2007): a soil element under the wheel is displaced
sideways, while it is in contact, by the lateral slip of the wheel. It entered the contact at the
angle theta_1 (rigid wheel) or at the leading edge x = 0 (flat contact of a flexible tire); since
then the wheel centre has travelled ``r (theta_1 - theta) f(s)`` or ``x f(s)``, with
``f(s) = V / (r omega)`` (:func:`~vehdyn.tire.terramechanics.wong_reece.travel_ratio`), so that::

    j_y = r (theta_1 - theta) f(s) |tan alpha|          (rigid wheel, on the arc)
    j_y = x f(s) |tan alpha|                            (flat contact)
    tau_y = (c + sigma tan phi) (1 - exp(-j_y / K_y))    (Janosi-Hanamoto with the lateral modulus K_y)

The side shear is ``r b int tau_y d theta`` on the arc, and on a flat contact of length l with the
uniform pressure W / (b l): ``(A c + W tan phi) [1 - K_y / L (1 - exp(-L / K_y))]`` with
``L = l f(s) |tan alpha|``. The sidewall pushes the soil beside the rut: Ishigami et al. use
Hegedus' bulldozing formula; here it is the Rankine passive earth pressure on the wetted side
(:func:`~vehdyn.tire.terramechanics.bekker.rankine_wall_force`, per unit length of wall at the local
depth ``h``), integrated along the contact and scaled by ``|sin alpha|``, the share of the wheel's
motion normal to its side: ``|sin alpha| int F_wall(h(x)) dx``. The longitudinal and lateral shears
are computed independently (as Ishigami et al. do). The side force is
``F_y = -sgn(alpha) (side shear + bulldozing)`` (ISO-W: a positive slip angle pushes to -y).

References
----------
G. Ishigami, A. Miwa, K. Nagatani and K. Yoshida, "Terramechanics-based model for steering
maneuver of planetary exploration rovers on loose soil", J. Field Robotics 24(3), 233-250, 2007.
J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.2 (passive earth pressure).
"""

from __future__ import annotations

import numpy as np

from vehdyn.tire.terramechanics.bekker import bulldozing_resistance, rankine_wall_force
from vehdyn.tire.terramechanics.soil import Soil

__all__ = ["arc_side_force", "flat_side_force", "mobilized_fraction"]

#: Cap on f(s) = V / (r omega) (infinite for a locked wheel: the shear is then fully mobilized).
_MAX_TRAVEL = 1e12


def mobilized_fraction(length_over_k):
    """The mean of ``1 - exp(-j/K)`` over a uniform contact with ``j`` growing linearly to ``x K``.

    Parameters
    ----------
    length_over_k : array_like
        x = (shear displacement at the trailing edge) / K [-].

    Returns
    -------
    ndarray
        ``1 - (1 - exp(-x)) / x`` [-] (Janosi-Hanamoto integrated; x/2 near 0).
    """
    x = np.asarray(length_over_k, dtype=float)
    small = x < 1e-6
    safe = np.where(small, 1.0, x)
    return np.where(small, 0.5 * x, 1.0 + np.expm1(-safe) / safe)


def arc_side_force(soil: Soil, radius: float, width: float, theta, weight, strength, cos_theta, theta1, travel,
                   tan_alpha):
    """Side force [N] (ISO-W) of a rigid wheel from its contact-arc quadrature.

    Parameters
    ----------
    soil : Soil
        The soil.
    radius : float
        Wheel radius r [m].
    width : float
        Wheel width b [m].
    theta, weight : ndarray (n_points, n_nodes)
        Quadrature nodes [rad] and weights on the arc.
    strength : ndarray (n_points, n_nodes)
        ``c + sigma tan phi`` [Pa] at the nodes.
    cos_theta : ndarray (n_points, n_nodes)
        cos(theta) [-].
    theta1 : ndarray (n_points, 1)
        Entry angle [rad].
    travel : ndarray (n_points, 1)
        ``V / (r omega)`` [-].
    tan_alpha : ndarray (n_points,)
        tan of the slip angle [-].

    Returns
    -------
    ndarray (n_points,)
        F_y [N], ISO-W: ``-sgn(alpha) (side shear + |sin alpha| int F_wall(h) dx)``.

    References
    ----------
    .. [1] G. Ishigami, A. Miwa, K. Nagatani and K. Yoshida, "Terramechanics-based model for
       steering maneuver of planetary exploration rovers on loose soil", J. Field Robotics 24(3),
       233-250, 2007.
    """
    abs_tan = np.abs(tan_alpha)[:, None]
    jy = radius * (theta1 - theta) * np.minimum(travel, _MAX_TRAVEL) * abs_tan
    shear = radius * width * np.sum(weight * strength * -np.expm1(-jy / soil.side_shear_modulus), axis=1)
    depth = np.maximum(cos_theta - np.cos(theta1), 0.0) * radius  # true depth under the sidewall point
    sin_alpha = abs_tan[:, 0] / np.sqrt(1.0 + abs_tan[:, 0] ** 2)
    bulldozing = sin_alpha * radius * np.sum(weight * rankine_wall_force(soil, depth) * cos_theta, axis=1)
    return -np.sign(tan_alpha) * (shear + bulldozing)


def flat_side_force(soil: Soil, width: float, load, length, sinkage, travel, slip_angle):
    """Side force (ISO-W) of a flat contact carrying a load at a uniform pressure, in a rut.

    Parameters
    ----------
    soil : Soil
        The soil.
    width : float
        Contact width b [m].
    load : array_like
        Normal load W [N].
    length : array_like
        Contact length l [m].
    sinkage : array_like
        Rut depth z [m].
    travel : array_like
        ``V / (r omega)`` [-] (:func:`~vehdyn.tire.terramechanics.wong_reece.travel_ratio`).
    slip_angle : array_like
        alpha [rad].

    Returns
    -------
    ndarray
        F_y [N]: ``-sgn(alpha) [(A c + W tan phi) (1 - K_y / L (1 - exp(-L / K_y)))
        + |sin alpha| R_b]``, L = l f(s) |tan alpha|, R_b the bulldozing resistance of the rut
        wall over the contact length.

    References
    ----------
    .. [1] G. Ishigami, A. Miwa, K. Nagatani and K. Yoshida, "Terramechanics-based model for
       steering maneuver of planetary exploration rovers on loose soil", J. Field Robotics 24(3),
       233-250, 2007.
    """
    tan_alpha = np.tan(slip_angle)
    limit = width * length * soil.cohesion + load * np.tan(soil.friction_angle)  # A c + W tan(phi)
    reach = length * np.minimum(travel, _MAX_TRAVEL) * np.abs(tan_alpha)
    shear = limit * mobilized_fraction(reach / soil.side_shear_modulus)
    wall = np.where(length > 0, bulldozing_resistance(soil, sinkage, np.maximum(length, 1e-300)), 0.0)
    return -np.sign(tan_alpha) * (shear + np.abs(np.sin(slip_angle)) * wall)
