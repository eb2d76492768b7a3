"""Steering system: steering wheel, column torsion bar, rack with friction, power assist and the
aligning moment of the front tires fed back through the trail.

One rotational degree of freedom below the torsion bar (the pinion angle theta_p; rack, road
wheels about their kingpins and an assist motor are lumped into the inertia J_p referred to the
pinion) and, when the driver's torque is the input, one above it (the steering-wheel angle
theta_sw, inertia J_sw). The road-wheel steer angle is delta = theta_p / N with N the overall
steering ratio. SAE signs throughout: positive angles and torques steer to the right. Equations
(after Pfeffer & Harrer (eds.), *Steering Handbook*, Springer, 2017, ch. 5 and 7, and Pfeffer et
al., "A steering model for EPS", in the same line of work; Gillespie, *Fundamentals of Vehicle
Dynamics*, 1992, ch. 8, for the aligning moment about the steering axis)::

    T_c  = k_c (theta_sw - theta_p)                         column (torsion-bar) torque
    T_a  = G T_c^3 / (T_c^2 + T_k^2)                        power assist (boost curve)
    T_al = -(t_m + t_p) F_yf / N                           aligning moment at the pinion
    J_p d(omega_p)/dt = T_c + T_a + T_al - c omega_p - T_f tanh(omega_p / omega_f)
    J_sw d(omega_sw)/dt = T_d - T_c                         (driver-torque input only)

* The boost curve is the usual shape of hydraulic and electric power steering: almost no assist
  on centre (slope 0 at T_c = 0, so the on-centre feel is that of a manual rack) rising to a
  constant boost ratio G far from centre (Pfeffer & Harrer 2017, ch. 7: assist characteristic
  over the torsion-bar torque); G = 0 is a manual rack. T_k sets where the assist turns on.
* The aligning moment of the front axle about the steering axes is the axle lateral force F_yf
  times the total trail (caster trail t_m at the ground plus the tires' pneumatic trail t_p),
  turning the wheels back toward straight ahead; it reaches the pinion divided by N (virtual
  work: M delta' = T theta_p').
* Coulomb friction of the rack and gear, T_f sign(omega_p), is regularized as
  T_f tanh(omega_p / omega_f): a smooth law that equals the Coulomb force within 1 % once
  |omega_p| > 2.7 omega_f and behaves as a viscous damper of T_f / omega_f below (stiff: the
  default integrator of :func:`~vehdyn.procedures.weave_test` is implicit). It has no stiction: at
  rest the friction holds no torque, so the model shows the friction's hysteresis in motion, not
  a stick-slip deadband.

With the steering-wheel angle as the input (a steering robot, ``steering_input="angle"``), the
steering-wheel inertia carries no state: the output ``steering_wheel_torque`` is the column torque
T_c (what the robot's torque sensor reads but for J_sw theta_sw'', which at the 0.2-Hz weave is
J_sw (2 pi f)^2 = 0.06 N*m per rad of wheel amplitude: negligible).

:class:`SteeredVehicle` closes the loop with a vehicle model that has the input
``front_steer_angle`` and the output ``front_lateral_force`` (:class:`~vehdyn.handling.LinearBicycle`,
:class:`~vehdyn.handling.SingleTrack`): delta comes from the steering states, F_yf from the
vehicle's outputs, so the loop has no algebraic part.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import Model
from vehdyn.params import ParameterSet, Vehicle
from vehdyn.params.base import parameter
from vehdyn.signals import Signal

__all__ = ["SteeringSystemParameters", "steering_system_parameters", "SteeringSystem", "SteeredVehicle",
           "boost_torque"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class SteeringSystemParameters(ParameterSet):
    """The numbers of :class:`SteeringSystem` (defaults and sources in :class:`vehdyn.params.Steering`)."""

    ratio: float = parameter("-", "overall steering ratio N: steering-wheel angle / road-wheel angle", gt=0)
    steering_wheel_inertia: float = parameter("kg*m^2", "J_sw", gt=0, default=0.04)
    column_stiffness: float = parameter("N*m/rad", "k_c of column and torsion bar", gt=0, default=115.0)
    lower_steering_inertia: float = parameter("kg*m^2", "J_p: rack, wheels and motor referred to the pinion", gt=0,
                                              default=0.05)
    steering_damping: float = parameter("N*m*s/rad", "c, viscous, referred to the pinion", ge=0, default=0.5)
    steering_friction_torque: float = parameter("N*m", "T_f, Coulomb friction referred to the pinion", ge=0,
                                                default=1.0)
    assist_gain: float = parameter("-", "G, boost ratio far from centre (0: manual)", ge=0, default=0.0)
    assist_knee_torque: float = parameter("N*m", "T_k of the boost curve", gt=0, default=1.5)
    caster_trail: float = parameter("m", "t_m, mechanical trail at the ground", default=0.02)
    pneumatic_trail: float = parameter("m", "t_p, pneumatic trail of the front tires", default=0.0)
    friction_velocity: float = parameter("rad/s", "omega_f of the friction regularization", gt=0, default=0.02)

    @property
    def trail(self) -> float:
        """t_m + t_p [m]."""
        return self.caster_trail + self.pneumatic_trail


def _front_pneumatic_trail(vehicle: Vehicle) -> float:
    """-dM_z/dF_y [m] of the vehicle's front tire law at zero slip and half the static axle load."""
    from vehdyn.tire import tire_for_vehicle

    tire = tire_for_vehicle(vehicle, "front")
    load, eps, speed = 0.5 * vehicle.static_axle_loads()[0], 1e-4, 20.0
    plus, minus = tire.forces(load, 0.0, eps, 0.0, speed), tire.forces(load, 0.0, -eps, 0.0, speed)
    dfy = float(np.asarray(plus.fy) - np.asarray(minus.fy))
    mz_plus, mz_minus = getattr(plus, "mz", None), getattr(minus, "mz", None)
    if mz_plus is None or dfy == 0.0:
        return 0.0
    return -float(np.asarray(mz_plus) - np.asarray(mz_minus)) / dfy


