"""The full vehicle on the fidelity ladder: the builder :func:`ladder_setup` of its two rungs.

:mod:`vehdyn.scene.registry` registers :class:`~vehdyn.full_vehicle.FullVehicle` as the top rung of
both ladders (``"FullVehicle"`` on the handling ladder, ``"FullVehicle(ride)"`` on the ride
ladder) and calls :func:`ladder_setup` with the scene's :class:`~vehdyn.scene.drive.Drive`. It is
the only model that takes a steer and a road at once, so it is the reference of combined scenes
(cornering on a rough road) too.

How a scene's drive becomes the full vehicle's inputs
-----------------------------------------------------
* **Start**: the steady state of :meth:`FullVehicle.trim` at the scene's speed -- straight
  running, or the steady turn at ``drive.initial_turn`` (braking in a turn) -- with the drive
  torques that hold the speed against drag and rolling resistance (the single track's rung holds
  the drag with a constant drive force in the same way). The trim runs on the first ``run()``, not
  while planning.
* **Steer**: ``front_steer_angle`` (and ``rear_steer_angle``) are the full vehicle's own inputs
  (the bicycle road-wheel angle, split left/right by the vehicle's Ackermann fraction); any input
  of the full vehicle named in a user's mapping passes through; other inputs make the rung
  inadmissible.
* **Braking**: the axle force programmes (F_front(t), F_rear(t), start) [N, negative braking] of
  the scene become brake torques -F R_e / 2 on each wheel of the axle (R_e the rolling radius);
  the drive torques that held the speed are released at the start of braking, as the single
  track's drag-holding force is.
* **Driver** (ISO 3888-1): the full vehicle in the loop of the same preview driver as the other
  rungs (:class:`~vehdyn.driver.PreviewDriver` in a :class:`~vehdyn.interconnect.ClosedLoop`,
  steer only; the drive torques of the trim hold the speed).
* **Road**: each track's profile under its wheels at the scene's constant speed V, front wheels at
  distance V t, rear wheels a wheelbase behind (the exact wheelbase delay of
  :meth:`vehdyn.ride.RoadProfile.road_inputs`, sampled on the scene's time grid as for the ride
  rungs), as ``road_displacement_*`` and ``road_velocity_*`` of each corner.

The two rungs do not both answer one scene: the handling rung answers every scene with a steer,
braking, a turn or a driver (with or without a road), the ride rung the scenes with only a road.

Integration: :func:`vehdyn.simulate` with ``backend="auto"`` (a compiled right-hand side is used
when the model has one), RK45 at ``rtol`` 1e-6 and ``max_step`` the scene's time step: a scene
starting in equilibrium gives the adaptive solver no derivative to size its first steps by, and
without the bound its first step jumps over a steer that starts later.
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["ladder_setup", "linearized_setup", "scene_inputs", "road_inputs", "corner_body_accelerations",
           "SOLVER_OPTIONS"]

#: Options of :func:`vehdyn.simulate` for the full vehicle on the ladder (``max_step`` is the scene's
#: time step). rtol 1e-6 keeps the reference's integration error far below the tolerances of the
#: scenes (0.02 by default): against rtol 1e-9 (atol 1e-11) the outputs of the sedan's standard
#: scenes differ by at most 4e-6 relative on the handling scenes and 8e-5 on the road scenes.
SOLVER_OPTIONS = {"method": "RK45", "rtol": 1e-6, "atol": 1e-8, "backend": "auto"}


def corner_body_accelerations(model, result) -> dict:
    """Vertical acceleration [m/s^2] (up +, gravity excluded) of the body above each wheel.

    The body point at the corner's (x, y) and the sprung CG's height, a = a_CG + alpha x r +
    omega x (omega x r) in body axes (rigid body), projected on the earth vertical: the
    ``sprung_acceleration_*`` outputs of :class:`vehdyn.ride.FullCar` for the full vehicle
    (the corner values of the pothole scene). Exactly affine in the corner's (x, y), so that they
    interpolate to ``sprung_acceleration`` at the CG.

    Parameters
    ----------
    model : FullVehicle
    result : SimulationResult
        A simulation of ``model`` (states and inputs on its time grid).

    Returns
    -------
    dict
        ``{"sprung_acceleration_front_left": array, ...}`` on ``result.time``.
    """
    from vehdyn.full_vehicle import assembly
    from vehdyn.full_vehicle.corner import CORNERS

    states, e = model._evaluate(np.asarray(result.states, dtype=float), np.asarray(result.inputs, dtype=float))
    p, q, r = states[3], states[4], states[5]
    ap, aq, ar = e.angular_acceleration
    R = assembly.NUMPY.rotation_body_to_earth(states[6], states[7], states[8])
    out = {}
    for sfx, x, y in zip(CORNERS, model.corner_x, model.corner_y):
        omega_r = p * x + q * y  # omega . r with r = (x, y, 0)
        point = (e.cg_acceleration[0] - ar * y + p * omega_r - x * (p * p + q * q + r * r),
                 e.cg_acceleration[1] + ar * x + q * omega_r - y * (p * p + q * q + r * r),
                 e.cg_acceleration[2] + ap * y - aq * x + r * omega_r)
        out[f"sprung_acceleration{sfx}"] = -(R[2][0] * point[0] + R[2][1] * point[1] + R[2][2] * point[2])
    return out


def _with_corner_accelerations(model, result):
    """``result`` with the :func:`corner_body_accelerations` appended to its outputs."""
    import dataclasses

    from vehdyn.signals import Signal

    extra = corner_body_accelerations(model, result)
    signals = tuple(Signal(n, "m/s^2", "vertical acceleration of the body above the wheel (up)") for n in extra)
    return dataclasses.replace(result, outputs=np.vstack([result.outputs, np.array(list(extra.values()))]),
                               output_signals=tuple(result.output_signals) + signals)


def _setup_class():
    from dataclasses import dataclass

    from vehdyn.scene.registry import Setup

    @dataclass
    class FullVehicleSetup(Setup):
        """A Setup whose results carry the corner body accelerations besides the model's outputs."""

        extra_outputs: tuple = ()

        @property
        def output_names(self):
            return tuple(self.model.output_names) + tuple(self.extra_outputs)

    return FullVehicleSetup


