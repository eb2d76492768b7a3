"""Global sensitivity of sweep metrics to parameters: Sobol' indices and Morris screening.

The designs and the estimators are SALib's (Herman & Usher 2017; Iwanaga, Usher & Herman 2022):
Saltelli's extension of the Sobol' sequence with the first-order estimator of Saltelli et al.
(2010) and the total-order estimator of Jansen (1999), or Morris' elementary effects (Morris 1991)
with the ``mu_star`` of Campolongo, Cariboni & Saltelli (2007), each with a bootstrap confidence
interval. vehdyn maps SALib's unit-hypercube design onto the parameters (bounds or
distributions), runs it through :func:`vehdyn.sweep.api.run_table` on any engine, and keeps the
estimators honest when a metric is not finite everywhere (:func:`sensitivity`).

References
----------
Saltelli, A., Annoni, P., Azzini, I., Campolongo, F., Ratto, M., Tarantola, S. (2010). Variance
based sensitivity analysis of model output. Design and estimator for the total sensitivity index.
Computer Physics Communications 181(2), 259-270.
Jansen, M. J. W. (1999). Analysis of variance designs for model output. Computer Physics
Communications 117(1-2), 35-43.
Morris, M. D. (1991). Factorial sampling plans for preliminary computational experiments.
Technometrics 33(2), 161-174.
Campolongo, F., Cariboni, J., Saltelli, A. (2007). An effective screening design for sensitivity
analysis of large models. Environmental Modelling & Software 22(10), 1509-1518.
Herman, J., Usher, W. (2017). SALib: an open-source Python library for sensitivity analysis.
Journal of Open Source Software 2(9), 97.
"""

from __future__ import annotations

import math
import warnings
from typing import Any, Mapping

import numpy as np

from vehdyn.errors import ParameterError, SimulationError, VehdynWarning
from vehdyn.sweep.api import _check_seed, _metric_list, run_table
from vehdyn.sweep.engines import _is_real

__all__ = ["sensitivity", "plot_sensitivity"]

_METHODS = ("sobol", "morris")
#: Fewer whole blocks (Sobol') or trajectories (Morris) than this fraction of the design left
#: with finite values of a metric: its indices are refused.
_MIN_KEPT = 0.5


def _salib():
    try:
        import SALib  # noqa: F401
    except ImportError:  # pragma: no cover - SALib is in the test extra
        raise ImportError("vehdyn.sweep.sensitivity needs SALib: pip install SALib (or vehdyn[sensitivity])") from None


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
            low, high = spec
            if not (_is_real(low) and _is_real(high)):
                raise TypeError
            low, high = float(low), float(high)
        except (TypeError, ValueError):
            raise ParameterError(f"parameters[{name!r}] = {spec!r}: give bounds (low, high) or a frozen scipy.stats "
                                 "distribution", key=name, value=spec) from None
        if not (np.isfinite(low) and np.isfinite(high) and high > low):
            raise ParameterError(f"parameters[{name!r}] = {spec!r}: bounds must be finite with low < high",
                                 key=name, value=spec)
        out[name] = lambda u, lo=low, hi=high: lo + u * (hi - lo)
    return out


def _check_arguments(method, n, levels, confidence, seed) -> None:
    if method not in _METHODS:
        raise ParameterError(f"method = {method!r}: must be one of {list(_METHODS)}", key="method", value=method)
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)) or n < 2:
        raise ParameterError(f"n = {n!r}: must be an integer >= 2", key="n", value=n)
    if method == "sobol" and n & (n - 1):
        raise ParameterError(f"n = {n}: Sobol' designs need a power of 2 (e.g. {1 << int(n).bit_length()})", key="n",
                             value=n)
    if isinstance(levels, (bool, np.bool_)) or not isinstance(levels, (int, np.integer)) or levels < 2 or levels % 2:
        raise ParameterError(f"levels = {levels!r}: Morris grid levels must be an even integer >= 2 (Morris 1991: "
                             "with p even and the step p / (2 (p - 1)) every level is visited equally often)",
                             key="levels", value=levels)
    if not _is_real(confidence) or not 0 < confidence < 1:
        raise ParameterError(f"confidence = {confidence!r}: the level of the confidence intervals, a number in "
                             "(0, 1) (e.g. 0.95)", key="confidence", value=confidence)
    _check_seed(seed)


