"""Rigid-body kinematics in SAE vehicle axes: rotations, Euler-angle rates, motion of body points.

Axes and angles (SAE J670)
--------------------------
Earth axes X, Y, Z (Z down) and body axes x (forward), y (right), z (down). The attitude is given
by the Euler angles yaw psi, pitch theta, roll phi applied in that order (z-y-x, "yaw-pitch-roll"):
the body axes are obtained from the earth axes by a rotation psi about Z, then theta about the new
y, then phi about the new x. The body-to-earth matrix is

    R = Rz(psi) Ry(theta) Rx(phi),         v_earth = R v_body,   v_body = R^T v_earth.

The Euler-angle rates follow from the body rates p, q, r (B. Etkin, *Dynamics of Atmospheric
Flight*, Wiley, 1972, ch. 4, cited from memory; derived by projecting psi' e_Z + theta' e_y1 +
phi' e_x on the body axes and checked in the tests against R^T dR/dt = [omega x])::

    dphi/dt   = p + (q sin phi + r cos phi) tan theta
    dtheta/dt = q cos phi - r sin phi
    dpsi/dt   = (q sin phi + r cos phi) / cos theta

which are singular at theta = +-90 deg (gimbal lock): there the functions raise
:class:`~vehdyn.ParameterError` instead of returning huge or non-finite rates.

Vectors are arrays of shape (3,) or (3, n) (a trailing batch axis); angles are arrays that
broadcast against that batch axis.
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError

__all__ = [
    "GIMBAL_LOCK_MARGIN",
    "rotation_body_to_earth",
    "rotation_matrix",
    "euler_rates",
    "cross_components",
    "rotation_earth_to_body",
    "body_to_earth",
    "earth_to_body",
    "euler_angles_from_rotation",
    "euler_angle_rates",
    "body_rates",
    "check_gimbal_lock",
    "point_velocity",
    "point_acceleration",
    "moving_point_velocity",
    "moving_point_acceleration",
    "absolute_acceleration",
]

#: Default distance [rad] from pitch = +-90 deg inside which the Euler-angle rates are refused.
#: At the margin the rates are amplified 1/cos(theta) = 1000 times the body rates.
GIMBAL_LOCK_MARGIN = 1e-3


def as_vector3(value, name: str) -> np.ndarray:
    """``value`` as a float array of shape (3,) or (3, n); raises ParameterError naming ``name``."""
    v = np.asarray(value, dtype=float)
    if v.ndim not in (1, 2) or v.shape[0] != 3:
        raise ParameterError(f"{name} must have shape (3,) or (3, n_batch), got {v.shape}", key=name, value=v.shape)
    return v


def as_vectors3(batch: bool = False, **vectors) -> list[np.ndarray]:
    """Several 3-vectors made broadcast-compatible: if any has a batch axis (or ``batch`` is true),
    the single ones get shape (3, 1). Raises ParameterError naming a malformed one."""
    arrays = [as_vector3(value, name) for name, value in vectors.items()]
    if batch or any(a.ndim == 2 for a in arrays):
        arrays = [a[:, None] if a.ndim == 1 else a for a in arrays]
    return arrays


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product of 3-vectors along the first axis (batch axes broadcast).

    Written out by components: ``np.cross`` costs ten times more on the small arrays of a
    right-hand side.
    """
    a1, a2, a3 = a
    b1, b2, b3 = b
    c1, c2, c3 = a2 * b3 - a3 * b2, a3 * b1 - a1 * b3, a1 * b2 - a2 * b1
    if np.shape(c1) == np.shape(c2) == np.shape(c3):
        return np.array((c1, c2, c3))
    return np.array(np.broadcast_arrays(c1, c2, c3))


def apply_matrix(matrix: np.ndarray, vector: np.ndarray) -> np.ndarray:
    """matrix @ vector for a (3, 3) or (3, 3, n) matrix and a (3,) or (3, n) vector."""
    if matrix.ndim == 2:
        return matrix @ vector
    return np.einsum("ij...,j...->i...", matrix, vector)


# ---------------------------------------------------------------------------- rotations
def cross_components(a0, a1, a2, b0, b1, b2):
    """The components of a x b, written out (plain arithmetic: floats, arrays, compiled code).

    Parameters
    ----------
    a0, a1, a2 : float or ndarray
        a [any unit].
    b0, b1, b2 : float or ndarray
        b [any unit].

    Returns
    -------
    tuple
        (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0).
    """
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


