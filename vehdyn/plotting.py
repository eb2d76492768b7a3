"""Matplotlib figures in the textbook's form: labelled axes with units, legends, log frequency axes.

matplotlib is imported inside each function, so importing vehdyn does not import it.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Sequence

import numpy as np

from vehdyn._atomic import atomic_write

if TYPE_CHECKING:  # pragma: no cover
    from vehdyn.results import FrequencyResponse, SimulationResult

__all__ = ["plot_time_histories", "bode_plot", "axis_label", "new_figure", "save_figure"]


def axis_label(name: str, unit: str | None) -> str:
    """``"yaw rate [rad/s]"`` from a signal name and unit."""
    text = name.replace("_", " ")
    return f"{text} [{unit}]" if unit else text


def new_figure(nrows: int = 1, ncols: int = 1, *, width: float = 6.4, height_per_row: float = 2.4, **kwargs):
    """A figure with a grid of axes sized for a report page."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(nrows, ncols, figsize=(width, max(2.6, height_per_row * nrows)), squeeze=False, **kwargs)
    return fig, axes


def save_figure(fig, path, *, dpi: float = 110, close: bool = True) -> Path:
    """Save ``fig`` to ``path`` atomically (format from the suffix) and close it.

    The image is written to a temporary file beside ``path`` and moved over it when complete, so an
    interrupted or failed save (disk full, an exception, Ctrl-C) leaves the previous file, or none,
    never a truncated image.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    path : str or os.PathLike
        Destination; its folder must exist. The suffix (``.png``, ``.svg``, ``.pdf``) sets the format.
    dpi : float
        Resolution [dots per inch] of raster formats.
    close : bool
        Close the figure afterwards (frees its memory in long runs).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    try:
        with atomic_write(path, "wb") as handle:
            fig.savefig(handle, format=fmt, dpi=dpi, bbox_inches="tight")
    finally:
        if close:
            import matplotlib.pyplot as plt

            plt.close(fig)
    return path


def plot_time_histories(result: "SimulationResult", names: Sequence[str], *, fig=None, batch=None):
    """One axis per signal against time [s]."""
    import matplotlib.pyplot as plt

    if fig is None:
        fig, axes = new_figure(len(names), 1, sharex=True)
        axes = axes[:, 0]
    else:
        axes = fig.subplots(len(names), 1, sharex=True, squeeze=False)[:, 0]
    for ax, name in zip(axes, names):
        y = result[name]
        if y.ndim == 2 and batch is not None:
            y = y[:, batch]
        ax.plot(result.time, y)
        ax.set_ylabel(axis_label(name, result.unit(name)), fontsize=8)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("time [s]")
    fig.tight_layout()
    return fig


def bode_plot(fr: "FrequencyResponse", outputs=None, inputs=None, *, fig=None, hz=True, db=False, label=None):
    """Bode plot: magnitude (log-log, or dB) and phase [deg] against frequency (log axis)."""
    outputs = list(outputs) if outputs is not None else list(fr.output_names)
    inputs = list(inputs) if inputs is not None else list(fr.input_names)
    if fig is None:
        fig, axes = new_figure(2, 1, sharex=True, height_per_row=2.8)
        ax_mag, ax_ph = axes[:, 0]
    else:
        ax_mag, ax_ph = fig.axes[:2] if len(fig.axes) >= 2 else fig.subplots(2, 1, sharex=True)
    f = fr.frequency_hz if hz else fr.omega
    for o in outputs:
        for i in inputs:
            h = fr[o, i]
            lab = label or f"{o} / {i}"
            if db:
                ax_mag.semilogx(f, 20 * np.log10(np.abs(h)), label=lab)
            else:
                ax_mag.loglog(f, np.abs(h), label=lab)
            ax_ph.semilogx(f, np.rad2deg(np.unwrap(np.angle(h))), label=lab)
    unit = fr.unit(outputs[0], inputs[0]) if len(outputs) == 1 and len(inputs) == 1 else ""
    ax_mag.set_ylabel(("magnitude [dB]" if db else "magnitude") + (f" {unit}" if unit and not db else ""))
    ax_ph.set_ylabel("phase [deg]")
    ax_ph.set_xlabel("frequency [Hz]" if hz else "angular frequency [rad/s]")
    for ax in (ax_mag, ax_ph):
        ax.grid(True, which="both", alpha=0.3)
    ax_mag.legend(fontsize=7)
    fig.tight_layout()
    return fig
