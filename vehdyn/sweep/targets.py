"""What a sweep varies and runs: a :class:`~vehdyn.Scene` or a function of named parameters.

A target turns one variant's parameters into metric values. Targets are plain, picklable objects
(a Scene and names, or a module-level function) so that every engine - in-process, a process pool,
Dask workers - runs the same code on the same variants and gives bitwise the same numbers.
"""

from __future__ import annotations

import dataclasses
import difflib
import inspect
from typing import Any, Callable, Mapping

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.sweep import metrics as _metrics
from vehdyn.sweep.engines import RESERVED_COLUMNS, _is_real

__all__ = ["vectorized", "SceneTarget", "FunctionTarget", "as_target", "vehicle_parameter_names", "simulation_call"]


def vectorized(function: Callable) -> Callable:
    """Mark ``function(**params) -> mapping`` as accepting arrays of parameters (one element per
    variant, the trailing batch axis of DESIGN §3) and returning arrays of metrics.

    The in-process engine then calls it once per chunk; a chunk whose batched call raises is run
    again variant by variant, so that only the bad variants fail.

    Parameters
    ----------
    function : callable
        ``function(**params) -> mapping`` of metric name -> array (one value per variant, or a
        scalar broadcast to all).

    Returns
    -------
    callable
        ``function`` itself, marked (used as a decorator: ``@vehdyn.sweep.vectorized``).
    """
    function.__vehdyn_vectorized__ = True
    return function


def _python(value):
    """numpy scalars and 0-d arrays -> Python scalars (parameter validation accepts int and float)."""
    if isinstance(value, np.generic) or (isinstance(value, np.ndarray) and value.ndim == 0):
        return value.item()
    return value


def _close(name: str, known, what: str) -> ParameterError:
    close = difflib.get_close_matches(name, list(known), n=5, cutoff=0.6)
    hint = f"; close matches: {close}" if close else f"; the {what} are {sorted(known)}"
    return ParameterError(f"unknown parameter {name!r}{hint}", key=name, value=name)


def vehicle_parameter_names(vehicle, prefix: str = "vehicle.") -> dict[str, str]:
    """Dotted name -> unit of every numeric and text parameter of ``vehicle`` (nested groups).

    Parameters
    ----------
    vehicle : Vehicle or ParameterSet
        A vehicle (or one of its parameter groups).
    prefix : str
        Prepended to every name (``"vehicle."``: the names a Scene sweep varies).

    Returns
    -------
    dict
        E.g. ``{"vehicle.mass.mass": "kg", "vehicle.tires.front_cornering_stiffness": "N/rad", ...}``.
    """
    from vehdyn.params.base import ParameterSet

    out = {}
    for f in dataclasses.fields(vehicle):
        value = getattr(vehicle, f.name)
        if isinstance(value, ParameterSet):
            out.update(vehicle_parameter_names(value, f"{prefix}{f.name}."))
        elif "unit" in f.metadata:
            out[f"{prefix}{f.name}"] = f.metadata["unit"]
    return out


_SCENE_UNITS = {"speed": "m/s", "duration": "s", "tolerance": "-", "time_step": "s", "seed": "", "tire": "",
                "manoeuvre": "", "vehicle": "", "road": ""}


