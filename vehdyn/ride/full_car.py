"""Full-car ride model: heave, pitch and roll of the body and four wheel hops (7 DOF), anti-roll bars.

Body point above corner i (x_i ahead of the sprung CG, y_i to the right, SAE) moves up by
z + x_i theta - y_i phi; the suspension extension is d_i = z + x_i theta - y_i phi - z_ui and

    m z'' = -sum F_i,   I_y theta'' = -sum x_i F_i,   I_x phi'' = sum y_i F_i,
    F_i = k_i d_i + c_i d_i' + (anti-roll bar force),   m_ui z_ui'' = F_i + k_ti (z_ri - z_ui) + c_ti (z_ri' - z_ui')

(Jazar, *Vehicle Dynamics*, 2008, sec. 15.5 "Full car vibrating model"; Gillespie, *Fundamentals
of Vehicle Dynamics*, 1992, ch. 5). An anti-roll bar of roll stiffness K_arb [N*m/rad] over track t
is a spring of rate K_arb / t^2 on the difference of the left and right suspension extensions, so
that a body roll phi with fixed wheels meets the moment K_arb phi from the bar.
"""

from __future__ import annotations

import dataclasses

from vehdyn.params.base import ParameterSet, parameter
from vehdyn.errors import ParameterError
from vehdyn.units import GRAVITY
from vehdyn.ride._ride_model import Corner, RideModel, ride_model_constructor, vehicle_or_parameters

__all__ = ["FullCar", "FullCarParameters", "CORNERS"]

#: Corner suffixes in input order.
CORNERS = ("_front_left", "_front_right", "_rear_left", "_rear_right")


@dataclasses.dataclass(frozen=True, kw_only=True)
class FullCarParameters(ParameterSet):
    """Parameters of a full car; springs, dampers, tires and unsprung masses per corner."""

    mass: float = parameter("kg", "sprung mass", gt=0)
    roll_inertia: float = parameter("kg*m^2", "roll inertia of the sprung mass about its CG", gt=0)
    pitch_inertia: float = parameter("kg*m^2", "pitch inertia of the sprung mass about its CG", gt=0)
    a: float = parameter("m", "sprung CG to front axle", gt=0)
    b: float = parameter("m", "sprung CG to rear axle", gt=0)
    front_track: float = parameter("m", "front track", gt=0)
    rear_track: float = parameter("m", "rear track", gt=0)
    front_spring_rate: float = parameter("N/m", "front suspension wheel rate (per corner)", gt=0)
    rear_spring_rate: float = parameter("N/m", "rear suspension wheel rate (per corner)", gt=0)
    front_damping: float = parameter("N*s/m", "front damping (per corner)", ge=0, default=0.0)
    rear_damping: float = parameter("N*s/m", "rear damping (per corner)", ge=0, default=0.0)
    front_antiroll_stiffness: float = parameter("N*m/rad", "front anti-roll bar roll stiffness", ge=0, default=0.0)
    rear_antiroll_stiffness: float = parameter("N*m/rad", "rear anti-roll bar roll stiffness", ge=0, default=0.0)
    front_unsprung_mass: float = parameter("kg", "unsprung mass of one front wheel", gt=0)
    rear_unsprung_mass: float = parameter("kg", "unsprung mass of one rear wheel", gt=0)
    front_tire_stiffness: float = parameter("N/m", "vertical stiffness of one front tire", gt=0)
    rear_tire_stiffness: float = parameter("N/m", "vertical stiffness of one rear tire", gt=0)
    front_tire_damping: float = parameter("N*s/m", "vertical damping of one front tire", ge=0, default=0.0)
    rear_tire_damping: float = parameter("N*s/m", "vertical damping of one rear tire", ge=0, default=0.0)
    sprung_cg_height: float = parameter("m", "height of the sprung CG above the contact points (0: the "
                                        "couplings of the height left out)", ge=0, default=0.0)
    unsprung_cg_height: float = parameter("m", "height of the unsprung masses above the contact points",
                                          ge=0, default=0.0)
    wheel_spin_inertia: float = parameter("kg*m^2", "spin inertia of one wheel (with sprung_cg_height: the wheels "
                                          "spin as the contact points move fore and aft)", ge=0, default=0.0)
    rolling_radius: float = parameter("m", "rolling radius of the wheels (for wheel_spin_inertia)", gt=0,
                                      default=0.3)

    @property
    def wheelbase(self) -> float:
        return self.a + self.b


