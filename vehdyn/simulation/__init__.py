"""Simulation: :func:`simulate` (the matrix exponential for a :class:`~vehdyn.LinearModel`, every
``scipy.integrate.solve_ivp`` method, a batched fixed-step RK4, compiled Runge-Kutta and BDF
loops) and :func:`simulate_many`; the integrators' work-precision (:func:`work_precision`);
:mod:`vehdyn.simulation.compiled`, the contract of a model's compiled right-hand side.

``vehdyn.simulate`` is :func:`simulate`; this package holds it and its private modules, as
``scipy.integrate`` holds ``solve_ivp`` in ``scipy.integrate._ivp``.
"""

from vehdyn.simulation._api import (
    SOLVE_IVP_METHODS,
    STIFF_STEPS_REFUSE,
    STIFF_STEPS_WARN,
    exact_discretization,
    rk4_stability_limit,
    simulate,
    simulate_many,
    stability_interval,
)
from vehdyn.simulation._work_precision import DEFAULT_TOLERANCES, work_precision

__all__ = ["simulate", "simulate_many", "SOLVE_IVP_METHODS", "rk4_stability_limit", "stability_interval",
           "exact_discretization", "STIFF_STEPS_WARN", "STIFF_STEPS_REFUSE", "work_precision", "DEFAULT_TOLERANCES"]
