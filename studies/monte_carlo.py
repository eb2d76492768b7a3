"""Monte Carlo of parameter uncertainty: the sedan's handling and ride numbers as distributions.

The shipped sedan's mass (+-10 %), longitudinal CG position (+-5 cm) and front and rear cornering
stiffnesses (+-15 % each, independent) are uncertain, uniformly within those ranges. Each variant
is built consistently - the inertias scale with the mass (same radii of gyration), the sprung mass
takes the change, the sprung CG moves with the total CG - which is why the study sweeps a function
of four factors rather than four independent dotted parameter names (the vehicle's consistency
checks would reject most such combinations). Per variant: the linear understeer gradient and
characteristic speed (Gillespie 1992, ch. 6), the ISO 7401 yaw-rate overshoot of a 0.3 g step steer
at 100 km/h (linear single-track model, exact discretization), and ride comfort: the ISO 2631-1
Wk-weighted r.m.s. body acceleration of the front quarter car on an ISO 8608 class B road at
25 m/s (Lyapunov route). ``vehdyn.sweep.run`` draws a Latin hypercube; ``vehdyn.sweep.sensitivity``
gives the Sobol' indices (SALib, Saltelli design) of each number to each factor.
"""

import functools
import importlib.util

import numpy as np

import vehdyn
from vehdyn import handling, procedures
from vehdyn.plotting import new_figure
from vehdyn.report import Study

BASE = vehdyn.load_vehicle("sedan")
SPEED = 100 / 3.6  # [m/s] step steer
RIDE_SPEED = 25.0  # [m/s]
TARGET_AY = 0.3 * 9.80665  # [m/s^2] steady-state size of the step
RANGES = {"mass_factor": (0.9, 1.1), "cg_shift": (-0.05, 0.05), "front_stiffness_factor": (0.85, 1.15),
          "rear_stiffness_factor": (0.85, 1.15)}
METRICS = {"understeer_gradient_deg_per_g": "deg/g", "characteristic_speed": "m/s", "yaw_rate_overshoot": "-",
           "weighted_acceleration": "m/s^2"}


def sedan_variant(mass_factor, cg_shift, front_stiffness_factor, rear_stiffness_factor):
    """A consistent variant of the sedan: mass and inertias x mass_factor, CG moved forward by
    cg_shift [m], axle cornering stiffnesses scaled."""
    m, g, t = BASE.mass, BASE.geometry, BASE.tires
    mass = m.mass * mass_factor
    sprung = mass - m.front_unsprung_mass - m.rear_unsprung_mass
    inertias = {f: getattr(m, f) * mass_factor for f in ("roll_inertia", "pitch_inertia", "yaw_inertia",
                                                           "sprung_roll_inertia", "sprung_pitch_inertia")}
    a, b = g.cg_to_front_axle - cg_shift, g.cg_to_rear_axle + cg_shift
    x_sprung = (m.rear_unsprung_mass * b - m.front_unsprung_mass * a) / sprung  # total CG at x = 0
    return BASE.replace(
        mass__mass=mass, mass__sprung_mass=sprung, **{f"mass__{k}": v for k, v in inertias.items()},
        geometry__cg_to_front_axle=a, geometry__cg_to_rear_axle=b, geometry__sprung_cg_to_front_axle=a - x_sprung,
        tires__front_cornering_stiffness=t.front_cornering_stiffness * front_stiffness_factor,
        tires__rear_cornering_stiffness=t.rear_cornering_stiffness * rear_stiffness_factor)


@functools.lru_cache(maxsize=None)
def comfort_filter():
    """ISO 2631-1's W_k weighting as a linear model (sprung_acceleration -> aw): the same for every
    variant, built once per process (about a fifth of a variant's cost when built in each)."""
    from vehdyn.ride import weighting

    return weighting("Wk").to_linear_model(input_name="sprung_acceleration", output_name="aw")


def numbers(mass_factor, cg_shift, front_stiffness_factor, rear_stiffness_factor):
    """The four numbers of one variant."""
    from vehdyn.ride import QuarterCar, random_response

    v = sedan_variant(mass_factor, cg_shift, front_stiffness_factor, rear_stiffness_factor)
    car = handling.LinearBicycle(v, SPEED)
    delta = TARGET_AY / float(handling.steady_state_gains(car).lateral_acceleration)
    t = np.linspace(0.0, 4.0, 801)
    steer = np.where(t >= 0.5, delta, 0.0)
    res = vehdyn.simulate(car, t, {"front_steer_angle": steer}, method="exact")
    yaw = procedures.step_response_metrics(res, "yaw_rate")
    quarter = vehdyn.connect_in_series(QuarterCar(v, "front"), comfort_filter())
    aw = random_response(quarter, "B", RIDE_SPEED, outputs=["aw"])["aw"]
    return {"understeer_gradient_deg_per_g": handling.understeer_gradient_deg_per_g(v),
            "characteristic_speed": handling.characteristic_speed(v),
            "yaw_rate_overshoot": float(yaw.overshoot), "weighted_acceleration": float(aw)}


