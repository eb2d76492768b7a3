"""Compiled right-hand side of :class:`~vehdyn.full_vehicle.FullVehicle` (numba, optional).

Imported only when the compiled backend is used. Nothing here restates an equation: the functions
of :mod:`~vehdyn.full_vehicle.assembly` and the modules it calls (body, corner, steering,
driveline, aero) are registered with ``register_jitable`` and run with the compiled ``xp`` of
:mod:`vehdyn.components.compiled` (the shared components and the tire hooks on a
:class:`vehdyn.tire.compiled.TireLaw`) extended by two hooks, the mechanics layer's own xp
functions :func:`vehdyn.mechanics.kinematics.rotation_matrix` and
:func:`vehdyn.mechanics.kinematics.euler_rates` (no gimbal-lock test: the model's domain,
|pitch| <= pi/4, is checked first); the sprung body's Newton-Euler equations are
:func:`vehdyn.mechanics.equations_of_motion.rigid_body_accelerations`, registered here.

The compiled rhs also does what :meth:`FullVehicle.rhs` does around the equations: NaN derivatives
for a trial state far beyond the domain (the step is rejected; :func:`vehdyn.simulate` locates a
real crossing and raises :class:`~vehdyn.full_vehicle.assembly.DomainError`) and the road of a
:class:`~vehdyn.ride.RoadProfile` under each contact point (its elevation and slope samples
interpolated with ``np.interp``, as :meth:`RoadProfile.sample`). A constant road friction
compiles; roads and friction given as Python callables have no compiled form: the model then
refuses the compiled backend and says so.

Every per-corner quantity is a tuple and every loop is unrolled in the shared equations, so a call
allocates nothing (but the 32-state vector of a model without tire lag, and the inputs on a
road).
"""

from __future__ import annotations

import functools
import sys

import numpy as np
from numba.extending import register_jitable

from vehdyn.components.compiled import JIT_OPTIONS as _JIT
from vehdyn.components.compiled import FULL_FORCES, SOURCE_MODULES, WITHOUT_ALIGNING, namespace
from vehdyn.errors import ParameterError
from vehdyn.full_vehicle import aero, assembly, body, corner, driveline, steering
from vehdyn.mechanics import equations_of_motion, kinematics
from vehdyn.simulation.compiled import CompiledModel, compiled_copy, source_stamp
from vehdyn.tire.compiled import tire_law

__all__ = ["XP", "compiled_model", "compiled_functions"]

for _module, _names in ((kinematics, ("cross_components", "rotation_matrix", "euler_rates")),
                        (equations_of_motion, ("_matrix_vector", "rigid_body_accelerations")),
                        (body, ("_dot6", "body_accelerations")),
                        (corner, ("suspension_travel", "suspension_forces", "normal_load", "jacking_force", "camber")),
                        (steering, ("corner_steer_angles",)), (driveline, ("wheel_acceleration",)),
                        (aero, ("aero_forces",)),
                        (assembly, ("ground_point", "_road_plane_force", "_corner", "_column", "_total", "evaluate",
                                    "derivatives", "outputs"))):
    for _name in _names:
        register_jitable(**_JIT)(getattr(_module, _name))


def _rotation_body_to_earth(roll, pitch, yaw):
    """R (nested 3-tuples): :func:`vehdyn.mechanics.kinematics.rotation_matrix` with the compiled ``xp``."""
    return kinematics.rotation_matrix(XP, roll, pitch, yaw)


def _euler_angle_rates(roll, pitch, p, q, r):
    """(dphi, dtheta, dpsi) [rad/s]: :func:`vehdyn.mechanics.kinematics.euler_rates` with the compiled ``xp``."""
    return kinematics.euler_rates(XP, roll, pitch, p, q, r)


XP = namespace("vehdyn.full_vehicle._full_vehicle_numba.XP", **FULL_FORCES,
               rotation_body_to_earth=register_jitable(**_JIT)(_rotation_body_to_earth),
               euler_angle_rates=register_jitable(**_JIT)(_euler_angle_rates))
XP_WITHOUT_ALIGNING = namespace("vehdyn.full_vehicle._full_vehicle_numba.XP_WITHOUT_ALIGNING",
                                **{**{name: value for name, value in vars(XP).items()
                                      if not name.startswith("__")}, **WITHOUT_ALIGNING})
""":data:`XP` for a vehicle without aligning-moment compliance: the Magic Formula's M_z is not compiled."""


def _friction(k):
    """The road's friction ratio under the four corners: the model's constant."""
    return k.road_friction, k.road_friction, k.road_friction, k.road_friction


register_jitable(**_JIT)(_friction)


def _states(x, index):
    """The 32 states in the order of :data:`assembly.STATES` (zeros where the model lacks one):
    ``x`` itself when the model has them all in that order (with tire lag)."""
    if index[len(index) - 1] == len(index) - 1:  # the index of a model with every state is the identity
        return x
    s = np.zeros(len(index))
    for j in range(len(index)):
        if index[j] >= 0:
            s[j] = x[index[j]]
    return s


