"""Bekker's closed forms: plate pressure-sinkage, static sinkage and resistances of a rigid wheel.

With ``k = k_c / b + k_phi`` (Bekker 1969; Wong 2008, sec. 2.2 and 2.5):

* pressure-sinkage of a plate of width b: ``p = k z^n``;
* static sinkage of a towed rigid wheel of diameter D and width b under the load W::

      z0 = [3 W / ((3 - n) (k_c + b k_phi) sqrt(D))]^(2 / (2n + 1))

* compaction resistance (the work of making a rut of depth z0 per unit length)::

      R_c = b k z0^(n+1) / (n + 1)

* bulldozing resistance of a vertical wall of width b pushed to the depth z, from the Rankine
  passive earth pressure (Wong 2008, sec. 2.2), ``N_phi = tan^2(45 deg + phi/2)``::

      R_b = b (gamma z^2 N_phi / 2 + 2 c z sqrt(N_phi))

Limits of the closed forms: the contact arc is replaced by a parabola, which needs z0 / D small
(a few per cent); the normal stress is the plate pressure at the local sinkage with its maximum at
the bottom of the wheel (no slip, no shear); the factor (3 - n) / 3 is Bekker's series
approximation of ``B(n + 1, 1/2) / 2`` (:func:`parabolic_wheel_sinkage` keeps the exact Beta
function), exact for n = 0 and n = 1; its error in sinkage is -6 % at n = 0.5, +1.5 % at n = 1.1,
+5 % at n = 1.3 and +11 % at n = 1.6. The Rankine
wall is a simplification of Bekker's bulldozing formula (which uses Terzaghi's bearing-capacity
factors); it assumes a smooth vertical wall and a horizontal soil surface.

References
----------
M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press, 1969.
J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, ch. 2.
"""

from __future__ import annotations

import math

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.units import GRAVITY
from vehdyn.tire.terramechanics.soil import Soil

__all__ = ["bekker_pressure", "plate_sinkage", "rigid_wheel_sinkage", "parabolic_wheel_sinkage",
           "compaction_resistance", "bulldozing_resistance", "rankine_wall_force", "checked_array"]



def checked_array(name: str, value, *, ge: float | None = None, gt: float | None = None):
    """A value as a float array (0-d for scalars), checked finite and against a bound once.

    Parameters
    ----------
    name : str
        The parameter's name, for the error.
    value : array_like
        The value [any unit].
    ge, gt : float, optional
        Lower bound, inclusive or strict [the value's unit].

    Returns
    -------
    ndarray
        ``value`` as floats.

    Raises
    ------
    ParameterError
        Naming ``name`` and the first bad value.
    """
    raw = np.asarray(value)
    if raw.dtype.kind not in "iuf":  # a string, a bool, None or an object is not read as a number
        raise ParameterError(f"{name} must be a number or an array of numbers, got {type(value).__name__} "
                             f"{value!r:.80}", key=name, value=value)
    a = np.asarray(raw, dtype=float)
    ok = np.isfinite(a)
    if ge is not None:
        ok &= a >= ge
    if gt is not None:
        ok &= a > gt
    if not np.all(ok):
        bad = float(a[~ok].flat[0]) if a.ndim else float(a)
        bound = f" >= {ge}" if ge is not None else (f" > {gt}" if gt is not None else "")
        raise ParameterError(f"{name} must be finite{' and' + bound if bound else ''}, got {bad!r}", key=name,
                             value=bad)
    return a


def _out(a):
    return float(a) if np.ndim(a) == 0 else a


def bekker_pressure(soil: Soil, sinkage, width):
    r"""Bekker's pressure-sinkage law of a plate.

    .. math::

        p = \left(\frac{k_c}{b} + k_\phi\right) z^n

    Parameters
    ----------
    soil : Soil
        The soil (Bekker and Mohr-Coulomb parameters).
    sinkage : array_like
        z [m], >= 0.
    width : array_like
        b [m]: the smaller dimension of the plate (the wheel width), > 0.

    Returns
    -------
    float or ndarray
        Pressure p [Pa].

    References
    ----------
    .. [1] M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press,
       1969.
    .. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.2.

    Examples
    --------
    >>> from vehdyn.tire.terramechanics import bekker_pressure, load_soil, plate_sinkage
    >>> sand = load_soil("dry_sand")
    >>> p = bekker_pressure(sand, sinkage=0.02, width=0.2)              # [Pa]
    >>> round(p), round(plate_sinkage(sand, p, 0.2), 12)                # and back [m]
    (20739, 0.02)
    """
    z = checked_array("sinkage", sinkage, ge=0.0)
    return _out(soil.modulus(width) * z**soil.n)


def plate_sinkage(soil: Soil, pressure, width):
    """Sinkage of a plate under a pressure: the inverse of :func:`bekker_pressure`.

    Parameters
    ----------
    soil : Soil
        The soil (Bekker and Mohr-Coulomb parameters).
    pressure : array_like
        p [Pa], >= 0.
    width : array_like
        b [m], > 0.

    Returns
    -------
    float or ndarray
        z = (p / k)^(1/n) [m], k = k_c / b + k_phi.
    """
    p = checked_array("pressure", pressure, ge=0.0)
    return _out((p / soil.modulus(width)) ** (1.0 / soil.n))


