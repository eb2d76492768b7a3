"""Six-degree-of-freedom rigid body in SAE vehicle axes: :class:`RigidBody6DOF`."""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError, SimulationError
from vehdyn.model import Model
from vehdyn.signals import Signal
from vehdyn.mechanics.kinematics import GIMBAL_LOCK_MARGIN, apply_matrix, cross, euler_angle_rates, rotation_body_to_earth
from vehdyn.mechanics.equations_of_motion import accelerations, inverse_inertia, mass_array

__all__ = ["RigidBody6DOF"]

_STATES = (
    "longitudinal_velocity", "lateral_velocity", "vertical_velocity",
    "roll_rate", "pitch_rate", "yaw_rate",
    "x", "y", "z",
    "roll_angle", "pitch_angle", "yaw_angle",
)
_INPUTS = (
    Signal("longitudinal_force", "N", "applied force X along body x (forward), resultant at the CG"),
    Signal("lateral_force", "N", "applied force Y along body y (right)"),
    Signal("vertical_force", "N", "applied force Z along body z (down)"),
    Signal("roll_moment", "N*m", "applied moment L about body x, about the CG"),
    Signal("pitch_moment", "N*m", "applied moment M about body y (nose up positive)"),
    Signal("yaw_moment", "N*m", "applied moment N about body z (nose right positive)"),
)
_OUTPUTS = (
    Signal("x_velocity", "m/s", "earth-fixed velocity component dX/dt"),
    Signal("y_velocity", "m/s", "earth-fixed velocity component dY/dt"),
    Signal("z_velocity", "m/s", "earth-fixed velocity component dZ/dt (down positive)"),
    Signal("speed", "m/s", "magnitude of the CG velocity"),
    Signal("sideslip_angle", "rad", "sideslip beta = atan2(v, u) (atan(v/u) for u > 0)"),
    Signal("course_angle", "rad", "course angle nu = psi + beta"),
    Signal("longitudinal_acceleration", "m/s^2", "absolute CG acceleration along body x, du/dt + q w - r v"),
    Signal("lateral_acceleration", "m/s^2", "absolute CG acceleration along body y, dv/dt + r u - p w"),
    Signal("vertical_acceleration", "m/s^2", "absolute CG acceleration along body z, dw/dt + p v - q u"),
)


def _stack3(components) -> np.ndarray:
    """Three arrays stacked along a new first axis, broadcast only when their shapes differ."""
    if np.shape(components[0]) == np.shape(components[1]) == np.shape(components[2]):
        return np.array(components)
    return np.array(np.broadcast_arrays(*components))


def _skew(vector) -> np.ndarray:
    """The matrix [a x] with [a x] b = a x b."""
    a1, a2, a3 = vector
    return np.array([[0.0, -a3, a2], [a3, 0.0, -a1], [-a2, a1, 0.0]])