def _not_admissible(reason):
    from vehdyn.scene.registry import NotAdmissible

    return NotAdmissible(reason)


def road_inputs(drive) -> dict:
    """``road_displacement_*`` / ``road_velocity_*`` [m, m/s] of the four corners on ``drive.time``.

    Front wheels at distance V t on their track's profile, rear wheels a wheelbase behind (V the
    scene's speed), sampled by :meth:`vehdyn.ride.RoadProfile.road_inputs` as for the ride rungs.

    Parameters
    ----------
    drive : vehdyn.scene.drive.Drive
        A scene's inputs with a road (``drive.road`` = (distance, left, right) [m]); its
        vehicle's wheelbase, the scene's speed and ``drive.time``.

    Returns
    -------
    dict of str to ndarray
        ``road_displacement<sfx>`` [m] and ``road_velocity<sfx>`` [m/s] on ``drive.time`` for the
        four corners (``sfx`` ``_front_left``, ``_rear_left``, ``_front_right``, ``_rear_right``).
    """
    from vehdyn.road import RoadProfile

    distance, left, right = drive.road
    wheelbase = drive.vehicle.geometry.wheelbase
    out = {}
    for elevation, side in ((left, "left"), (right, "right")):
        profile = RoadProfile(distance, elevation)
        for axle, offset in (("front", 0.0), ("rear", wheelbase)):
            sfx = f"_{axle}_{side}"
            # RoadProfile puts the first axle at distance[0] + V t: shift so that it is at V t
            _, u = profile.road_inputs(drive.scene.speed, {sfx: offset + distance[0]}, time=drive.time)
            out.update(u)
    return out


def _step(start, before, after):
    """``before`` until ``start``, then ``after`` (numbers or callables of t), for scalar or array t."""
    def value(v, tt):
        return np.asarray(v(tt), dtype=float) if callable(v) else np.full(np.shape(tt), float(v))

    return lambda t: np.where(np.asarray(t, dtype=float) >= start, value(after, t), value(before, t))


def scene_inputs(drive, model, trim_inputs, road=None) -> dict:
    """The full vehicle's inputs for a scene: the trim's, the scene's programmes on top.

    Parameters
    ----------
    drive : vehdyn.scene.drive.Drive
    model : FullVehicle
    trim_inputs : array_like
        The input vector of the starting trim, in the order of ``model.input_names`` [each
        input's unit: N*m for the drive torques that hold the speed, rad for the steer of a steady
        turn]; the nonzero entries become constant inputs.
    road : dict, optional
        The corners' road inputs (:func:`road_inputs`).

    Returns
    -------
    dict
        Input name -> number, array on ``drive.time`` or callable of t, for :func:`vehdyn.simulate`.
    """
    from vehdyn.full_vehicle.corner import CORNERS

    inputs = {n: float(v) for n, v in zip(model.input_names, trim_inputs) if v != 0.0}
    inputs.update(drive.inputs)
    inputs.update(road or {})
    if drive.braking is not None:
        front, rear, begin = drive.braking
        radius = model.vehicle.tires.rolling_radius
        for name in [n for n in inputs if n.startswith("drive_torque")]:
            inputs[name] = _step(begin, inputs[name], 0.0)
        for sfx in CORNERS:
            force = front if sfx.startswith("_front") else rear
            inputs[f"brake_torque{sfx}"] = lambda t, f=force: -0.5 * radius * np.asarray(f(t), dtype=float)
    return inputs


