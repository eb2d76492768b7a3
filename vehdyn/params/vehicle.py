"""Vehicle parameters: a nested, frozen, validated :class:`Vehicle` loaded from TOML.

Conventions: SI units; per-corner quantities are said to be so in their description ("per
corner"), per-axle ones likewise. Distances along x are measured from the total centre of gravity
(CG) unless the name says ``sprung``. Products of inertia follow the definition I_xz = int x z dm
(SAE axes, x forward, z down), so the inertia matrix carries -I_xz off its diagonal.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.inertia import check_realizable
from vehdyn.units import GRAVITY
from vehdyn.params.base import ParameterSet, load_toml, parameter, text

__all__ = [
    "MassAndInertia",
    "Geometry",
    "Suspension",
    "Tires",
    "Steering",
    "Aerodynamics",
    "Driveline",
    "Vehicle",
    "load_vehicle",
    "shipped_vehicles",
    "data_path",
]


@dataclasses.dataclass(frozen=True, kw_only=True)
class MassAndInertia(ParameterSet):
    r"""The vehicle's masses, moments of inertia and centre-of-gravity heights: ``Vehicle.mass``.

    The ``[mass]`` table of a vehicle file. Whole-vehicle values (``mass``, ``roll_inertia``,
    ``pitch_inertia``, ``yaw_inertia``, ``roll_yaw_product``, ``cg_height``) are about the total
    centre of gravity; the ``sprung_*`` values are about the sprung mass's own centre of gravity.
    The longitudinal position of either centre of gravity is in :class:`Geometry`.

    Not to be confused with :class:`vehdyn.mechanics.MassProperties`, the mass, centre of mass and
    inertia tensor of one rigid part (for composing bodies from parts).

    Notes
    -----
    The products of inertia are the integrals ``I_xz = int x z dm`` in SAE body axes (x forward,
    z down), so the inertia matrix (:attr:`inertia_matrix`) carries ``-I_xz`` off its diagonal:

    .. math::

        \mathbf I = \begin{bmatrix} I_{xx} & 0 & -I_{xz} \\ 0 & I_{yy} & 0 \\
        -I_{xz} & 0 & I_{zz} \end{bmatrix}

    Checks beyond the fields' bounds: the sprung and unsprung masses add up to at most ``mass``,
    and the whole vehicle's tensor is a rigid body's (positive definite, principal moments obeying
    the triangle inequality; :func:`vehdyn.params.inertia.check_realizable`). A failure raises
    :class:`~vehdyn.ParameterError` naming the field (``mass.yaw_inertia`` when read from a file).

    References
    ----------
    .. [1] SAE J670, *Vehicle Dynamics Terminology*, 2008 (vehicle axes; moments and products of
       inertia).
    """

    mass: float = parameter("kg", "total vehicle mass", gt=0)
    sprung_mass: float = parameter("kg", "sprung mass", gt=0)
    front_unsprung_mass: float = parameter("kg", "unsprung mass of the front axle (both wheels)", ge=0)
    rear_unsprung_mass: float = parameter("kg", "unsprung mass of the rear axle (both wheels)", ge=0)
    roll_inertia: float = parameter("kg*m^2", "I_xx of the whole vehicle about its CG", gt=0)
    pitch_inertia: float = parameter("kg*m^2", "I_yy of the whole vehicle about its CG", gt=0)
    yaw_inertia: float = parameter("kg*m^2", "I_zz of the whole vehicle about its CG", gt=0)
    roll_yaw_product: float = parameter("kg*m^2", "I_xz = int x z dm of the whole vehicle (SAE axes)", default=0.0)
    sprung_roll_inertia: float = parameter("kg*m^2", "I_xx of the sprung mass about its own CG", gt=0)
    sprung_pitch_inertia: float = parameter("kg*m^2", "I_yy of the sprung mass about its own CG", gt=0)
    sprung_roll_yaw_product: float = parameter("kg*m^2", "I_xz of the sprung mass about its own CG", default=0.0)
    sprung_yaw_inertia: float | None = parameter(
        "kg*m^2", "I_zz of the sprung mass about its own CG; None: what yaw_inertia leaves after the unsprung "
        "masses (points at the wheel centres) and the sprung mass's offset from the total CG", default=None, gt=0)
    cg_height: float = parameter("m", "height of the total CG above the ground", gt=0)
    sprung_cg_height: float = parameter("m", "height of the sprung-mass CG above the ground", gt=0)

    def check(self):
        parts = self.sprung_mass + self.front_unsprung_mass + self.rear_unsprung_mass
        if parts > self.mass * (1 + 1e-6):
            raise ParameterError(
                f"sprung_mass + front_unsprung_mass + rear_unsprung_mass = {parts} kg exceeds mass = {self.mass} kg",
                key="sprung_mass", value=self.sprung_mass)
        # One realizability check for every inertia tensor in the package (params.inertia):
        # positive definite, principal moments obeying the triangle inequality.
        try:
            check_realizable(self.inertia_matrix, definite=True)
        except ParameterError as err:
            field = {"ixx": "roll_inertia", "iyy": "pitch_inertia", "izz": "yaw_inertia"}.get(err.key,
                                                                                            "roll_yaw_product")
            value = getattr(self, field)
            what = ("makes the inertia tensor indefinite (needs I_xz^2 < I_xx I_zz)" if field == "roll_yaw_product"
                    else "is not a rigid body's moment of inertia")
            raise ParameterError(f"{field} = {value} kg*m^2 {what}: the {err}", key=field, value=value) from None

    @property
    def unsprung_mass(self) -> float:
        """Both axles' unsprung mass [kg]."""
        return self.front_unsprung_mass + self.rear_unsprung_mass

    @property
    def inertia_matrix(self) -> np.ndarray:
        """3x3 inertia matrix about the CG in SAE axes [kg*m^2] (-I_xz off the diagonal)."""
        return np.array([[self.roll_inertia, 0.0, -self.roll_yaw_product],
                         [0.0, self.pitch_inertia, 0.0],
                         [-self.roll_yaw_product, 0.0, self.yaw_inertia]])


