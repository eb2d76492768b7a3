"""Handling: linear single-track (bicycle) model, steady-state and understeer analysis, transient
(ISO 7401) metrics, four-wheel steering, the lateral-yaw-roll model, crosswind sensitivity and
on-centre handling.

All vehicle models use SAE J670 axes (x forward, y right, z down): a positive front steer angle
turns right and gives a positive yaw rate and lateral acceleration. Cornering stiffnesses are per
AXLE (both tires).
"""

from vehdyn.handling.articulated_single_track import ArticulatedSingleTrack, ArticulationEvent
from vehdyn.handling.bicycle import BicycleParameters, LinearBicycle, bicycle_parameters
from vehdyn.handling.car_trailer import (
    CarTrailerParameters,
    CrosswindAmplification,
    LinearCarTrailer,
    SnakingMode,
    car_trailer_parameters,
    trailer_crosswind_amplification,
)
from vehdyn.handling.crosswind import steady_state_crosswind_yaw_rate
from vehdyn.handling.four_wheel_steer import (
    FourWheelSteerComparison,
    compare_four_wheel_steering,
    proportional_rear_steer,
    yaw_rate_feedback_rear_steer,
    zero_sideslip_rear_steer_ratio,
)
from vehdyn.handling.lateral_yaw_roll import LateralYawRoll, LateralYawRollParameters, lateral_yaw_roll_parameters, roll_gradient
from vehdyn.handling.lateral_yaw_roll_lag import LateralYawRollLag
from vehdyn.handling.nonlinear_steady_state import (
    NonlinearHandlingDiagram,
    SteadyStateCornering,
    limit_lateral_acceleration,
    nonlinear_handling_diagram,
    steady_state_cornering,
)
from vehdyn.handling.single_track import SingleTrack, SingleTrackParameters
from vehdyn.handling.roll_balance import SteadyRoll, steady_roll, unsprung_cg_height
from vehdyn.handling.understeer_terms import plot_understeer_budget, understeer_budget, vehicle_roll_understeer
from vehdyn.handling.steady_state import (
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
from vehdyn.handling.steering_system import (
    SteeredVehicle,
    SteeringSystem,
    SteeringSystemParameters,
    steering_system_parameters,
)
from vehdyn.handling.transient import (
    YawMode,
    lateral_acceleration_transfer_function,
    steering_frequency_response,
    yaw_mode,
    yaw_rate_transfer_function,
)

__all__ = [
    # linear single track (bicycle) and its closed forms
    "LinearBicycle", "BicycleParameters", "bicycle_parameters",
    "understeer_gradient", "understeer_gradient_deg_per_g", "understeer_gradient_rad_per_g", "stability_factor",
    "characteristic_speed", "critical_speed", "zero_sideslip_speed", "SteadyStateGains", "steady_state_gains",
    "NeutralSteerPoint", "neutral_steer_point", "static_margin", "AckermannWheelAngles", "ackermann_steer_angle",
    "ackermann_wheel_angles", "steer_angle_for", "HandlingDiagram", "handling_diagram",
    "YawMode", "yaw_mode", "yaw_rate_transfer_function", "lateral_acceleration_transfer_function",
    "steering_frequency_response", "steady_state_crosswind_yaw_rate",
    # four-wheel steering
    "FourWheelSteerComparison", "compare_four_wheel_steering", "proportional_rear_steer",
    "yaw_rate_feedback_rear_steer", "zero_sideslip_rear_steer_ratio",
    # roll
    "LateralYawRoll", "LateralYawRollParameters", "lateral_yaw_roll_parameters", "roll_gradient", "LateralYawRollLag",
    "SteadyRoll", "steady_roll", "unsprung_cg_height", "understeer_budget", "plot_understeer_budget",
    "vehicle_roll_understeer",
    # nonlinear single track and its steady state
    "SingleTrack", "SingleTrackParameters", "SteadyStateCornering", "steady_state_cornering",
    "NonlinearHandlingDiagram", "nonlinear_handling_diagram", "limit_lateral_acceleration",
    # steering system
    "SteeringSystem", "SteeringSystemParameters", "steering_system_parameters", "SteeredVehicle",
    # articulated vehicles
    "LinearCarTrailer", "CarTrailerParameters", "car_trailer_parameters", "SnakingMode", "CrosswindAmplification",
    "trailer_crosswind_amplification", "ArticulatedSingleTrack", "ArticulationEvent",
]
