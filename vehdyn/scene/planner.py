"""The planner: which rungs can answer a scene, what each costs and misses, and the pick.

:func:`plan` builds every registered rung for the scene (cheap: no simulation), keeps those that
have the outputs, the inputs and the domain the scene needs, runs the linear handling rungs as
probes (about a millisecond each) to estimate the lateral acceleration and the differences between
them, estimates each rung's cost and error (:mod:`vehdyn.scene.estimates`) and picks the cheapest
rung whose estimated error is within the scene's tolerance. :func:`run` runs the pick (or a named
rung), :func:`ladder` runs every admissible rung and measures its error against the top one.
"""

from __future__ import annotations

import time as _time
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from vehdyn.errors import ParameterError, SimulationError, TirFileError, VehdynWarning
from vehdyn.params.checks import finite_number, is_number, whole_number
from vehdyn.units import GRAVITY
from vehdyn.scene import estimates as est
from vehdyn.scene.drive import drive_of
from vehdyn.scene.registry import Rung, Setup, NotAdmissible, rungs

__all__ = ["Plan", "RungAssessment", "SceneResult", "plan", "run", "ladder", "plot_ladder"]


@dataclass
class RungAssessment:
    """One row of a :class:`Plan`: whether a rung can answer the scene, at what cost and error.

    Parameters
    ----------
    rung : Rung
        The rung assessed.
    admissible : bool
        Whether it can answer the scene (it builds for the vehicle and scene, has every output
        and, for a scene with longitudinal forces, longitudinal dynamics).
    reason : str
        Why not, or (admissible) how its estimated error compares with the tolerance and what it
        ignores; "" until :func:`plan` fills it.
    setup : Setup, optional
        What the rung built for the scene (None where building it failed).
    estimated_cost_s : float
        Estimated wall time of the run [s] (from the measured tables of
        :mod:`vehdyn.scene.estimates`, never this machine's timing); NaN until estimated.
    errors : dict of str to float
        Estimated relative error against the reference rung [-] per scene output (empty until
        estimated).
    outputs : dict of str to str
        Scene output name -> the model output that answers it.
    """

    rung: Rung
    admissible: bool
    reason: str
    setup: Setup | None = None
    estimated_cost_s: float = float("nan")
    errors: dict = field(default_factory=dict)
    outputs: dict = field(default_factory=dict)  # scene output name -> model output name

    @property
    def estimated_error(self) -> float:
        """The largest estimate over the outputs (NaN when one is unestimated: never picked)."""
        return float(np.max(list(self.errors.values()))) if self.errors else float("nan")


@dataclass
class Plan:
    """The assessment of every rung for a scene and the pick.

    Attributes
    ----------
    scene : Scene
    rows : list of RungAssessment
        One per registered (importable) rung, in ladder order.
    chosen, top : RungAssessment
        The pick (cheapest within tolerance) and the reference (highest fidelity admissible).
    needs : dict
        Phenomena the scene needs -> why.
    lateral_utilization : float or None
        Peak lateral acceleration of the linear probe over mu g [-] (without a linear handling
        probe, for a braking scene: the combined demand sqrt(a_x^2 + a_y^2) / (mu g)); None when
        neither applies.
    drive : Drive
        The scene's inputs (:func:`~vehdyn.scene.drive.drive_of`), shared by the rungs.
    probes : dict of str to SimulationResult
        The linear rungs run while planning (the linear handling rungs, and on a road the linear
        ride rungs), by rung name.
    """

    scene: Any
    rows: list
    chosen: RungAssessment
    top: RungAssessment
    needs: dict
    lateral_utilization: float | None
    drive: Any = None
    probes: dict = field(default_factory=dict)

    @property
    def choice(self):
        """The chosen model class (the vehicle model, also when a driver closes the loop around it)."""
        return self.chosen.rung.model_class()

    def to_frame(self):
        """The plan as a table.

        Returns
        -------
        pandas.DataFrame
            A row per rung in ladder order, the columns ``model`` (class name), ``rung``,
            ``ladder``, ``admissible``, ``estimated_cost_s`` [s], ``estimated_error`` [-] (NaN
            where not admissible), ``chosen``, ``reason``; the units in ``attrs["units"]``, the
            scene's tolerance in ``attrs["tolerance"]``.
        """
        import pandas as pd

        rows = [{"model": (r.rung.model.split(":")[1]), "rung": r.rung.name, "ladder": r.rung.ladder,
                 "admissible": r.admissible, "estimated_cost_s": r.estimated_cost_s,
                 "estimated_error": r.estimated_error if r.admissible else float("nan"),
                 "chosen": r is self.chosen, "reason": r.reason} for r in self.rows]
        frame = pd.DataFrame(rows)
        frame.attrs["units"] = {"estimated_cost_s": "s", "estimated_error": "-"}
        frame.attrs["tolerance"] = self.scene.tolerance
        return frame

    def __str__(self) -> str:
        needs = ", ".join(f"{k} ({v})" for k, v in self.needs.items()) or "none beyond the outputs"
        lines = [f"plan for {list(self.scene.outputs)} within {self.scene.tolerance:g} "
                 f"({self.scene.kind} scene, {self.scene.duration:g} s at {self.scene.speed:g} m/s)",
                 f"needs: {needs}",
                 f"{'':2}{'rung':<26}{'ok':>3} {'cost [s]':>10} {'error':>9}  reason"]
        for r in self.rows:
            mark = "->" if r is self.chosen else "  "
            cost = f"{r.estimated_cost_s:10.2e}" if r.admissible else f"{'':>10}"
            error = f"{r.estimated_error:9.2e}" if r.admissible else f"{'':>9}"
            lines.append(f"{mark}{r.rung.name:<26}{'yes' if r.admissible else 'no':>3} {cost} {error}  {r.reason}")
        lines.append(f"choice: {self.chosen.rung.name} ({self.choice.__name__}); reference: {self.top.rung.name}")
        return "\n".join(lines)

    def __repr__(self) -> str:
        return f"<Plan: {self.chosen.rung.name} for {list(self.scene.outputs)} (reference {self.top.rung.name})>"

    def row(self, name: str) -> RungAssessment:
        """The row of rung ``name`` (rung name or model class name; the first admissible match).

        Parameters
        ----------
        name : str
            A rung's name (``"LinearBicycle+lag"``) or, if no rung has that name, a model class
            name (``"SingleTrack"``).

        Returns
        -------
        RungAssessment
            The first admissible row that matches.

        Raises
        ------
        ParameterError
            ``key="model"``: no rung of that name (the message lists them), or none of the rungs
            that match can answer the scene (the message gives the reason).
        """
        matches = [r for r in self.rows if name == r.rung.name] \
            or [r for r in self.rows if name == r.rung.model.split(":")[1]]  # a rung's name first
        admissible = [r for r in matches if r.admissible]
        if admissible:
            return admissible[0]
        if matches:
            raise ParameterError(f"rung {name!r} cannot answer this scene: {matches[0].reason}", key="model",
                                 value=name)
        raise ParameterError(f"no rung named {name!r}; the rungs are {[r.rung.name for r in self.rows]}",
                             key="model", value=name)


