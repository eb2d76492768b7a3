"""Standard test procedures and their tracks, run on any vehicle model of :mod:`vehdyn.handling`
or :mod:`vehdyn.full_vehicle`.

Steer inputs (:mod:`~vehdyn.procedures.steer_inputs`)
    :func:`step_steer`, :func:`ramp_steer`, :func:`sine_steer` (ISO 7401), :func:`sine_with_dwell`
    (FMVSS 126), closed-form signals for :func:`vehdyn.simulate`.
ISO 7401 lateral transient response (:mod:`~vehdyn.procedures.iso7401`)
    :func:`step_response_metrics`, :func:`step_steer_metrics` -> :class:`StepResponseMetrics`.
ISO 4138 steady-state circular driving (:mod:`~vehdyn.procedures.iso4138`)
    :func:`constant_radius_test`.
ISO 3888 severe lane changes (:mod:`~vehdyn.procedures.iso3888`)
    :func:`double_lane_change_track` (-1), :func:`obstacle_avoidance_track` (-2),
    :class:`DoubleLaneChangeTrack`, :func:`lane_change_outcome`, :func:`spin_out_time`,
    :func:`lane_change_run`, :func:`lane_change_limit`, :func:`slip_angle_utilization`,
    :func:`lane_change_speed_bound`.
ISO 7975 braking in a turn (:mod:`~vehdyn.procedures.iso7975`)
    :func:`braking_in_turn` -> :class:`BrakingInTurn`.
ISO 13674-1 on-centre weave test (:mod:`~vehdyn.procedures.iso13674`)
    :func:`weave_test`, :func:`weave_metrics` -> :class:`WeaveTestMetrics`.
Crosswind (:mod:`~vehdyn.procedures.crosswind`)
    :func:`crosswind_gust`, :func:`crosswind_sensitivity` (ISO 12021) -> :class:`CrosswindSensitivity`,
    :func:`wind_zone_signal`.
FMVSS 126 electronic stability control (:mod:`~vehdyn.procedures.esc_compliance`)
    :func:`fmvss126` -> :class:`FMVSS126Result` (the S7.9.4 series and the S5.2 verdict),
    :func:`sine_with_dwell_metrics` -> :class:`SineWithDwellMetrics`.
"""

from vehdyn.procedures.crosswind import CrosswindSensitivity, crosswind_gust, crosswind_sensitivity, wind_zone_signal
from vehdyn.procedures.esc_compliance import FMVSS126Result, SineWithDwellMetrics, fmvss126, sine_with_dwell_metrics
from vehdyn.procedures.iso3888 import (
    DoubleLaneChangeTrack,
    double_lane_change_track,
    lane_change_limit,
    lane_change_outcome,
    lane_change_run,
    lane_change_speed_bound,
    obstacle_avoidance_track,
    slip_angle_utilization,
    spin_out_time,
)
from vehdyn.procedures.iso4138 import constant_radius_test
from vehdyn.procedures.iso7401 import StepResponseMetrics, step_response_metrics, step_steer_metrics
from vehdyn.procedures.iso7975 import BrakingInTurn, braking_in_turn
from vehdyn.procedures.iso13674 import WeaveTestMetrics, weave_metrics, weave_test
from vehdyn.procedures.steer_inputs import ramp_steer, sine_steer, sine_with_dwell, step_steer

__all__ = [
    "step_steer", "ramp_steer", "sine_steer", "sine_with_dwell",
    "StepResponseMetrics", "step_response_metrics", "step_steer_metrics",
    "constant_radius_test",
    "DoubleLaneChangeTrack", "double_lane_change_track", "obstacle_avoidance_track", "lane_change_outcome",
    "spin_out_time", "lane_change_run", "lane_change_limit", "slip_angle_utilization", "lane_change_speed_bound",
    "BrakingInTurn", "braking_in_turn",
    "WeaveTestMetrics", "weave_test", "weave_metrics",
    "CrosswindSensitivity", "crosswind_gust", "crosswind_sensitivity", "wind_zone_signal",
    "FMVSS126Result", "fmvss126", "SineWithDwellMetrics", "sine_with_dwell_metrics",
]
