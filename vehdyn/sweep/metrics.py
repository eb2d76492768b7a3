"""The one registry of sweep metrics: named reductions of a run to one number.

A metric is a function ``f(run) -> float`` of a :class:`Run` (the time grid, the output signals
of one variant, its vehicle and speed) registered under a name with a unit. Two kinds:

* fixed names: ``understeer_gradient`` [rad/(m/s^2)], ``understeer_gradient_deg_per_g`` [deg/g],
  ``characteristic_speed`` [m/s] (Gillespie 1992, ch. 6; from the variant's vehicle, no run
  needed), ``yaw_rate_gain`` [1/s] (steady-state yaw rate per road-wheel steer at the speed);
* families over any output signal ``<family>_<signal>``: ``peak_`` (max ``|x|``), ``max_``, ``min_``,
  ``rms_`` (r.m.s. over the run), ``final_`` (last value), ``mean_``, and the ISO 7401 step
  metrics ``overshoot_`` [-], ``response_time_`` [s], ``rise_time_`` [s], ``steady_state_``
  (:func:`vehdyn.handling.transient.step_response_metrics`).

A user names metrics (``metrics=["peak_yaw_rate", "understeer_gradient"]``) instead of writing
code; :func:`register_metric` adds one, :func:`remove_metric` removes it.

References
----------
Gillespie, T. D. (1992). Fundamentals of Vehicle Dynamics. SAE, ch. 6 (understeer gradient,
characteristic speed).
ISO 7401:2011. Road vehicles - Lateral transient response test methods - Open-loop test methods.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.sweep.engines import RESERVED_COLUMNS

__all__ = ["Run", "Metric", "register_metric", "remove_metric", "metric", "metric_names", "FAMILIES"]


@dataclass
class Run:
    """One variant's run, as the metrics see it.

    Attributes
    ----------
    time : ndarray
        Time grid [s].
    outputs : dict
        Signal name -> values on ``time``.
    units : dict
        Signal name -> unit.
    vehicle : Vehicle or None
        The variant's vehicle (Scene targets).
    speed : float or None
        Forward speed [m/s].
    result : SimulationResult or None
        The full result (for metrics that need inputs, e.g. the steer's step time).
    """

    time: np.ndarray
    outputs: dict
    units: dict = field(default_factory=dict)
    vehicle: Any = None
    speed: float | None = None
    result: Any = None

    def signal(self, name: str) -> np.ndarray:
        """One output signal as floats.

        Parameters
        ----------
        name : str
            Signal name (a scene output).

        Returns
        -------
        ndarray
            Its values on :attr:`time` (in the signal's unit, :attr:`units`).
        """
        if name not in self.outputs:
            raise ParameterError(f"the run has no output {name!r}; it has {sorted(self.outputs)}", key="metrics",
                                 value=name)
        return np.asarray(self.outputs[name], dtype=float)


@dataclass(frozen=True)
class Metric:
    """A registered metric.

    Parameters
    ----------
    name : str
        The name a sweep's ``metrics`` list gives.
    function : callable
        ``function(run) -> float`` of a :class:`Run`.
    unit : str
        Unit of the value.
    description : str
        One line for listings.
    needs_run : bool
        False: computed from the variant's vehicle and speed alone (no simulation).
    """

    name: str
    function: Callable[[Run], float]
    unit: str
    description: str = ""
    needs_run: bool = True


_REGISTRY: dict[str, Metric] = {}


def register_metric(name: str, function: Callable[[Run], float], unit: str, description: str = "", *,
                    needs_run: bool = True) -> Metric:
    """Add (or replace) a metric named ``name``.

    Parameters
    ----------
    name : str
        An identifier, not one of the sweep table's own columns (``variant``, ``error``).
    function : callable
        ``function(run) -> float`` of a :class:`Run`.
    unit : str
        Unit of the value.
    description : str
        One line for listings.
    needs_run : bool
        False: computed from the variant's vehicle and speed alone (no simulation).

    Returns
    -------
    Metric
        The registered metric.
    """
    if not isinstance(name, str) or not name.isidentifier():
        raise ParameterError(f"a metric name must be an identifier, got {name!r}", key="name", value=name)
    if name in RESERVED_COLUMNS:
        raise ParameterError(f"metric name {name!r} is one of the sweep table's own columns", key="name", value=name)
    if not callable(function):
        raise ParameterError(f"metric {name!r}: function must be callable, got {function!r}", key="function",
                             value=function)
    m = Metric(name, function, unit, description, needs_run)
    _REGISTRY[name] = m
    return m


def remove_metric(name: str) -> Metric:
    """Remove the metric ``name`` added by :func:`register_metric`.

    Parameters
    ----------
    name : str
        A registered metric's name.

    Returns
    -------
    Metric
        The removed metric.

    Raises
    ------
    ParameterError
        When no metric of that name is registered.
    """
    if name not in _REGISTRY:
        raise ParameterError(f"no registered metric {name!r}; registered: {sorted(_REGISTRY)}", key="name", value=name)
    return _REGISTRY.pop(name)


def _step(run: Run, signal: str, attribute: str) -> float:
    from vehdyn.procedures.iso7401 import step_response_metrics

    if run.result is None:
        raise ParameterError(f"ISO 7401 metrics of {signal!r} need a simulation result", key="metrics", value=signal)
    steer = "front_steer_angle" if "front_steer_angle" in run.result else None
    return float(getattr(step_response_metrics(run.result, signal, steer=steer), attribute))


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean(x * x)))


#: Families: prefix -> (reduction of (run, signal), unit of the result given the signal's unit, description).
FAMILIES: dict[str, tuple[Callable[[Run, str], float], Callable[[str], str], str]] = {
    "peak": (lambda r, s: float(np.max(np.abs(r.signal(s)))), lambda u: u, "max |{s}|"),
    "max": (lambda r, s: float(np.max(r.signal(s))), lambda u: u, "max of {s}"),
    "min": (lambda r, s: float(np.min(r.signal(s))), lambda u: u, "min of {s}"),
    "mean": (lambda r, s: float(np.mean(r.signal(s))), lambda u: u, "mean of {s}"),
    "rms": (lambda r, s: _rms(r.signal(s)), lambda u: u, "r.m.s. of {s} over the run"),
    "final": (lambda r, s: float(r.signal(s)[-1]), lambda u: u, "{s} at the end of the run"),
    "overshoot": (lambda r, s: _step(r, s, "overshoot"), lambda u: "-", "ISO 7401 overshoot of {s}"),
    "response_time": (lambda r, s: _step(r, s, "response_time"), lambda u: "s", "ISO 7401 response time of {s}"),
    "rise_time": (lambda r, s: _step(r, s, "rise_time"), lambda u: "s", "ISO 7401 rise time of {s}"),
    "steady_state": (lambda r, s: _step(r, s, "steady_state_value"), lambda u: u, "ISO 7401 steady state of {s}"),
}


def _vehicle(run: Run):
    if run.vehicle is None:
        raise ParameterError("this metric needs a vehicle (a Scene target)", key="metrics", value=None)
    return run.vehicle


def _register_builtins():
    def ug(run):
        from vehdyn.handling.steady_state import understeer_gradient

        return float(understeer_gradient(_vehicle(run)))

    def ug_deg(run):
        from vehdyn.handling.steady_state import understeer_gradient_deg_per_g

        return float(understeer_gradient_deg_per_g(_vehicle(run)))

    def vch(run):
        from vehdyn.handling.steady_state import characteristic_speed

        return float(characteristic_speed(_vehicle(run)))

    def yaw_gain(run):
        from vehdyn.handling.steady_state import steady_state_gains

        return float(steady_state_gains(_vehicle(run), run.speed).yaw_rate)

    register_metric("understeer_gradient", ug, "rad/(m/s^2)", "linear understeer gradient K (Gillespie 1992, 6)",
                    needs_run=False)
    register_metric("understeer_gradient_deg_per_g", ug_deg, "deg/g", "understeer gradient in deg/g",
                    needs_run=False)
    register_metric("characteristic_speed", vch, "m/s", "sqrt(L/K) (inf for a neutral or oversteering car)",
                    needs_run=False)
    register_metric("yaw_rate_gain", yaw_gain, "1/s", "steady-state yaw rate per front steer at the speed",
                    needs_run=False)


_register_builtins()


def metric_names() -> list[str]:
    """The fixed metric names and the family patterns (``peak_<signal>``, ...).

    Returns
    -------
    list of str
    """
    return sorted(_REGISTRY) + [f"{p}_<signal>" for p in FAMILIES]


def metric(name: str, signals: dict | None = None) -> Metric:
    """The :class:`Metric` called ``name`` (a fixed name or ``<family>_<signal>``).

    Parameters
    ----------
    name : str
        A fixed name or ``<family>_<signal>``.
    signals : dict, optional
        Output signal -> unit of the target; a family metric must name one of them.

    Returns
    -------
    Metric

    Raises
    ------
    ParameterError
        For an unknown name, listing the close matches.
    """
    if name in _REGISTRY:
        return _REGISTRY[name]
    for prefix in sorted(FAMILIES, key=len, reverse=True):
        if name.startswith(prefix + "_"):
            signal = name[len(prefix) + 1:]
            if signals is not None and signal not in signals:
                continue
            reduce, unit, text = FAMILIES[prefix]
            return Metric(name, lambda run, _s=signal, _f=reduce: _f(run, _s),
                          unit((signals or {}).get(signal, "")), text.format(s=signal))
    known = sorted(_REGISTRY) + [f"{p}_{s}" for p in FAMILIES for s in (signals or ())]
    close = difflib.get_close_matches(name, known, n=5, cutoff=0.6)
    hint = f"; close matches: {close}" if close else ""
    within = f" with <signal> one of {sorted(signals)}" if signals else ""
    raise ParameterError(f"unknown metric {name!r}{hint}. Metrics are {sorted(_REGISTRY)} and "
                         f"{[p + '_<signal>' for p in FAMILIES]}{within}", key="metrics", value=name)
