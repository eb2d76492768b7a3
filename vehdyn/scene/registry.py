"""The one registry of ladder rungs: which models can answer a scene, how each is built and run.

A rung is a :class:`Rung` entry in :data:`RUNGS`: a model class named by a lazy import path, the
ladder it climbs (``"handling"`` or ``"ride"``), its fidelity rank (higher: more complete, the
top admissible rung is the reference) and a builder ``build(drive) -> Setup`` that makes the model
for a scene and runs it on the scene's inputs. The planner knows nothing model-specific: adding a
model to the ladder is one :func:`register_rung` call (or one entry below) beside its builder.

A rung whose module cannot be imported is skipped (``available`` is False). The entries for
``vehdyn.full_vehicle.FullVehicle`` call that module's ``ladder_setup(drive, ladder)`` and, for the
full vehicle linearized at the scene's trim, ``linearized_setup(drive, ladder)``
(:mod:`vehdyn.scene.full_vehicle_rungs`).

What a rung costs is what ``Setup.run()`` does, every time it is called: the scene's start (a
trim, a steady turn), a linearization, the simulation. Building the model from the vehicle (and
reading its ``.tir`` file) is per vehicle and stays in the builder; importing and compiling are per
process (:func:`vehdyn.ladder` reports the best of several runs, the first loads compiled code).

The builder contract: ``build(drive, **options) -> Setup``. ``drive`` is a
:class:`~vehdyn.scene.drive.Drive`: ``vehicle``, ``scene`` (speed, duration, tire, ...), ``time``
(the common grid every result must be on), ``inputs`` (input name -> callable of t, e.g.
``front_steer_angle``), ``braking`` ((front force(t), rear force(t), start) [N], negative
braking) or None, ``initial_turn`` (a steady lateral acceleration to start in) or None,
``track`` and ``driver`` (ISO 3888-1) or None, ``road`` ((distance, left, right) elevations [m],
front axle at distance V t) or None. The Setup holds the model instance (its ``output_names``
answer the scene's outputs, also as ``name + "_left"``), ``run()`` returning a SimulationResult on
``drive.time``, what the rung ignores, and its ``phenomena`` if they differ from the model's.
A builder raises :class:`NotAdmissible` (message: the reason) when the rung cannot represent the
scene, and when the vehicle has a term of its understeer budget (roll steer, camber thrust,
compliance steer: :data:`UNDERSTEER_TERMS`) that the rung does not carry
(:func:`refuse_dropped_terms`), so the planner never picks a rung that drops one.
"""

from __future__ import annotations

import importlib
import time as _time
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["Rung", "Setup", "NotAdmissible", "RUNGS", "register_rung", "rungs", "SteadyStateAlgebra",
           "UNDERSTEER_TERMS", "refuse_dropped_terms"]


class NotAdmissible(Exception):
    """A builder's way of saying the rung cannot represent the scene (the message is the reason)."""


@dataclass
class Setup:
    """One rung built for one scene.

    Attributes
    ----------
    model : object
        The model instance that runs.
    run : callable
        ``run() -> SimulationResult`` on the scene's time grid.
    ignores : tuple of str
        What of the scene the rung does not see (for the plan's reasons).
    phenomena : frozenset, optional
        What the rung represents when it differs from ``model.phenomena`` (a SingleTrack with
        linear tires does not saturate).
    lateral_load_transfer : bool
        A rung without roll that carries the quasi-static lateral load transfer (the planner then
        does not charge it the side force that transfer takes through the tire's load sensitivity).
    """

    model: Any
    run: Callable[[], Any]
    ignores: tuple[str, ...] = ()
    phenomena: frozenset | None = None
    lateral_load_transfer: bool = False

    @property
    def output_names(self) -> tuple[str, ...]:
        return tuple(self.model.output_names)


