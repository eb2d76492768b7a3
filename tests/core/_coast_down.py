"""A coast-down (one mass, quadratic drag) with a compiled rhs, for the background-build tests: small
enough to compile in seconds, with a closed form to check both backends against.

With the drive force F = 0 the speed is v(t) = v0 / (1 + c v0 t / m) and the distance
x(t) = (m / c) ln(1 + c v0 t / m) (separation of variables).
"""

import sys

import numpy as np

import vehdyn
from vehdyn.simulation.compiled import CompiledModel, compiled_copy, source_stamp


def _rhs(t, x, u, args, dxdt):
    mass, drag = args
    dxdt[0] = (u[0] - drag * x[0] * abs(x[0])) / mass
    dxdt[1] = x[0]


class CoastDown(vehdyn.Model):
    def __init__(self, mass=1500.0, drag=0.4):
        self.mass, self.drag = mass, drag
        self.declare(states=["longitudinal_velocity", "x_position"], inputs=["rear_longitudinal_force"])

    def rhs(self, t, x, u):
        return np.array([(u[0] - self.drag * x[0] * np.abs(x[0])) / self.mass, x[0]])

    def compiled_rhs(self):
        key = "coast_down_" + source_stamp(sys.modules[__name__])
        return CompiledModel(compiled_copy(_rhs, f"{key}_rhs"), None, key, (self.mass, self.drag))

    def closed_form(self, t, v0):
        """(v, x) at t [s] from v0 [m/s] at t = 0 with no drive force."""
        a = self.drag * v0 / self.mass
        return v0 / (1.0 + a * t), self.mass / self.drag * np.log1p(a * t)
