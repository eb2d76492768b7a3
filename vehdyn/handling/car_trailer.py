"""Linear car–trailer model: lateral, yaw and articulation motion at constant speed.

Two rigid bodies on a flat road coupled by a hitch (a pin: no moment about z) at constant forward
speed u, linear tires, small angles. SAE J670 axes on each body (x forward, y right, z down; yaw
positive turning right). The car has its CG a behind the front axle and b ahead of the rear axle
and the hitch h behind its CG; the trailer has its CG e behind the hitch and its axle f behind
its CG (l_t = e + f). The articulation angle theta is the car's yaw angle minus the trailer's, so
that the trailer yaw rate is r_t = r - dtheta/dt and, in a right turn (positive steer), theta > 0.

Kinematics (linearized; v, r of the car at its CG in car axes)::

    hitch lateral velocity (trailer axes)     v - h r + u theta
    trailer CG lateral velocity               v_t = v - h r + u theta - e r_t
    trailer CG lateral acceleration           a_t = dv/dt - h dr/dt - e dr_t/dt + u r
    slip angles (SAE)   alpha_f = (v + a r)/u - delta,   alpha_r = (v - b r)/u,
                        alpha_t = (v - h r + u theta - (e + f) r_t)/u
    axle forces         Y_i = -C_i alpha_i      (C_i: AXLE cornering stiffness, positive)

Newton–Euler for the two bodies with the hitch force F_h (lateral force of the trailer on the
car; the trailer feels -F_h)::

    m (dv/dt + u r) = Y_f + Y_r + F_h                 I dr/dt     = a Y_f - b Y_r - h F_h
    m_t a_t         = Y_t - F_h                       I_t dr_t/dt = -e F_h - f Y_t

Eliminating F_h = Y_t - m_t a_t leaves three second-order equations in (dv/dt, dr/dt,
d^2theta/dt^2), solved here for the state-space form.

Crosswind (optional, ``crosswind=True``: input ``wind_velocity_lateral`` w [m/s], the air's velocity
across the road, positive toward the right): the side-force law of :mod:`vehdyn.handling.crosswind`
linearized about w = 0 acts on each body, F_w = k_w u w on the car at its centre of pressure x_p ahead
of its CG and F_wt = k_wt u w on the trailer at its centre of pressure d_p behind the hitch (to first
order in the articulation angle the wind crosses both bodies alike). The car's equations gain F_w and
x_p F_w, the trailer's m_t a_t = Y_t - F_h + F_wt and I_t dr_t/dt = -e F_h - f Y_t - (d_p - e) F_wt.
In the steady state the trailer passes the share (l_t - d_p)/l_t of its wind force to the hitch, so
the car steers as a bicycle under the side force F_s = F_w + F_wt (l_t - d_p)/l_t acting at
x_s = (x_p F_w - h F_wt (l_t - d_p)/l_t) / F_s, with the combination's understeer gradient K::

    r = u F_s (C_f + C_r) (x_s - x_n) / (C_f C_r L (L + K u^2))

(x_n the car's neutral steer point; :func:`~vehdyn.handling.steady_state_crosswind_yaw_rate` with
K of the combination). Near the critical speed the snaking mode is lightly damped and a gust that
excites it is amplified (:func:`trailer_crosswind_amplification`). References: Ellis, *Vehicle Dynamics*,
1969, ch. 10 (articulated vehicles); Bundorf, "Directional control dynamics of automobile–travel
trailer combinations", SAE 670099, 1967; Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012,
sec. 1.3.3 (the car–trailer combination, derived there with Lagrange's equations in the car's
body-fixed quasi-coordinates, which give the same equations: see the tests); Karnopp, *Vehicle
Dynamics, Stability, and Control*, 2nd ed., 2013, ch. 9; Sharp & Fernández, "Car-caravan snaking,
part 1", Proc. IMechE C 216, 2002.

Steady-state cornering (dv/dt = dr/dt = dtheta/dt = 0, a_y = u r) follows in closed form: the
trailer carries Y_t = m_t a_y e/l_t, so the hitch presses on the car with -F_h = m_t a_y f/l_t,
the lateral twin of the static tongue load m_t g f/l_t. The combination's understeer gradient
(delta = L/R + K a_y) is therefore::

    K = [m b - m_h (h - b)] / (L C_f) - [m a + m_h (a + h)] / (L C_r),     m_h = m_t f / l_t

and the articulation angle theta = (h - b + l_t)/R + alpha_t - alpha_r. With m_h > 0 and the
hitch behind the rear axle, the tongue load moves load to the rear axle: less understeer.

The snaking mode (the trailer's yaw oscillation) loses damping at the critical speed; a lighter
tongue load (CG moved back towards the axle) and a larger trailer yaw inertia lower it (Bundorf
1967; Sharp & Fernández 2002, sec. 5). A trailer CG behind its axle (f < 0, a negative tongue
load that lifts the hitch) is accepted: it is the unstable case to study, with a critical speed
well below that of the same trailer loaded nose-heavy (see :meth:`LinearCarTrailer.critical_speed`).
"""

from __future__ import annotations

import dataclasses
import math
from typing import NamedTuple

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import LinearModel
from vehdyn.params import ParameterSet, Trailer, Vehicle
from vehdyn.params.base import parameter
from vehdyn.signals import Signal
from vehdyn.handling.bicycle import bicycle_parameters, check_speed
from vehdyn.handling.crosswind import optional_wind_input