@dataclass(frozen=True)
class Rung:
    """A registry entry.

    Attributes
    ----------
    name : str
        Shown in the plan (``"LinearBicycle+lag"``).
    model : str
        ``"module:Class"`` of the model class (imported on use).
    ladder : {"handling", "ride"}
    fidelity : int
        Rank on its ladder (the admissible rung with the highest rank is the reference).
    build : str or callable
        ``build(drive) -> Setup``, or ``"module:function"``.
    linear : bool
        A linear model (its domain ends where the tires saturate).
    description : str
    probe : bool
        For a linear rung: the plan runs it while planning to estimate the others' errors (the
        linear models of a few states cost about a millisecond); False for a rung whose run costs
        more (a trim and a linearization).
    options : dict
        Keyword arguments passed to the builder, ``build(drive, **options)`` (default none; e.g.
        ``{"tire_lag": True}``), so that one builder serves several rungs.
    """

    name: str
    model: str
    ladder: str
    fidelity: int
    build: Any
    linear: bool = False
    description: str = ""
    options: dict = field(default_factory=dict)
    probe: bool = True

    def model_class(self):
        """The model class, or None when its module is not importable.

        Returns
        -------
        type or None
            The class named by :attr:`model` (``"module:Class"``), imported now; None when the
            module cannot be imported or lacks the class.
        """
        module, _, attr = self.model.partition(":")
        try:
            return getattr(importlib.import_module(module), attr)
        except (ImportError, AttributeError):
            return None

    @property
    def available(self) -> bool:
        return self.model_class() is not None

    def phenomena(self, setup: Setup | None = None) -> frozenset:
        """What the rung represents: the instance's ``phenomena`` when built, else the class's.

        Parameters
        ----------
        setup : Setup, optional
            The rung built for a scene; its own ``phenomena`` (where given) come first, then its
            model instance's.

        Returns
        -------
        frozenset of str
            The phenomena (``"lateral"``, ``"yaw"``, ``"roll"``, ``"longitudinal"``, ...); empty
            when neither the setup nor the model class names any (or the class is not importable).
        """
        if setup is not None and setup.phenomena is not None:
            return frozenset(setup.phenomena)
        if setup is not None and getattr(setup.model, "phenomena", None) is not None:
            return frozenset(setup.model.phenomena)
        return frozenset(getattr(self.model_class(), "phenomena", frozenset()))

    def setup(self, drive) -> Setup:
        """Build the rung for a scene: ``build(drive, **options)``.

        Parameters
        ----------
        drive : Drive
            The scene's inputs (:func:`~vehdyn.scene.drive.drive_of`).

        Returns
        -------
        Setup
            The model built for the scene and its ``run()``.

        Raises
        ------
        NotAdmissible
            The rung cannot represent the scene (the message is the reason), also when a builder
            named ``"module:function"`` cannot be imported.
        """
        build = self.build
        if isinstance(build, str):
            module, _, attr = build.partition(":")
            try:
                build = getattr(importlib.import_module(module), attr)
            except (ImportError, AttributeError):
                raise NotAdmissible(f"no ladder builder {self.build!r} yet") from None
        return build(drive, **self.options)


RUNGS: list[Rung] = []


def register_rung(rung: Rung) -> Rung:
    """Add ``rung`` to the ladder (replacing a rung of the same name).

    Parameters
    ----------
    rung : Rung
        The entry; its ``ladder`` must be ``"handling"`` or ``"ride"``.

    Returns
    -------
    Rung
        ``rung`` itself (now last in :data:`RUNGS`).

    Raises
    ------
    ParameterError
        ``key="ladder"``: a ladder other than ``"handling"`` or ``"ride"``.
    """
    if rung.ladder not in ("handling", "ride"):
        raise ParameterError(f"Rung.ladder must be 'handling' or 'ride', got {rung.ladder!r}", key="ladder",
                             value=rung.ladder)
    RUNGS[:] = [r for r in RUNGS if r.name != rung.name] + [rung]
    return rung


def rungs(*, available_only: bool = True) -> list[Rung]:
    """The registered rungs in ladder order (handling, then ride; by fidelity).

    Parameters
    ----------
    available_only : bool
        Leave out the rungs whose model class cannot be imported (default True).

    Returns
    -------
    list of Rung
        The rungs of the handling ladder by increasing fidelity, then those of the ride ladder.
    """
    out = [r for r in RUNGS if r.available or not available_only]
    return sorted(out, key=lambda r: (r.ladder != "handling", r.fidelity))


# ====================================================================== handling builders
def _result(model, time, outputs, wall_time, method):
    """A SimulationResult for a model without states (the steady-state algebra)."""
    from vehdyn.results import SimulationResult

    return SimulationResult(time=time, states=np.zeros((0, time.size)), inputs=np.zeros((0, time.size)),
                            outputs=np.asarray(outputs), state_signals=(), input_signals=(),
                            output_signals=tuple(model.outputs), method=method, wall_time=wall_time)


