"""Soil parameters of classical terramechanics and the shipped soil table.

A soil is described by Bekker's pressure-sinkage law ``p = (k_c / b + k_phi) z^n`` (b the smaller
dimension of the loading area, z the sinkage) and by the Mohr-Coulomb strength with the
Janosi-Hanamoto shear-displacement law ``tau = (c + sigma tan(phi)) (1 - exp(-j / K))``.

References
----------
M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press, 1969.
Z. Janosi and B. Hanamoto, "The analytical determination of drawbar pull as a function of slip for
tracked vehicles in deformable soils", 1st Int. Conf. Terrain-Vehicle Systems, Turin, 1961.
J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, ch. 2.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.base import ParameterSet, parameter, read_toml, text
from vehdyn.params.checks import is_number

__all__ = ["Soil", "load_soil", "shipped_soils", "soil_source"]

#: Factor to SI of each unit a soil table may give a parameter in (``k_c``, ``k_phi`` keep their
#: n-dependent dimension: only the force and length prefixes are converted).
_UNIT_FACTORS = {
    "k_c": {"N/m^(n+1)": 1.0, "kN/m^(n+1)": 1e3},
    "k_phi": {"N/m^(n+2)": 1.0, "kN/m^(n+2)": 1e3},
    "cohesion": {"Pa": 1.0, "kPa": 1e3},
    "friction_angle": {"rad": 1.0, "deg": math.pi / 180.0},
    "shear_modulus": {"m": 1.0, "cm": 1e-2, "mm": 1e-3},
    "lateral_shear_modulus": {"m": 1.0, "cm": 1e-2, "mm": 1e-3},
    "density": {"kg/m^3": 1.0, "g/cm^3": 1e3},
}

_SOIL_FILE = ("soils.toml",)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Soil(ParameterSet):
    r"""A deformable soil (SI units): Bekker's pressure-sinkage law and Mohr-Coulomb shear strength.

    .. math::

        p = \left(\frac{k_c}{b} + k_\phi\right) z^n, \qquad
        \tau = (c + \sigma \tan\phi) \left(1 - e^{-j / K}\right)

    (b the smaller dimension of the loading area, z the sinkage, sigma the normal stress, j the
    shear displacement: the Janosi-Hanamoto law).

    Parameters
    ----------
    n : float
        Exponent of deformation of Bekker's pressure-sinkage law [-], > 0.
    k_c : float
        Cohesive modulus of deformation [N/m^(n+1)].
    k_phi : float
        Frictional modulus of deformation [N/m^(n+2)].
    cohesion : float
        Cohesion c [Pa], >= 0.
    friction_angle : float
        Angle of internal shearing resistance phi [rad], in [0, pi/2).
    shear_modulus : float
        Shear deformation modulus K of the Janosi-Hanamoto law [m], > 0.
    lateral_shear_modulus : float, optional
        K_y for the side shear [m]; default ``shear_modulus``.
    density : float
        Bulk density [kg/m^3], for the bulldozing (passive earth pressure) terms; default 1600.
    name : str
        A label (the shipped table's key).

    Notes
    -----
    ``k_c / b + k_phi`` must be positive for the widths used; the functions that take a width
    check it.

    References
    ----------
    .. [1] M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press,
       1969.
    .. [2] Z. Janosi and B. Hanamoto, "The analytical determination of drawbar pull as a function
       of slip for tracked vehicles in deformable soils", 1st Int. Conf. Terrain-Vehicle Systems,
       Turin, 1961.
    .. [3] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, ch. 2 (sec. 2.2-2.4;
       table 2.3 holds the values of most shipped soils, see :func:`soil_source`).
    """

    n: float = parameter("-", "exponent of deformation of the pressure-sinkage law", gt=0)
    k_c: float = parameter("N/m^(n+1)", "cohesive modulus of deformation")
    k_phi: float = parameter("N/m^(n+2)", "frictional modulus of deformation")
    cohesion: float = parameter("Pa", "cohesion c", ge=0)
    friction_angle: float = parameter("rad", "angle of internal shearing resistance phi", ge=0, lt=math.pi / 2)
    shear_modulus: float = parameter("m", "shear deformation modulus K (Janosi-Hanamoto)", gt=0)
    lateral_shear_modulus: float = parameter("m", "lateral shear deformation modulus K_y", default=None, gt=0)
    density: float = parameter("kg/m^3", "bulk density (bulldozing terms)", default=1600.0, gt=0)
    name: str = text("label of the soil", default="custom")

    @property
    def side_shear_modulus(self) -> float:
        """K_y [m]: ``lateral_shear_modulus`` if given, else ``shear_modulus``."""
        return self.shear_modulus if self.lateral_shear_modulus is None else self.lateral_shear_modulus

    def modulus(self, width):
        """Bekker's modulus for a loading width.

        Parameters
        ----------
        width : float or array_like
            b [m], > 0.

        Returns
        -------
        float or ndarray
            k = k_c / b + k_phi [N/m^(n+2)].

        Raises
        ------
        ParameterError
            If a width is not finite and > 0, or k is not > 0 for it.
        """
        b = np.asarray(width, dtype=float)
        if not np.all(np.isfinite(b) & (b > 0)):
            bad = b[~(np.isfinite(b) & (b > 0))].flat[0] if b.ndim else b
            raise ParameterError(f"width must be finite and > 0 [m], got {float(bad)!r}", key="width", value=float(bad))
        k = self.k_c / b + self.k_phi
        if not np.all(k > 0):
            raise ParameterError(f"k_c / width + k_phi must be > 0 for soil {self.name!r} (k_c={self.k_c}, "
                                 f"k_phi={self.k_phi}, width={b})", key="k_phi", value=self.k_phi)
        return k if b.ndim else float(k)


def _soil_table() -> dict:
    from vehdyn.params.vehicle import data_path

    return read_toml(data_path("soils.toml"))


def shipped_soils() -> list[str]:
    """Names of the soils in the shipped table ``data/soils.toml``.

    Returns
    -------
    list of str
        Sorted names, each loadable with :func:`load_soil`.

    Examples
    --------
    >>> from vehdyn.tire.terramechanics import shipped_soils
    >>> shipped_soils()
    ['clayey_soil', 'dry_sand', 'heavy_clay', 'lete_sand', 'lunar_soil', 'sandy_loam', 'snow']
    """
    return sorted(_soil_table())


def soil_source(name: str) -> str:
    """The published source of a shipped soil.

    Parameters
    ----------
    name : str
        A shipped soil (:func:`shipped_soils`).

    Returns
    -------
    str
        Its ``source`` entry in ``data/soils.toml``.

    Raises
    ------
    ParameterError
        For an unknown name.
    """
    table = _soil_table()
    if name not in table:
        raise ParameterError(f"no shipped soil {name!r}; soils are {sorted(table)}", key="soil", value=name)
    return table[name]["source"]


def soil_from_table(entry: dict, name: str = "custom") -> Soil:
    """A :class:`Soil` from one table entry with values in the units its ``units`` table names."""
    entry = dict(entry)
    units = entry.pop("units", {})
    entry.pop("description", None)
    entry.pop("source", None)
    values = {}
    for key, value in entry.items():
        if key in _UNIT_FACTORS:
            unit = units.get(key)
            if unit is None:
                raise ParameterError(f"soil {name!r}: {key} has no unit in its units table", key=f"{name}.units.{key}",
                                     value=None)
            factors = _UNIT_FACTORS[key]
            if unit not in factors:
                raise ParameterError(f"soil {name!r}: unit {unit!r} of {key} is not one of {list(factors)}",
                                     key=f"{name}.units.{key}", value=unit)
            if not is_number(value):
                raise ParameterError(f"soil {name!r}: {key} must be a number, got {value!r}", key=f"{name}.{key}",
                                     value=value)
            value = value * factors[unit]
        values[key] = value
    return Soil.from_dict({**values, "name": name}, path=f"{name}.")


def load_soil(name_or_path: str | Path) -> Soil:
    """A shipped soil by name (``"dry_sand"``, see :func:`shipped_soils`), or the single soil of a
    user's TOML file laid out like ``data/soils.toml`` (``"file.toml"`` or ``"file.toml:name"``).

    Values are converted from the units the table gives (``kN/m^(n+1)``, ``kPa``, ``deg``, ``cm`` ...)
    to SI.

    Parameters
    ----------
    name_or_path : str or os.PathLike
        A shipped name, a TOML file with one soil, or ``"file.toml:NAME"``.

    Returns
    -------
    Soil

    Raises
    ------
    ParameterError
        For an unknown name, a file that holds several soils without a name given, a missing or
        invalid file, a unit the table may not use, or a value out of range.

    Examples
    --------
    >>> import math
    >>> from vehdyn.tire.terramechanics import load_soil
    >>> sand = load_soil("dry_sand")
    >>> sand.n, sand.k_phi, sand.cohesion, round(math.degrees(sand.friction_angle), 6)   # SI, phi in deg
    (1.1, 1528430.0, 1040.0, 28.0)
    """
    text_name = str(name_or_path)
    path, _, key = text_name.partition(".toml:")
    # a path (a .toml file, or any existing file or folder that is not a shipped name): read_toml names what is wrong
    if text_name.endswith(".toml") or key or (Path(text_name).exists() and text_name not in _soil_table()):
        path = Path(path if not key else path + ".toml")
        table = read_toml(path)
        if not key:
            if len(table) != 1:
                raise ParameterError(f"{path} holds soils {sorted(table)}: name one as '{path}:NAME'", key="soil",
                                     value=text_name)
            key = next(iter(table))
        if key not in table:
            raise ParameterError(f"{path} has no soil {key!r}; it has {sorted(table)}", key="soil", value=key)
        return soil_from_table(table[key], key)
    table = _soil_table()
    if text_name not in table:
        raise ParameterError(f"no shipped soil {text_name!r}; soils are {sorted(table)}", key="soil", value=text_name)
    return soil_from_table(table[text_name], text_name)