def _resolve_output(name: str, available) -> str | None:
    """The model output that answers scene output ``name`` (itself, or the left corner of a full car)."""
    for candidate in (name, name + "_left"):
        if candidate in available:
            return candidate
    return None


def _signals(result, outputs: dict) -> dict:
    return {scene_name: np.asarray(result[model_name], dtype=float) for scene_name, model_name in outputs.items()}


def _assess(rung: Rung, drive, scene) -> RungAssessment:
    try:
        setup = rung.setup(drive)
    except NotAdmissible as exc:
        return RungAssessment(rung, False, str(exc))
    except SimulationError as exc:  # e.g. no steady turn at the requested lateral acceleration
        return RungAssessment(rung, False, f"cannot start the scene: {exc}")
    except ParameterError as exc:  # the vehicle lacks what this model needs (e.g. consistent masses)
        return RungAssessment(rung, False, f"cannot build the model for this vehicle: {exc}")
    resolved = {o: _resolve_output(o, setup.output_names) for o in scene.outputs}
    missing = [o for o, m in resolved.items() if m is None]
    if missing:
        return RungAssessment(rung, False, f"has no output {', '.join(missing)}", setup)
    if drive.longitudinal and "longitudinal" not in rung.phenomena(setup):
        return RungAssessment(rung, False, "constant speed: no longitudinal dynamics", setup)
    return RungAssessment(rung, True, "", setup, outputs=resolved)


def _check_scene(scene, owner: str):
    """``scene``; ParameterError unless it is a :class:`~vehdyn.Scene` whose ``tire`` file (if any) reads."""
    from vehdyn.scene.definition import Scene

    if not isinstance(scene, Scene):
        raise ParameterError(f"{owner}: scene must be a vehdyn Scene (vehdyn.Scene(...) or Scene.from_toml(path)), "
                             f"got {type(scene).__name__} {scene!r:.80}", key="scene", value=scene)
    if scene.tire is not None:
        from vehdyn.tire import load_tire

        try:
            load_tire(scene.tire)
        except (TirFileError, ParameterError, OSError) as exc:
            raise ParameterError(f"Scene.tire = {scene.tire!r}: {exc}", key="tire", value=scene.tire) from None
    return scene


#: The largest road-wheel steer [rad] a scene may ask for: beyond +-90 degrees the wheel points
#: backwards and no model of the ladder holds (their slip angles and steer kinematics assume less).
MAX_STEER_ANGLE = 0.5 * np.pi


def _check_steer(scene, drive):
    """ParameterError naming the manoeuvre's parameter when its steer reaches beyond :data:`MAX_STEER_ANGLE`."""
    steer = drive.steer
    if steer is None:
        return
    try:
        peak = float(np.max(np.abs(np.asarray(steer(drive.time), dtype=float))))
    except (TypeError, ValueError):  # a user's scalar-only callable: simulate samples and names it
        return
    if not peak >= MAX_STEER_ANGLE:  # NaN is simulate's to name (at the instant it appears)
        return
    params = scene.manoeuvre_parameters
    if not isinstance(scene.manoeuvre, str):
        key, value, why = "manoeuvre", scene.manoeuvre, "the steer signal"
    elif "amplitude" in params:
        key, value, why = "manoeuvre_parameters.amplitude", params["amplitude"], "the amplitude"
    else:
        value = params.get("lateral_acceleration")
        key = "manoeuvre_parameters.lateral_acceleration"
        asked = "the manoeuvre's default lateral acceleration" if value is None else \
            f"a steady lateral acceleration of {value:g} m/s^2"
        why = f"{asked} at speed {scene.speed:g} m/s (the linear steady-state steer gain sizes the steer)"
    raise ParameterError(f"Scene.{key} = {value!r:.80}: {why} steers the road wheels to {peak:.3g} rad "
                         f"({np.degrees(peak):.0f} deg), beyond the +-90 deg where the ladder's models hold; ask for "
                         "less (or give amplitude [rad])", key=key, value=value)