def rigid_wheel_sinkage(soil: Soil, load, diameter, width):
    r"""Bekker's static sinkage of a towed rigid wheel (valid for z0/D small).

    .. math::

        z_0 = \left[\frac{3 W}{(3 - n)(k_c + b k_\phi) \sqrt D}\right]^{2 / (2n + 1)}

    Parameters
    ----------
    soil : Soil
        The soil (Bekker and Mohr-Coulomb parameters).
    load : array_like
        Normal load W [N], >= 0.
    diameter : array_like
        D [m], > 0.
    width : array_like
        b [m], > 0.

    Returns
    -------
    float or ndarray
        z0 [m].

    Raises
    ------
    ParameterError
        For n >= 3, or a bad load, diameter or width.

    References
    ----------
    .. [1] M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press,
       1969.
    .. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.5.
    """
    w = checked_array("load", load, ge=0.0)
    d = checked_array("diameter", diameter, gt=0.0)
    b = np.asarray(width, dtype=float)
    n = soil.n
    if n >= 3.0:
        raise ParameterError(f"Bekker's wheel sinkage needs n < 3, got n={n!r}", key="n", value=n)
    kb = soil.modulus(b) * b  # k_c + b k_phi
    return _out((3.0 * w / ((3.0 - n) * kb * np.sqrt(d))) ** (2.0 / (2.0 * n + 1.0)))


def parabolic_wheel_sinkage(soil: Soil, load, diameter, width):
    r"""Static sinkage of a rigid wheel with the arc taken as a parabola, integrated exactly.

    .. math::

        W = b k \sqrt D \, z_0^{n + 1/2} \, \frac{B(n + 1, 1/2)}{2}

    solved for z0 (B the Beta function); Bekker's :func:`rigid_wheel_sinkage` replaces
    B(n + 1, 1/2) / 2 by (3 - n) / 3. Same limits otherwise (z0/D small).

    Parameters
    ----------
    soil : Soil
        The soil (Bekker and Mohr-Coulomb parameters).
    load : array_like
        Normal load W [N], >= 0.
    diameter : array_like
        D [m], > 0.
    width : array_like
        b [m], > 0.

    Returns
    -------
    float or ndarray
        z0 [m].

    References
    ----------
    .. [1] M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press,
       1969.
    .. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.5.
    """
    w = checked_array("load", load, ge=0.0)
    d = checked_array("diameter", diameter, gt=0.0)
    n = soil.n
    beta = math.exp(math.lgamma(n + 1.0) + math.lgamma(0.5) - math.lgamma(n + 1.5))
    kb = soil.modulus(width) * np.asarray(width, dtype=float)
    return _out((2.0 * w / (kb * np.sqrt(d) * beta)) ** (1.0 / (n + 0.5)))


def compaction_resistance(soil: Soil, load, diameter, width):
    r"""Bekker's compaction resistance of a towed rigid wheel (valid for z0/D small).

    .. math::

        R_c = \frac{b k z_0^{n+1}}{n + 1}

    the work of making a rut of depth z0 (:func:`rigid_wheel_sinkage`) per unit length.

    Parameters
    ----------
    soil : Soil
        The soil (Bekker and Mohr-Coulomb parameters).
    load : array_like
        Normal load W [N], >= 0.
    diameter : array_like
        D [m], > 0.
    width : array_like
        b [m], > 0.

    Returns
    -------
    float or ndarray
        R_c [N].

    References
    ----------
    .. [1] M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press,
       1969.
    .. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.5.
    """
    z0 = np.asarray(rigid_wheel_sinkage(soil, load, diameter, width))
    b = np.asarray(width, dtype=float)
    return _out(b * soil.modulus(b) * z0 ** (soil.n + 1.0) / (soil.n + 1.0))


def rankine_wall_force(soil: Soil, depth):
    r"""Rankine passive force per unit width on a smooth vertical wall (no checks).

    .. math::

        F = \frac{\gamma_s z^2 N_\phi}{2} + 2 c z \sqrt{N_\phi}, \qquad
        N_\phi = \tan^2\left(45^\circ + \frac{\phi}{2}\right), \quad \gamma_s = \rho g

    Parameters
    ----------
    soil : Soil
        The soil (Bekker and Mohr-Coulomb parameters).
    depth : float or ndarray
        Depth z of the wall [m].

    Returns
    -------
    float or ndarray
        F [N/m].

    References
    ----------
    .. [1] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.2 (passive
       earth pressure).
    """
    n_phi = math.tan(math.pi / 4 + soil.friction_angle / 2) ** 2
    gamma = soil.density * GRAVITY
    return depth * (0.5 * gamma * n_phi * depth + 2.0 * soil.cohesion * math.sqrt(n_phi))


def bulldozing_resistance(soil: Soil, sinkage, width):
    """Bulldozing resistance of a vertical wall: ``b`` times :func:`rankine_wall_force`.

    Parameters
    ----------
    soil : Soil
        The soil (Bekker and Mohr-Coulomb parameters).
    sinkage : array_like
        Depth z [m], >= 0.
    width : array_like
        Wall width b [m], > 0.

    Returns
    -------
    float or ndarray
        R_b = b (gamma z^2 N_phi / 2 + 2 c z sqrt(N_phi)) [N].

    References
    ----------
    .. [1] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.2.
    """
    z = checked_array("sinkage", sinkage, ge=0.0)
    b = checked_array("width", width, gt=0.0)
    return _out(b * rankine_wall_force(soil, z))