@dataclasses.dataclass(frozen=True, kw_only=True)
class Geometry(ParameterSet):
    """Axle positions, tracks and roll centres."""

    cg_to_front_axle: float = parameter("m", "a: horizontal distance from the total CG to the front axle", gt=0)
    cg_to_rear_axle: float = parameter("m", "b: horizontal distance from the total CG to the rear axle", gt=0)
    sprung_cg_to_front_axle: float = parameter("m", "horizontal distance from the sprung-mass CG to the front axle",
                                               gt=0)
    front_track: float = parameter("m", "front track width", gt=0)
    rear_track: float = parameter("m", "rear track width", gt=0)
    front_roll_centre_height: float = parameter("m", "height of the front roll centre above the ground",
                                                default=0.0)
    rear_roll_centre_height: float = parameter("m", "height of the rear roll centre above the ground", default=0.0)

    def check(self):
        if self.sprung_cg_to_front_axle >= self.wheelbase:
            raise ParameterError(f"sprung_cg_to_front_axle = {self.sprung_cg_to_front_axle} m must be less than "
                                 f"the wheelbase {self.wheelbase} m", key="sprung_cg_to_front_axle",
                                 value=self.sprung_cg_to_front_axle)

    @property
    def wheelbase(self) -> float:
        """L = a + b [m]."""
        return self.cg_to_front_axle + self.cg_to_rear_axle

    @property
    def a(self) -> float:
        """CG to front axle [m] (textbook symbol)."""
        return self.cg_to_front_axle

    @property
    def b(self) -> float:
        """CG to rear axle [m] (textbook symbol)."""
        return self.cg_to_rear_axle

    @property
    def sprung_cg_to_rear_axle(self) -> float:
        """Horizontal distance from the sprung-mass CG to the rear axle [m]: L - sprung_cg_to_front_axle."""
        return self.wheelbase - self.sprung_cg_to_front_axle


