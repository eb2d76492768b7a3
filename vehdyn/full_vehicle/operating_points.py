"""Operating points of the full vehicle: steady straight running and steady cornering.

:func:`trim` solves rhs(x, u) = 0 for every state but the earth position and heading (x, y and
yaw angle move at constant rates), with two more conditions: the speed sqrt(u^2 + v^2) of the
sprung CG equals the requested one, and (cornering) the heading turns at
d(psi)/dt = a_y / V = V / R. The unknowns are those states (x = y = psi = 0), the drive torque
(split by ``driveline.front_drive_fraction``) that holds the speed and, when cornering, the front
steer angle. The body rates of a steady turn are the body components of the heading rate
(p = -psi' sin theta, q = psi' cos theta sin phi, r = psi' cos theta cos phi), found by the solver.

Solved by :func:`scipy.optimize.root` (Powell's hybrid method) on residuals scaled to be O(1),
from a start built from the closed forms (static equilibrium, free rolling, bicycle steer).
With ``lateral_acceleration`` the condition is on the output ``lateral_acceleration`` (the total
CG's, in the intermediate axes, as handling tests report it); with ``radius`` on the heading rate
V / R of the sprung CG's path.
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.checks import finite_number, is_number
from vehdyn.full_vehicle.corner import CORNERS

__all__ = ["trim"]

_FIXED = ("x", "y", "yaw_angle")


def _residual_scales(model, speed):
    """Typical size of each state's derivative (to make the residuals O(1) and the tolerance relative)."""
    g = model.gravity
    radius = model.vehicle.tires.rolling_radius
    scales = []
    for name in model.state_names:
        if name in ("longitudinal_velocity", "lateral_velocity", "vertical_velocity") or \
                name.startswith("unsprung_velocity"):
            scales.append(g)  # accelerations [m/s^2]
        elif name in ("roll_rate", "pitch_rate", "yaw_rate"):
            scales.append(g)  # angular accelerations, per metre of lever [rad/s^2]
        elif name.startswith("wheel_speed"):
            scales.append(g / radius)
        elif name in ("roll_angle", "pitch_angle", "yaw_angle"):
            scales.append(max(speed, 1.0))  # rad/s, per metre of lever
        else:  # positions, wheel travel, tire deflections [m/s]
            scales.append(max(speed, 1.0))
    return np.array(scales)


