"""Steady-state cornering of the linear single-track model: understeer, gains, stability.

Every function takes a :class:`~vehdyn.Vehicle`, a :class:`~vehdyn.handling.LinearBicycle` or
:class:`~vehdyn.handling.BicycleParameters`; speeds default to the bicycle's speed and broadcast
(numpy rules), so a whole speed sweep is one call. Closed forms (SAE signs, AXLE cornering
stiffnesses C_f, C_r, CG to axles a, b, wheelbase L = a + b)::

    K      = (m / L) (b / C_f - a / C_r)                  understeer gradient [rad/(m/s^2)]
    delta_f - delta_r = L / R + K a_y                     steer for a turn of radius R
    r / delta_f = u (1 - k) / (L + K u^2)                 (k = delta_r / delta_f, 0 for 2WS)
    beta / delta_f = k + (b - m a u^2 / (L C_r)) (1 - k) / (L + K u^2)
    u_char = sqrt(L / K) (K > 0),  u_crit = sqrt(-L / K) (K < 0)

from the equilibrium of the model in :mod:`vehdyn.handling.bicycle` (Gillespie, *Fundamentals of
Vehicle Dynamics*, 1992, eq. 6-15 to 6-22; Abe, *Vehicle Handling Dynamics*, 2009, sec. 3.3 and
3.4; Milliken & Milliken, *Race Car Vehicle Dynamics*, 1995, ch. 5). The neutral steer point is
where a lateral force produces no yaw: x_NSP = C_r L / (C_f + C_r) behind the front axle; the
static margin is its distance behind the CG over L, and K = m (C_f + C_r) SM / (C_f C_r).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.checks import is_number
from vehdyn.units import GRAVITY
from vehdyn.params import Vehicle
from vehdyn.handling.bicycle import bicycle_parameters, check_speed, speed_of

__all__ = [
    "understeer_gradient",
    "understeer_gradient_deg_per_g",
    "understeer_gradient_rad_per_g",
    "stability_factor",
    "characteristic_speed",
    "critical_speed",
    "zero_sideslip_speed",
    "SteadyStateGains",
    "steady_state_gains",
    "NeutralSteerPoint",
    "neutral_steer_point",
    "static_margin",
    "ackermann_steer_angle",
    "AckermannWheelAngles",
    "ackermann_wheel_angles",
    "steer_angle_for",
    "HandlingDiagram",
    "handling_diagram",
]


# --------------------------------------------------------------------------- understeer
def understeer_gradient(vehicle_or_bicycle) -> float:
    r"""Understeer gradient K [rad/(m/s^2)] of the linear single-track model.

    The extra road-wheel steer per unit lateral acceleration beyond the Ackermann angle L / R
    (SAE: a_y and the steer angle positive turning right):

    .. math::

        K = \frac{m}{L} \left( \frac{b}{C_f} - \frac{a}{C_r} \right)
          = \frac{W_f}{C_f} - \frac{W_r}{C_r} \text{ per unit } g,
        \qquad \delta_f - \delta_r = \frac{L}{R} + K a_y

    K > 0 understeer, K = 0 neutral steer, K < 0 oversteer. With compliance steer (the vehicle
    file's ``suspension.*_compliance_steer``) C_f, C_r are the effective stiffnesses
    C_i / (1 - (c_i - e_i t_i) C_i) of :class:`~vehdyn.handling.BicycleParameters`; for a Vehicle
    the roll steer and the camber thrust from roll are added
    (:func:`vehdyn.handling.vehicle_roll_understeer`, with the full vehicle's roll gradient), so that
    K is the road-wheel total of :func:`vehdyn.handling.understeer_budget` exactly.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).

    Returns
    -------
    float
        K [rad/(m/s^2)].

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 6, eq. 6-15 (with
       the axle loads W_f = m g b / L, W_r = m g a / L).
    .. [2] W. F. Milliken and D. L. Milliken, *Race Car Vehicle Dynamics*, SAE, 1995, ch. 5.
    """
    K = float(bicycle_parameters(vehicle_or_bicycle).understeer_gradient)
    if isinstance(vehicle_or_bicycle, Vehicle):
        from vehdyn.handling.understeer_terms import vehicle_roll_understeer

        K += sum(vehicle_roll_understeer(vehicle_or_bicycle, GRAVITY)) / GRAVITY
    return K


def understeer_gradient_rad_per_g(vehicle_or_bicycle, gravity: float = GRAVITY) -> float:
    """Understeer gradient in radians per g: K g.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).
    gravity : float, optional
        g [m/s^2] (default :data:`vehdyn.units.GRAVITY`).

    Returns
    -------
    float
        K g [rad/g] (K of :func:`understeer_gradient`).
    """
    return understeer_gradient(vehicle_or_bicycle) * gravity


def understeer_gradient_deg_per_g(vehicle_or_bicycle, gravity: float = GRAVITY) -> float:
    """Understeer gradient in degrees of road-wheel steer per g, the unit of handling tests.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).
    gravity : float, optional
        g [m/s^2] (default :data:`vehdyn.units.GRAVITY`).

    Returns
    -------
    float
        K g 180 / pi [deg/g] (K of :func:`understeer_gradient`); positive for understeer.

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.handling import understeer_gradient_deg_per_g
    >>> round(understeer_gradient_deg_per_g(vehdyn.load_vehicle("sedan")), 3)
    0.3
    """
    return float(np.rad2deg(understeer_gradient_rad_per_g(vehicle_or_bicycle, gravity)))


def stability_factor(vehicle_or_bicycle) -> float:
    """Abe's stability factor A = K / L: the yaw-rate gain is r / delta = (u / L) / (1 + A u^2).

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).

    Returns
    -------
    float
        A [s^2/m^2]; positive for understeer.

    References
    ----------
    .. [1] M. Abe, *Vehicle Handling Dynamics*, Butterworth-Heinemann, 2009, sec. 3.3.
    """
    return understeer_gradient(vehicle_or_bicycle) / bicycle_parameters(vehicle_or_bicycle).wheelbase


def characteristic_speed(vehicle_or_bicycle) -> float:
    r"""Characteristic speed of an understeering vehicle.

    The speed at which the steer angle needed on any radius is twice the Ackermann angle and at
    which the yaw-rate gain per unit speed, r / (delta u), has halved; the yaw-rate gain
    u / (L + K u^2) is largest there:

    .. math::

        u_{char} = \sqrt{L / K} \quad (K > 0)

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).

    Returns
    -------
    float
        u_char [m/s]; ``inf`` for a neutral or oversteering vehicle (K <= 0), which has none.

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 6 (the
       characteristic speed).
    .. [2] M. Abe, *Vehicle Handling Dynamics*, Butterworth-Heinemann, 2009, sec. 3.3.

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.handling import characteristic_speed
    >>> u = characteristic_speed(vehdyn.load_vehicle("sedan"))
    >>> round(u, 2), round(3.6 * u, 1)  # [m/s], [km/h]
    (69.53, 250.3)
    """
    K = understeer_gradient(vehicle_or_bicycle)
    L = bicycle_parameters(vehicle_or_bicycle).wheelbase
    return float(np.sqrt(L / K)) if K > 0 else float("inf")


def critical_speed(vehicle_or_bicycle) -> float:
    r"""Critical speed of an oversteering vehicle (K < 0).

    Above it the linear model has a real positive eigenvalue (the vehicle is directionally
    unstable: the constant term of its characteristic polynomial, proportional to L + K u^2, is
    negative) and the steady-state gains change sign:

    .. math::

        u_{crit} = \sqrt{-L / K} \quad (K < 0)

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).

    Returns
    -------
    float
        u_crit [m/s]; ``inf`` when K >= 0 (never unstable).

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 6 (the critical
       speed).
    .. [2] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 1.3 (stability of the two-degree-of-freedom model).
    """
    K = understeer_gradient(vehicle_or_bicycle)
    L = bicycle_parameters(vehicle_or_bicycle).wheelbase
    return float(np.sqrt(-L / K)) if K < 0 else float("inf")


def zero_sideslip_speed(vehicle_or_bicycle) -> float:
    """Speed at which the steady sideslip at the CG is zero (front steer only): sqrt(b L C_r / (m a)).

    Below it the CG sideslip has the sign of the steer angle, above it the opposite sign (the
    numerator b - m a u^2 / (L C_r) of beta / delta_f, module docstring).

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).

    Returns
    -------
    float
        The speed [m/s].
    """
    p = bicycle_parameters(vehicle_or_bicycle)
    return float(np.sqrt(p.b * p.wheelbase * p.rear_cornering_stiffness / (p.mass * p.a)))


# --------------------------------------------------------------------------- gains
@dataclass(frozen=True)
class SteadyStateGains:
    """Steady-state responses per unit front road-wheel steer angle, against speed.

    Attributes
    ----------
    speed : ndarray
        [m/s].
    rear_steer_ratio : ndarray
        k = delta_r / delta_f used [-].
    yaw_rate : ndarray
        r / delta_f [1/s].
    lateral_acceleration : ndarray
        a_y / delta_f [(m/s^2)/rad].
    sideslip_angle : ndarray
        beta / delta_f [rad/rad].
    path_curvature : ndarray
        (1/R) / delta_f [1/(m*rad)].
    """

    speed: np.ndarray
    rear_steer_ratio: np.ndarray
    yaw_rate: np.ndarray
    lateral_acceleration: np.ndarray
    sideslip_angle: np.ndarray
    path_curvature: np.ndarray

    @property
    def lateral_acceleration_g_per_deg(self) -> np.ndarray:
        """a_y / delta_f in g per degree of road-wheel steer."""
        return self.lateral_acceleration / GRAVITY * np.pi / 180.0

    def to_frame(self):
        """The gains as a table.

        Returns
        -------
        pandas.DataFrame
            Indexed by ``speed``; columns ``rear_steer_ratio``, ``yaw_rate``,
            ``lateral_acceleration``, ``sideslip_angle``, ``path_curvature`` (raveled against a
            speed array); units in ``attrs["units"]``.
        """
        import pandas as pd

        df = pd.DataFrame({
            "rear_steer_ratio": np.broadcast_to(self.rear_steer_ratio, self.speed.shape).ravel(),
            "yaw_rate": np.ravel(self.yaw_rate),
            "lateral_acceleration": np.ravel(self.lateral_acceleration),
            "sideslip_angle": np.ravel(self.sideslip_angle),
            "path_curvature": np.ravel(self.path_curvature),
        }, index=pd.Index(np.ravel(self.speed), name="speed"))
        df.attrs["units"] = {"speed": "m/s", "rear_steer_ratio": "-", "yaw_rate": "1/s",
                             "lateral_acceleration": "(m/s^2)/rad", "sideslip_angle": "rad/rad",
                             "path_curvature": "1/(m*rad)"}
        return df


def steady_state_gains(vehicle_or_bicycle, speed=None, *, rear_steer_ratio=0.0) -> SteadyStateGains:
    r"""Steady-state yaw-rate, lateral-acceleration, sideslip and curvature gains per unit front steer.

    The equilibrium of the linear single-track model (:class:`~vehdyn.handling.LinearBicycle`)
    with the rear wheels steered by k = delta_r / delta_f:

    .. math::

        \frac{r}{\delta_f} = \frac{u (1 - k)}{L + K u^2}, \qquad
        \frac{a_y}{\delta_f} = u \frac{r}{\delta_f}, \qquad
        \frac{1/R}{\delta_f} = \frac{1 - k}{L + K u^2}, \qquad
        \frac{\beta}{\delta_f} = k + \frac{(b - m a u^2 / (L C_r)) (1 - k)}{L + K u^2}

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).
    speed : float or array_like, optional
        Forward speed u [m/s], >= 0, broadcast against ``rear_steer_ratio``; defaults to the
        bicycle's.
    rear_steer_ratio : float or array_like
        k = delta_r / delta_f [-] (positive: rear wheels steer the same way as the front), e.g.
        :func:`~vehdyn.handling.zero_sideslip_rear_steer_ratio`; 0 for front steer only.

    Returns
    -------
    SteadyStateGains
        Per unit front road-wheel angle; at or above the critical speed the gains are those of
        the (unstable) equilibrium, infinite at u_crit exactly.

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 6 (eq. 6-15 to
       6-22: the steady-state gains of front steer).
    .. [2] M. Abe, *Vehicle Handling Dynamics*, Butterworth-Heinemann, 2009, sec. 3.3 and 3.4.

    Examples
    --------
    The sedan's yaw-rate gain [1/s] and lateral-acceleration gain [g/deg] grow with speed:

    >>> import vehdyn
    >>> from vehdyn.handling import steady_state_gains
    >>> gains = steady_state_gains(vehdyn.load_vehicle("sedan"), [10.0, 20.0, 30.0])
    >>> gains.yaw_rate.round(3).tolist()
    [3.799, 7.163, 9.807]
    >>> gains.lateral_acceleration_g_per_deg.round(4).tolist()
    [0.0676, 0.2549, 0.5234]
    """
    p = bicycle_parameters(vehicle_or_bicycle)
    u = speed_of(vehicle_or_bicycle, speed, allow_zero=True)
    k = _finite_array(rear_steer_ratio, "rear_steer_ratio")
    L, K = p.wheelbase, p.understeer_gradient
    with np.errstate(divide="ignore", invalid="ignore"):
        denominator = L + K * u**2
        yaw = u * (1.0 - k) / denominator
        beta = k + (p.b - p.mass * p.a * u**2 / (L * p.rear_cornering_stiffness)) * (1.0 - k) / denominator
        curvature = (1.0 - k) / denominator
    u_b, k_b = np.broadcast_arrays(u, k)
    return SteadyStateGains(speed=u_b, rear_steer_ratio=k_b, yaw_rate=yaw, lateral_acceleration=u * yaw,
                            sideslip_angle=beta, path_curvature=curvature)


# --------------------------------------------------------------------------- neutral steer point
class NeutralSteerPoint(NamedTuple):
    """Neutral steer point: where a lateral force on the vehicle makes no yaw moment.

    Attributes
    ----------
    from_front_axle : float
        Distance behind the front axle [m].
    behind_cg : float
        Distance behind the CG [m]; positive for an understeering vehicle.
    """

    from_front_axle: float
    behind_cg: float


def neutral_steer_point(vehicle_or_bicycle) -> NeutralSteerPoint:
    """Position of the neutral steer point: x_NSP = C_r L / (C_f + C_r) behind the front axle.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).

    Returns
    -------
    NeutralSteerPoint
        ``from_front_axle`` x_NSP [m] and ``behind_cg`` x_NSP - a [m] (positive when the point
        lies behind the CG: an understeering vehicle).

    References
    ----------
    .. [1] W. F. Milliken and D. L. Milliken, *Race Car Vehicle Dynamics*, SAE, 1995, ch. 5
       (neutral steer point and static margin).
    """
    p = bicycle_parameters(vehicle_or_bicycle)
    x = p.rear_cornering_stiffness * p.wheelbase / (p.front_cornering_stiffness + p.rear_cornering_stiffness)
    return NeutralSteerPoint(float(x), float(x - p.a))


def static_margin(vehicle_or_bicycle) -> float:
    """Static margin: the neutral steer point's distance behind the CG over the wheelbase.

    K = m (C_f + C_r) SM / (C_f C_r) (module docstring).

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).

    Returns
    -------
    float
        SM [-]; positive for understeer.
    """
    return neutral_steer_point(vehicle_or_bicycle).behind_cg / bicycle_parameters(vehicle_or_bicycle).wheelbase


# --------------------------------------------------------------------------- steer angles
def _wheelbase_of(vehicle_or_wheelbase) -> float:
    if is_number(vehicle_or_wheelbase):
        L = float(vehicle_or_wheelbase)
        if not (np.isfinite(L) and L > 0):
            raise ParameterError(f"wheelbase must be positive [m], got {L!r}", key="wheelbase", value=L)
        return L
    wheelbase = getattr(vehicle_or_wheelbase, "wheelbase", None)
    if wheelbase is not None:
        return float(wheelbase)
    return bicycle_parameters(vehicle_or_wheelbase).wheelbase


def _finite_array(value, name: str, *, finite: bool = True) -> np.ndarray:
    """``value`` as a float array; ParameterError naming ``name`` unless it holds (finite) numbers."""
    raw = np.asarray(value)
    if raw.dtype.kind not in "iuf":
        raise ParameterError(f"{name} must be a number or an array of numbers, got {type(value).__name__} "
                             f"{value!r:.80}", key=name, value=value)
    a = raw.astype(float)
    if finite and not np.all(np.isfinite(a)):
        raise ParameterError(f"{name} must be finite, got {value!r:.80}", key=name, value=value)
    return a


def _radius(radius) -> np.ndarray:
    R = _finite_array(radius, "radius", finite=False)
    if np.any(~np.isfinite(R) | (R == 0)):
        raise ParameterError(f"radius must be finite and non-zero [m], got {radius!r}", key="radius", value=radius)
    return R


def ackermann_steer_angle(vehicle_or_wheelbase, radius, *, exact: bool = False):
    """Ackermann (kinematic, low-speed) road-wheel steer angle of the single-track model [rad].

    Parameters
    ----------
    vehicle_or_wheelbase : Vehicle, LinearBicycle, BicycleParameters or float
        The vehicle, or its wheelbase L [m].
    radius : float or array_like
        Turn radius of the rear-axle centre [m]; positive for a right turn (SAE), negative left.
    exact : bool
        ``atan(L / R)`` instead of the small-angle L / R (Gillespie 1992, eq. 6-1).

    Returns
    -------
    ndarray or float
        Steer angle [rad], with the sign of the radius.
    """
    L = _wheelbase_of(vehicle_or_wheelbase)
    R = _radius(radius)
    return np.arctan(L / R) if exact else L / R


class AckermannWheelAngles(NamedTuple):
    """Road-wheel angles of the inner and outer front wheels in a kinematic turn.

    Attributes
    ----------
    inner : ndarray
        Angle of the wheel on the side of the turn centre [rad] (sign of the radius).
    outer : ndarray
        Angle of the other front wheel [rad].
    """

    inner: np.ndarray
    outer: np.ndarray


def ackermann_wheel_angles(vehicle_or_wheelbase, radius, *, track: float | None = None,
                           exact: bool = False) -> AckermannWheelAngles:
    """Inner and outer front-wheel angles of perfect Ackermann geometry.

    delta_i = L / (R - t/2), delta_o = L / (R + t/2) (Gillespie 1992, eq. 6-2), or with atan when
    ``exact``. Signs follow the radius (positive right turn, SAE); the inner wheel is on the side
    of the turn centre.

    Parameters
    ----------
    vehicle_or_wheelbase : Vehicle, LinearBicycle, BicycleParameters or float
        The vehicle, or its wheelbase L [m].
    radius : float or array_like
        Turn radius R of the rear-axle centre [m]; positive for a right turn (SAE); |R| > t / 2.
    track : float, optional
        Front track t [m]; default ``vehicle.geometry.front_track`` (needed unless a Vehicle is
        given).
    exact : bool, optional
        ``atan`` of the ratios instead of the small-angle ratios (default False).

    Returns
    -------
    AckermannWheelAngles
        ``inner`` and ``outer`` road-wheel angles [rad].
    """
    L = _wheelbase_of(vehicle_or_wheelbase)
    if track is None:
        geometry = getattr(vehicle_or_wheelbase, "geometry", None)
        if geometry is None:
            raise ParameterError("track [m] is needed unless a Vehicle is given", key="track", value=None)
        track = geometry.front_track
    if not (np.isfinite(track) and track > 0):
        raise ParameterError(f"track must be positive [m], got {track!r}", key="track", value=track)
    R = _radius(radius)
    sign = np.sign(R)
    Rabs = np.abs(R)
    if np.any(Rabs <= track / 2):
        raise ParameterError(f"radius must exceed half the track ({track / 2} m), got {radius!r}",
                             key="radius", value=radius)
    if exact:
        return AckermannWheelAngles(sign * np.arctan(L / (Rabs - track / 2)), sign * np.arctan(L / (Rabs + track / 2)))
    return AckermannWheelAngles(sign * L / (Rabs - track / 2), sign * L / (Rabs + track / 2))


def steer_angle_for(vehicle_or_bicycle, radius, speed=None, *, rear_steer_ratio=0.0):
    """Front road-wheel steer angle for a steady turn of radius ``radius`` at ``speed``.

    delta_f (1 - k) = L / R + K u^2 / R (Gillespie 1992, eq. 6-17 in consistent units), the
    Ackermann angle plus the understeer part K a_y.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).
    radius : float or array_like
        Radius R of the CG path [m], finite and non-zero; positive for a right turn (SAE).
    speed : float or array_like, optional
        Forward speed u [m/s], >= 0; defaults to the bicycle's.
    rear_steer_ratio : float or array_like, optional
        k = delta_r / delta_f [-] (default 0: front steer only).

    Returns
    -------
    float or ndarray
        delta_f [rad], with the sign of the radius (broadcast over the arguments).
    """
    p = bicycle_parameters(vehicle_or_bicycle)
    u = speed_of(vehicle_or_bicycle, speed, allow_zero=True)
    R = _radius(radius)
    k = _finite_array(rear_steer_ratio, "rear_steer_ratio")
    return (p.wheelbase / R + understeer_gradient(vehicle_or_bicycle) * u**2 / R) / (1.0 - k)


# --------------------------------------------------------------------------- handling diagram
@dataclass(frozen=True)
class HandlingDiagram:
    """Road-wheel steer angle against lateral acceleration at constant radius or constant speed.

    Attributes
    ----------
    lateral_acceleration : ndarray
        [m/s^2].
    steer_angle : ndarray
        Front road-wheel angle [rad].
    speed, radius : ndarray
        [m/s], [m] at each point (one of them constant).
    condition : str
        ``"constant radius"`` or ``"constant speed"``.
    """

    lateral_acceleration: np.ndarray
    steer_angle: np.ndarray
    speed: np.ndarray
    radius: np.ndarray
    condition: str

    def to_frame(self):
        """The diagram as a table.

        Returns
        -------
        pandas.DataFrame
            Indexed by ``lateral_acceleration``; columns ``steer_angle``, ``speed``, ``radius``;
            units in ``attrs["units"]``, the test in ``attrs["condition"]``.
        """
        import pandas as pd

        df = pd.DataFrame({"steer_angle": self.steer_angle, "speed": self.speed, "radius": self.radius},
                          index=pd.Index(self.lateral_acceleration, name="lateral_acceleration"))
        df.attrs["units"] = {"lateral_acceleration": "m/s^2", "steer_angle": "rad", "speed": "m/s", "radius": "m"}
        df.attrs["condition"] = self.condition
        return df

    def plot(self, ax=None, label: str | None = None):
        """Steer angle [deg] against lateral acceleration [g], the textbook's handling diagram.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; default a new figure.
        label : str, optional
            Legend label; default the test condition.

        Returns
        -------
        matplotlib.figure.Figure
            The figure of ``ax``.
        """
        from vehdyn.plotting import new_figure

        if ax is None:
            fig, axes = new_figure(1, 1, height_per_row=3.6)
            ax = axes[0, 0]
        ax.plot(self.lateral_acceleration / GRAVITY, np.rad2deg(self.steer_angle), label=label or self.condition)
        ax.set_xlabel("lateral acceleration [g]")
        ax.set_ylabel("road-wheel steer angle [deg]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        return ax.figure


def handling_diagram(vehicle_or_bicycle, lateral_acceleration, *, radius=None, speed=None) -> HandlingDiagram:
    """Linear handling diagram: steer angle against lateral acceleration.

    Give ``radius`` (constant-radius test, ISO 4138 method 1: u = sqrt(a_y R),
    delta = L / R + K a_y) or ``speed`` (constant-speed test: R = u^2 / a_y,
    delta = (L / u^2 + K) a_y). The slope of the constant-radius line is K; of the constant-speed
    line L / u^2 + K.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (its mass, axle positions and AXLE cornering stiffnesses, see
        :func:`~vehdyn.handling.bicycle_parameters`).
    lateral_acceleration : array_like
        a_y [m/s^2], finite (positive: the SAE right turn).
    radius : float, optional
        Radius R of the constant-radius test [m], finite and non-zero.
    speed : float, optional
        Speed u of the constant-speed test [m/s], > 0.

    Returns
    -------
    HandlingDiagram
        Steer angle [rad], speed [m/s] and radius [m] at each lateral acceleration.
    """
    if (radius is None) == (speed is None):
        raise ParameterError("give exactly one of radius or speed", key="radius", value=(radius, speed))
    ay = _finite_array(lateral_acceleration, "lateral_acceleration")
    p = bicycle_parameters(vehicle_or_bicycle)
    K = understeer_gradient(vehicle_or_bicycle)
    if radius is not None:
        R = float(_radius(radius))
        with np.errstate(invalid="ignore"):
            u = np.sqrt(ay * R)
        return HandlingDiagram(ay, p.wheelbase / R + K * ay, u, np.full_like(ay, R), "constant radius")
    u = float(check_speed(speed))
    with np.errstate(divide="ignore"):
        R = u**2 / ay
    return HandlingDiagram(ay, (p.wheelbase / u**2 + K) * ay, np.full_like(ay, u), R, "constant speed")