__all__ = ["CarTrailerParameters", "CrosswindAmplification", "EOM_TRUCK_TRAILER", "LinearCarTrailer", "SnakingMode",
           "car_trailer_parameters", "trailer_crosswind_amplification"]


_LOWEST_SCANNED_SPEED = 0.5  # [m/s] where critical_speed starts its scan

_STATES = (
    Signal("lateral_velocity", "m/s", "body-frame lateral velocity v of the car's CG (right, SAE)"),
    Signal("yaw_rate", "rad/s", "yaw rate r of the car (positive turning right, SAE)"),
    Signal("articulation_angle", "rad", "car yaw angle minus trailer yaw angle (positive in a right turn)"),
    Signal("articulation_rate", "rad/s", "d/dt of the articulation angle"),
)
_INPUTS = (Signal("front_steer_angle", "rad", "road-wheel steer angle of the car's front axle (SAE, + right)"),)
_OUTPUTS = (
    Signal("lateral_acceleration", "m/s^2", "lateral acceleration of the car's CG, dv/dt + u r (right, SAE)"),
    Signal("trailer_lateral_acceleration", "m/s^2", "lateral acceleration of the trailer's CG (trailer axes)"),
    Signal("articulation_angle", "rad", "car yaw angle minus trailer yaw angle"),
    Signal("yaw_rate", "rad/s", "yaw rate r of the car"),
    Signal("trailer_yaw_rate", "rad/s", "yaw rate of the trailer, r - dtheta/dt"),
    Signal("articulation_rate", "rad/s", "d/dt of the articulation angle"),
    Signal("lateral_velocity", "m/s", "body-frame lateral velocity v of the car's CG"),
    Signal("sideslip_angle", "rad", "car sideslip angle at its CG, v / u"),
    Signal("front_slip_angle", "rad", "car front-axle slip angle (SAE)"),
    Signal("rear_slip_angle", "rad", "car rear-axle slip angle (SAE)"),
    Signal("trailer_slip_angle", "rad", "trailer-axle slip angle (SAE, trailer axes)"),
    Signal("front_lateral_force", "N", "lateral force of the car's front axle"),
    Signal("rear_lateral_force", "N", "lateral force of the car's rear axle"),
    Signal("trailer_lateral_force", "N", "lateral force of the trailer axle (trailer axes)"),
    Signal("hitch_lateral_force", "N", "lateral force of the trailer on the car at the hitch (SAE y, car axes)"),
)


@dataclasses.dataclass(frozen=True, kw_only=True)
class CarTrailerParameters(ParameterSet):
    """The classical parameters of the linear car–trailer model (axle cornering stiffnesses).

    Build from textbook numbers, or from a :class:`~vehdyn.Vehicle` and a :class:`~vehdyn.Trailer`
    with :func:`car_trailer_parameters`.
    """

    mass: float = parameter("kg", "car mass m", gt=0)
    yaw_inertia: float = parameter("kg*m^2", "car yaw moment of inertia I about its CG", gt=0)
    a: float = parameter("m", "car CG to front axle", gt=0)
    b: float = parameter("m", "car CG to rear axle", gt=0)
    front_cornering_stiffness: float = parameter("N/rad", "front AXLE cornering stiffness C_f", gt=0)
    rear_cornering_stiffness: float = parameter("N/rad", "rear AXLE cornering stiffness C_r", gt=0)
    hitch_distance: float = parameter("m", "h: from the car's CG back to the hitch (negative: ahead of the CG)")
    trailer_mass: float = parameter("kg", "trailer mass m_t", gt=0)
    trailer_yaw_inertia: float = parameter("kg*m^2", "trailer yaw moment of inertia I_t about its CG", gt=0)
    trailer_hitch_to_cg: float = parameter("m", "e: from the hitch back to the trailer CG", ge=0)
    trailer_cg_to_axle: float = parameter("m", "f: from the trailer CG back to its axle (negative: CG behind it)")
    trailer_cornering_stiffness: float = parameter("N/rad", "trailer AXLE cornering stiffness C_t", gt=0)
    wind_side_force_factor: float = parameter("kg/m", "car's k_w = 0.5 rho A C_Y' of the crosswind side force "
                                                      "(0: no wind force on the car)", ge=0, default=0.0)
    centre_of_pressure: float = parameter("m", "car's aerodynamic centre of pressure x_p ahead of its CG",
                                          default=0.0)
    trailer_wind_side_force_factor: float = parameter("kg/m", "trailer's k_wt = 0.5 rho A_t C_Y,t' (0: no wind "
                                                              "force on the trailer)", ge=0, default=0.0)
    trailer_centre_of_pressure: float = parameter("m", "d_p: from the hitch back to the trailer's aerodynamic "
                                                       "centre of pressure", default=0.0)

    def check(self):
        if self.hitch_distance <= -self.a:
            raise ParameterError(f"hitch_distance = {self.hitch_distance} m puts the hitch at or ahead of the front "
                                 f"axle (a = {self.a} m); it must be > -a", key="hitch_distance",
                                 value=self.hitch_distance)
        if self.trailer_hitch_to_cg + self.trailer_cg_to_axle <= 0:
            raise ParameterError(f"trailer_cg_to_axle = {self.trailer_cg_to_axle} m puts the trailer axle at or "
                                 "ahead of the hitch (trailer_hitch_to_cg + trailer_cg_to_axle must be > 0)",
                                 key="trailer_cg_to_axle", value=self.trailer_cg_to_axle)

    @property
    def wheelbase(self) -> float:
        """Car wheelbase L = a + b [m]."""
        return self.a + self.b

    @property
    def trailer_wheelbase(self) -> float:
        """l_t = e + f, hitch to trailer axle [m]."""
        return self.trailer_hitch_to_cg + self.trailer_cg_to_axle

    @property
    def hitch_mass(self) -> float:
        """m_h = m_t f / l_t [kg]: the trailer mass the hitch carries (tongue load / g)."""
        return self.trailer_mass * self.trailer_cg_to_axle / self.trailer_wheelbase

    @property
    def understeer_gradient(self) -> float:
        """K [rad/(m/s^2)] of the combination (module docstring); with m_t -> 0 the car's own."""
        m, a, b, h, L = self.mass, self.a, self.b, self.hitch_distance, self.wheelbase
        mh = self.hitch_mass
        return (m * b - mh * (h - b)) / (L * self.front_cornering_stiffness) \
            - (m * a + mh * (a + h)) / (L * self.rear_cornering_stiffness)


