"""Handling: linear single-track (bicycle) model, steady-state and understeer analysis, transient
(ISO 7401) metrics, four-wheel steering, the lateral-yaw-roll model, crosswind sensitivity and
on-centre handling.

All vehicle models use SAE J670 axes (x forward, y right, z down): a positive front steer angle
turns right and gives a positive yaw rate and lateral acceleration. Cornering stiffnesses are per
AXLE (both tires).
"""

from vehdyn.handling.bicycle import BicycleParameters, LinearBicycle, bicycle_parameters
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
from vehdyn.handling.four_wheel_steer import (
    FourWheelSteerComparison,
    compare_four_wheel_steering,
    proportional_rear_steer,
    yaw_rate_feedback_rear_steer,
    zero_sideslip_rear_steer_ratio,
)
from vehdyn.handling.lateral_yaw_roll import LateralYawRoll, LateralYawRollParameters, lateral_yaw_roll_parameters, roll_gradient
from vehdyn.handling.lateral_yaw_roll_lag import LateralYawRollLag
from vehdyn.handling.transient import (
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
    "LateralYawRollLag",
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

# Nonlinear single track, its steady state, manoeuvres and the preview driver (issue 7)
from vehdyn.handling.single_track import SingleTrack, SingleTrackParameters  # noqa: E402
from vehdyn.handling.nonlinear_steady_state import (  # noqa: E402
    NonlinearHandlingDiagram,
    SteadyStateCornering,
    limit_lateral_acceleration,
    nonlinear_handling_diagram,
    steady_state_cornering,
)
from vehdyn.handling.driver import (  # noqa: E402
    CrossoverDriver,
    DriverInTheLoop,
    OptimalPreviewDriver,
    PreviewDriver,
    driver_loop,
    driver_loop_margins,
    driver_loop_response,
    lane_change_limit,
    lane_change_run,
    preview_gains,
    slip_angle_utilization,
)
from vehdyn.handling.crosswind import (  # noqa: E402
    CrosswindSensitivity,
    crosswind_sensitivity,
    steady_state_crosswind_yaw_rate,
    wind_zone_signal,
)
from vehdyn.handling.steering_system import (  # noqa: E402
    SteeredVehicle,
    SteeringSystem,
    SteeringSystemParameters,
    steering_system_parameters,
)
from vehdyn.handling.on_center import WeaveTestMetrics, weave_metrics, weave_test  # noqa: E402
from vehdyn.handling.maneuvers import (  # noqa: E402
    BrakingInTurn,
    DoubleLaneChangeTrack,
    SineWithDwellMetrics,
    braking_in_turn,
    constant_radius_test,
    crosswind_gust,
    double_lane_change_track,
    obstacle_avoidance_track,
    lane_change_speed_bound,
    lane_change_outcome,
    ramp_steer,
    sine_steer,
    sine_with_dwell,
    sine_with_dwell_metrics,
    spin_out_time,
    step_steer,
)

__all__ += [
    "SingleTrack",
    "SingleTrackParameters",
    "SteadyStateCornering",
    "steady_state_cornering",
    "NonlinearHandlingDiagram",
    "nonlinear_handling_diagram",
    "limit_lateral_acceleration",
    "PreviewDriver",
    "DriverInTheLoop",
    "CrossoverDriver",
    "OptimalPreviewDriver",
    "driver_loop",
    "driver_loop_margins",
    "driver_loop_response",
    "preview_gains",
    "lane_change_limit",
    "lane_change_run",
    "slip_angle_utilization",
    "step_steer",
    "ramp_steer",
    "sine_steer",
    "sine_with_dwell",
    "sine_with_dwell_metrics",
    "SineWithDwellMetrics",
    "constant_radius_test",
    "crosswind_gust",
    "braking_in_turn",
    "BrakingInTurn",
    "DoubleLaneChangeTrack",
    "double_lane_change_track",
    "obstacle_avoidance_track",
    "lane_change_speed_bound",
    "lane_change_outcome",
    "spin_out_time",
    "CrosswindSensitivity",
    "crosswind_sensitivity",
    "steady_state_crosswind_yaw_rate",
    "wind_zone_signal",
    "SteeredVehicle",
    "SteeringSystem",
    "SteeringSystemParameters",
    "steering_system_parameters",
    "WeaveTestMetrics",
    "weave_metrics",
    "weave_test",
]

# Articulated vehicles (issue 14)
from vehdyn.handling.car_trailer import (  # noqa: E402
    CarTrailerParameters,
    CrosswindAmplification,
    LinearCarTrailer,
    SnakingMode,
    car_trailer_parameters,
    trailer_crosswind_amplification,
)
from vehdyn.handling.articulated_single_track import ArticulatedSingleTrack, ArticulationEvent  # noqa: E402

__all__ += ["CarTrailerParameters", "CrosswindAmplification", "LinearCarTrailer", "SnakingMode",
            "car_trailer_parameters", "trailer_crosswind_amplification",
            "ArticulatedSingleTrack", "ArticulationEvent"]

# FMVSS 126 compliance (issue 15)
from vehdyn.handling.fmvss126 import FMVSS126Result, fmvss126  # noqa: E402

__all__ += ["FMVSS126Result", "fmvss126"]