@dataclasses.dataclass(frozen=True, kw_only=True)
class Suspension(ParameterSet):
    """Corner springs and dampers (wheel rates), anti-roll bars, roll steer, camber gain, anti-dive/squat,
    compliance steer and the treatment of the unsprung masses' lateral inertia."""

    front_spring_rate: float = parameter("N/m", "vertical spring rate at each front wheel (per corner, wheel rate)",
                                         gt=0)
    rear_spring_rate: float = parameter("N/m", "vertical spring rate at each rear wheel (per corner, wheel rate)",
                                        gt=0)
    front_damping: float = parameter("N*s/m", "linear damping rate at each front wheel (per corner)", ge=0)
    rear_damping: float = parameter("N*s/m", "linear damping rate at each rear wheel (per corner)", ge=0)
    front_antiroll_stiffness: float = parameter("N*m/rad", "roll stiffness of the front anti-roll bar (per axle)",
                                                ge=0, default=0.0)
    rear_antiroll_stiffness: float = parameter("N*m/rad", "roll stiffness of the rear anti-roll bar (per axle)",
                                               ge=0, default=0.0)
    front_roll_steer: float = parameter("rad/rad", "front road-wheel steer per unit body roll (SAE signs)",
                                        default=0.0)
    rear_roll_steer: float = parameter("rad/rad", "rear road-wheel steer per unit body roll (SAE signs)",
                                       default=0.0)
    front_camber_gain: float | None = parameter(
        "rad/m", "front camber change (top of the wheel outward +) per unit of bump travel; None: the wheels "
        "stay upright to the road (no camber from roll or travel)", default=None)
    rear_camber_gain: float | None = parameter(
        "rad/m", "rear camber change (top of the wheel outward +) per unit of bump travel; None: upright wheels",
        default=None)
    front_anti_dive: float = parameter(
        "-", "front anti-dive fraction tan(beta_f) L / h: share of the pitch moment of the front longitudinal "
        "tire forces taken by the linkage instead of the springs (0: none)", default=0.0)
    rear_anti_squat: float = parameter(
        "-", "rear anti-squat (and anti-lift) fraction tan(beta_r) L / h of the rear longitudinal tire forces "
        "(0: none)", default=0.0)
    # compliance steer (issue 28). SAE signs; 0: rigid. The understeer term of each is given in
    # closed form (W_i the static axle loads, t_i the tires' pneumatic trails, both of the axle) and
    # computed by vehdyn.handling.understeer_budget; Gillespie, Fundamentals of Vehicle Dynamics,
    # 1992, ch. 6, Table 6.1; Milliken & Milliken, Race Car Vehicle Dynamics, 1995, ch. 5 and 18
    front_lateral_force_compliance_steer: float = parameter(
        "rad/N", "front road-wheel steer per unit lateral force of the front AXLE (both tires), delta_c = c F_y, "
        "positive steering in the sense of the force (SAE: to the right for F_y > 0); a front axle that toes out "
        "of the turn has c < 0. Understeer term -c_f W_f [rad/g]. In the full vehicle each wheel steers by "
        "2 c times its own lateral force (the same axle steer when the wheels share the force)", default=0.0)
    rear_lateral_force_compliance_steer: float = parameter(
        "rad/N", "rear road-wheel steer per unit lateral force of the rear axle (both tires), delta_c = c F_y, "
        "positive in the sense of the force (SAE); a rear axle steering with the force (c > 0) understeers. "
        "Understeer term +c_r W_r [rad/g]", default=0.0)
    front_aligning_moment_compliance_steer: float = parameter(
        "rad/(N*m)", "front road-wheel steer per unit aligning moment of the front axle (both tires), "
        "delta_c = e M_z, positive in the sense of the moment (SAE yaw, nose right); with M_z = -t_f F_y "
        "(pneumatic trail t_f > 0 behind the contact centre) the understeer term is +e_f t_f W_f [rad/g]. "
        "Referred to the road wheel with the hand wheel held: the kingpin-axis compliance of the suspension "
        "alone; the steering system's stiffness is Steering.road_wheel_stiffness", default=0.0)
    rear_aligning_moment_compliance_steer: float = parameter(
        "rad/(N*m)", "rear road-wheel steer per unit aligning moment of the rear axle (both tires), "
        "delta_c = e M_z, positive in the sense of the moment (SAE); understeer term -e_r t_r W_r [rad/g]",
        default=0.0)
    front_unsprung_transfer_fraction: float = parameter(
        "-", "share lambda_f of the front unsprung masses' lateral-inertia moment about the roll centre that the "
        "tires take directly, bypassing the springs: 1 (default) a beam axle or swing axle, the textbook "
        "treatment (Milliken 1995 ch. 18, Gillespie 1992 ch. 7); (T/2)/d for an independent suspension whose "
        "front-view swing arm (contact patch to instant centre) is d long; 0 parallel equal-length links or a "
        "sliding pillar (the carrier keeps the body's orientation and passes the moment to the body as a "
        "couple, through the springs)", default=1.0, ge=0.0, le=1.0)
    rear_unsprung_transfer_fraction: float = parameter(
        "-", "share lambda_r of the rear unsprung masses' lateral-inertia moment about the roll centre that the "
        "tires take directly (see front_unsprung_transfer_fraction; 1: beam axle, the textbook; 0: parallel "
        "links)", default=1.0, ge=0.0, le=1.0)

    def compliance_steer(self, axle: str, pneumatic_trail: float = 0.0) -> float:
        r"""Net road-wheel steer per unit lateral force of an axle from both compliances.

        .. math::

            \frac{\partial \delta_c}{\partial F_y} = c_i - e_i t_i

        (the aligning moment M_z = -t_i F_y of the axle's tires, t_i their pneumatic trail).

        Parameters
        ----------
        axle : {"front", "rear"}
            The axle.
        pneumatic_trail : float, optional
            The axle's pneumatic trail t_i [m] (0: the aligning-moment compliance left out).

        Returns
        -------
        float
            c_i - e_i t_i [rad/N].
        """
        if axle not in ("front", "rear"):
            raise ParameterError(f"axle must be 'front' or 'rear', got {axle!r}", key="axle", value=axle)
        return (getattr(self, f"{axle}_lateral_force_compliance_steer")
                - getattr(self, f"{axle}_aligning_moment_compliance_steer") * float(pneumatic_trail))

    @property
    def has_compliance_steer(self) -> bool:
        """True when any compliance-steer field is nonzero."""
        return any(getattr(self, f"{a}_{k}_compliance_steer") != 0.0 for a in ("front", "rear")
                   for k in ("lateral_force", "aligning_moment"))


