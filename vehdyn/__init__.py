"""vehdyn: vehicle dynamics in Python -- tires, handling and ride.

API index (the curated entry points; every subpackage has its own index)
------------------------------------------------------------------------
Model contract (:mod:`vehdyn.model`)
    :class:`Signal`, :class:`Model`, :class:`LinearModel`, :class:`Modes`
Simulation and results (:mod:`vehdyn.simulation`)
    :func:`simulate` (backends "numpy" and "compiled"), :func:`simulate_many`, :class:`PiecewiseSignal`
    (closed-form inputs), :class:`SimulationResult`, :class:`FrequencyResponse`
Interconnection (:mod:`vehdyn.interconnect`)
    :class:`ClosedLoop` (a plant with drivers and chassis controllers in the loop), :func:`connect_in_series`
Parameters (:mod:`vehdyn.params`)
    :func:`load_vehicle`, :func:`shipped_vehicles`, :class:`Vehicle`, :func:`load_trailer`,
    :func:`shipped_trailers`, :class:`Trailer`, :func:`data_path`
Errors
    :class:`VehdynError`, :class:`ParameterError`, :class:`SimulationError`, :class:`TirFileError`,
    :class:`VehdynWarning`
Compiled code ahead of time
    :func:`warm_up` (``vehdyn compile``)
Scenes and the fidelity ladder (:mod:`vehdyn.scene`, imported on first use)
    :class:`Scene`, :func:`plan`, :func:`run`, :func:`ladder`, :func:`plot_ladder`

Subpackages, by layer (imported on first use)
    foundation: :mod:`vehdyn.params`, :mod:`vehdyn.conventions`, :mod:`vehdyn.units`;
    core: :mod:`vehdyn.model`, :mod:`vehdyn.simulation`, :mod:`vehdyn.interconnect`, :mod:`vehdyn.plotting`;
    physics: :mod:`vehdyn.mechanics`, :mod:`vehdyn.tire`, :mod:`vehdyn.road`, :mod:`vehdyn.components`;
    vehicles: :mod:`vehdyn.handling`, :mod:`vehdyn.ride`, :mod:`vehdyn.full_vehicle`;
    controllers: :mod:`vehdyn.driver`, :mod:`vehdyn.chassis`;
    procedures: :mod:`vehdyn.procedures`;
    applications: :mod:`vehdyn.scene`, :mod:`vehdyn.sweep` (sweeps, Monte Carlo, sensitivity);
    interfaces: :mod:`vehdyn.report`, :mod:`vehdyn.cli`.

Importing vehdyn imports numpy only; scipy, pandas, matplotlib and python-control are imported
when a function needs them.
"""

from __future__ import annotations

import importlib

from vehdyn.errors import ParameterError, SimulationError, TirFileError, VehdynError, VehdynWarning
from vehdyn.interconnect import ClosedLoop, connect_in_series
from vehdyn.model import LinearModel, Model, Modes
from vehdyn.params import Trailer, Vehicle, data_path, load_trailer, load_vehicle, shipped_trailers, shipped_vehicles
from vehdyn.piecewise_signal import PiecewiseSignal
from vehdyn.results import FrequencyResponse, SimulationResult
from vehdyn.signals import Signal
from vehdyn.simulation import simulate, simulate_many

__version__ = "0.1.0"

__all__ = [
    "Signal",
    "Model",
    "LinearModel",
    "Modes",
    "simulate",
    "simulate_many",
    "PiecewiseSignal",
    "SimulationResult",
    "FrequencyResponse",
    "ClosedLoop",
    "connect_in_series",
    "Vehicle",
    "load_vehicle",
    "shipped_vehicles",
    "data_path",
    "Trailer",
    "load_trailer",
    "shipped_trailers",
    "VehdynError",
    "ParameterError",
    "SimulationError",
    "TirFileError",
    "VehdynWarning",
    "Scene",
    "plan",
    "run",
    "ladder",
    "plot_ladder",
    "warm_up",
]

_SUBPACKAGES = {"params", "conventions", "units", "model", "simulation", "interconnect", "plotting", "mechanics",
                "tire", "road", "components", "handling", "ride", "full_vehicle", "driver", "chassis", "procedures",
                "scene", "sweep", "report", "cli"}
_SCENE_NAMES = {"Scene", "plan", "run", "ladder", "plot_ladder"}


def warm_up(models=None, progress: bool = True) -> dict:
    """Build the compiled code of the shipped models ahead of time (``vehdyn compile`` does the same).

    ``simulate``'s default ``backend="auto"`` answers a model's first call on numpy while its compiled
    code builds in the background (seconds for a single run, the compiler's time saved); call this once
    after installing when every run should be compiled from the first, e.g. before timing runs or a
    batch of short scripts. Takes 10-40 s per model the first time, a fraction of a second afterwards.

    Parameters
    ----------
    models : list of str, optional
        The models (default: all): names of :func:`vehdyn.cli.shipped_runs`.
    progress : bool
        Show a progress bar on stderr.

    Returns
    -------
    dict
        Per model the time it took [s].
    """
    from vehdyn import cli

    return cli.warm_up(models, progress=bool(progress))


def __getattr__(name: str):
    if name in _SUBPACKAGES:
        return importlib.import_module(f"vehdyn.{name}")
    if name in _SCENE_NAMES:
        return getattr(importlib.import_module("vehdyn.scene"), name)
    raise AttributeError(f"module 'vehdyn' has no attribute {name!r}")