def steering_system_parameters(vehicle, **overrides) -> SteeringSystemParameters:
    """The :class:`SteeringSystemParameters` of a Vehicle (its ``steering`` group), with overrides.

    ``vehicle.steering.pneumatic_trail`` left unset (None) is taken from the front tire law:
    -dM_z/dF_y at zero slip and half the static front axle load (0.042 m for the sedan's
    mf_185_80R14.tir).

    Parameters
    ----------
    vehicle : Vehicle or SteeringSystemParameters
        The vehicle (its ``steering`` group and front tire law); a SteeringSystemParameters
        passes through (with the overrides applied).
    **overrides
        Fields of :class:`SteeringSystemParameters` to replace, in their units
        (``steering_friction_torque=0.0`` [N*m], ``assist_gain=2.0`` [-], ...).

    Returns
    -------
    SteeringSystemParameters
        The validated parameters.

    Raises
    ------
    ParameterError
        For another ``vehicle``, or an override that is not a parameter of the steering system.
    """
    if isinstance(vehicle, SteeringSystemParameters):
        return dataclasses.replace(vehicle, **overrides) if overrides else vehicle
    if not isinstance(vehicle, Vehicle):
        raise ParameterError(f"vehicle must be a Vehicle or SteeringSystemParameters, got {type(vehicle).__name__}",
                             key="vehicle", value=vehicle)
    s = vehicle.steering
    values = {f.name: getattr(s, f.name) for f in dataclasses.fields(SteeringSystemParameters)
              if hasattr(s, f.name)}
    if values.get("pneumatic_trail") is None and "pneumatic_trail" not in overrides:
        values["pneumatic_trail"] = _front_pneumatic_trail(vehicle)
    names = [f.name for f in dataclasses.fields(SteeringSystemParameters)]
    unknown = sorted(set(overrides) - set(names))
    if unknown:
        raise ParameterError(f"the steering system has no parameter {unknown[0]!r}; its parameters are {names}",
                             key=unknown[0], value=overrides[unknown[0]])
    values.update(overrides)
    return SteeringSystemParameters(**values)