def _check_road_event(scene, drive):
    """ParameterError naming a road event's height or depth beyond the wheel's radius: a wall or a hole
    the wheel falls into, not a road the ladder's models drive over."""
    if not isinstance(scene.road, dict):
        return
    radius = drive.vehicle.tires.rolling_radius
    for key in ("height", "depth"):
        value = scene.road.get(key)
        if value is not None and abs(value) > radius:
            raise ParameterError(f"Scene.road.{key} = {value!r} m: more than the wheel's radius {radius:.3g} m, not a "
                                 "road the ladder's models drive over (a wall, or a hole the wheel falls into)",
                                 key=f"road.{key}", value=value)


def plan(scene) -> Plan:
    """Assess every registered rung for ``scene`` and pick the cheapest within its tolerance.

    The plan is a function of the scene and the registry alone: it keeps no state between calls
    and learns nothing from a run (a verified miss in :func:`run` is reported on its result and
    in a warning, and changes no threshold, cost or later plan).

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    Plan

    Raises
    ------
    ParameterError
        When no rung has the requested outputs (the message lists who has what) or the scene is
        malformed (not a Scene, an unreadable tire file, a steer beyond +-90 degrees).
    """
    _check_scene(scene, "plan")
    drive = drive_of(scene)
    est.check_drag_load_transfer(drive.vehicle, scene.speed)
    _check_steer(scene, drive)
    _check_road_event(scene, drive)
    rows = [_assess(r, drive, scene) for r in rungs()]
    admissible = [r for r in rows if r.admissible]
    if not admissible:
        who = "; ".join(f"{r.rung.name} ({r.reason})" + (f" has {', '.join(r.setup.output_names)}" if r.setup else "")
                        for r in rows)
        raise ParameterError(f"no rung can answer outputs {list(scene.outputs)} in this scene. Who has what: {who}",
                             key="outputs", value=list(scene.outputs))
    needs: dict = {}
    vehicle = drive.vehicle
    mu_g = vehicle.tires.friction_coefficient * GRAVITY
    # probes: the linear handling rungs, run now (milliseconds), also give the lateral acceleration;
    # on a road the linear ride rungs too (milliseconds), whose tire loads show a wheel lifting
    probes = {}
    for r in admissible:
        if r.rung.linear and r.rung.probe and (r.rung.ladder == "handling" or drive.road is not None):
            probes[r.rung.name] = r.setup.run()
    utilization = None
    linear_probe = next((probes[n] for n in ("LinearBicycle", "LinearBicycle+lag", "LateralYawRoll") if n in probes),
                        None)
    if linear_probe is not None:
        utilization = float(np.max(np.abs(linear_probe["lateral_acceleration"]))) / mu_g
    elif drive.braking is not None or drive.initial_turn is not None:
        p = scene.manoeuvre_parameters
        ax = float(p.get("deceleration", 0.0))
        ay = drive.initial_turn or 0.0
        utilization = float(np.hypot(ax, ay)) / mu_g
    if utilization is not None and utilization > est.THRESHOLDS["saturation_fraction"]:
        needs["tire_saturation"] = f"a_y ~ {utilization:.2f} mu g > {est.THRESHOLDS['saturation_fraction']:g} mu g"
    if drive.longitudinal:
        needs["longitudinal"] = "braking or longitudinal force input"
    elif "LinearBicycle" in probes:
        du = est.speed_change(probes["LinearBicycle"], vehicle, scene.speed)
        if du > est.THRESHOLDS["speed_change_fraction"]:
            needs["longitudinal"] = f"speed change ~{du:.2f} u > {est.THRESHOLDS['speed_change_fraction']:g} u"
    if any("torque" in name for name in drive.inputs):
        needs["wheel_spin"] = "wheel torque input"
    if drive.road is not None:
        needs["road_input"] = "road profile"
    if "roll_angle" in scene.outputs or "roll_rate" in scene.outputs:
        needs["roll"] = "roll output"
    if utilization is not None and utilization > est.THRESHOLDS["linear_domain_fraction"]:
        for r in admissible:
            if r.rung.linear and r.rung.ladder == "handling":
                r.admissible = False
                r.reason = (f"outside the linear domain: a_y ~ {utilization:.2f} mu g > "
                            f"{est.THRESHOLDS['linear_domain_fraction']:g} mu g")
        admissible = [r for r in rows if r.admissible]
        if not admissible:
            raise ParameterError(f"no rung can answer outputs {list(scene.outputs)} beyond the linear domain "
                                 f"(a_y ~ {utilization:.2f} mu g) on this branch's ladder", key="outputs",
                                 value=list(scene.outputs))
    top = max(admissible, key=lambda r: r.rung.fidelity)
    ctx = _Context(scene, drive, probes, utilization, {r.rung.name: r for r in admissible}, top,
                   {r.rung.name: r for r in rows if r.rung.name in probes})
    for r in admissible:
        # the measured tables, never this call's timing: the pick must not depend on the machine's load
        r.estimated_cost_s = est.estimated_cost(r.rung.name, scene.duration, closed_loop=drive.track is not None)
        r.errors, notes = ctx.errors(r)
        ignored = f"; ignores {', '.join(r.setup.ignores)}" if r.setup.ignores else ""
        if r is top:
            lacks = sorted(set(needs) - top.rung.phenomena(top.setup))
            caveat = f"; lacks {', '.join(lacks)}: errors are relative to it" if lacks else ""
            r.reason = f"reference (highest fidelity that answers){caveat}{ignored}"
        else:
            within = "within" if r.estimated_error <= scene.tolerance else "beyond"
            r.reason = f"{within} tolerance: {notes or 'same phenomena as the reference'}{ignored}"
    fits = [r for r in admissible if r.estimated_error <= scene.tolerance] or [top]
    chosen = min(fits, key=lambda r: (r.estimated_cost_s, -r.rung.fidelity))
    return Plan(scene, rows, chosen, top, needs, utilization, drive, probes)


