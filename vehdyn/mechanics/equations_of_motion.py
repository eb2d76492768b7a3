"""Newton-Euler equations of a rigid body in body axes (SAE vehicle axes).

With the body axes x forward, y right, z down fixed to the body at its centre of mass, body
velocities V = (u, v, w), body rates omega = (p, q, r), applied force F = (X, Y, Z) and moment
about the centre of mass M = (L, M, N), all in body axes, Newton's and Euler's laws read

    F = m (dV/dt + omega x V),              M = I domega/dt + omega x (I omega),

(Landau & Lifshitz, *Mechanics*, 3rd ed., 1976, sec. 36 for Euler's equations; B. Etkin, *Dynamics
of Atmospheric Flight*, Wiley, 1972, ch. 4, for the same equations in flight/vehicle body axes,
cited from memory).
Written out with all products of inertia (Ixy = integral x y dm etc., so the tensor's off-diagonal
entries are -Ixy, -Ixz, -Iyz; see :mod:`vehdyn.mechanics.inertia`)::

    X = m (du/dt + q w - r v)
    Y = m (dv/dt + r u - p w)
    Z = m (dw/dt + p v - q u)
    L = Ixx dp/dt - Ixy (dq/dt - p r) - Ixz (dr/dt + p q) - Iyz (q^2 - r^2) + (Izz - Iyy) q r
    M = Iyy dq/dt - Iyz (dr/dt - p q) - Ixy (dp/dt + q r) - Ixz (r^2 - p^2) + (Ixx - Izz) r p
    N = Izz dr/dt - Ixz (dp/dt - q r) - Iyz (dq/dt + r p) - Ixy (p^2 - q^2) + (Iyy - Ixx) p q

:func:`newton_euler` solves these for the accelerations.
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.mechanics.inertia import InertiaTensor, inertia_matrix
from vehdyn.mechanics.kinematics import apply_matrix, as_vector3, as_vectors3, cross, cross_components

__all__ = ["newton_euler", "torque_free_period", "accelerations", "rigid_body_accelerations", "angular_momentum",
           "kinetic_energy", "inverse_inertia", "mass_array"]


def mass_array(mass) -> np.ndarray:
    """A mass as a float array, checked.

    Parameters
    ----------
    mass : float or array_like, shape (n,)
        Mass [kg] (one value per batch member for an array).

    Returns
    -------
    ndarray
        ``mass`` as floats (0-d or 1-D) [kg].

    Raises
    ------
    ParameterError
        If a value is not finite or not > 0, or the array has more than one axis.
    """
    m = np.asarray(mass, dtype=float)
    if m.ndim > 1 or not np.all(np.isfinite(m)) or not np.all(m > 0):
        raise ParameterError(f"mass must be a finite number > 0 [kg] (or a 1-D array of them), got {mass!r}",
                             key="mass", value=mass)
    return m


def inverse_inertia(inertia) -> tuple[np.ndarray, np.ndarray]:
    """The validated inertia matrix and its inverse.

    Parameters
    ----------
    inertia : InertiaTensor or array_like, shape (3, 3) or (3, 3, n)
        Inertia tensor [kg m^2] (see :func:`~vehdyn.mechanics.inertia_matrix`).

    Returns
    -------
    matrix, inverse : ndarray, shape (3, 3) or (3, 3, n)
        I [kg m^2] and I^-1 [1/(kg m^2)], batch axis last.
    """
    mat = inertia_matrix(inertia)
    if mat.ndim == 2:
        return mat, np.linalg.inv(mat)
    return mat, np.moveaxis(np.linalg.inv(np.moveaxis(mat, -1, 0)), 0, -1)


def angular_momentum(inertia, angular_velocity) -> np.ndarray:
    """Angular momentum about the centre of mass in body axes.

    Parameters
    ----------
    inertia : InertiaTensor or array_like, shape (3, 3) or (3, 3, n)
        Inertia tensor about the centre of mass [kg m^2].
    angular_velocity : array_like, shape (3,) or (3, n)
        Body rates (p, q, r) [rad/s].

    Returns
    -------
    ndarray, shape (3,) or (3, n)
        H = I omega [kg m^2/s].
    """
    return apply_matrix(inertia_matrix(inertia), as_vector3(angular_velocity, "angular_velocity"))


def kinetic_energy(mass, inertia, velocity, angular_velocity) -> np.ndarray:
    """Kinetic energy of a rigid body.

    Parameters
    ----------
    mass : float or array_like, shape (n,)
        Mass m [kg].
    inertia : InertiaTensor or array_like, shape (3, 3) or (3, 3, n)
        Inertia tensor about the centre of mass, in body axes [kg m^2].
    velocity : array_like, shape (3,) or (3, n)
        Velocity of the centre of mass V [m/s] (any axes).
    angular_velocity : array_like, shape (3,) or (3, n)
        Body rates omega (p, q, r) [rad/s].

    Returns
    -------
    ndarray
        T = m V.V / 2 + omega . I omega / 2 [J] (0-d, or one value per batch member).
    """
    v, w = as_vectors3(velocity=velocity, angular_velocity=angular_velocity)
    return 0.5 * mass_array(mass) * np.sum(v * v, axis=0) + 0.5 * np.sum(w * angular_momentum(inertia, w), axis=0)


def newton_euler(mass, inertia, velocity, angular_velocity, force, moment):
    r"""Translational and angular acceleration of a rigid body from the Newton-Euler equations.

    .. math::

        \dot{\mathbf V} = \frac{\mathbf F}{m} - \boldsymbol\omega \times \mathbf V, \qquad
        \dot{\boldsymbol\omega} = \mathbf I^{-1} \left(\mathbf M - \boldsymbol\omega \times
        \mathbf I \boldsymbol\omega\right)

    in body axes fixed at the centre of mass (Newton's law for the centre of mass, Euler's
    equations for the rotation, with the full tensor; term by term in the module docstring).

    Parameters
    ----------
    mass : float or array_like, shape (n,)
        Mass m [kg].
    inertia : InertiaTensor or array_like, shape (3, 3) or (3, 3, n)
        Inertia tensor about the centre of mass in body axes [kg m^2]; a matrix carries -Ixy, -Ixz,
        -Iyz off the diagonal (products of inertia Ixy = integral x y dm etc.).
    velocity : array_like, shape (3,) or (3, n)
        Body-axis velocity of the centre of mass (u, v, w) [m/s].
    angular_velocity : array_like, shape (3,) or (3, n)
        Body rates (p, q, r) [rad/s].
    force : array_like, shape (3,) or (3, n)
        Resultant applied force (X, Y, Z) in body axes [N] (include gravity here if it acts).
    moment : array_like, shape (3,) or (3, n)
        Resultant moment about the centre of mass (L, M, N) in body axes [N m].

    Returns
    -------
    velocity_rate : ndarray
        dV/dt = F/m - omega x V [m/s^2]: the rates of the body-axis components (du/dt, dv/dt,
        dw/dt). The absolute acceleration of the centre of mass is F/m.
    angular_acceleration : ndarray
        domega/dt = I^-1 (M - omega x I omega) [rad/s^2].

    Raises
    ------
    ParameterError
        On a non-positive mass, a singular or non-symmetric tensor, or wrongly shaped vectors.

    Notes
    -----
    SAE vehicle axes, x forward, y right, z down; see the module docstring for the equations
    written term by term.

    References
    ----------
    .. [1] L. D. Landau and E. M. Lifshitz, *Mechanics*, 3rd ed., Pergamon, 1976, sec. 36 (Euler's
       equations).
    .. [2] H. Goldstein, C. Poole and J. Safko, *Classical Mechanics*, 3rd ed., 2002, sec. 5.5.
    .. [3] SAE J670, *Vehicle Dynamics Terminology*, 2008 (vehicle axes and the symbols u, v, w,
       p, q, r, X, Y, Z, L, M, N).

    Examples
    --------
    >>> from vehdyn.mechanics import InertiaTensor, newton_euler
    >>> dv, dw = newton_euler(1500.0, InertiaTensor(500.0, 2000.0, 2200.0), velocity=[20.0, 0.0, 0.0],
    ...                       angular_velocity=[0.0, 0.0, 0.5], force=[0.0, 15000.0, 0.0], moment=[0.0, 0.0, 0.0])
    >>> dv.tolist()      # a steady turn: F_y / m = r u, so dv/dt = 0 [m/s^2]
    [0.0, 0.0, 0.0]
    """
    matrix, inverse = inverse_inertia(inertia)
    m = mass_array(mass)
    v, w, f, mom = as_vectors3(m.ndim == 1 or matrix.ndim == 3, velocity=velocity, angular_velocity=angular_velocity,
                               force=force, moment=moment)
    return accelerations(m, matrix, inverse, v, w, f, mom)


def accelerations(mass, inertia, inverse, velocity, angular_velocity, force, moment):
    """:func:`newton_euler` on validated arrays, for models' inner loops (no checks, no copies).

    Parameters
    ----------
    mass : ndarray
        Mass [kg] from :func:`mass_array`.
    inertia, inverse : ndarray, shape (3, 3) or (3, 3, n)
        I [kg m^2] and I^-1 [1/(kg m^2)] from :func:`inverse_inertia`.
    velocity, angular_velocity, force, moment : ndarray, shape (3,) or (3, n)
        V [m/s], omega [rad/s], F [N] and M [N m] in body axes, broadcast-compatible.

    Returns
    -------
    velocity_rate, angular_acceleration : ndarray
        dV/dt [m/s^2] and domega/dt [rad/s^2], as :func:`newton_euler`.
    """
    velocity_rate = force / mass - cross(angular_velocity, velocity)
    angular_acceleration = apply_matrix(inverse, moment - cross(angular_velocity, apply_matrix(inertia, angular_velocity)))
    return velocity_rate, angular_acceleration


def _matrix_vector(m, a0, a1, a2):
    """m @ (a0, a1, a2) for a nested 3x3 tuple, written out."""
    return (m[0][0] * a0 + m[0][1] * a1 + m[0][2] * a2, m[1][0] * a0 + m[1][1] * a1 + m[1][2] * a2,
            m[2][0] * a0 + m[2][1] * a1 + m[2][2] * a2)


def rigid_body_accelerations(mass, inertia, inverse, velocity, rates, force, moment):
    r""":func:`accelerations` on 3-tuples, written out: the form vehicle models' equations call.

    Plain arithmetic on the components (floats, arrays along a batch axis, numba-compiled code,
    symbols), with the inertia and its inverse as nested 3x3 tuples:

    .. math::

        \dot V = F / m - \omega \times V,\qquad \dot\omega = J^{-1} (M - \omega \times J \omega)

    Parameters
    ----------
    mass : float
        m [kg].
    inertia, inverse : tuple
        J [kg*m^2] and J^-1 [1/(kg*m^2)], nested 3x3 tuples (rows).
    velocity : tuple
        (u, v, w) [m/s], body axes.
    rates : tuple
        (p, q, r) [rad/s].
    force : tuple
        (X, Y, Z) [N], body axes.
    moment : tuple
        (L, M, N) [N*m] about the centre of mass.

    Returns
    -------
    tuple
        ((du/dt, dv/dt, dw/dt) [m/s^2], (dp/dt, dq/dt, dr/dt) [rad/s^2]).

    References
    ----------
    .. [1] L. D. Landau, E. M. Lifshitz, *Mechanics*, 3rd ed., 1976, sec. 36.
    """
    p, q, r = rates
    cx, cy, cz = cross_components(p, q, r, velocity[0], velocity[1], velocity[2])
    h0, h1, h2 = _matrix_vector(inertia, p, q, r)
    gx, gy, gz = cross_components(p, q, r, h0, h1, h2)
    return ((force[0] / mass - cx, force[1] / mass - cy, force[2] / mass - cz),
            _matrix_vector(inverse, moment[0] - gx, moment[1] - gy, moment[2] - gz))


def torque_free_period(inertia, angular_velocity) -> float:
    """Period [s] of the body rates of a torque-free rigid body (Euler-Poinsot motion).

    Parameters
    ----------
    inertia : InertiaTensor or array_like, shape (3, 3)
        Inertia tensor about the centre of mass [kg m^2].
    angular_velocity : array_like, shape (3,)
        Body rates at any instant [rad/s], in the tensor's axes.

    Returns
    -------
    float
        T = 4 K(k) sqrt(I1 I2 I3 / ((I3 - I2)(H^2 - 2 E I1))),
        k^2 = (I2 - I1)(2 E I3 - H^2) / ((I3 - I2)(H^2 - 2 E I1)) for H^2 >= 2 E I2 (rotation
        about the major axis), with I1 and I3 exchanged for H^2 < 2 E I2 (about the minor axis);
        I1 < I2 < I3 are the principal moments, E the kinetic energy, H the angular momentum and K
        the complete elliptic integral of the first kind (Landau & Lifshitz, *Mechanics*, 3rd ed.,
        sec. 37). Over one period a body spun near its intermediate axis flips over and back. The
        period is infinite on the separatrix (H^2 = 2 E I2, e.g. a pure spin about the intermediate
        axis) and for a body at rest; for a pure spin about the minor or major axis it is the
        period of small wobbles about that spin.

    Raises
    ------
    ParameterError
        If two principal moments are equal (a symmetric body precesses steadily instead).
    """
    from scipy.special import ellipk

    tensor = inertia if isinstance(inertia, InertiaTensor) else InertiaTensor.from_matrix(inertia_matrix(inertia))
    moments, axes = tensor.principal()
    if np.min(np.diff(moments)) <= 1e-9 * moments[-1]:
        raise ParameterError(f"torque_free_period needs three distinct principal moments, got {moments.tolist()} "
                             "kg*m^2: a symmetric body precesses steadily", key="inertia", value=moments.tolist())
    w = axes.T @ as_vector3(angular_velocity, "angular_velocity")
    i1, i2, i3 = moments
    energy2 = float(np.sum(moments * w * w))  # 2 E
    momentum2 = float(np.sum((moments * w) ** 2))  # H^2
    if momentum2 < energy2 * i2:
        i1, i3 = i3, i1
    scale = (i3 - i2) * (momentum2 - energy2 * i1)
    if not scale > 0:
        return float("inf")
    k2 = min((i2 - i1) * (energy2 * i3 - momentum2) / scale, 1.0)
    return float(4.0 * ellipk(k2) * np.sqrt(i1 * i2 * i3 / scale))
