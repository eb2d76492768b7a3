"""Trailer parameters: a frozen, validated :class:`Trailer` loaded from TOML.

A trailer is one rigid body on one (lumped) axle, coupled to its towing vehicle at a hitch: a
ball coupling of a drawbar trailer or caravan, or the fifth wheel (king pin) of a semitrailer.
Lengths run backwards along the trailer's centre line: the trailer's centre of gravity (CG) lies
``hitch_to_cg`` behind the hitch and its axle ``cg_to_axle`` behind the CG. A tandem or tridem
axle group is lumped into one axle at its centre with the group's cornering stiffness.

A CG behind the axle (``cg_to_axle < 0``, a negative tongue load) is accepted: it is the classic
unstable case (the trailer snakes at a much lower speed than when loaded nose-heavy) that one
wants to be able to study. Negative lengths elsewhere, zero masses or inertias, and an axle ahead
of the hitch are rejected with a :class:`~vehdyn.ParameterError` naming the field.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from vehdyn.errors import ParameterError
from vehdyn.units import GRAVITY
from vehdyn.params.base import ParameterSet, parameter, text
from vehdyn.params.vehicle import load_shipped_or_file, shipped_names

__all__ = ["Trailer", "load_trailer", "shipped_trailers"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Trailer(ParameterSet):
    """A single-axle (or lumped multi-axle) trailer: caravan, drawbar trailer or semitrailer.

    Load shipped trailers with :func:`load_trailer` (``"caravan"``, ``"semitrailer"``) and make
    variants with :meth:`replace` (``caravan.replace(mass=1500.0)``).
    """

    name: str = text("short name")
    description: str = text("what trailer this is", default="")
    source: str = text("where the numbers come from", default="")
    coupling: str = text("kind of hitch: a ball coupling (drawbar) or a fifth wheel (semitrailer)",
                         default="ball", choices=("ball", "fifth_wheel"))
    towing_vehicle: str = text("the shipped vehicle (data/vehicles) that tows it in the examples, if any",
                               default="")
    mass: float = parameter("kg", "trailer mass m_t (laden as specified)", gt=0)
    yaw_inertia: float = parameter("kg*m^2", "yaw moment of inertia I_t about the trailer CG", gt=0)
    hitch_to_cg: float = parameter("m", "e: distance from the hitch back to the trailer CG", ge=0)
    cg_to_axle: float = parameter("m", "f: distance from the trailer CG back to its axle (negative: CG behind "
                                       "the axle, a low critical speed)")
    hitch_behind_rear_axle: float = parameter(
        "m", "distance from the towing vehicle's rear axle back to the hitch (negative: ahead of it, as a fifth "
             "wheel often is)")
    cornering_stiffness: float = parameter("N/rad", "cornering stiffness of the trailer AXLE (all its tires)", gt=0)
    relaxation_length: float = parameter("m", "lateral relaxation length of the trailer tires", ge=0, default=0.0)
    friction_coefficient: float = parameter("-", "peak road-tire friction coefficient of the trailer tires", gt=0,
                                            default=0.9)
    # crosswind (optional; 0 area or slope: no wind force on the trailer). The side force follows the law of
    # vehdyn.handling.crosswind, F = 0.5 rho A C_Y' beta_w V_r^2, with rho the towing vehicle's air density
    frontal_area: float = parameter("m^2", "reference area A of the trailer's side-force coefficient (its frontal "
                                           "area; 0: no wind force on the trailer)", ge=0, default=0.0)
    side_force_coefficient_slope: float = parameter(
        "1/rad", "dC_Y/d(beta_aero) of the trailer's aerodynamic side force, referred to frontal_area", ge=0,
        default=0.0)
    centre_of_pressure_behind_hitch: float = parameter(
        "m", "distance from the hitch back to the trailer's aerodynamic centre of pressure", default=0.0)

    def check(self):
        if self.hitch_to_cg + self.cg_to_axle <= 0:
            raise ParameterError(f"cg_to_axle = {self.cg_to_axle} m puts the trailer axle at or ahead of the hitch "
                                 f"(hitch_to_cg + cg_to_axle = {self.hitch_to_cg + self.cg_to_axle} m must be > 0)",
                                 key="cg_to_axle", value=self.cg_to_axle)

    @property
    def hitch_to_axle(self) -> float:
        """l_t = e + f: the trailer's wheelbase from the hitch to its axle [m]."""
        return self.hitch_to_cg + self.cg_to_axle

    def tongue_load(self, gravity: float = GRAVITY) -> float:
        """Static vertical load on the hitch.

        Parameters
        ----------
        gravity : float, optional
            Gravitational acceleration g [m/s^2].

        Returns
        -------
        float
            m_t g f / (e + f) [N] (negative: the hitch is lifted).
        """
        return self.mass * gravity * self.cg_to_axle / self.hitch_to_axle

    def static_axle_load(self, gravity: float = GRAVITY) -> float:
        """Static load of the trailer axle.

        Parameters
        ----------
        gravity : float, optional
            Gravitational acceleration g [m/s^2].

        Returns
        -------
        float
            m_t g e / (e + f) [N].
        """
        return self.mass * gravity * self.hitch_to_cg / self.hitch_to_axle


def shipped_trailers() -> list[str]:
    """Names of the trailers shipped in ``data/trailers``.

    Returns
    -------
    list of str
        Sorted names, each loadable with :func:`load_trailer`.
    """
    return shipped_names("trailers")


def load_trailer(name_or_path: str | Path) -> Trailer:
    """Load a shipped trailer by name (``"caravan"``, ``"semitrailer"``) or a user's TOML file by path.

    Parameters
    ----------
    name_or_path : str or os.PathLike
        The name of a shipped trailer (see :func:`shipped_trailers`) or a path to a TOML file with
        the fields of :class:`Trailer` (SI units).

    Returns
    -------
    Trailer
        The validated, frozen parameter set.

    Raises
    ------
    ParameterError
        As :func:`~vehdyn.load_vehicle`: unknown name, missing or unreadable file, invalid TOML, or a
        parameter missing, unknown, of the wrong type or out of range (the message names the key).

    Examples
    --------
    >>> from vehdyn.params import load_trailer
    >>> caravan = load_trailer("caravan")
    >>> round(caravan.tongue_load()), round(caravan.static_axle_load())   # [N]
    (751, 10040)
    """
    return load_shipped_or_file(Trailer, name_or_path, "trailer")