class _Context:
    """Per-scene estimates (see :mod:`vehdyn.scene.estimates`)."""

    def __init__(self, scene, drive, probes, utilization, admissible, top, probe_rows=None):
        self.scene, self.drive, self.probes = scene, drive, probes
        self.utilization, self.admissible, self.top = utilization, admissible, top
        # the probes' rows, also of linear rungs ruled out beyond the linear domain (their
        # differences still estimate what roll and tire lag change)
        self.probe_rows = {**(probe_rows or {}), **admissible}
        self.outputs = scene.outputs

    def _difference(self, a: str, b: str) -> dict | None:
        """Per-output relative difference of probe a against probe b (None if either is missing)."""
        if a not in self.probes or b not in self.probes:
            return None
        ra, rb = self.probe_rows[a], self.probe_rows[b]
        sa, sb = _signals(self.probes[a], ra.outputs), _signals(self.probes[b], rb.outputs)
        return est.relative_errors(sa, sb)

    @property
    def _linear_probe(self):
        """The linear bicycle's probe run (with tire lag where it ran), or None."""
        return next((self.probes[n] for n in ("LinearBicycle+lag", "LinearBicycle") if n in self.probes), None)

    def _lateral_load_transfer(self) -> float:
        """Side-force deficit of the lateral load transfer (:func:`estimates.lateral_load_transfer_deficit`)
        at the linear probe's peak lateral acceleration and slip angles, times its gain."""
        probe = self._linear_probe
        if probe is None or "front_slip_angle" not in probe:
            return float("nan")
        slips = [np.max(np.abs(probe["front_slip_angle"])), np.max(np.abs(probe["rear_slip_angle"]))]
        a_y = float(np.max(np.abs(probe["lateral_acceleration"])))
        return est.THRESHOLDS["load_transfer_gain"] * est.lateral_load_transfer_deficit(
            self.drive.vehicle, a_y, slips, self.scene.tire)

    def _roll_rung_share(self) -> float:
        """``roll_rung_gain`` times :func:`estimates.lateral_acceleration_share` at the linear probe's
        peak a_y times (speed / ``roll_rung_reference_speed``)^2."""
        probe = self._linear_probe
        if probe is None or "lateral_acceleration" not in probe:
            return float("nan")
        a_y = float(np.max(np.abs(probe["lateral_acceleration"])))
        speed = float(self.scene.speed) / est.THRESHOLDS["roll_rung_reference_speed"]
        return (est.THRESHOLDS["roll_rung_gain"] * est.lateral_acceleration_share(self.drive.vehicle, a_y)
                * speed * speed)

    def _lift(self) -> float:
        """Tire tension of the most complete linear ride probe (:func:`estimates.tire_lift`)."""
        ride = [r for n, r in self.probe_rows.items() if r.rung.ladder == "ride" and n in self.probes]
        if not ride:
            return float("nan")
        best = max(ride, key=lambda r: r.rung.fidelity)
        return est.tire_lift(self.probes[best.rung.name], self.drive.vehicle)

    def _saturation(self) -> float:
        vehicle = self.drive.vehicle
        probe = self._linear_probe
        if probe is not None and "front_slip_angle" in probe:
            slips = [np.max(np.abs(probe["front_slip_angle"])), np.max(np.abs(probe["rear_slip_angle"]))]
        elif not self.drive.handling_input:
            return 0.0  # straight running at constant speed: the tires carry no side force
        elif self.drive.braking is not None:
            p = self.scene.manoeuvre_parameters
            rho = est.combined_utilization(vehicle, self.drive.initial_turn or 0.0,
                                           float(p.get("deceleration", 0.0)), float(p.get("brake_front_share", 0.65)))
            return est.combined_slip_error(rho)
        else:
            return float("nan")
        return est.THRESHOLDS["saturation_gain"] * est.tire_deficit(vehicle, slips, self.scene.tire)

    def _phenomenon(self, p: str, rung: RungAssessment) -> tuple[dict | float, str]:
        """Estimated error (per output dict, or one number) of missing or adding phenomenon p."""
        d = self.drive
        if p == "tire_saturation":
            e = self._saturation()
            note = f"tire saturation ~{e:.1e}" if e != 0 else ""
            both_roll = "roll" in rung.rung.phenomena(rung.setup) and "roll" in self.top.rung.phenomena(self.top.setup)
            if both_roll and d.handling_input and not d.longitudinal:
                # a linear tire with roll: the law's load sensitivity under the lateral load transfer
                transfer = self._lateral_load_transfer()
                e += transfer
                note = " and ".join(filter(None, [note, f"lateral load transfer ~{transfer:.1e}"]))
            if "load_transfer" in rung.rung.phenomena(rung.setup) and not d.longitudinal and not rung.rung.linear:
                # a linear tire law in a nonlinear model with load transfer: its load sensitivity
                # differs from the law's (a linear model takes the law's stiffness at its loads)
                dg = abs(est.drag_load_transfer_gain_change(d.vehicle, self.scene.speed, law="linear")
                         - est.drag_load_transfer_gain_change(d.vehicle, self.scene.speed, self.scene.tire))
                e += dg
                note = " and ".join(filter(None, [note, f"load sensitivity ~{dg:.1e}"]))
            return e, note
        if p == "wheel_lift":  # on a road, charged in errors() (the linear tire's tension); flat: none
            return 0.0, ""
        if p == "wheel_spin":  # free-rolling wheels: the spin follows the speed
            return (float("nan"), "wheel spin under torque unestimated") if d.longitudinal else (0.0, "")
        if p in ("longitudinal", "aero", "load_transfer"):
            if d.longitudinal:
                return float("nan"), f"{p} needed"
            probe = self._linear_probe
            if probe is None or "lateral_velocity" not in probe:
                return 0.0, ""
            du = est.speed_change(probe, d.vehicle, self.scene.speed)
            if "load_transfer" in rung.rung.phenomena(rung.setup):
                return du, f"speed change ~{du:.1e}"  # the rung carries the drag's load transfer
            dg = est.drag_load_transfer_gain_change(d.vehicle, self.scene.speed, self.scene.tire)
            return du + dg, f"speed change ~{du:.1e} and drag load transfer ~{dg:.1e}"
        if p in ("heave", "wheel_hop", "road_input") and d.road is None:
            return 0.0, ""  # a flat road: nothing excites the vertical modes
        if p in ("lateral", "yaw", "tire_lag", "steering") and not d.handling_input:
            return 0.0, ""  # no steer: nothing excites the lateral modes
        if p == "tire_lag":
            diff = self._difference("LinearBicycle", "LinearBicycle+lag")
            return (diff, "tire lag (probes)") if diff else (float("nan"), "tire lag unestimated")
        if p == "roll":
            if rung.rung.ladder == "ride" or self.top.rung.ladder == "ride":
                k = est.THRESHOLDS["roll_asymmetry_gain"] * est.road_asymmetry(d.road)
                per_output = {o: (0.0 if est.is_body_output(o) else k) for o in self.outputs}
                note = f"roll, road asymmetry ~{k:.1e}" if any(per_output.values()) else "roll (blind at the CG)"
                return per_output, note
            diff = self._difference("LinearBicycle", "LateralYawRoll")
            if not diff:
                return float("nan"), "roll unestimated"
            # a rung that carries the lateral load transfer itself misses only the roll's dynamics
            transfer = self._lateral_load_transfer() if "roll" in self.top.rung.phenomena(self.top.setup) \
                and not rung.setup.lateral_load_transfer else 0.0
            if transfer:
                return {o: v + transfer for o, v in diff.items()}, f"roll (probes), lateral load transfer ~{transfer:.1e}"
            return diff, "roll (probes)"
        if p == "pitch" and d.road is None:
            # steer on a flat road: the body's pitch and heave and the wheels' motion that a planar or
            # roll model leaves out (a floor measured against the full vehicle linearized)
            k = est.THRESHOLDS["handling_reduction_floor"] if d.handling_input else 0.0
            note = f"pitch, heave and wheel motion ~{k:.1e}" if k else ""
            if k and not rung.rung.linear and "roll" in rung.rung.phenomena(rung.setup):
                # a nonlinear rung with roll: what its roll degree of freedom leaves out grows with a_y
                extra = self._roll_rung_share()
                k += extra
                note += f", roll beyond one degree of freedom ~{extra:.1e}"
            return k, note
        if p == "pitch":
            k = est.THRESHOLDS["dynamic_index_gain"] * est.dynamic_index_coupling(d.vehicle) ** 2
            return k, f"pitch coupling (1-DI)^2 ~{k:.1e}"
        return float("nan"), f"{p} unestimated"

    def errors(self, r: RungAssessment) -> tuple[dict, str]:
        floor = est.THRESHOLDS["numerical_error"]
        if r is self.top:
            return {o: 0.0 for o in self.outputs}, ""
        total = {o: floor for o in self.outputs}
        notes = []
        differ = sorted(r.rung.phenomena(r.setup) ^ self.top.rung.phenomena(self.top.setup))
        grouped = {"longitudinal", "aero", "load_transfer"}
        done_group = False
        for p in differ:
            if p in grouped:
                if done_group:
                    continue
                done_group = True
            value, note = self._phenomenon(p, r)
            if note:
                notes.append(note)
            for o in self.outputs:
                total[o] += value.get(o, float("nan")) if isinstance(value, dict) else value
        if self.drive.track is not None:
            factor = est.THRESHOLDS["closed_loop_factor"]
            total = {o: factor * v for o, v in total.items()}
            notes.append(f"closed loop x{factor:g}")
        if r.rung.linear and not self.top.rung.linear and self.drive.road is not None:
            lift = self._lift()
            value = est.THRESHOLDS["tire_lift_floor"] + est.THRESHOLDS["tire_lift_gain"] * lift
            total = {o: v + value for o, v in total.items()}
            notes.append(f"wheel lift (linear tire in tension) ~{value:.1e}" if lift else
                         f"linear against nonlinear contact ~{value:.1e}")
        elif "wheel_lift" in r.rung.phenomena(r.setup) and r.rung.ladder == "ride" and not self.top.rung.linear \
                and self.drive.road is not None:
            # a ride model whose tires lift off: what it misses grows with the lift and the speed
            lift = self._lift()
            value = est.lift_off_error(lift, self.scene.speed, est.road_asymmetry(self.drive.road), self.outputs)
            total = {o: v + value[o] for o, v in total.items()}
            notes.append(f"lift-off without wheel spin ~{max(value.values()):.1e}")
        if r.rung.name == "SteadyState":
            diff = self._difference("SteadyState", "LinearBicycle")
            notes.append("no transient (probes)")
            for o in self.outputs:
                total[o] += diff[o] if diff else float("nan")
        return total, ", ".join(notes)