_EXAMPLE = ("mass=..., roll_inertia=..., pitch_inertia=..., a=..., b=..., front_track=..., rear_track=..., "
            "front_spring_rate=..., rear_spring_rate=..., front_unsprung_mass=..., rear_unsprung_mass=..., "
            "front_tire_stiffness=..., rear_tire_stiffness=...")


class FullCar(RideModel):
    r"""Seven-degree-of-freedom full car (heave, pitch, roll, four wheel hops), anti-roll bars, an exact LinearModel.

    Parameters
    ----------
    vehicle : Vehicle or FullCarParameters
        A shipped or user vehicle (``vehdyn.load_vehicle("sedan")``): the sprung mass and its
        inertias about the sprung CG, the sprung CG's distances to the axles, the tracks, the
        per-corner springs, dampers, unsprung masses and tires and the anti-roll bars of the file.
        Or the full car's numbers (build those with :meth:`from_parameters`).
    cg_heights : bool, optional
        With a Vehicle: keep the couplings of the sprung CG's height above the ground
        (``sprung_cg_height`` the file's; ``unsprung_cg_height`` where it puts the total CG at the
        file's height, as in :class:`vehdyn.full_vehicle.FullVehicle`; the wheels' spin inertia
        and rolling radius). Default False: both heights 0. Not used with a FullCarParameters.
    actuators : bool, optional
        Add an ``actuator_force_<corner>`` input [N] per corner (default False).
    name : str, optional
        The model's name; default ``"full_car_<vehicle>"``, or ``"full_car"`` with a
        FullCarParameters.

    Attributes
    ----------
    parameters : FullCarParameters
        The validated numbers (per corner).

    Raises
    ------
    ParameterError
        When ``vehicle`` is neither a Vehicle nor a FullCarParameters (numbers, a dict, None: the
        message says to call :meth:`from_parameters`), or when gravity's moment m g h_s exceeds the
        suspension's pitch or roll stiffness (the body would tip over).

    Notes
    -----
    Heave z of the sprung CG (up), pitch theta (SAE: nose up), roll phi (SAE: right side down).
    Corner i sits x_i ahead of and y_i to the right of the sprung CG (x = a front, -b rear;
    y = -t/2 left, +t/2 right, t the axle's track); its suspension extension is d_i and its
    suspension force F_i, with an anti-roll bar of roll stiffness K_arb a spring K_arb / t^2 on
    the difference of the left and right extensions of its axle (+ on the left corner, - on the
    right); f_i is the actuator force extending the suspension:

    .. math::

        d_i &= z + x_i \theta - y_i \phi - z_{ui}, \qquad
        F_i = k_i d_i + c_i \dot d_i \pm \frac{K_{arb}}{t^2} (d_{left} - d_{right}), \\
        m \ddot z &= \sum_i (f_i - F_i), \\
        I_y' \ddot\theta &= \sum_i x_i (f_i - F_i) + m g h_s \theta, \\
        I_x' \ddot\phi &= \sum_i y_i (F_i - f_i) + m g h_s \phi, \\
        m_{ui} \ddot z_{ui} &= F_i - f_i + k_{ti} (z_{ri} - z_{ui}) + c_{ti} (\dot z_{ri} - \dot z_{ui}), \\
        I_y' &= I_y + m_u (h_s - h_u)^2 + 4 I_w (h_s / R_e)^2, \qquad
        I_x' = I_x + m_u (h_s - h_u)^2

    with m [kg], I_x, I_y [kg*m^2] the sprung mass and its inertias about the sprung CG, per corner
    k_i [N/m], c_i [N*s/m] the wheel rate and damping, m_ui [kg] the unsprung mass and
    k_ti [N/m], c_ti [N*s/m] the tire's stiffness and damping, m_u the four unsprung masses
    together, h_s and h_u the heights of the sprung CG and of the unsprung masses above the
    contact points [m], I_w the spin inertia of one wheel and R_e its rolling radius. With the CG
    above the ground, gravity's moment m g h_s destabilizes pitch and roll, the unsprung masses
    move fore-aft and sideways with the body about the sprung CG and the wheels spin as the contact
    points move fore and aft (rolling without slip); with h_s = h_u = 0 (the default) those terms
    vanish.

    Corners are suffixed ``_front_left``, ``_front_right``, ``_rear_left``, ``_rear_right``
    (:data:`CORNERS`). Inputs ``road_displacement_<corner>`` then ``road_velocity_<corner>``.
    Outputs as :class:`~vehdyn.ride.BouncePitch` plus ``roll_angle``, ``roll_rate``,
    ``roll_acceleration``, all per corner.

    References
    ----------
    .. [1] R. N. Jazar, *Vehicle Dynamics: Theory and Application*, Springer, 2008, sec. 15.5,
       "Full car vibrating model".
    .. [2] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5 (ride rates,
       pitch and bounce) and ch. 9 (roll stiffness of springs and anti-roll bars).
    .. [3] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 7.2.

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.ride import FullCar, ride_modes
    >>> car = FullCar(vehdyn.load_vehicle("sedan"))
    >>> modes = ride_modes(car)
    >>> modes.labels[:3]
    ('body bounce', 'pitch', 'roll')
    >>> modes.undamped_frequency_hz[:3].round(3).tolist()
    [1.42, 1.436, 2.303]
    """

    phenomena = frozenset({"heave", "pitch", "roll", "wheel_hop", "road_input"})

    @ride_model_constructor(FullCarParameters, _EXAMPLE)
    def __init__(self, vehicle, *, cg_heights: bool = False, actuators: bool = False, name: str | None = None):
        vehicle = vehicle_or_parameters("FullCar", vehicle, FullCarParameters, _EXAMPLE)
        if isinstance(vehicle, FullCarParameters):
            self.parameters = vehicle
            name = "full_car" if name is None else name
        else:
            self.parameters = _full_car(vehicle, cg_heights)
            name = f"full_car_{vehicle.name}" if name is None else name
        p = self.parameters
        corners = []
        for axle, x, track in (("front", p.a, p.front_track), ("rear", -p.b, p.rear_track)):
            for side, y in (("left", -0.5 * track), ("right", 0.5 * track)):
                corners.append(Corner(
                    f"_{axle}_{side}", x, y, getattr(p, f"{axle}_spring_rate"), getattr(p, f"{axle}_damping"),
                    getattr(p, f"{axle}_unsprung_mass"), getattr(p, f"{axle}_tire_stiffness"),
                    getattr(p, f"{axle}_tire_damping"), track=side))
        antiroll = [(0, 1, p.front_antiroll_stiffness / p.front_track**2),
                    (2, 3, p.rear_antiroll_stiffness / p.rear_track**2)]
        # the CG above the contact points: gravity's moment on the pitched or rolled body and the
        # unsprung masses' fore-aft and sideways inertia about the sprung CG
        lever = p.sprung_cg_height - p.unsprung_cg_height
        wheels = 2.0 * (p.front_unsprung_mass + p.rear_unsprung_mass) * lever**2
        spin = 4.0 * p.wheel_spin_inertia * (p.sprung_cg_height / p.rolling_radius) ** 2
        tilt = -p.mass * GRAVITY * p.sprung_cg_height
        pitch_stiffness = 2.0 * (p.front_spring_rate * p.a**2 + p.rear_spring_rate * p.b**2)
        roll_stiffness = (0.5 * p.front_spring_rate * p.front_track**2 + 0.5 * p.rear_spring_rate * p.rear_track**2
                          + p.front_antiroll_stiffness + p.rear_antiroll_stiffness)
        if min(pitch_stiffness, roll_stiffness) + tilt <= 0:
            raise ParameterError(f"sprung_cg_height = {p.sprung_cg_height} m: gravity's moment m g h = {-tilt:.4g} "
                                 f"N*m/rad exceeds the suspension's pitch ({pitch_stiffness:.4g}) or roll "
                                 f"({roll_stiffness:.4g}) stiffness [N*m/rad]: the body would tip over",
                                 key="sprung_cg_height", value=p.sprung_cg_height)
        self._assemble(body_dof=("heave", "pitch", "roll"),
                       body_mass=[p.mass, p.pitch_inertia + wheels + spin, p.roll_inertia + wheels],
                       corners=corners, antiroll=antiroll, actuators=actuators, name=name,
                       phenomena=self.phenomena, body_stiffness=[0.0, tilt, tilt])

    @classmethod
    def from_parameters(cls, *, actuators: bool = False, name: str = "full_car", **parameters) -> "FullCar":
        """A full car from the numbers of a textbook problem (springs, dampers and tires per corner).

        Parameters
        ----------
        **parameters
            The fields of :class:`FullCarParameters`:

            mass, roll_inertia, pitch_inertia : float
                Sprung mass [kg] and its inertias about the sprung CG [kg*m^2].
            a, b : float
                Sprung CG to front and rear axle [m].
            front_track, rear_track : float
                Tracks [m].
            front_spring_rate, rear_spring_rate : float
                Wheel rates of one corner [N/m].
            front_damping, rear_damping : float, optional
                Damping of one corner [N*s/m] (default 0).
            front_antiroll_stiffness, rear_antiroll_stiffness : float, optional
                Anti-roll bar roll stiffnesses [N*m/rad] (default 0).
            front_unsprung_mass, rear_unsprung_mass : float
                Unsprung mass of one wheel [kg].
            front_tire_stiffness, rear_tire_stiffness : float
                Vertical stiffness of one tire [N/m].
            front_tire_damping, rear_tire_damping : float, optional
                Vertical damping of one tire [N*s/m] (default 0).
            sprung_cg_height, unsprung_cg_height : float, optional
                Heights of the sprung CG and of the unsprung masses above the contact points [m]
                (default 0: the couplings of the height left out; see the class's Notes).
            wheel_spin_inertia : float, optional
                Spin inertia of one wheel [kg*m^2] (default 0).
            rolling_radius : float, optional
                Rolling radius of the wheels [m] (default 0.3; used with ``wheel_spin_inertia``).
        actuators : bool, optional
            Add an ``actuator_force_<corner>`` input [N] per corner (default False).
        name : str, optional
            The model's name (default ``"full_car"``).

        Returns
        -------
        FullCar
            ``FullCar(FullCarParameters(**parameters), actuators=actuators, name=name)``.

        Raises
        ------
        ParameterError
            Naming the first number that is missing, unknown, not finite or out of its range.
        """
        return cls(FullCarParameters.from_dict(parameters), actuators=actuators, name=name)

    @property
    def wheelbase(self) -> float:
        """a + b [m]."""
        return self.parameters.wheelbase

    @property
    def roll_stiffness(self) -> float:
        """Suspension roll stiffness with the wheels held [N*m/rad]: sum k_i y_i^2 + anti-roll bars."""
        p = self.parameters
        return (0.5 * p.front_spring_rate * p.front_track**2 + 0.5 * p.rear_spring_rate * p.rear_track**2
                + p.front_antiroll_stiffness + p.rear_antiroll_stiffness)


