"""Unit conversions for the edges of vehdyn (inside, everything is SI and radians).

Names say the unit: ``kmh_to_ms(100.0)``, ``rad_to_deg(x)``, ``in_g(ay)``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["GRAVITY", "kmh_to_ms", "ms_to_kmh", "deg_to_rad", "rad_to_deg", "in_g", "per_g_to_per_ms2"]

#: Gravitational acceleration [m/s^2] used by vehdyn's models unless a model is given another.
#: 9.81 is the value of the shipped vehicle data (CommonRoad) and of the reference cases;
#: standard gravity is 9.80665.
GRAVITY = 9.81


def kmh_to_ms(speed_kmh):
    """Speed from km/h to m/s.

    Parameters
    ----------
    speed_kmh : float or array_like
        Speed [km/h].

    Returns
    -------
    ndarray
        Speed [m/s], ``speed_kmh / 3.6``.

    Examples
    --------
    >>> from vehdyn.units import kmh_to_ms
    >>> float(kmh_to_ms(90.0))
    25.0
    """
    return np.asarray(speed_kmh, dtype=float) / 3.6


def ms_to_kmh(speed_ms):
    """Speed from m/s to km/h.

    Parameters
    ----------
    speed_ms : float or array_like
        Speed [m/s].

    Returns
    -------
    ndarray
        Speed [km/h], ``3.6 speed_ms``.
    """
    return np.asarray(speed_ms, dtype=float) * 3.6


def deg_to_rad(angle_deg):
    """Angle from degrees to radians.

    Parameters
    ----------
    angle_deg : float or array_like
        Angle [deg].

    Returns
    -------
    ndarray
        Angle [rad].
    """
    return np.deg2rad(angle_deg)


def rad_to_deg(angle_rad):
    """Angle from radians to degrees.

    Parameters
    ----------
    angle_rad : float or array_like
        Angle [rad].

    Returns
    -------
    ndarray
        Angle [deg].
    """
    return np.rad2deg(angle_rad)


def in_g(acceleration, gravity: float = GRAVITY):
    """Acceleration expressed in units of g.

    Parameters
    ----------
    acceleration : float or array_like
        Acceleration [m/s^2].
    gravity : float
        The value of g [m/s^2] (:data:`GRAVITY` by default).

    Returns
    -------
    ndarray
        ``acceleration / gravity`` [g].

    Examples
    --------
    >>> from vehdyn.units import in_g
    >>> float(in_g(4.905))
    0.5
    """
    return np.asarray(acceleration, dtype=float) / gravity


def per_g_to_per_ms2(value_per_g, gravity: float = GRAVITY):
    """A gradient per g (e.g. an understeer gradient in deg/g) to the same gradient per m/s^2.

    Parameters
    ----------
    value_per_g : float or array_like
        Gradient per g [any unit per g].
    gravity : float
        The value of g [m/s^2] (:data:`GRAVITY` by default).

    Returns
    -------
    ndarray
        ``value_per_g / gravity`` [the same unit per m/s^2].
    """
    return np.asarray(value_per_g, dtype=float) / gravity