@dataclass
class SceneResult:
    """The outcome of :func:`run`.

    Attributes
    ----------
    model : object
        The model instance run.
    result : SimulationResult
        Its result on the scene's time grid.
    rung : str
        The rung's name (after an escalation, the rung that met the tolerance).
    outputs : dict
        Scene output name -> array on the time grid.
    estimated_error : dict
        Output -> estimated relative error against the reference rung.
    verified_error : dict or None
        Output -> measured relative error against the reference rung (``verify=True``).
    reference : str
        The reference rung's name.
    plan : Plan
        The plan as it was made (its ``chosen`` row is the rung it picked, also after an escalation).
    signals : dict
        Scene output name -> the model's output name that answers it.
    within_tolerance : bool or None
        ``verify=True``: whether the verified error of the rung returned is within the scene's
        tolerance; None without verification (nothing was measured).
    misses : tuple of dict
        Every rung run and verified beyond the tolerance, in the order run: ``rung``,
        ``estimated_error`` and ``verified_error`` (largest over the outputs). Empty when the first
        rung met it.
    escalated_from : str or None
        The rung the plan picked (or ``model`` named) when a verified miss made :func:`run` rerun the
        scene on a rung further up; None otherwise.
    tolerance : float
        The scene's tolerance [-].
    """

    model: Any
    result: Any
    rung: str
    outputs: dict
    estimated_error: dict
    verified_error: dict | None
    reference: str
    plan: Plan
    signals: dict = field(default_factory=dict)
    within_tolerance: bool | None = None
    misses: tuple = ()
    escalated_from: str | None = None
    tolerance: float = float("nan")

    def _verdict(self) -> str:
        """One line on the verification: within or beyond the tolerance, and any escalation."""
        if self.verified_error is None:
            return ""
        worst = max(self.verified_error.values())
        if self.escalated_from is not None:
            first = self.misses[0]
            return (f"escalated from {self.escalated_from} (verified {first['verified_error']:.2e} > tolerance "
                    f"{self.tolerance:g}, estimated {first['estimated_error']:.2e}) to {self.rung} "
                    f"(verified {worst:.2e})")
        if self.within_tolerance:
            return f"within tolerance {self.tolerance:g} (verified {worst:.2e})"
        return f"BEYOND TOLERANCE: verified {worst:.2e} > {self.tolerance:g}"

    def headline(self) -> str:
        """Peak |value| of each output with its estimated (and verified) error, and the verdict.

        Returns
        -------
        str
            Lines: the rung, its model class and integration wall time [s]; per output its peak
            |value| with unit, estimated error and (``verify=True``) verified error against the
            reference; then the verdict (within or beyond the tolerance, or the escalation).
        """
        lines = [f"{self.rung} ({type(self.model).__name__}): {self.result.wall_time:.3g} s of integration"]
        for name, x in self.outputs.items():
            unit = self.result.unit(self.signals[name]) if name in self.signals else ""
            line = (f"  {name:<28} peak {float(np.max(np.abs(x))):.5g} {unit}  estimated error "
                    f"{self.estimated_error[name]:.2e}")
            if self.verified_error is not None:
                line += f", verified {self.verified_error[name]:.2e} against {self.reference}"
            lines.append(line)
        if self.verified_error is not None:
            lines.append(f"  {self._verdict()}")
        return "\n".join(lines)

    def __repr__(self) -> str:
        verdict = self._verdict()
        return f"<SceneResult of {self.rung}: {list(self.outputs)}{'; ' + verdict if verdict else ''}>"