def _model_for(drive, ladder, name):
    """The FullVehicle for ``drive`` and the corners' road inputs, or NotAdmissible (see
    :func:`ladder_setup`: which of the two ladders answers which scene)."""
    from vehdyn.scene.registry import refuse_dropped_terms, tire_laws
    from vehdyn.full_vehicle.model import FullVehicle

    if ladder not in ("handling", "ride"):
        raise ParameterError(f"ladder must be 'handling' or 'ride', got {ladder!r}", key="ladder", value=ladder)
    if ladder == "ride" and drive.handling_input:
        raise _not_admissible(f"steer or braking: the handling rung {name} answers")
    if ladder == "ride" and drive.road is None:
        raise _not_admissible("no road input")
    if ladder == "handling" and not drive.handling_input:
        raise _not_admissible(f"no steer or braking: the ride rung {name}(ride) answers")
    refuse_dropped_terms(drive.vehicle, ("roll_steer", "camber_thrust", "compliance_steer"))
    # one model for this plan's full-vehicle rungs, the tire laws the other rungs read
    model = drive.once("FullVehicle", lambda: FullVehicle(drive.vehicle, *tire_laws(drive)))
    unknown = [k for k in drive.inputs if k not in model.input_names]
    if unknown:
        raise _not_admissible(f"has no input {unknown[0]!r}")
    return model, (road_inputs(drive) if drive.road is not None else {})


def ladder_setup(drive, ladder: str = "handling"):
    """The full vehicle built for a scene: a :class:`~vehdyn.scene.registry.Setup`.

    Parameters
    ----------
    drive : vehdyn.scene.drive.Drive
        The scene's materialized inputs.
    ladder : {"handling", "ride"}
        Which of the two rungs asks: the handling rung answers scenes with a ground-plane input
        (steer, braking, a turn, a driver; a road too), the ride rung scenes with a road only.

    Returns
    -------
    Setup
        ``model`` the :class:`FullVehicle` (or the driver loop around it), ``run()`` its
        :class:`~vehdyn.SimulationResult` on ``drive.time`` (without a driver, with the
        :func:`corner_body_accelerations` added to the outputs).

    Raises
    ------
    NotAdmissible
        When the scene is not this rung's (see ``ladder``) or names an input the full vehicle does
        not have.
    """
    from vehdyn.scene.registry import Setup
    from vehdyn.simulation import simulate
    from vehdyn.full_vehicle.corner import CORNERS

    model, road = _model_for(drive, ladder, "FullVehicle")
    scene = drive.scene
    options = dict(SOLVER_OPTIONS, max_step=float(scene.effective_time_step))

    def start():
        """(x0, inputs): the trim and the scene's programmes on top of it (every run: the trim is
        part of what the scene costs, see :mod:`vehdyn.scene.registry`)."""
        x0, u0 = model.trim(scene.speed, lateral_acceleration=drive.initial_turn or 0.0)
        return x0, scene_inputs(drive, model, u0, road)

    if drive.track is not None:
        from vehdyn.scene.registry import _with_driver

        loop = _with_driver(model, drive, speed_control=False)

        def run_loop():
            x0, inputs = start()
            x0 = np.asarray(x0, dtype=float).copy()
            x0[model.index("x")] = float(drive.track.path_x[0])
            inputs = {k: v for k, v in inputs.items() if k in loop.input_names}
            return simulate(loop, drive.time, inputs, x0=np.concatenate([x0, [0.0]]), **options)

        return Setup(loop, run_loop)

    def run():
        x0, inputs = start()
        return _with_corner_accelerations(model, simulate(model, drive.time, inputs, x0=x0, **options))

    return _setup_class()(model, run, extra_outputs=tuple(f"sprung_acceleration{sfx}" for sfx in CORNERS))