@dataclasses.dataclass(frozen=True, kw_only=True)
class Tires(ParameterSet):
    """Tire data the vehicle models need, and the tire property file."""

    front_cornering_stiffness: float = parameter("N/rad", "cornering stiffness of the front axle (both tires)",
                                                 gt=0)
    rear_cornering_stiffness: float = parameter("N/rad", "cornering stiffness of the rear axle (both tires)", gt=0)
    vertical_stiffness: float = parameter("N/m", "vertical stiffness of one tire", gt=0)
    vertical_damping: float = parameter("N*s/m", "vertical damping of one tire", ge=0, default=0.0)
    rolling_radius: float = parameter("m", "effective rolling radius", gt=0)
    wheel_spin_inertia: float = parameter("kg*m^2", "spin inertia of one wheel", gt=0)
    friction_coefficient: float = parameter("-", "peak road-tire friction coefficient", gt=0)
    front_relaxation_length: float = parameter("m", "lateral relaxation length of the front tires", ge=0,
                                               default=0.0)
    rear_relaxation_length: float = parameter("m", "lateral relaxation length of the rear tires", ge=0,
                                              default=0.0)
    tir_file: str = text("name of a .tir file in data/tires/ or a path to one")
    model: str = text("tire law used by nonlinear vehicle models", default="magic_formula")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Steering(ParameterSet):
    """Steering system."""

    ratio: float = parameter("-", "overall steering ratio: hand-wheel angle / road-wheel angle", gt=0)
    max_road_wheel_angle: float = parameter("rad", "largest road-wheel steer angle", gt=0, le=np.pi / 2)
    ackermann_fraction: float = parameter(
        "-", "share of Ackermann geometry in the left/right split of the front steer angle (0: parallel steer, "
        "1: both front wheels square to the turn centre)", default=0.0, ge=0, le=1)
    # steering system (optional; used by vehdyn.handling.SteeringSystem). Defaults: typical
    # passenger-car values, assumed, after Pfeffer & Harrer (eds.), Steering Handbook, Springer,
    # 2017 (column and torsion bar, friction, boost curves of power steering) and Gillespie,
    # Fundamentals of Vehicle Dynamics, 1992, ch. 8 (caster trail); no shipped vehicle has measured ones
    steering_wheel_inertia: float = parameter("kg*m^2", "steering-wheel inertia about the column (typical 0.04)",
                                              gt=0, default=0.04)
    column_stiffness: float = parameter("N*m/rad", "torsional stiffness of the column with its torsion bar (typical "
                                        "115, about 2 N*m/deg)", gt=0, default=115.0)
    lower_steering_inertia: float = parameter("kg*m^2", "inertia of rack, pinion, road wheels about the kingpins and "
                                              "assist motor, referred to the pinion (typical 0.05)", gt=0, default=0.05)
    steering_damping: float = parameter("N*m*s/rad", "viscous damping of the rack, referred to the pinion", ge=0,
                                        default=0.5)
    steering_friction_torque: float = parameter("N*m", "Coulomb friction of rack and gear, referred to the pinion "
                                                "(typical 1)", ge=0, default=1.0)
    assist_gain: float = parameter("-", "power-assist boost: assist torque per torsion-bar torque far from centre "
                                   "(0: manual steering)", ge=0, default=0.0)
    assist_knee_torque: float = parameter("N*m", "torsion-bar torque around which the boost curve turns on", gt=0,
                                          default=1.5)
    caster_trail: float = parameter("m", "mechanical (caster) trail of the front wheels at the ground (typical "
                                    "0.02)", default=0.02)
    pneumatic_trail: float = parameter("m", "pneumatic trail of the front tires (None: from the tire law, -dM_z/dF_y "
                                       "at zero slip and the static load)", default=None)

    @property
    def road_wheel_stiffness(self) -> float:
        r"""Steering-system stiffness K_ss between the held hand wheel and the road wheels [N*m/rad].

        The on-centre stiffness of the system :class:`vehdyn.handling.SteeringSystem` models, referred
        to the road wheels about the kingpins: the column (with its torsion bar) seen through the
        overall ratio N,

        .. math::

            K_{ss} = N^2 k_c

        (manual or assisted alike: the boost curve has zero slope at centre, so the assist adds no
        stiffness there). The rack, the tie rods and the kingpin bushes are taken as rigid beside the
        torsion bar (no separate field: a compliance of the suspension about the kingpin axis is
        :attr:`Suspension.front_aligning_moment_compliance_steer`). The understeer it adds to a gradient
        measured against the hand-wheel angle / N is (t_m + t_p) W_f / K_ss [rad/g] (Gillespie,
        *Fundamentals of Vehicle Dynamics*, 1992, ch. 6, Table 6.1), with t_m the caster trail and
        t_p the pneumatic trail: the steering torque about the kingpins is -(t_m + t_p) F_f.

        Returns
        -------
        float
            K_ss [N*m/rad].
        """
        return self.ratio**2 * self.column_stiffness


