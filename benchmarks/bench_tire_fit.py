"""Magic Formula 6.1 fit to 20,000 points: wall time on one core, recovery error, and the
finite-difference Jacobian column by column against one call for all coefficients.

Data: the shipped MF 6.1 example tire sampled on a dense test-like grid (4 loads, slip angle
+-15 deg, slip ratio +-0.3, camber 0/+-4 deg, combined slip at six slip angles; 20,184 points) with
1 % Gaussian noise; the fit starts from the default (data-derived) start and runs every stage.
Also: one Jacobian column by column (as shipped) against one call on (k, n) arrays.
Goal (issue 18): <= 30 s on one core. Errors are r.m.s. over the peak of the noise-free truth.

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


def main():
    quick = os.environ.get("VEHDYN_QUICK") == "1"
    tire = load_tire("MagicFormula61_Parameters")
    n_angles, n_ratios = (61, 37) if quick else (601, 361)
    data = sample_tire(tire, slip_angles=np.radians(np.linspace(-15, 15, n_angles)),
                       slip_ratios=np.linspace(-0.3, 0.3, n_ratios),
                       combined_angles=np.radians([-8.0, -4.0, -2.0, 2.0, 4.0, 8.0]), noise=0.01, seed=3)
    print(f"vehdyn {vehdyn.__version__}: MF 6.1 fit, {len(data)} points, every stage, default start, 1 % noise")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VehdynWarning)  # no pressure sweep: the pressure terms are not identifiable
        began = time.perf_counter()
        fit = fit_magic_formula(data)
        total = time.perf_counter() - began
    print(fit)
    print(f"\n{'stage':<20}{'seconds':>9}{'evaluations':>13}")
    for stage in fit.stages.values():
        print(f"{stage.name:<20}{stage.seconds:>9.2f}{stage.nfev:>13d}")
    print(f"{'total':<20}{total:>9.2f}   (goal <= 30 s)")
    truth = data.attrs["truth"]
    model = fit.tire.forces(data["fz"].to_numpy(), data["kappa"].to_numpy(), data["alpha"].to_numpy(),
                            data["gamma"].to_numpy(), data["vx"].to_numpy())
    print("\nerror against the noise-free truth (r.m.s. / peak):")
    for name in ("fx", "fy", "mz", "mx", "my"):
        error = np.sqrt(np.mean((getattr(model, name) - truth[name]) ** 2)) / np.max(np.abs(truth[name]))
        print(f"  {name}: {100 * error:.3f} %")

    # One Jacobian of the pure-lateral stage, column by column (the shipped one) against one call
    # on (k, n) arrays (each coefficient a column that broadcasts against the points).
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