def boost_torque(column_torque, assist_gain, knee_torque):
    r"""Assist torque of the power-steering boost curve (module docstring).

    .. math::

        T_a = G \frac{T_c^3}{T_c^2 + T_k^2}

    Almost no assist on centre (slope 0 at T_c = 0), the boost ratio G far from it.

    Parameters
    ----------
    column_torque : float or array_like
        Column (torsion-bar) torque T_c [N*m].
    assist_gain : float
        Boost ratio G far from centre [-] (0: a manual rack).
    knee_torque : float
        T_k [N*m], where the assist turns on.

    Returns
    -------
    float or ndarray
        T_a [N*m], with the sign of T_c.
    """
    t = np.asarray(column_torque, dtype=float)
    return assist_gain * t**3 / (t * t + knee_torque * knee_torque)


class SteeringSystem(Model):
    r"""Steering wheel, column, rack with friction and power assist, and the tires' aligning moment.

    Parameters
    ----------
    vehicle : Vehicle or SteeringSystemParameters
        The vehicle (its ``steering`` group and front tire law, see
        :func:`steering_system_parameters`) or the parameters.
    steering_input : {"angle", "torque"}
        ``"angle"`` (default): the steering-wheel angle is an input (a steering robot; the weave
        test); ``"torque"``: the driver's torque is, and the steering wheel has its inertia and
        angle states.
    **overrides
        Fields of :class:`SteeringSystemParameters` (``steering_friction_torque=0.0``, ...).

    Signals
    -------
    states
        ``pinion_angle`` [rad], ``pinion_rate`` [rad/s]; with torque input first
        ``steering_wheel_angle``, ``steering_wheel_rate``.
    inputs
        ``steering_wheel_angle`` [rad] or ``steering_wheel_torque`` [N*m]; ``front_lateral_force`` [N].
    outputs
        ``front_steer_angle`` [rad], ``steering_wheel_torque`` [N*m] (the column torque T_c),
        ``assist_torque``, ``aligning_torque`` (at the pinion) [N*m], ``steering_wheel_angle`` [rad].

    Notes
    -----
    The pinion angle theta_p (rack, road wheels and assist motor lumped into J_p referred to the
    pinion) below the torsion bar and, with the driver's torque T_d as the input, the steering
    wheel's angle theta_sw above it; SAE signs (positive steering right):

    .. math::

        T_c &= k_c (\theta_{sw} - \theta_p), \qquad
        T_a = G \frac{T_c^3}{T_c^2 + T_k^2}, \qquad
        T_{al} = -\frac{(t_m + t_p) F_{yf}}{N}, \\
        J_p \dot\omega_p &= T_c + T_a + T_{al} - c \, \omega_p - T_f \tanh(\omega_p / \omega_f),
        \qquad \dot\theta_p = \omega_p, \\
        J_{sw} \dot\omega_{sw} &= T_d - T_c \quad \text{(torque input only)}, \qquad
        \delta = \theta_p / N

    with N the overall steering ratio, k_c the column stiffness, G and T_k the boost curve, t_m and
    t_p the caster and pneumatic trails, F_yf the front axle's lateral force, c the viscous
    damping and T_f the Coulomb friction regularized within omega_f (no stiction). With the
    steering-wheel angle as the input the wheel's inertia carries no state and the output
    ``steering_wheel_torque`` is T_c.

    References
    ----------
    .. [1] P. Pfeffer and M. Harrer (eds.), *Steering Handbook*, Springer, 2017, ch. 5 (steering
       system models) and ch. 7 (the assist characteristic over the torsion-bar torque).
    .. [2] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 8 (the aligning
       moment about the steering axis: the lateral force times the trail).
    """

    phenomena = frozenset({"steering"})

    def __init__(self, vehicle, *, steering_input: str = "angle", **overrides):
        if steering_input not in ("angle", "torque"):
            raise ParameterError(f"steering_input must be 'angle' or 'torque', got {steering_input!r}",
                                 key="steering_input", value=steering_input)
        self.parameters = steering_system_parameters(vehicle, **overrides)
        self.steering_input = steering_input
        states = [Signal("pinion_angle", "rad", "pinion angle theta_p = N delta (positive steering right)"),
                  Signal("pinion_rate", "rad/s", "pinion angular velocity")]
        if steering_input == "torque":
            states = [Signal("steering_wheel_angle", "rad", "steering-wheel angle theta_sw (positive right)"),
                      Signal("steering_wheel_rate", "rad/s", "steering-wheel angular velocity")] + states
            first = Signal("driver_torque", "N*m", "torque of the driver on the steering wheel (positive right)")
        else:
            first = Signal("steering_wheel_angle", "rad", "steering-wheel angle theta_sw (positive right)")
        self.declare(
            states=states,
            inputs=[first, Signal("front_lateral_force", "N", "lateral force of the front axle (SAE y)")],
            outputs=[Signal("front_steer_angle", "rad", "road-wheel steer angle delta = theta_p / N"),
                     Signal("steering_wheel_torque", "N*m", "column (torsion-bar) torque T_c, positive right"),
                     Signal("assist_torque", "N*m", "power-assist torque T_a at the pinion"),
                     Signal("aligning_torque", "N*m", "aligning moment of the front tires at the pinion"),
                     Signal("steering_wheel_angle", "rad", "steering-wheel angle theta_sw")])

    def _torques(self, x, u):
        p = self.parameters
        if self.steering_input == "torque":
            wheel, wheel_rate, pinion, pinion_rate = x[0], x[1], x[2], x[3]
        else:
            wheel, wheel_rate, pinion, pinion_rate = u[0], None, x[0], x[1]
        column = p.column_stiffness * (wheel - pinion)
        assist = boost_torque(column, p.assist_gain, p.assist_knee_torque)
        aligning = -p.trail * u[1] / p.ratio
        return wheel, wheel_rate, pinion, pinion_rate, column, assist, aligning

    def rhs(self, t, x, u):
        p = self.parameters
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        wheel, wheel_rate, pinion, pinion_rate, column, assist, aligning = self._torques(x, u)
        friction = p.steering_friction_torque * np.tanh(pinion_rate / p.friction_velocity)
        pinion_acc = (column + assist + aligning - p.steering_damping * pinion_rate - friction) / \
            p.lower_steering_inertia
        if self.steering_input == "torque":
            wheel_acc = (u[0] - column) / p.steering_wheel_inertia
            return np.stack(np.broadcast_arrays(wheel_rate, wheel_acc, pinion_rate, pinion_acc))
        return np.stack(np.broadcast_arrays(pinion_rate, pinion_acc))

    def output(self, t, x, u):
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        wheel, _, pinion, _, column, assist, aligning = self._torques(x, u)
        return np.stack(np.broadcast_arrays(pinion / self.parameters.ratio, column, assist, aligning, wheel))

    def __repr__(self) -> str:
        p = self.parameters
        return (f"<SteeringSystem ({self.steering_input} input): N={p.ratio:g}, k_c={p.column_stiffness:g} N*m/rad, "
                f"T_f={p.steering_friction_torque:g} N*m, G={p.assist_gain:g}, trail={p.trail:.4g} m>")


