"""Magic Formula 6.1 fit to 20,000 points: wall and CPU time on one core, recovery error at the data
and between the measured conditions, with and without the validity conditions, the hold of
undetermined coefficients and the cross-validation; and the finite-difference Jacobian column by
column against one call for all coefficients.

Data: the shipped MF 6.1 example tire sampled on a dense test-like grid (4 loads, slip angle
+-15 deg, slip ratio +-0.3, camber 0/+-4 deg, combined slip at six slip angles; 20,184 points) with
1 % Gaussian noise; every fit starts from the default (data-derived) start and runs every stage.
Rows (one process, one run each):

* ``fit``: as shipped, without the cross-validation;
* ``fit + cross-validation``: as shipped (the default of ``fit_magic_formula``);
* ``baseline``: the same fit without the validity penalties and without the ridge
  (``validity=False, regularization=0``), the ratios' reference.

Goal (issues 18, 27): a full fit <= 30 s on one core. Errors are r.m.s. over the peak of the
noise-free truth at the data; "between" is the largest error at camber +-2 deg and the loads midway
between the measured ones (0.6, 1.0, 1.4 FNOMIN), over the data's peak.

Run: ``python benchmarks/bench_tire_fit.py`` (VEHDYN_QUICK=1: 2,000 points).
"""

from __future__ import annotations

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
import os
import time
import warnings

import numpy as np

import vehdyn
from vehdyn.errors import VehdynWarning
from vehdyn.tire import fit_magic_formula, load_tire
from vehdyn.tire.fitting.magic_formula_fit import _Problem
from vehdyn.tire.fitting.synthetic import sample_tire


def _between(fit_tire, tire, peaks):
    """Largest |fit - truth| over the data's peak at camber +-2 deg and loads between the measured."""
    alpha = np.radians(np.linspace(-15, 15, 61))
    kappa = np.linspace(-0.3, 0.3, 41)
    worst = {"fx": 0.0, "fy": 0.0, "mz": 0.0}
    for load in tire.nominal_load * np.array([0.6, 1.0, 1.4]):
        for gamma in np.radians([-2.0, 2.0]):
            for name, k, a in (("fy", 0.0, alpha), ("mz", 0.0, alpha), ("fx", kappa, 0.0)):
                error = getattr(fit_tire.forces(load, k, a, gamma), name) - getattr(tire.forces(load, k, a, gamma), name)
                worst[name] = max(worst[name], float(np.max(np.abs(error))) / peaks[name])
    return worst


def main():
    quick = os.environ.get("VEHDYN_QUICK") == "1"
    tire = load_tire("MagicFormula61_Parameters")
    n_angles, n_ratios = (61, 37) if quick else (601, 361)
    data = sample_tire(tire, slip_angles=np.radians(np.linspace(-15, 15, n_angles)),
                       slip_ratios=np.linspace(-0.3, 0.3, n_ratios),
                       combined_angles=np.radians([-8.0, -4.0, -2.0, 2.0, 4.0, 8.0]), noise=0.01, seed=3)
    truth = data.attrs["truth"]
    peaks = {name: float(np.max(np.abs(values))) for name, values in truth.items()}
    print(f"vehdyn {vehdyn.__version__}: MF 6.1 fit, {len(data)} points, every stage, default start, 1 % noise")
    runs = {"fit": {"cross_validation": False},
            "fit + cross-validation": {},
            "baseline": {"cross_validation": False, "validity": False, "regularization": 0.0}}
    results = {}
    for label, options in runs.items():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", VehdynWarning)  # no pressure sweep: the pressure terms are not identifiable
            wall, cpu = time.perf_counter(), time.process_time()
            fit = fit_magic_formula(data, **options)
            results[label] = (fit, time.perf_counter() - wall, time.process_time() - cpu)
    shipped = results["fit + cross-validation"][0]
    print(shipped)
    print(f"\n{'stage':<20}{'seconds':>9}{'evaluations':>13}   (fit + cross-validation)")
    for stage in shipped.stages.values():
        print(f"{stage.name:<20}{stage.seconds:>9.2f}{stage.nfev:>13d}")
    base_wall = results["baseline"][1]
    print(f"\n{'run':<24}{'wall [s]':>9}{'cpu [s]':>9}{'/ baseline':>11}  error at the data (r.m.s.) / between "
          f"(largest) [% of peak]; validity")
    for label, (fit, wall, cpu) in results.items():
        model = fit.tire.forces(data["fz"].to_numpy(), data["kappa"].to_numpy(), data["alpha"].to_numpy(),
                                data["gamma"].to_numpy(), data["vx"].to_numpy())
        at_data = {name: 100 * np.sqrt(np.mean((getattr(model, name) - truth[name]) ** 2)) / peaks[name]
                   for name in ("fx", "fy", "mz", "mx", "my")}
        between = _between(fit.tire, tire, peaks)
        broken = list(fit.violations.index)
        print(f"{label:<24}{wall:>9.2f}{cpu:>9.2f}{wall / base_wall:>11.2f}  "
              + " ".join(f"{k} {v:.3f}" for k, v in at_data.items()) + " / "
              + " ".join(f"{k} {100 * v:.2f}" for k, v in between.items())
              + f"; {'all hold' if not broken else 'violated: ' + ', '.join(broken)}")
    print("(goal: fit + cross-validation <= 30 s on one core)")
    cv = shipped.cross_validation
    interior = cv[~cv["extrapolation"]]
    print("\nheld out, between the measured conditions (largest, %): "
          + ", ".join(f"{c} {interior.loc[interior['channel'] == c, 'held_out_percent'].max():.2f}"
                      for c in ("fx", "fy", "mz", "mx", "my")))

    # One Jacobian of the pure-lateral stage, column by column (the shipped one) against one call
    # on (k, n) arrays (each coefficient a column that broadcasts against the points).
    fit = shipped
    lateral = data[np.abs(data["kappa"]) < 0.005]
    rows = {k: lateral[k].to_numpy() for k in ("fz", "kappa", "alpha", "gamma", "vx", "fy")}
    rows["pressure"] = np.full(len(lateral), fit.tire._c.INFLPRES)
    names = tuple(fit.stages["pure_lateral"].coefficients)
    problem = _Problem(fit.tire._c, "pure_lateral", rows, ("fy",), names, None)
    x = np.array([getattr(fit.tire._c, n) for n in names])
    inf = np.full(x.size, np.inf)

    def one_call():
        h = 1e-7 * np.maximum(np.abs(x), 1.0)
        columns = np.repeat(x[None, :], x.size + 1, axis=0)
        columns[1:] += np.diag(h)
        c = problem.base._replace(**{n: columns[:, j:j + 1] for j, n in enumerate(names)})
        r = problem.residuals(problem.model(c))  # one output: (k + 1, n)
        return ((r[1:] - r[0]) / h[:, None]).T

    problem.fun(x)
    by_column, jac_c = best_time(lambda: problem.jac(x, -inf, inf))
    at_once, jac_v = best_time(one_call)
    agree = np.max(np.abs(jac_v - jac_c)) / np.max(np.abs(jac_c))
    print(f"\nJacobian, pure lateral, {len(lateral)} points x {x.size} coefficients: column by column (shipped) "
          f"{1e3 * by_column:.1f} ms, one call on (k, n) arrays {1e3 * at_once:.1f} ms, ratio "
          f"{at_once / by_column:.2f}; max difference {agree:.1e} of the largest entry")


if __name__ == "__main__":
    main()