EOM_TRUCK_TRAILER = CarTrailerParameters(
    mass=16975 / 9.81, yaw_inertia=3508.0, a=1.289, b=2.885 - 1.289, front_cornering_stiffness=80e3,
    rear_cornering_stiffness=80e3, hitch_distance=2.7, trailer_mass=2000.0, trailer_yaw_inertia=3000.0,
    trailer_hitch_to_cg=2.9, trailer_cg_to_axle=0.1, trailer_cornering_stiffness=80e3)
"""A published light-truck–trailer set: the truck-and-trailer example of Minaker's EoM.

Source: B. P. Minaker, *Fundamentals of Vehicle Dynamics and Modelling*, Wiley, 2019, companion
code github.com/BPMinaker/EoM_samples (GPL-3): ``models/input_ex_truck_trailer.jl`` (commit c32ed25)
gives the truck (a = 1.289 m, b = 2.885 - 1.289 m, m = 16975/9.81 kg, I_z = 3508 kg m^2, hitch
d = 2.7 m behind its CG), the trailer (m_t = 2000 kg, I_t = 3000 kg m^2) and the AXLE cornering
stiffnesses ("total") c_f = c_r = c_t = 80 kN/rad; the sample script ``truck_trailer.jl`` (commit
5c7d008) places the trailer CG e = 2.9 m behind the hitch and its axle h = 0.1 m behind the CG.
Every parameter of the linear model is stated there (no wind data). Its light tongue load makes
it snake at about 18.4 m/s, inside the script's 0.4-40 m/s sweep; the source states no critical
speed as a number.
"""


def car_trailer_parameters(vehicle, trailer: Trailer | None = None) -> CarTrailerParameters:
    """The :class:`CarTrailerParameters` of a towing vehicle and a trailer.

    Parameters
    ----------
    vehicle : Vehicle, BicycleParameters or CarTrailerParameters
        The towing vehicle (its axle cornering stiffnesses as given: not corrected for the tongue
        load); a CarTrailerParameters is returned as it is.
    trailer : Trailer
        The trailer; its ``hitch_behind_rear_axle`` places the hitch, h = b + that distance.
        Not needed with a CarTrailerParameters.

    Returns
    -------
    CarTrailerParameters
        The validated parameters (with the wind numbers of ``vehicle.aero`` and the trailer's).
    """
    if isinstance(vehicle, CarTrailerParameters):
        return vehicle
    if not isinstance(trailer, Trailer):
        raise ParameterError(f"trailer must be a vehdyn Trailer (see vehdyn.load_trailer), got "
                             f"{type(trailer).__name__}", key="trailer", value=trailer)
    from vehdyn.components.aero import trailer_wind_side_force_factor

    car = bicycle_parameters(vehicle)
    rho = vehicle.aero.air_density if isinstance(vehicle, Vehicle) else None  # None: the standard air
    h = car.b + trailer.hitch_behind_rear_axle
    if h <= -car.a:
        raise ParameterError(f"hitch_behind_rear_axle = {trailer.hitch_behind_rear_axle} m puts the hitch at or "
                             f"ahead of the towing vehicle's front axle (wheelbase {car.wheelbase} m)",
                             key="hitch_behind_rear_axle", value=trailer.hitch_behind_rear_axle)
    return CarTrailerParameters(
        mass=car.mass, yaw_inertia=car.yaw_inertia, a=car.a, b=car.b,
        front_cornering_stiffness=car.front_cornering_stiffness, rear_cornering_stiffness=car.rear_cornering_stiffness,
        hitch_distance=h, trailer_mass=trailer.mass, trailer_yaw_inertia=trailer.yaw_inertia,
        trailer_hitch_to_cg=trailer.hitch_to_cg, trailer_cg_to_axle=trailer.cg_to_axle,
        trailer_cornering_stiffness=trailer.cornering_stiffness,
        wind_side_force_factor=car.wind_side_force_factor, centre_of_pressure=car.centre_of_pressure,
        trailer_wind_side_force_factor=trailer_wind_side_force_factor(trailer, rho),
        trailer_centre_of_pressure=trailer.centre_of_pressure_behind_hitch)


