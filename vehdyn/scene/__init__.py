"""Scenes and the fidelity ladder: the cheapest model that answers a scene, with its error.

A :class:`Scene` says what is asked (vehicle, manoeuvre and/or road, speed, duration, outputs,
tolerance). :func:`plan` assesses every rung of the one registry (:mod:`vehdyn.scene.registry`) and
picks the cheapest whose estimated error is within the tolerance, with a reason per rung;
:func:`run` runs it (``verify=True`` also runs the reference rung and measures the error);
:func:`ladder` runs every admissible rung and returns the speed-against-error table;
:func:`plot_ladder` draws it; :func:`standard_scenes` are the scenes the thresholds are measured on
(``benchmarks/bench_ladder.py``). Estimates and their provenance: :mod:`vehdyn.scene.estimates`.

Example::

    scene = vehdyn.Scene(vehicle="sedan", manoeuvre="lane_change", speed=27.8, duration=6.0,
                         manoeuvre_parameters={"lateral_acceleration": 1.0},
                         outputs=("yaw_rate", "lateral_acceleration"))
    print(vehdyn.plan(scene))
    out = vehdyn.run(scene, verify=True)
"""

from vehdyn.scene.definition import ROAD_EVENTS, STANDARD_MANOEUVRES, Scene
from vehdyn.scene.estimates import COST_PER_SIMULATED_SECOND, THRESHOLDS, relative_error
from vehdyn.scene.planner import Plan, RungAssessment, SceneResult, ladder, plan, plot_ladder, run
from vehdyn.scene.registry import RUNGS, NotAdmissible, Rung, Setup, SteadyStateAlgebra, register_rung, rungs
from vehdyn.scene.standard import standard_scenes

__all__ = ["Scene", "STANDARD_MANOEUVRES", "ROAD_EVENTS", "Plan", "RungAssessment", "SceneResult", "plan", "run",
           "ladder", "plot_ladder", "Rung", "Setup", "NotAdmissible", "RUNGS", "register_rung", "rungs",
           "SteadyStateAlgebra", "THRESHOLDS", "COST_PER_SIMULATED_SECOND", "relative_error", "standard_scenes"]
