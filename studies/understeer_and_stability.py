"""Understeer and directional stability of the linear single-track model.

The understeer gradient K = (m/L)(b/C_f - a/C_r) decides how the steady-state yaw-rate,
lateral-acceleration and sideslip gains vary with speed: an understeering vehicle (K > 0) has a
yaw-rate gain that peaks at the characteristic speed sqrt(L/K); an oversteering one (K < 0) has
gains that grow without bound at the critical speed sqrt(-L/K), above which it is unstable. The
study sweeps the CG position and the front/rear cornering-stiffness balance for the three shipped
vehicles, draws their gains against speed with the characteristic speed marked, and adds an
oversteering variant of the sedan (rear axle stiffness x 0.6) to show the critical speed.
"""

import dataclasses

import numpy as np

import vehdyn
from vehdyn import handling
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.units import GRAVITY

VEHICLES = ("sedan", "compact", "van")


def run(study: Study) -> None:
    import pandas as pd

    n = 21 if study.quick else 101
    params = {name: handling.bicycle_parameters(vehdyn.load_vehicle(name)) for name in VEHICLES}
    sedan = params["sedan"]
    params["sedan, rear C x 0.6 (oversteer)"] = dataclasses.replace(
        sedan, rear_cornering_stiffness=0.6 * sedan.rear_cornering_stiffness)

    # --- understeer gradient against CG position and cornering-stiffness balance
    fig, axes = new_figure(1, 2, width=10.0, height_per_row=3.6)
    ax_cg, ax_c = axes[0]
    fraction = np.linspace(0.30, 0.65, n)  # a / L
    ratio = np.linspace(0.6, 1.6, n)  # C_f / C_r at constant C_f + C_r
    for name in VEHICLES:
        p = params[name]
        L = p.wheelbase
        k_cg = [handling.understeer_gradient_deg_per_g(dataclasses.replace(p, a=f * L, b=(1 - f) * L))
                for f in fraction]
        ax_cg.plot(fraction, k_cg, label=name)
        ax_cg.plot(p.a / L, handling.understeer_gradient_deg_per_g(p), "ko", ms=4)
        total = p.front_cornering_stiffness + p.rear_cornering_stiffness
        k_c = [handling.understeer_gradient_deg_per_g(dataclasses.replace(
            p, front_cornering_stiffness=total * q / (1 + q), rear_cornering_stiffness=total / (1 + q)))
            for q in ratio]
        ax_c.plot(ratio, k_c, label=name)
        ax_c.plot(p.front_cornering_stiffness / p.rear_cornering_stiffness, handling.understeer_gradient_deg_per_g(p),
                  "ko", ms=4)
    for ax in (ax_cg, ax_c):
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_ylabel("understeer gradient [deg/g]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    ax_cg.set_xlabel("CG position a / L [-] (C_f, C_r fixed)")
    ax_c.set_xlabel("cornering stiffness ratio C_f / C_r [-] (C_f + C_r fixed)")
    fig.tight_layout()
    study.figure(fig, "understeer_gradient_sweeps",
                 caption="Understeer gradient against CG position and front/rear cornering-stiffness balance; "
                         "dots: the shipped vehicles")

    # --- gains against speed
    speeds = np.linspace(1.0, 60.0, 60 if study.quick else 300)
    fig, axes = new_figure(3, 1, width=7.0, height_per_row=2.6, sharex=True)
    rows = []
    for name, p in params.items():
        gains = handling.steady_state_gains(p, speeds)
        unstable = speeds >= handling.critical_speed(p)  # no steady state to draw beyond it
        gains = dataclasses.replace(gains, **{f: np.where(unstable, np.nan, getattr(gains, f))
                                              for f in ("yaw_rate", "lateral_acceleration", "sideslip_angle")})
        style = "--" if "oversteer" in name else "-"
        (line,) = axes[0, 0].plot(speeds, gains.yaw_rate, style, label=name)
        axes[1, 0].plot(speeds, gains.lateral_acceleration_g_per_deg, style, color=line.get_color())
        axes[2, 0].plot(speeds, gains.sideslip_angle, style, color=line.get_color())
        vch, vcrit = handling.characteristic_speed(p), handling.critical_speed(p)
        for v, marker in ((vch, "v"), (vcrit, "x")):
            if v < speeds[-1]:
                axes[0, 0].axvline(v, color=line.get_color(), lw=0.8, ls=":")
                if marker == "v":
                    axes[0, 0].plot(v, float(handling.steady_state_gains(p, v).yaw_rate), marker,
                                    color=line.get_color())
        nsp = handling.neutral_steer_point(p)
        rows.append({
            "vehicle": name,
            "understeer_gradient_deg_per_g": handling.understeer_gradient_deg_per_g(p),
            "understeer_gradient": handling.understeer_gradient(p),
            "stability_factor": handling.stability_factor(p),
            "characteristic_speed": vch,
            "critical_speed": vcrit,
            "zero_sideslip_speed": handling.zero_sideslip_speed(p),
            "neutral_steer_point_behind_cg": nsp.behind_cg,
            "static_margin": handling.static_margin(p),
            "yaw_gain_at_25_mps": float(handling.steady_state_gains(p, 25.0).yaw_rate),
        })
    axes[0, 0].set_ylabel("r / delta [1/s]")
    axes[1, 0].set_ylabel("a_y / delta [g/deg]")
    axes[2, 0].set_ylabel("beta / delta [rad/rad]")
    axes[2, 0].set_xlabel("speed [m/s]")
    axes[0, 0].set_ylim(0, 15)
    axes[1, 0].set_ylim(0, 2)
    axes[2, 0].set_ylim(-4, 1)
    for ax in axes[:, 0]:
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    study.figure(fig, "gains_vs_speed",
                 caption="Steady-state gains per unit road-wheel steer against speed; triangles: yaw-rate gain at "
                         "the characteristic speed, dotted lines: characteristic and critical speeds")

    # --- linear handling diagram: steer angle against lateral acceleration
    ay = np.linspace(0.0, 0.4 * GRAVITY, 9 if study.quick else 41)
    fig, axes = new_figure(1, 2, width=10.0, height_per_row=3.4)
    for name, p in params.items():
        style = "--" if "oversteer" in name else "-"
        radius = handling.handling_diagram(p, ay, radius=40.0)
        speed = handling.handling_diagram(p, ay, speed=20.0)
        (line,) = axes[0, 0].plot(ay / GRAVITY, np.rad2deg(radius.steer_angle), style, label=name)
        axes[0, 1].plot(ay / GRAVITY, np.rad2deg(speed.steer_angle), style, color=line.get_color(), label=name)
    axes[0, 0].axhline(np.rad2deg(handling.ackermann_steer_angle(params["sedan"], 40.0)), color="k", lw=0.8, ls=":",
                       label="Ackermann (sedan)")
    axes[0, 0].set_title("constant radius 40 m", fontsize=9)
    axes[0, 1].set_title("constant speed 20 m/s", fontsize=9)
    for ax in axes[0]:
        ax.set_xlabel("lateral acceleration [g]")
        ax.set_ylabel("road-wheel steer angle [deg]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    study.figure(fig, "handling_diagram",
                 caption="Linear handling diagram: road-wheel angle against lateral acceleration; the slope at "
                         "constant radius is the understeer gradient")

    table = pd.DataFrame(rows).set_index("vehicle")
    table.attrs["units"] = {"understeer_gradient_deg_per_g": "deg/g", "understeer_gradient": "rad/(m/s^2)",
                            "stability_factor": "s^2/m^2", "characteristic_speed": "m/s", "critical_speed": "m/s",
                            "zero_sideslip_speed": "m/s", "neutral_steer_point_behind_cg": "m",
                            "static_margin": "-", "yaw_gain_at_25_mps": "1/s"}
    study.table(table, "understeer_summary", caption="Understeer and stability numbers (inf: none)")
    k = {r["vehicle"]: r["understeer_gradient_deg_per_g"] for r in rows}
    vch_text = ", ".join(f"{r['characteristic_speed']:.1f}" for r in rows[:len(VEHICLES)])
    margins = ", ".join(f"{r['vehicle']} {100 * r['static_margin']:.1f} %" for r in rows[:len(VEHICLES)])
    study.text(
        f"The shipped vehicles understeer mildly ({', '.join(f'{n} {k[n]:.2f} deg/g' for n in VEHICLES)}), so "
        f"the yaw-rate gain keeps rising up to characteristic speeds of {vch_text} m/s. "
        f"Moving the CG back by the static margin ("
        f"{margins} of the wheelbase) "
        f"makes each neutral; softening the rear axle makes it oversteer: the sedan with 40 % less rear "
        f"cornering stiffness has K = "
        f"{k['sedan, rear C x 0.6 (oversteer)']:.2f} deg/g and becomes unstable above "
        f"{rows[-1]['critical_speed']:.1f} m/s. Gravity g = {GRAVITY} m/s^2.")


if __name__ == "__main__":
    Study.main(run, __file__)