class SnakingMode(NamedTuple):
    """The trailer's least-damped oscillatory mode at one speed.

    Attributes
    ----------
    speed : float
        [m/s].
    eigenvalue : complex
        lambda [1/s], the one with positive imaginary part.
    frequency_hz : float
        Damped frequency Im(lambda) / (2 pi) [Hz].
    natural_frequency_hz : float
        |lambda| / (2 pi) [Hz].
    damping_ratio : float
        -Re(lambda) / |lambda| [-] (negative: the oscillation grows).
    """

    speed: float
    """[m/s]"""
    eigenvalue: complex
    """[1/s] (the one with positive imaginary part)"""
    frequency_hz: float
    """damped frequency Im(lambda) / (2 pi) [Hz]"""
    natural_frequency_hz: float
    """|lambda| / (2 pi) [Hz]"""
    damping_ratio: float
    """-Re(lambda) / |lambda| [-] (negative: the oscillation grows)"""


def _state_space(p: CarTrailerParameters, u: float):
    """Exact (A, B, C, D) at speed ``u``, inputs (steer, wind) (equations in the module docstring)."""
    m, iz, a, b, h = p.mass, p.yaw_inertia, p.a, p.b, p.hitch_distance
    mt, it, e, f = p.trailer_mass, p.trailer_yaw_inertia, p.trailer_hitch_to_cg, p.trailer_cg_to_axle
    cf, cr, ct = p.front_cornering_stiffness, p.rear_cornering_stiffness, p.trailer_cornering_stiffness
    lt = e + f
    # slip angles alpha = S x + T delta over x = [v, r, theta, dtheta] (SAE, linear)
    S = np.array([[1 / u, a / u, 0.0, 0.0],
                  [1 / u, -b / u, 0.0, 0.0],
                  [1 / u, -(h + lt) / u, 1.0, lt / u]])
    T = np.array([[-1.0, 0.0], [0.0, 0.0], [0.0, 0.0]])  # inputs: steer (front slip), wind (no slip)
    stiff = np.array([cf, cr, ct])
    Y_x, Y_u = -stiff[:, None] * S, -stiff[:, None] * T  # axle forces Y = Y_x x + Y_u delta
    # a_t = dv/dt - (h + e) dr/dt + e theta'' + u r: its acceleration part over z = [v', r', theta'']
    at_z = np.array([1.0, -(h + e), e])
    # M z = G Y + g x (rows: car lateral, car yaw, trailer yaw; F_h = Y_t - m_t a_t eliminated)
    M = np.array([[m, 0.0, 0.0], [0.0, iz, 0.0], [0.0, it, -it]]) + mt * np.outer([1.0, -h, -e], at_z)
    G = np.array([[1.0, 1.0, 1.0], [a, -b, -h], [0.0, 0.0, -lt]])
    g = np.zeros((3, 4))
    g[:, 1] = -u * mt * np.array([1.0, -h, -e])  # the u r part of m_t a_t
    g[0, 1] -= m * u  # m u r of the car
    # wind per unit w: F_w = k_w u at x_p on the car, F_wt = k_wt u at d_p behind the hitch on the trailer
    fw, fwt = p.wind_side_force_factor * u, p.trailer_wind_side_force_factor * u
    wind = fw * np.array([1.0, p.centre_of_pressure, 0.0]) + fwt * np.array([1.0, -h, -p.trailer_centre_of_pressure])
    Minv = np.linalg.inv(M)
    z_x, z_u = Minv @ (G @ Y_x + g), Minv @ (G @ Y_u + np.column_stack([np.zeros(3), wind]))
    A = np.zeros((4, 4))
    B = np.zeros((4, 2))
    A[0], A[1], A[3] = z_x[0], z_x[1], z_x[2]
    A[2, 3] = 1.0
    B[0], B[1], B[3] = z_u[0], z_u[1], z_u[2]
    eye = np.eye(4)
    ay_x, ay_u = A[0] + u * eye[1], B[0]
    at_x, at_u = at_z @ z_x + u * eye[1], at_z @ z_u
    fh_x, fh_u = Y_x[2] - mt * at_x, Y_u[2] + np.array([0.0, fwt]) - mt * at_u  # F_h = Y_t + F_wt - m_t a_t
    C = np.vstack([ay_x, at_x, eye[2], eye[1], eye[1] - eye[3], eye[3], eye[0], eye[0] / u, S, Y_x, fh_x])
    D = np.vstack([ay_u, at_u, np.zeros((6, 2)), T, Y_u, fh_u])
    return A, B, C, D