def _inputs(k, road, s, u):
    """The inputs with the road under each contact point added (``u`` itself on a flat road);
    ``road`` = (on, distance, elevation, slope) of a RoadProfile (:meth:`FullVehicle._inputs_with_road`)."""
    on, distance, elevation, slope = road
    if not on:
        return u
    i = u.copy()
    R = XP.rotation_body_to_earth(s[6], s[7], s[8])
    for c in range(4):
        X, _Y, VX, _VY = assembly.ground_point(R, k, s, c)
        inside = distance[0] <= X <= distance[distance.shape[0] - 1]
        i[10 + c] += np.interp(X, distance, elevation)
        i[14 + c] += (np.interp(X, distance, slope) if inside else 0.0) * VX
    return i


def _outside_domain(s, domain):
    """True when the roll or pitch angle lies outside its trial bounds (or is NaN), as the numpy rhs."""
    for j in range(2):
        value = s[6 + j]
        low, high = domain[j]
        if not (low <= value <= high):
            return True
    return False


for _function in (_states, _inputs, _outside_domain):
    register_jitable(**_JIT)(_function)


def _rhs(t, x, u, args, dxdt):
    """dx/dt of a FullVehicle at (t, x, u) into ``dxdt``; ``args`` from :func:`compiled_model`."""
    k, laws, index, domain, road = args
    s = _states(x, index)
    if _outside_domain(s, domain):  # a trial stage far outside the domain: NaN rejects the step
        for j in range(dxdt.shape[0]):
            dxdt[j] = np.nan
        return
    e = assembly.evaluate(XP, laws, k, s, _inputs(k, road, s, u), _friction(k))
    rates = assembly.derivatives(s, e)
    for j in range(len(index)):
        if index[j] >= 0:
            dxdt[index[j]] = rates[j]


def _output(t, x, u, args, y):
    """The outputs of a FullVehicle at (t, x, u) into ``y``."""
    k, laws, index, _domain, road = args
    s = _states(x, index)
    e = assembly.evaluate(XP, laws, k, s, _inputs(k, road, s, u), _friction(k))
    values = assembly.outputs(XP, s, e)
    for j in range(len(values)):
        y[j] = values[j]
    if k.compliance_on > 0.5:  # the compliance steer of each corner
        for j in range(4):
            y[len(values) + j] = e.compliance_steer[j]


@functools.lru_cache(maxsize=None)
def compiled_functions(aligning: bool = False):
    """(rhs, output, cache key): compiled on first call, cached on disk per source digest; with
    ``aligning`` the copy whose compliance steer reads the laws' M_z (:data:`XP`), else without it
    (:data:`XP_WITHOUT_ALIGNING`)."""
    key = "full_vehicle_" + source_stamp(assembly, body, corner, steering, driveline, aero, kinematics,
                                         equations_of_motion, *SOURCE_MODULES, sys.modules[__name__])
    key += "_aligning" if aligning else ""
    xp = XP if aligning else XP_WITHOUT_ALIGNING
    compiled = [compiled_copy(python, f"{key}_{suffix}", XP=xp) for python, suffix in ((_rhs, "rhs"),
                                                                                       (_output, "output"))]
    return compiled[0], compiled[1], key


def _road(model):
    """The road argument: (on, distance, elevation, slope) of a RoadProfile, or a flat road."""
    from vehdyn.road import RoadProfile

    road = model.road
    if road is None:
        flat = np.zeros(2)
        return False, np.array([0.0, 1.0]), flat, flat
    if not isinstance(road, RoadProfile):
        raise ParameterError("the compiled FullVehicle takes a road as a vehdyn.ride.RoadProfile (sampled, "
                             f"interpolated in compiled code); road is a Python callable ({type(road).__name__}), "
                             "which compiled code cannot call: use backend='numpy', or sample it into a RoadProfile",
                             key="road", value=road)
    distance = np.ascontiguousarray(road.distance, dtype=float)
    return (True, distance, np.ascontiguousarray(road.elevation, dtype=float),
            np.ascontiguousarray(road.slope(), dtype=float))


def compiled_model(model) -> CompiledModel:
    """The compiled rhs and outputs of a FullVehicle (see :meth:`FullVehicle.compiled_rhs`)."""
    if callable(model.friction):
        raise ParameterError("the compiled FullVehicle takes a constant road friction; friction is a Python "
                             f"callable ({type(model.friction).__name__}), which compiled code cannot call: use "
                             "backend='numpy'", key="friction", value=model.friction)
    laws = []
    for axle, tire in (("front", model.front_tire), ("rear", model.rear_tire)):
        try:
            laws.append(tire_law(tire, f"{axle}_tire"))
        except ParameterError:
            raise ParameterError(f"the compiled FullVehicle supports the MagicFormula and LinearTire laws; the {axle} "
                                 f"tire is a {type(tire).__name__}: use backend='numpy'", key=f"{axle}_tire",
                                 value=type(tire).__name__) from None
    k = model._k
    domain = tuple(tuple(float(b) for b in assembly.trial_bounds(*model.domain[name])) for name in assembly.DOMAIN_STATES)
    rhs, output, key = compiled_functions(any(e != 0.0 for e in k.moment_compliance))
    # tuples, not arrays, for the constants and the index: passed by value, without reference counting
    args = (k, tuple(laws), tuple(int(i) for i in model._state_index), domain, _road(model))
    return CompiledModel(rhs, output, key, args)