#: States of the full vehicle that the linearized rung leaves out: the earth position and heading
#: integrate the motion and feed nothing else back (flat road, uniform friction).
_INTEGRATED_ONLY = ("x", "y", "yaw_angle")


def linearized_run(model, drive, road):
    """One run of the linearized full vehicle on ``drive``: trim, linearize, simulate exactly.

    The full vehicle is trimmed (:meth:`FullVehicle.trim`: straight running, or the steady turn of
    ``drive.initial_turn``), linearized there (:meth:`vehdyn.Model.linearize`: fourth-order central
    differences, all perturbed points in one batched call of the numpy right-hand side), the earth
    position and heading dropped (they feed nothing back on a flat road), and the deviation system
    dx/dt = A dx + B du simulated exactly on the scene's grid (:func:`vehdyn.simulate`,
    ``method="exact"``: one matrix exponential, inputs held first-order between samples). The result
    holds the full vehicle's outputs y_op + C dx + D du and states x_op + dx.

    Returns
    -------
    SimulationResult
    """
    import dataclasses
    import time as _time

    from vehdyn.model import LinearModel
    from vehdyn.simulation import simulate

    start = _time.perf_counter()
    x0, u0 = model.trim(drive.scene.speed, lateral_acceleration=drive.initial_turn or 0.0)
    lin = model.linearize(x0, u0)
    keep = [j for j, n in enumerate(model.state_names) if n not in _INTEGRATED_ONLY]
    dropped = [model.index(n) for n in _INTEGRATED_ONLY]
    coupling = np.max(np.abs(lin.A[np.ix_(keep, dropped)]))  # finite differences: round-off, not zero
    if coupling > 1e-6 * np.max(np.abs(lin.A)):  # a position-dependent road or friction: not this rung's
        raise ParameterError("the linearized full vehicle needs a road and friction that do not depend on the "
                             "position", key="road", value=model.road)
    inputs = scene_inputs(drive, model, u0, road)
    used = [i for i, n in enumerate(model.input_names) if n in inputs]
    t = drive.time
    du = np.empty((len(used), t.size))
    for row, i in zip(du, used):
        value = inputs[model.input_names[i]]
        row[:] = np.asarray(value(t) if callable(value) else value, dtype=float) - u0[i]
    reduced = LinearModel(lin.A[np.ix_(keep, keep)], lin.B[np.ix_(keep, used)], lin.C[:, keep], lin.D[:, used],
                          states=[model.states[j] for j in keep], inputs=[model.inputs[i] for i in used],
                          outputs=model.output_signals)
    res = simulate(reduced, t, du, method="exact", hold="foh")
    return dataclasses.replace(res, states=res.states + x0[keep][:, None], inputs=res.inputs + u0[used][:, None],
                               outputs=res.outputs + lin.y_op[:, None], method="linearized full vehicle, exact",
                               wall_time=_time.perf_counter() - start)


def linearized_setup(drive, ladder: str = "handling"):
    """The full vehicle linearized at the scene's trim: a :class:`~vehdyn.scene.registry.Setup`.

    The rung below :func:`ladder_setup`'s on both ladders: the same model, equations and parameters,
    linear about the operating point the scene starts in (:func:`linearized_run`). Exact for small
    steer and road inputs (gentle handling, smooth roads); it misses the tire's saturation, the
    load changes' effect on the tire forces and the wheels lifting off (the plan's estimates). Its
    cost is the trim, the Jacobian and the simulation, every run.

    Parameters
    ----------
    drive : vehdyn.scene.drive.Drive
    ladder : {"handling", "ride"}
        As :func:`ladder_setup`.

    Returns
    -------
    Setup
        ``model`` the :class:`FullVehicle`, ``run()`` the linearized run
        (:func:`linearized_run`: trim, Jacobian, simulation) on ``drive.time``, ``phenomena`` the
        model's without ``tire_saturation`` and ``wheel_lift``.

    Raises
    ------
    NotAdmissible
        As :func:`ladder_setup`, and for braking and the ISO 3888-1 driver (large slips, the
        driver's nonlinear loop on the earth position: the nonlinear rung answers).
    """
    from vehdyn.scene.registry import Setup

    model, road = _model_for(drive, ladder, "FullVehicle(linearized)")
    if drive.braking is not None:
        raise _not_admissible("braking: the tire forces of a braking programme are far from the trim's")
    if drive.track is not None:
        raise _not_admissible("the driver loop steers on the earth position (nonlinear kinematics)")
    return Setup(model, lambda: linearized_run(model, drive, road), (),
                 phenomena=model.phenomena - {"tire_saturation", "wheel_lift"})
