"""Simulation: :func:`simulate` (the matrix exponential for a :class:`~vehdyn.LinearModel`, every
``scipy.integrate.solve_ivp`` method, a batched fixed-step RK4, compiled Runge-Kutta and BDF
loops) and :func:`simulate_many`; the integrators' work-precision (:func:`work_precision`);
:mod:`vehdyn.simulation.compiled`, the contract of a model's compiled right-hand side.

``vehdyn.simulate`` is :func:`simulate`; this package holds it and its private modules, as
``scipy.integrate`` holds ``solve_ivp`` in ``scipy.integrate._ivp``: ``_api`` (``simulate``,
``simulate_many``), ``_inputs`` (the time grid, the options, input sampling and interpolation),
``_exact`` (the matrix exponential), ``_explicit`` (RK4, stability limits and intervals),
``_stiffness`` (the state Jacobian, the stiffness estimate, the method choice of ``"auto"``),
``_ivp`` (the ``solve_ivp`` route, the domain as events), ``_domain`` (a model's domain),
``_backend`` (the compiled backend and the batches), ``_bdf`` (the compiled BDF) and
``_work_precision``.
"""

from vehdyn.simulation._api import simulate, simulate_many
from vehdyn.simulation._exact import exact_discretization
from vehdyn.simulation._explicit import rk4_stability_limit, stability_interval
from vehdyn.simulation._ivp import SOLVE_IVP_METHODS
from vehdyn.simulation._stiffness import STIFF_STEPS_REFUSE, STIFF_STEPS_WARN
from vehdyn.simulation._work_precision import DEFAULT_TOLERANCES, work_precision

__all__ = ["simulate", "simulate_many", "SOLVE_IVP_METHODS", "rk4_stability_limit", "stability_interval",
           "exact_discretization", "STIFF_STEPS_WARN", "STIFF_STEPS_REFUSE", "work_precision", "DEFAULT_TOLERANCES"]