@dataclasses.dataclass(frozen=True, kw_only=True)
class Aerodynamics(ParameterSet):
    """Aerodynamic drag (and lift) coefficients."""

    frontal_area: float = parameter("m^2", "frontal (reference) area", gt=0)
    drag_coefficient: float = parameter("-", "drag coefficient c_x", ge=0)
    air_density: float = parameter("kg/m^3", "air density (1.206 kg/m^3 at 20 degC, 101.325 kPa)", gt=0,
                                   default=1.206)
    front_lift_coefficient: float = parameter("-", "front-axle lift coefficient", default=0.0)
    rear_lift_coefficient: float = parameter("-", "rear-axle lift coefficient", default=0.0)
    # crosswind (optional; typical passenger-car values, not measurements of a given vehicle):
    # Hucho, Aerodynamics of Road Vehicles, 4th ed., 1998, sec. 4.4 (side force and yaw moment of
    # passenger cars grow about linearly with the aerodynamic sideslip up to about 20 deg);
    # Wong, Theory of Ground Vehicles, 4th ed., 2008, sec. 3.2 (centre of pressure of cars in the
    # front half of the wheelbase, ahead of the neutral steer point)
    side_force_coefficient_slope: float = parameter(
        "1/rad", "dC_Y/d(beta_aero) of the aerodynamic side force, referred to the frontal area (typical car 2.0)",
        ge=0, default=2.0)
    centre_of_pressure_from_front_axle: float = parameter(
        "-", "distance from the front axle back to the aerodynamic centre of pressure, as a fraction of the "
        "wheelbase (typical car 0.3; negative: ahead of the front axle)", gt=-1.0, lt=2.0, default=0.3)

    def drag_force(self, speed):
        r"""Aerodynamic drag force at an air speed.

        .. math::

            F_D = \tfrac12 \rho \, c_x A \, V |V|

        Parameters
        ----------
        speed : float or array_like
            Air speed V along the vehicle's x axis [m/s]; negative for air from behind.

        Returns
        -------
        ndarray
            Drag force F_D [N], of the sign of ``speed`` (it opposes the motion through the air).

        References
        ----------
        .. [1] W.-H. Hucho, *Aerodynamics of Road Vehicles*, 4th ed., SAE, 1998, ch. 4.

        Examples
        --------
        >>> import vehdyn
        >>> round(float(vehdyn.load_vehicle("sedan").aero.drag_force(30.0)), 1)
        420.2
        """
        speed = np.asarray(speed, dtype=float)
        return 0.5 * self.air_density * self.drag_coefficient * self.frontal_area * speed * np.abs(speed)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Driveline(ParameterSet):
    """How drive and brake torque split between the axles (used by operating points and manoeuvres).

    Optional in vehicle files: a file without a ``[driveline]`` table gets these defaults.
    """

    front_drive_fraction: float = parameter("-", "share of the drive torque on the front axle (0: rear-wheel drive)",
                                            default=0.0, ge=0, le=1)
    front_brake_fraction: float = parameter("-", "share of the brake torque on the front axle", default=0.65,
                                            ge=0, le=1)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Vehicle(ParameterSet):
    """A complete vehicle parameter set: one frozen, validated group per TOML table.

    Load shipped vehicles with :func:`load_vehicle` (``"sedan"``, ``"compact"``, ``"van"``,
    ``"tractor"``) and make variants with :meth:`replace` (``sedan.replace(mass__mass=1500.0)``
    reaches into a group).

    Parameters
    ----------
    name, description, source, category : str
        Short name, what the vehicle is, where its numbers come from, and its kind
        (``"passenger_car"`` or ``"truck_tractor"``).
    mass : MassAndInertia
        Masses, moments of inertia and centre-of-gravity heights (the ``[mass]`` table).
    geometry : Geometry
        Axle positions from the centre of gravity, tracks, roll-centre heights (``[geometry]``).
    suspension : Suspension
        Corner springs and dampers, anti-roll bars, roll steer, camber gain, anti-dive/squat
        (``[suspension]``).
    tires : Tires
        Axle cornering stiffnesses, vertical tire stiffness, rolling radius, friction, relaxation
        lengths and the ``.tir`` file (``[tires]``).
    steering : Steering
        Steering ratio, steer limits, Ackermann share and the steering system (``[steering]``).
    aero : Aerodynamics
        Drag, lift and side-force coefficients (``[aero]``).
    driveline : Driveline, optional
        Drive and brake torque split between the axles (``[driveline]``; defaults when absent).

    Raises
    ------
    ParameterError
        If a group fails its checks, or the sprung-mass CG position of ``geometry`` contradicts
        the masses and the total CG (more than 1 % of the wheelbase apart).

    Notes
    -----
    SI units throughout; SAE vehicle axes (x forward, y right, z down) for the products of
    inertia. The consistency check places the sprung-mass CG where the total CG and the unsprung
    masses, lumped at the axles, put it:

    .. math::

        m_s x_s + m_{uf} a - m_{ur} b = 0
    """

    name: str = text("short name")
    description: str = text("what vehicle this is", default="")
    source: str = text("where the numbers come from", default="")
    category: str = text("kind of vehicle: studies that compare cars take the passenger cars only",
                         default="passenger_car", choices=("passenger_car", "truck_tractor"))
    mass: MassAndInertia
    geometry: Geometry
    suspension: Suspension
    tires: Tires
    steering: Steering
    aero: Aerodynamics
    driveline: Driveline = dataclasses.field(default_factory=Driveline)

    def check(self):
        g = self.geometry
        m = self.mass
        # the sprung CG must sit where the total CG and the unsprung masses (at the axles) put it
        # total CG at x = 0 (x forward): 0 = m_s x_s + m_uf a - m_ur b
        x_sprung = (m.rear_unsprung_mass * g.b - m.front_unsprung_mass * g.a) / m.sprung_mass
        implied = g.a - x_sprung
        if abs(implied - g.sprung_cg_to_front_axle) > 0.01 * g.wheelbase:
            raise ParameterError(
                f"geometry.sprung_cg_to_front_axle = {g.sprung_cg_to_front_axle} m is inconsistent with the "
                f"masses and the total CG (it implies {implied:.4f} m)",
                key="geometry.sprung_cg_to_front_axle", value=g.sprung_cg_to_front_axle)
        # the compliance steer must leave each axle an effective cornering stiffness C / (1 - c C) > 0
        # (the aligning-moment part needs the tire law's trail: checked where a model reads it,
        # vehdyn.handling.bicycle.vehicle_compliance_steer)
        for axle in ("front", "rear"):
            c = getattr(self.suspension, f"{axle}_lateral_force_compliance_steer")
            C = getattr(self.tires, f"{axle}_cornering_stiffness")
            if 1.0 - c * C <= 0.0:
                raise ParameterError(
                    f"suspension.{axle}_lateral_force_compliance_steer = {c:.6g} rad/N with "
                    f"tires.{axle}_cornering_stiffness = {C:.6g} N/rad makes 1 - c C = {1.0 - c * C:.6g} <= 0: the "
                    f"axle's force would steer it further than its slip (no effective cornering stiffness)",
                    key=f"suspension.{axle}_lateral_force_compliance_steer", value=c)

    # ------------------------------------------------------------------ derived quantities
    @property
    def wheelbase(self) -> float:
        """Wheelbase [m]."""
        return self.geometry.wheelbase

    def static_axle_loads(self, gravity: float = GRAVITY) -> tuple[float, float]:
        """Static axle loads of the vehicle standing on level ground.

        Parameters
        ----------
        gravity : float, optional
            Gravitational acceleration g [m/s^2] (default :data:`vehdyn.units.GRAVITY`).

        Returns
        -------
        front, rear : float
            Axle loads m g b / L and m g a / L [N] (both wheels of the axle).
        """
        g = self.geometry
        w = self.mass.mass * gravity
        return w * g.b / g.wheelbase, w * g.a / g.wheelbase

    @property
    def front_roll_stiffness(self) -> float:
        """Front suspension roll stiffness [N*m/rad]: k_s T^2 / 2 + anti-roll bar (tires excluded)."""
        return self.suspension.front_spring_rate * self.geometry.front_track**2 / 2 + \
            self.suspension.front_antiroll_stiffness

    @property
    def rear_roll_stiffness(self) -> float:
        """Rear suspension roll stiffness [N*m/rad]: k_s T^2 / 2 + anti-roll bar (tires excluded)."""
        return self.suspension.rear_spring_rate * self.geometry.rear_track**2 / 2 + \
            self.suspension.rear_antiroll_stiffness

    def tir_path(self) -> Path:
        """Path of the vehicle's ``.tir`` file.

        Returns
        -------
        pathlib.Path
            ``tires.tir_file`` if it names an existing file, else the shipped tire of that name in
            ``data/tires``.

        Raises
        ------
        ParameterError
            If ``tires.tir_file`` is neither a file nor a shipped tire (key ``tires.tir_file``).
        """
        p = Path(self.tires.tir_file)
        if p.is_file():
            return p
        shipped = data_path("tires", self.tires.tir_file)
        if shipped.is_file():
            return shipped
        raise ParameterError(f"tires.tir_file {self.tires.tir_file!r} is neither a file nor a shipped tire",
                             key="tires.tir_file", value=self.tires.tir_file)


