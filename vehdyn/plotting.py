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
    """An axis label from a signal name and unit.

    Parameters
    ----------
    name : str
        Signal name (snake_case; underscores become spaces).
    unit : str or None
        Its unit; none (or ``""``) leaves the brackets out.

    Returns
    -------
    str
        E.g. ``"yaw rate [rad/s]"``.

    Examples
    --------
    >>> from vehdyn.plotting import axis_label
    >>> axis_label("yaw_rate", "rad/s")
    'yaw rate [rad/s]'
    """
    text = name.replace("_", " ")
    return f"{text} [{unit}]" if unit else text


def new_figure(nrows: int = 1, ncols: int = 1, *, width: float = 6.4, height_per_row: float = 2.4, **kwargs):
    """A figure with a grid of axes sized for a report page.

    Parameters
    ----------
    nrows, ncols : int
        Rows and columns of axes.
    width : float
        Figure width [in].
    height_per_row : float
        Height of each row of axes [in]; the figure is at least 2.6 in high.
    **kwargs
        Passed to ``matplotlib.pyplot.subplots`` (``sharex=True``, ...).

    Returns
    -------
    fig : matplotlib.figure.Figure
        The figure.
    axes : ndarray of matplotlib.axes.Axes
        Its axes, shape (nrows, ncols) always.
    """
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
        The figure to save.
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
    """One axis per signal against time [s], each labelled with its unit.

    Parameters
    ----------
    result : SimulationResult
        The run.
    names : sequence of str
        Signals to plot (outputs, states or inputs), one axis each.
    fig : matplotlib.figure.Figure, optional
        An empty figure to draw into (default: a new one, :func:`new_figure`).
    batch : int, optional
        For a batched run, the variant to plot (default: every variant, one line each).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """

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
    """Bode plot: magnitude (log-log, or dB) and phase [deg] against frequency (log axis).

    Parameters
    ----------
    fr : FrequencyResponse
        The response.
    outputs, inputs : sequence of str, optional
        The channels (every output and every input by default); one line per pair.
    fig : matplotlib.figure.Figure, optional
        A figure to draw into: its first two axes if it has them (so that responses overlay),
        else two new ones (default: a new figure).
    hz : bool
        Frequency axis in Hz (default) or in rad/s.
    db : bool
        Magnitude in dB (20 log10) instead of a log axis.
    label : str, optional
        Legend label of every line (default: ``"output / input"``).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
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
