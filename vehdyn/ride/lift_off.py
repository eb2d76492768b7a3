"""Unilateral tire contact for the linear ride models: the wheel lifts off the road and lands again.

:class:`LiftOff` takes a linear ride model (:class:`~vehdyn.ride.FullCar`,
:class:`~vehdyn.ride.BouncePitch`, :class:`~vehdyn.ride.QuarterCar`, each with unsprung masses)
and replaces its bilateral tire spring by a contact that can push but not pull. Everything else
is the linear model's own matrices: the model adds one correction force per wheel, nothing of the
ride model's equations is restated.

Equations
---------
The linear model (:mod:`vehdyn.ride._ride_model`) is M q'' + C q' + K q = F u with the tire of
wheel i a spring k_t and damper c_t on the tire deflection (compression) z_r - z_u, so that its
force on the wheel is the static load plus

    dF_lin = k_t (z_r - z_u) + c_t (z_r' - z_u')           [N, up on the wheel]

with z_r the road under the wheel and z_u the wheel's displacement (both up from static
equilibrium, as in every ride model). A real tire carries no tension: with the static load F_s and
the static deflection delta_0 = F_s / k_t, the tire's total compression is
delta = delta_0 + z_r - z_u and its force

    F = max(F_s + dF_lin, 0)   where delta > 0,   F = 0 where delta <= 0

(the same law as the full vehicle's corners, :func:`vehdyn.full_vehicle.corner.normal_load`: the
wheel is off the road when the tire is uncompressed; while it unloads, the damper cannot pull it
down either). The model is the linear one with the correction f_c = F - (F_s + dF_lin) added as a
force on the wheel:

    x' = A x + B u + e_i f_c / m_u,       y = C x + D u (+ f_c in ``dynamic_tire_load``,
    + f_c / m_u in ``unsprung_acceleration`` of wheel i)

so that with every wheel on the road (f_c = 0) it *is* the linear model, to round-off. While a
wheel is off the road it flies under gravity and its suspension spring and damper only,
m_u z_u'' = F_susp - m_u g in absolute terms (in the model's coordinates about the static
equilibrium the static loads are part of the correction).

Static loads: the static equilibrium of the linear model's springs under gravity, K q_g = f_g with
f_g = -g x (the mass of each translational coordinate: the body's heave, the wheels), F_s,i =
-k_t,i z_u,i(q_g); for the full car of a vehicle the sprung weight splits by the sprung CG's
position (m_s g b / (2 L) at a front wheel) and each wheel adds its own weight.

Signs: as the ride models (up positive, ``dynamic_tire_load`` positive = more load, so a lifted
wheel shows -F_s). Units SI.

References
----------
Gillespie, T. D., *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5 (ride; wheel hop and the
tire's vertical load). Jazar, R. N., *Vehicle Dynamics: Theory and Application*, Springer, 2008,
ch. 14 (vehicle vibrations) and 15 (suspension optimization; full car, sec. 15.5). Wong, J. Y.,
*Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 7.2 (tire lift-off on rough roads).
"""

from __future__ import annotations

import functools

import numpy as np

from ..errors import ParameterError
from ..model import Model
from ..units import GRAVITY

__all__ = ["LiftOff"]


