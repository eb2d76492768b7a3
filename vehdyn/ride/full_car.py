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
from vehdyn.ride._ride_model import Corner, RideModel

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


class FullCar(RideModel):
    """Seven-degree-of-freedom full car as an exact :class:`~vehdyn.LinearModel`.

    Parameters
    ----------
    mass, roll_inertia, pitch_inertia : float
        Sprung mass [kg] and its inertias about the sprung CG [kg*m^2].
    a, b : float
        Sprung CG to front and rear axle [m].
    front_track, rear_track : float
        Tracks [m].
    front_spring_rate, rear_spring_rate, front_damping, rear_damping : float
        Per-corner wheel rates [N/m] and damping [N*s/m] (damping defaults to 0).
    front_antiroll_stiffness, rear_antiroll_stiffness : float, optional
        Anti-roll bar roll stiffnesses [N*m/rad] (default 0).
    front_unsprung_mass, rear_unsprung_mass : float
        Unsprung mass of one wheel [kg].
    front_tire_stiffness, rear_tire_stiffness, front_tire_damping, rear_tire_damping : float
        Per-tire vertical stiffness [N/m] and damping [N*s/m] (damping defaults to 0).
    sprung_cg_height, unsprung_cg_height : float, optional
        Heights of the sprung CG and of the unsprung masses above the contact points [m] (default
        0): gravity's moment and the wheels' horizontal inertia (module docstring).
    wheel_spin_inertia, rolling_radius : float, optional
        Spin inertia of one wheel [kg*m^2] (default 0) and rolling radius [m]: the wheels' share
        of the pitch inertia when the CG is above the ground.
    actuators : bool, optional
        Add an ``actuator_force_<corner>`` input per corner.

    Notes
    -----
    Corners are suffixed ``_front_left``, ``_front_right``, ``_rear_left``, ``_rear_right``
    (:data:`CORNERS`). Inputs ``road_displacement_<corner>`` then ``road_velocity_<corner>``.
    Outputs as :class:`~vehdyn.ride.BouncePitch` plus ``roll_angle``, ``roll_rate``,
    ``roll_acceleration``, all per corner.
    """

    phenomena = frozenset({"heave", "pitch", "roll", "wheel_hop", "road_input"})

    def __init__(self, *, actuators: bool = False, name: str = "full_car", **parameters):
        self.parameters = FullCarParameters(**parameters)
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

    @classmethod
    def from_vehicle(cls, vehicle, *, actuators: bool = False, cg_heights: bool = False) -> "FullCar":
        """The full car of a shipped or user vehicle (sprung inertias about the sprung CG).

        ``cg_heights=True`` keeps the couplings of the sprung CG's height (``sprung_cg_height`` the
        file's, ``unsprung_cg_height`` where it puts the total CG at the file's height, as in
        :class:`vehdyn.full_vehicle.FullVehicle`, and the wheels' spin inertia and rolling radius);
        by default the heights are 0.
        """
        g, m, s, t = vehicle.geometry, vehicle.mass, vehicle.suspension, vehicle.tires
        heights = {}
        if cg_heights:
            unsprung = (m.mass * m.cg_height - m.sprung_mass * m.sprung_cg_height) / m.unsprung_mass
            heights = dict(sprung_cg_height=m.sprung_cg_height, unsprung_cg_height=unsprung,
                           wheel_spin_inertia=t.wheel_spin_inertia, rolling_radius=t.rolling_radius)
        return cls(**heights,
            mass=m.sprung_mass, roll_inertia=m.sprung_roll_inertia, pitch_inertia=m.sprung_pitch_inertia,
            a=g.sprung_cg_to_front_axle, b=g.sprung_cg_to_rear_axle, front_track=g.front_track,
            rear_track=g.rear_track, front_spring_rate=s.front_spring_rate, rear_spring_rate=s.rear_spring_rate,
            front_damping=s.front_damping, rear_damping=s.rear_damping,
            front_antiroll_stiffness=s.front_antiroll_stiffness, rear_antiroll_stiffness=s.rear_antiroll_stiffness,
            front_unsprung_mass=0.5 * m.front_unsprung_mass, rear_unsprung_mass=0.5 * m.rear_unsprung_mass,
            front_tire_stiffness=t.vertical_stiffness, rear_tire_stiffness=t.vertical_stiffness,
            front_tire_damping=t.vertical_damping, rear_tire_damping=t.vertical_damping,
            actuators=actuators, name=f"full_car_{vehicle.name}",
        )