class RigidBody6DOF(Model):
    r"""A rigid body with six degrees of freedom in SAE vehicle axes (x forward, y right, z down).

    Parameters
    ----------
    mass : float or array_like, shape (n,)
        Mass m [kg] (an array gives one value per batch member).
    inertia : InertiaTensor or array_like, shape (3, 3) or (3, 3, n)
        Inertia tensor about the centre of mass in body axes [kg m^2]. Products of inertia are
        Ixy = integral x y dm etc.; a matrix carries -Ixy, -Ixz, -Iyz off the diagonal (see
        :mod:`vehdyn.mechanics.inertia`).
    gravity : float, optional
        Gravitational acceleration [m/s^2] along the earth z axis (down), added to the applied
        forces as m g R^T e_Z. Default 0: the force inputs are then the whole resultant force, as
        in a vehicle model that adds the weight itself (and the linearization about straight
        running splits into three groups; with gravity the pitch angle tilts the weight and
        couples the longitudinal group to the vertical-pitch one).
    gimbal_lock_margin : float, optional
        The right-hand side raises :class:`~vehdyn.SimulationError` when the pitch angle comes
        within this distance [rad] of +-90 deg (default
        :data:`~vehdyn.mechanics.kinematics.GIMBAL_LOCK_MARGIN`).

    States
    ------
    longitudinal_velocity, lateral_velocity, vertical_velocity : u, v, w [m/s]
        Velocity of the centre of mass in body axes.
    roll_rate, pitch_rate, yaw_rate : p, q, r [rad/s]
        Angular velocity in body axes.
    x, y, z : [m]
        Position of the centre of mass in earth axes (z down).
    roll_angle, pitch_angle, yaw_angle : phi, theta, psi [rad]
        Euler angles, yaw-pitch-roll order.

    Inputs
    ------
    longitudinal_force, lateral_force, vertical_force : X, Y, Z [N]
        Applied force in body axes.
    roll_moment, pitch_moment, yaw_moment : L, M, N [N m]
        Applied moment about the centre of mass in body axes.

    Outputs
    -------
    x_velocity, y_velocity, z_velocity [m/s]
        Earth-axis velocity R V.
    speed [m/s]
        |V|.
    sideslip_angle [rad]
        beta = atan2(v, u), equal to atan(v/u) for u > 0 (four-quadrant so that it stays the
        direction of travel in the body's x-y plane when reversing).
    course_angle [rad]
        nu = psi + beta (the direction of travel in the ground plane when roll and pitch are zero).
    longitudinal_acceleration, lateral_acceleration, vertical_acceleration [m/s^2]
        Absolute acceleration of the centre of mass in body axes, dV/dt + omega x V = F/m (+ gravity).

    Notes
    -----
    Newton's and Euler's laws in body axes fixed at the centre of mass, the position in earth
    axes and the yaw-pitch-roll Euler-angle kinematics:

    .. math::

        \dot{\mathbf V} &= \frac{\mathbf F}{m} + g R^T \mathbf e_Z - \boldsymbol\omega \times \mathbf V \\
        \dot{\boldsymbol\omega} &= \mathbf I^{-1} (\mathbf M - \boldsymbol\omega \times \mathbf I \boldsymbol\omega) \\
        (\dot x, \dot y, \dot z)^T &= R \mathbf V, \qquad R = R_z(\psi) R_y(\theta) R_x(\phi) \\
        \dot\phi &= p + (q \sin\phi + r \cos\phi) \tan\theta, \quad
        \dot\theta = q \cos\phi - r \sin\phi, \quad
        \dot\psi = \frac{q \sin\phi + r \cos\phi}{\cos\theta}

    with V = (u, v, w), omega = (p, q, r) (:func:`~vehdyn.mechanics.newton_euler`,
    :func:`~vehdyn.mechanics.rotation_body_to_earth`, :func:`~vehdyn.mechanics.euler_angle_rates`).
    Every array may carry a trailing batch axis. :meth:`jacobian` gives the exact derivatives, so
    :meth:`linearize` returns exact matrices (structural zeros are exact zeros).

    References
    ----------
    .. [1] H. Goldstein, C. Poole and J. Safko, *Classical Mechanics*, 3rd ed., Addison-Wesley,
       2002, ch. 4-5 (rotations, Euler angles, Euler's equations).
    .. [2] D. T. Greenwood, *Principles of Dynamics*, 2nd ed., Prentice-Hall, 1988, ch. 7-8
       (rigid-body kinematics and dynamics in three dimensions).
    .. [3] B. Etkin, *Dynamics of Atmospheric Flight*, Wiley, 1972, ch. 4 (the equations in
       vehicle body axes).
    .. [4] SAE J670, *Vehicle Dynamics Terminology*, 2008 (axes, states and signs).

    Examples
    --------
    A body driven round a steady turn by the side force m r u closes the circle of radius u / r
    after one period 2 pi / r:

    >>> import numpy as np
    >>> import vehdyn
    >>> from vehdyn.mechanics import InertiaTensor, RigidBody6DOF
    >>> body = RigidBody6DOF(mass=1500.0, inertia=InertiaTensor(500.0, 2000.0, 2200.0))
    >>> t = np.linspace(0.0, 4 * np.pi, 401)                              # one period at r = 0.5 rad/s
    >>> result = vehdyn.simulate(body, t, {"lateral_force": 1500.0 * 0.5 * 20.0},
    ...                          x0={"longitudinal_velocity": 20.0, "yaw_rate": 0.5}, rtol=1e-10, atol=1e-10)
    >>> round(float(result["y"].max()), 6), round(abs(float(result["x"][-1])), 6)   # diameter 80 m, back at 0
    (80.0, 0.0)
    >>> float(result["lateral_acceleration"][0])                         # r u [m/s^2]
    10.0
    """

    states = _STATES
    inputs = _INPUTS
    outputs = _OUTPUTS
    phenomena = frozenset({"longitudinal", "lateral", "yaw", "roll", "pitch", "heave"})

    def __init__(self, *, mass, inertia, gravity: float = 0.0, gimbal_lock_margin: float = GIMBAL_LOCK_MARGIN):
        self.mass = mass_array(mass)
        self.inertia, self._inverse_inertia = inverse_inertia(inertia)
        if isinstance(gravity, bool) or not isinstance(gravity, (int, float)) or not np.isfinite(gravity):
            raise ParameterError(f"gravity must be a finite number [m/s^2], got {gravity!r}", key="gravity",
                                 value=gravity)
        self.gravity = float(gravity)
        if not (isinstance(gimbal_lock_margin, (int, float)) and 0 < gimbal_lock_margin < 0.5):
            raise ParameterError(f"gimbal_lock_margin must be in (0, 0.5) rad, got {gimbal_lock_margin!r}",
                                 key="gimbal_lock_margin", value=gimbal_lock_margin)
        self.gimbal_lock_margin = float(gimbal_lock_margin)

    def _motion(self, t, x, u):
        """Body-axis velocity, rates, their derivatives, the rotation matrix, the Euler-angle rates, yaw."""
        x = np.asarray(x, dtype=float)
        u_in = np.asarray(u, dtype=float)
        if self.mass.ndim or self.inertia.ndim == 3 or x.ndim != u_in.ndim:
            # a batch (of parameters, states or inputs): single states and inputs broadcast against it
            x = x.reshape(x.shape[:1] + (-1,))
            u_in = u_in.reshape(u_in.shape[:1] + (-1,))
        (longitudinal_velocity, lateral_velocity, vertical_velocity, roll_rate, pitch_rate, yaw_rate,
         _x, _y, _z, roll_angle, pitch_angle, yaw_angle) = x
        velocity = x[0:3]
        angular_velocity = x[3:6]
        force, moment = u_in[0:3], u_in[3:6]
        try:
            euler_rates = euler_angle_rates(roll_angle, pitch_angle, roll_rate, pitch_rate, yaw_rate,
                                            margin=self.gimbal_lock_margin)
        except ParameterError as exc:
            when = float(t) if np.ndim(t) == 0 else None
            raise SimulationError(f"RigidBody6DOF at t = {when:.6g} s: {exc}" if when is not None else
                                  f"RigidBody6DOF: {exc}", time=when, signal="pitch_angle") from None
        rotation = rotation_body_to_earth(roll_angle, pitch_angle, yaw_angle)
        velocity_rate, angular_acceleration = accelerations(
            self.mass, self.inertia, self._inverse_inertia, velocity, angular_velocity, force, moment)
        if self.gravity:
            velocity_rate = velocity_rate + self.gravity * rotation[2]  # g R^T e_Z: row 3 of R
        return velocity, angular_velocity, velocity_rate, angular_acceleration, rotation, euler_rates, yaw_angle

    def rhs(self, t, x, u):
        """dx/dt for states x (12,) or (12, n) and inputs u (6,) or (6, n); see the class Notes."""
        velocity, _, velocity_rate, angular_acceleration, rotation, euler_rates, _ = self._motion(t, x, u)
        earth_velocity = apply_matrix(rotation, velocity)
        parts = (velocity_rate, angular_acceleration, earth_velocity, _stack3(euler_rates))
        if all(part.shape == velocity_rate.shape for part in parts):
            return np.concatenate(parts)
        shape = np.broadcast_shapes(*(part.shape for part in parts))
        return np.concatenate([np.broadcast_to(part, shape) for part in parts])

    def jacobian(self, t, x, u):
        """Exact Jacobians (A, B, C, D) at a single point (x of shape (12,), u of shape (6,)).

        Raises
        ------
        ParameterError
            For a body whose mass or inertia is a batch (linearize one variant at a time).
        """
        if self.mass.ndim or self.inertia.ndim == 3:
            raise ParameterError("RigidBody6DOF.jacobian: mass and inertia must be single values, not a batch; "
                                 "build one model per variant to linearize it", key="mass", value=self.mass)
        x = np.asarray(x, dtype=float)
        velocity, angular_velocity, _, _, rotation, _, _ = self._motion(t, x, u)
        roll, pitch = x[9], x[10]
        p, q, r = angular_velocity
        inertia, inverse, mass, g = self.inertia, self._inverse_inertia, float(self.mass), self.gravity
        sf, cf, st, ct = np.sin(roll), np.cos(roll), np.sin(pitch), np.cos(pitch)
        # derivatives of the body-to-earth matrix with respect to roll, pitch and yaw
        ex, ey, ez = (_skew(e) for e in np.eye(3))
        r_yaw_pitch = rotation_body_to_earth(0.0, pitch, x[11])
        d_rotation = (rotation @ ex, r_yaw_pitch @ ey @ rotation_body_to_earth(roll, 0.0, 0.0), ez @ rotation)
        # d(g R^T e_Z)/d(angles): row 3 of R is (-st, sf ct, cf ct)
        d_gravity = g * np.array([[0.0, -ct, 0.0], [cf * ct, -sf * st, 0.0], [-sf * ct, -cf * st, 0.0]])
        q_r, q_r_roll = q * sf + r * cf, q * cf - r * sf
        A = np.zeros((12, 12))
        A[0:3, 0:3] = -_skew(angular_velocity)
        A[0:3, 3:6] = _skew(velocity)
        A[0:3, 9:12] = d_gravity
        A[3:6, 3:6] = inverse @ (_skew(inertia @ angular_velocity) - _skew(angular_velocity) @ inertia)
        A[6:9, 0:3] = rotation
        A[6:9, 9:12] = np.stack([d @ velocity for d in d_rotation], axis=1)
        A[9:12, 3:6] = [[1.0, sf * st / ct, cf * st / ct], [0.0, cf, -sf], [0.0, sf / ct, cf / ct]]
        A[9:12, 9:11] = [[q_r_roll * st / ct, q_r / ct**2], [-q_r, 0.0], [q_r_roll / ct, q_r * st / ct**2]]
        B = np.zeros((12, 6))
        B[0:3, 0:3] = np.eye(3) / mass
        B[3:6, 3:6] = inverse
        C = np.zeros((9, 12))
        D = np.zeros((9, 6))
        C[0:3] = A[6:9]
        u_body, v_body = velocity[0], velocity[1]
        speed = float(np.linalg.norm(velocity))
        if speed > 0:
            C[3, 0:3] = velocity / speed
        planar = u_body * u_body + v_body * v_body
        if planar > 0:
            C[4, 0:2] = [-v_body / planar, u_body / planar]
        C[5] = C[4]
        C[5, 11] = 1.0
        # absolute acceleration F/m + g R^T e_Z
        C[6:9, 9:12] = d_gravity
        D[6:9, 0:3] = np.eye(3) / mass
        return A, B, C, D

    def output(self, t, x, u):
        """The outputs listed in the class docstring, shape (9,) or (9, n)."""
        velocity, angular_velocity, velocity_rate, _, rotation, _, yaw_angle = self._motion(t, x, u)
        earth_velocity = apply_matrix(rotation, velocity)
        acceleration = velocity_rate + cross(angular_velocity, velocity)
        u_body, v_body = velocity[0], velocity[1]
        sideslip = np.arctan2(v_body, u_body)
        course = yaw_angle + sideslip
        speed = np.sqrt(np.sum(velocity * velocity, axis=0))
        shape = np.broadcast_shapes(earth_velocity.shape, acceleration.shape)
        return np.concatenate([np.broadcast_to(earth_velocity, shape),
                               np.broadcast_to(np.stack([speed, sideslip, course]), shape),
                               np.broadcast_to(acceleration, shape)])
