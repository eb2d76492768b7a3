"""Handling: linear single-track (bicycle) model, steady-state and understeer analysis, transient
(ISO 7401) metrics, four-wheel steering and the lateral-yaw-roll model.

All vehicle models use SAE J670 axes (x forward, y right, z down): a positive front steer angle
turns right and gives a positive yaw rate and lateral acceleration. Cornering stiffnesses are per
AXLE (both tires).
"""

from .bicycle import BicycleParameters, LinearBicycle, bicycle_parameters
from .steady_state import (
    AckermannWheelAngles,
    HandlingDiagram,
    NeutralSteerPoint,
    SteadyStateGains,
    ackermann_steer_angle,
    ackermann_wheel_angles,
    characteristic_speed,
    critical_speed,
    handling_diagram,
    neutral_steer_point,
    stability_factor,
    static_margin,
    steady_state_gains,
    steer_angle_for,
    understeer_gradient,
    understeer_gradient_deg_per_g,
    understeer_gradient_rad_per_g,
    zero_sideslip_speed,
)
from .four_wheel_steer import (
    FourWheelSteerComparison,
    compare_four_wheel_steering,
    proportional_rear_steer,
    yaw_rate_feedback_rear_steer,
    zero_sideslip_rear_steer_ratio,
)
from .lateral_yaw_roll import LateralYawRoll, LateralYawRollParameters, lateral_yaw_roll_parameters, roll_gradient
from .transient import (
    StepResponseMetrics,
    YawMode,
    lateral_acceleration_transfer_function,
    steering_frequency_response,
    step_response_metrics,
    step_steer_metrics,
    yaw_mode,
    yaw_rate_transfer_function,
)

__all__ = [
    "BicycleParameters",
    "LinearBicycle",
    "bicycle_parameters",
    "AckermannWheelAngles",
    "HandlingDiagram",
    "NeutralSteerPoint",
    "SteadyStateGains",
    "ackermann_steer_angle",
    "ackermann_wheel_angles",
    "characteristic_speed",
    "critical_speed",
    "handling_diagram",
    "neutral_steer_point",
    "stability_factor",
    "static_margin",
    "steady_state_gains",
    "steer_angle_for",
    "understeer_gradient",
    "understeer_gradient_deg_per_g",
    "understeer_gradient_rad_per_g",
    "zero_sideslip_speed",
    "FourWheelSteerComparison",
    "compare_four_wheel_steering",
    "proportional_rear_steer",
    "yaw_rate_feedback_rear_steer",
    "zero_sideslip_rear_steer_ratio",
    "LateralYawRoll",
    "LateralYawRollParameters",
    "lateral_yaw_roll_parameters",
    "roll_gradient",
    "StepResponseMetrics",
    "YawMode",
    "lateral_acceleration_transfer_function",
    "steering_frequency_response",
    "step_response_metrics",
    "step_steer_metrics",
    "yaw_mode",
    "yaw_rate_transfer_function",
]