class LinearCarTrailer(LinearModel):
    r"""Car–trailer combination at constant speed: lateral, yaw and articulation motion, an exact LinearModel.

    Parameters
    ----------
    vehicle : Vehicle or CarTrailerParameters
        The towing vehicle (mass, yaw inertia, axle positions and axle cornering stiffnesses), or
        the full parameter set (then ``trailer`` is not needed).
    trailer : Trailer, optional
        The trailer (mass, yaw inertia, hitch and axle positions, axle cornering stiffness).
    speed : float
        Constant forward speed u [m/s], > 0 (required).
    crosswind : bool
        Add the input ``wind_velocity_lateral`` [m/s] (module docstring), the wind acting on both
        bodies with the side-force factors and centres of pressure of the parameters (from
        ``vehicle.aero`` and the trailer's ``frontal_area``, ``side_force_coefficient_slope`` and
        ``centre_of_pressure_behind_hitch``). Default False.

    Attributes
    ----------
    car_trailer_parameters : CarTrailerParameters
    speed : float
        [m/s].

    Notes
    -----
    Two rigid bodies joined by a pin hitch h behind the car's CG, SAE axes on each: the car's
    lateral velocity v and yaw rate r at its CG, the articulation angle theta (car yaw minus
    trailer yaw, so that the trailer's yaw rate is r_t = r - dtheta/dt), the trailer's CG e behind
    the hitch and its axle f behind its CG (l_t = e + f), F_h the hitch's lateral force on the
    car, Y the axle forces of the AXLE cornering stiffnesses C, F_w = k_w u w and F_wt = k_wt u w
    the wind's side forces on the two bodies (``crosswind=True``) at x_p ahead of the car's CG and
    d_p behind the hitch:

    .. math::

        m (\dot v + u r) &= Y_f + Y_r + F_h + F_w, \qquad
        I \dot r = a Y_f - b Y_r - h F_h + x_p F_w, \\
        m_t a_t &= Y_t - F_h + F_{wt}, \qquad
        I_t \dot r_t = -e F_h - f Y_t - (d_p - e) F_{wt}, \\
        a_t &= \dot v - h \dot r - e \dot r_t + u r, \qquad Y_i = -C_i \alpha_i, \\
        \alpha_f &= \frac{v + a r}{u} - \delta, \quad \alpha_r = \frac{v - b r}{u}, \quad
        \alpha_t = \frac{v - h r + u \theta - l_t r_t}{u}

    F_h is eliminated, leaving three second-order equations in dv/dt, dr/dt and d^2theta/dt^2. In
    the steady state the hitch passes the share f / l_t of the trailer's lateral inertia force to
    the car, which gives the combination's understeer gradient (:attr:`understeer_gradient`):

    .. math::

        K = \frac{m b - m_h (h - b)}{L C_f} - \frac{m a + m_h (a + h)}{L C_r}, \qquad
        m_h = m_t \frac{f}{l_t}

    The snaking mode (the trailer's yaw oscillation) loses its damping at the critical speed
    (:meth:`critical_speed`).

    States ``lateral_velocity`` [m/s], ``yaw_rate`` [rad/s], ``articulation_angle`` [rad] (car yaw
    minus trailer yaw), ``articulation_rate`` [rad/s]; input ``front_steer_angle`` [rad] (and with
    ``crosswind=True`` ``wind_velocity_lateral`` [m/s]); outputs
    ``lateral_acceleration``, ``trailer_lateral_acceleration``, ``articulation_angle``,
    ``yaw_rate``, ``trailer_yaw_rate``, ``articulation_rate``, ``lateral_velocity``,
    ``sideslip_angle``, the three slip angles and axle forces and ``hitch_lateral_force``. SAE
    signs: a positive steer gives a positive yaw rate, lateral acceleration and articulation angle.

    References
    ----------
    .. [1] J. R. Ellis, *Vehicle Dynamics*, Business Books, 1969, ch. 10 (articulated vehicles).
    .. [2] R. T. Bundorf, "Directional control dynamics of automobile–travel trailer
       combinations", SAE 670099, 1967.
    .. [3] R. S. Sharp and M. A. Alonso Fernández, "Car–caravan snaking. Part 1: the influence of
       pintle pin friction", Proc. IMechE Part C 216, 2002 (snaking and its critical speed).
    .. [4] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 1.3.3 (the car–trailer combination, by Lagrange's equations in the car's body-fixed
       quasi-coordinates: the same equations, see the tests).
    .. [5] D. Karnopp, *Vehicle Dynamics, Stability, and Control*, 2nd ed., CRC Press, 2013, ch. 9.

    Examples
    --------
    >>> from vehdyn.handling import LinearCarTrailer
    >>> combo = LinearCarTrailer.from_parameters(mass=1500, yaw_inertia=2500, a=1.1, b=1.6,
    ...     front_cornering_stiffness=110e3, rear_cornering_stiffness=120e3, hitch_distance=2.6,
    ...     trailer_mass=1200, trailer_yaw_inertia=2500, trailer_hitch_to_cg=3.2,
    ...     trailer_cg_to_axle=0.3, trailer_cornering_stiffness=80e3, speed=20.0)
    >>> round(combo.critical_speed(), 2)  # [m/s], snaking above it
    35.59
    """

    phenomena = frozenset({"lateral", "yaw"})

    def __init__(self, vehicle, trailer: Trailer | None = None, speed: float | None = None, *,
                 crosswind: bool = False):
        if speed is None:
            raise ParameterError("a speed [m/s] is needed (LinearCarTrailer(vehicle, trailer, speed))", key="speed",
                                 value=None)
        params = car_trailer_parameters(vehicle, trailer)
        u = float(check_speed(speed))
        self.car_trailer_parameters = params
        self.speed = u
        A, B, C, D = _state_space(params, u)
        B, D, inputs, phenomena = optional_wind_input(crosswind, B, D, _INPUTS, {"lateral", "yaw"})
        super().__init__(A, B, C, D, states=_STATES, inputs=inputs, outputs=_OUTPUTS,
                         name=f"LinearCarTrailer at {u:g} m/s", phenomena=phenomena)

    @classmethod
    def from_parameters(cls, *, mass: float, yaw_inertia: float, a: float, b: float,
                        front_cornering_stiffness: float, rear_cornering_stiffness: float, hitch_distance: float,
                        trailer_mass: float, trailer_yaw_inertia: float, trailer_hitch_to_cg: float,
                        trailer_cg_to_axle: float, trailer_cornering_stiffness: float,
                        speed: float, wind_side_force_factor: float = 0.0, centre_of_pressure: float = 0.0,
                        trailer_wind_side_force_factor: float = 0.0,
                        trailer_centre_of_pressure: float = 0.0) -> "LinearCarTrailer":
        """A car–trailer model from the classical numbers (SI units; see :class:`CarTrailerParameters`).

        Parameters
        ----------
        mass, yaw_inertia : float
            Car mass [kg] and yaw inertia about its CG [kg*m^2].
        a, b : float
            Car CG to front and rear axle [m].
        front_cornering_stiffness, rear_cornering_stiffness : float
            Car AXLE cornering stiffnesses [N/rad].
        hitch_distance : float
            From the car's CG back to the hitch [m].
        trailer_mass, trailer_yaw_inertia : float
            [kg], [kg*m^2] about the trailer CG.
        trailer_hitch_to_cg, trailer_cg_to_axle : float
            Hitch to trailer CG and trailer CG to trailer axle, both measured backwards [m].
        trailer_cornering_stiffness : float
            Trailer AXLE cornering stiffness [N/rad].
        speed : float
            Forward speed [m/s].
        wind_side_force_factor, centre_of_pressure : float, optional
            The car's k_w = 0.5 rho A C_Y' [kg/m] and centre of pressure x_p ahead of its CG [m].
        trailer_wind_side_force_factor, trailer_centre_of_pressure : float, optional
            The trailer's k_wt [kg/m] and centre of pressure d_p behind the hitch [m]. A positive
            k_w or k_wt adds the crosswind input ``wind_velocity_lateral``.

        Returns
        -------
        LinearCarTrailer
            The combination at ``speed``.
        """
        params = CarTrailerParameters(
            mass=mass, yaw_inertia=yaw_inertia, a=a, b=b, front_cornering_stiffness=front_cornering_stiffness,
            rear_cornering_stiffness=rear_cornering_stiffness, hitch_distance=hitch_distance,
            trailer_mass=trailer_mass, trailer_yaw_inertia=trailer_yaw_inertia,
            trailer_hitch_to_cg=trailer_hitch_to_cg, trailer_cg_to_axle=trailer_cg_to_axle,
            trailer_cornering_stiffness=trailer_cornering_stiffness, wind_side_force_factor=wind_side_force_factor,
            centre_of_pressure=centre_of_pressure, trailer_wind_side_force_factor=trailer_wind_side_force_factor,
            trailer_centre_of_pressure=trailer_centre_of_pressure)
        return cls(params, speed=speed, crosswind=wind_side_force_factor > 0 or trailer_wind_side_force_factor > 0)

    def at_speed(self, speed: float) -> "LinearCarTrailer":
        """The same combination at another forward speed (with the wind input if this one has it).

        Parameters
        ----------
        speed : float
            Forward speed u [m/s], > 0.

        Returns
        -------
        LinearCarTrailer
            The same parameters at ``speed``.
        """
        return type(self)(self.car_trailer_parameters, speed=speed,
                          crosswind="wind_velocity_lateral" in self.input_names)

    # ------------------------------------------------------------------ stability
    def snaking_mode(self, speed: float | None = None) -> SnakingMode:
        """The trailer's snaking mode: the least-damped oscillatory eigenvalue pair.

        Parameters
        ----------
        speed : float, optional
            Forward speed [m/s], > 0; default the model's own.

        Returns
        -------
        SnakingMode
            Its eigenvalue, frequencies and damping ratio.

        Raises
        ------
        ParameterError
            When no mode oscillates at that speed.
        """
        u = self.speed if speed is None else float(check_speed(speed))
        lam = _snaking_eigenvalue(self.car_trailer_parameters, u)
        if lam is None:
            raise ParameterError(f"no oscillatory mode at {u:g} m/s", key="speed", value=u)
        wn = abs(lam)
        return SnakingMode(u, complex(lam), float(lam.imag) / (2 * math.pi), float(wn) / (2 * math.pi),
                           float(-lam.real / wn))

    def critical_speed(self, max_speed: float = 100.0, *, xtol: float = 1e-10) -> float:
        """Speed [m/s] at which the snaking mode loses its damping, from the eigenvalues.

        The real part of the least-damped oscillatory eigenvalue is scanned on a grid from 0.5 m/s
        to ``max_speed`` and its first sign change is refined by Brent's method to ``xtol``.

        Parameters
        ----------
        max_speed : float, optional
            Highest speed scanned [m/s], finite and above the lowest speed scanned (0.5 m/s)
            (default 100).
        xtol : float, optional
            Absolute tolerance of the critical speed [m/s], finite and > 0 (default 1e-10).

        Returns
        -------
        float
            The critical speed [m/s]; ``math.inf`` if the snaking mode stays damped below
            ``max_speed``; 0.5 (the lowest speed scanned) if it is undamped from the start.

        Notes
        -----
        Warning: a trailer whose CG lies behind its axle (``trailer_cg_to_axle < 0``, a negative
        tongue load) is accepted, and it is the dangerous case: its critical speed lies far below
        that of the same trailer loaded nose-heavy (the critical speed falls steadily as the CG
        moves back). Only the oscillatory (snaking) instability is reported here: a divergent
        real eigenvalue (the combination's oversteer, when its understeer gradient is negative)
        is not; :meth:`max_real_part` shows every instability.
        """
        from scipy.optimize import brentq

        from vehdyn.params.checks import finite_number

        max_speed = finite_number(max_speed, "max_speed")
        if not max_speed > _LOWEST_SCANNED_SPEED:
            raise ParameterError(f"max_speed must be above the lowest speed scanned, {_LOWEST_SCANNED_SPEED} m/s, got "
                                 f"{max_speed!r}", key="max_speed", value=max_speed)
        xtol = finite_number(xtol, "xtol", positive=True)
        p = self.car_trailer_parameters
        if max_speed > 10.5:
            speeds = np.concatenate([np.linspace(_LOWEST_SCANNED_SPEED, 10.0, 20), np.linspace(10.5, max_speed, 190)])
        else:  # the same spacing, or finer, below 10.5 m/s: the scan ends at max_speed
            speeds = np.linspace(_LOWEST_SCANNED_SPEED, max_speed, 20)
        growth = np.array([_snaking_real_part(p, u) for u in speeds])
        positive = np.flatnonzero(growth >= 0)
        if positive.size == 0:
            return math.inf
        k = positive[0]
        if k == 0:
            return float(speeds[0])
        return float(brentq(lambda u: _snaking_real_part(p, u), speeds[k - 1], speeds[k], xtol=xtol, rtol=1e-14))

    def max_real_part(self, speed: float | None = None) -> float:
        """Largest real part of all eigenvalues at ``speed``.

        Parameters
        ----------
        speed : float, optional
            Forward speed [m/s], > 0; default the model's own.

        Returns
        -------
        float
            max Re(lambda) [1/s]; > 0: unstable in some mode (snaking or divergence).
        """
        u = self.speed if speed is None else float(check_speed(speed))
        return float(np.max(np.linalg.eigvals(_state_space(self.car_trailer_parameters, u)[0]).real))

    # ------------------------------------------------------------------ steady state
    @property
    def understeer_gradient(self) -> float:
        """Understeer gradient K of the combination [rad/(m/s^2)] (closed form, module docstring)."""
        return self.car_trailer_parameters.understeer_gradient

    def articulation_gain(self) -> float:
        """Steady-state articulation angle per lateral acceleration at this speed [rad/(m/s^2)].

        theta / a_y = (h - b + l_t) / u^2 + m_h' / C_r - m_t e / (l_t C_t) with
        m_h' = (m a + m_h (a + h)) / L (module docstring), from the DC gains.

        Returns
        -------
        float
            theta / a_y [rad/(m/s^2)] (positive: the car's heading leads the trailer's in the turn).
        """
        gain = self.dc_gain()
        return float(gain[self.index("articulation_angle", "outputs"), 0]
                     / gain[self.index("lateral_acceleration", "outputs"), 0])

    def low_speed_offtracking(self, radius) -> np.ndarray:
        """Off-tracking [m] of the trailer axle inside the car's rear axle on a circle at walking pace.

        Kinematic steady state (no tire slip): the rear axle runs on ``radius`` R, the hitch on
        sqrt(R^2 + d^2) with d = h - b its distance behind the rear axle, the trailer axle on
        sqrt(R^2 + d^2 - l_t^2); the off-tracking is R minus that (positive: inside).

        Parameters
        ----------
        radius : float or array_like
            Radius R of the car's rear-axle path [m], > 0, with R^2 + d^2 >= l_t^2.

        Returns
        -------
        float or ndarray
            Off-tracking [m] (positive: the trailer axle runs inside the car's rear axle).
        """
        p = self.car_trailer_parameters
        R = np.asarray(radius, dtype=float)
        d = p.hitch_distance - p.b
        inner = R**2 + d**2 - p.trailer_wheelbase**2
        if np.any(~np.isfinite(R)) or np.any(R <= 0) or np.any(inner < 0):
            raise ParameterError(f"radius must be finite, positive and large enough for the trailer to follow "
                                 f"(R^2 + d^2 >= l_t^2), got {radius!r}", key="radius", value=radius)
        return R - np.sqrt(inner)

    def __repr__(self) -> str:
        p = self.car_trailer_parameters
        return (f"<LinearCarTrailer at {self.speed:g} m/s: car m={p.mass:g} kg, trailer m_t={p.trailer_mass:g} kg, "
                f"h={p.hitch_distance:g} m, e={p.trailer_hitch_to_cg:g} m, f={p.trailer_cg_to_axle:g} m>")