def _full_car(vehicle, cg_heights: bool) -> FullCarParameters:
    """The :class:`FullCarParameters` of a Vehicle (sprung inertias about the sprung CG; see :class:`FullCar`)."""
    g, m, s, t = vehicle.geometry, vehicle.mass, vehicle.suspension, vehicle.tires
    heights = {}
    if cg_heights:
        unsprung = (m.mass * m.cg_height - m.sprung_mass * m.sprung_cg_height) / m.unsprung_mass
        heights = dict(sprung_cg_height=m.sprung_cg_height, unsprung_cg_height=unsprung,
                       wheel_spin_inertia=t.wheel_spin_inertia, rolling_radius=t.rolling_radius)
    return FullCarParameters(
        **heights,
        mass=m.sprung_mass, roll_inertia=m.sprung_roll_inertia, pitch_inertia=m.sprung_pitch_inertia,
        a=g.sprung_cg_to_front_axle, b=g.sprung_cg_to_rear_axle, front_track=g.front_track,
        rear_track=g.rear_track, front_spring_rate=s.front_spring_rate, rear_spring_rate=s.rear_spring_rate,
        front_damping=s.front_damping, rear_damping=s.rear_damping,
        front_antiroll_stiffness=s.front_antiroll_stiffness, rear_antiroll_stiffness=s.rear_antiroll_stiffness,
        front_unsprung_mass=0.5 * m.front_unsprung_mass, rear_unsprung_mass=0.5 * m.rear_unsprung_mass,
        front_tire_stiffness=t.vertical_stiffness, rear_tire_stiffness=t.vertical_stiffness,
        front_tire_damping=t.vertical_damping, rear_tire_damping=t.vertical_damping)
