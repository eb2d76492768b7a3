"""The understeer budget of the shipped cars, and the gradient every rung of the ladder measures.

A vehicle-dynamics engineer explains a car's understeer as a budget (Gillespie, *Fundamentals of
Vehicle Dynamics*, 1992, ch. 6, Table 6.1): weight distribution over cornering stiffness, lateral
load transfer, camber thrust, roll steer, lateral-force and aligning-moment compliance steer, and
(referred to the hand wheel) the steering system's compliance.
:func:`vehdyn.handling.understeer_budget` computes the terms from the vehicle file; the road-wheel
rows add up to :func:`vehdyn.handling.understeer_gradient_deg_per_g`. Beside each budget, the
gradient each rung measures from its own steady states at 20 m/s (central differences of
delta - L r / u at a_y = +-0.1 and +-0.2 m/s^2, Richardson-extrapolated; one difference at
+-0.1 m/s^2 in quick mode): the linear rungs carry the file's terms exactly; the nonlinear rungs
add what their tire law and their speed add (the law's cornering stiffness at the running loads,
the load transfer of the drag and of the drive force, rolling resistance, ply steer). The budget at
the speed has those as rows of the full vehicle, and their total is set beside the full vehicle's
gradient with its own Magic Formula tires and drag (20 m/s; 10, 20 and 30 m/s in the full run).
A fourth budget, the sedan with roll steer, camber gains and compliance steer, shows every row,
with the gradients of the two rungs that carry them all (the full vehicle and the single track with
load transfer, linear tires with the law's camber stiffness and trail at the static loads, no drag).
"""

import numpy as np

import vehdyn
from vehdyn import handling
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.units import GRAVITY

VEHICLES = ("sedan", "compact", "van")
SPEED = 20.0  # [m/s]
DEG_PER_G = np.rad2deg(GRAVITY)


def _richardson(k, quick):
    """(4 k(0.1) - k(0.2)) / 3 of a gradient k(A) from central differences at +-A [m/s^2]."""
    return k(0.1) if quick else (4.0 * k(0.1) - k(0.2)) / 3.0


def _linear_gradient(model):
    dc = model.D - model.C @ np.linalg.solve(model.A, model.B)
    j = model.index("front_steer_angle", "inputs")
    ay, r = dc[model.index("lateral_acceleration", "outputs"), j], dc[model.index("yaw_rate", "outputs"), j]
    return r, ay


def full_vehicle_gradient(model, speed, quick):
    """The full vehicle's gradient from its own steady trims at ``speed`` [deg/g] (:func:`_richardson`)."""
    L = model.vehicle.wheelbase

    def k(A):
        s = []
        for a in (A, -A):
            x0, u0 = model.trim(speed, lateral_acceleration=a)
            s.append(u0[model.index("front_steer_angle", "inputs")]
                     - L * x0[model.index("yaw_rate")] / x0[model.index("longitudinal_velocity")])
        return (s[0] - s[1]) / (2 * A)

    return _richardson(k, quick) * DEG_PER_G


def measured_gradients(vehicle, quick):
    """{rung: gradient [deg/g]} of the rungs that can take the vehicle, at SPEED."""
    from vehdyn.full_vehicle import FullVehicle
    from vehdyn.tire import LinearTire

    L = vehicle.wheelbase
    out = {}
    for name, model in (("LinearBicycle", handling.LinearBicycle(vehicle, SPEED)),
                        ("LateralYawRoll", handling.LateralYawRoll(vehicle, SPEED))):
        r, ay = _linear_gradient(model)
        out[name] = (1.0 - L * r / SPEED) / ay * DEG_PER_G

    def single_track(model):
        def k(A):
            v = [handling.steady_state_cornering(model, lateral_acceleration=a, speed=SPEED) for a in (A, -A)]
            s = [x.steer_angle - L * x.yaw_rate / x.speed for x in v]
            return (s[0] - s[1]) / (2 * A)
        return _richardson(k, quick) * DEG_PER_G

    def full_vehicle(model):
        return full_vehicle_gradient(model, SPEED, quick)

    out["SingleTrack+roll"] = single_track(handling.SingleTrack(vehicle, lateral_load_transfer=True, roll=True))
    no_drag = vehicle.replace(aero__drag_coefficient=0.0)
    linear = [LinearTire.from_vehicle(no_drag, axle) for axle in ("front", "rear")]
    out["FullVehicle (linear tires, no drag)"] = full_vehicle(FullVehicle(no_drag, *linear, tire_lag=False))
    if not quick:
        out["SingleTrack"] = single_track(handling.SingleTrack(vehicle))
        out["SingleTrack+LLT"] = single_track(handling.SingleTrack(vehicle, lateral_load_transfer=True))
        out["FullVehicle"] = full_vehicle(FullVehicle(vehicle, tire_lag=False))
    return out


