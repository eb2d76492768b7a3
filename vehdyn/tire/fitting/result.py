"""The result of a tire fit: :class:`TireFit` (the fitted tire and per-stage diagnostics)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["StageResult", "TireFit"]


@dataclass
class StageResult:
    """Diagnostics of one fitting stage.

    Attributes
    ----------
    name : str
    skipped : str or None
        Why the stage did not run (missing columns, no points), else None.
    coefficients : dict of str to float
        The coefficients fitted, with their values.
    steps : tuple of str
        Steps run (``"nominal"``, ``"load"``, ``"camber"``, ``"pressure"``).
    outputs : tuple of str
        Measured outputs fitted.
    n_points : int
        Points of the stage's data selection.
    rms : dict of str to float
        Root-mean-square error per output on the stage's points [N or N*m].
    nrms : dict of str to float
        ``rms`` over the largest |measured value| [-].
    r2 : dict of str to float
        Coefficient of determination per output [-].
    at_bounds : tuple of str
        Coefficients that ended on a bound.
    condition : float
        Condition number of the column-normalized Jacobian at the solution of the last step.
    not_identifiable : dict of str to str
        Coefficients the data cannot determine (kept at their start values) and why.
    weakest : tuple of str
        When ``condition`` is large, the coefficients of the least determined direction.
    nfev : int
        Residual evaluations of the last step.
    seconds : float
        Wall time of the stage [s].
    """

    name: str
    skipped: str | None = None
    coefficients: dict = field(default_factory=dict)
    steps: tuple = ()
    outputs: tuple = ()
    n_points: int = 0
    rms: dict = field(default_factory=dict)
    nrms: dict = field(default_factory=dict)
    r2: dict = field(default_factory=dict)
    at_bounds: tuple = ()
    condition: float = float("nan")
    not_identifiable: dict = field(default_factory=dict)
    weakest: tuple = ()
    nfev: int = 0
    seconds: float = 0.0


_OUTPUT_UNITS = {"fx": "N", "fy": "N", "mz": "N*m", "mx": "N*m", "my": "N*m"}


@dataclass
class TireFit:
    """A fitted Magic Formula tire and how well it fits.

    Attributes
    ----------
    tire : MagicFormula
        The fitted model (its ``params`` hold every fitted coefficient).
    stages : dict of str to StageResult
        Per stage, in the order run.
    messages : list of str
        What the fit did on the user's behalf (rows dropped, stages skipped, ranges widened).
    data : dict of str to ndarray
        The data fitted (canonical columns after NaN rows were dropped).
    """

    tire: object
    stages: dict
    messages: list
    data: dict

    @property
    def coefficients(self) -> dict:
        """Every fitted coefficient, over all stages."""
        return {k: v for stage in self.stages.values() for k, v in stage.coefficients.items()}

    def table(self):
        """Per stage and output: points, r.m.s. and normalized r.m.s. error, R², condition, bounds hit
        (a pandas DataFrame)."""
        import pandas as pd

        rows = []
        for stage in self.stages.values():
            if stage.skipped:
                rows.append({"stage": stage.name, "output": "-", "points": 0, "rms": np.nan, "unit": "",
                             "nrms_percent": np.nan, "r2": np.nan, "coefficients": 0, "condition": np.nan,
                             "at_bounds": "", "note": stage.skipped})
                continue
            for out in stage.outputs:
                rows.append({"stage": stage.name, "output": out, "points": stage.n_points, "rms": stage.rms[out],
                             "unit": _OUTPUT_UNITS[out], "nrms_percent": 100 * stage.nrms[out], "r2": stage.r2[out],
                             "coefficients": len(stage.coefficients), "condition": stage.condition,
                             "at_bounds": " ".join(stage.at_bounds),
                             "note": "; ".join(sorted(set(stage.not_identifiable.values())))})
        return pd.DataFrame(rows)

    def __str__(self) -> str:
        lines = [f"Magic Formula {self.tire.version} fit, FNOMIN = {self.tire.nominal_load:g} N"]
        lines.append(f"{'stage':<20}{'out':>4}{'points':>8}{'rms':>12}{'nrms %':>9}{'R2':>9}{'cond':>10}  notes")
        for stage in self.stages.values():
            if stage.skipped:
                lines.append(f"{stage.name:<20}{'-':>4}  {stage.skipped}")
                continue
            for out in stage.outputs:
                notes = []
                if stage.at_bounds:
                    notes.append("at bound: " + " ".join(stage.at_bounds))
                if stage.not_identifiable:
                    notes.append("not identifiable: " + " ".join(stage.not_identifiable))
                lines.append(f"{stage.name:<20}{out:>4}{stage.n_points:>8}{stage.rms[out]:>10.4g} "
                             f"{_OUTPUT_UNITS[out]:<1}{100 * stage.nrms[out]:>8.3f}{stage.r2[out]:>9.5f}"
                             f"{stage.condition:>10.2e}  {'; '.join(notes)}")
        lines.extend(self.messages)
        return "\n".join(lines)

    def to_tir(self, path):
        """Write the fitted Magic Formula to a ``.tir`` file that reads back to the same coefficients.

        Written by :func:`vehdyn.tire.write_tir` and moved into place atomically (an interrupted
        write leaves the previous file). Returns the path.
        """
        import tempfile
        from pathlib import Path

        from vehdyn._atomic import atomic_write_bytes
        from vehdyn.errors import ParameterError
        from vehdyn.tire.tir import write_tir

        if not hasattr(self.tire, "params"):
            raise ParameterError(f"only a Magic Formula fit writes a .tir file; this fit's tire is "
                                 f"{type(self.tire).__name__}", key="tire", value=type(self.tire).__name__)
        path = Path(path)
        with tempfile.TemporaryDirectory(dir=path.parent) as folder:
            text = write_tir(self.tire.params, Path(folder) / path.name).read_bytes()
        return atomic_write_bytes(path, text)

    def plot(self):
        """Data against fit per stage: the textbook figures (force or moment against slip, per load).

        Returns
        -------
        dict of str to matplotlib.figure.Figure
            One figure per stage that ran.
        """
        import matplotlib.pyplot as plt

        from vehdyn.tire.fitting.magic_formula_fit import PURE_SLIP_ANGLE, PURE_SLIP_RATIO, _select
        from vehdyn.tire.fitting.stages import STAGES

        data = self.data
        model = self.tire.forces(data["fz"], data["kappa"], data["alpha"], data["gamma"], data["vx"])
        fitted = {"fx": model.fx, "fy": model.fy, "mz": model.mz, "mx": model.mx, "my": model.my}
        figures = {}
        x_of = {"pure_longitudinal": ("kappa", "slip ratio [-]", 1.0),
                "pure_lateral": ("alpha", "slip angle [deg]", 180 / np.pi),
                "aligning": ("alpha", "slip angle [deg]", 180 / np.pi),
                "combined": ("kappa", "slip ratio [-]", 1.0)}
        for stage in self.stages.values():
            if stage.skipped:
                continue
            fig, axes = plt.subplots(1, len(stage.outputs), figsize=(5.5 * len(stage.outputs), 4.2), squeeze=False)
            for ax, out in zip(axes[0], stage.outputs):
                if stage.name in STAGES:
                    select = _select(stage.name, data)
                    key, label, factor = x_of.get(stage.name, ("alpha", "slip angle [deg]", 180 / np.pi))
                elif out == "fx":  # brush, linear: each output on its pure-slip sweeps
                    select = np.abs(data["alpha"]) < PURE_SLIP_ANGLE
                    key, label, factor = x_of["pure_longitudinal"]
                else:
                    select = np.abs(data["kappa"]) < PURE_SLIP_RATIO
                    key, label, factor = x_of["pure_lateral"]
                loads = np.round(data["fz"][select], -2)
                levels = np.unique(loads)
                if levels.size > 6:
                    levels = levels[np.linspace(0, levels.size - 1, 6).astype(int)]
                for i, level in enumerate(levels):
                    on = select.copy()
                    on[select] = loads == level
                    on &= np.abs(data["gamma"]) < np.radians(0.5)
                    if stage.name == "combined" and on.any():  # the sweep at the largest slip angle
                        on &= np.isclose(data["alpha"], data["alpha"][on].max())
                    if not on.any():
                        continue
                    order = np.argsort(data[key][on])
                    x = data[key][on][order] * factor
                    color = f"C{i}"
                    ax.plot(x, data[out][on][order], ".", color=color, ms=3, label=f"data {level:.0f} N")
                    ax.plot(x, fitted[out][on][order], "-", color=color, lw=1.2)
                ax.set_xlabel(label)
                ax.set_ylabel(f"{out} [{_OUTPUT_UNITS[out]}]")
                title = f"{stage.name}: {out}, nrms {100 * stage.nrms[out]:.2f} %"
                if stage.name == "combined":
                    title += " (largest slip angle)"
                ax.set_title(title)
                ax.grid(True, alpha=0.3)
                ax.legend(fontsize=7)
            fig.tight_layout()
            figures[stage.name] = fig
        return figures