class SteadyStateAlgebra:
    """Quasi-steady handling: the linear bicycle's steady-state gains times the steer at each instant.

    y(t) = G(u) delta(t) for the yaw rate, lateral acceleration, sideslip and path curvature
    (:func:`vehdyn.handling.steady_state_gains`; Gillespie 1992, ch. 6). Exact for a
    steer that changes slowly against the yaw mode; no states.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle whose linear bicycle gives the gains.
    speed : float
        Forward speed [m/s], finite and >= 0 (as :func:`vehdyn.handling.steady_state_gains`
        takes it; an oversteering vehicle's gains are finite below its critical speed only).

    Attributes
    ----------
    gains : dict of str to float
        Steady-state gain per unit front steer of ``yaw_rate`` [1/s], ``lateral_acceleration``
        [m/s^2/rad], ``sideslip_angle`` [-] and ``path_curvature`` [1/(m rad)].
    output_names : tuple of str
        The keys of ``gains``.
    """

    phenomena = frozenset({"lateral", "yaw"})

    def __init__(self, vehicle, speed):
        from vehdyn.handling.steady_state import steady_state_gains
        from vehdyn.signals import Signal

        self.speed = float(speed)
        g = steady_state_gains(vehicle, self.speed)
        self.gains = {"yaw_rate": float(g.yaw_rate), "lateral_acceleration": float(g.lateral_acceleration),
                      "sideslip_angle": float(g.sideslip_angle), "path_curvature": float(g.path_curvature)}
        units = {"yaw_rate": "rad/s", "lateral_acceleration": "m/s^2", "sideslip_angle": "rad",
                 "path_curvature": "1/m"}
        self.outputs = tuple(Signal(k, units[k], f"steady-state {k.replace('_', ' ')}") for k in self.gains)
        self.output_names = tuple(self.gains)

    def __repr__(self):
        return f"<SteadyStateAlgebra at {self.speed:g} m/s>"

    def evaluate(self, time, steer):
        """The outputs at ``time``: each gain times the steer at that instant.

        Parameters
        ----------
        time : ndarray
            The time grid [s].
        steer : callable
            ``steer(t)``, the front steer angle [rad], vectorized over ``t``.

        Returns
        -------
        SimulationResult
            The outputs of :attr:`output_names` on ``time``, no states or inputs, method
            ``"algebraic"``, the evaluation's wall time.
        """
        start = _time.perf_counter()
        delta = np.asarray(steer(time), dtype=float)
        outputs = np.array([gain * delta for gain in self.gains.values()])
        return _result(self, time, outputs, _time.perf_counter() - start, "algebraic")


#: The terms of a vehicle's understeer budget (:func:`vehdyn.handling.understeer_budget`) a rung may
#: or may not carry, with the vehicle-file fields that switch each on.
UNDERSTEER_TERMS = {
    "roll_steer": ("suspension.front_roll_steer", "suspension.rear_roll_steer"),
    "camber_thrust": ("suspension.front_camber_gain", "suspension.rear_camber_gain"),
    "compliance_steer": ("suspension.front_lateral_force_compliance_steer",
                         "suspension.rear_lateral_force_compliance_steer",
                         "suspension.front_aligning_moment_compliance_steer",
                         "suspension.rear_aligning_moment_compliance_steer"),
}


def refuse_dropped_terms(vehicle, carries=()) -> None:
    """NotAdmissible when the vehicle has a term of its understeer budget that the rung does not carry.

    Parameters
    ----------
    vehicle : Vehicle
        The scene's vehicle.
    carries : tuple of str
        The keys of :data:`UNDERSTEER_TERMS` the rung carries.

    Raises
    ------
    NotAdmissible
        Naming the first field (and its value) of a term the rung would drop.
    """
    for term, fields in UNDERSTEER_TERMS.items():
        if term in carries:
            continue
        for name in fields:
            group, _, attr = name.partition(".")
            value = getattr(getattr(vehicle, group), attr)
            if value is not None and value != 0.0:
                raise NotAdmissible(f"does not carry the {term.replace('_', ' ')} of the vehicle ({name} = {value:g}): "
                                    f"a term of its understeer budget")


def _steer_only(drive, accepted=("front_steer_angle", "rear_steer_angle")):
    """The scene's inputs for a constant-speed model (NotAdmissible for an input it does not have)."""
    unknown = [k for k in drive.inputs if k not in accepted]
    if unknown:
        raise NotAdmissible(f"has no input {unknown[0]!r}")
    return dict(drive.inputs)


def _constant_speed_ignores(drive):
    return ("road",) if drive.road is not None else ()


def build_steady_state(drive) -> Setup:
    if drive.braking is not None or drive.track is not None or drive.initial_turn is not None:
        raise NotAdmissible("quasi-steady algebra needs an open-loop steer at constant speed")
    steer = _steer_only(drive, ("front_steer_angle",)).get("front_steer_angle")
    if steer is None:
        raise NotAdmissible("no steer input")
    refuse_dropped_terms(drive.vehicle, ("compliance_steer",))
    model = SteadyStateAlgebra(drive.vehicle, drive.scene.speed)
    return Setup(model, lambda: model.evaluate(drive.time, steer), _constant_speed_ignores(drive))




def _with_driver(model, drive, speed_control):
    """The model in the loop with the ISO 3888-1 preview driver (states x, y, yaw_angle and
    longitudinal_velocity needed): a :class:`~vehdyn.interconnect.ClosedLoop`."""
    from vehdyn.driver import PreviewDriver

    track, vehicle = drive.track, drive.vehicle
    speed = dict(target_speed=drive.scene.speed, mass=vehicle.mass.mass) if speed_control else {}
    driver = PreviewDriver(track.path_x, track.path_y, wheelbase=vehicle.geometry.wheelbase, **speed, **drive.driver)
    return driver.close(model)