def rotation_matrix(xp, roll, pitch, yaw):
    r"""R = Rz(yaw) Ry(pitch) Rx(roll) as nested 3-tuples, over an ``xp`` namespace.

    The one source of the rotation (:func:`rotation_body_to_earth` stacks it into an array;
    vehicle models' compiled code reads it as tuples).

    .. math::

        R = \begin{pmatrix} c_\theta c_\psi & s_\phi s_\theta c_\psi - c_\phi s_\psi &
        c_\phi s_\theta c_\psi + s_\phi s_\psi \\ c_\theta s_\psi & s_\phi s_\theta s_\psi
        + c_\phi c_\psi & c_\phi s_\theta s_\psi - s_\phi c_\psi \\ -s_\theta & s_\phi c_\theta
        & c_\phi c_\theta \end{pmatrix}

    Parameters
    ----------
    xp : namespace
        ``numpy`` or any namespace with ``sin`` and ``cos``.
    roll, pitch, yaw : float or ndarray
        phi, theta, psi [rad].

    Returns
    -------
    tuple
        Three rows of three entries [-]; v_earth = R v_body.
    """
    sf, cf = xp.sin(roll), xp.cos(roll)
    st, ct = xp.sin(pitch), xp.cos(pitch)
    ss, cs = xp.sin(yaw), xp.cos(yaw)
    return ((ct * cs, sf * st * cs - cf * ss, cf * st * cs + sf * ss),
            (ct * ss, sf * st * ss + cf * cs, cf * st * ss - sf * cs),
            (-st, sf * ct, cf * ct))


def euler_rates(xp, roll, pitch, roll_rate, pitch_rate, yaw_rate):
    r"""Euler-angle rates from the body rates over an ``xp`` namespace, without the gimbal-lock check.

    The one source of :func:`euler_angle_rates` (which checks the pitch first); a model whose
    domain keeps away from +-90 deg of pitch calls it directly.

    .. math::

        \dot\phi = p + (q \sin\phi + r \cos\phi) \tan\theta,\quad
        \dot\theta = q \cos\phi - r \sin\phi,\quad
        \dot\psi = (q \sin\phi + r \cos\phi) / \cos\theta

    Parameters
    ----------
    xp : namespace
        ``numpy`` or any namespace with ``sin`` and ``cos``.
    roll, pitch : float or ndarray
        phi, theta [rad].
    roll_rate, pitch_rate, yaw_rate : float or ndarray
        p, q, r [rad/s].

    Returns
    -------
    tuple
        (dphi/dt, dtheta/dt, dpsi/dt) [rad/s].
    """
    sf, cf = xp.sin(roll), xp.cos(roll)
    q_r = pitch_rate * sf + yaw_rate * cf  # rate about the intermediate (once-rotated) z axis, times cos theta
    ct = xp.cos(pitch)
    return roll_rate + q_r * xp.sin(pitch) / ct, pitch_rate * cf - yaw_rate * sf, q_r / ct


def rotation_body_to_earth(roll, pitch, yaw) -> np.ndarray:
    r"""Body-to-earth rotation matrix R = Rz(yaw) Ry(pitch) Rx(roll).

    .. math::

        R = \begin{bmatrix}
        c_\theta c_\psi & s_\phi s_\theta c_\psi - c_\phi s_\psi & c_\phi s_\theta c_\psi + s_\phi s_\psi \\
        c_\theta s_\psi & s_\phi s_\theta s_\psi + c_\phi c_\psi & c_\phi s_\theta s_\psi - s_\phi c_\psi \\
        -s_\theta & s_\phi c_\theta & c_\phi c_\theta \end{bmatrix}

    (c, s: cosine and sine of the subscripted angle).

    Parameters
    ----------
    roll, pitch, yaw : float or array_like
        Euler angles phi, theta, psi [rad] (yaw-pitch-roll order), broadcast together.

    Returns
    -------
    ndarray, shape (3, 3) or (3, 3, n)
        v_earth = R v_body [-]. Its columns are the body axes expressed in earth axes.

    References
    ----------
    .. [1] SAE J670, *Vehicle Dynamics Terminology*, 2008 (earth and vehicle axes, Euler angles).
    .. [2] B. Etkin, *Dynamics of Atmospheric Flight*, Wiley, 1972, ch. 4.

    Examples
    --------
    >>> import numpy as np
    >>> from vehdyn.mechanics import rotation_body_to_earth
    >>> R = rotation_body_to_earth(0.0, 0.0, np.pi / 2)     # heading 90 deg: nose along earth Y
    >>> np.round(R @ [1.0, 0.0, 0.0], 12).tolist()
    [0.0, 1.0, 0.0]
    """
    phi, theta, psi = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (roll, pitch, yaw)))
    return np.array(rotation_matrix(np, phi, theta, psi))


