"""Assembly of the linear ride models from a rigid body, corners and suspension elements.

Every ride model in :mod:`vehdyn.ride` (quarter car, bounce-pitch, full car) is the same mechanical
system in different sizes: a rigid sprung body with one to three coordinates (heave, pitch, roll),
and at each wheel ("corner") a suspension spring and damper, optionally an unsprung mass on a tire
spring and damper, optionally an active force. :class:`RideModel` assembles the mass, damping and
stiffness matrices by virtual work and builds the exact state-space model through
:meth:`vehdyn.LinearModel.from_second_order`.

Sign conventions (all ride models)
----------------------------------
* Vertical displacements are measured **upward** from static equilibrium, as road elevations are
  (ISO 8608). Pitch and roll angles follow SAE J670: pitch positive nose up, roll positive right
  side down. A body point ``x`` ahead of and ``y`` to the right of the sprung CG (SAE x, y) moves
  up by ``z + x theta - y phi`` (small angles).
* ``suspension_travel = z_body - z_wheel`` (positive in extension / rebound); for a corner without
  unsprung mass the wheel is the road.
* ``tire_deflection = z_road - z_wheel`` (positive in compression); ``dynamic_tire_load =
  k_t (z_r - z_u) + c_t (z_r' - z_u')`` [N] is the change of the wheel load from static (positive
  = more load). For a corner with a rigid tire it is the force the suspension passes to the road.
* ``actuator_force`` [N] acts between body and wheel, positive extending the suspension (body up,
  wheel down).

Equations: M q'' + C q' + K q = F_d z_r + F_v z_r' + F_a f (e.g. Gillespie, *Fundamentals of
Vehicle Dynamics*, 1992, ch. 5; Jazar, *Vehicle Dynamics*, 2008, ch. 15; Wong, *Theory of Ground
Vehicles*, 4th ed., 2008, sec. 7.2). A suspension element with stiffness k and damping c acting on
the deflection delta = G q - R z_r adds k G'G to K, c G'G to C, k G'R to F_d and c G'R to F_v.
"""

from __future__ import annotations

import functools
import inspect
from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import LinearModel
from vehdyn.params import Vehicle
from vehdyn.signals import Signal

__all__ = ["RideModel", "Corner"]


def vehicle_or_parameters(model: str, vehicle, parameter_class, example: str):
    """The first argument of a ride model: a :class:`~vehdyn.Vehicle` or its parameter set.

    Anything else (numbers, a dict, None) raises a ParameterError that says how to call the model
    now: ``Model(vehicle, ...)`` or ``Model.from_parameters(...)`` with the numbers.

    Parameters
    ----------
    model : str
        The class name (``"QuarterCar"``).
    vehicle : object
        What the caller passed first.
    parameter_class : type
        The model's :class:`~vehdyn.params.ParameterSet` (``QuarterCarParameters``).
    example : str
        The keywords of ``from_parameters`` to show in the message (``"sprung_mass=..., ..."``).

    Returns
    -------
    Vehicle or ParameterSet
        ``vehicle``, checked.
    """
    if isinstance(vehicle, (Vehicle, parameter_class)):
        return vehicle
    if isinstance(vehicle, dict):
        got = "a dict of parameters"
        hint = f"{model}.from_parameters(**parameters)"
    else:
        got = f"the {type(vehicle).__name__} {vehicle!r}"
        hint = f"{model}.from_parameters({example})"
    raise ParameterError(f"{model}(vehicle, ...) takes a vehdyn Vehicle (e.g. vehdyn.load_vehicle('sedan')) or a "
                         f"{parameter_class.__name__}, got {got}; to build one from numbers call {hint}",
                         key="vehicle", value=vehicle)


def ride_model_constructor(parameter_class, example: str):
    """Decorator of a ride model's ``__init__``: a call that does not fit its signature (the numbers
    given as keywords, the old way, or too many positional arguments) raises a ParameterError that
    says how to call it now, instead of a bare TypeError. The signature stays the wrapped one.

    Parameters
    ----------
    parameter_class : type
        The model's parameter set (``QuarterCarParameters``), named in the message.
    example : str
        The keywords of the model's ``from_parameters`` to show in the message.

    Returns
    -------
    callable
        The decorator.
    """
    def decorate(init):
        signature = inspect.signature(init)

        @functools.wraps(init)
        def checked(self, *args, **kwargs):
            try:
                signature.bind(self, *args, **kwargs)
            except TypeError as exc:
                model = type(self).__name__
                numbers = [key for key in kwargs if key not in signature.parameters]
                what = f"the keyword(s) {', '.join(numbers)}" if numbers else str(exc)
                raise ParameterError(
                    f"{model}(vehicle, ...) takes a vehdyn Vehicle or a {parameter_class.__name__}, got {what}; to "
                    f"build one from numbers call {model}.from_parameters({example})",
                    key=numbers[0] if numbers else "vehicle", value=kwargs[numbers[0]] if numbers else args,
                ) from None
            init(self, *args, **kwargs)

        return checked

    return decorate