def _linear_setup(model, drive) -> Setup:
    from vehdyn.simulation import simulate

    if drive.braking is not None or drive.initial_turn is not None:
        raise NotAdmissible("constant speed: no braking")
    inputs = _steer_only(drive)
    if drive.track is not None:
        loop = _with_driver(_Positioned(model, drive.scene.speed), drive, speed_control=False)
        x0 = np.zeros(loop.n_states)
        x0[loop.index("x")] = float(drive.track.path_x[0])
        x0[loop.index("longitudinal_velocity")] = drive.scene.speed
        return Setup(loop, lambda: simulate(loop, drive.time, None, x0=x0, method="RK45", rtol=1e-8, atol=1e-10),
                     _constant_speed_ignores(drive))
    return Setup(model, lambda: simulate(model, drive.time, inputs, method="exact"), _constant_speed_ignores(drive))


def build_linear_bicycle(drive, tire_lag=False) -> Setup:
    from vehdyn.handling.bicycle import LinearBicycle

    refuse_dropped_terms(drive.vehicle, ("compliance_steer",))
    return _linear_setup(LinearBicycle(drive.vehicle, drive.scene.speed, tire_lag=tire_lag), drive)


def build_lateral_yaw_roll(drive) -> Setup:
    from vehdyn.handling.lateral_yaw_roll import LateralYawRoll

    refuse_dropped_terms(drive.vehicle, ("roll_steer", "compliance_steer"))
    return _linear_setup(LateralYawRoll(drive.vehicle, drive.scene.speed), drive)


def tire_laws(drive) -> tuple:
    """(front, rear) tire laws of the scene: its ``tire`` on both axles, else the vehicle's; read
    once per plan (:meth:`Drive.once`)."""
    from vehdyn.tire import load_tire, tire_for_vehicle

    def read():
        if drive.scene.tire is not None:
            return (load_tire(drive.scene.tire),) * 2
        return tuple(tire_for_vehicle(drive.vehicle, axle) for axle in ("front", "rear"))

    return drive.once("tire laws", read)


def build_lateral_yaw_roll_lag(drive) -> Setup:
    """LateralYawRollLag: the tires' laws are loaded here (per vehicle); the model, whose cornering
    stiffnesses and ply-steer coefficients come from the law at the running loads of the scene's
    speed, is derived again in every run (per-scene work is part of the cost)."""
    from vehdyn.handling.lateral_yaw_roll_lag import LateralYawRollLag

    refuse_dropped_terms(drive.vehicle, ("roll_steer", "compliance_steer"))
    front, rear = tire_laws(drive)

    def make():
        return LateralYawRollLag(drive.vehicle, drive.scene.speed, front_tire=front, rear_tire=rear)

    setup = _linear_setup(make(), drive)
    if drive.track is None:
        from vehdyn.simulation import simulate

        inputs = _steer_only(drive)
        setup.run = lambda: simulate(make(), drive.time, inputs, method="exact")
    setup.phenomena = LateralYawRollLag.phenomena | {"load_transfer"}
    return setup


def _positioned_class():
    from vehdyn.model import Model
    from vehdyn.signals import Signal

    from vehdyn.components.planar import position_rates
    from vehdyn.components.xp import NUMPY

    class Positioned(Model):
        """A constant-speed lateral model with the earth-fixed position and heading added.

        dX/dt = u cos(psi) - v sin(psi), dY/dt = u sin(psi) + v cos(psi), dpsi/dt = r (SAE,
        :func:`vehdyn.components.planar.position_rates`), and the constant forward speed u as a
        state (du/dt = 0) for a driver that reads it.
        """

        def __init__(self, model, speed):
            self.model, self.speed = model, float(speed)
            extra = (Signal("x", "m", "earth X"), Signal("y", "m", "earth Y (SAE)"),
                     Signal("yaw_angle", "rad", "heading psi"),
                     Signal("longitudinal_velocity", "m/s", "forward speed u (constant)"))
            self.declare(states=tuple(model.states) + extra, inputs=model.inputs,
                         outputs=tuple(model.output_signals) + extra)
            self.phenomena = model.phenomena
            self._iv, self._ir = model.index("lateral_velocity"), model.index("yaw_rate")

        def rhs(self, t, x, u):
            n = self.model.n_states
            inner, psi = x[:n], x[n + 2]
            v, r = inner[self._iv], inner[self._ir]
            dx, dy = position_rates(NUMPY, self.speed, v, psi)
            return np.concatenate([np.asarray(self.model.rhs(t, inner, u), dtype=float),
                                   np.stack([dx, dy, r, 0.0 * r])])

        def output(self, t, x, u):
            n = self.model.n_states
            return np.concatenate([np.asarray(self.model.output(t, x[:n], u), dtype=float), x[n:]])

    return Positioned


