"""Off-road: wheels and tires on deformable soil (Bekker, Janosi-Hanamoto, Wong-Reece).

(1) Sinkage, drawbar pull, torque and tractive efficiency against slip of a rigid wheel
(r = 0.3 m, b = 0.2 m, W = 1.5 kN) on each shipped soil (data/soils.toml, Wong 2008 Table 2.3 and
the Lunar Sourcebook), with the Wong-Reece stress distribution; a wheel that cannot carry its load
before sinking to its axle is reported stuck. (2) The Wong-Reece integration against Bekker's
closed-form static sinkage and compaction resistance where their assumptions hold (zero slip,
maximum stress at the bottom, small sinkage). (3) Rigid wheel against flexible tire: the sedan's
tire at its corner load, at road inflation and aired down, in the rigid or elastic (flat-contact)
mode that the inflation plus carcass pressure selects. (4) A launch of the sedan (rear drive,
wheel-spin states) on dry sand and on sandy loam (road inflation, and aired down) against asphalt
(Fiala tires from the vehicle file): acceleration, wheel slip and rear sinkage, against the traction limit: the rear tires' peak
drawbar pull less the motion resistance of the free-rolling (towed) front tires.
"""

from __future__ import annotations

import dataclasses

import numpy as np

import vehdyn
from vehdyn.handling import SingleTrack
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.tire import tire_for_vehicle
from vehdyn.tire.terramechanics import (FlexibleWheel, RigidWheel, SoftSoilTire, SoftSoilTireGeometry,
                                        compaction_resistance, load_soil, rigid_wheel_sinkage, shipped_soils)
from vehdyn.tire.terramechanics.curves import plot_soil_curves

G = vehdyn.units.GRAVITY


