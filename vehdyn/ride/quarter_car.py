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
from vehdyn.ride._ride_model import Corner, RideModel

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


class QuarterCar(RideModel):
    """Quarter car as an exact :class:`~vehdyn.LinearModel`.

    Parameters
    ----------
    sprung_mass : float
        m_s [kg].
    unsprung_mass : float
        m_u [kg].
    spring_rate : float
        k_s, suspension wheel rate [N/m].
    damping : float, optional
        c_s [N*s/m] (default 0).
    tire_stiffness : float
        k_t [N/m].
    tire_damping : float, optional
        c_t [N*s/m] (default 0).
    actuator : bool, optional
        Add the input ``actuator_force`` [N] between body and wheel (active suspension).

    Notes
    -----
    States: ``sprung_displacement``, ``unsprung_displacement``, ``sprung_velocity``,
    ``unsprung_velocity``. Inputs: ``road_displacement`` and ``road_velocity`` (its time
    derivative; it enters only through the tire damping) and optionally ``actuator_force``.
    Outputs: the states, ``sprung_acceleration``, ``unsprung_acceleration``,
    ``suspension_travel``, ``suspension_velocity``, ``tire_deflection``, ``dynamic_tire_load``.

    Examples
    --------
    >>> from vehdyn.ride import QuarterCar
    >>> qc = QuarterCar(sprung_mass=250.0, unsprung_mass=35.0, spring_rate=16e3, damping=1000.0,
    ...                 tire_stiffness=160e3)
    >>> qc.modal_analysis().natural_frequency_hz.round(3).tolist()
    [1.213, 11.293]
    """

    phenomena = frozenset({"heave", "wheel_hop", "road_input"})
    _actuator_keyword = "actuator"

    def __init__(self, *, sprung_mass, unsprung_mass, spring_rate, damping=0.0, tire_stiffness, tire_damping=0.0,
                 actuator: bool = False, name: str = "quarter_car"):
        self.parameters = QuarterCarParameters(
            sprung_mass=sprung_mass, unsprung_mass=unsprung_mass, spring_rate=spring_rate, damping=damping,
            tire_stiffness=tire_stiffness, tire_damping=tire_damping)
        p = self.parameters
        corner = Corner("", 0.0, 0.0, p.spring_rate, p.damping, p.unsprung_mass, p.tire_stiffness, p.tire_damping)
        self._assemble(body_dof=("heave",), body_mass=[p.sprung_mass], corners=[corner], actuators=actuator,
                       name=name, phenomena=self.phenomena)

    @classmethod
    def from_vehicle(cls, vehicle, axle: str = "front", *, actuator: bool = False) -> "QuarterCar":
        """One corner of a shipped or user vehicle.

        Parameters
        ----------
        vehicle : Vehicle
            e.g. ``vehdyn.load_vehicle("sedan")``.
        axle : {"front", "rear"}
            The sprung mass of the corner is half the sprung mass's static share on that axle
            (from ``geometry.sprung_cg_to_front_axle``); the unsprung mass is half the axle's.
        actuator : bool
            Add the ``actuator_force`` input.
        """
        if axle not in ("front", "rear"):
            raise ParameterError(f"axle must be 'front' or 'rear', got {axle!r}", key="axle", value=axle)
        g, m, s, t = vehicle.geometry, vehicle.mass, vehicle.suspension, vehicle.tires
        share = (g.sprung_cg_to_rear_axle if axle == "front" else g.sprung_cg_to_front_axle) / g.wheelbase
        return cls(
            sprung_mass=0.5 * m.sprung_mass * share,
            unsprung_mass=0.5 * getattr(m, f"{axle}_unsprung_mass"),
            spring_rate=getattr(s, f"{axle}_spring_rate"),
            damping=getattr(s, f"{axle}_damping"),
            tire_stiffness=t.vertical_stiffness,
            tire_damping=t.vertical_damping,
            actuator=actuator,
            name=f"quarter_car_{vehicle.name}_{axle}",
        )

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
