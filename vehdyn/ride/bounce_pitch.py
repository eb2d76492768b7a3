"""Bounce-pitch (half-car) ride model: heave and pitch of the body, front and rear axle hop.

    m z'' = -sum_i F_i,            I_y theta'' = -sum_i x_i F_i,
    F_i = k_i (z + x_i theta - z_ui) + c_i (z' + x_i theta' - z_ui')  (suspension force, i = front, rear)
    m_ui z_ui'' = F_i + k_ti (z_ri - z_ui) + c_ti (z_ri' - z_ui')

with x_front = a, x_rear = -b (Gillespie, *Fundamentals of Vehicle Dynamics*, 1992, ch. 5
"Pitch/bounce"; Jazar, *Vehicle Dynamics*, 2008, sec. 15.3; Wong, *Theory of Ground Vehicles*,
4th ed., 2008, sec. 7.2.2). Given no unsprung masses, the wheels are the road (rigid tires) and it
is the classic 2-DOF bounce-pitch model, whose spring rates are then the axle *ride* rates.

The rear wheel meets the road the front wheel met a wheelbase earlier: rear input = front input
delayed by (a + b) / V. The model keeps independent front and rear inputs; the delay is applied by
:func:`vehdyn.ride.road_frequency_response` (exact, frequency domain),
:func:`vehdyn.ride.road_inputs` (exact, time domain) or :func:`vehdyn.ride.with_wheelbase_delay`
(Padé approximant, state space).
"""

from __future__ import annotations

import dataclasses

from vehdyn.errors import ParameterError
from vehdyn.params.base import ParameterSet, parameter
from vehdyn.ride._ride_model import Corner, RideModel, ride_model_constructor, vehicle_or_parameters

