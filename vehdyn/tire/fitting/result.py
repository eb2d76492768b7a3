"""The result of a tire fit: :class:`TireFit` (the fitted tire, per-stage diagnostics, validity
conditions on the data's envelope and the errors at conditions left out of the fit)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["StageResult", "TireFit"]


@dataclass
class StageResult:
    """Diagnostics of one fitting stage.

    Parameters
    ----------
    name : str
        The stage (:data:`vehdyn.tire.fitting.STAGE_NAMES`, or ``"brush"``, ``"linear"``).
    skipped : str or None
        Why the stage did not run (missing columns, no points), else None.
    coefficients : dict of str to float
        The coefficients fitted, with their values [each in its unit of the coefficient record,
        SI; most Magic Formula coefficients are dimensionless, -].
    steps : tuple of str
        Steps run (``"nominal"``, ``"load"``, ``"camber"``, ``"pressure"``).
    outputs : tuple of str
        Measured outputs fitted.
    n_points : int
        Points of the stage's data selection [-].
    rms : dict of str to float
        Root-mean-square error per output on the stage's points [N or N*m].
    nrms : dict of str to float
        ``rms`` over the largest |measured value| [-].
    r2 : dict of str to float
        Coefficient of determination per output [-].
    at_bounds : tuple of str
        Coefficients that ended on a bound.
    condition : float
        Condition number of the column-normalized data Jacobian at the solution of the last step [-].
    not_identifiable : dict of str to str
        Coefficients the data cannot determine at all (kept at their start values) and why.
    weakest : tuple of str
        When ``condition`` exceeds 1e8, the coefficients of the least determined direction.
    held : tuple of str
        Coefficients of the directions the data leave open, held at their start (or reference)
        values by the regularization of :func:`~vehdyn.tire.fitting.fit_magic_formula`.
    nfev : int
        Residual evaluations of the stage's steps [-].
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
    held: tuple = ()
    nfev: int = 0
    seconds: float = 0.0


_OUTPUT_UNITS = {"fx": "N", "fy": "N", "mz": "N*m", "mx": "N*m", "my": "N*m"}
_LEVEL_UNITS = {"load": ("N", 1.0), "camber": ("deg", 180 / math.pi), "pressure": ("bar", 1e-5)}