def every_term_gradients(vehicle, quick):
    """{rung: gradient [deg/g]} of the rungs that carry every term (linear tires with the law's camber
    stiffness and pneumatic trail at the static loads, so that the budget's rows are the same; no drag)."""
    from vehdyn.full_vehicle import FullVehicle
    from vehdyn.handling.axle_tires import camber_stiffness, pneumatic_trail
    from vehdyn.tire import LinearTire

    L = vehicle.wheelbase
    no_drag = vehicle.replace(aero__drag_coefficient=0.0)
    # LinearTire: F_y,ISO = C_g gamma - C alpha per tire, the axle's SAE camber stiffness -2 C_g
    linear = [LinearTire.from_vehicle(no_drag, axle).replace(camber_stiffness=-0.5 * camber_stiffness(vehicle, axle),
                                                             pneumatic_trail=pneumatic_trail(vehicle, axle))
              for axle in ("front", "rear")]

    def steer(model, a):
        if isinstance(model, FullVehicle):
            x0, u0 = model.trim(SPEED, lateral_acceleration=a)
            return u0[model.index("front_steer_angle", "inputs")] - L * x0[model.index("yaw_rate")] / SPEED
        x = handling.steady_state_cornering(model, lateral_acceleration=a, speed=SPEED)
        return x.steer_angle - L * x.yaw_rate / x.speed

    out = {}
    for name, model in (("FullVehicle (linear tires, no drag)", FullVehicle(no_drag, *linear, tire_lag=False)),
                        ("SingleTrack+LLT (linear tires, no drag)",
                         handling.SingleTrack(no_drag, *linear, lateral_load_transfer=True))):
        out[name] = _richardson(lambda A: (steer(model, A) - steer(model, -A)) / (2 * A), quick) * DEG_PER_G
    return out


def at_speed_rows(vehicle, speeds):
    """[row] of the at-speed budget (the full vehicle's speed- and law-dependent rows, its own Magic Formula
    tires, drag) beside the gradient the full vehicle measures from its own steady trims at each speed
    (Richardson-extrapolated from +-0.1 and +-0.2 m/s^2 in both modes: the comparison is at the 1e-4 level)."""
    from vehdyn.full_vehicle import FullVehicle

    model = FullVehicle(vehicle, tire_lag=False)
    rows = []
    for speed in speeds:
        budget = handling.understeer_budget(vehicle, speed)
        measured = full_vehicle_gradient(model, speed, False)
        total = budget.attrs["at_speed_total_deg_per_g"]
        rows.append({"vehicle": vehicle.name, "speed_m_per_s": speed,
                     "road_wheel_total": budget.attrs["road_wheel_total_deg_per_g"],
                     **budget.loc[budget["at_speed"], "deg_per_g"].to_dict(), "at_speed_total": total,
                     "full_vehicle_measured": measured, "difference": measured - total})
    return rows