def _Positioned(model, speed):  # noqa: N802 - a class made on first use (Model import stays lazy)
    return _positioned_class()(model, speed)


def build_single_track(drive, tires="vehicle", lateral_load_transfer=False, roll=False, rtol=1e-8) -> Setup:
    """SingleTrack on the scene (options: ``tires`` "vehicle" or "linear", the model's
    ``lateral_load_transfer`` and ``roll``, ``rtol`` of its RK45 run, atol = rtol / 100)."""
    from vehdyn.handling.single_track import SingleTrack
    from vehdyn.simulation import simulate
    from vehdyn.tire import load_tire, tire_for_vehicle

    vehicle, scene = drive.vehicle, drive.scene
    # compliance steer always; roll steer and camber from roll with the load transfer (the roll state
    # or the steady roll), not without it
    refuse_dropped_terms(vehicle, ("compliance_steer",) + (("roll_steer", "camber_thrust") if lateral_load_transfer
                                                          else ()))
    if tires == "linear":
        front, rear = tire_for_vehicle(vehicle, "front", "linear"), tire_for_vehicle(vehicle, "rear", "linear")
    elif scene.tire is not None:
        front = rear = load_tire(scene.tire)
    else:
        front = rear = None
    model = SingleTrack(vehicle, front, rear, lateral_load_transfer=lateral_load_transfer, roll=roll)
    accepted = tuple(model.input_names)
    unknown = [k for k in drive.inputs if k not in accepted]
    if unknown:
        raise NotAdmissible(f"has no input {unknown[0]!r}")
    ignores = ("road",) if drive.road is not None else ()
    kw = dict(method="RK45", rtol=rtol, atol=1e-2 * rtol)
    phenomena = model.phenomena - {"tire_saturation"} if tires == "linear" else model.phenomena
    if drive.track is not None:
        loop = _with_driver(model, drive, speed_control=True)
        x0 = np.concatenate([model.straight_running(scene.speed, x=float(drive.track.path_x[0])), [0.0]])
        return Setup(loop, lambda: simulate(loop, drive.time, None, x0=x0, **kw), ignores, phenomena,
                     lateral_load_transfer)
    if drive.initial_turn is not None:
        from vehdyn.handling.nonlinear_steady_state import steady_state_cornering

        # the steady turn the scene starts in: checked here (no turn: not admissible), solved again
        # in every run (the start is part of what the scene costs)
        steady_state_cornering(model, lateral_acceleration=drive.initial_turn, speed=scene.speed)

    def run():
        drag = float(model.parameters.drag_factor) * scene.speed**2
        x0 = model.straight_running(scene.speed)
        inputs = dict(drive.inputs)
        if drive.initial_turn is not None:
            turn = steady_state_cornering(model, lateral_acceleration=drive.initial_turn, speed=scene.speed)
            x0, drag = turn.state, float(turn.drive)
            inputs["front_steer_angle"] = float(turn.steer_angle)
        if drive.braking is not None:
            front_force, rear_force, start = drive.braking
            hold = drag
            inputs["front_longitudinal_force"] = front_force
            inputs["rear_longitudinal_force"] = lambda t: np.where(np.asarray(t) >= start, rear_force(t), hold)
        elif "rear_longitudinal_force" not in inputs:
            inputs["rear_longitudinal_force"] = drag  # hold the entry speed against the drag
        inputs = {k: (v if callable(v) else (lambda t, c=float(v): np.full(np.shape(t), c)))
                  for k, v in inputs.items()}
        return simulate(model, drive.time, inputs, x0=x0, **kw)

    return Setup(model, run, ignores, phenomena, lateral_load_transfer)


# ====================================================================== ride builders
def _ride_inputs(model, drive, average: bool):
    from vehdyn.ride.wheelbase import road_inputs

    if drive.road is None:
        raise NotAdmissible("no road input")
    distance, left, right = drive.road
    if average:
        return road_inputs(model, drive.time, drive.scene.speed, distance, 0.5 * (left + right))
    return road_inputs(model, drive.time, drive.scene.speed, distance, left, right)


def _ride_ignores(drive):
    return tuple(drive.inputs) + (("braking",) if drive.braking is not None else ())


