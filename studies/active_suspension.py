"""Active and semi-active suspension of the quarter car: skyhook, groundhook, LQR against the passive car.

The sedan's front corner (vehdyn.ride.QuarterCar(vehicle, "front")) on an ISO 8608 class-C road at 20 m/s,
whose road velocity is white with one-sided PSD (2 pi n0)^2 G_d(n0) V. Ideal skyhook, groundhook and
hybrid dampers and an LQR controller (designed through LinearModel.to_control() and python-control's
lqr) are compared with the passive car on comfort (r.m.s. body acceleration), suspension travel and
road holding (r.m.s. dynamic tire load), exactly, from the Lyapunov equation with the road's
shaping filter appended (vehdyn.ride.random_vibration). A clipped semi-active
skyhook damper, which is nonlinear, is simulated in the time domain on a road synthesized by the
same shaping filter (synthesize_profile(..., method="white_noise")); the passive car simulated the
same way shows the statistical error of that estimate. Last, the response to a single bump.
"""

import numpy as np

import vehdyn
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.ride import (
    QuarterCar,
    SemiActiveQuarterCar,
    compare_suspensions,
    groundhook,
    lqr_quarter_car,
    random_response,
    relative_quarter_car,
    skyhook,
)
from vehdyn.road import RoadSpectrum, synthesize_profile

ROAD = RoadSpectrum.from_class("C")  # Gd(n0) = 256e-6 m^3, waviness 2
SPEED = 20.0  # m/s
MEASURES = ["sprung_acceleration", "suspension_travel", "dynamic_tire_load"]


def critical(qc: QuarterCar, zeta: float) -> float:
    p = qc.parameters
    return 2 * zeta * np.sqrt(p.spring_rate * p.sprung_mass)


def exact_rms(model, outputs=MEASURES) -> dict[str, float]:
    """Exact r.m.s. on the class-C road at SPEED (Lyapunov route of random_response)."""
    res = random_response(model, ROAD, SPEED, outputs=outputs)
    return dict(zip(res.output_names, res.rms))


