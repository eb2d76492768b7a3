"""Rigid-body mechanics in SAE vehicle axes (x forward, y right, z down).

The bottom layer of vehdyn: the Newton-Euler equations with the full inertia tensor, the 6-DOF
rigid-body model, Euler-angle kinematics and point transfer, and mass properties.

Newton-Euler (:mod:`~vehdyn.mechanics.equations_of_motion`)
    :func:`newton_euler`, :func:`angular_momentum`, :func:`kinetic_energy`, :func:`torque_free_period`
Model (:mod:`~vehdyn.mechanics.rigid_body`)
    :class:`RigidBody6DOF`
Kinematics (:mod:`~vehdyn.mechanics.kinematics`)
    :func:`rotation_body_to_earth`, :func:`rotation_earth_to_body`, :func:`body_to_earth`,
    :func:`earth_to_body`, :func:`euler_angles_from_rotation`, :func:`euler_angle_rates`,
    :func:`body_rates`, :func:`check_gimbal_lock`, :func:`point_velocity`,
    :func:`point_acceleration`, :func:`moving_point_velocity`, :func:`moving_point_acceleration`,
    :func:`absolute_acceleration`, :data:`GIMBAL_LOCK_MARGIN`
Inertia (:mod:`~vehdyn.mechanics.inertia`)
    :class:`InertiaTensor` (products of inertia Ixz = integral x z dm; the matrix carries -Ixz),
    :class:`MassProperties` (of one rigid part; the vehicle's mass group is
    :class:`vehdyn.params.MassAndInertia`), :func:`composite`, :func:`parallel_axis_shift`,
    :func:`inertia_matrix`, primitives :func:`solid_box`, :func:`solid_cylinder`, :func:`hollow_cylinder`,
    :func:`solid_sphere`, :func:`hollow_sphere`, :func:`solid_cone`, :func:`slender_rod`
"""

from vehdyn.mechanics.inertia import (
    InertiaTensor,
    MassProperties,
    composite,
    hollow_cylinder,
    hollow_sphere,
    inertia_matrix,
    parallel_axis_shift,
    slender_rod,
    solid_box,
    solid_cone,
    solid_cylinder,
    solid_sphere,
)
from vehdyn.mechanics.kinematics import (
    GIMBAL_LOCK_MARGIN,
    absolute_acceleration,
    body_rates,
    body_to_earth,
    check_gimbal_lock,
    earth_to_body,
    euler_angle_rates,
    euler_angles_from_rotation,
    moving_point_acceleration,
    moving_point_velocity,
    point_acceleration,
    point_velocity,
    rotation_body_to_earth,
    rotation_earth_to_body,
)
from vehdyn.mechanics.equations_of_motion import angular_momentum, kinetic_energy, newton_euler, torque_free_period
from vehdyn.mechanics.rigid_body import RigidBody6DOF

__all__ = [
    "newton_euler",
    "angular_momentum",
    "kinetic_energy",
    "torque_free_period",
    "RigidBody6DOF",
    "rotation_body_to_earth",
    "rotation_earth_to_body",
    "body_to_earth",
    "earth_to_body",
    "euler_angles_from_rotation",
    "euler_angle_rates",
    "body_rates",
    "check_gimbal_lock",
    "GIMBAL_LOCK_MARGIN",
    "point_velocity",
    "point_acceleration",
    "moving_point_velocity",
    "moving_point_acceleration",
    "absolute_acceleration",
    "InertiaTensor",
    "MassProperties",
    "composite",
    "parallel_axis_shift",
    "inertia_matrix",
    "solid_box",
    "solid_cylinder",
    "hollow_cylinder",
    "solid_sphere",
    "hollow_sphere",
    "solid_cone",
    "slender_rod",
]
