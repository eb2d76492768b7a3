"""Unit conversions for the edges of vehdyn (inside, everything is SI and radians).

Names say the unit: ``kmh_to_ms(100.0)``, ``rad_to_deg(x)``, ``per_g(ay)``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["GRAVITY", "kmh_to_ms", "ms_to_kmh", "deg_to_rad", "rad_to_deg", "in_g", "per_g_to_per_ms2"]

#: Gravitational acceleration [m/s^2] used by vehdyn's models unless a model is given another.
#: 9.81 is the value of the shipped vehicle data (CommonRoad) and of the reference cases;
#: standard gravity is 9.80665.
GRAVITY = 9.81


def kmh_to_ms(speed_kmh):
    """Speed from km/h to m/s."""
    return np.asarray(speed_kmh, dtype=float) / 3.6


def ms_to_kmh(speed_ms):
    """Speed from m/s to km/h."""
    return np.asarray(speed_ms, dtype=float) * 3.6


def deg_to_rad(angle_deg):
    """Angle from degrees to radians."""
    return np.deg2rad(angle_deg)


def rad_to_deg(angle_rad):
    """Angle from radians to degrees."""
    return np.rad2deg(angle_rad)


def in_g(acceleration, gravity: float = GRAVITY):
    """Acceleration [m/s^2] expressed in units of g."""
    return np.asarray(acceleration, dtype=float) / gravity


def per_g_to_per_ms2(value_per_g, gravity: float = GRAVITY):
    """A gradient per g (e.g. deg/g) to the same gradient per m/s^2."""
    return np.asarray(value_per_g, dtype=float) / gravity