def build_quarter_car(drive) -> Setup:
    """Front and rear quarter cars on the mean of the two tracks, side by side; the body heave at
    the sprung CG from the two corners' sprung motion, z = (b z_f + a z_r) / L."""
    from vehdyn.model import LinearModel
    from vehdyn.ride.quarter_car import QuarterCar
    from vehdyn.simulation import simulate

    v = drive.vehicle
    qf, qr = QuarterCar(v, "front"), QuarterCar(v, "rear")
    A = np.block([[qf.A, np.zeros_like(qf.A)], [np.zeros_like(qr.A), qr.A]])
    B = np.block([[qf.B, np.zeros_like(qf.B)], [np.zeros_like(qr.B), qr.B]])
    C = np.block([[qf.C, np.zeros_like(qf.C)], [np.zeros_like(qr.C), qr.C]])
    D = np.block([[qf.D, np.zeros_like(qf.D)], [np.zeros_like(qr.D), qr.D]])
    a, b = v.geometry.sprung_cg_to_front_axle, v.geometry.sprung_cg_to_rear_axle
    L = a + b
    from vehdyn.signals import Signal

    outputs = [Signal(s.name + "_front", s.unit, s.description + " (front corner)") for s in qf.output_signals]
    outputs += [Signal(s.name + "_rear", s.unit, s.description + " (rear corner)") for s in qr.output_signals]
    extra_c, extra_d = [], []
    for name in ("sprung_displacement", "sprung_velocity", "sprung_acceleration"):
        i = qf.index(name, "outputs")
        extra_c.append(np.concatenate([b / L * qf.C[i], a / L * qr.C[i]]))
        extra_d.append(np.concatenate([b / L * qf.D[i], a / L * qr.D[i]]))
        outputs.append(Signal(name, qf.output_signals[i].unit, f"{name.replace('_', ' ')} at the sprung CG"))
    states = [Signal(s.name + "_front", s.unit) for s in qf.states] + [Signal(s.name + "_rear", s.unit)
                                                                        for s in qr.states]
    inputs = [Signal(s.name + sfx, s.unit) for sfx in ("_front", "_rear") for s in qf.inputs]
    pair = LinearModel(A, B, np.vstack([C] + extra_c), np.vstack([D] + extra_d), states=states, inputs=inputs,
                       outputs=outputs, name=f"front and rear QuarterCar of {v.name}", phenomena=qf.phenomena)
    if drive.road is None:
        raise NotAdmissible("no road input")
    distance, left, right = drive.road
    from vehdyn.road import RoadProfile

    profile = RoadProfile(distance, 0.5 * (left + right))
    u = {}
    for sfx, offset in (("_front", 0.0), ("_rear", v.geometry.wheelbase)):
        _, w = profile.road_inputs(drive.scene.speed, {sfx: offset + distance[0]}, time=drive.time)
        u.update(w)
    return Setup(pair, lambda: simulate(pair, drive.time, u, method="exact"), _ride_ignores(drive))


def build_bounce_pitch(drive) -> Setup:
    """Bounce-pitch half car on the mean of the two tracks: for a left-right symmetric vehicle the
    heave and pitch of the full car respond to the mean track only (the roll to the difference)."""
    from vehdyn.ride.bounce_pitch import BouncePitch
    from vehdyn.simulation import simulate

    model = BouncePitch(drive.vehicle)
    u = _ride_inputs(model, drive, average=True)
    return Setup(model, lambda: simulate(model, drive.time, u, method="exact"), _ride_ignores(drive))


def build_full_car(drive) -> Setup:
    from vehdyn.ride.full_car import FullCar
    from vehdyn.simulation import simulate

    model = FullCar(drive.vehicle)
    u = _ride_inputs(model, drive, average=False)
    return Setup(model, lambda: simulate(model, drive.time, u, method="exact"), _ride_ignores(drive))


def lateral_slip(drive):
    """:class:`vehdyn.ride.LateralSlip` of the scene's vehicle and tire laws at its speed: each
    axle's tire law (antisymmetric part) at half the static axle load, its cornering stiffness
    (slip 1e-4 rad) and the stiffness's load derivative (central difference, +-10 % load)."""
    from vehdyn.ride.lift_off import LateralSlip
    from vehdyn.units import GRAVITY
    from vehdyn.scene.estimates import _axle_tire_forces

    vehicle = drive.vehicle
    loads = vehicle.static_axle_loads(GRAVITY)
    alpha = 1e-4
    stiffness = {}
    for (axle, law), load in zip(zip(("front", "rear"), tire_laws(drive)), loads):
        wheel = 0.5 * load
        c = [float(_axle_tire_forces(law, wheel * f, alpha)) / alpha for f in (1.0, 0.9, 1.1)]
        stiffness[f"{axle}_cornering_stiffness"] = c[0]
        stiffness[f"{axle}_load_sensitivity"] = max((c[2] - c[1]) / (0.2 * wheel), 0.0)
    t = vehicle.tires
    return LateralSlip(speed=drive.scene.speed, yaw_inertia=vehicle.mass.yaw_inertia,
                       front_relaxation_length=t.front_relaxation_length, rear_relaxation_length=t.rear_relaxation_length,
                       **stiffness)


