"""FMVSS 126 compliance of the shipped passenger cars with and without ESC, on two vehicle models.

vehdyn.procedures.fmvss126 runs the sine-with-dwell series of 49 CFR 571.126 S7.9 on each car's
nonlinear single-track model and, with ``vehdyn report --full``, on its full vehicle model
(vehdyn.full_vehicle.FullVehicle: roll, lateral load transfer, four wheels) at 80 km/h: amplitudes from 1.5 A in steps of 0.5 A up to the greater
of 6.5 A and 270 degrees of hand-wheel angle, steered counter-clockwise and clockwise, and checks
S5.2: the yaw rate 1.00 s and 1.75 s after completion of steer within 35 % and 20 % of its peak,
and for runs of 5 A or more a lateral displacement of at least 1.83 m 1.07 s after the beginning of
steer. Each car runs alone and with vehdyn.chassis.ESC (yaw-rate reference of the linear bicycle
limited by mu g / u, sideslip guard) closed around the model by vehdyn.interconnect.ClosedLoop: on the
single track one-wheel braking enters as a yaw moment and an axle force, on the full vehicle the
ESC brakes the wheel itself (ESC(car, corners=True)). The results describe the models, not a
certification. Every run is compiled (numba), controller included. The complete series runs on the
single track; on the full vehicle the 5 A and 6.5 A runs (both directions) by default and the
complete series with --full. (Without numba the runs are numpy batches: then the single track runs
only the 5 A and 6.5 A runs and the full vehicle none, unless --full.)
"""

import numpy as np

import vehdyn
from vehdyn.simulation.compiled import numba_available
from vehdyn.chassis import ESC
from vehdyn.interconnect import ClosedLoop
from vehdyn.handling import SingleTrack, steady_state_cornering
from vehdyn.procedures import fmvss126, sine_with_dwell
from vehdyn.plotting import new_figure
from vehdyn.report import Study

G = vehdyn.units.GRAVITY


def run(study: Study) -> None:
    import pandas as pd

    # the full vehicle (its closed loops compile for ~30 s on first use) only with --full, where it
    # runs the complete series; tests/chassis check it with ESC at 6.5 A
    subset = {} if study.full else dict(amplitude_multiples=[5.0, 6.5])
    subsets = {"single_track": {} if numba_available() else subset}
    if study.full:
        subsets["full_vehicle"] = {}
    frames, verdicts = [], []
    for plant, options in subsets.items():
        for name in vehdyn.shipped_vehicles("passenger_car"):
            car = vehdyn.load_vehicle(name)
            for controller in (None, ESC(car, corners=plant == "full_vehicle")):
                result = fmvss126(car, controller, plant=plant, **options)
                frame = result.to_frame()
                frame.insert(0, "esc", controller is not None)
                frame.insert(0, "model", plant)
                frame.insert(0, "vehicle", name)
                frames.append(frame)
                verdicts.append({"vehicle": name, "model": plant, "esc": controller is not None,
                                 "runs": len(result.runs), "passed": result.passed,
                                 "failed_runs": int(sum(not r["passed"] for r in result.runs))})
    table = pd.concat(frames, ignore_index=True)
    table.attrs["units"] = frames[0].attrs["units"]
    columns = ["vehicle", "model", "esc", "direction", "amplitude_multiple", "hand_wheel_amplitude_deg",
               "yaw_rate_ratio_1000ms", "yaw_rate_ratio_1750ms", "lateral_displacement", "passed"]
    study.table(table[columns], "runs", caption="Every run of the series (limits 0.35, 0.20, >= 1.83 m from 5 A)")
    summary = pd.DataFrame(verdicts)
    study.table(summary, "verdict", caption="49 CFR 571.126 S5.2 verdict per car and model, without and with ESC")
    for plant, options in subsets.items():
        study.text(f"{plant.replace('_', ' ').capitalize()}: "
                   + ("the 5 A and 6.5 A runs, both directions (amplitudes where the cars without ESC fail; "
                      "`vehdyn report --full` runs the complete series)." if options else
                      "the complete series (1.5 A to 6.5 A or 270 deg, both directions)."))
    for plant in subsets:
        study.text(f"{plant.replace('_', ' ').capitalize()}, without ESC: "
                   + ", ".join(f"{v['vehicle']} {'passes' if v['passed'] else 'fails'}"
                               for v in verdicts if not v["esc"] and v["model"] == plant)
                   + ". With ESC: " + ", ".join(f"{v['vehicle']} {'passes' if v['passed'] else 'fails'}"
                                               for v in verdicts if v["esc"] and v["model"] == plant) + ".")

    # time histories of the sedan at 6.5 A, alone and with ESC
    car = vehdyn.load_vehicle("sedan")
    plant = SingleTrack(car)
    speed = float(vehdyn.units.kmh_to_ms(80.0))
    a = steady_state_cornering(plant, lateral_acceleration=0.3 * G, speed=speed).steer_angle
    steer = sine_with_dwell(6.5 * a)
    t = np.linspace(0.0, steer.completion_of_steer + 2.0, 301)
    fig, axes = new_figure(3, 1, height_per_row=2.4)
    for label, model in (("no ESC", plant), ("ESC", ClosedLoop(plant, ESC(car)))):
        x0 = model.state_vector(dict(zip(plant.state_names, plant.straight_running(speed))))
        r = vehdyn.simulate(model, t, {"front_steer_angle": steer}, x0=x0, method="RK45", rtol=1e-5, atol=1e-8,
                            max_step=0.02)
        axes[0, 0].plot(t, np.degrees(r["yaw_rate"]), label=label)
        axes[1, 0].plot(t, np.degrees(r["sideslip_angle"]), label=label)
        if label == "ESC":
            for wheel in ("front_left", "front_right", "rear_left", "rear_right"):
                axes[2, 0].plot(t, r[f"{wheel}_esc_brake_torque"], label=wheel.replace("_", " "))
    for ax, cos in ((axes[0, 0], steer.completion_of_steer), (axes[1, 0], steer.completion_of_steer)):
        for dt in (1.0, 1.75):
            ax.axvline(cos + dt, color="0.6", lw=0.8, ls=":")
    axes[0, 0].set_ylabel("yaw rate [deg/s]")
    axes[1, 0].set_ylabel("sideslip [deg]")
    axes[2, 0].set_ylabel("ESC brake torque [N m]")
    axes[2, 0].set_xlabel("time [s]")
    axes[0, 0].legend(fontsize=8)
    axes[2, 0].legend(fontsize=7, ncol=2)
    axes[0, 0].set_title("sedan, sine with dwell at 6.5 A, 80 km/h (dotted: 1.00 s and 1.75 s after completion of steer)")
    study.figure(fig, "sedan_6p5A", caption="Yaw rate, sideslip and the ESC's one-wheel brake torques")


if __name__ == "__main__":
    Study.main(run, __file__)