@dataclass
class TireFit:
    """A fitted tire and how well it fits, at the data and between them.

    Parameters
    ----------
    tire : TireModel
        The fitted model (a :class:`~vehdyn.tire.MagicFormula` whose ``params`` hold every fitted
        coefficient, or the :class:`~vehdyn.tire.BrushTire` / :class:`~vehdyn.tire.LinearTire` of
        :func:`~vehdyn.tire.fitting.fit_brush`, :func:`~vehdyn.tire.fitting.fit_linear`).
    stages : dict of str to StageResult
        Per stage, in the order run.
    messages : list of str
        What the fit did on the user's behalf (rows dropped, stages skipped, ranges widened,
        coefficients held) and what it found (validity, held-out errors).
    data : dict of str to ndarray
        The data fitted (canonical columns [SI] after non-finite rows were dropped).
    validity : pandas.DataFrame or None
        The Magic Formula's validity conditions on the grid that fills the data's span
        (:func:`~vehdyn.tire.fitting.check_validity`): one row per condition with the worst value,
        where it occurs and the number of violations. None for the simple laws.
    grid : ValidityGrid or None
        That grid (loads, cambers, pressures, slips).
    held_out : list of dict or None
        The leave-one-condition-out records (see :attr:`cross_validation`); None when the fit ran
        without cross-validation.
    """

    tire: object
    stages: dict
    messages: list
    data: dict
    validity: object = None
    grid: object = None
    held_out: list = None

    @property
    def coefficients(self) -> dict:
        """Every fitted coefficient, over all stages (dict of str to float)."""
        return {k: v for stage in self.stages.values() for k, v in stage.coefficients.items()}

    @property
    def violations(self):
        """The validity conditions that fail somewhere on the grid (rows of :attr:`validity`;
        empty when all hold; None without a validity check)."""
        if self.validity is None:
            return None
        return self.validity[~self.validity["ok"]]

    @property
    def cross_validation(self):
        """Errors at each measured condition left out of the fit, beside the training error.

        Returns
        -------
        pandas.DataFrame or None
            One row per left-out condition (each load level, each camber level, each pressure
            level) and channel (``fx``, ``fy``, ``mz``, ``mx``, ``my`` where fitted): ``variable``,
            ``level`` [N, rad or Pa], ``level_text``, ``channel``, ``points``, ``held_out_percent``
            (r.m.s. error of the fit made without the condition, at the condition's points, over
            the largest |measured value| there [%]), ``training_percent`` (the same for the full
            fit [%]), ``ratio`` (held-out over training), ``extrapolation`` (the condition is the
            smallest or largest level: leaving it out extrapolates) and ``note`` (why a refit
            failed). None when the fit ran without cross-validation.
        """
        if self.held_out is None:
            return None
        import pandas as pd

        from vehdyn.tire.fitting.cross_validation import level_text

        rows = []
        for r in self.held_out:
            rows.append({"variable": r["variable"], "level": r["level"],
                         "level_text": level_text(r["variable"], r["level"]), "channel": r["channel"],
                         "points": r["points"], "held_out_percent": 100 * r["held_out"],
                         "training_percent": 100 * r["training"],
                         "ratio": r["held_out"] / r["training"] if r["training"] > 0 else math.inf,
                         "extrapolation": r["extrapolation"], "note": r["note"]})
        return pd.DataFrame(rows, columns=["variable", "level", "level_text", "channel", "points", "held_out_percent",
                                           "training_percent", "ratio", "extrapolation", "note"])

    def table(self):
        """Per stage and output: points, errors, R², coefficients, condition, bounds hit, and the
        largest held-out error of that output.

        Returns
        -------
        pandas.DataFrame
            Columns ``stage``, ``output``, ``points``, ``rms`` [N or N*m], ``unit``,
            ``nrms_percent`` [%], ``r2`` [-], ``coefficients``, ``condition`` [-], ``at_bounds``,
            ``held``, ``held_out_max_percent`` (the largest leave-one-condition-out error of the
            output, interpolated conditions only [%]; NaN without cross-validation) and ``note``.
        """
        import pandas as pd

        worst = self._worst_held_out(extrapolation=False)
        rows = []
        for stage in self.stages.values():
            if stage.skipped:
                rows.append({"stage": stage.name, "output": "-", "points": 0, "rms": np.nan, "unit": "",
                             "nrms_percent": np.nan, "r2": np.nan, "coefficients": 0, "condition": np.nan,
                             "at_bounds": "", "held": "", "held_out_max_percent": np.nan, "note": stage.skipped})
                continue
            for out in stage.outputs:
                rows.append({"stage": stage.name, "output": out, "points": stage.n_points, "rms": stage.rms[out],
                             "unit": _OUTPUT_UNITS[out], "nrms_percent": 100 * stage.nrms[out], "r2": stage.r2[out],
                             "coefficients": len(stage.coefficients), "condition": stage.condition,
                             "at_bounds": " ".join(stage.at_bounds), "held": " ".join(stage.held),
                             "held_out_max_percent": worst.get(out, (np.nan,))[0],
                             "note": "; ".join(sorted(set(stage.not_identifiable.values())))})
        return pd.DataFrame(rows)

    def _worst_held_out(self, extrapolation):
        """Channel -> (largest held-out error [%], its condition text, training error there [%])."""
        worst = {}
        if self.held_out is None:
            return worst
        from vehdyn.tire.fitting.cross_validation import level_text

        for r in self.held_out:
            if r["extrapolation"] and not extrapolation or not np.isfinite(r["held_out"]):
                continue
            if r["channel"] not in worst or 100 * r["held_out"] > worst[r["channel"]][0]:
                worst[r["channel"]] = (100 * r["held_out"], level_text(r["variable"], r["level"]),
                                       100 * r["training"])
        return worst

    def __str__(self) -> str:
        lines = [f"{type(self.tire).__name__} fit"
                 + (f" (Magic Formula {self.tire.version}), FNOMIN = {self.tire.nominal_load:g} N"
                    if hasattr(self.tire, "version") else "")]
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
                if stage.held:
                    notes.append("held: " + " ".join(stage.held))
                lines.append(f"{stage.name:<20}{out:>4}{stage.n_points:>8}{stage.rms[out]:>10.4g} "
                             f"{_OUTPUT_UNITS[out]:<1}{100 * stage.nrms[out]:>8.3f}{stage.r2[out]:>9.5f}"
                             f"{stage.condition:>10.2e}  {'; '.join(notes)}")
        if self.held_out is not None:
            inside, edges = self._worst_held_out(False), self._worst_held_out(True)
            lines.append("held out (each measured condition left out of the fit in turn; r.m.s. over the peak):")
            for channel in ("fx", "fy", "mz", "mx", "my"):
                if channel in edges:
                    text = (f"  {channel}: between the measured conditions at most "
                            + (f"{inside[channel][0]:.2f} % ({inside[channel][1]}, training {inside[channel][2]:.2f} %)"
                               if channel in inside else "- (no interior condition)")
                            + f"; any condition at most {edges[channel][0]:.2f} % ({edges[channel][1]})")
                    lines.append(text)
        if self.validity is not None:
            bad = self.violations
            if len(bad):
                lines.append("validity conditions violated: " + ", ".join(bad.index))
            elif self.grid is not None:
                g = self.grid
                lines.append(f"validity: all {len(self.validity)} conditions hold on {g.loads.size} loads x "
                             f"{g.cambers.size} cambers x {g.pressures.size} pressures x {g.slip_angles.size} slip "
                             f"angles spanning the data")
        lines.extend(self.messages)
        return "\n".join(lines)

    def to_tir(self, path):
        """Write the fitted Magic Formula to a ``.tir`` file that reads back to the same coefficients.

        Written by :func:`vehdyn.tire.write_tir` and moved into place atomically (an interrupted
        write leaves the previous file).

        Parameters
        ----------
        path : str or pathlib.Path
            The file to write.

        Returns
        -------
        pathlib.Path
            The path written.

        Raises
        ------
        ParameterError
            If the fitted tire is not a Magic Formula.
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
        """Data against fit per stage, with the fitted curves between the measured conditions.

        Each stage's figure is the textbook one (force or moment against slip, one colour per
        load): the measured points, the fit through them (solid) and the fit at the loads midway
        between the measured ones (dashed, no data there). A Magic Formula fit to data at several
        cambers adds ``"camber"``: Fy and Mz against slip angle at the nominal load, at every
        measured camber and midway between them; with cross-validation, ``"cross_validation"``:
        per channel, the error at each measured condition when it was left out of the fit, beside
        the training error.

        Returns
        -------
        dict of str to matplotlib.figure.Figure
            One figure per stage that ran, and the two above where they apply.
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
        vx = float(np.median(data["vx"]))
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
                slip_span = None
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
                    slip_span = (x.min(), x.max(), data["alpha"][on][0] if stage.name == "combined" else 0.0)
                if slip_span is not None and stage.name != "combined" and levels.size > 1:
                    self._between_loads(ax, out, key, factor, slip_span, levels, vx)
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
        camber = self._camber_figure(vx)
        if camber is not None:
            figures["camber"] = camber
        if self.held_out:
            figures["cross_validation"] = self._cross_validation_figure()
        return figures

    def _between_loads(self, ax, out, key, factor, span, levels, vx):
        """Dashed fitted curves at the loads midway between the plotted ones (zero camber)."""
        x = np.linspace(span[0], span[1], 61) / factor
        for level in 0.5 * (levels[1:] + levels[:-1]):
            kappa, alpha = (x, np.zeros_like(x)) if key == "kappa" else (np.zeros_like(x), x)
            model = self.tire.forces(np.full(x.size, level), kappa, alpha, 0.0, vx)
            ax.plot(x * factor, getattr(model, out), "--", color="0.45", lw=0.9)
        ax.plot([], [], "--", color="0.45", lw=0.9, label="fit between the loads")

    def _camber_figure(self, vx):
        """Fy and Mz against slip angle at the load nearest the nominal one, at the measured
        cambers (data and fit) and midway between them (fit, dashed); None without a camber sweep."""
        import matplotlib.pyplot as plt

        from vehdyn.tire.fitting.cross_validation import CAMBER_GAP, clusters
        from vehdyn.tire.fitting.magic_formula_fit import _select

        data = self.data
        if not hasattr(self.tire, "version") or "pure_lateral" not in self.stages:
            return None
        lateral = _select("pure_lateral", data)
        cambers = clusters(data["gamma"][lateral], CAMBER_GAP)
        if cambers.size < 2:
            return None
        loads = data["fz"][lateral]
        load = float(loads[np.argmin(np.abs(loads - self.tire.nominal_load))])  # a measured load
        outputs = [o for o in ("fy", "mz") if o in data]
        fig, axes = plt.subplots(1, len(outputs), figsize=(5.5 * len(outputs), 4.2), squeeze=False)
        alpha_max = float(np.max(np.abs(data["alpha"][lateral])))
        x = np.linspace(-alpha_max, alpha_max, 81)
        for ax, out in zip(axes[0], outputs):
            for i, gamma in enumerate(cambers):
                on = lateral & (np.abs(data["fz"] - load) < 0.02 * load) & (np.abs(data["gamma"] - gamma) < CAMBER_GAP)
                color = f"C{i}"
                if on.any():
                    order = np.argsort(data["alpha"][on])
                    ax.plot(np.degrees(data["alpha"][on][order]), data[out][on][order], ".", color=color, ms=3,
                            label=f"data {np.degrees(gamma):+.1f} deg")
                model = self.tire.forces(np.full(x.size, load), 0.0, x, gamma, vx)
                ax.plot(np.degrees(x), getattr(model, out), "-", color=color, lw=1.2)
            for gamma in 0.5 * (cambers[1:] + cambers[:-1]):
                model = self.tire.forces(np.full(x.size, load), 0.0, x, gamma, vx)
                ax.plot(np.degrees(x), getattr(model, out), "--", lw=1.0, color="0.45")
            ax.plot([], [], "--", color="0.45", label="fit between the cambers")
            ax.set_xlabel("slip angle [deg]")
            ax.set_ylabel(f"{out} [{_OUTPUT_UNITS[out]}]")
            ax.set_title(f"{out} at {load:.0f} N against camber")
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7)
        fig.tight_layout()
        return fig

    def _cross_validation_figure(self):
        import matplotlib.pyplot as plt

        table = self.cross_validation
        channels = [c for c in ("fx", "fy", "mz", "mx", "my") if c in set(table["channel"])]
        fig, axes = plt.subplots(1, len(channels), figsize=(4.0 * len(channels), 4.2), squeeze=False)
        for ax, channel in zip(axes[0], channels):
            rows = table[table["channel"] == channel]
            positions = np.arange(len(rows))
            ax.bar(positions - 0.2, rows["held_out_percent"], 0.4, label="left out")
            ax.bar(positions + 0.2, rows["training_percent"], 0.4, label="in the fit")
            ax.set_xticks(positions)
            ax.set_xticklabels([t + (" *" if e else "") for t, e in zip(rows["level_text"], rows["extrapolation"])],
                               rotation=60, ha="right", fontsize=7)
            ax.set_ylabel("r.m.s. error over the peak [%]")
            ax.set_title(f"{channel}: each condition left out (* extrapolated)", fontsize=9)
            ax.grid(True, axis="y", alpha=0.3)
            ax.legend(fontsize=7)
        fig.tight_layout()
        return fig
