"""Linear single-track (bicycle) model: lateral velocity and yaw rate at constant speed.

Equations (SAE J670 vehicle axes: x forward, y right, z down; a positive steer angle turns the
vehicle to the right)::

    m (dv/dt + u r) = F_yf + F_yr
    I_z dr/dt       = a F_yf - b F_yr

    F_yf = -C_f alpha_f,   alpha_f = (v + a r) / u - delta_f
    F_yr = -C_r alpha_r,   alpha_r = (v - b r) / u - delta_r

with u the forward speed [m/s], v the lateral velocity [m/s], r the yaw rate [rad/s], a and b the
distances from the centre of gravity (CG) to the front and rear axles [m], C_f and C_r the
cornering stiffnesses of the front and rear AXLES (both tires, positive, [N/rad]) and alpha the
SAE slip angles (atan of lateral over longitudinal contact velocity, linearized), as defined in
:mod:`vehdyn.conventions`. References: Gillespie, *Fundamentals of Vehicle Dynamics*, 1992,
sec. 6 (eq. 6-15 to 6-24); Abe, *Vehicle Handling Dynamics*, 2009, sec. 3.2 (eq. 3.11-3.12, where
K_f, K_r are per tire so that 2 K = C); Rajamani, *Vehicle Dynamics and Control*, 2nd ed., 2012,
sec. 2.3 (eq. 2.31, per tire too). The sign of the slip angle differs from Gillespie's (who uses
the angle of the wheel relative to the velocity); the forces are the same.

Outputs are linear in the states and inputs: ``lateral_acceleration`` a_y = dv/dt + u r (of the CG,
in the vehicle frame), ``sideslip_angle`` beta = v/u, ``path_curvature`` a_y/u^2 = r/u + (d beta/dt)/u
(of the CG path), the slip angles and the axle lateral forces.

Minimum speed. The linear models take u >= :data:`LINEAR_MIN_SPEED` (0.01 m/s). At low speed the
slip angles are small differences of O(delta) terms, (v + a r)/u - delta with v -> u b delta / L, so
a_y = (F_yf + F_yr)/m carries a rounding error of about eps (C_f + C_r) (b/L) delta / m, and
path_curvature = a_y/u^2 that error divided by u^2: relative to the steady curvature delta/L, about
eps (C_f + C_r) b / (m u^2). This is the conditioning of the output (d(curvature)/dv =
-(C_f + C_r)/(m u^3)), not of a formula: r/u + (d beta/dt)/u, computed from the same states,
cancels the same way. For a passenger car the error is 4e-10 of the
steady-state curvature at 0.01 m/s, 4e-6 at 1e-4 m/s, 3 % at 1e-6 m/s; below walking pace the
linear slip-angle tire is no model of a tire anyway (use :class:`~vehdyn.handling.SingleTrack`,
which runs through standstill).

Compliance steer (from the vehicle file's ``suspension.*_compliance_steer`` fields, through
:func:`bicycle_parameters`): each axle steers by delta_c = c F_y, c = c_i - e_i t_i the net
road-wheel steer per unit axle force of the lateral-force and aligning-moment compliances
(:meth:`vehdyn.params.Suspension.compliance_steer`, t_i the pneumatic trail), quasi-statically::

    F_yi = -C_i (alpha_i - c_i F_yi)   ->   F_yi = -C_i,eff alpha_i,   C_i,eff = C_i / (1 - c_i C_i)

so the matrices, transfer functions and understeer gradient are the rigid ones with C_eff
(Gillespie 1992, ch. 6, Table 6.1: the understeer terms -c_f W_f + c_r W_r). With tire lag the
relaxation acts on the slip the tire sees: (sigma/u) d(alpha')/dt + alpha' = alpha + c C alpha'.

Crosswind (optional, ``crosswind=True``: input ``wind_velocity_lateral`` w [m/s], the air's velocity
along y, positive toward the right): the aerodynamic side force of :mod:`vehdyn.handling.crosswind`
linearized about w = 0, F_w = k_w u w with k_w = 0.5 rho A C_Y', acts at the centre of pressure x_p
ahead of the CG::

    m (dv/dt + u r) = F_yf + F_yr + k_w u w,    I_z dr/dt = a F_yf - b F_yr + x_p k_w u w

(an input column only: the aerodynamic sideslip of the vehicle's own motion is neglected, see
:mod:`vehdyn.handling.crosswind`).

Tire lag (optional). With a relaxation length sigma > 0 on an axle, the force follows the transient
slip angle alpha', a named state, through the first-order law (Pacejka, *Tire and Vehicle
Dynamics*, 3rd ed., 2012, sec. 7.1.2, eq. 7.12 linearized; Rill, *Road Vehicle Dynamics*, 2012,
sec. 3.10)::

    (sigma / u) d(alpha')/dt + alpha' = alpha    ->    F_y = -C alpha'

so that the axle force lags the kinematic slip angle by the time constant sigma/u.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import LinearModel
from vehdyn.model import float_array
from vehdyn.params import ParameterSet, Vehicle
from vehdyn.params.base import parameter
from vehdyn.signals import STEER_INPUTS, Signal
from vehdyn.handling.crosswind import optional_wind_input

__all__ = ["BicycleParameters", "LinearBicycle", "bicycle_parameters", "vehicle_compliance_steer", "LINEAR_MIN_SPEED"]

LINEAR_MIN_SPEED = 0.01
"""Lowest forward speed [m/s] of the linear handling models (LinearBicycle, LateralYawRoll); see the
module docstring, "Minimum speed"."""

_STATE_SIGNALS = (
    Signal("lateral_velocity", "m/s", "body-frame lateral velocity v of the CG (right, SAE)"),
    Signal("yaw_rate", "rad/s", "yaw rate r (positive turning right, SAE)"),
)
_LAG_SIGNALS = {
    "front": Signal("front_transient_slip_angle", "rad",
                    "front-axle transient slip angle alpha' of the relaxation-length law (SAE)"),
    "rear": Signal("rear_transient_slip_angle", "rad",
                   "rear-axle transient slip angle alpha' of the relaxation-length law (SAE)"),
}
_INPUT_SIGNALS = STEER_INPUTS
_OUTPUT_SIGNALS = (
    Signal("lateral_acceleration", "m/s^2", "lateral acceleration of the CG, dv/dt + u r (right, SAE)"),
    Signal("sideslip_angle", "rad", "vehicle sideslip angle at the CG, beta = v / u"),
    Signal("yaw_rate", "rad/s", "yaw rate r (positive turning right, SAE)"),
    Signal("lateral_velocity", "m/s", "body-frame lateral velocity v of the CG"),
    Signal("front_slip_angle", "rad", "front-axle kinematic slip angle (v + a r)/u - delta_f (SAE)"),
    Signal("rear_slip_angle", "rad", "rear-axle kinematic slip angle (v - b r)/u - delta_r (SAE)"),
    Signal("path_curvature", "1/m", "curvature of the CG path, a_y / u^2 (positive turning right)"),
    Signal("front_lateral_force", "N", "lateral force of the front axle (both tires, SAE y)"),
    Signal("rear_lateral_force", "N", "lateral force of the rear axle (both tires, SAE y)"),
)


@dataclasses.dataclass(frozen=True, kw_only=True)
class BicycleParameters(ParameterSet):
    """The classical parameters of the single-track model (axle cornering stiffnesses).

    Build from textbook numbers directly, or from a :class:`~vehdyn.Vehicle` with
    :func:`bicycle_parameters`. Textbooks that print cornering stiffness PER TIRE (Abe, Rajamani,
    Wong) need it doubled here.
    """

    mass: float = parameter("kg", "total vehicle mass m", gt=0)
    yaw_inertia: float = parameter("kg*m^2", "yaw moment of inertia I_z about the CG", gt=0)
    a: float = parameter("m", "CG to front axle", gt=0)
    b: float = parameter("m", "CG to rear axle", gt=0)
    front_cornering_stiffness: float = parameter("N/rad", "front AXLE cornering stiffness C_f (both tires)", gt=0)
    rear_cornering_stiffness: float = parameter("N/rad", "rear AXLE cornering stiffness C_r (both tires)", gt=0)
    front_relaxation_length: float = parameter("m", "front tire lateral relaxation length (0: no lag)",
                                               ge=0, default=0.0)
    rear_relaxation_length: float = parameter("m", "rear tire lateral relaxation length (0: no lag)",
                                              ge=0, default=0.0)
    wind_side_force_factor: float = parameter("kg/m", "k_w = 0.5 rho A C_Y' of the crosswind side force (0: no wind)",
                                              ge=0, default=0.0)
    centre_of_pressure: float = parameter("m", "aerodynamic centre of pressure x_p ahead of the CG (negative: behind)",
                                          default=0.0)
    front_compliance_steer: float = parameter(
        "rad/N", "net front road-wheel compliance steer per unit front axle force, c_f - e_f t_f (lateral-force "
        "and aligning-moment compliance, :meth:`vehdyn.params.Suspension.compliance_steer`; SAE, positive "
        "steering with the force; 0: rigid)", default=0.0)
    rear_compliance_steer: float = parameter(
        "rad/N", "net rear road-wheel compliance steer per unit rear axle force, c_r - e_r t_r (0: rigid)",
        default=0.0)

    def check(self):
        for axle in ("front", "rear"):
            c = getattr(self, f"{axle}_compliance_steer")
            C = getattr(self, f"{axle}_cornering_stiffness")
            if 1.0 - c * C <= 0.0:
                raise ParameterError(
                    f"{axle}_compliance_steer = {c:.6g} rad/N with {axle}_cornering_stiffness = {C:.6g} N/rad makes "
                    f"1 - c C = {1.0 - c * C:.6g} <= 0: the axle's force steers it further than its slip "
                    f"(no effective cornering stiffness)", key=f"{axle}_compliance_steer", value=c)

    @property
    def wheelbase(self) -> float:
        """L = a + b [m]."""
        return self.a + self.b

    @property
    def effective_cornering_stiffnesses(self) -> tuple[float, float]:
        r"""(front, rear) axle cornering stiffness with the compliance steer, C / (1 - c C) [N/rad].

        The compliance steer delta_c = c F_y (quasi-static) takes c F_y off the slip the tire sees,
        F_y = -C (alpha_kin - c F_y), so that

        .. math::

            F_y = -\frac{C}{1 - c C} \alpha_{kin}

        (Gillespie, *Fundamentals of Vehicle Dynamics*, 1992, ch. 6, compliance steer).
        """
        return (self.front_cornering_stiffness / (1.0 - self.front_compliance_steer * self.front_cornering_stiffness),
                self.rear_cornering_stiffness / (1.0 - self.rear_compliance_steer * self.rear_cornering_stiffness))

    @property
    def understeer_gradient(self) -> float:
        """K = (m / L) (b / C_f,eff - a / C_r,eff) [rad/(m/s^2)] (Gillespie eq. 6-15 with W = m g b / L; the
        effective stiffnesses with the compliance steer, :attr:`effective_cornering_stiffnesses`)."""
        cf, cr = self.effective_cornering_stiffnesses
        return self.mass / self.wheelbase * (self.b / cf - self.a / cr)


def bicycle_parameters(vehicle_or_model) -> BicycleParameters:
    """The :class:`BicycleParameters` of a Vehicle, a LinearBicycle or a BicycleParameters.

    Parameters
    ----------
    vehicle_or_model : Vehicle, LinearBicycle or BicycleParameters
        For a Vehicle the total mass and yaw inertia (``vehicle.mass``, whole vehicle), the total
        CG's distances to the axles (``vehicle.geometry``), the AXLE cornering stiffnesses and
        relaxation lengths (``vehicle.tires``) and the crosswind numbers (``vehicle.aero``, see
        :mod:`vehdyn.handling.crosswind`); a model (anything with a ``bicycle_parameters``
        attribute, such as :class:`LinearBicycle`) gives its own; a BicycleParameters passes through.

    Returns
    -------
    BicycleParameters
        The validated parameters.

    Raises
    ------
    ParameterError
        For any other argument (``key="vehicle"``).
    """
    if isinstance(vehicle_or_model, BicycleParameters):
        return vehicle_or_model
    params = getattr(vehicle_or_model, "bicycle_parameters", None)
    if isinstance(params, BicycleParameters):
        return params
    if isinstance(vehicle_or_model, Vehicle):
        from vehdyn.components.aero import centre_of_pressure_ahead_of_cg, wind_side_force_factor

        v = vehicle_or_model
        compliance = vehicle_compliance_steer(v)
        return BicycleParameters(
            mass=v.mass.mass,
            yaw_inertia=v.mass.yaw_inertia,
            a=v.geometry.cg_to_front_axle,
            b=v.geometry.cg_to_rear_axle,
            front_cornering_stiffness=v.tires.front_cornering_stiffness,
            rear_cornering_stiffness=v.tires.rear_cornering_stiffness,
            front_relaxation_length=v.tires.front_relaxation_length,
            rear_relaxation_length=v.tires.rear_relaxation_length,
            wind_side_force_factor=wind_side_force_factor(v),
            centre_of_pressure=centre_of_pressure_ahead_of_cg(v),
            front_compliance_steer=compliance[0], rear_compliance_steer=compliance[1],
        )
    raise ParameterError(
        f"expected a Vehicle, a LinearBicycle or BicycleParameters, got {type(vehicle_or_model).__name__}",
        key="vehicle", value=vehicle_or_model)


def vehicle_compliance_steer(vehicle, trails=None) -> tuple[float, float]:
    """(front, rear) net compliance steer c_i - e_i t_i [rad/N] of a Vehicle, checked against its cornering stiffness.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle (``suspension.*_compliance_steer``, ``tires.*_cornering_stiffness``).
    trails : tuple of float, optional
        (front, rear) pneumatic trails t_i [m]; default from the vehicle's tire law where an
        aligning-moment compliance is set (:func:`vehdyn.handling.axle_tires.pneumatic_trail`).

    Returns
    -------
    tuple of float
        (c_f - e_f t_f, c_r - e_r t_r) [rad/N].

    Raises
    ------
    ParameterError
        Naming ``suspension.<axle>_lateral_force_compliance_steer`` when 1 - (c - e t) C <= 0 (the
        compliance loop has no stable solution: no effective cornering stiffness).
    """
    from vehdyn.handling.axle_tires import pneumatic_trail

    s, out = vehicle.suspension, []
    for k, axle in enumerate(("front", "rear")):
        e = getattr(s, f"{axle}_aligning_moment_compliance_steer")
        t = trails[k] if trails is not None else (pneumatic_trail(vehicle, axle) if e != 0.0 else 0.0)
        c = s.compliance_steer(axle, t)
        C = getattr(vehicle.tires, f"{axle}_cornering_stiffness")
        if 1.0 - c * C <= 0.0:
            key = f"suspension.{axle}_lateral_force_compliance_steer"
            raise ParameterError(f"{key} = {getattr(s, f'{axle}_lateral_force_compliance_steer'):.6g} rad/N (with "
                                 f"{axle}_aligning_moment_compliance_steer = {e:.6g} rad/(N*m), trail {t:.4g} m) "
                                 f"and tires.{axle}_cornering_stiffness = {C:.6g} N/rad make 1 - (c - e t) C = "
                                 f"{1.0 - c * C:.6g} <= 0: the axle's force steers it further than its slip (no "
                                 f"effective cornering stiffness)", key=key,
                                 value=getattr(s, f"{axle}_lateral_force_compliance_steer"))
        out.append(float(c))
    return out[0], out[1]


def check_speed(speed, *, allow_zero: bool = False, name: str = "speed") -> np.ndarray:
    """``speed`` [m/s] as a float array, checked numeric, finite and positive (or >= 0)."""
    s = float_array(speed, name)
    bad = ~np.isfinite(s) | ((s < 0) if allow_zero else (s <= 0))
    if np.any(bad):
        value = s[bad].flat[0] if s.ndim else float(s)
        word = "non-negative" if allow_zero else "positive"
        raise ParameterError(f"{name} must be finite and {word} [m/s], got {value!r}", key=name, value=value)
    return s


def linear_model_speed(speed, model: str) -> float:
    """The one forward speed [m/s] of a linear handling model: a number >= LINEAR_MIN_SPEED.

    A linear model is one set of matrices at one speed; an array of speeds is refused with a
    ParameterError that names ``speed`` and says what to use instead.
    """
    s = check_speed(speed)
    if s.size != 1:
        raise ParameterError(f"speed must be one number [m/s]: a {model} is one linear model at one speed, got an "
                             f"array of shape {s.shape} ({speed!r}); build one model per speed (model.at_speed(u)), "
                             "or vehdyn.handling.steady_state_gains / yaw_mode, which take speed arrays",
                             key="speed", value=speed)
    u = float(s.reshape(()))
    if u < LINEAR_MIN_SPEED:
        raise ParameterError(f"speed {u!r} m/s is below the {LINEAR_MIN_SPEED} m/s minimum of the linear handling "
                             "models (their path curvature a_y/u^2 loses its digits as 1/u^2; see "
                             "vehdyn.handling.bicycle); use SingleTrack at and through standstill",
                             key="speed", value=u)
    return u


def speed_of(model, speed=None, *, allow_zero: bool = False) -> np.ndarray:
    """``speed`` [m/s] checked, or the model's own ``speed`` when ``speed`` is None."""
    if speed is None:
        speed = getattr(model, "speed", None)
        if speed is None:
            raise ParameterError(f"a speed [m/s] is needed with a {type(model).__name__} (give speed=...)",
                                 key="speed", value=None)
    return check_speed(speed, allow_zero=allow_zero)