def _finite_blocks(runs, name: str, n: int, block: int, names, method: str) -> np.ndarray:
    """The runs of whole blocks (Sobol') or trajectories (Morris) in which ``name`` is finite;
    a VehdynWarning when some were dropped, SimulationError when too few remain."""
    y = runs[name].to_numpy(dtype=float)
    finite = np.isfinite(y)
    if finite.all():
        return np.ones(y.size, dtype=bool)
    whole = finite.reshape(n, block).all(axis=1)
    kept = int(whole.sum())
    first = int(np.flatnonzero(~finite)[0])
    at = ", ".join(f"{p} = {runs[p].iloc[first]:.6g}" for p in names)
    unit = "blocks" if method == "sobol" else "trajectories"
    why = ("Sobol' indices need every run of a Saltelli block (A, B and the d = {d} mixes AB_i)" if method == "sobol"
           else "The Morris statistics are taken over whole trajectories of d + 1 = {b} runs").format(d=len(names),
                                                                                                   b=block)
    text = (f"sensitivity of {name!r}: {int((~finite).sum())} of {y.size} runs gave a non-finite value "
            f"({int(np.isinf(y).sum())} inf, {int(np.isnan(y).sum())} NaN; the first at {at}). {why}, so the "
            f"{n - kept} {unit} holding one are dropped")
    advice = ("narrow the parameters to where the metric is finite, or index a metric finite over the box (the "
              "understeer gradient K rather than the characteristic speed sqrt(L/K), infinite for K <= 0)")
    if kept < max(2, math.ceil(_MIN_KEPT * n)):
        raise SimulationError(f"{text}, and {kept} of {n} remain: too few for indices of the parameter box asked for; "
                              f"{advice}")
    warnings.warn(f"{text}: the indices come from the other {kept} of {n} {unit} and describe the metric where it "
                  f"is finite, not over the whole parameter box (an infinite value has no variance); {advice}",
                  VehdynWarning, stacklevel=3)
    return np.repeat(whole, block)