class SceneTarget:
    """A :class:`~vehdyn.Scene` varied by dotted names, run on one rung of the ladder.

    The rung is planned once, on the base scene (``model="auto"``), or named; every variant runs on
    it, so that the metrics of all variants come from the same model.

    Parameters
    ----------
    scene : Scene
        The base scene; each variant is this scene with some of its values replaced.
    model : str
        ``"auto"`` or a rung name (``"SingleTrack"``, ``"LinearBicycle"``, ``"QuarterCar"`` ...).
    solver : mapping, optional
        ``method``, ``rtol`` [-], ``atol`` of every variant's ``simulate`` call in place of the
        rung's (:func:`vehdyn.sweep.run`); ParameterError for another key, a bad value, or a rung
        that does not integrate with a solver (an exact linear discretization).
    """

    def __init__(self, scene, model: str = "auto", solver=None):
        from vehdyn.scene.planner import plan

        self.scene = scene
        self.vehicle = scene.load_vehicle()
        p = plan(scene)
        row = p.chosen if model == "auto" else p.row(model)
        self.rung = row.rung.name
        self.solver = _solver_options(solver)
        if self.solver:
            call = simulation_call(row.setup.run)
            method = None if call is None else call[1].get("method")
            if call is None or method in (None, "exact"):
                raise ParameterError(f"solver={solver!r}: the rung {self.rung!r} does not integrate with a solver "
                                     "(its runs are exact or not one simulate call)", key="solver", value=solver)
        self.signals = dict(row.outputs)  # scene output -> model output
        model_units = {s.name: s.unit for s in getattr(row.setup.model, "outputs", ())}
        self.units = {o: model_units.get(m, "") for o, m in self.signals.items()}
        self.parameters = dict(vehicle_parameter_names(self.vehicle))
        for f in dataclasses.fields(scene):
            if f.name not in ("outputs", "manoeuvre_parameters"):
                self.parameters[f.name] = _SCENE_UNITS.get(f.name, "")
        from vehdyn.scene.definition import ROAD_EVENTS, STANDARD_MANOEUVRES

        if isinstance(scene.manoeuvre, str):
            for k in STANDARD_MANOEUVRES[scene.manoeuvre]:
                self.parameters[f"manoeuvre_parameters.{k}"] = ""
        if isinstance(scene.road, Mapping):
            for k in ROAD_EVENTS[scene.road["event"]]:
                self.parameters[f"road.{k}"] = ""

    def identity(self) -> dict:
        """What the variants' results depend on, for the sweep's manifest.

        Returns
        -------
        dict
            ``kind`` ("scene"), ``scene`` (the base scene), ``vehicle`` (its loaded parameters),
            ``tires`` (the tire laws its ``.tir`` files and the scene's ``tire`` hold, so that a
            file edited between two runs shows), ``rung`` (the model every variant runs) and
            ``solver`` (the options replacing the rung's).
        """
        from vehdyn.tire import load_tire, tire_for_vehicle

        tires = {}
        try:
            if self.scene.tire is not None:
                tires["scene"] = load_tire(self.scene.tire)
            if getattr(self.vehicle.tires, "tir_file", None):
                tires.update({axle: tire_for_vehicle(self.vehicle, axle) for axle in ("front", "rear")})
        except Exception:  # a tire that does not load fails in the variants' rows; its name is in the scene
            pass
        return {"kind": "scene", "scene": self.scene, "vehicle": self.vehicle, "tires": tires, "rung": self.rung,
                "solver": self.solver}

    def check_names(self, names) -> dict[str, str]:
        """Units of ``names``; ParameterError with the close matches for an unknown one.

        Parameters
        ----------
        names : sequence of str
            Dotted parameter names.

        Returns
        -------
        dict
            Name -> unit.
        """
        for name in names:
            if name not in self.parameters:
                raise _close(name, self.parameters, "parameters")
        return {n: self.parameters[n] for n in names}

    def default_metrics(self) -> list[str]:
        """``peak_<output>`` of each of the scene's outputs.

        Returns
        -------
        list of str
        """
        return [f"peak_{o}" for o in self.scene.outputs]

    def resolve_metrics(self, names) -> dict[str, str]:
        """Units of the metrics ``names`` (ParameterError for an unknown one).

        Parameters
        ----------
        names : sequence of str
            Metric names (:mod:`vehdyn.sweep.metrics`).

        Returns
        -------
        dict
            Name -> unit.
        """
        return {n: _metrics.metric(n, self.units).unit for n in names}

    def variant(self, params: Mapping[str, Any]):
        """The scene of one variant (ParameterError for invalid values).

        Parameters
        ----------
        params : mapping
            Dotted name -> value (units as the scene's and vehicle's fields).

        Returns
        -------
        Scene
        """
        vehicle_changes, fields, manoeuvre, road = {}, {}, {}, {}
        for name, value in params.items():
            value = _python(value)
            head, _, rest = name.partition(".")
            if head == "vehicle" and rest:
                vehicle_changes[rest.replace(".", "__")] = value
            elif head == "manoeuvre_parameters":
                manoeuvre[rest] = value
            elif head == "road" and rest:
                road[rest] = value
            else:
                fields[name] = value
        if vehicle_changes:
            base = fields.pop("vehicle", None)
            vehicle = self.vehicle if base is None else self.scene.replace(vehicle=base).load_vehicle()
            fields["vehicle"] = vehicle.replace(**vehicle_changes)
        elif "vehicle" not in fields:
            fields["vehicle"] = self.vehicle
        if manoeuvre:
            fields["manoeuvre_parameters"] = {**self.scene.manoeuvre_parameters, **manoeuvre}
        if road:
            fields["road"] = {**self.scene.road, **road}
        return self.scene.replace(**fields)

    def _build(self, scene):
        from vehdyn.scene.drive import drive_of
        from vehdyn.scene.registry import rungs

        rung = next(r for r in rungs() if r.name == self.rung)
        return rung.setup(drive_of(scene))

    def setup(self, params: Mapping[str, Any]):
        """The sweep's rung built for one variant: its model and its run (the rung's own
        solver; :meth:`call` gives the call with the sweep's ``solver`` options).

        Parameters
        ----------
        params : mapping
            Dotted name -> value.

        Returns
        -------
        vehdyn.scene.registry.Setup
        """
        return self._build(self.variant(params))

    def _prepare(self, params: Mapping[str, Any], wanted):
        """(run, setup) of one variant: the metrics' :class:`~vehdyn.sweep.metrics.Run` without
        outputs and the rung built for the variant's scene (None when no metric needs a run)."""
        scene = self.variant(params)
        run = _metrics.Run(time=scene.time(), outputs={}, units=self.units, vehicle=scene.load_vehicle(),
                           speed=scene.speed)
        if not any(m.needs_run for m in wanted):
            return run, None
        return run, self._build(scene)

    def _finish(self, run, result, wanted) -> dict[str, float]:
        if result is not None:
            run.outputs = {o: np.asarray(result[m], dtype=float) for o, m in self.signals.items()}
            run.result = result
        return {m.name: float(m.function(run)) for m in wanted}

    def call(self, setup):
        """The ``simulate`` call of a variant's rung, with the sweep's solver options.

        Parameters
        ----------
        setup : vehdyn.scene.registry.Setup
            The rung built for the variant (:meth:`setup`).

        Returns
        -------
        tuple or None
            ``(args, kwargs)`` of :func:`vehdyn.simulate`, or None when the rung's run is not one
            ``simulate`` call (it then runs as it is).
        """
        call = simulation_call(setup.run)
        if call is not None and self.solver:
            call[1].update(self.solver)
        return call

    def run(self, params: Mapping[str, Any], metric_names) -> dict[str, float]:
        """The metrics of one variant.

        Parameters
        ----------
        params : mapping
            Dotted name -> value.
        metric_names : sequence of str
            Metric names.

        Returns
        -------
        dict
            Metric name -> value (unit of the metric).
        """
        from vehdyn.simulation import simulate

        wanted = [_metrics.metric(n, self.units) for n in metric_names]
        run, setup = self._prepare(params, wanted)
        if setup is None:
            return self._finish(run, None, wanted)
        call = self.call(setup) if self.solver else None
        return self._finish(run, setup.run() if call is None else simulate(*call[0], **call[1]), wanted)

    def run_many(self, rows: list[Mapping[str, Any]], metric_names, threads=None) -> list:
        """:meth:`run` of many variants, their simulations batched by
        :func:`vehdyn.simulate_many` (compiled batches of the variants that share a model
        structure; bitwise the results of :meth:`run`).

        Parameters
        ----------
        rows : list of mapping
            One mapping dotted name -> value per variant.
        metric_names : sequence of str
            Metric names.
        threads : int, optional
            Threads of the compiled batches (:func:`vehdyn.simulate_many`).

        Returns
        -------
        list
            Per variant its metrics (a dict) or the exception it raised.
        """
        from vehdyn.simulation import simulate_many

        wanted = [_metrics.metric(n, self.units) for n in metric_names]
        out: list = [None] * len(rows)
        pending, calls = [], []
        for i, params in enumerate(rows):
            try:
                run, setup = self._prepare(params, wanted)
                call = None if setup is None else self.call(setup)
                if setup is None or call is None:
                    out[i] = self._finish(run, None if setup is None else setup.run(), wanted)
                else:
                    pending.append((i, run))
                    calls.append(call)
            except Exception as exc:  # one bad variant never loses the sweep
                out[i] = exc
        for (i, run), result in zip(pending, simulate_many(calls, threads=threads)):
            try:
                if isinstance(result, Exception):
                    raise result
                out[i] = self._finish(run, result, wanted)
            except Exception as exc:
                out[i] = exc
        return out