def data_path(*parts: str) -> Path:
    """Path of a shipped data file: ``vehdyn/data`` in a wheel, ``data/`` beside the package in a checkout.

    Parameters
    ----------
    *parts : str
        Path components below the data folder (``"tires", "mf_185_80R14.tir"``).

    Returns
    -------
    pathlib.Path
        The path (not checked to exist; the folder itself is).

    Raises
    ------
    ParameterError
        If the installation has no data folder.
    """
    here = Path(__file__).resolve().parent.parent
    for root in (here / "data", here.parent / "data"):
        if root.is_dir():
            return root.joinpath(*parts)
    raise ParameterError("vehdyn's shipped data folder is missing from this installation", key="data", value=str(here))


def shipped_vehicles(category: str | None = None) -> list[str]:
    """Names of the vehicles shipped in ``data/vehicles``.

    Parameters
    ----------
    category : {"passenger_car", "truck_tractor"}, optional
        Only the vehicles of this ``category`` (the vehicle file's field; default of a file:
        ``"passenger_car"``). None: every shipped vehicle.

    Returns
    -------
    list of str
        Sorted names, each loadable with :func:`load_vehicle`.

    Raises
    ------
    ParameterError
        For an unknown ``category``.

    Examples
    --------
    >>> import vehdyn
    >>> vehdyn.shipped_vehicles("passenger_car")
    ['compact', 'sedan', 'van']
    """
    names = shipped_names("vehicles")
    if category is None:
        return names
    choices = dataclasses.fields(Vehicle)
    allowed = next(f for f in choices if f.name == "category").metadata["choices"]
    if category not in allowed:
        raise ParameterError(f"category = {category!r} is not one of {list(allowed)}", key="category", value=category)
    return [name for name in names if load_vehicle(name).category == category]


