"""Compiled right-hand side of :class:`~vehdyn.full_vehicle.FullVehicle` (numba, optional).

Imported only when the compiled backend is used. Nothing here restates a full-vehicle equation:
the functions of :mod:`~vehdyn.full_vehicle.assembly` and the modules it calls (body, corner,
steering, driveline, aero, and the single track's slip and relaxation functions) are registered
with ``register_jitable`` and run with a compiled ``xp`` (:data:`XP`) whose four hooks are the
float forms of the mechanics layer's numpy functions:

* ``rotation_body_to_earth`` -- :func:`vehdyn.mechanics.rotation_body_to_earth` as nested tuples;
* ``euler_angle_rates`` -- :func:`vehdyn.mechanics.euler_angle_rates` (no gimbal-lock test: the
  model's domain, |pitch| <= pi/4, is checked first);
* ``rigid_body_accelerations`` -- :func:`vehdyn.mechanics.equations_of_motion.accelerations` written out
  for 3-tuples;
* ``axle_tire_loads`` -- one corner's tire law as :meth:`FullVehicle.corner_law_loads` evaluates
  it (friction similarity, the mirror-image tire of ``k.mirror_image``): the Magic Formula through the compiled equations of
  :mod:`vehdyn.tire._mf_numba` (the laws of :func:`vehdyn.handling._single_track_numba.tire_law`),
  or the linear law.

The compiled rhs also does what :meth:`FullVehicle.rhs` does around the equations: NaN derivatives
for a trial state far beyond the domain (the step is rejected; :func:`vehdyn.simulate` locates a
real crossing and raises :class:`~vehdyn.full_vehicle.assembly.DomainError`) and the road of a
:class:`~vehdyn.ride.RoadProfile` under each contact point (its elevation and slope samples
interpolated with ``np.interp``, as :meth:`RoadProfile.sample`). Roads
and friction given as Python callables have no compiled form: the model then refuses the compiled
backend and says so.

Every per-corner quantity is a tuple and every loop is unrolled in the shared equations, so a call
allocates nothing (but the 32-state vector of a model without tire lag, and the inputs on a
road).
"""

from __future__ import annotations

import functools
import math
import sys
import types

import numba
import numpy as np
from numba.extending import register_jitable

from vehdyn import conventions
from vehdyn.simulation.compiled import CompiledModel, compiled_copy, source_stamp
from vehdyn.errors import ParameterError
from vehdyn.handling import _single_track_numba as stn
from vehdyn.components import aero as crosswind
from vehdyn.handling import single_track_equations
from vehdyn.tire import _mf_numba, linear, magic_formula
from vehdyn.full_vehicle import aero, assembly, body, corner, driveline, steering

__all__ = ["XP", "compiled_model", "compiled_functions"]

_JIT = {"error_model": "numpy"}
_MAGIC_FORMULA = 0  # TireLaw.kind of vehdyn.handling._single_track_numba
_NO_FRICTION_SCALING = (1.0, 1.0, 1.0, 1.0)

for _module, _names in ((body, ("cross", "_dot6", "body_accelerations")),
                        (corner, ("suspension_travel", "suspension_forces", "normal_load", "jacking_force", "camber")),
                        (steering, ("corner_steer_angles",)), (driveline, ("wheel_acceleration",)),
                        (aero, ("aero_forces",)),
                        (assembly, ("ground_point", "_road_plane_force", "_corner", "_column", "_total", "evaluate", "derivatives",
                                    "outputs"))):
    for _name in _names:
        register_jitable(**_JIT)(getattr(_module, _name))


def _rotation_body_to_earth(roll, pitch, yaw):
    """R = Rz(yaw) Ry(pitch) Rx(roll) as nested 3-tuples (:func:`vehdyn.mechanics.rotation_body_to_earth`)."""
    sf, cf = math.sin(roll), math.cos(roll)
    st, ct = math.sin(pitch), math.cos(pitch)
    ss, cs = math.sin(yaw), math.cos(yaw)
    return ((ct * cs, sf * st * cs - cf * ss, cf * st * cs + sf * ss),
            (ct * ss, sf * st * ss + cf * cs, cf * st * ss - sf * cs),
            (-st, sf * ct, cf * ct))


def _euler_angle_rates(roll, pitch, p, q, r):
    """(dphi, dtheta, dpsi) [rad/s] from the body rates (:func:`vehdyn.mechanics.euler_angle_rates`)."""
    sf, cf = math.sin(roll), math.cos(roll)
    q_r = q * sf + r * cf
    ct = math.cos(pitch)
    return p + q_r * math.sin(pitch) / ct, q * cf - r * sf, q_r / ct


def _matrix_vector(m, a0, a1, a2):
    return (m[0][0] * a0 + m[0][1] * a1 + m[0][2] * a2, m[1][0] * a0 + m[1][1] * a1 + m[1][2] * a2,
            m[2][0] * a0 + m[2][1] * a1 + m[2][2] * a2)