class _Recorded(Exception):
    pass


def simulation_call(run: Callable):
    """The ``simulate`` call a rung's ``Setup.run`` makes, as ``(args, kwargs)``, without running it.

    The ladder's builders return ``lambda: simulate(model, time, inputs, x0=..., **options)``: the
    closure is called once with its ``simulate`` cell replaced by a recorder.

    Parameters
    ----------
    run : callable
        A rung's ``Setup.run``.

    Returns
    -------
    tuple or None
        ``(args, kwargs)``; None when ``run`` is not a closure that calls :func:`vehdyn.simulate`
        (it then runs as is).
    """
    import types

    from vehdyn.simulation import simulate

    code, cells = getattr(run, "__code__", None), getattr(run, "__closure__", None)
    if code is None or not cells or "simulate" not in code.co_freevars:
        return None
    names = dict(zip(code.co_freevars, cells))
    try:
        if names["simulate"].cell_contents is not simulate:
            return None
    except ValueError:  # an empty cell
        return None
    recorded = []

    def record(*args, **kwargs):
        recorded.append((args, kwargs))
        raise _Recorded

    closure = tuple(types.CellType(record) if n == "simulate" else c for n, c in names.items())
    try:
        types.FunctionType(code, run.__globals__, run.__name__, run.__defaults__, closure)()
    except _Recorded:
        return recorded[0]
    return None


