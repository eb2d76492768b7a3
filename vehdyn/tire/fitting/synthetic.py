"""Synthetic test data from a known tire: the grid of a flat-track test program.

Used to validate the fits by recovering a known tire (tests, ``studies/tire_fitting.py``,
``benchmarks/bench_tire_fit.py``).
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["sample_tire"]


def sample_tire(tire, *, loads=None, slip_angles=np.radians(np.linspace(-15.0, 15.0, 31)),
                slip_ratios=np.linspace(-0.3, 0.3, 31), cambers=np.radians([0.0, -4.0, 4.0]),
                combined_angles=np.radians([-6.0, -3.0, 3.0, 6.0]), pressures=None, vx=None, noise=0.0, seed=None):
    """Sample ``tire`` on a test-like grid: pure slip-angle and slip-ratio sweeps and combined slip.

    Parameters
    ----------
    tire : TireModel
        A tire with ``forces(fz, kappa, alpha, gamma, vx)`` (e.g. :class:`vehdyn.tire.MagicFormula`).
    loads : array_like, optional
        Normal loads [N]; default 0.4, 0.8, 1.2 and 1.6 times the tire's nominal load.
    slip_angles : array_like
        Slip angles of the pure lateral sweeps [rad] (default -15 to 15 degrees by 1 degree).
    slip_ratios : array_like
        Slip ratios of the pure longitudinal and the combined sweeps [-] (default -0.3 to 0.3).
    cambers : array_like
        Inclination angles [rad] of every sweep (default 0, -4, 4 degrees).
    combined_angles : array_like
        Slip angles [rad] of the combined sweeps (slip-ratio sweeps at these angles, zero camber).
    pressures : array_like, optional
        Inflation pressures [Pa] of the pure-slip sweeps at zero camber (besides the nominal one);
        needs a tire with ``evaluate(..., pressure=...)`` (:class:`vehdyn.tire.MagicFormula`). Default:
        the nominal pressure only, and no ``pressure`` column.
    vx : float, optional
        Speed [m/s]; default the tire's LONGVL (or 16.7 m/s).
    noise : float
        Standard deviation of Gaussian noise added to each measured output, as a fraction of that
        output's largest magnitude [-].
    seed : int, optional
        Seed of the noise.

    Returns
    -------
    pandas.DataFrame
        Columns ``fz kappa alpha gamma vx fx fy mz mx my`` (ISO-W, SI) and ``sweep``
        (``"lateral"``, ``"longitudinal"``, ``"combined"``); ``attrs["truth"]`` holds the
        noise-free outputs.
    """
    import pandas as pd

    if not noise >= 0:
        raise ParameterError(f"noise must be >= 0, got {noise!r}", key="noise", value=noise)
    nominal = float(getattr(tire, "nominal_load", 4000.0))
    loads = nominal * np.array([0.4, 0.8, 1.2, 1.6]) if loads is None else np.asarray(loads, dtype=float)
    if vx is None:
        vx = float(getattr(getattr(tire, "_c", None), "LONGVL", 16.7))
    parts = []
    for fz in loads:
        for gamma in np.atleast_1d(cambers):
            a = np.asarray(slip_angles, dtype=float)
            parts.append(("lateral", np.full(a.size, fz), np.zeros(a.size), a, np.full(a.size, gamma)))
            k = np.asarray(slip_ratios, dtype=float)
            parts.append(("longitudinal", np.full(k.size, fz), k, np.zeros(k.size), np.full(k.size, gamma)))
        for alpha in np.atleast_1d(combined_angles):
            k = np.asarray(slip_ratios, dtype=float)
            k = k[np.abs(k) > 0]
            parts.append(("combined", np.full(k.size, fz), k, np.full(k.size, alpha), np.zeros(k.size)))
    nominal_pressure = float(getattr(getattr(tire, "_c", None), "INFLPRES", 0.0))
    parts = [(*p, np.full(p[1].size, nominal_pressure)) for p in parts]
    for pressure in () if pressures is None else np.atleast_1d(pressures):
        for fz in loads:
            a = np.asarray(slip_angles, dtype=float)
            k = np.asarray(slip_ratios, dtype=float)
            parts.append(("lateral", np.full(a.size, fz), np.zeros(a.size), a, np.zeros(a.size),
                          np.full(a.size, pressure)))
            parts.append(("longitudinal", np.full(k.size, fz), k, np.zeros(k.size), np.zeros(k.size),
                          np.full(k.size, pressure)))
    sweep = np.concatenate([np.full(p[1].size, p[0], dtype=object) for p in parts])
    fz, kappa, alpha, gamma, pressure = (np.concatenate([p[i] for p in parts]) for i in range(1, 6))
    if pressures is None:
        out = tire.forces(fz, kappa, alpha, gamma, vx)
    else:
        out = tire.evaluate(fz, kappa, alpha, gamma, vx, pressure=pressure)
    frame = pd.DataFrame({"fz": fz, "kappa": kappa, "alpha": alpha, "gamma": gamma, "vx": np.full(fz.size, vx)})
    if pressures is not None:
        frame["pressure"] = pressure
    truth = {name: np.asarray(getattr(out, name), dtype=float) for name in ("fx", "fy", "mz", "mx", "my")}
    rng = np.random.default_rng(seed)
    for name, values in truth.items():
        scale = noise * float(np.max(np.abs(values))) if values.size else 0.0
        frame[name] = values + (rng.normal(0.0, scale, values.size) if scale > 0 else 0.0)
    frame["sweep"] = sweep
    frame.attrs["truth"] = truth
    return frame