class LinearBicycle(LinearModel):
    r"""2-DOF lateral/yaw single-track (bicycle) model at constant forward speed, an exact LinearModel.

    Parameters
    ----------
    vehicle : Vehicle or BicycleParameters
        Mass, yaw inertia, axle positions and axle cornering stiffnesses (see
        :func:`bicycle_parameters`).
    speed : float
        Constant forward speed u [m/s], >= :data:`LINEAR_MIN_SPEED` (0.01 m/s, see the module
        docstring); one number (a ParameterError names an array).
    tire_lag : bool
        Add first-order tire lag on each axle whose relaxation length is positive (states
        ``front_transient_slip_angle``, ``rear_transient_slip_angle``), with the relaxation lengths of
        ``vehicle.tires``. Default False (the classical 2-DOF model).
    crosswind : bool
        Add the input ``wind_velocity_lateral`` [m/s] (module docstring), with the side-force factor
        and centre of pressure of the parameters (for a Vehicle: ``vehicle.aero``). Default False.

    Attributes
    ----------
    bicycle_parameters : BicycleParameters
    speed : float
        [m/s].

    Notes
    -----
    SAE J670 axes (x forward, y right, z down): u the forward speed, v the lateral velocity of the
    CG, r the yaw rate, delta_f and delta_r the front and rear road-wheel steer angles (positive
    steering right), C_f and C_r the AXLE cornering stiffnesses (both tires, positive), a and b
    the CG's distances to the axles, alpha the SAE slip angles (linearized):

    .. math::

        m (\dot v + u r) &= F_{yf} + F_{yr} + k_w u w, \qquad
        I_z \dot r = a F_{yf} - b F_{yr} + x_p k_w u w, \\
        F_{yf} &= -C_f \alpha_f, \qquad \alpha_f = \frac{v + a r}{u} - \delta_f, \qquad
        F_{yr} = -C_r \alpha_r, \qquad \alpha_r = \frac{v - b r}{u} - \delta_r

    The wind term (``crosswind=True``) is the side force 0.5 rho A C_Y' u w of a lateral wind w
    linearized about w = 0, at the centre of pressure x_p ahead of the CG. With tire lag
    (``tire_lag=True``, relaxation length sigma > 0) the axle's force follows the transient slip
    angle alpha', a state:

    .. math::

        \frac{\sigma}{u} \dot\alpha' + \alpha' = \alpha, \qquad F_y = -C \alpha'

    Outputs are linear in the states and inputs: a_y = dv/dt + u r, beta = v / u, the path
    curvature a_y / u^2, the slip angles and the axle forces. The model takes u >=
    :data:`LINEAR_MIN_SPEED`: below it the path curvature loses its digits as 1/u^2 (module
    docstring, "Minimum speed").

    States ``lateral_velocity`` [m/s], ``yaw_rate`` [rad/s] (then the transient slip angles);
    inputs ``front_steer_angle``, ``rear_steer_angle`` (road-wheel angles [rad]; with
    ``crosswind=True`` also ``wind_velocity_lateral`` [m/s], toward +y); outputs
    ``lateral_acceleration``, ``sideslip_angle``, ``yaw_rate``, ``lateral_velocity``,
    ``front_slip_angle``, ``rear_slip_angle``, ``path_curvature``, ``front_lateral_force``,
    ``rear_lateral_force``. SAE signs: a positive front steer gives a positive yaw rate and a
    positive lateral acceleration.

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 6 (the cornering
       equations, eq. 6-15 to 6-24). Gillespie's slip angle is the wheel's angle to its velocity,
       the opposite sign of the SAE slip angle used here; the forces are the same.
    .. [2] M. Abe, *Vehicle Handling Dynamics*, Butterworth-Heinemann, 2009, sec. 3.2
       (eq. 3.11-3.12; K_f, K_r there are per tire: C = 2 K).
    .. [3] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, sec. 2.3
       (eq. 2.31; cornering stiffness per tire).
    .. [4] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 1.3 (the two-degree-of-freedom model and its stability) and sec. 7.1.2 (eq. 7.12, the
       relaxation-length law, linearized here).
    .. [5] W. F. Milliken and D. L. Milliken, *Race Car Vehicle Dynamics*, SAE, 1995, ch. 5.
    .. [6] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, ch. 5 (handling
       characteristics of road vehicles).

    Examples
    --------
    The yaw-rate gain of a textbook car at 20 m/s, per radian of road-wheel steer:

    >>> import vehdyn
    >>> from vehdyn.handling import LinearBicycle
    >>> car = LinearBicycle.from_parameters(mass=1500, yaw_inertia=2500, a=1.1, b=1.6,
    ...     front_cornering_stiffness=110e3, rear_cornering_stiffness=120e3, speed=20.0)
    >>> round(float(car.dc_gain()[car.index("yaw_rate", "outputs"), 0]), 4)
    5.1344

    A shipped vehicle, its yaw mode at 30 m/s:

    >>> sedan = LinearBicycle(vehdyn.load_vehicle("sedan"), 30.0)
    >>> sedan.state_names
    ('lateral_velocity', 'yaw_rate')
    >>> bool(sedan.is_stable())
    True
    """

    phenomena = frozenset({"lateral", "yaw"})

    def __init__(self, vehicle, speed: float, *, tire_lag: bool = False, crosswind: bool = False):
        params = bicycle_parameters(vehicle)
        u = linear_model_speed(speed, "LinearBicycle")
        if not tire_lag:
            params = dataclasses.replace(params, front_relaxation_length=0.0, rear_relaxation_length=0.0)
        self.bicycle_parameters = params
        self.speed = u
        A, B, C, D, states = _state_space(params, u)
        phenomena = {"lateral", "yaw"} | ({"tire_lag"} if len(states) > 2 else set())
        B, D, inputs, phenomena = optional_wind_input(crosswind, B, D, _INPUT_SIGNALS, phenomena)
        super().__init__(A, B, C, D, states=states, inputs=inputs, outputs=_OUTPUT_SIGNALS,
                         name=f"LinearBicycle at {u:g} m/s", phenomena=phenomena)

    @classmethod
    def from_parameters(cls, *, mass: float, yaw_inertia: float, a: float, b: float,
                        front_cornering_stiffness: float, rear_cornering_stiffness: float, speed: float,
                        front_relaxation_length: float = 0.0, rear_relaxation_length: float = 0.0,
                        wind_side_force_factor: float = 0.0, centre_of_pressure: float = 0.0
                        ) -> "LinearBicycle":
        """A bicycle model from the classical numbers of a textbook problem.

        Parameters
        ----------
        mass : float
            Total mass m [kg].
        yaw_inertia : float
            I_z [kg*m^2].
        a, b : float
            CG to front and rear axle [m].
        front_cornering_stiffness, rear_cornering_stiffness : float
            AXLE cornering stiffnesses (both tires), positive [N/rad].
        speed : float
            Forward speed [m/s].
        front_relaxation_length, rear_relaxation_length : float, optional
            Relaxation lengths [m]; a positive value adds that axle's tire-lag state.
        wind_side_force_factor : float, optional
            k_w = 0.5 rho A C_Y' [kg/m]; a positive value adds the crosswind input
            ``wind_velocity_lateral``.
        centre_of_pressure : float, optional
            x_p [m], the aerodynamic centre of pressure ahead of the CG.

        Returns
        -------
        LinearBicycle
            With tire lag where a relaxation length is positive and the crosswind input where
            ``wind_side_force_factor`` is.
        """
        params = BicycleParameters(mass=mass, yaw_inertia=yaw_inertia, a=a, b=b,
                                   front_cornering_stiffness=front_cornering_stiffness,
                                   rear_cornering_stiffness=rear_cornering_stiffness,
                                   front_relaxation_length=front_relaxation_length,
                                   rear_relaxation_length=rear_relaxation_length,
                                   wind_side_force_factor=wind_side_force_factor,
                                   centre_of_pressure=centre_of_pressure)
        lag = front_relaxation_length > 0 or rear_relaxation_length > 0
        return cls(params, speed, tire_lag=lag, crosswind=wind_side_force_factor > 0)

    def at_speed(self, speed: float) -> "LinearBicycle":
        """The same vehicle at another forward speed.

        Parameters
        ----------
        speed : float
            Forward speed u [m/s], >= :data:`LINEAR_MIN_SPEED`.

        Returns
        -------
        LinearBicycle
            The same parameters, tire lag and crosswind input at ``speed``.
        """
        p = self.bicycle_parameters
        return type(self)(p, speed, tire_lag=p.front_relaxation_length > 0 or p.rear_relaxation_length > 0,
                          crosswind="wind_velocity_lateral" in self.input_names)

    @property
    def wheelbase(self) -> float:
        """L = a + b [m]."""
        return self.bicycle_parameters.wheelbase

    def __repr__(self) -> str:
        p = self.bicycle_parameters
        return (f"<LinearBicycle at {self.speed:g} m/s: m={p.mass:g} kg, I_z={p.yaw_inertia:g} kg*m^2, "
                f"a={p.a:g} m, b={p.b:g} m, C_f={p.front_cornering_stiffness:g} N/rad, "
                f"C_r={p.rear_cornering_stiffness:g} N/rad, states {list(self.state_names)}>")


