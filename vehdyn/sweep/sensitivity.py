"""Global sensitivity of sweep metrics to parameters: Sobol' indices and Morris screening.

The designs and the estimators are SALib's (Herman & Usher 2017; Iwanaga, Usher & Herman 2022):
Saltelli's extension of the Sobol' sequence with Jansen's estimators for first-order ``S1`` and
total-order ``ST`` indices (Saltelli et al. 2010), or Morris' elementary effects (``mu_star``,
``sigma``; Campolongo, Cariboni & Saltelli 2007), each with a bootstrap confidence interval.
vehdyn only maps SALib's unit-hypercube design onto the parameters (bounds or distributions) and
runs it through :func:`~vehdyn.sweep.api.run_table`, on any engine.

References
----------
Saltelli, A. et al. (2010). Variance based sensitivity analysis of model output. Design and
estimator for the total sensitivity index. Computer Physics Communications 181, 259-270.
Campolongo, F., Cariboni, J., Saltelli, A. (2007). An effective screening design for sensitivity
analysis of large models. Environmental Modelling & Software 22, 1509-1518.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from vehdyn.errors import ParameterError, SimulationError

__all__ = ["sensitivity", "plot_sensitivity"]

_METHODS = ("sobol", "morris")


def _salib():
    try:
        import SALib  # noqa: F401
    except ImportError:  # pragma: no cover - SALib is in the test extra
        raise ImportError("vehdyn.sensitivity needs SALib: pip install SALib (or vehdyn[sensitivity])") from None


def _mapping(parameters: Mapping[str, Any]):
    """name -> function of u in (0, 1) giving the parameter value."""
    if not isinstance(parameters, Mapping) or not parameters:
        raise ParameterError(f"parameters must be a non-empty mapping name -> (low, high) or distribution, got "
                             f"{parameters!r}", key="parameters", value=parameters)
    out = {}
    for name, spec in parameters.items():
        if hasattr(spec, "ppf"):
            out[name] = spec.ppf
            continue
        try:
            low, high = (float(v) for v in spec)
        except (TypeError, ValueError):
            raise ParameterError(f"parameters[{name!r}] = {spec!r}: give bounds (low, high) or a frozen scipy.stats "
                                 "distribution", key=name, value=spec) from None
        if not (np.isfinite(low) and np.isfinite(high) and high > low):
            raise ParameterError(f"parameters[{name!r}] = {spec!r}: bounds must be finite with low < high",
                                 key=name, value=spec)
        out[name] = lambda u, lo=low, hi=high: lo + u * (hi - lo)
    return out


def sensitivity(target, parameters: Mapping[str, Any], metric, *, method: str = "sobol", n: int = 256,
                levels: int = 4, confidence: float = 0.95, seed: int | None = 0, executor=None, chunk_size=None,
                progress: bool = False, model: str = "auto"):
    """Sobol' or Morris sensitivity indices of metrics of ``target`` to ``parameters``.

    Parameters
    ----------
    target : Scene or callable
        As for :func:`vehdyn.sweep`.
    parameters : mapping
        Name -> ``(low, high)`` (uniform) or a frozen ``scipy.stats`` distribution.
    metric : str or sequence of str
        Metric name(s) (:mod:`vehdyn.sweep.metrics`, or keys of a function's result).
    method : {"sobol", "morris"}
    n : int
        Base sample size: ``n (d + 2)`` runs for Sobol' (a power of 2), ``n (d + 1)`` for Morris
        (``n`` trajectories), d = number of parameters.
    levels : int
        Morris grid levels, from low to high of bounds; distributions are evaluated at the
        levels' mid-quantiles (k + 1/2) / levels.
    confidence : float
        Level of the bootstrap confidence intervals.
    seed : int, optional
        Seed of the design and of the bootstrap.
    executor, chunk_size, progress, model
        As for :func:`vehdyn.sweep`.

    Returns
    -------
    pandas.DataFrame
        Index ``parameter`` (or ``(metric, parameter)`` for several metrics). Sobol': ``S1``,
        ``S1_conf``, ``ST``, ``ST_conf`` (half-widths of the intervals); Morris: ``mu_star``,
        ``mu_star_conf``, ``mu``, ``sigma``. ``attrs``: ``method``, ``runs`` (the sweep table).

    Raises
    ------
    ParameterError
        For bad parameters, method or n.
    SimulationError
        When variants failed (the indices need every run); the message gives the first error.
    """
    import pandas as pd

    _salib()
    if method not in _METHODS:
        raise ParameterError(f"method = {method!r}: must be one of {list(_METHODS)}", key="method", value=method)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
        raise ParameterError(f"n = {n!r}: must be an integer >= 2", key="n", value=n)
    if method == "sobol" and n & (n - 1):
        raise ParameterError(f"n = {n}: Sobol' designs need a power of 2 (e.g. {1 << int(n).bit_length()})", key="n",
                             value=n)
    if not 0 < confidence < 1:
        raise ParameterError(f"confidence = {confidence!r}: must be in (0, 1)", key="confidence", value=confidence)
    maps = _mapping(parameters)
    laws = [hasattr(parameters[name], "ppf") for name in maps]
    names = list(maps)
    metrics = [metric] if isinstance(metric, str) else list(metric)
    problem = {"num_vars": len(names), "names": names, "bounds": [[0.0, 1.0]] * len(names)}
    if method == "sobol":
        from SALib.sample import sobol as design

        u = design.sample(problem, int(n), calc_second_order=False, scramble=True, seed=seed)
    else:
        from SALib.sample import morris as design

        u = design.sample(problem, int(n), num_levels=int(levels), seed=seed)
        # distributions at the levels' mid-quantiles (finite for unbounded laws); bounds at the levels
        u[:, laws] = (u[:, laws] * (levels - 1) + 0.5) / levels
    from vehdyn.sweep.api import run_table

    table = pd.DataFrame({name: np.asarray(maps[name](u[:, j]), dtype=float) for j, name in enumerate(names)})
    runs = run_table(target, table, metrics=metrics, executor=executor, chunk_size=chunk_size, progress=progress,
                     model=model)
    failed = runs["error"].notna()
    if failed.any():
        first = runs.index[failed][0]
        raise SimulationError(f"{int(failed.sum())} of {len(runs)} sensitivity runs failed (variant {first}: "
                              f"{runs.loc[first, 'error']}); narrow the parameter ranges")
    frames = []
    for name in metrics:
        y = runs[name].to_numpy(dtype=float)
        if method == "sobol":
            from SALib.analyze import sobol as analyze

            s = analyze.analyze(problem, y, calc_second_order=False, conf_level=confidence, seed=seed)
            cols = {"S1": s["S1"], "S1_conf": s["S1_conf"], "ST": s["ST"], "ST_conf": s["ST_conf"]}
        else:
            from SALib.analyze import morris as analyze

            s = analyze.analyze(problem, u, y, conf_level=confidence, num_levels=int(levels), seed=seed)
            cols = {"mu_star": s["mu_star"], "mu_star_conf": s["mu_star_conf"], "mu": s["mu"], "sigma": s["sigma"]}
        frame = pd.DataFrame({k: np.asarray(v, dtype=float) for k, v in cols.items()},
                             index=pd.Index(names, name="parameter"))
        frames.append(frame)
    out = frames[0] if len(metrics) == 1 else pd.concat(frames, keys=metrics, names=["metric", "parameter"])
    out.attrs["method"] = method
    out.attrs["metric"] = metrics
    out.attrs["runs"] = runs
    return out


def plot_sensitivity(frame, *, ax=None, title: str | None = None):
    """Bar plot of the indices in ``frame`` (from :func:`sensitivity`) with their intervals.

    Sobol': first-order and total-order bars per parameter; Morris: ``mu_star`` and ``sigma``.

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 3.5))
    sobol = "S1" in frame.columns
    pairs = [("S1", "S1_conf", "first order"), ("ST", "ST_conf", "total order")] if sobol else \
        [("mu_star", "mu_star_conf", "mu*"), ("sigma", None, "sigma")]
    labels = [" / ".join(map(str, k)) if isinstance(k, tuple) else str(k) for k in frame.index]
    x = np.arange(len(labels))
    width = 0.38
    for k, (col, conf, label) in enumerate(pairs):
        err = frame[conf].to_numpy() if conf else None
        ax.bar(x + (k - 0.5) * width, frame[col].to_numpy(), width, yerr=err, capsize=3, label=label)
    ax.set_xticks(x)
    ax.set_xticklabels(labels, rotation=30, ha="right", fontsize=7)
    ax.set_ylabel("Sobol' index [-]" if sobol else "elementary effect")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.legend(fontsize=8)
    if title:
        ax.set_title(title, fontsize=9)
    return ax
