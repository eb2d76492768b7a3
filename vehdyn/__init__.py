"""vehdyn: vehicle dynamics in Python — tires, handling and ride.

API index
---------
Model contract
    :class:`Signal`, :class:`Model`, :class:`LinearModel`, :func:`connect_in_series`
Simulation and results
    :func:`simulate` (backends "numpy" and "compiled"), :class:`PiecewiseSignal` (closed-form inputs),
    :class:`SimulationResult`, :class:`FrequencyResponse`, :class:`Modes`
Parameters
    :func:`load_vehicle`, :func:`shipped_vehicles`, :class:`Vehicle` (and its groups in
    :mod:`vehdyn.params`), :func:`load_trailer`, :func:`shipped_trailers`, :class:`Trailer`, :func:`data_path`
Errors
    :class:`VehdynError`, :class:`ParameterError`, :class:`SimulationError`, :class:`TirFileError`,
    :class:`VehdynWarning`
Scenes and the fidelity ladder (imported on first use)
    :class:`Scene`, :func:`plan`, :func:`run`, :func:`ladder`, :func:`plot_ladder` (:mod:`vehdyn.scene`)
Sweeps, Monte Carlo and sensitivity (imported on first use)
    :mod:`vehdyn.sweep`: :func:`vehdyn.sweep.run` (grids and samples of a scene or a function;
    in-process, processes or Dask), :func:`vehdyn.sweep.sensitivity` (Sobol' and Morris indices
    through SALib)
Conventions and units
    :mod:`vehdyn.conventions` (SAE J670 / ISO 8855 / ISO-W signs), :mod:`vehdyn.units`
Subpackages (imported on first use)
    :mod:`vehdyn.mechanics` (rigid body), :mod:`vehdyn.tire`, :mod:`vehdyn.handling`,
    :mod:`vehdyn.ride`, :mod:`vehdyn.full_vehicle`, :mod:`vehdyn.chassis` (ABS, traction control, ESC,
    ``ClosedLoop``), :mod:`vehdyn.analysis`, :mod:`vehdyn.plotting`

Importing vehdyn imports numpy only; scipy, pandas, matplotlib and python-control are imported
when a function needs them.
"""

from __future__ import annotations

import importlib

from .errors import ParameterError, SimulationError, TirFileError, VehdynError, VehdynWarning
from .linear import LinearModel, connect_in_series
from .model import Model
from .params import Trailer, Vehicle, data_path, load_trailer, load_vehicle, shipped_trailers, shipped_vehicles
from .piecewise_signal import PiecewiseSignal
from .results import FrequencyResponse, SimulationResult
from .signals import Signal
from .simulate import simulate, simulate_many

__version__ = "0.1.0"

__all__ = [
    "Signal",
    "Model",
    "LinearModel",
    "connect_in_series",
    "simulate",
    "simulate_many",
    "PiecewiseSignal",
    "SimulationResult",
    "FrequencyResponse",
    "Modes",
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
]

_SUBPACKAGES = {"mechanics", "tire", "handling", "ride", "full_vehicle", "chassis", "analysis", "plotting",
                "conventions", "units", "params", "cli", "scene", "sweep"}
_SCENE_NAMES = {"Scene", "plan", "run", "ladder", "plot_ladder"}


def __getattr__(name: str):
    if name in _SUBPACKAGES:
        return importlib.import_module(f".{name}", __name__)
    if name in _SCENE_NAMES:
        return getattr(importlib.import_module(".scene", __name__), name)
    if name == "Modes":
        from .analysis.modal import Modes

        return Modes
    raise AttributeError(f"module 'vehdyn' has no attribute {name!r}")