class LiftOff(Model):
    """A linear ride model with unilateral tire contact (the wheels lift off and land again).

    Parameters
    ----------
    model : RideModel
        A :class:`~vehdyn.ride.QuarterCar`, :class:`~vehdyn.ride.BouncePitch` or
        :class:`~vehdyn.ride.FullCar` whose every corner has an unsprung mass (a wheel that can
        leave the road).
    gravity : float, optional
        Gravitational acceleration [m/s^2] that sets the static tire loads (default
        :data:`vehdyn.units.GRAVITY`).
    name : str, optional

    Attributes
    ----------
    linear : RideModel
        The model with bilateral tires (the same states, inputs and outputs).
    static_tire_load : ndarray
        F_s [N] per corner, in the order of ``linear.corners``.

    Notes
    -----
    States, inputs and outputs are the linear model's (module docstring: the equations); the
    phenomena add ``wheel_lift``. On a road that never unloads a wheel the result equals the
    linear model's. ``simulate(model, ..., method="RK45")`` runs a compiled right-hand side when
    numba is installed (:meth:`compiled_rhs`), else the numpy one.

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.ride import FullCar, LiftOff
    >>> car = LiftOff(FullCar.from_vehicle(vehdyn.load_vehicle("sedan")))
    >>> sorted(car.phenomena)[-1]
    'wheel_lift'
    """

    def __init__(self, model, *, gravity: float = GRAVITY, name: str | None = None):
        from ._ride_model import RideModel

        if not isinstance(model, RideModel):
            raise ParameterError(f"LiftOff needs a linear ride model (QuarterCar, BouncePitch, FullCar), got "
                                 f"{type(model).__name__}", key="model", value=type(model).__name__)
        rigid = [c.suffix or "(single corner)" for c in model.corners if not c.has_unsprung_mass]
        if rigid:
            raise ParameterError(f"LiftOff needs an unsprung mass at every corner (a wheel that can leave the road); "
                                 f"corners {rigid} have none", key="model", value=rigid)
        if model.has_actuators:
            raise ParameterError("LiftOff takes a passive ride model (no actuator inputs)", key="model",
                                 value=model.name)
        g = float(gravity) if isinstance(gravity, (int, float, np.floating)) and not isinstance(gravity, bool) \
            else float("nan")
        if not np.isfinite(g) or g <= 0:
            raise ParameterError(f"gravity must be a finite number > 0 [m/s^2], got {gravity!r}", key="gravity",
                                 value=gravity)
        self.linear, self.gravity = model, g
        self.name = name or f"{model.name}_lift_off"
        self.declare(states=model.states, inputs=model.inputs, outputs=model.output_signals)
        self.phenomena = frozenset(model.phenomena) | {"wheel_lift"}

        M, _, K, _, dof = model.second_order
        n, nb, nc = M.shape[0], len(model.body_dof), len(model.corners)
        wheel = nb + np.arange(nc)  # the wheels' coordinates follow the body's, in corner order
        # static equilibrium of the linear model under gravity: the translational coordinates
        # (heave, wheels) carry their mass's weight, the angles none (the origin is the sprung CG)
        translational = np.array([name != "pitch_angle" and name != "roll_angle" for name in dof])
        # (the suspension's and tires' stiffness: gravity's moment on a tilted body, in
        # ``body_stiffness``, is no spring that carries the weight)
        springs = K.copy()
        springs[range(nb), range(nb)] -= model.body_stiffness
        q_g = np.linalg.solve(springs, -g * np.diag(M) * translational)
        self.tire_stiffness = np.array([c.tire_stiffness for c in model.corners])
        self.tire_damping = np.array([c.tire_damping for c in model.corners])
        self.unsprung_mass = np.array([c.unsprung_mass for c in model.corners])
        self.static_tire_load = -self.tire_stiffness * q_g[wheel]
        if np.any(self.static_tire_load <= 0):
            raise ParameterError(f"LiftOff: the static tire loads {self.static_tire_load} [N] must be positive (a "
                                 "wheel that carries no weight is off the road already)", key="model",
                                 value=self.static_tire_load.tolist())
        self._wheel = wheel  # states: wheel displacements
        self._wheel_rate = n + wheel  # states: wheel velocities (rows of their accelerations in x')
        names = model.input_names
        self._road = np.array([names.index(f"road_displacement{c.suffix}") for c in model.corners])
        self._road_rate = np.array([names.index(f"road_velocity{c.suffix}") for c in model.corners])
        out = model.output_names
        self._acc_rows = np.array([out.index(f"unsprung_acceleration{c.suffix}") for c in model.corners])
        self._load_rows = np.array([out.index(f"dynamic_tire_load{c.suffix}") for c in model.corners])

    def __repr__(self) -> str:
        return f"<LiftOff {self.name}: {self.n_states} states, static tire loads {np.round(self.static_tire_load)} N>"

    def correction(self, x, u):
        """f_c [N] per corner (rows; columns along any batch axis of ``x``, ``u``): the unilateral
        contact force minus the linear tire's (0 while the tire is compressed and pushing)."""
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        col = (slice(None),) + (None,) * (x.ndim - 1)
        compression = u[self._road] - x[self._wheel]
        linear = self.static_tire_load[col] + self.tire_stiffness[col] * compression \
            + self.tire_damping[col] * (u[self._road_rate] - x[self._wheel_rate])
        deflection = self.static_tire_load[col] / self.tire_stiffness[col] + compression
        return np.where(deflection > 0.0, np.maximum(linear, 0.0), 0.0) - linear

    def rhs(self, t, x, u):
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        col = (slice(None),) + (None,) * (x.ndim - 1)
        dxdt = self.linear.A @ x + self.linear.B @ u
        dxdt[self._wheel_rate] += self.correction(x, u) / self.unsprung_mass[col]
        return dxdt

    def output(self, t, x, u):
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        col = (slice(None),) + (None,) * (x.ndim - 1)
        f = self.correction(x, u)
        y = self.linear.C @ x + self.linear.D @ u
        y[self._acc_rows] += f / self.unsprung_mass[col]
        y[self._load_rows] += f
        return y

    def compiled_rhs(self):
        """The rhs compiled by numba (see :meth:`vehdyn.Model.compiled_rhs`): the same law, one loop
        over the corners; the outputs come from :meth:`output` (numpy, once on the time grid)."""
        from .._compiled_ode import CompiledModel

        rhs, key = _compiled_rhs()
        c = np.ascontiguousarray
        args = (c(self.linear.A), c(self.linear.B), c(self._wheel), c(self._wheel_rate), c(self._road),
                c(self._road_rate), c(self.static_tire_load), c(self.tire_stiffness), c(self.tire_damping),
                c(self.unsprung_mass))
        return CompiledModel(rhs, None, key, args)


def _rhs(t, x, u, args, dxdt):
    """dx/dt of a :class:`LiftOff` into ``dxdt`` (compiled; ``args`` from :meth:`LiftOff.compiled_rhs`)."""
    A, B, wheel, wheel_rate, road, road_rate, static, stiffness, damping, mass = args
    n, m = A.shape[0], B.shape[1]
    for i in range(n):
        s = 0.0
        for j in range(n):
            s += A[i, j] * x[j]
        for j in range(m):
            s += B[i, j] * u[j]
        dxdt[i] = s
    for c in range(wheel.shape[0]):
        compression = u[road[c]] - x[wheel[c]]
        linear = static[c] + stiffness[c] * compression + damping[c] * (u[road_rate[c]] - x[wheel_rate[c]])
        force = 0.0
        if static[c] / stiffness[c] + compression > 0.0 and linear > 0.0:
            force = linear
        dxdt[wheel_rate[c]] += (force - linear) / mass[c]


@functools.lru_cache(maxsize=None)
def _compiled_rhs():
    """(compiled rhs, cache key), compiled on first use and cached on disk per source digest."""
    import sys

    from .._compiled_ode import compiled_copy, source_stamp

    key = "lift_off_" + source_stamp(sys.modules[__name__])
    return compiled_copy(_rhs, f"{key}_rhs"), key
