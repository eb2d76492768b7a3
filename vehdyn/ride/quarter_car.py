"""Quarter-car ride model: sprung and unsprung mass on a suspension and a tire (2 DOF).

    m_s z_s'' = -k_s (z_s - z_u) - c_s (z_s' - z_u') + f
    m_u z_u'' =  k_s (z_s - z_u) + c_s (z_s' - z_u') + k_t (z_r - z_u) + c_t (z_r' - z_u') - f

(Gillespie, *Fundamentals of Vehicle Dynamics*, 1992, ch. 5, "Quarter-car model"; Wong, *Theory of
Ground Vehicles*, 4th ed., 2008, sec. 7.2.1; Jazar, *Vehicle Dynamics*, 2008, sec. 14.1). Signs and
output definitions: see :mod:`vehdyn.ride._ride_model` (displacements up; suspension travel
positive in rebound; tire deflection and dynamic tire load positive in compression).
"""

from __future__ import annotations

import dataclasses

from vehdyn.errors import ParameterError
from vehdyn.params.base import ParameterSet, parameter
from vehdyn.ride._ride_model import Corner, RideModel, ride_model_constructor, vehicle_or_parameters

__all__ = ["QuarterCar", "QuarterCarParameters"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class QuarterCarParameters(ParameterSet):
    """Parameters of one corner of a vehicle."""

    sprung_mass: float = parameter("kg", "sprung mass carried by the corner", gt=0)
    unsprung_mass: float = parameter("kg", "unsprung mass of the wheel", gt=0)
    spring_rate: float = parameter("N/m", "suspension spring rate at the wheel (wheel rate)", gt=0)
    damping: float = parameter("N*s/m", "suspension damping at the wheel", ge=0, default=0.0)
    tire_stiffness: float = parameter("N/m", "tire vertical stiffness", gt=0)
    tire_damping: float = parameter("N*s/m", "tire vertical damping", ge=0, default=0.0)


_EXAMPLE = "sprung_mass=..., unsprung_mass=..., spring_rate=..., damping=..., tire_stiffness=..."


class QuarterCar(RideModel):
    r"""Quarter car: one corner's sprung and unsprung mass on a suspension and a tire, an exact LinearModel.

    Parameters
    ----------
    vehicle : Vehicle or QuarterCarParameters
        A shipped or user vehicle (``vehdyn.load_vehicle("sedan")``), of which the corner of
        ``axle`` is taken, or the corner's numbers (build those with :meth:`from_parameters`).
    axle : {"front", "rear"}
        With a Vehicle: the corner's sprung mass is half the sprung mass's static share on that
        axle, m_s = (m_sprung / 2) (b_s / L) for the front (a_s / L for the rear; a_s, b_s from the
        sprung CG to the axles, ``geometry.sprung_cg_to_front_axle``), the unsprung mass half the
        axle's, the spring rate and damping the axle's per-corner values, the tire's vertical
        stiffness and damping ``vehicle.tires``'. Not used with a QuarterCarParameters.
    actuator : bool, optional
        Add the input ``actuator_force`` [N] between body and wheel (active suspension). Default
        False.
    name : str, optional
        The model's name; default ``"quarter_car_<vehicle>_<axle>"``, or ``"quarter_car"`` with a
        QuarterCarParameters.

    Attributes
    ----------
    parameters : QuarterCarParameters
        The validated numbers.

    Raises
    ------
    ParameterError
        When ``vehicle`` is neither a Vehicle nor a QuarterCarParameters (numbers, a dict, None:
        the message says to call :meth:`from_parameters`), or ``axle`` is not front or rear.

    Notes
    -----
    Coordinates measured up from static equilibrium, as road elevations are (ISO 8608): the
    sprung mass's heave z_s, the wheel's z_u, the road's z_r under the wheel; f the actuator force
    extending the suspension (up on the body):

    .. math::

        m_s \ddot z_s &= -k_s (z_s - z_u) - c_s (\dot z_s - \dot z_u) + f \\
        m_u \ddot z_u &= k_s (z_s - z_u) + c_s (\dot z_s - \dot z_u)
                         + k_t (z_r - z_u) + c_t (\dot z_r - \dot z_u) - f

    with m_s, m_u [kg] the sprung and unsprung masses, k_s [N/m] and c_s [N*s/m] the suspension
    wheel rate and damping, k_t [N/m] and c_t [N*s/m] the tire's vertical stiffness and damping.
    Outputs: ``suspension_travel`` z_s - z_u (rebound +), ``tire_deflection`` z_r - z_u
    (compression +), ``dynamic_tire_load`` k_t (z_r - z_u) + c_t (z_r' - z_u') [N] (more load +).

    States: ``sprung_displacement``, ``unsprung_displacement``, ``sprung_velocity``,
    ``unsprung_velocity``. Inputs: ``road_displacement`` and ``road_velocity`` (its time
    derivative; it enters only through the tire damping) and optionally ``actuator_force``.
    Outputs: the states, ``sprung_acceleration``, ``unsprung_acceleration``,
    ``suspension_travel``, ``suspension_velocity``, ``tire_deflection``, ``dynamic_tire_load``.

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5, "Quarter-car
       model" (eq. 5-6 for the ride rate, 5-7 and 5-8 for the natural frequencies).
    .. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 7.2.1.
    .. [3] R. N. Jazar, *Vehicle Dynamics: Theory and Application*, Springer, 2008, sec. 14.1.

    Examples
    --------
    From the numbers of a textbook problem:

    >>> from vehdyn.ride import QuarterCar
    >>> qc = QuarterCar.from_parameters(sprung_mass=250.0, unsprung_mass=35.0, spring_rate=16e3,
    ...                                 damping=1000.0, tire_stiffness=160e3)
    >>> qc.modal_analysis().natural_frequency_hz.round(3).tolist()
    [1.213, 11.293]

    The front corner of a shipped vehicle:

    >>> import vehdyn
    >>> front = QuarterCar(vehdyn.load_vehicle("sedan"), axle="front")
    >>> front.name, round(front.parameters.sprung_mass, 1)
    ('quarter_car_sedan_front', 266.4)
    """

    phenomena = frozenset({"heave", "wheel_hop", "road_input"})
    _actuator_keyword = "actuator"

    @ride_model_constructor(QuarterCarParameters, _EXAMPLE)
    def __init__(self, vehicle, axle: str = "front", *, actuator: bool = False, name: str | None = None):
        vehicle = vehicle_or_parameters("QuarterCar", vehicle, QuarterCarParameters, _EXAMPLE)
        if axle not in ("front", "rear"):
            raise ParameterError(f"axle must be 'front' or 'rear', got {axle!r}", key="axle", value=axle)
        if isinstance(vehicle, QuarterCarParameters):
            self.parameters = vehicle
            name = "quarter_car" if name is None else name
        else:
            g, m, s, t = vehicle.geometry, vehicle.mass, vehicle.suspension, vehicle.tires
            share = (g.sprung_cg_to_rear_axle if axle == "front" else g.sprung_cg_to_front_axle) / g.wheelbase
            self.parameters = QuarterCarParameters(
                sprung_mass=0.5 * m.sprung_mass * share,
                unsprung_mass=0.5 * getattr(m, f"{axle}_unsprung_mass"),
                spring_rate=getattr(s, f"{axle}_spring_rate"),
                damping=getattr(s, f"{axle}_damping"),
                tire_stiffness=t.vertical_stiffness,
                tire_damping=t.vertical_damping)
            name = f"quarter_car_{vehicle.name}_{axle}" if name is None else name
        p = self.parameters
        corner = Corner("", 0.0, 0.0, p.spring_rate, p.damping, p.unsprung_mass, p.tire_stiffness, p.tire_damping)
        self._assemble(body_dof=("heave",), body_mass=[p.sprung_mass], corners=[corner], actuators=actuator,
                       name=name, phenomena=self.phenomena)

    @classmethod
    def from_parameters(cls, *, sprung_mass: float, unsprung_mass: float, spring_rate: float, damping: float = 0.0,
                        tire_stiffness: float, tire_damping: float = 0.0, actuator: bool = False,
                        name: str = "quarter_car") -> "QuarterCar":
        """A quarter car from the numbers of a textbook problem.

        Parameters
        ----------
        sprung_mass : float
            m_s, the sprung mass the corner carries [kg], > 0.
        unsprung_mass : float
            m_u, the wheel's unsprung mass [kg], > 0.
        spring_rate : float
            k_s, suspension rate at the wheel (wheel rate) [N/m], > 0.
        damping : float, optional
            c_s, suspension damping at the wheel [N*s/m], >= 0 (default 0).
        tire_stiffness : float
            k_t, tire vertical stiffness [N/m], > 0.
        tire_damping : float, optional
            c_t, tire vertical damping [N*s/m], >= 0 (default 0).
        actuator : bool, optional
            Add the input ``actuator_force`` [N] (default False).
        name : str, optional
            The model's name (default ``"quarter_car"``).

        Returns
        -------
        QuarterCar
            ``QuarterCar(QuarterCarParameters(...), actuator=actuator, name=name)``.

        Raises
        ------
        ParameterError
            Naming the first number that is missing, not finite or out of its range.
        """
        return cls(QuarterCarParameters(sprung_mass=sprung_mass, unsprung_mass=unsprung_mass, spring_rate=spring_rate,
                                        damping=damping, tire_stiffness=tire_stiffness, tire_damping=tire_damping),
                   actuator=actuator, name=name)

    # ------------------------------------------------------------------ textbook estimates
    @property
    def ride_rate(self) -> float:
        """k_s k_t / (k_s + k_t) [N/m]: springs in series (Gillespie 1992, eq. 5-6)."""
        p = self.parameters
        return p.spring_rate * p.tire_stiffness / (p.spring_rate + p.tire_stiffness)

    def estimates(self) -> dict[str, float]:
        """Uncoupled closed-form estimates of the two modes (Gillespie 1992, ch. 5).

        Returns
        -------
        dict
            ``ride_rate`` [N/m]; ``body_frequency_hz`` = sqrt(RR / m_s) / (2 pi);
            ``wheel_hop_frequency_hz`` = sqrt((k_s + k_t) / m_u) / (2 pi);
            ``body_damping_ratio`` = c_s / (2 sqrt(k_s m_s)).
        """
        import math

        p = self.parameters
        return {
            "ride_rate": self.ride_rate,
            "body_frequency_hz": math.sqrt(self.ride_rate / p.sprung_mass) / (2 * math.pi),
            "wheel_hop_frequency_hz": math.sqrt((p.spring_rate + p.tire_stiffness) / p.unsprung_mass) / (2 * math.pi),
            "body_damping_ratio": p.damping / (2 * math.sqrt(p.spring_rate * p.sprung_mass)),
        }