def run(study: Study) -> None:
    import pandas as pd

    qc = QuarterCar(vehdyn.load_vehicle("sedan"), "front")
    c_nominal = qc.parameters.damping
    c_sky = critical(qc, 0.7)
    soft = qc.replace(damping=critical(qc, 0.1))
    mu, kt, ks = qc.parameters.unsprung_mass, qc.parameters.tire_stiffness, qc.parameters.spring_rate
    c_ground = 2 * 0.1 * np.sqrt((ks + kt) * mu)  # wheel-hop damping ratio 0.1

    # LQR: best comfort with travel and tire load no worse than passive, over a small weight grid
    passive = relative_quarter_car(qc, actuator=False)
    ref = exact_rms(passive)
    grid_t = [3e3, 3e4] if study.quick else np.logspace(3, 5.5, 8)
    grid_d = [1e4, 1e5, 1e6] if study.quick else np.logspace(3.5, 6.5, 8)
    best = None
    for wt in grid_t:
        for wd in grid_d:
            d = lqr_quarter_car(qc, {"sprung_acceleration": 1.0, "suspension_travel": wt, "tire_deflection": wd},
                                force_weight=1e-8)
            r = exact_rms(d.closed_loop)
            if r["suspension_travel"] <= ref["suspension_travel"] and r["dynamic_tire_load"] <= ref["dynamic_tire_load"]:
                if best is None or r["sprung_acceleration"] < best[1]["sprung_acceleration"]:
                    best = (d, r)
    lqr = best[0] if best is not None else lqr_quarter_car(qc)

    systems = {
        "passive": passive,
        "skyhook": skyhook(relative_quarter_car(soft), c_sky),
        "groundhook": groundhook(relative_quarter_car(qc), c_ground),
        "hybrid": skyhook(relative_quarter_car(soft), 0.5 * c_sky, 0.5 * c_ground),
        "lqr": lqr.closed_loop,
    }
    table = compare_suspensions(systems, ROAD, SPEED)

    # semi-active: time domain, with the passive car simulated the same way for the statistical error
    duration = 8.0 if study.quick else 120.0
    profile = synthesize_profile(ROAD, SPEED * duration, SPEED * 2e-3, seed=2026, method="white_noise")
    t, road = profile.road_inputs(SPEED)
    semi = SemiActiveQuarterCar(qc, skyhook_damping=c_sky, min_damping=0.2 * c_nominal, max_damping=3.0 * c_nominal)
    settle = t > 1.0
    for label, model, method in (("semi-active skyhook (sim)", semi, "rk4"), ("passive (sim)", qc, "exact")):
        r = vehdyn.simulate(model, t, inputs=road, method=method, hold="zoh")
        row = {m: float(np.sqrt(np.mean(r[m][settle] ** 2))) for m in MEASURES}
        for m in MEASURES:
            row[f"{m}_ratio"] = row[m] / table.loc["passive", m]
        table.loc[label] = pd.Series(row)
    table.attrs["units"] = {"sprung_acceleration": "m/s^2", "suspension_travel": "m", "dynamic_tire_load": "N",
                            "actuator_force": "N"}
    study.table(table, "comparison", caption=f"R.m.s. values on a class-C road at {SPEED:g} m/s: exact (Lyapunov) for "
                f"the linear laws, time simulation ({duration:g} s) for the semi-active damper and, as a check of the "
                "statistical error, for the passive car", floatfmt="{:.4g}")
    sim_err = abs(table.loc["passive (sim)", "sprung_acceleration_ratio"] - 1)

    # ---------------------------------------------------------------- frequency responses
    f = np.logspace(-1, 1.5, 200 if study.quick else 500)
    w = 2 * np.pi * f
    fig, axes = new_figure(2, 1, sharex=True, height_per_row=2.8)
    for label, sys in systems.items():
        fr = sys.frequency_response(w, outputs=["sprung_acceleration", "dynamic_tire_load"], inputs=["road_velocity"])
        per_elevation = fr.response[:, 0] * (1j * w)  # road velocity = j w road elevation
        axes[0, 0].loglog(f, np.abs(per_elevation[0]), label=label)
        axes[1, 0].loglog(f, np.abs(per_elevation[1]) / 1e3, label=label)
    axes[0, 0].set_ylabel("|body acc. / z_r| [(m/s^2)/m]", fontsize=8)
    axes[1, 0].set_ylabel("|F_t / z_r| [kN/m]", fontsize=8)
    axes[1, 0].set_xlabel("frequency [Hz]")
    for ax in axes[:, 0]:
        ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    study.figure(fig, "frequency_responses", caption="Body acceleration and dynamic tire load per unit road elevation")

    # ---------------------------------------------------------------- LQR trade-off against the passive family
    fig, axes = new_figure(1, 2, width=10.0, height_per_row=4.0)
    zetas = np.linspace(0.1, 1.0, 6 if study.quick else 15)
    pas = [exact_rms(relative_quarter_car(qc.replace(damping=critical(qc, z)), actuator=False)) for z in zetas]
    rho = np.logspace(2.5, 5, 5 if study.quick else 12)
    act = [exact_rms(lqr_quarter_car(qc, {"sprung_acceleration": 1.0, "suspension_travel": r,
                                           "tire_deflection": 10 * r}, force_weight=1e-8).closed_loop) for r in rho]
    for ax, x in zip(axes[0], ("dynamic_tire_load", "suspension_travel")):
        scale = 1e3 if x == "suspension_travel" else 1.0
        ax.plot([p[x] * scale for p in pas], [p["sprung_acceleration"] for p in pas], "o-", label="passive, zeta 0.1..1")
        ax.plot([a[x] * scale for a in act], [a["sprung_acceleration"] for a in act], "s-",
                label="LQR, travel weight 3e2..1e5")
        for label in ("skyhook", "groundhook", "hybrid"):
            ax.plot(table.loc[label, x] * scale, table.loc[label, "sprung_acceleration"], "^", label=label)
        ax.set_xlabel("r.m.s. dynamic tire load [N]" if x == "dynamic_tire_load" else "r.m.s. suspension travel [mm]")
        ax.set_ylabel("r.m.s. body acceleration [m/s^2]")
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    study.figure(fig, "tradeoff", caption="Comfort against road holding and travel: passive damping family, LQR designs "
                 "and the ideal hook laws (class C, 20 m/s)")

    # ---------------------------------------------------------------- a single bump
    tb = np.arange(0.0, 1.2, 1e-3)
    length, height = 1.0, 0.05  # m
    s = SPEED * (tb - 0.2)
    bump = np.where((s > 0) & (s < length), 0.5 * height * (1 - np.cos(2 * np.pi * s / length)), 0.0)
    bump_velocity = np.where((s > 0) & (s < length), 0.5 * height * SPEED * 2 * np.pi / length *
                             np.sin(2 * np.pi * s / length), 0.0)
    fig, axes = new_figure(3, 1, sharex=True, height_per_row=2.0)
    for label, sys in systems.items():
        r = vehdyn.simulate(sys, tb, inputs={"road_velocity": bump_velocity}, method="exact")
        for k, m in enumerate(MEASURES):
            axes[k, 0].plot(tb, r[m], label=label)
    r = vehdyn.simulate(semi, tb, inputs={"road_displacement": bump, "road_velocity": bump_velocity}, method="rk4")
    for k, m in enumerate(MEASURES):
        axes[k, 0].plot(tb, r[m], "k--", label="semi-active skyhook")
        axes[k, 0].set_ylabel(m.replace("_", " ") + (" [m/s^2]" if k == 0 else " [m]" if k == 1 else " [N]"),
                              fontsize=7)
        axes[k, 0].grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize=6, ncol=3)
    axes[-1, 0].set_xlabel("time [s]")
    fig.tight_layout()
    study.figure(fig, "bump", caption=f"A {height * 100:g} cm, {length:g} m cosine bump at {SPEED:g} m/s")

    t_lqr = table.loc["lqr"]
    study.text(
        f"Finding: the LQR design chosen (best comfort with travel and tire load no worse than passive) lowers the r.m.s. "
        f"body acceleration to {100 * t_lqr['sprung_acceleration_ratio']:.0f} % of the passive car's, with travel at "
        f"{100 * t_lqr['suspension_travel_ratio']:.0f} % and tire load at {100 * t_lqr['dynamic_tire_load_ratio']:.0f} %. "
        + ("On this white road velocity the groundhook's reaction on the body costs comfort and does not buy wheel "
           "control. " if table.loc["groundhook", "dynamic_tire_load_ratio"] >= 1 else "")
        + " ".join(f"Ideal {k}: acceleration {100 * table.loc[k, 'sprung_acceleration_ratio']:.0f} %, travel "
                   f"{100 * table.loc[k, 'suspension_travel_ratio']:.0f} %, tire load "
                   f"{100 * table.loc[k, 'dynamic_tire_load_ratio']:.0f} %." for k in ("skyhook", "groundhook", "hybrid"))
        + f" The clipped semi-active skyhook reaches "
        f"{100 * table.loc['semi-active skyhook (sim)', 'sprung_acceleration_ratio']:.0f} % of the passive acceleration "
        f"without any power; its time-domain estimate carries a statistical error of the order of "
        f"{100 * sim_err:.1f} % (the passive car's simulation against its exact value).")


if __name__ == "__main__":
    Study.main(run, __file__)