def longitudinal_slip(drive):
    """:class:`vehdyn.ride.LongitudinalSlip` of the scene's vehicle and tire laws at its speed: each
    axle's tire law at half the static axle load, its slip stiffness (antisymmetric part at slip
    ratio 1e-4), the stiffness's load derivative (central difference, +-10 % load), the force F_x /
    F_z and the rolling resistance lever -M_y / F_z at zero slip, the longitudinal relaxation lengths of the full
    vehicle, and the drive torques that hold the speed against the drag and the rolling resistance
    (split by ``driveline.front_drive_fraction``, as the full vehicle's trim)."""
    from vehdyn.components.tire_setup import longitudinal_relaxation_lengths
    from vehdyn.ride.lift_off import LongitudinalSlip
    from vehdyn.units import GRAVITY

    vehicle, speed = drive.vehicle, drive.scene.speed
    loads = vehicle.static_axle_loads(GRAVITY)
    t, a = vehicle.tires, vehicle.aero
    kappa = 1e-4
    values, resistance = {}, 0.0
    laws = tire_laws(drive)
    for axle, law, load in zip(("front", "rear"), laws, loads):
        wheel = 0.5 * load

        def fx(f):
            plus, minus = law.forces(wheel * f, kappa, 0.0, 0.0, speed), law.forces(wheel * f, -kappa, 0.0, 0.0, speed)
            return 0.5 * (float(plus.fx) - float(minus.fx)) / kappa

        c = [fx(f) for f in (1.0, 0.9, 1.1)]
        rolling = law.forces(wheel, 0.0, 0.0, 0.0, speed)
        lever = max(-float(rolling.my) / wheel, 0.0)
        values[f"{axle}_zero_slip_force"] = float(rolling.fx) / wheel
        values[f"{axle}_slip_stiffness"] = c[0]
        values[f"{axle}_load_sensitivity"] = max((c[2] - c[1]) / (0.2 * wheel), 0.0)
        values[f"{axle}_rolling_resistance"] = lever
        resistance += 2.0 * lever * wheel
    lengths = longitudinal_relaxation_lengths(vehicle, dict(zip(("front", "rear"), laws)), None,
                                              (t.front_relaxation_length, t.rear_relaxation_length), GRAVITY)
    torque = t.rolling_radius * 0.5 * a.air_density * a.frontal_area * a.drag_coefficient * speed**2 + resistance
    front = vehicle.driveline.front_drive_fraction
    return LongitudinalSlip(speed=speed, rolling_radius=t.rolling_radius, wheel_spin_inertia=t.wheel_spin_inertia,
                            front_relaxation_length=lengths[0], rear_relaxation_length=lengths[1],
                            front_drive_torque=0.5 * front * torque, rear_drive_torque=0.5 * (1.0 - front) * torque,
                            **values)


def build_full_car_lift_off(drive) -> Setup:
    """The full car with tires that lift off (:class:`vehdyn.ride.LiftOff`), the couplings of the
    sprung CG's height (``FullCar(vehicle, cg_heights=True)``), the tires' lateral slip
    under the rolling body (:func:`lateral_slip`) and their longitudinal slip with the wheels' spin
    and the body's fore-aft motion (:func:`longitudinal_slip`), on both tracks; RK45 at rtol 1e-5, atol 1e-7
    and ``max_step`` the scene's time step (compiled when numba is installed): against rtol 1e-9,
    1e-4 of the body accelerations on the sedan's rough road at 108 km/h, a 20th of the full
    vehicle's rtol-1e-6 cost there (its wheel lifts make many steps fail at tighter tolerances)."""
    from vehdyn.scene.full_vehicle_rungs import SOLVER_OPTIONS
    from vehdyn.ride.full_car import FullCar
    from vehdyn.ride.lift_off import LiftOff
    from vehdyn.simulation import simulate

    v = drive.vehicle
    raised = {"geometry.front_roll_centre_height": v.geometry.front_roll_centre_height,
              "geometry.rear_roll_centre_height": v.geometry.rear_roll_centre_height,
              "suspension.front_anti_dive": v.suspension.front_anti_dive,
              "suspension.rear_anti_squat": v.suspension.rear_anti_squat}
    raised = {k: x for k, x in raised.items() if x}
    if raised or v.suspension.front_camber_gain or v.suspension.rear_camber_gain:
        raise NotAdmissible(f"the full car's lateral slip acts through roll centres on the ground, without "
                            f"anti-pitch or camber gains ({raised or 'camber gains'})")
    model = LiftOff(FullCar(v, cg_heights=True), lateral=lateral_slip(drive),
                    longitudinal=longitudinal_slip(drive))
    u = _ride_inputs(model.linear, drive, average=False)
    options = dict(SOLVER_OPTIONS, rtol=1e-5, atol=1e-7, max_step=float(drive.scene.effective_time_step))
    return Setup(model, lambda: simulate(model, drive.time, u, **options), _ride_ignores(drive))