def rotation_earth_to_body(roll, pitch, yaw) -> np.ndarray:
    """Earth-to-body rotation matrix R^T (see :func:`rotation_body_to_earth`).

    Parameters
    ----------
    roll, pitch, yaw : float or array_like
        Euler angles phi, theta, psi [rad] (yaw-pitch-roll order), broadcast together.

    Returns
    -------
    ndarray, shape (3, 3) or (3, 3, n)
        R^T [-]: v_body = R^T v_earth.
    """
    return np.swapaxes(rotation_body_to_earth(roll, pitch, yaw), 0, 1)


def body_to_earth(vector, roll, pitch, yaw) -> np.ndarray:
    """Earth-axis components of a vector given in body axes.

    Parameters
    ----------
    vector : array_like, shape (3,) or (3, n)
        Body-axis components [any unit: that of the result].
    roll, pitch, yaw : float or array_like
        Euler angles phi, theta, psi [rad] (yaw-pitch-roll order), broadcast together.

    Returns
    -------
    ndarray
        R v, in the unit of ``vector``.
    """
    return apply_matrix(rotation_body_to_earth(roll, pitch, yaw), as_vector3(vector, "vector"))


def earth_to_body(vector, roll, pitch, yaw) -> np.ndarray:
    """Body-axis components of a vector given in earth axes.

    Parameters
    ----------
    vector : array_like, shape (3,) or (3, n)
        Earth-axis components [any unit: that of the result].
    roll, pitch, yaw : float or array_like
        Euler angles phi, theta, psi [rad] (yaw-pitch-roll order), broadcast together.

    Returns
    -------
    ndarray
        R^T v, in the unit of ``vector``.
    """
    return apply_matrix(rotation_earth_to_body(roll, pitch, yaw), as_vector3(vector, "vector"))