def _state_space(p: BicycleParameters, u: float):
    """Exact (A, B, C, D) and the state signals of the bicycle model at speed ``u``."""
    m, iz, a, b = p.mass, p.yaw_inertia, p.a, p.b
    cf, cr = p.front_cornering_stiffness, p.rear_cornering_stiffness
    lag = {"front": p.front_relaxation_length, "rear": p.rear_relaxation_length}
    lagged = [axle for axle in ("front", "rear") if lag[axle] > 0]
    states = _STATE_SIGNALS + tuple(_LAG_SIGNALS[axle] for axle in lagged)
    n = len(states)
    # kinematic slip angles alpha = S x + T delta over the states [v, r, ...] and inputs [df, dr]
    S = np.zeros((2, n))
    S[0, :2] = [1.0 / u, a / u]
    S[1, :2] = [1.0 / u, -b / u]
    T = -np.eye(2)
    # axle forces F = -C alpha_force, alpha_force = kinematic slip, or the transient slip state
    # compliance steer: the tire sees alpha_kin - c F; without lag F = -C_eff alpha_kin,
    # C_eff = C / (1 - c C); with lag the transient slip relaxes to alpha_kin + c C alpha'
    compliance = np.array([p.front_compliance_steer, p.rear_compliance_steer])
    stiff = np.array(p.effective_cornering_stiffnesses)
    stiff_lag = np.array([cf, cr])
    F_x = -stiff[:, None] * S
    F_u = -stiff[:, None] * T
    for k, axle in enumerate(lagged):
        row = 0 if axle == "front" else 1
        F_x[row] = 0.0
        F_x[row, 2 + k] = -stiff_lag[row]
        F_u[row] = 0.0
    # m (v' + u r) = Ff + Fr + Fw ;  Iz r' = a Ff - b Fr + x_p Fw,  Fw = k_w u w (crosswind)
    lever = np.array([[1.0 / m, 1.0 / m], [a / iz, -b / iz]])
    A = np.zeros((n, n))
    B = np.zeros((n, 3))
    A[:2] = lever @ F_x
    A[0, 1] -= u
    B[:2, :2] = lever @ F_u
    wind = p.wind_side_force_factor * u
    B[:2, 2] = [wind / m, p.centre_of_pressure * wind / iz]
    # transient slip: d(alpha')/dt = (u / sigma) (alpha - alpha')
    for k, axle in enumerate(lagged):
        row = 0 if axle == "front" else 1
        rate = u / lag[axle]
        A[2 + k] = rate * S[row]
        A[2 + k, 2 + k] -= rate * (1.0 - compliance[row] * stiff_lag[row])
        B[2 + k, :2] = rate * T[row]
    # outputs: a_y = v' + u r, beta, r, v, alpha_f, alpha_r, curvature, Ff, Fr
    ay_x = A[0].copy()
    ay_x[1] += u
    ay_u = B[0]
    C = np.vstack([ay_x, np.eye(n)[0] / u, np.eye(n)[1], np.eye(n)[0], S[0], S[1], ay_x / u**2, F_x[0], F_x[1]])
    # the slips and axle forces do not see the wind directly (zero third column)
    T3, F_u3 = np.hstack([T, np.zeros((2, 1))]), np.hstack([F_u, np.zeros((2, 1))])
    D = np.vstack([ay_u, np.zeros(3), np.zeros(3), np.zeros(3), T3[0], T3[1], ay_u / u**2, F_u3[0], F_u3[1]])
    return A, B, C, D, states