def _snaking_eigenvalue(p: CarTrailerParameters, u: float):
    """The least-damped oscillatory eigenvalue (positive imaginary part) at speed ``u``, or None."""
    lam = np.linalg.eigvals(_state_space(p, u)[0])
    lam = lam[lam.imag > 1e-9 * np.maximum(np.abs(lam), 1.0)]
    if lam.size == 0:
        return None
    return lam[np.argmin(-lam.real / np.abs(lam))]


def _snaking_real_part(p: CarTrailerParameters, u: float) -> float:
    lam = _snaking_eigenvalue(p, u)
    return -math.inf if lam is None else float(lam.real)


class CrosswindAmplification(NamedTuple):
    """How a trailer changes the towing car's response to a lateral wind (:func:`trailer_crosswind_amplification`).

    Gains are per unit lateral wind w [m/s] (steering held), magnitudes of the frequency responses
    of the linear models with the wind input.

    Attributes
    ----------
    speed : float
        [m/s].
    omega : ndarray
        Angular frequencies of the wind [rad/s].
    car_yaw_rate, combination_yaw_rate : ndarray
        |r / w| of the car alone and with the trailer [(rad/s)/(m/s)].
    car_lateral_offset, combination_lateral_offset : ndarray
        |y / w| of the car's CG alone and with the trailer, y the lateral offset from the straight
        path [m/(m/s)].
    steady_yaw_rate_ratio : float
        Steady (w constant) yaw rate of the combination over that of the car alone [-] (signed).
    peak_yaw_rate_ratio : float
        Largest |r / w| of the combination over the car's largest, both over ``omega`` [-].
    """

    speed: float
    """[m/s]"""
    omega: np.ndarray
    """angular frequencies of the wind [rad/s]"""
    car_yaw_rate: np.ndarray
    """|r / w| of the car alone [(rad/s)/(m/s)]"""
    combination_yaw_rate: np.ndarray
    """|r / w| of the car with the trailer [(rad/s)/(m/s)]"""
    car_lateral_offset: np.ndarray
    """|y / w| of the car alone, y the lateral offset of its CG from the straight path [m/(m/s)]"""
    combination_lateral_offset: np.ndarray
    """|y / w| of the car's CG with the trailer [m/(m/s)]"""
    steady_yaw_rate_ratio: float
    """steady (w constant) yaw rate of the combination over that of the car alone [-] (signed)"""
    peak_yaw_rate_ratio: float
    """largest |r / w| of the combination over the car's largest, both over ``omega`` [-]"""