def euler_angles_from_rotation(rotation) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Roll, pitch and yaw of a body-to-earth rotation matrix (inverse of :func:`rotation_body_to_earth`).

    Parameters
    ----------
    rotation : array_like, shape (3, 3) or (3, 3, n)
        Body-to-earth rotation matrix R [-].

    Returns
    -------
    roll, pitch, yaw : ndarray
        phi, theta, psi [rad], with pitch in [-pi/2, pi/2] and roll, yaw in (-pi, pi].

    Raises
    ------
    ParameterError
        At pitch = +-90 deg (within :data:`GIMBAL_LOCK_MARGIN`), where only roll -+ yaw is defined.
    """
    rot = np.asarray(rotation, dtype=float)
    if rot.shape[:2] != (3, 3):
        raise ParameterError(f"rotation must have shape (3, 3) or (3, 3, n), got {rot.shape}", key="rotation",
                             value=rot.shape)
    pitch = np.arcsin(np.clip(-rot[2, 0], -1.0, 1.0))
    check_gimbal_lock(pitch)
    roll = np.arctan2(rot[2, 1], rot[2, 2])
    yaw = np.arctan2(rot[1, 0], rot[0, 0])
    return roll, pitch, yaw


def check_gimbal_lock(pitch, margin: float = GIMBAL_LOCK_MARGIN) -> None:
    """Raise :class:`~vehdyn.ParameterError` if a pitch angle is within ``margin`` of +-90 deg.

    The test is cos(pitch) < sin(margin), so it holds for pitch angles beyond +-90 deg (which
    occur when the angles are integrated) as well.

    Parameters
    ----------
    pitch : float or array_like
        Pitch angle(s) theta [rad].
    margin : float
        Distance from +-90 deg [rad] inside which the angles are refused.

    Raises
    ------
    ParameterError
        Naming the first offending pitch angle (key ``pitch_angle``) and its batch member.
    """
    pitch = np.asarray(pitch, dtype=float)
    locked = ~(np.abs(np.cos(pitch)) >= np.sin(margin))  # also catches NaN
    if locked.any():
        idx = np.unravel_index(int(np.argmax(locked)), pitch.shape) if pitch.ndim else ()
        value = float(pitch[idx])
        where = f" (batch member {idx[0]})" if pitch.ndim else ""
        raise ParameterError(
            f"pitch_angle = {value:.9g} rad ({np.degrees(value):.6f} deg){where} is within {margin:g} rad of "
            "+-90 deg: the yaw-pitch-roll Euler angles are singular there (gimbal lock) and their rates "
            "1/cos(pitch) times the body rates. Start from another attitude or use a model whose attitude "
            "never pitches through the vertical.", key="pitch_angle", value=value)


def euler_angle_rates(roll, pitch, roll_rate, pitch_rate, yaw_rate, *, margin: float = GIMBAL_LOCK_MARGIN):
    r"""Euler-angle rates from the body rates.

    .. math::

        \dot\phi = p + (q \sin\phi + r \cos\phi) \tan\theta, \qquad
        \dot\theta = q \cos\phi - r \sin\phi, \qquad
        \dot\psi = \frac{q \sin\phi + r \cos\phi}{\cos\theta}

    Parameters
    ----------
    roll, pitch : float or array_like
        Roll and pitch angles phi, theta [rad].
    roll_rate, pitch_rate, yaw_rate : float or array_like
        Body rates p, q, r [rad/s].
    margin : float
        Distance from pitch = +-90 deg [rad] inside which the rates are refused.

    Returns
    -------
    tuple of ndarray
        (dphi/dt, dtheta/dt, dpsi/dt) [rad/s].

    Raises
    ------
    ParameterError
        When ``pitch`` is within ``margin`` of +-90 deg (gimbal lock).

    References
    ----------
    .. [1] B. Etkin, *Dynamics of Atmospheric Flight*, Wiley, 1972, ch. 4.
    """
    check_gimbal_lock(pitch, margin)
    return euler_rates(np, np.asarray(roll, dtype=float), np.asarray(pitch, dtype=float), roll_rate, pitch_rate,
                       yaw_rate)


def body_rates(roll, pitch, roll_angle_rate, pitch_angle_rate, yaw_angle_rate):
    r"""Body rates from the Euler-angle rates (the inverse of :func:`euler_angle_rates`).

    .. math::

        p = \dot\phi - \dot\psi \sin\theta, \qquad
        q = \dot\theta \cos\phi + \dot\psi \cos\theta \sin\phi, \qquad
        r = -\dot\theta \sin\phi + \dot\psi \cos\theta \cos\phi

    regular at every attitude.

    Parameters
    ----------
    roll, pitch : float or array_like
        Roll and pitch angles phi, theta [rad].
    roll_angle_rate, pitch_angle_rate, yaw_angle_rate : float or array_like
        Euler-angle rates dphi/dt, dtheta/dt, dpsi/dt [rad/s].

    Returns
    -------
    tuple
        Body rates (p, q, r) [rad/s].

    References
    ----------
    .. [1] B. Etkin, *Dynamics of Atmospheric Flight*, Wiley, 1972, ch. 4.
    """
    sf, cf = np.sin(roll), np.cos(roll)
    st, ct = np.sin(pitch), np.cos(pitch)
    return (roll_angle_rate - yaw_angle_rate * st,
            pitch_angle_rate * cf + yaw_angle_rate * ct * sf,
            -pitch_angle_rate * sf + yaw_angle_rate * ct * cf)


# ---------------------------------------------------------------------------- body points
def absolute_acceleration(velocity, angular_velocity, velocity_rate) -> np.ndarray:
    """Absolute (inertial) acceleration of the body origin in body axes: a = dV/dt + omega x V [m/s^2].

    Parameters
    ----------
    velocity : array_like, shape (3,) or (3, n)
        Body-axis components (u, v, w) of the origin's velocity [m/s].
    angular_velocity : array_like
        Body rates (p, q, r) [rad/s].
    velocity_rate : array_like
        Rates of change of the body-axis components (du/dt, dv/dt, dw/dt) [m/s^2], as seen in the
        rotating body axes.

    Returns
    -------
    ndarray
        (du/dt + q w - r v, dv/dt + r u - p w, dw/dt + p v - q u) [m/s^2]; e.g. the lateral
        acceleration of a car in a steady turn is r u, not dv/dt = 0.
    """
    v, w, v_dot = as_vectors3(velocity=velocity, angular_velocity=angular_velocity, velocity_rate=velocity_rate)
    return v_dot + cross(w, v)


def point_velocity(v_o, omega, r) -> np.ndarray:
    """Velocity of a point P fixed on the body: V_P = V_O + omega x r [m/s].

    Parameters
    ----------
    v_o : array_like, shape (3,) or (3, n)
        Velocity of the body origin O in body axes [m/s].
    omega : array_like
        Body angular velocity (p, q, r) [rad/s].
    r : array_like
        Position of P relative to O in body axes [m].

    Returns
    -------
    ndarray, shape (3,) or (3, n)
        V_P in body axes [m/s].
    """
    v_o, omega, r = as_vectors3(v_o=v_o, omega=omega, r=r)
    return v_o + cross(omega, r)


def point_acceleration(a_o, omega, omega_dot, r) -> np.ndarray:
    r"""Absolute acceleration of a point P fixed on the body, in body axes.

    .. math::

        \mathbf a_P = \mathbf a_O + \dot{\boldsymbol\omega} \times \mathbf r
        + \boldsymbol\omega \times (\boldsymbol\omega \times \mathbf r)

    Parameters
    ----------
    a_o : array_like, shape (3,) or (3, n)
        Absolute acceleration of the body origin O in body axes [m/s^2] (dV/dt + omega x V, see
        :func:`absolute_acceleration`).
    omega : array_like
        Body angular velocity (p, q, r) [rad/s].
    omega_dot : array_like
        Angular acceleration [rad/s^2].
    r : array_like
        Position of P relative to O in body axes [m].

    Returns
    -------
    ndarray, shape (3,) or (3, n)
        a_P in body axes [m/s^2].
    """
    a_o, w, w_dot, r = as_vectors3(a_o=a_o, omega=omega, omega_dot=omega_dot, r=r)
    return a_o + cross(w_dot, r) + cross(w, cross(w, r))


def moving_point_velocity(v_o, omega, r, r_dot) -> np.ndarray:
    """Velocity of a point P moving on the body: V_P = V_O + omega x r + r_dot.

    Parameters
    ----------
    v_o : array_like, shape (3,) or (3, n)
        Velocity of the body origin O in body axes [m/s].
    omega : array_like
        Body angular velocity (p, q, r) [rad/s].
    r : array_like
        Position of P relative to O in body axes [m].
    r_dot : array_like
        Velocity of P relative to the body, in body axes [m/s] (e.g. a wheel centre's suspension
        travel rate).

    Returns
    -------
    ndarray, shape (3,) or (3, n)
        V_P in body axes [m/s].
    """
    v_o, omega, r, r_dot = as_vectors3(v_o=v_o, omega=omega, r=r, r_dot=r_dot)
    return point_velocity(v_o, omega, r) + r_dot


def moving_point_acceleration(a_o, omega, omega_dot, r, r_dot, r_ddot) -> np.ndarray:
    r"""Absolute acceleration of a point P moving on the body, in body axes (five-term formula).

    .. math::

        \mathbf a_P = \mathbf a_O + \dot{\boldsymbol\omega} \times \mathbf r
        + \boldsymbol\omega \times (\boldsymbol\omega \times \mathbf r)
        + 2 \boldsymbol\omega \times \dot{\mathbf r} + \ddot{\mathbf r}

    (2 omega x r_dot: the Coriolis term).

    Parameters
    ----------
    a_o : array_like, shape (3,) or (3, n)
        Absolute acceleration of the body origin O in body axes [m/s^2].
    omega : array_like
        Body angular velocity (p, q, r) [rad/s].
    omega_dot : array_like
        Angular acceleration [rad/s^2].
    r : array_like
        Position of P relative to O in body axes [m].
    r_dot, r_ddot : array_like
        Velocity [m/s] and acceleration [m/s^2] of P relative to the body, in body axes.

    Returns
    -------
    ndarray, shape (3,) or (3, n)
        a_P in body axes [m/s^2].

    References
    ----------
    .. [1] H. Goldstein, C. Poole and J. Safko, *Classical Mechanics*, 3rd ed., 2002, sec. 4.9-4.10
       (rates of change in rotating axes, the Coriolis term).
    """
    a_o, omega, omega_dot, r, r_dot, r_ddot = as_vectors3(a_o=a_o, omega=omega, omega_dot=omega_dot, r=r,
                                                          r_dot=r_dot, r_ddot=r_ddot)
    return point_acceleration(a_o, omega, omega_dot, r) + 2.0 * cross(omega, r_dot) + r_ddot