def run(study: Study) -> None:
    import pandas as pd

    slips = np.linspace(-1.0, 1.0, 41 if study.quick else 201)
    soils = {name: load_soil(name) for name in shipped_soils()}

    # (1) curves on every shipped soil
    curves = {name: RigidWheel(radius=0.3, width=0.2, soil=soil).solve(1500.0, slips) for name, soil in soils.items()}
    study.figure(plot_soil_curves(curves), "soil_curves",
                 caption="Rigid wheel r = 0.3 m, b = 0.2 m, W = 1.5 kN on the shipped soils (Wong-Reece); "
                         "stuck points left out")
    rows = []
    for name, r in curves.items():
        best = int(np.argmax(np.where(r.stuck, -np.inf, r.drawbar_pull)))
        all_stuck = bool(r.stuck.all())
        rows.append({"soil": name, "sinkage_at_zero_slip_mm": float(np.interp(0.0, r.slip, r.sinkage)) * 1e3,
                     "peak_drawbar_pull_over_load": np.nan if all_stuck else r.drawbar_pull[best] / 1500.0,
                     "slip_at_peak": np.nan if all_stuck else r.slip[best], "stuck_points": int(r.stuck.sum())})
    study.table(pd.DataFrame(rows).set_index("soil"), "soil_summary", caption="Per soil: sinkage, peak drawbar pull")

    # (2) Wong-Reece against Bekker's closed forms (c1 = c2 = 0, zero slip, z0/D about 0.5 %)
    rows = []
    for name in ("lunar_soil", "dry_sand", "sandy_loam"):
        wheel = RigidWheel(radius=0.3, width=0.2, soil=soils[name], c1=0.0, c2=0.0)
        load = float(wheel.supported_load(0.003))
        r = wheel.solve(load, 0.0)
        rows.append({"soil": name, "n": soils[name].n, "load_N": load,
                     "sinkage_quadrature_mm": float(r.sinkage) * 1e3,
                     "sinkage_bekker_mm": rigid_wheel_sinkage(soils[name], load, 0.6, 0.2) * 1e3,
                     "resistance_quadrature_N": float(r.motion_resistance),
                     "resistance_bekker_N": compaction_resistance(soils[name], load, 0.6, 0.2)})
    frame = pd.DataFrame(rows).set_index("soil")
    frame["sinkage_difference"] = frame["sinkage_quadrature_mm"] / frame["sinkage_bekker_mm"] - 1
    study.table(frame, "closed_forms", caption="Wong-Reece integration against Bekker's closed forms "
                "(Bekker's (3 - n)/3 factor is exact at n = 1 only)")

    # (3) rigid wheel against flexible tire, the sedan's tire at its corner load
    vehicle = vehdyn.load_vehicle("sedan")
    corner = 0.25 * vehicle.mass.mass * G
    radius, width = vehicle.tires.rolling_radius, 0.205
    tires = {"rigid": None, "2.2 bar": 2.2e5, "0.8 bar": 0.8e5}
    fig, axes = new_figure(1, 2, width=10.0, height_per_row=3.0)
    axes = np.asarray(axes).reshape(-1)
    rows = []
    for soil_name in ("sandy_loam", "lete_sand"):
        for label, pressure in tires.items():
            wheel = FlexibleWheel(geometry=SoftSoilTireGeometry(radius=radius, width=width, inflation_pressure=pressure,
                                                                carcass_pressure=0.3e5 if pressure else 0.0),
                                  soil=soils[soil_name])
            r = wheel.solve(corner, slips[slips >= 0])
            ax = axes[0] if soil_name == "sandy_loam" else axes[1]
            ax.plot(r.slip, r.drawbar_pull / corner, label=f"{label} ({r.mode[0]} mode)")
            at = wheel.solve(corner, 0.2)
            rows.append({"soil": soil_name, "tire": label, "mode": str(at.mode), "sinkage_mm": float(at.sinkage) * 1e3,
                         "motion_resistance_N": float(at.motion_resistance),
                         "drawbar_pull_over_load_at_s_0.2": float(at.drawbar_pull) / corner})
    for ax, soil_name in zip(axes, ("sandy_loam", "lete_sand")):
        ax.set_title(f"{soil_name}, W = {corner:.0f} N")
        ax.set_xlabel("slip s [-]")
        ax.set_ylabel("drawbar pull / load [-]")
        ax.legend(fontsize=8)
        ax.grid(True, alpha=0.3)
    study.figure(fig, "rigid_vs_flexible", caption="Sedan tire on soft soil: rigid wheel, road inflation, aired down")
    study.table(pd.DataFrame(rows).set_index(["soil", "tire"]), "rigid_vs_flexible",
                caption="Mode, sinkage and resistance at slip 0.2")

    # (4) launch of the sedan: asphalt against sand
    duration = 2.0 if study.full else 0.4  # each soft-soil rhs solves the Wong-Reece wheel: ~10-30 ms
    t = np.linspace(0.0, duration, int(duration / 0.02) + 1)
    torque = 1500.0
    geometry = SoftSoilTireGeometry(radius=radius, width=width, inflation_pressure=2.2e5, carcass_pressure=0.3e5)
    surfaces = {"asphalt (Fiala)": (tire_for_vehicle(vehicle, "front", "fiala"), tire_for_vehicle(vehicle, "rear", "fiala"))}
    for soil_name in ("sandy_loam", "dry_sand"):
        tire = SoftSoilTire(geometry, soils[soil_name])
        surfaces[f"{soil_name}, 2.2 bar"] = (tire, tire)
    aired_down = SoftSoilTire(dataclasses.replace(geometry, inflation_pressure=0.8e5), soils["sandy_loam"])
    surfaces["sandy_loam, 0.8 bar"] = (aired_down, aired_down)  # the elastic (flat-contact) mode
    fig, axes = new_figure(2, 2, width=10.0, height_per_row=2.6)
    rows = []
    rear_static = vehicle.mass.mass * G * vehicle.geometry.a / vehicle.wheelbase
    front_static = vehicle.mass.mass * G - rear_static
    for number, (label, (front, rear)) in enumerate(surfaces.items()):
        color = f"C{number}"
        model = SingleTrack(vehicle, front, rear, wheel_spin=True, tire_lag=False)
        result = vehdyn.simulate(model, t, {"rear_drive_torque": torque}, x0=model.straight_running(1.0), method="LSODA",
                                 rtol=1e-5, atol=1e-7)
        ax_ = result["longitudinal_acceleration"]
        slip_ratio = result["rear_slip_ratio"]
        axes[0, 0].plot(t, ax_, color=color, label=label)
        axes[0, 1].plot(t, result["longitudinal_velocity"], color=color, label=label)
        axes[1, 0].plot(t, slip_ratio / (1 + np.abs(slip_ratio)), color=color, label=label)
        row = {"surface": label, "peak_a_x": float(np.max(ax_)), "final_speed": float(result["longitudinal_velocity"][-1])}
        if isinstance(rear, SoftSoilTire):
            state = rear.evaluate(0.5 * rear_static, slip_ratio)
            axes[1, 1].plot(t, state.sinkage * 1e3, color=color, label=label)
            peak = rear.evaluate(0.5 * rear_static, np.linspace(0.0, 20.0, 201)).drawbar_pull.max()
            towed = front.evaluate(0.5 * front_static, np.linspace(-0.5, 0.5, 2001))  # towed: zero torque
            front_resistance = -float(towed.drawbar_pull[np.argmin(np.abs(towed.torque))])
            row.update(rear_sinkage_mm=float(state.sinkage[-1]) * 1e3, front_resistance=2 * front_resistance,
                       traction_limit_a_x=2 * (peak - front_resistance) / vehicle.mass.mass)
        rows.append(row)
    for ax, ylabel in zip(axes.flat, ("a_x [m/s^2]", "speed u [m/s]", "rear slip s [-]", "rear sinkage [mm]")):
        ax.set_ylabel(ylabel)
        ax.set_xlabel("time [s]")
        ax.legend(fontsize=8)
    study.figure(fig, "launch", caption=f"Sedan launch, {torque:.0f} N*m on the rear axle: asphalt against soft soil")
    study.table(pd.DataFrame(rows).set_index("surface"), "launch",
                caption="Launch: peak acceleration against the traction limit 2 (max DP_rear - R_front) / m at the "
                        "static loads (R_front: motion resistance of a towed front tire, at zero torque)")
    study.text("On soft soil the drawbar pull peaks at a moderate slip and the sinkage grows with slip (slip "
               "sinkage through theta_m = (c1 + c2 s) theta_1); on loose dry sand a street tire's net traction "
               "is a small fraction of its load, so the launch is traction-limited far below the asphalt value. "
               "The free-rolling front tires run as towed wheels: their wheel-spin balance carries the tire's "
               "rolling-resistance moment M_y = r F_x - T, so they settle at zero soil torque with the motion "
               "resistance of a towed wheel, which the rear tires must overcome before the car accelerates: at "
               "road inflation the sedan bogs down on sandy loam and on dry sand; aired down to 0.8 bar its tires "
               "run flattened (elastic mode) with less sinkage and compaction resistance, and it drives off.")


if __name__ == "__main__":
    Study.main(run, __file__)