def _run_row(p: Plan, row: RungAssessment):
    cached = p.probes.get(row.rung.name)
    return cached if cached is not None else row.setup.run()


def _worst(errors: dict) -> float:
    """The largest error over the outputs (NaN counts as the largest: never within a tolerance)."""
    values = np.asarray(list(errors.values()), dtype=float)
    return float("nan") if np.any(np.isnan(values)) else float(np.max(values))


def _rungs_above(p: Plan, row: RungAssessment) -> list:
    """The admissible rungs of higher fidelity than ``row``'s, the next one up first (then the cheaper)."""
    above = [r for r in p.rows if r.admissible and r is not row and r.rung.fidelity > row.rung.fidelity]
    return sorted(above, key=lambda r: (r.rung.fidelity, r.estimated_cost_s))


def run(scene, model: str = "auto", verify: bool = False, *, escalate: bool | None = None) -> SceneResult:
    """Run the rung the plan picks (or the rung named ``model``) on ``scene``.

    With ``verify=True`` the reference (top admissible) rung runs too and the error of the rung
    against it is measured. A rung whose verified error exceeds the scene's tolerance is a miss:
    the result says so (``within_tolerance`` False, its repr and :meth:`SceneResult.headline`),
    a :class:`~vehdyn.VehdynWarning` names the rung, its estimated and verified errors, and --
    with ``escalate`` -- the scene is run again on the rungs above it, the next one up first, until
    one meets the tolerance (the reference always does: it is what the errors are measured
    against); the result is that rung's, ``escalated_from`` names the first, ``misses`` lists every
    rung that missed. The plan learns nothing from a miss: thresholds, costs and later plans are
    unchanged (:func:`plan`).

    Parameters
    ----------
    scene : Scene
    model : str
        ``"auto"`` (the plan's pick) or a rung or model class name (``"LinearBicycle"``).
    verify : bool
        Also run the reference (top admissible) rung and report the measured errors.
    escalate : bool, optional
        After a verified miss, rerun the scene on the next rung up that meets the tolerance.
        Default: True for ``model="auto"`` (the plan promised the tolerance), False for a rung named
        by ``model`` (its result is what was asked for; the miss is still flagged and warned about).

    Returns
    -------
    SceneResult

    Raises
    ------
    ParameterError
        A bad scene (see :func:`plan`), an unknown or inadmissible ``model``, a ``verify`` or
        ``escalate`` that is not a bool.
    """
    for name, value in (("verify", verify), ("escalate", escalate)):
        if not (isinstance(value, (bool, np.bool_)) or (value is None and name == "escalate")):
            raise ParameterError(f"run: {name} must be True or False, got {value!r}", key=name, value=value)
    if not isinstance(model, str):
        raise ParameterError(f"run: model must be 'auto' or a rung or model class name, got {model!r}", key="model",
                             value=model)
    _check_scene(scene, "run")
    p = plan(scene)
    row = p.chosen if model == "auto" else p.row(model)
    result = _run_row(p, row)
    outputs = _signals(result, row.outputs)
    if not verify:
        return SceneResult(row.setup.model, result, row.rung.name, outputs, dict(row.errors), None, p.top.rung.name,
                           p, dict(row.outputs), tolerance=scene.tolerance)
    reference_result = _run_row(p, p.top)
    reference = _signals(reference_result, p.top.outputs)
    verified = est.relative_errors(outputs, reference)
    tolerance = scene.tolerance
    if _worst(verified) <= tolerance:
        return SceneResult(row.setup.model, result, row.rung.name, outputs, dict(row.errors), verified,
                           p.top.rung.name, p, dict(row.outputs), within_tolerance=True, tolerance=tolerance)
    misses = [{"rung": row.rung.name, "estimated_error": row.estimated_error, "verified_error": _worst(verified)}]
    what = "picked" if row is p.chosen else "named"
    promise = (f"estimated {row.estimated_error:.2e}" + (f", planned within the tolerance {tolerance:g}"
                                                           if row.estimated_error <= tolerance else ""))
    worst_output = max(verified, key=lambda o: np.inf if np.isnan(verified[o]) else verified[o])
    head = (f"run: the {what} rung {row.rung.name} ({promise}) is {_worst(verified):.2e} off the reference "
            f"{p.top.rung.name} in {worst_output} (verified), beyond the scene's tolerance {tolerance:g}")
    if escalate is None:
        escalate = model == "auto"
    if not escalate:
        warnings.warn(f"{head}; the result is {row.rung.name}'s (result.within_tolerance is False; "
                      "escalate=True reruns the scene on the next rung up that meets the tolerance)", VehdynWarning,
                      stacklevel=2)
        return SceneResult(row.setup.model, result, row.rung.name, outputs, dict(row.errors), verified,
                           p.top.rung.name, p, dict(row.outputs), within_tolerance=False, misses=tuple(misses),
                           tolerance=tolerance)
    for candidate in _rungs_above(p, row):
        cand_result = reference_result if candidate is p.top else _run_row(p, candidate)
        cand_outputs = _signals(cand_result, candidate.outputs)
        cand_verified = est.relative_errors(cand_outputs, reference)
        if _worst(cand_verified) <= tolerance:
            tried = ", ".join(f"{m['rung']} {m['verified_error']:.2e}" for m in misses[1:])
            warnings.warn(f"{head}; reran the scene on {candidate.rung.name} (verified {_worst(cand_verified):.2e})"
                          + (f" after {tried} also missed" if tried else "") + "; the result is that rung's", VehdynWarning,
                          stacklevel=2)
            return SceneResult(candidate.setup.model, cand_result, candidate.rung.name, cand_outputs,
                               dict(candidate.errors), cand_verified, p.top.rung.name, p, dict(candidate.outputs),
                               within_tolerance=True, misses=tuple(misses), escalated_from=row.rung.name,
                               tolerance=tolerance)
        misses.append({"rung": candidate.rung.name, "estimated_error": candidate.estimated_error,
                       "verified_error": _worst(cand_verified)})
    # the reference meets the tolerance against itself unless its own outputs are not finite
    raise SimulationError(f"{head}; no rung above it met the tolerance (the reference's outputs are not finite)")


