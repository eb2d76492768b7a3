"""Symbolic forms of vehdyn's models: the same equations on CasADi symbols.

:func:`to_casadi` builds ``casadi.Function`` objects of a model's right-hand side and outputs by
calling the model's own equation functions (the ones its numpy and compiled paths run) with
CasADi [1]_ symbols through the namespace of :func:`casadi_namespace`: no equation is restated, and
every derivative an optimal-control solver asks for is exact. A model has a symbolic form when it
defines ``symbolic_equations(xp, x, u, parameters)`` (:meth:`vehdyn.Model.symbolic_equations`).

casadi is optional (``pip install 'vehdyn[optimal]'``) and imported on first use, never when
vehdyn is imported.

References
----------
.. [1] J. A. E. Andersson, J. Gillis, G. Horn, J. B. Rawlings and M. Diehl, "CasADi: a software
   framework for nonlinear optimization and optimal control", *Mathematical Programming
   Computation* 11(1), 1-36, 2019.
"""

from vehdyn.symbolic.form import SymbolicModel, to_casadi
from vehdyn.symbolic.namespace import casadi_namespace, is_symbolic, require_casadi

__all__ = ["SymbolicModel", "to_casadi", "casadi_namespace", "is_symbolic", "require_casadi"]
