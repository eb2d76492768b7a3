"""Estimated cost and error of each rung: the one table of thresholds and where each number comes from.

Error of a rung R against the top admissible rung T, per output: the sum over the phenomena that
one of R and T represents and the other does not (the symmetric difference of their
``phenomena``) of an estimate of what that phenomenon changes in the output, plus R's intrinsic
error (the steady-state algebra's missing transient). The estimates are of two kinds:

* **computed**: the linear handling rungs cost about a millisecond per simulated second, so the
  plan runs them (its *probes*) and measures their mutual differences exactly: tire lag is
  |LinearBicycle - LinearBicycle+lag|, roll (for the yaw and lateral outputs) is
  |LinearBicycle - LateralYawRoll|, the transient is |SteadyState - LinearBicycle|.
* **model-based with a measured gain**: the tire saturation a linear rung misses is
  ``SATURATION_GAIN * d``, with d = |1 - F_MF(alpha) / (C alpha)| the relative deficit of the
  vehicle's own tire law against the linear tire at the probe's peak slip angle and the static
  load of each axle; the speed change a constant-speed rung misses is max |du| / u, with
  du/dt = v r - F_yf sin(delta) / m integrated along the probe (Pacejka 2012, eq. 1.43, the
  longitudinal equation with the drive holding the drag); the pitch coupling the two independent
  quarter cars miss grows with |1 - DI|, DI = I_y / (m a b) the dynamic index (Gillespie 1992,
  ch. 5: the front and rear ends decouple at DI = 1); the roll a mean-track ride model misses at a
  corner grows with the road's left-right asymmetry max|z_l - z_r| / max(|z_l| + |z_r|) (for a
  left-right symmetric vehicle the heave and pitch at the sprung CG do not see it at all).

Every gain below is measured by ``benchmarks/bench_ladder.py`` (its "calibration" table: the
measured error of the rung divided by the model-based quantity, over the 12 standard scenes on the
sedan), and the thresholds are read off its error matrix.
"""

from __future__ import annotations

import numpy as np

from ..units import GRAVITY

__all__ = ["THRESHOLDS", "COST_PER_SIMULATED_SECOND", "relative_error", "relative_errors"]

#: The planner's thresholds and gains. Provenance of each number in the comments: all from
#: benchmarks/bench_ladder.py on the 12 standard scenes (sedan, its Magic Formula tires).
THRESHOLDS = {
    # a_y (linear probe) / (mu g) above which a scene needs tire_saturation: the linear rungs'
    # measured error passes 2 % between 0.3 (gentle lane change 0.1 g: 0.4 %) and ... (see bench)
    "saturation_fraction": 0.3,
    # a_y / (mu g) above which the linear rungs are outside their domain (inadmissible): a linear
    # tire makes forces beyond the friction limit there.
    "linear_domain_fraction": 0.9,
    # measured error of a linear rung against SingleTrack / tire-law deficit d (bench calibration)
    "saturation_gain": 1.5,
    # measured corner-output error of BouncePitch against FullCar / road asymmetry (pothole scene)
    "roll_asymmetry_gain": 1.0,
    # measured heave error of the quarter-car pair against BouncePitch / |1 - DI| (ride scenes)
    "dynamic_index_gain": 1.0,
    # floor of every estimate: integration error of the references (rtol 1e-8, exact linear)
    "numerical_error": 1e-6,
}

#: Measured cost [s of wall time per s simulated] of each rung (bench_ladder, median over the
#: standard scenes it runs, one core of the development machine); the plan scales it by the
#: scene's duration. A rung the plan runs as a probe reports its measured time instead.
COST_PER_SIMULATED_SECOND = {
    "SteadyState": 2e-5,
    "LinearBicycle": 2e-4,
    "LinearBicycle+lag": 2e-4,
    "LateralYawRoll": 2e-4,
    "SingleTrack(linear tires)": 2e-3,
    "SingleTrack": 3e-3,
    "QuarterCar": 3e-3,
    "BouncePitch": 3e-3,
    "FullCar": 5e-3,
}
_UNKNOWN_COST = 0.1  # [s/s] a rung not in the table (e.g. a newly registered one) until it is measured


def estimated_cost(rung_name: str, duration: float) -> float:
    """Estimated wall time [s] of a rung over ``duration`` [s] (the table above)."""
    return COST_PER_SIMULATED_SECOND.get(rung_name, _UNKNOWN_COST) * duration


def relative_error(x, x_ref) -> float:
    """max |x - x_ref| / max |x_ref| on a common time grid (0 when both are zero, inf when only x_ref is)."""
    x, x_ref = np.asarray(x, dtype=float), np.asarray(x_ref, dtype=float)
    scale = float(np.max(np.abs(x_ref))) if x_ref.size else 0.0
    diff = float(np.max(np.abs(x - x_ref))) if x.size else 0.0
    if scale == 0.0:
        return 0.0 if diff == 0.0 else float("inf")
    return diff / scale


def relative_errors(signals: dict, reference: dict) -> dict:
    """:func:`relative_error` per output name."""
    return {name: relative_error(signals[name], reference[name]) for name in reference}


# ---------------------------------------------------------------------- model-based quantities
def _axle_tire_forces(tire, load, alpha):
    """Lateral force [N] of one tire at ``load`` and slip angle(s) ``alpha``, its antisymmetric part
    (ply steer and conicity cancel between the two mirrored tires of an axle, as in SingleTrack)."""
    alpha = np.asarray(alpha, dtype=float)
    plus = np.asarray(tire.forces(np.full(alpha.shape, load), 0.0 * alpha, alpha, 0.0, 20.0).fy)
    minus = np.asarray(tire.forces(np.full(alpha.shape, load), 0.0 * alpha, -alpha, 0.0, 20.0).fy)
    return 0.5 * np.abs(plus - minus)