_LONG_RUN_S = 1.0  # [s] a run this long is timed well enough by the best of two
_MAX_RUNS = 50  # runs of one rung at most, however short and however long ``min_time``


def ladder(scene, *, repeat: int = 1, min_time: float = 0.0):
    """Run every admissible rung of ``scene`` and measure its cost and error against the top rung.

    Parameters
    ----------
    scene : Scene
    repeat : int
        Runs per rung at least; the wall time is the fastest (the first run of a compiled model
        includes compiling or loading its code). A rung whose second run takes longer than 1 s is
        not run again (the machine's noise is small against it).
    min_time : float
        Time [s] to spend on each rung at least, counted from its second run (the first may
        compile), at most 50 runs (timeit's autorange): a rung of a few milliseconds is timed by
        the best of many runs, which a pause of the machine (another process, garbage collection)
        cannot all hit. 0 (default): ``repeat`` runs.

    Returns
    -------
    pandas.DataFrame
        A row per admissible rung (cheapest first): ``model``, ``rung``, ``wall_time_s``,
        ``estimated_cost_s``, ``estimated_error``, ``error`` (max over outputs), ``error_<output>``,
        ``within_tolerance`` (``error`` <= the scene's tolerance), ``planned``, ``reference``.
        ``attrs["tolerance"]`` and ``attrs["scene"]``. When the planned rung's measured error
        exceeds the tolerance the plan promised, a :class:`~vehdyn.VehdynWarning` says so.

    Raises
    ------
    ParameterError
        A bad scene (see :func:`plan`), ``repeat`` not a whole number >= 1, ``min_time`` not a
        finite number >= 0.
    """
    import pandas as pd

    _check_scene(scene, "ladder")
    repeat = whole_number(repeat, "repeat", minimum=1)
    if not (is_number(min_time) and 0.0 <= min_time < np.inf):
        raise ParameterError(f"min_time must be a finite number of seconds >= 0, got {min_time!r}", key="min_time",
                             value=min_time)
    min_time = float(min_time)
    p = plan(scene)
    results, times = {}, {}
    for row in p.rows:
        if not row.admissible:
            continue
        best, spent, k = np.inf, 0.0, 0
        while True:
            start = _time.perf_counter()
            res = row.setup.run()
            elapsed = _time.perf_counter() - start
            best, spent, k = min(best, elapsed), spent + (elapsed if k >= 1 else 0.0), k + 1
            if (k >= 2 and elapsed > _LONG_RUN_S) or k >= _MAX_RUNS or (
                    k >= int(repeat) and (min_time == 0.0 or spent >= min_time)):
                break
        results[row.rung.name], times[row.rung.name] = res, best
    reference = _signals(results[p.top.rung.name], p.top.outputs)
    records = []
    for row in p.rows:
        if not row.admissible:
            continue
        errors = est.relative_errors(_signals(results[row.rung.name], row.outputs), reference)
        worst = _worst(errors)
        rec = {"model": row.rung.model.split(":")[1], "rung": row.rung.name, "wall_time_s": times[row.rung.name],
               "estimated_cost_s": row.estimated_cost_s, "estimated_error": row.estimated_error,
               "error": max(errors.values()), "within_tolerance": bool(worst <= scene.tolerance),
               "planned": row is p.chosen, "reference": row is p.top}
        rec.update({f"error_{k}": v for k, v in errors.items()})
        records.append(rec)
        if row is p.chosen and not worst <= scene.tolerance:
            warnings.warn(f"ladder: the planned rung {row.rung.name} (estimated {row.estimated_error:.2e}) is "
                          f"{worst:.2e} off the reference {p.top.rung.name} (measured), beyond the scene's tolerance "
                          f"{scene.tolerance:g}; vehdyn.run(scene, verify=True) reruns it on the next rung up that "
                          "meets it", VehdynWarning, stacklevel=2)
    frame = pd.DataFrame(records).sort_values("wall_time_s", kind="stable").reset_index(drop=True)
    frame.attrs["tolerance"] = scene.tolerance
    frame.attrs["scene"] = scene
    frame.attrs["units"] = {"wall_time_s": "s", "estimated_cost_s": "s"}
    return frame