# ====================================================================== the registry
_HERE = "vehdyn.scene.registry"
for _rung in (
    Rung("SteadyState", f"{_HERE}:SteadyStateAlgebra", "handling", 0, build_steady_state, linear=True,
         description="steady-state gains times the steer (no transient)"),
    Rung("LinearBicycle", "vehdyn.handling.bicycle:LinearBicycle", "handling", 10, build_linear_bicycle,
         linear=True, description="2-DOF linear single track"),
    Rung("LinearBicycle+lag", "vehdyn.handling.bicycle:LinearBicycle", "handling", 20, build_linear_bicycle,
         linear=True, options={"tire_lag": True}, description="linear single track with tire relaxation"),
    Rung("LateralYawRoll", "vehdyn.handling.lateral_yaw_roll:LateralYawRoll", "handling", 30,
         build_lateral_yaw_roll, linear=True, description="3-DOF linear lateral-yaw-roll"),
    Rung("LateralYawRoll+lag", "vehdyn.handling.lateral_yaw_roll_lag:LateralYawRollLag", "handling", 35,
         build_lateral_yaw_roll_lag, linear=True,
         description="3-DOF linear lateral-yaw-roll, tire lag, tire law at the running loads"),
    Rung("SingleTrack(linear tires)", "vehdyn.handling.single_track:SingleTrack", "handling", 40,
         build_single_track, options={"tires": "linear"}, description="nonlinear planar, linear tire law"),
    Rung("SingleTrack", "vehdyn.handling.single_track:SingleTrack", "handling", 50, build_single_track,
         description="nonlinear planar, the vehicle's Magic Formula tires"),
    Rung("SingleTrack+LLT", "vehdyn.handling.single_track:SingleTrack", "handling", 60, build_single_track,
         options={"lateral_load_transfer": True},
         description="nonlinear planar, Magic Formula tires at the wheel loads of the quasi-static lateral "
                     "load transfer"),
    # rtol 1e-6 as the full vehicle's run: 1.5-1.7x cheaper than 1e-8, the same errors to 5 digits
    Rung("SingleTrack+roll", "vehdyn.handling.single_track:SingleTrack", "handling", 70, build_single_track,
         options={"lateral_load_transfer": True, "roll": True, "rtol": 1e-6},
         description="nonlinear planar with a roll degree of freedom: Magic Formula tires at the wheel loads of "
                     "the dynamic lateral load transfer"),
    Rung("QuarterCar", "vehdyn.ride.quarter_car:QuarterCar", "ride", 10, build_quarter_car, linear=True,
         description="front and rear quarter cars, mean track"),
    Rung("BouncePitch", "vehdyn.ride.bounce_pitch:BouncePitch", "ride", 20, build_bounce_pitch, linear=True,
         description="half car in pitch, mean track"),
    Rung("FullCar", "vehdyn.ride.full_car:FullCar", "ride", 30, build_full_car, linear=True,
         description="7-DOF full car, both tracks"),
    Rung("FullCar+lift", "vehdyn.ride.lift_off:LiftOff", "ride", 40, build_full_car_lift_off,
         description="7-DOF full car, both tracks, tires that lift off, slip and spin, CG-height couplings"),
    # The top rung of both ladders: vehdyn.full_vehicle.ladder_setup(drive, ladder) -> Setup with the
    # contract of the builders above (the handling rung answers every scene with a ground-plane
    # input, road or not; the ride rung the road-only scenes).
    Rung("FullVehicle", "vehdyn.full_vehicle:FullVehicle", "handling", 100, "vehdyn.scene.full_vehicle_rungs:ladder_setup",
         options={"ladder": "handling"}, description="6-DOF body, four corners, wheel spin"),
    Rung("FullVehicle(ride)", "vehdyn.full_vehicle:FullVehicle", "ride", 100, "vehdyn.scene.full_vehicle_rungs:ladder_setup",
         options={"ladder": "ride"}, description="6-DOF body, four corners, wheel spin"),
    # the same model linearized at the scene's trim (vehdyn.scene.full_vehicle_rungs.linearized_setup)
    Rung("FullVehicle(linearized)", "vehdyn.full_vehicle:FullVehicle", "handling", 90,
         "vehdyn.scene.full_vehicle_rungs:linearized_setup", linear=True, probe=False, options={"ladder": "handling"},
         description="the full vehicle linearized at the trim, simulated exactly"),
    Rung("FullVehicle(linearized, ride)", "vehdyn.full_vehicle:FullVehicle", "ride", 90,
         "vehdyn.scene.full_vehicle_rungs:linearized_setup", linear=True, probe=False, options={"ladder": "ride"},
         description="the full vehicle linearized at the trim, simulated exactly"),
):
    register_rung(_rung)
del _rung