__all__ = ["BouncePitch", "BouncePitchParameters"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class BouncePitchParameters(ParameterSet):
    """Parameters of a half car; every rate is per axle (both wheels together)."""

    mass: float = parameter("kg", "sprung mass", gt=0)
    pitch_inertia: float = parameter("kg*m^2", "pitch inertia of the sprung mass about its CG", gt=0)
    a: float = parameter("m", "sprung CG to front axle", gt=0)
    b: float = parameter("m", "sprung CG to rear axle", gt=0)
    front_spring_rate: float = parameter("N/m", "front suspension rate (axle; ride rate when rigid tires)", gt=0)
    rear_spring_rate: float = parameter("N/m", "rear suspension rate (axle; ride rate when rigid tires)", gt=0)
    front_damping: float = parameter("N*s/m", "front suspension damping (axle)", ge=0, default=0.0)
    rear_damping: float = parameter("N*s/m", "rear suspension damping (axle)", ge=0, default=0.0)
    front_unsprung_mass: float = parameter("kg", "front unsprung mass (axle); 0 = rigid tire", ge=0, default=0.0)
    rear_unsprung_mass: float = parameter("kg", "rear unsprung mass (axle); 0 = rigid tire", ge=0, default=0.0)
    front_tire_stiffness: float = parameter("N/m", "front tire stiffness (axle); 0 without unsprung mass", ge=0,
                                            default=0.0)
    rear_tire_stiffness: float = parameter("N/m", "rear tire stiffness (axle); 0 without unsprung mass", ge=0,
                                           default=0.0)
    front_tire_damping: float = parameter("N*s/m", "front tire damping (axle)", ge=0, default=0.0)
    rear_tire_damping: float = parameter("N*s/m", "rear tire damping (axle)", ge=0, default=0.0)

    def check(self):
        for axle in ("front", "rear"):
            mu = getattr(self, f"{axle}_unsprung_mass")
            kt = getattr(self, f"{axle}_tire_stiffness")
            if mu > 0 and kt == 0:
                raise ParameterError(f"{axle}_tire_stiffness is needed with {axle}_unsprung_mass = {mu} kg",
                                     key=f"{axle}_tire_stiffness", value=kt)
            if mu == 0 and kt > 0:
                raise ParameterError(
                    f"{axle}_tire_stiffness = {kt} N/m given without an unsprung mass: with rigid wheels give the "
                    f"ride rate k_s k_t / (k_s + k_t) as {axle}_spring_rate instead", key=f"{axle}_tire_stiffness",
                    value=kt)

    @property
    def wheelbase(self) -> float:
        return self.a + self.b


_EXAMPLE = "mass=..., pitch_inertia=..., a=..., b=..., front_spring_rate=..., rear_spring_rate=..."


class BouncePitch(RideModel):
    r"""Half car in the pitch plane (bounce and pitch of the body, front and rear axle hop), an exact LinearModel.

    Parameters
    ----------
    vehicle : Vehicle or BouncePitchParameters
        A shipped or user vehicle (``vehdyn.load_vehicle("sedan")``), whose two corners of each
        axle are lumped into one (rates, dampings and masses doubled, the sprung mass and pitch
        inertia about the sprung CG from ``vehicle.mass``), or the half car's numbers (build those
        with :meth:`from_parameters`).
    unsprung : bool, optional
        With a Vehicle. True (default): 4 DOF with the axles' unsprung masses and tires. False:
        the classic 2-DOF model whose axle rates are the ride rates k_s k_t / (k_s + k_t) (tire
        compliance kept, wheel mass and the tire's series effect on the damper neglected). Not
        used with a BouncePitchParameters.
    actuators : bool, optional
        Add ``actuator_force_front`` and ``actuator_force_rear`` inputs [N] (default False).
    name : str, optional
        The model's name; default ``"bounce_pitch_<vehicle>"``, or ``"bounce_pitch"`` with a
        BouncePitchParameters.

    Attributes
    ----------
    parameters : BouncePitchParameters
        The validated numbers (per axle).

    Raises
    ------
    ParameterError
        When ``vehicle`` is neither a Vehicle nor a BouncePitchParameters (numbers, a dict, None:
        the message says to call :meth:`from_parameters`).

    Notes
    -----
    Heave z of the sprung CG (up), pitch theta (SAE: nose up), the axles at x_f = a ahead of and
    x_r = -b behind the sprung CG, each with a suspension force F_i on its wheel of height z_ui
    (the road z_ri itself when the axle has no unsprung mass: a rigid tire), f_i the actuator
    force extending the suspension:

    .. math::

        m \ddot z &= \sum_i (f_i - F_i), \qquad
        I_y \ddot\theta = \sum_i x_i (f_i - F_i), \\
        F_i &= k_i (z + x_i \theta - z_{ui}) + c_i (\dot z + x_i \dot\theta - \dot z_{ui}), \\
        m_{ui} \ddot z_{ui} &= F_i - f_i + k_{ti} (z_{ri} - z_{ui}) + c_{ti} (\dot z_{ri} - \dot z_{ui}),
        \qquad i \in \{f, r\}

    with m [kg] and I_y [kg*m^2] the sprung mass and its pitch inertia about the sprung CG, and
    per axle (both wheels together) k_i [N/m], c_i [N*s/m] the suspension rate and damping,
    m_ui [kg] the unsprung mass, k_ti [N/m], c_ti [N*s/m] the tire stiffness and damping. The rear
    wheel meets the road the front met a wheelbase earlier, tau = (a + b) / V: the model keeps
    independent front and rear road inputs; :func:`~vehdyn.ride.road_frequency_response`,
    :func:`~vehdyn.ride.road_inputs` and :func:`~vehdyn.ride.with_wheelbase_delay` apply the delay.

    Coordinates ``sprung_displacement``, ``pitch_angle`` and, per axle with mass,
    ``unsprung_displacement_front``/``_rear``. Inputs ``road_displacement_front``,
    ``road_displacement_rear``, ``road_velocity_front``, ``road_velocity_rear`` (and actuator
    forces). Outputs: body heave, pitch and their rates and accelerations, the body's vertical
    acceleration above each axle (``sprung_acceleration_front``/``_rear``), and per axle the wheel
    motion, ``suspension_travel``, ``suspension_velocity``, ``tire_deflection`` and
    ``dynamic_tire_load`` with suffixes ``_front``/``_rear``.

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5, "Pitch/bounce
       frequencies".
    .. [2] R. N. Jazar, *Vehicle Dynamics: Theory and Application*, Springer, 2008, sec. 15.3.
    .. [3] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 7.2.2.

    Examples
    --------
    >>> from vehdyn.ride import BouncePitch
    >>> bp = BouncePitch.from_parameters(mass=1600.0, pitch_inertia=1600.0 * 0.95**2, a=1.3, b=1.6,
    ...                                  front_spring_rate=38e3, rear_spring_rate=34e3)
    >>> bp.modal_analysis().natural_frequency_hz.round(4).tolist()
    [1.0655, 1.6303]
    """

    phenomena = frozenset({"heave", "pitch", "wheel_hop", "road_input"})

    @ride_model_constructor(BouncePitchParameters, _EXAMPLE)
    def __init__(self, vehicle, *, unsprung: bool = True, actuators: bool = False, name: str | None = None):
        vehicle = vehicle_or_parameters("BouncePitch", vehicle, BouncePitchParameters, _EXAMPLE)
        if isinstance(vehicle, BouncePitchParameters):
            self.parameters = vehicle
            name = "bounce_pitch" if name is None else name
        else:
            self.parameters = _half_car(vehicle, unsprung)
            name = f"bounce_pitch_{vehicle.name}" if name is None else name
        p = self.parameters
        corners = [
            Corner("_front", p.a, 0.0, p.front_spring_rate, p.front_damping, p.front_unsprung_mass,
                   p.front_tire_stiffness, p.front_tire_damping),
            Corner("_rear", -p.b, 0.0, p.rear_spring_rate, p.rear_damping, p.rear_unsprung_mass,
                   p.rear_tire_stiffness, p.rear_tire_damping),
        ]
        phenomena = self.phenomena if p.front_unsprung_mass + p.rear_unsprung_mass > 0 else \
            self.phenomena - {"wheel_hop"}
        self._assemble(body_dof=("heave", "pitch"), body_mass=[p.mass, p.pitch_inertia], corners=corners,
                       actuators=actuators, name=name, phenomena=phenomena)

    @classmethod
    def from_parameters(cls, *, actuators: bool = False, name: str = "bounce_pitch",
                        **parameters) -> "BouncePitch":
        """A half car from the numbers of a textbook problem (every rate per axle: both wheels).

        Parameters
        ----------
        **parameters
            The fields of :class:`BouncePitchParameters`:

            mass, pitch_inertia : float
                Sprung mass [kg] and its pitch inertia about the sprung CG [kg*m^2].
            a, b : float
                Distances from the sprung CG to the front and rear axles [m].
            front_spring_rate, rear_spring_rate : float
                Axle suspension rates [N/m]; with no unsprung mass, the axle ride rates.
            front_damping, rear_damping : float, optional
                Axle damping [N*s/m] (default 0).
            front_unsprung_mass, rear_unsprung_mass : float, optional
                Axle unsprung masses [kg]; 0 (default) makes the wheel rigid on the road.
            front_tire_stiffness, rear_tire_stiffness : float, optional
                Axle tire stiffnesses [N/m] (needed with an unsprung mass, 0 without).
            front_tire_damping, rear_tire_damping : float, optional
                Axle tire damping [N*s/m] (default 0).
        actuators : bool, optional
            Add ``actuator_force_front`` and ``actuator_force_rear`` inputs [N] (default False).
        name : str, optional
            The model's name (default ``"bounce_pitch"``).

        Returns
        -------
        BouncePitch
            ``BouncePitch(BouncePitchParameters(**parameters), actuators=actuators, name=name)``.

        Raises
        ------
        ParameterError
            Naming the first number that is missing, unknown, not finite or out of its range, or
            a tire stiffness without an unsprung mass (and the reverse).
        """
        return cls(BouncePitchParameters.from_dict(parameters), actuators=actuators, name=name)

    @property
    def wheelbase(self) -> float:
        """a + b [m]."""
        return self.parameters.wheelbase


def _half_car(vehicle, unsprung: bool) -> BouncePitchParameters:
    """The half car of a Vehicle: corner rates doubled to axle rates (see :class:`BouncePitch`)."""
    g, m, s, t = vehicle.geometry, vehicle.mass, vehicle.suspension, vehicle.tires
    kw = dict(mass=m.sprung_mass, pitch_inertia=m.sprung_pitch_inertia, a=g.sprung_cg_to_front_axle,
              b=g.sprung_cg_to_rear_axle, front_damping=2 * s.front_damping, rear_damping=2 * s.rear_damping)
    for axle in ("front", "rear"):
        ks = 2 * getattr(s, f"{axle}_spring_rate")
        kt = 2 * t.vertical_stiffness
        if unsprung:
            kw.update({f"{axle}_spring_rate": ks, f"{axle}_unsprung_mass": getattr(m, f"{axle}_unsprung_mass"),
                       f"{axle}_tire_stiffness": kt, f"{axle}_tire_damping": 2 * t.vertical_damping})
        else:
            kw[f"{axle}_spring_rate"] = ks * kt / (ks + kt)
    return BouncePitchParameters(**kw)
