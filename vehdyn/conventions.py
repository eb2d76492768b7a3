"""Axis systems and sign conventions: the one place where vehdyn flips a sign.

Three axis systems meet in vehicle dynamics:

* **SAE J670 vehicle axes** (used by every vehdyn vehicle model): x forward, y to the right, z down;
  body velocities u, v, w; body rates p, q, r; Euler angles roll phi, pitch theta, yaw psi in the
  order yaw-pitch-roll. A positive steer angle turns the vehicle to the right.
* **ISO 8855 vehicle axes**: x forward, y to the left, z up. A positive steer angle turns left.
* **ISO-W (TYDEX) tire axes**, the convention of ``.tir`` files and of MFeval: x forward in the
  wheel plane, y to the left, z up; slip angle alpha = atan(V_sy / |V_cx|), so that a tire sliding
  to its left (alpha > 0) makes a negative lateral force for a tire with the usual negative
  ``PKY1``; longitudinal slip kappa = -V_sx / V_cx with the signed wheel-centre speed V_cx, so
  kappa > 0 means the wheel drives in its direction of travel, forwards or in reverse (MFeval
  4.3.1 then flips F_x with sign(V_cx), and keeps F_y); camber gamma positive for a rotation
  about +x; normal load F_z a positive compressive magnitude.

Both pairs (SAE/ISO 8855 and SAE-tire/ISO-W) differ by a half turn about the x axis: components
along y and z change sign, components along x do not. So do rotations: a rate or angle about x
keeps its sign, one about y or z changes it. Tire slip angle, turn slip and steer angle, being
rotations about z, change sign; slip ratio and camber keep theirs.

Vehicle models call these functions; nothing else in vehdyn flips a sign between conventions.

References
----------
SAE J670 (2008), *Vehicle Dynamics Terminology*. ISO 8855:2011, *Road vehicles - Vehicle dynamics
and road-holding ability - Vocabulary*. H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed.,
Butterworth-Heinemann, 2012, sec. 1.2 and Fig. 4.21 (TYDEX W-axis system).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = [
    "flip_y_z",
    "iso8855_to_sae",
    "sae_to_iso8855",
    "rotation_iso8855_to_sae",
    "rotation_sae_to_iso8855",
    "steer_angle_sae_to_iso8855",
    "steer_angle_iso8855_to_sae",
    "TireSlips",
    "TireForces",
    "tire_slips_sae_to_iso_w",
    "tire_slips_iso_w_to_sae",
    "tire_forces_iso_w_to_sae",
    "tire_forces_sae_to_iso_w",
    "planar_tire_slips_sae_to_iso_w",
    "planar_tire_forces_iso_w_to_sae",
]


def flip_y_z(x, y, z):
    r"""Components of a vector in the other of two axis systems related by a half turn about x.

    Parameters
    ----------
    x, y, z : array_like
        Components of a force, velocity, position or acceleration [any unit, the same for all
        three].

    Returns
    -------
    tuple of ndarray
        ``(x, -y, -z)`` [the unit of the input]. The map is its own inverse.

    Notes
    -----
    SAE J670 and ISO 8855 vehicle axes (and the SAE and ISO-W tire axes) differ by a half turn
    about x:

    .. math::

        \begin{bmatrix} x' \\ y' \\ z' \end{bmatrix} = R_x(\pi)
        \begin{bmatrix} x \\ y \\ z \end{bmatrix}, \qquad
        R_x(\pi) = \begin{bmatrix} 1 & 0 & 0 \\ 0 & -1 & 0 \\ 0 & 0 & -1 \end{bmatrix}
        = R_x(\pi)^{-1}.

    References
    ----------
    .. [1] SAE J670 (2008), *Vehicle Dynamics Terminology*, sec. 2 (vehicle axis system).
    .. [2] ISO 8855:2011, *Road vehicles - Vehicle dynamics and road-holding ability -
       Vocabulary*, sec. 2 (axis systems).

    Examples
    --------
    >>> from vehdyn.conventions import flip_y_z
    >>> [float(c) for c in flip_y_z(1.0, 2.0, 3.0)]
    [1.0, -2.0, -3.0]
    """
    return np.asarray(x), -np.asarray(y), -np.asarray(z)


def iso8855_to_sae(x, y, z):
    r"""Vector components from ISO 8855 (y left, z up) to SAE J670 (y right, z down).

    Parameters
    ----------
    x, y, z : array_like
        Components in ISO 8855 axes of a force, velocity, position or acceleration [any unit,
        the same for all three].

    Returns
    -------
    tuple of ndarray
        The components in SAE axes, ``(x, -y, -z)`` [the unit of the input]: a half turn about x,
        :math:`R_x(\pi)` (:func:`flip_y_z`).

    References
    ----------
    .. [1] SAE J670 (2008), *Vehicle Dynamics Terminology*.
    .. [2] ISO 8855:2011, *Road vehicles - Vehicle dynamics and road-holding ability - Vocabulary*.
    """
    return flip_y_z(x, y, z)


def sae_to_iso8855(x, y, z):
    r"""Vector components from SAE J670 (y right, z down) to ISO 8855 (y left, z up).

    Parameters
    ----------
    x, y, z : array_like
        Components in SAE axes of a force, velocity, position or acceleration [any unit, the
        same for all three].

    Returns
    -------
    tuple of ndarray
        The components in ISO 8855 axes, ``(x, -y, -z)`` [the unit of the input]: the half turn
        about x is its own inverse (:func:`flip_y_z`).

    References
    ----------
    .. [1] SAE J670 (2008), *Vehicle Dynamics Terminology*.
    .. [2] ISO 8855:2011, *Road vehicles - Vehicle dynamics and road-holding ability - Vocabulary*.
    """
    return flip_y_z(x, y, z)


def rotation_iso8855_to_sae(about_x, about_y, about_z):
    r"""Angles, rates or moments from ISO 8855 to SAE J670: about x kept, about y and z negated.

    Parameters
    ----------
    about_x, about_y, about_z : array_like
        Components about the ISO 8855 axes of an angular rate [rad/s], a moment [N*m] or a small
        rotation angle [rad] (roll, pitch, yaw).

    Returns
    -------
    tuple of ndarray
        The components about the SAE axes, ``(about_x, -about_y, -about_z)`` [the unit of the
        input].

    Notes
    -----
    An axial vector transforms as a vector under a proper rotation (det R = +1), so the half turn
    about x, :math:`R_x(\pi) = \operatorname{diag}(1, -1, -1)`, maps
    :math:`(p, q, r) \mapsto (p, -q, -r)`: roll keeps its sign, pitch and yaw change it.
    """
    return np.asarray(about_x), -np.asarray(about_y), -np.asarray(about_z)


def rotation_sae_to_iso8855(about_x, about_y, about_z):
    """Angles, rates or moments from SAE J670 to ISO 8855 (the inverse map; the same flips).

    Parameters
    ----------
    about_x, about_y, about_z : array_like
        Components about the SAE axes of an angular rate [rad/s], a moment [N*m] or a small
        rotation angle [rad].

    Returns
    -------
    tuple of ndarray
        The components about the ISO 8855 axes, ``(about_x, -about_y, -about_z)`` [the unit of
        the input].
    """
    return rotation_iso8855_to_sae(about_x, about_y, about_z)


def steer_angle_sae_to_iso8855(steer_angle):
    """Steer angle: SAE (positive turns right) to ISO 8855 (positive turns left).

    Parameters
    ----------
    steer_angle : array_like
        Road-wheel steer angle in SAE axes [rad], a rotation about z (down).

    Returns
    -------
    ndarray
        The steer angle in ISO 8855 axes [rad], ``-steer_angle``.
    """
    return -np.asarray(steer_angle)


def steer_angle_iso8855_to_sae(steer_angle):
    """Steer angle: ISO 8855 (positive turns left) to SAE (positive turns right).

    Parameters
    ----------
    steer_angle : array_like
        Road-wheel steer angle in ISO 8855 axes [rad], a rotation about z (up).

    Returns
    -------
    ndarray
        The steer angle in SAE axes [rad], ``-steer_angle``.
    """
    return -np.asarray(steer_angle)


class TireSlips(NamedTuple):
    """Slip quantities of one tire, in one axis system.

    Parameters
    ----------
    kappa : ndarray
        Longitudinal slip ratio [-].
    alpha : ndarray
        Slip angle [rad].
    gamma : ndarray
        Inclination (camber) angle [rad].
    phit : ndarray
        Turn slip [1/m].
    """

    kappa: np.ndarray
    alpha: np.ndarray
    gamma: np.ndarray
    phit: np.ndarray


class TireForces(NamedTuple):
    """Forces and moments on a tire at the contact centre, in one axis system.

    Tire laws return them in ISO-W axes (``fz`` is then the positive normal load they were computed
    for); :func:`tire_forces_iso_w_to_sae` gives the same loads in SAE axes.

    Parameters
    ----------
    fx, fy, fz : ndarray
        Longitudinal, lateral and normal force [N].
    mx, my, mz : ndarray
        Overturning moment, rolling-resistance moment and self-aligning moment [N*m].
    """

    fx: np.ndarray
    fy: np.ndarray
    fz: np.ndarray
    mx: np.ndarray
    my: np.ndarray
    mz: np.ndarray


def tire_slips_sae_to_iso_w(kappa, alpha, gamma=0.0, phit=0.0) -> TireSlips:
    """Tire slips from the SAE tire axis system to ISO-W (the ``.tir`` file's convention).

    Parameters
    ----------
    kappa : array_like
        Longitudinal slip ratio [-]; the same in both systems (positive when driving).
    alpha : array_like
        SAE slip angle [rad], atan(v_y / v_x) with y to the right.
    gamma : array_like, optional
        Inclination (camber) angle [rad], a rotation about x: the same in both systems.
    phit : array_like, optional
        Turn slip [1/m], a curvature about z: negated.

    Returns
    -------
    TireSlips
        ``(kappa, -alpha, gamma, -phit)``.
    """
    return TireSlips(np.asarray(kappa), -np.asarray(alpha), np.asarray(gamma), -np.asarray(phit))


def tire_slips_iso_w_to_sae(kappa, alpha, gamma=0.0, phit=0.0) -> TireSlips:
    """Tire slips from ISO-W to the SAE tire axis system (the same flips as the inverse).

    Parameters
    ----------
    kappa : array_like
        Longitudinal slip ratio [-]; the same in both systems.
    alpha : array_like
        ISO-W slip angle [rad], atan(V_sy / abs(V_cx)) with y to the left.
    gamma : array_like, optional
        Inclination (camber) angle [rad]: the same in both systems.
    phit : array_like, optional
        Turn slip [1/m]: negated.

    Returns
    -------
    TireSlips
        ``(kappa, -alpha, gamma, -phit)`` in SAE tire axes.
    """
    return tire_slips_sae_to_iso_w(kappa, alpha, gamma, phit)


def tire_forces_iso_w_to_sae(fx, fy, fz, mx, my, mz) -> TireForces:
    r"""Tire forces and moments from ISO-W (y left, z up) to SAE (y right, z down).

    F_x and M_x keep their signs; F_y, F_z, M_y and M_z change sign. The ISO-W normal force F_z is
    the positive load; in SAE axes the road pushes the tire up, so the SAE F_z is negative.

    Parameters
    ----------
    fx, fy, fz : array_like
        Longitudinal, lateral and normal force in ISO-W axes [N].
    mx, my, mz : array_like
        Overturning, rolling-resistance and self-aligning moment in ISO-W axes [N*m].

    Returns
    -------
    TireForces
        ``(fx, -fy, -fz, mx, -my, -mz)`` in SAE tire axes [N, N*m].

    Notes
    -----
    Force and moment both transform by the half turn about x,
    :math:`R_x(\pi) = \operatorname{diag}(1, -1, -1)` (Pacejka 2012, sec. 1.2 and Fig. 4.21).

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 1.2 (axis systems) and Fig. 4.21 (the TYDEX W-axis system).
    .. [2] SAE J670 (2008), *Vehicle Dynamics Terminology*.

    Examples
    --------
    A tire carrying 4 kN and pushing 1 kN to its left (ISO-W +y) pushes 1 kN to the vehicle's
    left in SAE axes (-y), and the road's normal force points up (-z):

    >>> from vehdyn.conventions import tire_forces_iso_w_to_sae
    >>> forces = tire_forces_iso_w_to_sae(0.0, 1000.0, 4000.0, 0.0, 0.0, 20.0)
    >>> float(forces.fy), float(forces.fz), float(forces.mz)
    (-1000.0, -4000.0, -20.0)
    """
    fx, fy, fz = flip_y_z(fx, fy, fz)
    mx, my, mz = rotation_iso8855_to_sae(mx, my, mz)
    return TireForces(fx, fy, fz, mx, my, mz)


def tire_forces_sae_to_iso_w(fx, fy, fz, mx, my, mz) -> TireForces:
    """Tire forces and moments from SAE to ISO-W (the inverse of :func:`tire_forces_iso_w_to_sae`).

    Parameters
    ----------
    fx, fy, fz : array_like
        Longitudinal, lateral and normal force in SAE tire axes [N].
    mx, my, mz : array_like
        Overturning, rolling-resistance and self-aligning moment in SAE tire axes [N*m].

    Returns
    -------
    TireForces
        ``(fx, -fy, -fz, mx, -my, -mz)`` in ISO-W axes [N, N*m].
    """
    return tire_forces_iso_w_to_sae(fx, fy, fz, mx, my, mz)


def planar_tire_slips_sae_to_iso_w(kappa, alpha):
    """Slip ratio and slip angle from SAE to ISO-W: ``(kappa, -alpha)``.

    The planar part of :func:`tire_slips_sae_to_iso_w` in plain arithmetic (no numpy call), so that
    it works on floats, on arrays and inside numba-compiled code alike.

    Parameters
    ----------
    kappa : float or array_like
        Longitudinal slip ratio [-].
    alpha : float or array_like
        SAE slip angle [rad].

    Returns
    -------
    tuple
        ``(kappa, -alpha)``: slip ratio [-] and ISO-W slip angle [rad].
    """
    return kappa, -alpha


def planar_tire_forces_iso_w_to_sae(fx, fy):
    """Longitudinal and lateral tire force from ISO-W to SAE: ``(fx, -fy)``.

    The planar part of :func:`tire_forces_iso_w_to_sae` in plain arithmetic (floats, arrays and
    numba-compiled code).

    Parameters
    ----------
    fx, fy : float or array_like
        Longitudinal and lateral tire force in ISO-W axes [N].

    Returns
    -------
    tuple
        ``(fx, -fy)``: the forces in SAE tire axes [N].
    """
    return fx, -fy