def shipped_names(folder: str) -> list[str]:
    """Stems of the TOML files shipped in ``data/FOLDER``."""
    return sorted(p.stem for p in data_path(folder).glob("*.toml"))


def load_vehicle(name_or_path: str | Path) -> Vehicle:
    """Load a shipped vehicle by name (``"sedan"``) or a user's TOML file by path.

    Parameters
    ----------
    name_or_path : str or os.PathLike
        The name of a shipped vehicle (see :func:`shipped_vehicles`), or a path to a TOML file
        with the tables ``[mass]``, ``[geometry]``, ``[suspension]``, ``[tires]``, ``[steering]``,
        ``[aero]`` and optionally ``[driveline]`` (SI units).

    Returns
    -------
    Vehicle
        The frozen, validated parameter set (SI units); ``Vehicle.replace(group__field=value)``
        makes a variant.

    Raises
    ------
    ParameterError
        If the name is unknown, the argument is neither a name nor a path, the file is missing, a
        folder, unreadable, not UTF-8 text or not valid TOML (a UTF-8 byte-order mark is accepted),
        or a parameter is missing, unknown, of the wrong type, non-finite or out of range (the
        message names the key and the value).

    Examples
    --------
    >>> import vehdyn
    >>> sedan = vehdyn.load_vehicle("sedan")
    >>> type(sedan.mass).__name__, round(sedan.mass.mass, 1), round(sedan.wheelbase, 3)
    ('MassAndInertia', 1093.3, 2.579)
    >>> [round(load) for load in sedan.static_axle_loads()]   # front, rear [N]
    [5852, 4873]
    >>> heavier = sedan.replace(mass__mass=1300.0)        # a variant; sedan itself is unchanged
    >>> heavier.mass.mass, round(sedan.mass.mass, 1)
    (1300.0, 1093.3)
    """
    return load_shipped_or_file(Vehicle, name_or_path, "vehicle")


def load_shipped_or_file(cls, name_or_path, kind: str):
    """A ``cls`` parameter set from a shipped file ``data/{kind}s/NAME.toml`` or a user's TOML file.

    ``kind`` (``"vehicle"``, ``"trailer"``) names the argument in the errors.
    """
    if not isinstance(name_or_path, (str, os.PathLike)):
        raise ParameterError(f"{kind} must be a shipped {kind}'s name or a path to a .toml file, got "
                             f"{type(name_or_path).__name__} {name_or_path!r}", key=kind, value=name_or_path)
    p = Path(name_or_path)
    if p.suffix == ".toml" or p.is_file():
        return load_toml(cls, p)
    candidate = data_path(f"{kind}s", f"{name_or_path}.toml")
    if not candidate.is_file():
        if p.is_dir():
            return load_toml(cls, p)  # reports the folder
        shipped = shipped_names(f"{kind}s")
        raise ParameterError(f"unknown {kind} {str(name_or_path)!r}; shipped {kind}s are {shipped}, "
                             "or give a path to a .toml file", key=kind, value=str(name_or_path))
    return load_toml(cls, candidate)