class SteeredVehicle(Model):
    r"""A vehicle model steered through a :class:`SteeringSystem`: the loop closed.

    Parameters
    ----------
    vehicle_model : Model
        Has the input ``front_steer_angle`` and the output ``front_lateral_force``
        (LinearBicycle, SingleTrack, ...).
    steering : SteeringSystem
        The steering (its first input, the steering-wheel angle or the driver's torque, becomes
        this model's first input).

    Notes
    -----
    The road-wheel angle comes from the steering's pinion state, the aligning moment from the
    vehicle's front axle force; the vehicle's other inputs u_v pass through:

    .. math::

        \dot x_v = f_v(x_v, [\theta_p / N, u_v]), \qquad
        \dot x_s = f_s(x_s, [u_0, F_{yf}(x_v, \theta_p / N, u_v)])

    (x_v, f_v the vehicle's states and equations, x_s, f_s the steering's, u_0 the steering
    wheel's angle or torque). F_yf depends on the states, not on the steering's outputs, so the
    loop has no algebraic part.

    References
    ----------
    .. [1] P. Pfeffer and M. Harrer (eds.), *Steering Handbook*, Springer, 2017, ch. 5.
    .. [2] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 8.

    Signals
    -------
    The vehicle's states then the steering's; inputs: the steering's first input
    (``steering_wheel_angle`` or ``driver_torque``) then the vehicle's other inputs; outputs: the
    vehicle's, then the steering's (``front_steer_angle`` once, from the steering).
    """

    def __init__(self, vehicle_model: Model, steering: SteeringSystem):
        if not isinstance(steering, SteeringSystem):
            raise ParameterError(f"steering must be a SteeringSystem, got {type(steering).__name__}", key="steering",
                                 value=steering)
        if "front_steer_angle" not in vehicle_model.input_names or \
                "front_lateral_force" not in vehicle_model.output_names:
            raise ParameterError(f"{type(vehicle_model).__name__} needs the input front_steer_angle and the output "
                                 "front_lateral_force to be steered", key="vehicle_model",
                                 value=type(vehicle_model).__name__)
        self.vehicle_model, self.steering = vehicle_model, steering
        vm = vehicle_model
        self._i_steer = vm.index("front_steer_angle", "inputs")
        self._i_force = vm.index("front_lateral_force", "outputs")
        self._passed = [k for k, n in enumerate(vm.input_names) if n != "front_steer_angle"]
        self._nv = vm.n_states
        keep_out = [k for k, n in enumerate(steering.output_names) if n not in vm.output_names]
        self._steer_out = keep_out
        steer_outputs = tuple(steering.outputs[k] for k in keep_out)
        self.declare(states=tuple(vm.states) + tuple(steering.states),
                     inputs=(steering.inputs[0],) + tuple(vm.inputs[k] for k in self._passed),
                     outputs=tuple(vm.output_signals) + steer_outputs)
        self.phenomena = frozenset(vm.phenomena) | steering.phenomena
        self.name = f"{getattr(vm, 'name', type(vm).__name__)} with steering system"

    def _split(self, t, x, u):
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        xv, xs = x[:self._nv], x[self._nv:]
        steer = self.steering
        p = steer.parameters
        pinion = xs[steer.index("pinion_angle")]
        uv = np.zeros((self.vehicle_model.n_inputs,) + np.shape(x)[1:])
        if self._passed:
            uv[self._passed] = u[1:]
        uv[self._i_steer] = pinion / p.ratio
        yv = np.asarray(self.vehicle_model.output(t, xv, uv), dtype=float)
        us = np.stack(np.broadcast_arrays(u[0], yv[self._i_force]))
        return xv, xs, uv, yv, us

    def rhs(self, t, x, u):
        xv, xs, uv, _, us = self._split(t, x, u)
        return np.concatenate([np.asarray(self.vehicle_model.rhs(t, xv, uv), dtype=float),
                               np.asarray(self.steering.rhs(t, xs, us), dtype=float)])

    def output(self, t, x, u):
        xv, xs, uv, yv, us = self._split(t, x, u)
        ys = np.asarray(self.steering.output(t, xs, us), dtype=float)
        return np.concatenate([yv, ys[self._steer_out]])
