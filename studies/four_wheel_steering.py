"""Four-wheel steering: the zero-sideslip rear-steer ratio and what it does to the vehicle's response.

Proportional rear steer delta_r = k(u) delta_f with the speed-dependent ratio that keeps the
steady-state sideslip at the CG zero: opposite phase at low speed (k -> -b/a, a tighter turn),
in phase above the zero-sideslip speed (k -> a C_f / (b C_r), a calmer, less yaw-sensitive car).
The study compares front steering only (2WS) with this 4WS law for the three shipped vehicles:
the ratio against speed, the steady sideslip and yaw-rate gains, the yaw-rate frequency response
at 30 m/s, and a step steer at 30 m/s, all through the same LinearBicycle with the rear-steer law
plugged in as a static gain in series (``proportional_rear_steer``).
"""

import numpy as np

import vehdyn
from vehdyn import handling
from vehdyn.plotting import new_figure
from vehdyn.report import Study

VEHICLES = ("sedan", "compact", "van")


def run(study: Study) -> None:
    speeds = np.linspace(2.0, 50.0, 25 if study.quick else 97)

    fig, axes = new_figure(3, 1, width=7.0, height_per_row=2.5, sharex=True)
    tables = []
    for j, name in enumerate(VEHICLES):
        vehicle = vehdyn.load_vehicle(name)
        comp = handling.compare_four_wheel_steering(vehicle, speeds, frequency_hz=1.0)
        color = f"C{j}"
        axes[0, 0].plot(speeds, comp.rear_steer_ratio, color=color, label=name)
        axes[1, 0].plot(speeds, comp.sideslip_gain_2ws, color=color, label=f"{name} 2WS")
        axes[1, 0].plot(speeds, comp.sideslip_gain_4ws, "--", color=color, label=f"{name} 4WS")
        axes[2, 0].plot(speeds, comp.yaw_rate_gain_2ws, color=color)
        axes[2, 0].plot(speeds, comp.yaw_rate_gain_4ws, "--", color=color)
        frame = comp.to_frame()
        frame.insert(0, "vehicle", name)
        tables.append(frame)
    axes[0, 0].axhline(0.0, color="k", lw=0.8)
    axes[0, 0].set_ylabel("k = delta_r / delta_f [-]")
    axes[1, 0].set_ylabel("beta / delta_f [rad/rad]")
    axes[2, 0].set_ylabel("r / delta_f [1/s]")
    axes[2, 0].set_xlabel("speed [m/s]")
    axes[0, 0].legend(fontsize=7)
    axes[1, 0].legend(fontsize=6, ncol=3)
    for ax in axes[:, 0]:
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    study.figure(fig, "zero_sideslip_ratio_and_gains",
                 caption="Zero-sideslip rear-steer ratio, and steady sideslip and yaw-rate gains with front "
                         "steering only (solid) and with 4WS (dashed)")

    # --- frequency response and step steer at 30 m/s
    u = 30.0
    omega = 2 * np.pi * np.logspace(-1.3, 0.7, 120 if study.quick else 400)
    t = np.linspace(0.0, 3.0, 301 if study.quick else 1501)
    fig, axes = new_figure(2, 2, width=10.0, height_per_row=3.0)
    for j, name in enumerate(VEHICLES):
        car = handling.LinearBicycle(vehdyn.load_vehicle(name), u)
        four = handling.proportional_rear_steer(car)
        color = f"C{j}"
        for model, style, label in ((car, "-", "2WS"), (four, "--", "4WS")):
            fr = model.frequency_response(omega, outputs=["yaw_rate"], inputs=["front_steer_angle"])
            h = fr["yaw_rate", "front_steer_angle"]
            axes[0, 0].loglog(omega / (2 * np.pi), np.abs(h), style, color=color, label=f"{name} {label}")
            axes[1, 0].semilogx(omega / (2 * np.pi), np.rad2deg(np.unwrap(np.angle(h))), style, color=color)
            res = vehdyn.simulate(model, t, {"front_steer_angle": np.deg2rad(1.0)}, method="exact")
            axes[0, 1].plot(t, np.rad2deg(res["yaw_rate"]), style, color=color, label=f"{name} {label}")
            axes[1, 1].plot(t, np.rad2deg(res["sideslip_angle"]), style, color=color)
    axes[0, 0].set_ylabel("|r / delta_f| [1/s]")
    axes[1, 0].set_ylabel("phase of r / delta_f [deg]")
    axes[1, 0].set_xlabel("frequency [Hz]")
    axes[0, 1].set_ylabel("yaw rate [deg/s]")
    axes[1, 1].set_ylabel("sideslip angle [deg]")
    axes[1, 1].set_xlabel("time [s]")
    axes[0, 0].legend(fontsize=6, ncol=2)
    for ax in axes.ravel():
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    study.figure(fig, "response_at_30_mps",
                 caption=f"Yaw-rate frequency response and 1-deg step steer at {u:g} m/s, 2WS (solid) and "
                         "zero-sideslip 4WS (dashed)")

    import pandas as pd

    table = pd.concat(tables).reset_index().set_index(["vehicle", "speed"])
    table.attrs["units"] = tables[0].attrs["units"]
    at = table.xs(30.0, level="speed") if 30.0 in table.index.get_level_values("speed") else table.groupby(
        level="vehicle").last()
    slow = table.groupby(level="vehicle").first()
    shown = table if study.quick else table.iloc[::4]
    shown.attrs["units"] = table.attrs["units"]
    study.table(shown, "two_vs_four_wheel_steering", caption="2WS against zero-sideslip 4WS (phases at 1 Hz)")
    study.text("At speed the zero-sideslip law steers the rear wheels in phase and cuts the yaw-rate gain to "
               + ", ".join(f"{100 * r.yaw_rate_gain_4ws / r.yaw_rate_gain_2ws:.0f} % ({v})" for v, r in at.iterrows())
               + " of front steering alone at 30 m/s, while the sideslip stays zero in the steady state; at "
               f"{speeds[0]:g} m/s it steers them in opposite phase and multiplies the yaw response by "
               + ", ".join(f"{r.yaw_rate_gain_4ws / r.yaw_rate_gain_2ws:.2f} ({v})" for v, r in slow.iterrows())
               + ", i.e. shortens the turning circle by that factor.")


if __name__ == "__main__":
    Study.main(run, __file__)