def run(study: Study) -> None:
    import pandas as pd

    cars = {name: vehdyn.load_vehicle(name) for name in VEHICLES}
    everything = cars["sedan"].replace(
        suspension__front_roll_steer=0.08, suspension__rear_roll_steer=-0.04, suspension__front_camber_gain=0.6,
        suspension__rear_camber_gain=0.4, suspension__front_lateral_force_compliance_steer=-1.0e-6,
        suspension__rear_lateral_force_compliance_steer=0.5e-6,
        suspension__front_aligning_moment_compliance_steer=2.0e-5,
        suspension__rear_aligning_moment_compliance_steer=1.0e-5, name="sedan, every term")
    fig, axes = new_figure(2, 2, width=12.0, height_per_row=4.6)
    rows, measured_rows, at_speed_table = [], [], []
    speeds = (SPEED,) if study.quick else (10.0, SPEED, 30.0)
    for ax, (name, vehicle) in zip(axes.flat, list(cars.items()) + [("sedan, every term", everything)]):
        # the shipped cars at the speed (their full vehicle's rows too); the every-term sedan's rungs run
        # with linear tires and no drag, so its budget is the linear one
        budget = handling.understeer_budget(vehicle, None if vehicle is everything else SPEED)
        # every term at once: the rungs that carry them all (the ladder refuses each that drops one)
        measured = (every_term_gradients if vehicle is everything else measured_gradients)(vehicle, study.quick)
        shown = dict(measured)
        if vehicle is not everything:
            at_speed_table += at_speed_rows(vehicle, speeds)
            # the full vehicle with its own tires and drag, beside the at-speed total (the full run measures
            # it among the rungs already)
            shown.setdefault("FullVehicle", next(r["full_vehicle_measured"] for r in at_speed_table
                                                 if r["vehicle"] == vehicle.name and r["speed_m_per_s"] == SPEED))
        handling.plot_understeer_budget(budget, ax=ax, measured=shown)
        ax.set_title(name, fontsize=9)
        linear = ~budget["at_speed"]
        row = {"vehicle": name, **budget.loc[linear, "deg_per_g"].to_dict(),
               "road_wheel_total": budget.attrs["road_wheel_total_deg_per_g"],
               "hand_wheel_total": budget.attrs["hand_wheel_total_deg_per_g"],
               **budget.loc[~linear, "deg_per_g"].to_dict(),
               "at_speed_total": budget.attrs["at_speed_total_deg_per_g"]}
        rows.append(row)
        for rung, value in measured.items():
            measured_rows.append({"vehicle": name, "rung": rung, "measured_deg_per_g": value,
                                  "budget_deg_per_g": row["road_wheel_total"],
                                  "difference_deg_per_g": value - row["road_wheel_total"]})
    fig.tight_layout()
    study.figure(fig, "understeer_budgets",
                 caption="Understeer budgets (bars; the hand-wheel-only steering row pale) with the road-wheel and "
                         "hand-wheel totals (dashed, dotted) and the gradients the rungs measure at 20 m/s (lines)")
    table = pd.DataFrame(rows).set_index("vehicle")
    table.attrs["units"] = {c: "deg/g" for c in table.columns}
    study.table(table, "understeer_budget", caption="Budget rows and totals [deg/g]")
    measured = pd.DataFrame(measured_rows).set_index(["vehicle", "rung"])
    measured.attrs["units"] = {c: "deg/g" for c in measured.columns}
    study.table(measured, "measured_gradients",
                caption="Understeer gradient each rung measures from its own steady states at 20 m/s against the "
                        "budget's road-wheel total [deg/g]")
    at_speed = pd.DataFrame(at_speed_table).set_index(["vehicle", "speed_m_per_s"])
    at_speed.attrs["units"] = {c: "deg/g" for c in at_speed.columns}
    study.table(at_speed, "at_speed_budget",
                caption="The full vehicle's speed- and law-dependent rows (its Magic Formula tires, drag), the "
                        "at-speed total and the gradient the full vehicle measures from its own steady trims [deg/g]")
    worst = float((at_speed["difference"].abs() / at_speed["full_vehicle_measured"]).max())
    lin = measured.drop("sedan, every term").xs("FullVehicle (linear tires, no drag)",
                                                 level="rung")["difference_deg_per_g"].abs().max()
    every = measured.loc["sedan, every term", "difference_deg_per_g"].abs().max()
    totals = ", ".join(f"{n} {rows[i]['road_wheel_total']:.3f}" for i, n in enumerate(VEHICLES))
    study.text(
        "The shipped files have no roll steer, camber gain or compliance: their budget is the weight distribution "
        f"over the cornering stiffnesses ({totals} "
        "deg/g), and the steering system's compliance doubles to triples it at the hand wheel. The full vehicle with "
        f"linear tires and no drag measures the budget within {lin:.1e} deg/g; the linear rungs carry it exactly. "
        "The nonlinear rungs (Magic Formula tires, drag) are 5-30 % above the file's linear budget: at a speed the "
        "budget adds the full vehicle's own rows (lighter bars; dash-dotted total): the law's cornering stiffness, "
        "drag's longitudinal load transfer through the load sensitivity, drag and pitch with the roll, the tires' "
        "ply steer under the load transfer and turned by the steer, the rolling-resistance couple, the front "
        "rolling resistance turned by the steer and the drive slip. Their total is the full vehicle's measured "
        f"gradient within {worst:.1e} (relative) for the three cars (table at_speed_budget). The fourth panel switches "
        "every term on (roll steer 0.08 / -0.04 rad/rad, "
        "camber gains 0.6 / 0.4 rad/m, compliance steer -1e-6 / 0.5e-6 rad/N and 2e-5 / 1e-5 rad/(N m)); the full "
        "vehicle and the single track with load transfer carry them all (linear tires with the law's camber "
        f"stiffness and trail, no drag) and measure its budget within {every:.1e} deg/g.")


if __name__ == "__main__":
    Study.main(run, __file__)