def plot_ladder(frame, *, ax=None, title: str | None = None, error_floor: float = 1e-7):
    """Cost against error, one point per rung, and the tolerance line.

    Parameters
    ----------
    frame : pandas.DataFrame
        From :func:`ladder` (its ``attrs["tolerance"]`` draws the line).
    ax : matplotlib Axes, optional
    title : str, optional
    error_floor : float
        Errors below it (the reference's zero) are drawn at it [-], > 0 (default 1e-7; both axes
        are logarithmic).

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib.pyplot as plt

    error_floor = finite_number(error_floor, "error_floor", positive=True)
    columns = getattr(frame, "columns", ())
    missing = [c for c in ("rung", "error", "wall_time_s", "planned", "reference") if c not in columns]
    if missing:
        raise ParameterError(f"plot_ladder: frame must be a table from vehdyn.ladder, got {type(frame).__name__} "
                             f"without the columns {missing}", key="frame", value=type(frame).__name__)
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 4.0))
    err = np.maximum(frame["error"].to_numpy(dtype=float), error_floor)
    cost = frame["wall_time_s"].to_numpy(dtype=float)
    # named: the planned rung, the reference and the rungs no other beats in both cost and error
    # (the speed-against-error frontier); the others are unnamed points, so names do not pile up
    dominated = [bool(np.any((cost <= c) & (err <= e) & ((cost < c) | (err < e)))) for c, e in zip(cost, err)]
    for k, (c, e) in enumerate(zip(cost, err)):
        planned, ref = bool(frame["planned"].iloc[k]), bool(frame["reference"].iloc[k])
        ax.plot(c, e, "o", ms=9 if planned else 6, mfc="none" if ref and not planned else None,
                color="C3" if planned else "C0" if not dominated[k] else "0.6")
        if planned or ref or not dominated[k]:
            ax.annotate(frame["rung"].iloc[k], (c, e), textcoords="offset points", xytext=(4, 4), fontsize=7)
    tol = frame.attrs.get("tolerance")
    if tol is not None:
        ax.axhline(tol, color="k", ls="--", lw=0.8, label=f"tolerance {tol:g}")
        ax.legend(fontsize=8)
    from matplotlib.ticker import NullFormatter

    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("error against the reference [-]")
    if title:
        ax.set_title(title, fontsize=9)
    return ax
