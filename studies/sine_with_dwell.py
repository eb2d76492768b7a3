"""Sine with dwell (FMVSS 126) of the shipped vehicles without stability control.

The nonlinear single-track model with each vehicle's Magic Formula tires enters at 80 km/h and
coasts through the FMVSS 126 sine with dwell (0.7 Hz, 0.5 s dwell at the second peak). The steer
amplitude is a multiple of A, the road-wheel angle that gives 0.3 g in a steady turn at 80 km/h
(found with vehdyn.handling.steady_state_cornering in place of the slowly increasing steer test),
from 1.5 A up to 6.5 A as the standard's series does. Reported per run: the yaw-rate ratios 1.0 s
and 1.75 s after completion of steer (limits 35 % and 20 %) and the lateral displacement 1.07 s
after the beginning of steer (at least 1.83 m from 5 A on). A single-track model has no roll and no
lateral load transfer, which make a real vehicle more stable at the limit: the results show the
model's behaviour, not a certification.
"""

import numpy as np

import vehdyn
from vehdyn.handling import SingleTrack, steady_state_cornering
from vehdyn.procedures import sine_with_dwell, sine_with_dwell_metrics
from vehdyn.plotting import new_figure
from vehdyn.report import Study

G = vehdyn.units.GRAVITY


def run(study: Study) -> None:
    import pandas as pd

    speed = float(vehdyn.units.kmh_to_ms(80.0))
    vehicles = ["sedan"] if study.quick else vehdyn.shipped_vehicles("passenger_car")
    multiples = [3.0, 6.5] if study.quick else [1.5, 3.0, 4.0, 5.0, 5.5, 6.0, 6.5]
    rows = []
    fig, axes = new_figure(2, 1, height_per_row=2.8)
    for name in vehicles:
        model = SingleTrack(vehdyn.load_vehicle(name))
        a = steady_state_cornering(model, lateral_acceleration=0.3 * G, speed=speed).steer_angle
        for multiple in multiples:
            steer = sine_with_dwell(multiple * a)
            t = np.linspace(0.0, steer.completion_of_steer + 2.0, 301)
            r = vehdyn.simulate(model, t, {"front_steer_angle": steer}, x0=model.straight_running(speed),
                                method="RK45", rtol=1e-5, atol=1e-8, max_step=0.02)
            m = sine_with_dwell_metrics(r, steer)
            rows.append({"vehicle": name, "amplitude_multiple": multiple, "road_wheel_amplitude": np.degrees(multiple * a),
                         "yaw_rate_ratio_1000ms": m.yaw_rate_ratio_1000ms,
                         "yaw_rate_ratio_1750ms": m.yaw_rate_ratio_1750ms,
                         "lateral_displacement": m.lateral_displacement, "stable": m.stable})
            if name == vehicles[0]:
                axes[0, 0].plot(t, np.degrees(r["front_steer_angle"] if "front_steer_angle" in r.output_names
                                              else steer(t)), label=f"{multiple:g} A")
                axes[1, 0].plot(t, np.degrees(r["yaw_rate"]), label=f"{multiple:g} A")
    axes[0, 0].set_ylabel("road-wheel steer [deg]")
    axes[1, 0].set_ylabel("yaw rate [deg/s]")
    axes[1, 0].set_xlabel("time [s]")
    axes[0, 0].legend(fontsize=7, ncol=4)
    axes[0, 0].set_title(f"{vehicles[0]}: sine with dwell at 80 km/h")
    study.figure(fig, "time_histories", caption="Steer input and yaw-rate response (SAE: positive turning right)")
    frame = pd.DataFrame(rows)
    frame.attrs["units"] = {"road_wheel_amplitude": "deg", "lateral_displacement": "m", "yaw_rate_ratio_1000ms": "-",
                            "yaw_rate_ratio_1750ms": "-"}
    study.table(frame, "metrics", caption="FMVSS 126 metrics (limits: 0.35 at 1.0 s, 0.20 at 1.75 s, >= 1.83 m)")
    unstable = frame[~frame["stable"]]
    study.text("Runs that fail the yaw-rate ratio criteria: " + (", ".join(
        f"{v} at {m:g} A" for v, m in zip(unstable["vehicle"], unstable["amplitude_multiple"])) or "none") + ".")


if __name__ == "__main__":
    Study.main(run, __file__)