def _rigid_body_accelerations(mass, inertia, inverse, velocity, rates, force, moment):
    """dV/dt = F/m - w x V, dw/dt = J^-1 (M - w x J w) for 3-tuples
    (:func:`vehdyn.mechanics.equations_of_motion.accelerations`)."""
    p, q, r = rates
    cx, cy, cz = body.cross(p, q, r, velocity[0], velocity[1], velocity[2])
    h0, h1, h2 = _matrix_vector(inertia, p, q, r)
    gx, gy, gz = body.cross(p, q, r, h0, h1, h2)
    return ((force[0] / mass - cx, force[1] / mass - cy, force[2] / mass - cz),
            _matrix_vector(inverse, moment[0] - gx, moment[1] - gy, moment[2] - gz))


def _corner_tire_loads(tires, corner_index, fz, kappa, alpha, vx):
    """ISO-W (fx, fy, my) [N, N, N*m] of one corner's tire (:meth:`FullVehicle.corner_law_loads`;
    the linear law has no M_y)."""
    laws, camber, friction, mirror_image = tires
    law = laws[corner_index // 2]
    mu = friction[corner_index]
    gamma = camber[corner_index]
    scaled = mu != 1.0
    if scaled:
        kappa, alpha = kappa / mu, math.atan(math.tan(alpha) / mu)
    mirror = mirror_image[corner_index] > 0.5
    if mirror:
        alpha, gamma = -alpha, -gamma
    if law.kind == _MAGIC_FORMULA:
        c = law.records[law.record]
        f = magic_formula._forces_kernel(_mf_numba.OPS, c, fz, kappa, alpha, gamma, vx, c.INFLPRES, True, False)
        fx, fy, my = f[0], f[1], f[4]
    else:
        fx, fy, _ = linear.linear_tire_law(_mf_numba.OPS, law.linear, fz, kappa, alpha, gamma, vx)
        my = 0.0
    if mirror:
        fy = -fy
    if scaled:
        return mu * fx, mu * fy, my
    return fx, fy, my


for _function in (_matrix_vector,):
    register_jitable(**_JIT)(_function)

XP = types.ModuleType("vehdyn.full_vehicle._full_vehicle_numba.XP")
XP.__doc__ = "The ``xp`` of the full-vehicle equations in compiled code (floats; hooks on tuples)."
for _name in ("cos", "sin", "tan", "tanh", "atan", "sqrt", "atan2"):
    setattr(XP, _name, getattr(math, _name))
for _name in ("abs", "where", "minimum", "maximum"):
    setattr(XP, _name, getattr(_mf_numba.OPS, _name))
XP.rotation_body_to_earth = numba.njit(**_JIT)(_rotation_body_to_earth)
XP.euler_angle_rates = numba.njit(**_JIT)(_euler_angle_rates)
XP.rigid_body_accelerations = numba.njit(**_JIT)(_rigid_body_accelerations)
XP.axle_tire_loads = numba.njit(**_JIT)(_corner_tire_loads)


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
    e = assembly.evaluate(XP, laws, k, s, _inputs(k, road, s, u), _NO_FRICTION_SCALING)
    rates = assembly.derivatives(s, e)
    for j in range(len(index)):
        if index[j] >= 0:
            dxdt[index[j]] = rates[j]


def _output(t, x, u, args, y):
    """The outputs of a FullVehicle at (t, x, u) into ``y``."""
    k, laws, index, _domain, road = args
    s = _states(x, index)
    e = assembly.evaluate(XP, laws, k, s, _inputs(k, road, s, u), _NO_FRICTION_SCALING)
    values = assembly.outputs(XP, s, e)
    for j in range(len(values)):
        y[j] = values[j]


@functools.lru_cache(maxsize=None)
def compiled_functions():
    """(rhs, output, cache key): compiled on first call, cached on disk per source digest."""
    key = "full_vehicle_" + source_stamp(assembly, body, corner, steering, driveline, aero, crosswind,
                                         single_track_equations,
                                         conventions, linear, *_mf_numba.SOURCE_MODULES, stn, sys.modules[__name__])
    compiled = [compiled_copy(python, f"{key}_{suffix}") for python, suffix in ((_rhs, "rhs"), (_output, "output"))]
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
    if model.friction is not None:
        raise ParameterError("the compiled FullVehicle runs on the tire laws' own friction; friction is a Python "
                             f"callable ({type(model.friction).__name__}), which compiled code cannot call: use "
                             "backend='numpy'", key="friction", value=model.friction)
    laws = []
    for axle, tire, mirrored in (("front", model.front_tire, model._mirrored[0]),
                                 ("rear", model.rear_tire, model._mirrored[1])):
        try:
            laws.append(stn.tire_law(tire, mirrored, axle))
        except ParameterError:
            raise ParameterError(f"the compiled FullVehicle supports the MagicFormula and LinearTire laws; the {axle} "
                                 f"tire is a {type(tire).__name__}: use backend='numpy'", key=f"{axle}_tire",
                                 value=type(tire).__name__) from None
    k = model._k
    domain = tuple(tuple(float(b) for b in assembly.trial_bounds(*model.domain[name])) for name in assembly.DOMAIN_STATES)
    rhs, output, key = compiled_functions()
    # tuples, not arrays, for the constants and the index: passed by value, without reference counting
    args = (k, tuple(laws), tuple(int(i) for i in model._state_index), domain, _road(model))
    return CompiledModel(rhs, output, key, args)