class FunctionTarget:
    """A function ``f(**params) -> mapping of scalars`` (or arrays, if :func:`vectorized`).

    Parameters
    ----------
    function : callable
        Called with the parameters by name; returns metric name -> value. Its attribute
        ``units`` (a mapping name -> unit), if any, gives the units of the table's columns.
    """

    def __init__(self, function: Callable):
        self.function = function
        self.vectorized = bool(getattr(function, "__vehdyn_vectorized__", False))
        self.units = dict(getattr(function, "units", {}) or {})
        try:
            sig = inspect.signature(function)
        except (TypeError, ValueError):
            sig = None
        params = [] if sig is None else list(sig.parameters.values())
        self.any_name = sig is None or any(p.kind is p.VAR_KEYWORD for p in params)
        self.parameters = [p.name for p in params if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]

    def identity(self) -> dict:
        """What the variants' results depend on, for the sweep's manifest.

        Returns
        -------
        dict
            ``kind`` ("function"), ``function`` (described by
            :func:`vehdyn.sweep.manifest.canonical`: qualified name, source hash, defaults and
            closure) and ``vectorized``.
        """
        return {"kind": "function", "function": self.function, "vectorized": self.vectorized}

    def check_names(self, names) -> dict[str, str]:
        """Units of ``names``; ParameterError with the close matches for a name the function
        does not take.

        Parameters
        ----------
        names : sequence of str
            Parameter names.

        Returns
        -------
        dict
            Name -> unit (from the function's ``units``; "" when it has none).
        """
        if not self.any_name:
            for name in names:
                if name not in self.parameters:
                    raise _close(name, self.parameters, "parameters")
        return {n: self.units.get(n, "") for n in names}

    def default_metrics(self) -> None:
        """None: every key the function returns is a metric.

        Returns
        -------
        None
        """
        return None

    def resolve_metrics(self, names) -> dict[str, str]:
        """Units of the metrics ``names`` (from the function's ``units``).

        Parameters
        ----------
        names : sequence of str
            Metric names (keys of the function's result).

        Returns
        -------
        dict
            Name -> unit.
        """
        return {n: self.units.get(n, "") for n in names}

    @staticmethod
    def _select(out, metric_names, params) -> list[str]:
        if not isinstance(out, Mapping):
            raise ParameterError(f"the sweep function must return a mapping of metrics, got {type(out).__name__}",
                                 key="target", value=type(out).__name__)
        if metric_names is not None:
            keys = list(metric_names)
        else:  # every key: none may take a column of the table's own
            keys = list(out)
            for k in keys:
                if not isinstance(k, str) or not k:
                    raise ParameterError(f"the sweep function returned a metric named {k!r}; metric names are "
                                         "non-empty text", key="metrics", value=k)
                if k in RESERVED_COLUMNS or k in params:
                    what = "the table's own column" if k in RESERVED_COLUMNS else "a parameter's column"
                    raise ParameterError(f"the sweep function returned a metric named {k!r}, which is {what}; "
                                         "rename it, or name the metrics wanted with metrics=[...]", key="metrics",
                                         value=k)
        missing = [k for k in keys if k not in out]
        if missing:
            raise ParameterError(f"the sweep function returned no metric {missing[0]!r}; it returned {sorted(out)}",
                                 key="metrics", value=missing[0])
        return keys

    def run(self, params: Mapping[str, Any], metric_names) -> dict[str, float]:
        """The metrics of one variant.

        Parameters
        ----------
        params : mapping
            Parameter name -> value (numpy scalars passed as Python numbers).
        metric_names : sequence of str or None
            The metrics to keep (None: every key returned).

        Returns
        -------
        dict
            Metric name -> float.
        """
        out = self.function(**{k: _python(v) for k, v in params.items()})
        return {k: float(out[k]) for k in self._select(out, metric_names, params)}

    def run_batch(self, columns: Mapping[str, np.ndarray], count: int, metric_names) -> dict[str, np.ndarray]:
        """The metrics of ``count`` variants from one call with array parameters.

        Parameters
        ----------
        columns : mapping
            Parameter name -> array of ``count`` values.
        count : int
            Number of variants.
        metric_names : sequence of str or None
            The metrics to keep (None: every key returned).

        Returns
        -------
        dict
            Metric name -> array of ``count`` floats.
        """
        out = self.function(**columns)
        return {k: np.array(np.broadcast_to(np.asarray(out[k], dtype=float), (count,)))
                for k in self._select(out, metric_names, columns)}


