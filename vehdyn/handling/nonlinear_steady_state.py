"""Steady-state cornering of the nonlinear single-track model: equilibrium, handling diagram, limit.

A steady turn of the :class:`~vehdyn.handling.SingleTrack` model at forward speed u and lateral
acceleration a_y has constant u, v and r = a_y / u, and every internal state (wheel spins, tire
deflections) at rest. The unknowns are the front steer angle, the lateral velocity v, the drive
input of the driven axle (axle force, or drive torque with wheel spin) that holds the speed against
drag and the steer-induced drag, and the internal states; the equations are the model's own state
derivatives du/dt, dv/dt, dr/dt and those of the internal states, all set to zero. So the algebraic
solution is the simulation's end point by construction of the same equations (Pacejka, *Tire and
Vehicle Dynamics*, 3rd ed., 2012, sec. 1.3.1-1.3.2, the handling diagram; Milliken & Milliken,
*Race Car Vehicle Dynamics*, 1995, ch. 5 and 8).

A turn is given by its radius R (then u = sqrt(a_y R)) or its speed u (then R = u^2 / a_y). The
handling diagram continues the solution in a_y from straight running until no equilibrium exists:
that a_y is the limit lateral acceleration of the model (the fold of the equilibrium branch, where
the front axle saturates for an understeering car, or the vehicle can no longer hold the turn).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from vehdyn.errors import ParameterError, SimulationError
from vehdyn.params.checks import is_number

__all__ = ["SteadyStateCornering", "steady_state_cornering", "nonlinear_handling_diagram",
           "NonlinearHandlingDiagram", "limit_lateral_acceleration"]

_FIXED = ("longitudinal_velocity", "yaw_rate", "x", "y", "yaw_angle")


@dataclass(frozen=True)
class SteadyStateCornering:
    """One steady turn of a :class:`~vehdyn.handling.SingleTrack` model (SAE signs).

    Attributes
    ----------
    speed : float
        Forward speed u [m/s].
    radius : float
        Radius of the CG path [m] (positive turning right).
    lateral_acceleration : float
        a_y = u r [m/s^2].
    steer_angle : float
        Front road-wheel steer angle [rad].
    sideslip_angle : float
        atan(v / u) at the CG [rad].
    yaw_rate : float
        [rad/s].
    drive : float
        The driven axle's longitudinal force [N] (force mode) or drive torque [N*m] (wheel spin).
    state, inputs : ndarray
        The full state and input vectors of the equilibrium [each signal in its unit, see the
        model's ``states`` and ``inputs``] (for ``simulate`` or ``linearize``).
    outputs : dict
        Every model output at the equilibrium.
    """

    speed: float
    radius: float
    lateral_acceleration: float
    steer_angle: float
    sideslip_angle: float
    yaw_rate: float
    drive: float
    state: np.ndarray = field(repr=False)
    inputs: np.ndarray = field(repr=False)
    outputs: dict = field(repr=False)


def _check_model(model):
    from vehdyn.handling.single_track import SingleTrack

    if not isinstance(model, SingleTrack):
        raise ParameterError(f"model must be a SingleTrack, got {type(model).__name__}", key="model", value=model)
    if model.n_variants is not None:
        raise ParameterError("steady_state_cornering needs a model with scalar parameters (not variants)",
                             key="model", value=model.n_variants)


def _drive_input(model, driven_axle: str) -> str:
    if driven_axle not in ("front", "rear"):
        raise ParameterError(f"driven_axle must be 'front' or 'rear', got {driven_axle!r}", key="driven_axle",
                             value=driven_axle)
    return f"{driven_axle}_drive_torque" if model.wheel_spin else f"{driven_axle}_longitudinal_force"


def _speed_and_yaw_rate(radius, speed, lateral_acceleration):
    ay = float(lateral_acceleration)
    if not np.isfinite(ay):
        raise ParameterError(f"lateral_acceleration must be finite, got {ay!r}", key="lateral_acceleration", value=ay)
    if (radius is None) == (speed is None):
        raise ParameterError("give exactly one of radius and speed", key="radius", value=(radius, speed))
    if radius is not None:
        radius = float(radius)
        if not np.isfinite(radius) or radius == 0:
            raise ParameterError(f"radius must be finite and non-zero [m], got {radius!r}", key="radius", value=radius)
        if ay * radius < 0:
            raise ParameterError(f"lateral_acceleration {ay} and radius {radius} must have the same sign (SAE: "
                                 "positive turning right)", key="lateral_acceleration", value=ay)
        u = float(np.sqrt(ay * radius))
        return u, (u / radius if u > 0 else 0.0)
    u = float(speed)
    if not np.isfinite(u) or u <= 0:
        raise ParameterError(f"speed must be finite and > 0 [m/s], got {u!r}", key="speed", value=u)
    return u, ay / u


def _solve(model, u, r, drive_name, guess):
    from scipy.optimize import root

    free = [k for k, name in enumerate(model.state_names) if name not in _FIXED]
    rows = [model.index(name) for name in ("longitudinal_velocity", "lateral_velocity", "yaw_rate")]
    rows += [k for k in free if model.state_names[k] != "lateral_velocity"]
    i_steer = model.index("front_steer_angle", "inputs")
    i_drive = model.index(drive_name, "inputs")
    p = model.parameters
    # scales: steer [rad], drive [N or N*m], states as they come; residual rows scaled to m/s^2-like
    drive_scale = float(p.mass * p.gravity) * (float(p.rolling_radius) if model.wheel_spin else 1.0)
    row_scale = np.ones(len(rows))
    for j, k in enumerate(rows):
        name = model.state_names[k]
        if name.endswith("wheel_speed"):
            row_scale[j] = 2 * float(p.wheel_spin_inertia) / (float(p.rolling_radius) * float(p.mass))
        elif name.endswith("deflection"):
            row_scale[j] = 1.0

    def unpack(z):
        x = np.zeros(model.n_states)
        x[model.index("longitudinal_velocity")] = u
        x[model.index("yaw_rate")] = r
        x[free] = z[2:]
        uin = np.zeros(model.n_inputs)
        uin[i_steer] = z[0]
        uin[i_drive] = z[1] * drive_scale
        return x, uin

    def residual(z):
        x, uin = unpack(z)
        f = np.asarray(model.rhs(0.0, x, uin), dtype=float)
        return f[rows] * row_scale

    sol = root(residual, guess, method="hybr", options={"xtol": 1e-12})
    ok = sol.success and np.max(np.abs(residual(sol.x))) < 1e-8
    x, uin = unpack(sol.x)
    return ok, sol.x, x, uin, free


def _initial_guess(model, u, r, drive_name):
    """Linear-bicycle steer and sideslip, free-rolling wheels, relaxed tires."""
    p = model.parameters
    a, b, m = float(p.a), float(p.b), float(p.mass)
    cf, cr = (float(c) for c in model.axle_cornering_stiffness())
    length = a + b
    ay = u * r
    k = m / length * (b / cf - a / cr)
    steer = length * r / max(u, 1e-9) + k * ay
    rear_slip = m * ay * a / (length * cr)  # SAE: alpha_r = (v - b r)/u, F_yr = -C_r alpha_r
    v = -rear_slip * u + b * r
    free = [name for name in model.state_names if name not in _FIXED]
    x = model.state_vector({"longitudinal_velocity": u, "yaw_rate": r, "lateral_velocity": v,
                            **({f"{ax}_wheel_speed": u / float(p.rolling_radius) for ax in ("front", "rear")}
                               if model.wheel_spin else {})})
    drag = float(p.drag_factor) * u * u
    drive_scale = float(p.mass * p.gravity) * (float(p.rolling_radius) if model.wheel_spin else 1.0)
    drive = (drag + abs(steer) * m * abs(ay) * b / length) * (float(p.rolling_radius) if model.wheel_spin else 1.0)
    return np.concatenate([[steer, drive / drive_scale], [x[model.index(n)] for n in free]])


def steady_state_cornering(model, *, lateral_acceleration, radius=None, speed=None, driven_axle: str = "rear",
                           initial_guess=None) -> SteadyStateCornering:
    """The steady turn of ``model`` at ``lateral_acceleration`` [m/s^2] on ``radius`` [m] or at ``speed`` [m/s].

    Parameters
    ----------
    model : SingleTrack
    lateral_acceleration : float
        a_y [m/s^2], positive turning right (SAE).
    radius, speed : float
        Exactly one: the path radius [m] (same sign as a_y) or the forward speed [m/s] (> 0).
    driven_axle : {"rear", "front"}
        The axle whose drive input holds the speed.
    initial_guess : SteadyStateCornering, optional
        A nearby solution to start from (continuation); default the linear-bicycle estimate.

    Returns
    -------
    SteadyStateCornering

    Raises
    ------
    SimulationError
        When no equilibrium is found (beyond the limit lateral acceleration).
    ParameterError
        On malformed arguments.
    """
    _check_model(model)
    u, r = _speed_and_yaw_rate(radius, speed, lateral_acceleration)
    drive_name = _drive_input(model, driven_axle)
    guess = _initial_guess(model, u, r, drive_name) if initial_guess is None else _guess_from(model, initial_guess,
                                                                                              drive_name)
    ok, z, x, uin, _ = _solve(model, u, r, drive_name, guess)
    if not ok:
        raise SimulationError(f"no steady-state turn found at a_y = {float(lateral_acceleration):.4g} m/s^2, "
                              f"u = {u:.4g} m/s: beyond the limit of the model or of the driven axle")
    y = np.asarray(model.output(0.0, x, uin), dtype=float)
    outputs = dict(zip(model.output_names, y))
    v = x[model.index("lateral_velocity")]
    return SteadyStateCornering(
        speed=u, radius=(u / r if r != 0 else np.inf), lateral_acceleration=float(u * r), steer_angle=float(z[0]),
        sideslip_angle=float(np.arctan2(v, u)), yaw_rate=float(r), drive=float(uin[model.index(drive_name, "inputs")]),
        state=x, inputs=uin, outputs=outputs)


def _guess_from(model, previous: SteadyStateCornering, drive_name):
    p = model.parameters
    drive_scale = float(p.mass * p.gravity) * (float(p.rolling_radius) if model.wheel_spin else 1.0)
    free = [k for k, name in enumerate(model.state_names) if name not in _FIXED]
    return np.concatenate([[previous.steer_angle, previous.inputs[model.index(drive_name, "inputs")] / drive_scale],
                           previous.state[free]])


@dataclass(frozen=True)
class NonlinearHandlingDiagram:
    """Steady-state turns from straight running up to the limit (arrays over the points).

    Attributes
    ----------
    lateral_acceleration, steer_angle, sideslip_angle, speed, yaw_rate, drive,
    front_slip_angle, rear_slip_angle : ndarray
        [m/s^2], [rad], [rad], [m/s], [rad/s], [N or N*m], [rad], [rad].
    limit_lateral_acceleration : float
        The largest a_y with an equilibrium [m/s^2] (to ``tolerance``).
    radius, speed_given : float or None
        The turn definition: the constant radius [m] or the constant speed [m/s] (the other
        None).
    """

    lateral_acceleration: np.ndarray
    steer_angle: np.ndarray
    sideslip_angle: np.ndarray
    speed: np.ndarray
    yaw_rate: np.ndarray
    drive: np.ndarray
    front_slip_angle: np.ndarray
    rear_slip_angle: np.ndarray
    limit_lateral_acceleration: float
    radius: float | None = None
    speed_given: float | None = None

    def to_frame(self):
        """The diagram as a table.

        Returns
        -------
        pandas.DataFrame
            Indexed by ``lateral_acceleration``, one column per array attribute; units in
            ``attrs["units"]``.
        """
        import pandas as pd

        frame = pd.DataFrame({"steer_angle": self.steer_angle, "sideslip_angle": self.sideslip_angle,
                              "speed": self.speed, "yaw_rate": self.yaw_rate, "drive": self.drive,
                              "front_slip_angle": self.front_slip_angle, "rear_slip_angle": self.rear_slip_angle},
                             index=pd.Index(self.lateral_acceleration, name="lateral_acceleration"))
        frame.attrs["units"] = {"lateral_acceleration": "m/s^2", "steer_angle": "rad", "sideslip_angle": "rad",
                                "speed": "m/s", "yaw_rate": "rad/s", "drive": "N or N*m",
                                "front_slip_angle": "rad", "rear_slip_angle": "rad"}
        return frame

    def plot(self, ax=None):
        """Steer angle and sideslip [deg] against lateral acceleration [g] (the handling diagram).

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; default a new figure.

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        from vehdyn.plotting import new_figure

        if ax is None:
            ax = new_figure()[1][0, 0]
        g = 9.81
        ax.plot(self.lateral_acceleration / g, np.degrees(self.steer_angle), label="steer angle")
        ax.plot(self.lateral_acceleration / g, np.degrees(self.sideslip_angle), label="sideslip angle")
        ax.axvline(self.limit_lateral_acceleration / g, color="0.5", ls=":", label="limit")
        ax.set_xlabel("lateral acceleration [g]")
        ax.set_ylabel("angle [deg]")
        ax.legend()
        return ax


_MAX_STEPS = 10_000  # steady turns of one handling diagram at most (a step of 3 mm/s^2 to 30 m/s^2)


def nonlinear_handling_diagram(model, *, radius=None, speed=None, driven_axle: str = "rear", step: float = 0.25,
                               tolerance: float = 0.01, max_lateral_acceleration: float = 30.0
                               ) -> NonlinearHandlingDiagram:
    """Continue the steady turn in a_y from 0 until no equilibrium exists (the limit).

    Parameters
    ----------
    model : SingleTrack
    radius, speed : float
        Exactly one: the path radius [m] (positive: right turns) or the forward speed [m/s] (> 0).
    driven_axle : {"rear", "front"}
    step : float
        Initial a_y step [m/s^2]; halved near the limit.
    tolerance : float
        Resolution of the limit [m/s^2].
    max_lateral_acceleration : float
        Stop here if no limit was met [m/s^2].

    Returns
    -------
    NonlinearHandlingDiagram
    """
    _check_model(model)
    if radius is not None and float(radius) <= 0:
        raise ParameterError(f"radius must be > 0 for the handling diagram, got {radius!r}", key="radius", value=radius)
    limits = (("step", step), ("tolerance", tolerance), ("max_lateral_acceleration", max_lateral_acceleration))
    for name, value in limits:
        if not (is_number(value) and np.isfinite(value) and value > 0):
            raise ParameterError(f"{name} must be > 0, got {value!r}", key=name, value=value)
    if step < tolerance:  # the continuation would stop before its first step
        raise ParameterError(f"step = {step!r} m/s^2 must be at least the tolerance {tolerance!r} m/s^2 (the step is "
                             "halved down to it near the limit)", key="step", value=step)
    if max_lateral_acceleration / step > _MAX_STEPS:
        raise ParameterError(f"step = {step!r} m/s^2 takes {max_lateral_acceleration / step:.3g} steps to "
                             f"max_lateral_acceleration = {max_lateral_acceleration!r} m/s^2, more than {_MAX_STEPS}",
                             key="step", value=step)
    points, previous, ay, h = [], None, 0.0, float(step)
    while h >= tolerance and ay + h <= max_lateral_acceleration:
        try:
            point = steady_state_cornering(model, lateral_acceleration=ay + h, radius=radius, speed=speed,
                                           driven_axle=driven_axle, initial_guess=previous)
            # a continuation that jumps to another branch (steer falling by more than the step) is a fold
            if previous is not None and abs(point.steer_angle - previous.steer_angle) > 0.2:
                raise SimulationError("branch jump")
        except SimulationError:
            h *= 0.5
            continue
        points.append(point)
        previous, ay = point, ay + h
    if not points:
        raise SimulationError("no steady-state turn found even at the first step of the handling diagram")

    def arr(getter):
        return np.array([getter(pt) for pt in points])

    return NonlinearHandlingDiagram(
        lateral_acceleration=arr(lambda q: q.lateral_acceleration), steer_angle=arr(lambda q: q.steer_angle),
        sideslip_angle=arr(lambda q: q.sideslip_angle), speed=arr(lambda q: q.speed), yaw_rate=arr(lambda q: q.yaw_rate),
        drive=arr(lambda q: q.drive), front_slip_angle=arr(lambda q: q.outputs["front_slip_angle"]),
        rear_slip_angle=arr(lambda q: q.outputs["rear_slip_angle"]), limit_lateral_acceleration=float(ay),
        radius=None if radius is None else float(radius), speed_given=None if speed is None else float(speed))


def limit_lateral_acceleration(model, *, radius=None, speed=None, driven_axle: str = "rear",
                               tolerance: float = 0.01) -> float:
    """The largest steady-state lateral acceleration of ``model`` on ``radius`` or at ``speed``.

    The end of :func:`nonlinear_handling_diagram`'s continuation: the fold of the equilibrium
    branch, where no steady turn exists any more (Pacejka 2012, sec. 1.3.2).

    Parameters
    ----------
    model : SingleTrack
        With scalar parameters.
    radius, speed : float
        Exactly one: the path radius [m] (> 0) or the forward speed [m/s] (> 0).
    driven_axle : {"rear", "front"}, optional
        The axle whose drive input holds the speed (default ``"rear"``).
    tolerance : float, optional
        Resolution of the limit [m/s^2] (default 0.01).

    Returns
    -------
    float
        The limit lateral acceleration [m/s^2].

    Raises
    ------
    SimulationError
        When not even the first step of the continuation has an equilibrium.
    """
    return nonlinear_handling_diagram(model, radius=radius, speed=speed, driven_axle=driven_axle,
                                      tolerance=tolerance).limit_lateral_acceleration
