r"""Linear lateral-yaw-roll model (3 DOF): the bicycle model plus the sprung mass rolling about the roll axis.

States ``lateral_velocity`` v [m/s], ``yaw_rate`` r [rad/s], ``roll_rate`` p [rad/s],
``roll_angle`` phi [rad]; inputs ``front_steer_angle``, ``rear_steer_angle`` [rad]; SAE J670 axes
(x forward, y right, z down; positive roll puts the right side down; a positive steer turns right).

Derivation (Lagrange's equations about the roll axis)
-----------------------------------------------------
Assumptions: constant forward speed u; small v, r, p, phi (terms of second order in them dropped
from the equations, i.e. kept to second order in the energies); the unsprung masses do not roll
and move with the non-rolling vehicle frame; the sprung mass m_s rolls by phi about a straight roll
axis through the front and rear roll centres, inclined by theta to the ground (theta > 0 when the
axis rises towards the front); tire forces act on the non-rolling part and follow the linear
axle law of the bicycle model, with roll steer; roll stiffness K_phi and damping C_phi act
between the sprung mass and the axles. The generalized speeds are the quasi-velocities v, r of the
non-rolling frame and the roll rate p = dphi/dt.

Let e = (cos theta, 0, -sin theta) be the roll axis direction and h the perpendicular distance
from the sprung CG to the axis (h > 0 above it), x_s the distance of the sprung CG ahead of the
total CG. Roll moves the sprung CG sideways by h sin(phi) and lowers it by h cos(theta)(1 - cos
phi); its velocity in the non-rolling frame is (u - r h phi, v + r x_s + h p, .). With
Omega = r k + p e the sprung angular velocity and J_s its inertia tensor at its CG, the kinetic
energy to second order is

    T = 1/2 m (u^2 + v^2) + 1/2 I_z r^2 + 1/2 I_x p^2 - I_xz r p + m_s h v p - m_s h u r phi

where m is the total mass, I_z the total yaw inertia about the total CG,
I_x = e.J_s.e + m_s h^2 the sprung roll inertia about the roll axis and
I_xz = J_xz cos(theta) + J_zz sin(theta) - m_s h x_s the roll-yaw product of inertia about the
roll axis (SAE definition, int x z dm). The potential and dissipation functions are

    V = 1/2 K_phi phi^2 + m_s g h cos(theta) cos(phi),      D = 1/2 C_phi p^2.

Lagrange's equations in quasi-coordinates for a frame turning at r about z (Meirovitch, *Methods
of Analytical Dynamics*, 1970, sec. 4.12; Genta, *Motor Vehicle Dynamics*, 1997, sec. 5.7)::

    d/dt dT/dv + r dT/du                 = F_y
    d/dt dT/dr + u dT/dv - v dT/du       = N_z
    d/dt dT/dp - dT/dphi + dV/dphi + dD/dp = 0

give, linearized (the m_s h u p terms of the yaw equation cancel),

    m (dv/dt + u r) + m_s h dp/dt        = F_yf + F_yr
    I_z dr/dt - I_xz dp/dt               = a F_yf - b F_yr
    I_x dp/dt - I_xz dr/dt + m_s h (dv/dt + u r) = -(K_phi - m_s g h cos theta) phi - C_phi p
    dphi/dt = p

    F_yf = C_f (delta_f + eps_f phi - (v + a r) / u),   F_yr = C_r (delta_r + eps_r phi - (v - b r) / u)

with eps the roll-steer coefficients (road-wheel steer per unit roll, SAE signs); with compliance
steer (``front_compliance_steer``, ``rear_compliance_steer``: delta_c = c F_y, quasi-static) C_f and
C_r are the effective stiffnesses C / (1 - c C) of :class:`~vehdyn.handling.BicycleParameters`. This is the
model of Segel (*Theoretical prediction and experimental substantiation of the response of the
automobile to steering control*, Proc. IMechE AD 1956) in the form of Mastinu & Ploechl (eds.),
*Road and Off-Road Vehicle System Dynamics Handbook*, 2014, sec. 20.5, and Kiencke & Nielsen,
*Automotive Control Systems*, 2005, sec. 7.4. In steady state p = 0 and a_y = u r, so

    phi = -m_s h a_y / (K_phi - m_s g h cos theta)                (the body rolls out of the turn)
    K_eff = K + (eps_f - eps_r) m_s h / (K_phi - m_s g h cos theta)

(roll understeer). With m_s h = 0, I_xz = 0 and no roll steer the lateral and yaw equations are
those of :class:`~vehdyn.handling.LinearBicycle`.

From a :class:`~vehdyn.Vehicle`: K_phi and C_phi from the corner springs, dampers and anti-roll
bars (K_phi = k_f T_f^2 / 2 + k_arb,f + ..., C_phi = c_f T_f^2 / 2 + c_r T_r^2 / 2; optionally with
the tires' vertical compliance in series), the roll axis through the front and rear roll centres,
J_zz of the sprung mass = I_z - m_s x_s^2 - m_uf a^2 - m_ur b^2 (unsprung masses as points).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import LinearModel
from vehdyn.params import ParameterSet, Vehicle
from vehdyn.params.base import parameter
from vehdyn.signals import STEER_INPUTS, Signal
from vehdyn.units import GRAVITY
from vehdyn.handling.bicycle import BicycleParameters, LinearBicycle, linear_model_speed

__all__ = ["LateralYawRollParameters", "LateralYawRoll", "lateral_yaw_roll_parameters", "roll_gradient"]

_STATES = (
    Signal("lateral_velocity", "m/s", "lateral velocity v of the non-rolling frame at the total CG (SAE)"),
    Signal("yaw_rate", "rad/s", "yaw rate r (positive turning right, SAE)"),
    Signal("roll_rate", "rad/s", "roll rate p of the sprung mass about the roll axis"),
    Signal("roll_angle", "rad", "roll angle phi of the sprung mass (positive right side down, SAE)"),
)
_INPUTS = STEER_INPUTS
_OUTPUTS = (
    Signal("lateral_acceleration", "m/s^2", "dv/dt + u r of the non-rolling frame at the total CG"),
    Signal("sideslip_angle", "rad", "vehicle sideslip angle at the CG, v / u"),
    Signal("yaw_rate", "rad/s", "yaw rate"),
    Signal("lateral_velocity", "m/s", "lateral velocity"),
    Signal("roll_angle", "rad", "roll angle (positive right side down)"),
    Signal("roll_rate", "rad/s", "roll rate"),
    Signal("front_slip_angle", "rad", "front-axle slip angle including roll steer (SAE)"),
    Signal("rear_slip_angle", "rad", "rear-axle slip angle including roll steer (SAE)"),
    Signal("path_curvature", "1/m", "curvature of the CG path, a_y / u^2"),
    Signal("front_lateral_force", "N", "lateral force of the front axle (SAE y)"),
    Signal("rear_lateral_force", "N", "lateral force of the rear axle (SAE y)"),
)


@dataclasses.dataclass(frozen=True, kw_only=True)
class LateralYawRollParameters(ParameterSet):
    """Parameters of the lateral-yaw-roll model (symbols of the module docstring)."""

    mass: float = parameter("kg", "total mass m", gt=0)
    sprung_mass: float = parameter("kg", "sprung mass m_s", gt=0)
    yaw_inertia: float = parameter("kg*m^2", "total yaw inertia I_z about the total CG", gt=0)
    roll_inertia: float = parameter("kg*m^2", "sprung-mass roll inertia I_x ABOUT THE ROLL AXIS", gt=0)
    roll_yaw_product: float = parameter("kg*m^2", "roll-yaw product I_xz about the roll axis (SAE, int x z dm)",
                                        default=0.0)
    a: float = parameter("m", "total CG to front axle", gt=0)
    b: float = parameter("m", "total CG to rear axle", gt=0)
    roll_arm: float = parameter("m", "h: distance of the sprung CG above the roll axis (perpendicular)")
    front_cornering_stiffness: float = parameter("N/rad", "front AXLE cornering stiffness", gt=0)
    rear_cornering_stiffness: float = parameter("N/rad", "rear AXLE cornering stiffness", gt=0)
    roll_stiffness: float = parameter("N*m/rad", "total roll stiffness K_phi", gt=0)
    roll_damping: float = parameter("N*m*s/rad", "total roll damping C_phi", ge=0, default=0.0)
    front_roll_steer: float = parameter("rad/rad", "front road-wheel steer per unit roll (SAE)", default=0.0)
    rear_roll_steer: float = parameter("rad/rad", "rear road-wheel steer per unit roll (SAE)", default=0.0)
    roll_axis_inclination: float = parameter("rad", "theta, positive when the roll axis rises to the front",
                                             default=0.0, gt=-np.pi / 4, lt=np.pi / 4)
    gravity: float = parameter("m/s^2", "gravitational acceleration", gt=0, default=GRAVITY)
    front_compliance_steer: float = parameter(
        "rad/N", "net front compliance steer c_f - e_f t_f per unit axle force (SAE; 0: rigid; "
        ":class:`~vehdyn.handling.BicycleParameters`)", default=0.0)
    rear_compliance_steer: float = parameter("rad/N", "net rear compliance steer c_r - e_r t_r (0: rigid)",
                                             default=0.0)

    def check(self):
        self.bicycle_parameters()  # the compliance leaves an effective cornering stiffness
        if self.sprung_mass > self.mass:
            raise ParameterError(f"sprung_mass = {self.sprung_mass} kg exceeds mass = {self.mass} kg",
                                 key="sprung_mass", value=self.sprung_mass)
        if self.roll_yaw_product**2 >= self.roll_inertia * self.yaw_inertia:
            raise ParameterError(f"roll_yaw_product = {self.roll_yaw_product} kg*m^2 makes the inertia matrix "
                                 "indefinite (needs I_xz^2 < I_x I_z)", key="roll_yaw_product",
                                 value=self.roll_yaw_product)
        if self.roll_stiffness <= self.pendulum_stiffness:
            raise ParameterError(
                f"roll_stiffness = {self.roll_stiffness} N*m/rad does not exceed m_s g h cos(theta) = "
                f"{self.pendulum_stiffness:.6g} N*m/rad: the body would roll over statically",
                key="roll_stiffness", value=self.roll_stiffness)

    @property
    def wheelbase(self) -> float:
        return self.a + self.b

    @property
    def pendulum_stiffness(self) -> float:
        """m_s g h cos(theta) [N*m/rad], the destabilizing gravity moment per unit roll."""
        return self.sprung_mass * self.gravity * self.roll_arm * np.cos(self.roll_axis_inclination)

    @property
    def roll_gradient(self) -> float:
        """m_s h / (K_phi - m_s g h cos theta) [rad/(m/s^2)]; phi = -roll_gradient * a_y (SAE)."""
        return self.sprung_mass * self.roll_arm / (self.roll_stiffness - self.pendulum_stiffness)

    def bicycle_parameters(self) -> BicycleParameters:
        """The single-track part (mass, yaw inertia, axles, cornering stiffnesses).

        Returns
        -------
        BicycleParameters
            Without tire lag or wind.
        """
        return BicycleParameters(mass=self.mass, yaw_inertia=self.yaw_inertia, a=self.a, b=self.b,
                                 front_cornering_stiffness=self.front_cornering_stiffness,
                                 rear_cornering_stiffness=self.rear_cornering_stiffness,
                                 front_compliance_steer=self.front_compliance_steer,
                                 rear_compliance_steer=self.rear_compliance_steer)


def lateral_yaw_roll_parameters(vehicle: Vehicle, *, tire_compliance: bool = False,
                                gravity: float = GRAVITY) -> LateralYawRollParameters:
    """:class:`LateralYawRollParameters` of a Vehicle (formulas in the module docstring).

    The roll axis runs through the front and rear roll centres; h is the sprung CG's distance
    above it, I_x and I_xz the sprung mass's inertias about it; K_phi and C_phi come from the
    corner springs, dampers and anti-roll bars.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle file's masses, inertias, geometry, suspension and tires.
    tire_compliance : bool, optional
        Put each axle's tire roll stiffness k_t T^2 / 2 in series with its suspension roll
        stiffness (default False).
    gravity : float, optional
        g [m/s^2] (default :data:`vehdyn.units.GRAVITY`).

    Returns
    -------
    LateralYawRollParameters
        The validated parameters.

    Raises
    ------
    ParameterError
        When the yaw inertia leaves none for the sprung mass, or the roll stiffness does not
        exceed the pendulum term m_s g h cos(theta).
    """
    from vehdyn.handling.bicycle import vehicle_compliance_steer

    ms, g, s, t = vehicle.mass, vehicle.geometry, vehicle.suspension, vehicle.tires
    compliance = vehicle_compliance_steer(vehicle)
    L = g.wheelbase
    theta = np.arctan2(g.front_roll_centre_height - g.rear_roll_centre_height, L)
    axis_height = g.front_roll_centre_height + (g.rear_roll_centre_height - g.front_roll_centre_height) \
        * g.sprung_cg_to_front_axle / L
    h = (ms.sprung_cg_height - axis_height) * np.cos(theta)
    x_s = g.a - g.sprung_cg_to_front_axle
    jzz = ms.yaw_inertia - ms.sprung_mass * x_s**2 - ms.front_unsprung_mass * g.a**2 - ms.rear_unsprung_mass * g.b**2
    if jzz <= 0:
        raise ParameterError(f"mass.yaw_inertia = {ms.yaw_inertia} kg*m^2 leaves no yaw inertia for the sprung mass "
                             f"({jzz:.4g} kg*m^2)", key="mass.yaw_inertia", value=ms.yaw_inertia)
    c, sn = np.cos(theta), np.sin(theta)
    jxx, jxz = ms.sprung_roll_inertia, ms.sprung_roll_yaw_product
    roll_inertia = jxx * c**2 + 2 * jxz * c * sn + jzz * sn**2 + ms.sprung_mass * h**2
    roll_yaw_product = jxz * c + jzz * sn - ms.sprung_mass * h * x_s
    k_front, k_rear = vehicle.front_roll_stiffness, vehicle.rear_roll_stiffness
    if tire_compliance:
        kt_front = t.vertical_stiffness * g.front_track**2 / 2
        kt_rear = t.vertical_stiffness * g.rear_track**2 / 2
        k_front = k_front * kt_front / (k_front + kt_front)
        k_rear = k_rear * kt_rear / (k_rear + kt_rear)
    return LateralYawRollParameters(
        mass=ms.mass, sprung_mass=ms.sprung_mass, yaw_inertia=ms.yaw_inertia, roll_inertia=float(roll_inertia),
        roll_yaw_product=float(roll_yaw_product), a=g.a, b=g.b, roll_arm=float(h),
        front_cornering_stiffness=t.front_cornering_stiffness, rear_cornering_stiffness=t.rear_cornering_stiffness,
        roll_stiffness=float(k_front + k_rear),
        roll_damping=s.front_damping * g.front_track**2 / 2 + s.rear_damping * g.rear_track**2 / 2,
        front_roll_steer=s.front_roll_steer, rear_roll_steer=s.rear_roll_steer,
        roll_axis_inclination=float(theta), gravity=gravity, front_compliance_steer=compliance[0],
        rear_compliance_steer=compliance[1])


class LateralYawRoll(LinearModel):
    r"""3-DOF lateral-yaw-roll model at constant speed (Segel's model), an exact LinearModel.

    Parameters
    ----------
    vehicle : Vehicle or LateralYawRollParameters
        The vehicle (its parameters by :func:`lateral_yaw_roll_parameters`), or the parameters
        themselves (build those from textbook numbers with :meth:`from_parameters`).
    speed : float
        Forward speed u [m/s], >= :data:`~vehdyn.handling.bicycle.LINEAR_MIN_SPEED` (0.01 m/s: below it
        ``path_curvature`` = a_y/u^2 loses its digits, see :mod:`vehdyn.handling.bicycle`); one number.
    tire_compliance : bool
        With a Vehicle: tires' vertical compliance in series with the suspension roll stiffness
        (default False).

    Attributes
    ----------
    parameters : LateralYawRollParameters
    speed : float
        [m/s].
    mass_matrix : ndarray, shape (4, 4)
        The matrix M of M dx/dt = ... over [v, r, p, phi] (the Hessian of T in v, r, p, and 1).

    Notes
    -----
    The bicycle model (:class:`~vehdyn.handling.LinearBicycle`) plus the sprung mass m_s rolling
    by phi about the roll axis (SAE: positive right side down), h the sprung CG's height above
    the axis, theta the axis's inclination, K_phi and C_phi the roll stiffness and damping,
    eps_f and eps_r the roll-steer coefficients; Lagrange's equations in quasi-coordinates,
    linearized (derivation and assumptions in the module docstring):

    .. math::

        m (\dot v + u r) + m_s h \dot p &= F_{yf} + F_{yr} \\
        I_z \dot r - I_{xz} \dot p &= a F_{yf} - b F_{yr} \\
        I_x \dot p - I_{xz} \dot r + m_s h (\dot v + u r) &=
            -(K_\phi - m_s g h \cos\theta) \phi - C_\phi p, \qquad \dot\phi = p \\
        F_{yf} &= C_f \left(\delta_f + \varepsilon_f \phi - \frac{v + a r}{u}\right), \qquad
        F_{yr} = C_r \left(\delta_r + \varepsilon_r \phi - \frac{v - b r}{u}\right)

    with I_x and I_xz the sprung mass's roll inertia and roll-yaw product about the roll axis,
    I_z the total yaw inertia. In the steady state the body rolls out of the turn and roll steer
    adds to the understeer gradient:

    .. math::

        \phi = -\frac{m_s h}{K_\phi - m_s g h \cos\theta} a_y, \qquad
        K_{eff} = K + (\varepsilon_f - \varepsilon_r) \frac{m_s h}{K_\phi - m_s g h \cos\theta}

    Outputs: ``lateral_acceleration`` (dv/dt + u r of the non-rolling frame), ``sideslip_angle``,
    ``yaw_rate``, ``lateral_velocity``, ``roll_angle``, ``roll_rate``, ``front_slip_angle``,
    ``rear_slip_angle``, ``path_curvature``, ``front_lateral_force``, ``rear_lateral_force``.

    References
    ----------
    .. [1] L. Segel, "Theoretical prediction and experimental substantiation of the response of the
       automobile to steering control", Proc. IMechE Automobile Division, 1956.
    .. [2] G. Mastinu and M. Ploechl (eds.), *Road and Off-Road Vehicle System Dynamics Handbook*,
       CRC Press, 2014, sec. 20.5.
    .. [3] U. Kiencke and L. Nielsen, *Automotive Control Systems*, 2nd ed., Springer, 2005,
       sec. 7.4.
    .. [4] L. Meirovitch, *Methods of Analytical Dynamics*, McGraw-Hill, 1970, sec. 4.12
       (Lagrange's equations in quasi-coordinates).
    .. [5] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 6 (roll steer in
       the understeer gradient).

    Examples
    --------
    >>> import numpy as np
    >>> import vehdyn
    >>> from vehdyn.handling import LateralYawRoll
    >>> model = LateralYawRoll(vehdyn.load_vehicle("sedan"), 20.0)
    >>> round(model.roll_gradient_deg_per_g(), 3)
    7.318

    The steady state of the simulation model is the closed form's roll gradient:

    >>> gain = model.dc_gain()[:, 0]
    >>> roll, ay = gain[model.index("roll_angle", "outputs")], gain[model.index("lateral_acceleration", "outputs")]
    >>> bool(np.isclose(-roll / ay, model.roll_gradient(), rtol=1e-12))
    True
    """

    phenomena = frozenset({"lateral", "yaw", "roll"})

    def __init__(self, vehicle, speed: float, *, tire_compliance: bool = False):
        if isinstance(vehicle, LateralYawRollParameters):
            params = vehicle
        elif isinstance(vehicle, Vehicle):
            params = lateral_yaw_roll_parameters(vehicle, tire_compliance=tire_compliance)
        else:
            raise ParameterError(f"expected a Vehicle or LateralYawRollParameters, got {type(vehicle).__name__}",
                                 key="vehicle", value=vehicle)
        u = linear_model_speed(speed, "LateralYawRoll")
        self.parameters = params
        self.speed = u
        A, B, C, D, self.mass_matrix = _state_space(params, u)
        super().__init__(A, B, C, D, states=_STATES, inputs=_INPUTS, outputs=_OUTPUTS,
                         name=f"LateralYawRoll at {u:g} m/s", phenomena={"lateral", "yaw", "roll"})

    @classmethod
    def from_parameters(cls, *, mass: float, sprung_mass: float, yaw_inertia: float, sprung_roll_inertia: float,
                        a: float, b: float, roll_arm: float, front_cornering_stiffness: float,
                        rear_cornering_stiffness: float, roll_stiffness: float, speed: float,
                        roll_damping: float = 0.0, roll_yaw_product: float = 0.0, front_roll_steer: float = 0.0,
                        rear_roll_steer: float = 0.0, gravity: float = GRAVITY) -> "LateralYawRoll":
        """The model from textbook numbers, with a horizontal roll axis.

        Parameters
        ----------
        mass : float
            Total mass m [kg].
        sprung_mass : float
            Sprung mass m_s [kg], <= m.
        yaw_inertia : float
            Total yaw inertia I_z about the total CG [kg*m^2].
        sprung_roll_inertia : float
            Roll inertia of the sprung mass about ITS OWN CG [kg*m^2]; the model uses
            I_x = sprung_roll_inertia + m_s h^2 about the roll axis.
        a, b : float
            Total CG to front and rear axle [m].
        roll_arm : float
            h, sprung CG height above the roll axis [m].
        front_cornering_stiffness, rear_cornering_stiffness : float
            AXLE cornering stiffnesses (both tires), positive [N/rad].
        roll_stiffness : float
            Total roll stiffness K_phi [N*m/rad], > m_s g h.
        speed : float
            Forward speed u [m/s].
        roll_damping : float, optional
            Total roll damping C_phi [N*m*s/rad] (default 0).
        roll_yaw_product : float, optional
            I_xz of the sprung mass about the roll axis, SAE axes (int x z dm, z down) [kg*m^2]
            (default 0).
        front_roll_steer, rear_roll_steer : float, optional
            Road-wheel steer per unit roll, SAE signs [rad/rad] (default 0).
        gravity : float, optional
            g [m/s^2] (default :data:`vehdyn.units.GRAVITY`).

        Returns
        -------
        LateralYawRoll
            The model at ``speed``.
        """
        params = LateralYawRollParameters(
            mass=mass, sprung_mass=sprung_mass, yaw_inertia=yaw_inertia,
            roll_inertia=sprung_roll_inertia + sprung_mass * roll_arm**2, roll_yaw_product=roll_yaw_product,
            a=a, b=b, roll_arm=roll_arm, front_cornering_stiffness=front_cornering_stiffness,
            rear_cornering_stiffness=rear_cornering_stiffness, roll_stiffness=roll_stiffness,
            roll_damping=roll_damping, front_roll_steer=front_roll_steer, rear_roll_steer=rear_roll_steer,
            gravity=gravity)
        return cls(params, speed)

    def at_speed(self, speed: float) -> "LateralYawRoll":
        """The same vehicle at another speed.

        Parameters
        ----------
        speed : float
            Forward speed u [m/s], >= :data:`~vehdyn.handling.bicycle.LINEAR_MIN_SPEED`.

        Returns
        -------
        LateralYawRoll
            The same parameters at ``speed``.
        """
        return type(self)(self.parameters, speed)

    def bicycle(self) -> LinearBicycle:
        """The bicycle model of the same vehicle (the roll taken away).

        Returns
        -------
        LinearBicycle
            The same mass, yaw inertia, axles and tires, at the same speed.
        """
        return LinearBicycle(self.parameters.bicycle_parameters(), self.speed)

    @property
    def wheelbase(self) -> float:
        return self.parameters.wheelbase

    def roll_gradient(self) -> float:
        """Steady roll per unit lateral acceleration, m_s h / (K_phi - m_s g h cos theta).

        Returns
        -------
        float
            The roll gradient [rad/(m/s^2)], a magnitude: the body rolls out of the turn,
            phi = -roll_gradient * a_y in SAE axes.
        """
        return float(self.parameters.roll_gradient)

    def roll_gradient_deg_per_g(self) -> float:
        """:meth:`roll_gradient` in the unit of handling tests.

        Returns
        -------
        float
            The roll gradient [deg/g] (with the model's g).
        """
        return float(np.rad2deg(self.roll_gradient() * self.parameters.gravity))

    def understeer_gradient(self) -> float:
        """Understeer gradient including roll steer, K + (eps_f - eps_r) roll_gradient.

        Returns
        -------
        float
            K_eff [rad/(m/s^2)] (class Notes; K of :func:`~vehdyn.handling.understeer_gradient`).
        """
        p = self.parameters
        return float(p.bicycle_parameters().understeer_gradient
                     + (p.front_roll_steer - p.rear_roll_steer) * p.roll_gradient)

    def __repr__(self) -> str:
        p = self.parameters
        return (f"<LateralYawRoll at {self.speed:g} m/s: m={p.mass:g} kg, m_s={p.sprung_mass:g} kg, h={p.roll_arm:.4g} m, "
                f"K_phi={p.roll_stiffness:.6g} N*m/rad, C_phi={p.roll_damping:.6g} N*m*s/rad>")


def roll_gradient(vehicle_or_model, *, tire_compliance: bool = False) -> float:
    """Steady-state roll gradient of a Vehicle, LateralYawRoll or its parameters.

    m_s h / (K_phi - m_s g h cos theta) with h the sprung-CG height above the roll axis; the body
    rolls out of the turn (phi = -gradient * a_y in SAE axes).

    Parameters
    ----------
    vehicle_or_model : Vehicle, LateralYawRoll or LateralYawRollParameters
        The vehicle (through :func:`lateral_yaw_roll_parameters`) or the model.
    tire_compliance : bool, optional
        With a Vehicle: the tires' vertical compliance in series with the suspension roll
        stiffness (default False).

    Returns
    -------
    float
        The roll gradient [rad/(m/s^2)], a magnitude.
    """
    if isinstance(vehicle_or_model, LateralYawRoll):
        return vehicle_or_model.roll_gradient()
    if isinstance(vehicle_or_model, LateralYawRollParameters):
        return float(vehicle_or_model.roll_gradient)
    if isinstance(vehicle_or_model, Vehicle):
        return float(lateral_yaw_roll_parameters(vehicle_or_model, tire_compliance=tire_compliance).roll_gradient)
    raise ParameterError(f"expected a Vehicle or LateralYawRoll, got {type(vehicle_or_model).__name__}",
                         key="vehicle", value=vehicle_or_model)


def _state_space(p: LateralYawRollParameters, u: float):
    """Exact (A, B, C, D) over x = [v, r, p, phi], inputs [delta_f, delta_r]."""
    m, ms, h, a, b = p.mass, p.sprung_mass, p.roll_arm, p.a, p.b
    cf, cr = p.bicycle_parameters().effective_cornering_stiffnesses  # with the compliance steer
    M = np.array([[m, 0.0, ms * h, 0.0],
                  [0.0, p.yaw_inertia, -p.roll_yaw_product, 0.0],
                  [ms * h, -p.roll_yaw_product, p.roll_inertia, 0.0],
                  [0.0, 0.0, 0.0, 1.0]])
    # slip angles alpha = S x + T delta (SAE), axle forces F = -C alpha
    S = np.array([[1.0 / u, a / u, 0.0, -p.front_roll_steer],
                  [1.0 / u, -b / u, 0.0, -p.rear_roll_steer]])
    T = -np.eye(2)
    stiffness = np.array([[cf], [cr]])
    F_x, F_u = -stiffness * S, -stiffness * T
    # generalized forces: right-hand sides of the four equations
    Q_x = np.zeros((4, 4))
    Q_u = np.zeros((4, 2))
    Q_x[0] = F_x[0] + F_x[1]
    Q_x[0, 1] -= m * u
    Q_u[0] = F_u[0] + F_u[1]
    Q_x[1] = a * F_x[0] - b * F_x[1]
    Q_u[1] = a * F_u[0] - b * F_u[1]
    Q_x[2, 1] = -ms * h * u
    Q_x[2, 2] = -p.roll_damping
    Q_x[2, 3] = -(p.roll_stiffness - p.pendulum_stiffness)
    Q_x[3, 2] = 1.0
    A = np.linalg.solve(M, Q_x)
    B = np.linalg.solve(M, Q_u)
    ay_x = A[0].copy()
    ay_x[1] += u
    ay_u = B[0]
    eye = np.eye(4)
    C = np.vstack([ay_x, eye[0] / u, eye[1], eye[0], eye[3], eye[2], S[0], S[1], ay_x / u**2, F_x[0], F_x[1]])
    D = np.vstack([ay_u, np.zeros((5, 2)), T[0], T[1], ay_u / u**2, F_u[0], F_u[1]])
    return A, B, C, D, M