@dataclass(frozen=True)
class Corner:
    """One wheel station of a ride model.

    Attributes
    ----------
    suffix : str
        Appended to the corner's signal names (``""``, ``"_front"``, ``"_front_left"``).
    x : float
        Position ahead of the sprung CG [m].
    y : float
        Position to the right of the sprung CG [m] (SAE).
    spring_rate : float
        Suspension (wheel) rate [N/m].
    damping : float
        Suspension damping [N*s/m].
    unsprung_mass : float
        Unsprung mass [kg]; 0 for a rigid tire (the suspension then acts on the road directly).
    tire_stiffness, tire_damping : float
        Tire vertical stiffness [N/m] and damping [N*s/m] (unused when ``unsprung_mass`` is 0).
    track : str
        Road track the corner runs on (``"left"``, ``"right"`` or ``""`` for a single track).
    """

    suffix: str
    x: float
    y: float
    spring_rate: float
    damping: float
    unsprung_mass: float
    tire_stiffness: float
    tire_damping: float
    track: str = ""

    @property
    def has_unsprung_mass(self) -> bool:
        return self.unsprung_mass > 0


_BODY_DOF = {
    "heave": Signal("sprung_displacement", "m", "heave of the sprung mass at its CG (up)"),
    "pitch": Signal("pitch_angle", "rad", "pitch of the sprung mass (SAE: nose up positive)"),
    "roll": Signal("roll_angle", "rad", "roll of the sprung mass (SAE: right side down positive)"),
}
_BODY_VELOCITY = {
    "heave": Signal("sprung_velocity", "m/s", "heave velocity of the sprung mass (up)"),
    "pitch": Signal("pitch_rate", "rad/s", "pitch rate of the sprung mass"),
    "roll": Signal("roll_rate", "rad/s", "roll rate of the sprung mass"),
}
_BODY_ACCELERATION = {
    "heave": Signal("sprung_acceleration", "m/s^2", "vertical acceleration of the sprung mass at its CG (up)"),
    "pitch": Signal("pitch_acceleration", "rad/s^2", "pitch acceleration of the sprung mass"),
    "roll": Signal("roll_acceleration", "rad/s^2", "roll acceleration of the sprung mass"),
}