def sensitivity(target, parameters: Mapping[str, Any], metric, *, method: str = "sobol", n: int = 256,
                levels: int = 4, confidence: float = 0.95, seed: int | None = 0, executor=None, chunk_size=None,
                progress: bool = False, model: str = "auto", solver=None):
    r"""Sobol' or Morris sensitivity indices of metrics of ``target`` to ``parameters``.

    Sobol' indices (variance-based, Saltelli et al. 2010) of a metric :math:`Y = f(X_1, ..., X_d)`:

    .. math::

        S_i = \frac{V[E(Y \mid X_i)]}{V(Y)}, \qquad
        S_{Ti} = \frac{E[V(Y \mid X_{\sim i})]}{V(Y)},

    estimated from ``n`` blocks of the Saltelli design, each holding two independent points
    :math:`A_j, B_j` of the parameter box and the :math:`d` mixes :math:`A_{B,j}^{(i)}` (:math:`A_j`
    with its i-th coordinate from :math:`B_j`), by

    .. math::

        V_i \approx \frac{1}{n} \sum_j f(B_j) \left(f(A_{B,j}^{(i)}) - f(A_j)\right), \qquad
        V_{Ti} \approx \frac{1}{2n} \sum_j \left(f(A_j) - f(A_{B,j}^{(i)})\right)^2

    (Saltelli et al. 2010, Table 2 (b); Jansen 1999), divided by the variance of the
    :math:`f(A_j), f(B_j)`. Morris screening (Morris 1991) takes ``n`` trajectories of
    :math:`d + 1` points of a ``levels``-level grid, each point one step :math:`\Delta` from the
    previous in one parameter, and the elementary effects

    .. math::

        EE_i = \frac{f(x + \Delta e_i) - f(x)}{\Delta}, \qquad
        \mu_i^* = \frac{1}{n} \sum_{\text{trajectories}} |EE_i| \quad \text{(Campolongo et al. 2007)},

    with their mean :math:`\mu_i` and standard deviation :math:`\sigma_i`.

    A run whose metric is infinite or NaN (the characteristic speed of an oversteering variant)
    cannot enter these sums. Every term of the Sobol' estimators takes one whole block, and every
    Morris statistic is a mean over the same trajectories for all parameters; so the blocks (the
    trajectories) holding a non-finite value are dropped whole, which keeps each estimator a mean
    over complete, independent blocks (dropping single runs would pair values from different
    blocks). The indices then describe the metric where it is finite, not over the whole box - a
    metric that is infinite on part of the box has no variance there, and its indices do not
    exist - and a :class:`~vehdyn.VehdynWarning` says how many runs and blocks were dropped and
    why. With fewer than half the blocks (trajectories) left, or fewer than two, the indices are
    refused (SimulationError).

    Parameters
    ----------
    target : Scene or callable
        As for :func:`vehdyn.sweep.run`.
    parameters : mapping
        Name -> ``(low, high)`` (uniform; in the parameter's unit) or a frozen ``scipy.stats``
        distribution.
    metric : str or sequence of str
        Metric name(s) (:mod:`vehdyn.sweep.metrics`, or keys of a function's result).
    method : {"sobol", "morris"}
        Variance-based indices or elementary-effects screening.
    n : int
        Base sample size: ``n (d + 2)`` runs for Sobol' (``n`` a power of 2), ``n (d + 1)`` for
        Morris (``n`` trajectories), d = number of parameters; at least 2.
    levels : int
        Morris grid levels (an even integer >= 2), from low to high of bounds; distributions are
        evaluated at the levels' mid-quantiles (k + 1/2) / levels.
    confidence : float
        Level of the bootstrap confidence intervals, in (0, 1) [-].
    seed : int, optional
        Seed of the design and of the bootstrap (an integer >= 0, or None for fresh entropy).
    executor : None, str, Executor or dask.distributed.Client
        As for :func:`vehdyn.sweep.run`.
    chunk_size : int, optional
        As for :func:`vehdyn.sweep.run`.
    progress : bool
        As for :func:`vehdyn.sweep.run`.
    model : str
        As for :func:`vehdyn.sweep.run`.
    solver : mapping, optional
        As for :func:`vehdyn.sweep.run`.

    Returns
    -------
    pandas.DataFrame
        Index ``parameter`` (or ``(metric, parameter)`` for several metrics). Sobol': ``S1``,
        ``S1_conf``, ``ST``, ``ST_conf`` (half-widths of the intervals) [-]; Morris: ``mu_star``,
        ``mu_star_conf``, ``mu``, ``sigma`` [unit of the metric]. ``attrs``: ``method``,
        ``metric``, ``runs`` (the sweep table), ``kept`` (metric -> (blocks or trajectories
        kept, n)).

    Raises
    ------
    ParameterError
        For bad parameters, metric, method, n, levels, confidence or seed (and the arguments of
        :func:`vehdyn.sweep.run`).
    SimulationError
        When variants failed (the indices need every run; the message gives the first error), or
        when too few blocks have finite values of a metric.

    Warns
    -----
    VehdynWarning
        When blocks (trajectories) with non-finite values of a metric were dropped.

    References
    ----------
    .. [1] Saltelli, A., Annoni, P., Azzini, I., Campolongo, F., Ratto, M., Tarantola, S. (2010).
       Variance based sensitivity analysis of model output. Design and estimator for the total
       sensitivity index. Computer Physics Communications 181(2), 259-270.
    .. [2] Jansen, M. J. W. (1999). Analysis of variance designs for model output. Computer
       Physics Communications 117(1-2), 35-43.
    .. [3] Morris, M. D. (1991). Factorial sampling plans for preliminary computational
       experiments. Technometrics 33(2), 161-174.
    .. [4] Campolongo, F., Cariboni, J., Saltelli, A. (2007). An effective screening design for
       sensitivity analysis of large models. Environmental Modelling & Software 22(10),
       1509-1518.
    .. [5] Herman, J., Usher, W. (2017). SALib: an open-source Python library for sensitivity
       analysis. Journal of Open Source Software 2(9), 97.

    Examples
    --------
    An additive function of two uniform parameters, :math:`Y = 2a + b`, has the indices
    :math:`S_a = S_{Ta} = 4/5` and :math:`S_b = S_{Tb} = 1/5` (the variances :math:`4/12` and
    :math:`1/12`):

    >>> import vehdyn
    >>> @vehdyn.sweep.vectorized
    ... def additive(a, b):
    ...     return {"y": 2.0 * a + b}
    >>> frame = vehdyn.sweep.sensitivity(additive, {"a": (0.0, 1.0), "b": (0.0, 1.0)}, "y", n=1024)
    >>> frame[["S1", "ST"]].round(1)  # doctest: +NORMALIZE_WHITESPACE
                S1   ST
    parameter
    a          0.8  0.8
    b          0.2  0.2
    """
    import pandas as pd

    _salib()
    _check_arguments(method, n, levels, confidence, seed)
    seed = None if seed is None else int(seed)  # SALib takes Python integers only
    maps = _mapping(parameters)
    laws = [hasattr(parameters[name], "ppf") for name in maps]
    names = list(maps)
    metrics = _metric_list(metric, "metric")
    problem = {"num_vars": len(names), "names": names, "bounds": [[0.0, 1.0]] * len(names)}
    if method == "sobol":
        from SALib.sample import sobol as design

        u = design.sample(problem, int(n), calc_second_order=False, scramble=True, seed=seed)
    else:
        from SALib.sample import morris as design

        u = design.sample(problem, int(n), num_levels=int(levels), seed=seed)
        # distributions at the levels' mid-quantiles (finite for unbounded laws); bounds at the levels
        u[:, laws] = (u[:, laws] * (levels - 1) + 0.5) / levels
    table = pd.DataFrame({name: np.asarray(maps[name](u[:, j]), dtype=float) for j, name in enumerate(names)})
    runs = run_table(target, table, metrics=metrics, executor=executor, chunk_size=chunk_size, progress=progress,
                     model=model, solver=solver)
    failed = runs["error"].notna()
    if failed.any():
        first = runs.index[failed][0]
        raise SimulationError(f"{int(failed.sum())} of {len(runs)} sensitivity runs failed (variant {first}: "
                              f"{runs.loc[first, 'error']}); narrow the parameter ranges")
    block = len(names) + (2 if method == "sobol" else 1)
    frames, kept = [], {}
    for name in metrics:
        rows = _finite_blocks(runs, name, int(n), block, names, method)
        y = runs[name].to_numpy(dtype=float)[rows]
        kept[name] = (int(rows.sum()) // block, int(n))
        if method == "sobol":
            from SALib.analyze import sobol as analyze

            s = analyze.analyze(problem, y, calc_second_order=False, conf_level=float(confidence), seed=seed)
            cols = {"S1": s["S1"], "S1_conf": s["S1_conf"], "ST": s["ST"], "ST_conf": s["ST_conf"]}
        else:
            from SALib.analyze import morris as analyze

            s = analyze.analyze(problem, u[rows], y, conf_level=float(confidence), num_levels=int(levels), seed=seed)
            cols = {"mu_star": s["mu_star"], "mu_star_conf": s["mu_star_conf"], "mu": s["mu"], "sigma": s["sigma"]}
        frame = pd.DataFrame({k: np.asarray(v, dtype=float) for k, v in cols.items()},
                             index=pd.Index(names, name="parameter"))
        frames.append(frame)
    out = frames[0] if len(metrics) == 1 else pd.concat(frames, keys=metrics, names=["metric", "parameter"])
    out.attrs["method"] = method
    out.attrs["metric"] = metrics
    out.attrs["runs"] = runs
    out.attrs["kept"] = kept
    return out


def plot_sensitivity(frame, *, ax=None, title: str | None = None):
    """Bar plot of the indices in ``frame`` (from :func:`sensitivity`) with their intervals.

    Sobol': first-order and total-order bars per parameter; Morris: ``mu_star`` and ``sigma``.

    Parameters
    ----------
    frame : pandas.DataFrame
        The result of :func:`sensitivity` (one metric's rows, e.g. ``frame.loc["metric"]``, or
        all of them).
    ax : matplotlib Axes, optional
        Where to draw (default: a new figure).
    title : str, optional
        The axes' title.

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