def trailer_crosswind_amplification(vehicle, trailer: Trailer | None = None, speed: float = 80 / 3.6,
                                    omega=None) -> CrosswindAmplification:
    """Crosswind sensitivity of a car–trailer combination against that of the car alone.

    Both are the exact linear models with the wind input (:class:`LinearCarTrailer` and
    :class:`~vehdyn.handling.LinearBicycle` with ``crosswind=True``, the same side-force law of
    :mod:`vehdyn.handling.crosswind` on each body) at the same speed, steering held. The lateral
    offset of the car's CG from its straight path follows from its lateral velocity and yaw rate,
    y = (v + u psi) / (j omega) with psi = r / (j omega) (small angles).

    Parameters
    ----------
    vehicle : Vehicle or CarTrailerParameters
    trailer : Trailer, optional
        Not needed with a CarTrailerParameters.
    speed : float
        [m/s]; default 80 km/h (a common speed limit for cars towing caravans).
    omega : array_like, optional
        Wind frequencies [rad/s]; default 200 points from 0.1 to 30 rad/s (log-spaced).

    Returns
    -------
    CrosswindAmplification
        The amplification grows as the speed approaches the critical speed (the lightly damped
        snaking mode resonates) and, once the trailer's side force dominates, with its area; a
        small trailer side force can first cancel the car's own wind yaw (its hitch share acts
        behind the car's neutral steer point, turning the car the other way).
    """
    from vehdyn.handling.bicycle import BicycleParameters, LinearBicycle

    p = car_trailer_parameters(vehicle, trailer)
    u = float(check_speed(speed))
    w = np.logspace(-1, np.log10(30.0), 200) if omega is None else np.asarray(omega, dtype=float)
    if w.ndim != 1 or w.size == 0 or not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise ParameterError(f"omega must be a non-empty 1-D array of positive finite frequencies [rad/s], got "
                             f"{omega!r}", key="omega", value=omega)
    car = LinearBicycle(BicycleParameters(
        mass=p.mass, yaw_inertia=p.yaw_inertia, a=p.a, b=p.b, front_cornering_stiffness=p.front_cornering_stiffness,
        rear_cornering_stiffness=p.rear_cornering_stiffness, wind_side_force_factor=p.wind_side_force_factor,
        centre_of_pressure=p.centre_of_pressure), u, crosswind=True)
    combo = LinearCarTrailer(p, speed=u, crosswind=True)
    s = 1j * w
    gains = {}
    for key, model in (("car", car), ("combination", combo)):
        fr = model.frequency_response(w, outputs=["lateral_velocity", "yaw_rate"], inputs=["wind_velocity_lateral"])
        v, r = fr.response[0, 0], fr.response[1, 0]
        gains[key] = (np.abs(r), np.abs((v + u * r / s) / s))
        j, k = model.index("yaw_rate", "outputs"), model.index("wind_velocity_lateral", "inputs")
        # steady state D - C A^-1 B of the one gain (A is regular below the divergence speed)
        gains[key + "_dc"] = float(model.D[j, k] - model.C[j] @ np.linalg.solve(model.A, model.B[:, k]))
    return CrosswindAmplification(
        speed=u, omega=w, car_yaw_rate=gains["car"][0], combination_yaw_rate=gains["combination"][0],
        car_lateral_offset=gains["car"][1], combination_lateral_offset=gains["combination"][1],
        steady_yaw_rate_ratio=gains["combination_dc"] / gains["car_dc"],
        peak_yaw_rate_ratio=float(np.max(gains["combination"][0]) / np.max(gains["car"][0])))