def trim(model, speed, *, lateral_acceleration=0.0, radius=None, longitudinal_acceleration=0.0, tol=1e-9,
         guess=None, backend="numpy"):
    """``(x0, u0)`` of steady running at ``speed``: what :meth:`FullVehicle.trim` returns.

    Parameters
    ----------
    model : FullVehicle
        The model.
    speed : float
        Speed of the sprung CG [m/s].
    lateral_acceleration : float
        Steady lateral acceleration [m/s^2].
    radius : float, optional
        Path radius [m] (overrides ``lateral_acceleration``).
    longitudinal_acceleration : float
        Quasi-steady braking or driving [m/s^2].
    tol : float
        Largest derivative allowed, relative [-].
    guess : (x, u), optional
        A nearby operating point to start from.
    backend : {"numpy", "compiled"}
        The residuals from the model's numpy ``rhs`` and ``output``, or from its compiled code
        (:func:`vehdyn.simulation.compiled.point_by_point`: the same equations within a few ulps,
        about 100x less time per evaluation once compiled; compiles them on first use).

    Returns
    -------
    x0, u0 : ndarray
        The state and inputs [SI units] (see :meth:`FullVehicle.trim`).
    """
    if not is_number(speed) or not np.isfinite(speed) or speed <= 0:
        raise ParameterError(f"speed must be a finite number > 0 [m/s], got {speed!r}", key="speed", value=speed)
    speed = float(speed)
    if radius is not None:
        if not is_number(radius) or not np.isfinite(radius) or radius == 0:
            raise ParameterError(f"radius must be a finite non-zero number [m] (positive turning right), got "
                                 f"{radius!r}", key="radius", value=radius)
        lateral_acceleration = speed**2 / float(radius)
    if not is_number(lateral_acceleration) or not np.isfinite(lateral_acceleration):
        raise ParameterError(f"lateral_acceleration must be a finite number [m/s^2], got {lateral_acceleration!r}",
                             key="lateral_acceleration", value=lateral_acceleration)
    lateral_acceleration = float(lateral_acceleration)
    tol = finite_number(tol, "tol", positive=True)
    rhs, output = _equations(model, backend)
    mu_g = model.vehicle.tires.friction_coefficient * model.gravity
    if abs(lateral_acceleration) >= mu_g:
        raise ParameterError(f"lateral_acceleration = {lateral_acceleration} m/s^2 is not below the friction limit "
                             f"mu g = {mu_g:.4g} m/s^2: no steady turn", key="lateral_acceleration",
                             value=lateral_acceleration)
    a_x = longitudinal_acceleration
    if not is_number(a_x) or not np.isfinite(a_x) or abs(a_x) >= mu_g:
        raise ParameterError(f"longitudinal_acceleration must be a finite number below mu g = {mu_g:.4g} m/s^2 in "
                             f"size [m/s^2], got {a_x!r}", key="longitudinal_acceleration", value=a_x)
    a_x = float(a_x)
    if a_x != 0.0 and lateral_acceleration != 0.0:
        raise ParameterError("trim takes a longitudinal or a lateral acceleration, not both",
                             key="longitudinal_acceleration", value=a_x)
    heading_rate = float(lateral_acceleration) / speed
    cornering = heading_rate != 0.0
    v = model.vehicle
    names = model.state_names
    free = [j for j, n in enumerate(names) if n not in _FIXED]
    equations = free
    braking = a_x < 0.0
    front_fraction = v.driveline.front_brake_fraction if braking else v.driveline.front_drive_fraction
    kind = "brake_torque" if braking else "drive_torque"
    drive = [model.index(f"{kind}{sfx}", "inputs") for sfx in CORNERS]
    # quasi-steady states that scale with the speed: their rates follow the deceleration
    scaling = [j for j in equations if names[j] in ("lateral_velocity", "vertical_velocity")
               or names[j].startswith("wheel_speed")]
    ax_output = model.index("longitudinal_acceleration", "outputs")
    ay_output = model.index("lateral_acceleration", "outputs")
    lon = model.index("longitudinal_velocity")
    steer = model.index("front_steer_angle", "inputs")
    yaw = model.index("yaw_angle")
    scales = _residual_scales(model, speed)[equations]

    # start: closed forms
    x0 = model.state_vector(longitudinal_velocity=speed)
    re = v.tires.rolling_radius
    for sfx in CORNERS:
        x0[model.index(f"wheel_speed{sfx}")] = speed / re
    drag = 0.5 * v.aero.air_density * v.aero.drag_coefficient * v.aero.frontal_area * speed**2
    torque0 = abs(drag + v.mass.mass * a_x) * re
    L = v.wheelbase
    delta0 = 0.0
    if cornering:
        from vehdyn.handling.bicycle import BicycleParameters

        t = v.tires
        bicycle = BicycleParameters(mass=v.mass.mass, yaw_inertia=v.mass.yaw_inertia, a=v.geometry.a,
                                    b=v.geometry.b, front_cornering_stiffness=t.front_cornering_stiffness,
                                    rear_cornering_stiffness=t.rear_cornering_stiffness)
        delta0 = L * heading_rate / speed + bicycle.understeer_gradient * lateral_acceleration
        x0[model.index("yaw_rate")] = heading_rate
        roll_stiffness = v.front_roll_stiffness + v.rear_roll_stiffness
        x0[model.index("roll_angle")] = -model.sprung_mass * v.mass.sprung_cg_height * lateral_acceleration \
            / roll_stiffness
    starts = [np.concatenate([x0[free], [torque0 / 1000.0, delta0]])]  # the closed-form start
    if guess is not None:  # continuation from a nearby operating point (x, u), tried first
        gx, gu = (np.asarray(g, dtype=float) for g in guess)
        if gx.shape != (model.n_states,) or gu.shape != (model.n_inputs,):
            raise ParameterError(f"guess must be (x, u) of shapes ({model.n_states},), ({model.n_inputs},)",
                                 key="guess", value=(gx.shape, gu.shape))
        if not (np.all(np.isfinite(gx)) and np.all(np.isfinite(gu))):
            raise ParameterError("guess must be finite", key="guess", value=(gx, gu))
        total = sum(gu[j] for j in drive)
        starts.insert(0, np.concatenate([_towards_speed(model, gx, speed, heading_rate)[free],
                                         [total / 1000.0, gu[steer]]]))

    def unpack(z):
        x = x0.copy()
        x[free] = z[:len(free)]
        u = model.input_vector()
        torques = (0.5 * front_fraction * z[-2] * 1000.0,) * 2 + (0.5 * (1 - front_fraction) * z[-2] * 1000.0,) * 2
        for j, tq in zip(drive, torques):
            u[j] = tq
        u[steer] = z[-1]
        return x, u

    def residual(z):
        x, u = unpack(z)
        if np.any(model._outside_domain(x)):  # the iterate left the model's domain (rolled over): push it back
            return np.full(z.size, 1e6)
        d = rhs(0.0, x, u)
        if a_x != 0.0:
            d = d.copy()
            d[scaling] -= x[scaling] * d[lon] / x[lon]
            d[lon] = output(0.0, x, u)[ax_output] - a_x
        out = list(d[equations] / scales)
        u_, v_ = x[model.index("longitudinal_velocity")], x[model.index("lateral_velocity")]
        out.append((np.hypot(u_, v_) - speed) / max(speed, 1.0))
        if not cornering:
            out.append(z[-1])  # no steer
        elif radius is not None:  # the heading turns at V / R
            out.append((d[yaw] - heading_rate) / max(speed, 1.0))
        else:  # the lateral acceleration of the total CG (intermediate axes) is the requested one
            out.append((output(0.0, x, u)[ay_output] - lateral_acceleration) / model.gravity)
        return np.array(out)

    best = None
    for z0 in starts:  # the guess first; the closed-form start when it fails
        z, worst, message = _solve(residual, z0, tol)
        if best is None or worst < best[1]:
            best = (z, worst, message)
        if worst <= tol:
            break
    z, worst, message = best
    if not worst <= tol:
        raise ParameterError(f"trim found no steady state at speed = {speed} m/s, lateral_acceleration = "
                             f"{lateral_acceleration} m/s^2: the largest relative derivative is {worst:.3g} "
                             f"(> {tol:g}) from {'the guess and ' if guess is not None else ''}the closed-form "
                             f"start; {message}", key="lateral_acceleration", value=lateral_acceleration)
    return unpack(z)