_SOLVER_KEYS = ("method", "rtol", "atol")


def _solver_options(solver) -> dict:
    """The validated ``solver`` options of a Scene sweep ({} for None)."""
    if solver is None:
        return {}
    from vehdyn.simulation import SOLVE_IVP_METHODS

    if not isinstance(solver, Mapping):
        raise ParameterError(f"solver must be a mapping of {_SOLVER_KEYS}, got {solver!r}", key="solver",
                             value=solver)
    unknown = [k for k in solver if k not in _SOLVER_KEYS]
    if unknown:
        raise ParameterError(f"solver option {unknown[0]!r} is not one of {_SOLVER_KEYS}", key="solver",
                             value=unknown[0])
    options = dict(solver)
    if "method" in options and options["method"] not in SOLVE_IVP_METHODS:
        raise ParameterError(f"solver method {options['method']!r} is not one of {SOLVE_IVP_METHODS}",
                             key="solver", value=options["method"])
    for key in ("rtol", "atol"):
        if key in options:
            value = options[key]
            if not _is_real(value) or not (0 < value < np.inf):
                raise ParameterError(f"solver {key} must be a positive number, got {value!r}", key="solver",
                                     value=value)
            options[key] = float(value)
    if "rtol" in options and "atol" not in options:
        options["atol"] = 1e-2 * options["rtol"]
    return options


def as_target(target, model: str = "auto", solver=None):
    """A :class:`SceneTarget` or :class:`FunctionTarget` for ``target``.

    Parameters
    ----------
    target : Scene, callable, SceneTarget or FunctionTarget
        What a sweep runs (a target is returned as it is).
    model : str
        Scene targets: ``"auto"`` or a rung name.
    solver : mapping, optional
        Scene targets only: options of every variant's ``simulate`` call.

    Returns
    -------
    SceneTarget or FunctionTarget
    """
    from vehdyn.scene.definition import Scene

    if isinstance(target, (SceneTarget, FunctionTarget)):
        if solver is not None:
            raise ParameterError("solver= applies when the target is a Scene (give it to SceneTarget)", key="solver",
                                 value=solver)
        return target
    if isinstance(target, Scene):
        return SceneTarget(target, model, solver)
    if callable(target):
        if solver is not None:
            raise ParameterError("solver= applies to a Scene target; a function runs its own simulations",
                                 key="solver", value=solver)
        return FunctionTarget(target)
    raise ParameterError(f"sweep target must be a Scene or a function of the parameters, got "
                         f"{type(target).__name__}", key="target", value=type(target).__name__)