numbers.units = METRICS


def run(study: Study) -> None:
    import pandas as pd
    import scipy.stats as st

    n = 64 if study.quick else 1000
    laws = {k: st.uniform(lo, hi - lo) for k, (lo, hi) in RANGES.items()}
    table = vehdyn.sweep.run(numbers, samples=laws, n=n, seed=1, progress=False)
    failed = int(table["error"].notna().sum())
    nominal = numbers(1.0, 0.0, 1.0, 1.0)

    fig, axes = new_figure(2, 2, width=9.0, height_per_row=3.0)
    labels = {"understeer_gradient_deg_per_g": "understeer gradient [deg/g]",
              "characteristic_speed": "characteristic speed [m/s]",
              "yaw_rate_overshoot": "yaw-rate overshoot (ISO 7401) [-]",
              "weighted_acceleration": "Wk-weighted body acceleration [m/s^2]"}
    for ax, (name, label) in zip(axes.ravel(), labels.items()):
        values = table[name].to_numpy()
        values = values[np.isfinite(values)]  # the characteristic speed is infinite for K <= 0
        ax.hist(values, bins=12 if study.quick else 30, color="C0", alpha=0.8)
        ax.axvline(nominal[name], color="k", ls="--", lw=1.0, label="nominal sedan")
        ax.set_xlabel(label)
        ax.set_ylabel("variants")
        ax.legend(fontsize=7)
    fig.tight_layout()
    study.figure(fig, "distributions", caption=f"{len(table)} Latin-hypercube variants of the sedan (mass +-10 %, "
                 "CG +-5 cm, cornering stiffnesses +-15 %); dashed: the nominal car")

    oversteer = int((table["understeer_gradient_deg_per_g"] <= 0).sum())
    finite = table.replace([np.inf, -np.inf], np.nan)
    summary = pd.DataFrame({name: {"unit": unit, "nominal": nominal[name], "mean": finite[name].mean(),
                                   "std": finite[name].std(), "p05": finite[name].quantile(0.05),
                                   "p95": finite[name].quantile(0.95)} for name, unit in METRICS.items()}).T
    summary.index.name = "number"
    study.table(summary.reset_index(), "distribution_summary",
                caption=f"Monte Carlo summary ({len(table)} variants, {failed} failed, {oversteer} oversteering: "
                        "their characteristic speed is infinite, left out of its statistics)")

    # Sobol' indices need finite numbers: the characteristic speed sqrt(L/K) is infinite for the
    # oversteering variants, so it has no variance over the box (sensitivity() would drop the Saltelli
    # blocks holding those runs, with a warning); the understeer gradient K carries its information
    indexed = [k for k in METRICS if k != "characteristic_speed"]
    if importlib.util.find_spec("SALib") is None:
        study.text("The Sobol' sensitivity indices need SALib, which is not installed here: "
                   "pip install \"vehdyn[sensitivity]\" (the README's report command installs it).")
        return
    sobol = vehdyn.sweep.sensitivity(numbers, RANGES, indexed, method="sobol", n=16 if study.quick else 256, seed=2)
    fig, axes = new_figure(1, 3, width=12.0, height_per_row=3.4)
    for ax, name in zip(axes.ravel(), indexed):
        vehdyn.sweep.plot_sensitivity(sobol.loc[name], ax=ax, title=labels[name])
    fig.tight_layout()
    study.figure(fig, "sobol_indices", caption="Sobol' first-order (S1) and total-order (ST) indices with 95 % "
                 "bootstrap intervals (SALib, Saltelli design, "
                 f"{len(sobol.attrs['runs'])} runs)")
    study.table(sobol.reset_index(), "sobol_indices", caption="Sobol' indices of each number to each factor")

    top = {name: sobol.loc[name]["ST"].idxmax() for name in indexed}
    study.text(
        f"Over the uncertainty box the understeer gradient spans {summary.loc['understeer_gradient_deg_per_g', 'p05']:.2f}"
        f" to {summary.loc['understeer_gradient_deg_per_g', 'p95']:.2f} deg/g (5-95 %), nominal "
        f"{nominal['understeer_gradient_deg_per_g']:.2f} deg/g; the largest total-order index of each number: "
        + ", ".join(f"{k} <- {v}" for k, v in top.items())
        + f". {oversteer} of {len(table)} variants oversteer (K <= 0: no characteristic speed, which therefore "
          "has no Sobol' indices over the box; those of K stand for it). The cornering-stiffness balance and the CG position dominate the steady-state handling numbers; "
          "the body's weighted acceleration depends on the mass and, through the front axle's share of the "
          "sprung mass, on the CG position, but not on the cornering stiffnesses, whose indices are zero.")


if __name__ == "__main__":
    Study.main(run, __file__)