def _equations(model, backend):
    """The (rhs, output) functions ``f(t, x, u)`` the residuals read, by ``backend``, or ParameterError."""
    from vehdyn.simulation.compiled import backend_option, point_by_point

    return (model.rhs, model.output) if backend_option(backend) == "numpy" else point_by_point(model)


def _towards_speed(model, x, speed, heading_rate):
    """A guess's states carried to ``speed`` and the heading rate: velocities and wheel speeds scaled
    by the speed ratio (the slips and attitude kept), the yaw rate set to the heading rate, position
    and heading zeroed; for straight running its left-right symmetric part (a noisy guess could
    otherwise lead the solver to another equilibrium, a steady yaw under braking)."""
    x = np.array(x, dtype=float, copy=True)
    names = model.state_names
    u, v = x[model.index("longitudinal_velocity")], x[model.index("lateral_velocity")]
    old = float(np.hypot(u, v))
    ratio = speed / old if np.isfinite(old) and old > 0.0 else 1.0
    for j, name in enumerate(names):
        if name in ("longitudinal_velocity", "lateral_velocity", "vertical_velocity", "roll_rate", "pitch_rate") \
                or name.startswith("wheel_speed"):
            x[j] *= ratio
        elif name in _FIXED:
            x[j] = 0.0
    if ratio == 1.0 and not old > 0.0:
        x[model.index("longitudinal_velocity")] = speed
    x[model.index("yaw_rate")] = heading_rate * np.cos(x[model.index("roll_angle")]) \
        * np.cos(x[model.index("pitch_angle")])
    if heading_rate == 0.0:  # straight: the symmetric part of the guess (no other equilibrium to slide to)
        for name in ("lateral_velocity", "roll_rate", "yaw_rate", "roll_angle"):
            x[model.index(name)] = 0.0
        for kind in ("wheel_speed", "unsprung_displacement", "unsprung_velocity", "longitudinal_deflection"):
            for left, right in ((CORNERS[0], CORNERS[1]), (CORNERS[2], CORNERS[3])):
                if f"{kind}{left}" in names:
                    j, k = model.index(f"{kind}{left}"), model.index(f"{kind}{right}")
                    x[j] = x[k] = 0.5 * (x[j] + x[k])
        for sfx in CORNERS:
            if f"lateral_deflection{sfx}" in names:
                x[model.index(f"lateral_deflection{sfx}")] = 0.0
    return x


def _jacobian(residual, z, r):
    """Central-difference Jacobian of ``residual`` at ``z`` (``r`` = residual(z), for the shape)."""
    J = np.empty((r.size, z.size))
    for j in range(z.size):
        h = 1e-7 * max(abs(z[j]), 1e-3)
        e = np.zeros_like(z)
        e[j] = h
        J[:, j] = (residual(z + e) - residual(z - e)) / (2 * h)
    return J


def _solve(residual, z0, tol):
    """``(z, largest |residual|, message)``: Powell's hybrid method from ``z0``, then, where it ended
    near a root (largest residual below 1e-3), Newton steps on the central-difference Jacobian with
    backtracking (halving the step until the largest residual falls), until the largest residual is
    below tol / 100 or no longer falls by a factor of ten a step."""
    from scipy.optimize import root

    solution = root(residual, z0, method="hybr", options={"xtol": 1e-14, "maxfev": 20000})
    z = solution.x
    r = residual(z)
    worst = float(np.max(np.abs(r)))
    if not np.isfinite(worst):
        return z, float("inf"), solution.message
    for _ in range(8):
        if worst < 0.01 * tol or worst > 1e-3:  # done, or no root near enough for Newton's method
            break
        J = _jacobian(residual, z, r)
        if not np.all(np.isfinite(J)):
            break
        step = np.linalg.lstsq(J, r, rcond=None)[0]
        for _halving in range(12):
            trial = z - step
            r_trial = residual(trial)
            worst_trial = float(np.max(np.abs(r_trial)))
            if worst_trial < worst:
                break
            step = 0.5 * step
        else:  # no step lowers the residual: as good as it gets
            break
        converging = worst_trial < 0.1 * worst
        z, r, worst = trial, r_trial, worst_trial
        if not converging:  # Newton's method near a root cuts the residual by far more
            break
    return z, worst, solution.message