class RideModel(LinearModel):
    """Base class of the linear ride models (built by :meth:`_assemble`).

    Attributes
    ----------
    corners : tuple of Corner
        The wheel stations, in input order.
    body_dof : tuple of str
        ``"heave"``, ``"pitch"``, ``"roll"`` (those the model has).
    mass_matrix, damping_matrix, stiffness_matrix : ndarray
        M, C, K over the coordinates (body, then unsprung masses).
    parameters : ParameterSet
        The validated parameters the model was built from.
    """

    corners: tuple[Corner, ...] = ()
    body_dof: tuple[str, ...] = ()

    def _assemble(self, *, body_dof, body_mass, corners, antiroll=(), actuators=False, name, phenomena,
                  body_stiffness=None):
        """Build the matrices and initialize the :class:`LinearModel`.

        Parameters
        ----------
        body_dof : sequence of {"heave", "pitch", "roll"}
        body_mass : array_like
            Diagonal of the body's mass matrix [kg, kg*m^2, kg*m^2].
        corners : sequence of Corner
        antiroll : sequence of (left_index, right_index, stiffness [N/m])
            Springs on the difference of the suspension deflections of two corners (anti-roll bars
            in wheel-rate units: a bar of roll stiffness K [N*m/rad] over track t is K / t^2).
        actuators : bool
            Add an ``actuator_force`` input per corner.
        body_stiffness : array_like, optional
            Added to the diagonal of K on the body's coordinates [N/m, N*m/rad, N*m/rad] (gravity's
            moment on a pitched or rolled body whose CG lies above the contact points: negative).
        """
        self.body_dof = tuple(body_dof)
        self.corners = tuple(corners)
        nb = len(body_dof)
        wheels = [i for i, c in enumerate(corners) if c.has_unsprung_mass]
        n = nb + len(wheels)
        nc = len(corners)
        wheel_col = {i: nb + k for k, i in enumerate(wheels)}

        M = np.zeros((n, n))
        M[range(nb), range(nb)] = body_mass
        for i in wheels:
            M[wheel_col[i], wheel_col[i]] = corners[i].unsprung_mass

        # body displacement at each corner: T_i q ; suspension extension: D_i q - s_i z_r
        T = np.zeros((nc, n))
        geometry = {"heave": lambda c: 1.0, "pitch": lambda c: c.x, "roll": lambda c: -c.y}
        for j, dof in enumerate(body_dof):
            T[:, j] = [geometry[dof](c) for c in corners]
        D = T.copy()
        S = np.zeros((nc, nc))  # road terms of the suspension deflection
        for i, c in enumerate(corners):
            if c.has_unsprung_mass:
                D[i, wheel_col[i]] = -1.0
            else:
                S[i, i] = 1.0
        # suspension elements: weights over corners, stiffness, damping
        elements = [(np.eye(nc)[i], c.spring_rate, c.damping) for i, c in enumerate(corners)]
        for left, right, k in antiroll:
            w = np.zeros(nc)
            w[left], w[right] = 1.0, -1.0
            elements.append((w, k, 0.0))
        K = np.zeros((n, n))
        self.body_stiffness = np.zeros(nb) if body_stiffness is None else np.asarray(body_stiffness, dtype=float)
        K[range(nb), range(nb)] = self.body_stiffness
        C = np.zeros((n, n))
        Fd = np.zeros((n, nc))
        Fv = np.zeros((n, nc))
        # force each element puts on each road contact (rigid-tire corners), for the tire loads
        load_q = np.zeros((nc, 2 * n))  # over [q, q']
        load_u = np.zeros((nc, 2 * nc))  # over [z_r, z_r']
        for w, k, c in elements:
            G = w @ D
            R = w @ S
            K += k * np.outer(G, G)
            C += c * np.outer(G, G)
            Fd += k * np.outer(G, R)
            Fv += c * np.outer(G, R)
            # road reaction at a rigid corner i (up, = extra load): -(w_i s_i)(k delta + c delta')
            contact = -(w * np.diag(S))
            load_q += np.outer(contact, np.concatenate([k * G, c * G]))
            load_u += np.outer(contact, np.concatenate([-k * R, -c * R]))
        for i in wheels:
            c = corners[i]
            e = np.zeros(n)
            e[wheel_col[i]] = 1.0
            K += c.tire_stiffness * np.outer(e, e)
            C += c.tire_damping * np.outer(e, e)
            Fd[:, i] += c.tire_stiffness * e
            Fv[:, i] += c.tire_damping * e
            load_q[i] = np.concatenate([-c.tire_stiffness * e, -c.tire_damping * e])
            load_u[i] = 0.0
            load_u[i, i] = c.tire_stiffness
            load_u[i, nc + i] = c.tire_damping
        Fa = D.T.copy() if actuators else np.zeros((n, 0))
        F = np.hstack([Fd, Fv, Fa])

        dof = [_BODY_DOF[d] for d in body_dof] + [
            Signal(f"unsprung_displacement{corners[i].suffix}", "m", "vertical displacement of the wheel (up)")
            for i in wheels
        ]
        velocities = [_BODY_VELOCITY[d] for d in body_dof] + [
            Signal(f"unsprung_velocity{corners[i].suffix}", "m/s", "vertical velocity of the wheel (up)")
            for i in wheels
        ]
        inputs = (
            [Signal(f"road_displacement{c.suffix}", "m", "road elevation under the wheel (up)") for c in corners]
            + [Signal(f"road_velocity{c.suffix}", "m/s", "rate of change of the road elevation under the wheel")
               for c in corners]
            + ([Signal(f"actuator_force{c.suffix}", "N", "active force extending the suspension")
                for c in corners] if actuators else [])
        )
        m_in = len(inputs)
        Minv = np.linalg.inv(M)
        acc_x = np.hstack([-Minv @ K, -Minv @ C])  # q'' over [q, q']
        acc_u = Minv @ F
        Z = np.zeros

        rows_x, rows_u, names = [], [], []

        def add(signal, cx, cu=None):
            names.append(signal)
            rows_x.append(cx)
            rows_u.append(Z(m_in) if cu is None else cu)

        eye = np.eye(2 * n)
        pad_u = lambda v: np.concatenate([v, Z(m_in - v.size)])  # noqa: E731
        for j, d in enumerate(body_dof):
            add(_BODY_DOF[d], eye[j])
        for j, d in enumerate(body_dof):
            add(_BODY_VELOCITY[d], eye[n + j])
        for j, d in enumerate(body_dof):
            add(_BODY_ACCELERATION[d], acc_x[j], acc_u[j])
        if len(body_dof) > 1:
            for i, c in enumerate(corners):
                add(Signal(f"sprung_acceleration{c.suffix}", "m/s^2",
                           "vertical acceleration of the body above the wheel (up)"), T[i] @ acc_x, T[i] @ acc_u)
        for i in wheels:
            j = wheel_col[i]
            sfx = corners[i].suffix
            add(Signal(f"unsprung_displacement{sfx}", "m", "vertical displacement of the wheel (up)"), eye[j])
            add(Signal(f"unsprung_velocity{sfx}", "m/s", "vertical velocity of the wheel (up)"), eye[n + j])
            add(Signal(f"unsprung_acceleration{sfx}", "m/s^2", "vertical acceleration of the wheel (up)"),
                acc_x[j], acc_u[j])
        for i, c in enumerate(corners):
            add(Signal(f"suspension_travel{c.suffix}", "m", "suspension extension z_body - z_wheel (rebound +)"),
                np.concatenate([D[i], Z(n)]), pad_u(-S[i]))
            add(Signal(f"suspension_velocity{c.suffix}", "m/s", "rate of suspension extension"),
                np.concatenate([Z(n), D[i]]), pad_u(np.concatenate([Z(nc), -S[i]])))
        for i in wheels:
            c = corners[i]
            e = np.zeros(n)
            e[wheel_col[i]] = 1.0
            add(Signal(f"tire_deflection{c.suffix}", "m", "tire compression z_road - z_wheel"),
                np.concatenate([-e, Z(n)]), pad_u(np.eye(nc)[i]))
        for i, c in enumerate(corners):
            add(Signal(f"dynamic_tire_load{c.suffix}", "N", "wheel load change from static (more load +)"),
                load_q[i], pad_u(load_u[i]))

        # outputs that are coordinates keep their unique names; drop repeats (states listed twice)
        seen, keep = set(), []
        for k, s in enumerate(names):
            if s.name not in seen:
                seen.add(s.name)
                keep.append(k)
        names = [names[k] for k in keep]
        Cy = np.array([rows_x[k] for k in keep])
        Dy = np.array([rows_u[k] for k in keep])

        built = LinearModel.from_second_order(
            M, C, K, F, dof=dof, velocities=velocities, inputs=inputs, outputs=names,
            output_matrix=Cy, feedthrough=Dy, name=name, phenomena=phenomena,
        )
        LinearModel.__init__(
            self, built.A, built.B, built.C, built.D, states=built.states, inputs=built.inputs,
            outputs=built.outputs, name=name, phenomena=phenomena,
        )
        self.second_order = built.second_order
        self.mass_matrix, self.damping_matrix, self.stiffness_matrix = M, C, K

    # ------------------------------------------------------------------ conveniences
    _actuator_keyword = "actuators"

    def replace(self, **changes) -> "RideModel":
        """The same kind of model with some parameters changed (``qc.replace(damping=2000.0)``).

        Parameters
        ----------
        **changes
            Fields of the model's parameter set, in their units (``damping=2000.0`` [N*s/m]), and
            the actuator option (``actuator`` for the quarter car, ``actuators`` otherwise).

        Returns
        -------
        RideModel
            A new model of the same class and name, its parameters validated again.

        Raises
        ------
        ParameterError
            Naming an unknown field or a value out of its range.
        """
        flag = changes.pop(self._actuator_keyword, self.has_actuators)
        params = self.parameters.replace(**changes)
        return type(self)(params, **{self._actuator_keyword: flag}, name=self.name)

    @property
    def corner_suffixes(self) -> tuple[str, ...]:
        """Suffixes of the corners' signal names, in input order."""
        return tuple(c.suffix for c in self.corners)

    @property
    def has_actuators(self) -> bool:
        """True when the model has ``actuator_force`` inputs."""
        return any(name.startswith("actuator_force") for name in self.input_names)

    def road_input_names(self) -> tuple[tuple[str, str], ...]:
        """The names of the road inputs, per corner.

        Returns
        -------
        tuple of (str, str)
            ``((road_displacement<sfx>, road_velocity<sfx>), ...)`` in corner order.
        """
        return tuple((f"road_displacement{s}", f"road_velocity{s}") for s in self.corner_suffixes)
