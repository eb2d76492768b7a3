"""Step steer: transient yaw-rate and lateral-acceleration responses and ISO 7401 metrics against speed.

A step of the front road-wheel angle (applied over 0.15 s, as a driver or a steering robot would,
sized for 0.3 g in steady state) is simulated with the exact discretization of the linear
bicycle model, for the three shipped vehicles, with and without tire lag (relaxation lengths from
their tire files). The ISO 7401 metrics (response time to 90 %, peak response time, overshoot,
counted from the instant the steer passes 50 %) are computed from the simulation results, the
same way they would be from a test or from a nonlinear model. The TB factor (peak response time
times steady-state sideslip angle) summarises the yaw transient in one number.
"""

import numpy as np

import vehdyn
from vehdyn import handling, procedures
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.units import GRAVITY

VEHICLES = ("sedan", "compact", "van")
RAMP_TIME = 0.15  # s
TARGET_AY = 0.3 * GRAVITY


def _step(t, amplitude, start=0.5):
    return amplitude * np.clip((t - start) / RAMP_TIME, 0.0, 1.0)


def run(study: Study) -> None:
    import pandas as pd

    speeds = np.array([15.0, 25.0, 35.0]) if study.quick else np.linspace(10.0, 40.0, 13)
    t = np.linspace(0.0, 4.0, 801 if study.quick else 4001)
    rows = []
    histories = {}
    for name in VEHICLES:
        vehicle = vehdyn.load_vehicle(name)
        for lag in (False, True):
            for u in speeds:
                car = handling.LinearBicycle(vehicle, float(u), tire_lag=lag)
                gain = float(handling.steady_state_gains(car).lateral_acceleration)
                delta = TARGET_AY / gain
                res = vehdyn.simulate(car, t, {"front_steer_angle": _step(t, delta)}, method="exact")
                m = procedures.step_steer_metrics(res, signals=("yaw_rate", "lateral_acceleration", "sideslip_angle"),
                                                steady_window=1.0)
                yaw, ay, beta = m["yaw_rate"], m["lateral_acceleration"], m["sideslip_angle"]
                rows.append({
                    "vehicle": name, "tire_lag": lag, "speed": u, "steer_angle_deg": np.rad2deg(delta),
                    "yaw_rate_steady_deg_s": np.rad2deg(float(yaw.steady_state_value)),
                    "yaw_rate_response_time": float(yaw.response_time),
                    "yaw_rate_peak_response_time": float(yaw.peak_response_time),
                    "yaw_rate_overshoot_pct": 100 * float(yaw.overshoot),
                    "lateral_acceleration_response_time": float(ay.response_time),
                    "lateral_acceleration_overshoot_pct": 100 * float(ay.overshoot),
                    "tb_factor_s_deg": float(yaw.peak_response_time) * np.rad2deg(abs(float(beta.steady_state_value))),
                })
                if u == speeds[len(speeds) // 2]:
                    histories[(name, lag)] = res

    # --- time histories at the middle speed
    u_mid = speeds[len(speeds) // 2]
    fig, axes = new_figure(3, 1, width=7.0, height_per_row=2.4, sharex=True)
    for (name, lag), res in histories.items():
        style = "--" if lag else "-"
        color = f"C{VEHICLES.index(name)}"
        label = f"{name}{' (tire lag)' if lag else ''}"
        axes[0, 0].plot(res.time, np.rad2deg(res["front_steer_angle"]), style, color=color, label=label)
        axes[1, 0].plot(res.time, np.rad2deg(res["yaw_rate"]), style, color=color)
        axes[2, 0].plot(res.time, res["lateral_acceleration"] / GRAVITY, style, color=color)
    axes[0, 0].set_ylabel("road-wheel angle [deg]")
    axes[1, 0].set_ylabel("yaw rate [deg/s]")
    axes[2, 0].set_ylabel("lateral acceleration [g]")
    axes[2, 0].set_xlabel("time [s]")
    axes[0, 0].legend(fontsize=7, ncol=2)
    for ax in axes[:, 0]:
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    study.figure(fig, "step_steer_time_histories",
                 caption=f"Step steer at {u_mid:g} m/s to 0.3 g steady state (0.15-s ramp); dashed: with tire lag")

    table = pd.DataFrame(rows)
    # --- metrics against speed
    fig, axes = new_figure(2, 2, width=10.0, height_per_row=3.0, sharex=True)
    panels = (("yaw_rate_response_time", "yaw-rate response time [s]"),
              ("yaw_rate_peak_response_time", "yaw-rate peak response time [s]"),
              ("yaw_rate_overshoot_pct", "yaw-rate overshoot [%]"),
              ("lateral_acceleration_response_time", "lateral-acc. response time [s]"))
    for ax, (column, label) in zip(axes.ravel(), panels):
        for name in VEHICLES:
            for lag in (False, True):
                sel = table[(table.vehicle == name) & (table.tire_lag == lag)]
                ax.plot(sel.speed, sel[column], "--" if lag else "-", marker="o", ms=3,
                        color=f"C{VEHICLES.index(name)}", label=f"{name}{' (lag)' if lag else ''}")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("speed [m/s]")
    axes[0, 0].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    study.figure(fig, "iso7401_metrics_vs_speed", caption="ISO 7401 step-steer metrics against speed")

    table = table.set_index(["vehicle", "tire_lag", "speed"])
    table.attrs["units"] = {"speed": "m/s", "steer_angle_deg": "deg", "yaw_rate_steady_deg_s": "deg/s",
                            "yaw_rate_response_time": "s", "yaw_rate_peak_response_time": "s",
                            "yaw_rate_overshoot_pct": "%", "lateral_acceleration_response_time": "s",
                            "lateral_acceleration_overshoot_pct": "%", "tb_factor_s_deg": "s*deg"}
    study.table(table, "iso7401_metrics", caption="ISO 7401 metrics (times from 50 % steer)")
    lagged = table.xs(True, level="tire_lag")["yaw_rate_response_time"]
    plain = table.xs(False, level="tire_lag")["yaw_rate_response_time"]
    delay = (lagged - plain).groupby(level="vehicle").mean()
    study.text("Tire lag changes the yaw-rate response time by "
               + ", ".join(f"{v * 1000:+.0f} ms ({k})" for k, v in delay.items())
               + " on average over the speeds. It does not simply slow the vehicle down: the lag of the front "
               "axle delays the yaw build-up, but the lag of the rear axle delays the rear force that resists it, "
               "so the yaw rate rises sooner and overshoots more. The effect is largest at low speed, where the "
               "lag time constant sigma/u is longest. The yaw-rate overshoot grows with speed as the yaw mode's "
               "damping falls.")


if __name__ == "__main__":
    Study.main(run, __file__)
