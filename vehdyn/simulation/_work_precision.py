"""Work-precision: the cost of a simulation against its error, for every integration method.

For each method and tolerance (or fixed step) the model is simulated on the same grid and the
maximum error against a reference solution is recorded with the best wall-clock time of a few
repeats, as in Hairer, Norsett & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
sec. II.10 (work-precision diagrams).
"""

from __future__ import annotations

import time as _time
from typing import Mapping, Sequence

import numpy as np

from vehdyn.errors import ParameterError, SimulationError

__all__ = ["work_precision", "DEFAULT_TOLERANCES"]

#: Relative tolerances tried for each adaptive method (atol = rtol * 1e-3).
DEFAULT_TOLERANCES = (1e-3, 1e-5, 1e-7, 1e-9, 1e-11)


def work_precision(
    model,
    time,
    reference,
    *,
    inputs=None,
    x0=None,
    methods: Mapping[str, Sequence[float]] | None = None,
    rk4_steps: Sequence[float] = (),
    repeats: int = 3,
    signals: Sequence[str] | None = None,
):
    r"""Run ``model`` with each method and tolerance; time it and measure its error.

    Parameters
    ----------
    model : Model
        The model to integrate.
    time : array_like
        Output grid [s]; errors are measured on it.
    reference : ndarray, shape (n_signals, n_times)
        Reference histories of ``signals`` (by default the states) on ``time`` [each signal's
        unit]: a closed form, or a run at a much tighter tolerance.
    inputs, x0 : optional
        As for :func:`vehdyn.simulate` [each signal's unit].
    methods : mapping of str to sequence of float
        ``{method: [rtol, ...]}``; ``"exact"`` takes ``[0]`` (no tolerance). Defaults to every
        ``solve_ivp`` method at :data:`DEFAULT_TOLERANCES`.
    rk4_steps : sequence of float
        Fixed steps [s] for ``"rk4"`` (each must divide the grid spacing: it is run with
        ``substeps = round(grid step / step)``).
    repeats : int
        Timing repeats; the best is kept.
    signals : sequence of str, optional
        Names compared with ``reference``.

    Returns
    -------
    pandas.DataFrame
        Columns ``method``, ``rtol``, ``step``, ``cpu_time`` [s], ``max_error``, ``nfev``,
        ``status`` (``"ok"`` or the error message for a run that failed or was refused).

    Notes
    -----
    The error of a run is the largest absolute difference over every compared signal and
    instant,

    .. math::

        e = \max_{i,k} \left| y_i(t_k) - y_i^{\mathrm{ref}}(t_k) \right|,

    and its cost the best wall-clock time of ``repeats`` runs (``cpu_time``): the two axes of a
    work-precision diagram (Hairer, Nørsett & Wanner, sec. II.10).

    References
    ----------
    .. [1] E. Hairer, S. P. Nørsett and G. Wanner, *Solving Ordinary Differential Equations I:
       Nonstiff Problems*, 2nd ed., Springer, 1993, sec. II.10.

    Examples
    --------
    A first-order lag against its closed form: ``"exact"`` is at rounding level, RK45 at its
    tolerance.

    >>> import numpy as np
    >>> import vehdyn
    >>> from vehdyn.simulation import work_precision
    >>> lag = vehdyn.LinearModel([[-2.0]], [[2.0]], states=["yaw_rate"], inputs=["front_steer_angle"])
    >>> t = np.linspace(0.0, 2.0, 21)
    >>> table = work_precision(lag, t, [1.0 - np.exp(-2.0 * t)], inputs={"front_steer_angle": 1.0},
    ...                        methods={"exact": [0], "RK45": [1e-6]}, repeats=1)
    >>> table["method"].tolist(), table["status"].tolist()
    (['exact', 'RK45'], ['ok', 'ok'])
    >>> bool(table["max_error"].iloc[0] < 1e-14), bool(table["max_error"].iloc[1] < 1e-5)
    (True, True)
    """
    import pandas as pd

    from vehdyn.simulation import SOLVE_IVP_METHODS, simulate

    t = np.asarray(time, dtype=float)
    reference = np.asarray(reference, dtype=float)
    if methods is None:
        methods = {m: DEFAULT_TOLERANCES for m in SOLVE_IVP_METHODS}
    if repeats < 1:
        raise ParameterError(f"repeats must be >= 1, got {repeats}", key="repeats", value=repeats)
    names = list(signals) if signals is not None else list(model.state_names)
    if reference.shape != (len(names), t.size):
        raise ParameterError(f"reference must have shape {(len(names), t.size)}, got {reference.shape}",
                             key="reference", value=reference.shape)
    runs = [(m, tol, None) for m, tols in methods.items() for tol in tols]
    dt = float(np.min(np.diff(t)))
    runs += [("rk4", None, h) for h in rk4_steps]
    rows = []
    for method, tol, step in runs:
        kwargs = {}
        if method == "rk4":
            kwargs["substeps"] = max(1, int(round(dt / step)))
        elif method != "exact":
            kwargs.update(rtol=tol, atol=tol * 1e-3)
        best, result, status = np.inf, None, "ok"
        for _ in range(repeats):
            start = _time.perf_counter()
            try:
                result = simulate(model, t, inputs=inputs, x0=x0, method=method, **kwargs)
            except SimulationError as exc:
                status = str(exc).splitlines()[0]
                result = None
                break
            best = min(best, _time.perf_counter() - start)
        if result is None:
            rows.append({"method": method, "rtol": tol, "step": step, "cpu_time": np.nan, "max_error": np.nan,
                         "nfev": 0, "status": status})
            continue
        sim = np.stack([result[n] for n in names])
        err = float(np.max(np.abs(sim - reference)))
        rows.append({"method": method, "rtol": tol, "step": dt / kwargs["substeps"] if step else None,
                     "cpu_time": best, "max_error": err, "nfev": result.nfev, "status": status})
    df = pd.DataFrame(rows)
    df.attrs["units"] = {"rtol": "-", "step": "s", "cpu_time": "s", "max_error": "state units", "nfev": "-"}
    return df
