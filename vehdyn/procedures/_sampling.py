"""A procedure's own grid beside the output grid asked for: one integration, two samplings.

A procedure reads its metrics (and its verdict) off a grid fine enough for them, whatever output
grid the user asks for: both grids are integrated together (their union; an adaptive solver's steps
do not depend on the output times, so the samples on each grid are those of a run on it alone) and
the result is then taken apart.
"""

from __future__ import annotations

import dataclasses

import numpy as np

__all__ = ["union_grid", "at_samples"]


def union_grid(metric_time, output_time):
    """``(t, on_metric, on_output)``: the sorted union of both grids [s] and where each lies in it."""
    t = np.union1d(metric_time, output_time)
    return t, np.searchsorted(t, metric_time), np.searchsorted(t, output_time)


def at_samples(result, index, member=None):
    """The SimulationResult ``result`` at the time samples ``index`` (of batch ``member`` if given);
    ``result`` itself when that is all of it."""
    if member is None and index.size == result.time.size:
        return result

    def pick(values):
        values = values[:, index]
        return values[..., member] if member is not None and values.ndim == 3 else values

    return dataclasses.replace(result, time=result.time[index], states=pick(result.states),
                               inputs=pick(result.inputs), outputs=pick(result.outputs))
