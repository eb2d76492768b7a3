"""Optimal control of vehdyn's models: direct multiple shooting over their symbolic forms, solved by IPOPT.

:class:`Problem` transcribes a model with a symbolic form (:func:`vehdyn.symbolic.to_casadi`) into a
nonlinear program by direct multiple shooting (Bock & Plitt 1984 [1]_): the states at the nodes of a grid
are unknowns, each interval is integrated by Runge-Kutta steps of the model's own equations, and the
continuity of the states across the nodes is a constraint. The grid runs in time, or along a state
(the distance travelled: a track's cones then sit at fixed nodes). Bounds and constraints on any
signal (states, inputs, outputs, input rates, time) and the cost are written in the signals' names;
IPOPT [2]_ (shipped with casadi) solves the program with CasADi's exact derivatives. casadi is optional
(``pip install 'vehdyn[optimal]'``).

References
----------
.. [1] H. G. Bock and K. J. Plitt, "A multiple shooting algorithm for direct solution of optimal
   control problems", *IFAC Proceedings Volumes* 17(2), 1603-1608, 1984.
.. [2] A. Wächter and L. T. Biegler, "On the implementation of an interior-point filter line-search
   algorithm for large-scale nonlinear programming", *Mathematical Programming* 106(1), 25-57, 2006.
"""

from vehdyn.optimal.lane_change import minimum_time_lane_change, passage_time
from vehdyn.optimal.nmpc import PathTrackingNMPC
from vehdyn.optimal.transcription import OptimalControlError, Problem, Solution

__all__ = ["Problem", "Solution", "OptimalControlError", "minimum_time_lane_change", "passage_time",
           "PathTrackingNMPC"]