def _tires(vehicle, tire_name):
    from ..tire import load_tire, tire_for_vehicle

    if tire_name is not None:
        tire = load_tire(tire_name)
        return {"front": tire, "rear": tire}
    return {axle: tire_for_vehicle(vehicle, axle) for axle in ("front", "rear")}


def tire_deficit(vehicle, slip_angles, tire_name=None) -> float:
    """max over axles of |1 - F_law(alpha) / (C alpha)| at the peak |slip angle| [rad] of each axle.

    F_law is the vehicle's tire law (or the ``.tir`` file ``tire_name``) at half the static axle
    load (antisymmetric part); C alpha the linear axle model's force per tire
    (``tires.<axle>_cornering_stiffness / 2``).
    """
    loads = vehicle.static_axle_loads(GRAVITY)
    tires = _tires(vehicle, tire_name)
    worst = 0.0
    for axle, load, alpha in zip(("front", "rear"), loads, slip_angles):
        alpha = max(abs(float(alpha)), 1e-4)
        linear = 0.5 * getattr(vehicle.tires, f"{axle}_cornering_stiffness") * alpha
        law = float(_axle_tire_forces(tires[axle], 0.5 * load, alpha))
        worst = max(worst, abs(1.0 - law / linear))
    return worst


def drag_load_transfer_gain_change(vehicle, speed, tire_name=None, *, law=None) -> float:
    """Relative change of the steady-state yaw-rate gain from the load transfer of the drive force
    that holds ``speed`` against the drag: dF_z = h F_drag / L off the front axle onto the rear,
    the axles' cornering stiffnesses taken from the tire law at the shifted loads (Gillespie 1992,
    eq. 2-18 and 6-15). Near neutral steer at speed this is several percent (the understeer
    gradient is a small difference of two terms). ``law="linear"``: the load-proportional linear
    tire instead of the vehicle's law."""
    from ..handling.steady_state import steady_state_gains
    from ..handling.bicycle import bicycle_parameters

    aero, g = vehicle.aero, vehicle.geometry
    drag = 0.5 * aero.air_density * aero.frontal_area * aero.drag_coefficient * speed**2
    shift = vehicle.mass.cg_height * drag / g.wheelbase
    if law is not None:
        from ..tire import tire_for_vehicle

        tires = {axle: tire_for_vehicle(vehicle, axle, law) for axle in ("front", "rear")}
    else:
        tires = _tires(vehicle, tire_name)
    loads = vehicle.static_axle_loads(GRAVITY)
    eps = 1e-4

    def stiffness(axle, load):
        return 2.0 * float(_axle_tire_forces(tires[axle], 0.5 * load, eps)) / eps

    base = bicycle_parameters(vehicle)
    scale_f = stiffness("front", loads[0] - shift) / stiffness("front", loads[0])
    scale_r = stiffness("rear", loads[1] + shift) / stiffness("rear", loads[1])
    import dataclasses

    shifted = dataclasses.replace(base, front_cornering_stiffness=base.front_cornering_stiffness * scale_f,
                                  rear_cornering_stiffness=base.rear_cornering_stiffness * scale_r)
    g0 = float(steady_state_gains(base, speed).yaw_rate)
    g1 = float(steady_state_gains(shifted, speed).yaw_rate)
    return abs(g1 - g0) / abs(g0)


def slip_for_utilization(vehicle, utilization: float):
    """Axle slip angles [rad] at which the linear tires would use ``utilization`` of mu F_z."""
    mu = vehicle.tires.friction_coefficient
    loads = vehicle.static_axle_loads(GRAVITY)
    return [utilization * mu * load / getattr(vehicle.tires, f"{axle}_cornering_stiffness")
            for axle, load in zip(("front", "rear"), loads)]


def speed_change(probe, vehicle, speed: float) -> float:
    """max |du| / u along a constant-speed probe: du/dt = v r - F_yf sin(delta) / m."""
    t = probe.time
    v, r = probe["lateral_velocity"], probe["yaw_rate"]
    rate = v * r
    if "front_lateral_force" in probe and "front_steer_angle" in probe:
        rate = rate - probe["front_lateral_force"] * np.sin(probe["front_steer_angle"]) / vehicle.mass.mass
    du = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))])
    return float(np.max(np.abs(du))) / speed


def dynamic_index_coupling(vehicle) -> float:
    """|1 - DI| with DI = I_y / (m_s a b) of the sprung mass (0: front and rear decouple)."""
    m, g = vehicle.mass, vehicle.geometry
    a, b = g.sprung_cg_to_front_axle, g.sprung_cg_to_rear_axle
    return abs(1.0 - m.sprung_pitch_inertia / (m.sprung_mass * a * b))


def road_asymmetry(road) -> float:
    """max |z_l - z_r| / max(|z_l| + |z_r|) of the two tracks (0: identical tracks)."""
    _, left, right = road
    scale = float(np.max(np.abs(left) + np.abs(right)))
    return 0.0 if scale == 0 else float(np.max(np.abs(left - right))) / scale


_BODY_OUTPUTS = ("sprung_displacement", "sprung_velocity", "sprung_acceleration", "pitch_angle", "pitch_rate",
                 "pitch_acceleration")


def is_body_output(name: str) -> bool:
    """A heave or pitch output at the sprung CG (blind to a road's left-right difference)."""
    return name in _BODY_OUTPUTS
