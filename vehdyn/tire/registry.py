"""Tire laws by name, so that a vehicle file can say which law its nonlinear models use.

A vehicle's ``[tires]`` table names its law (``model = "brush"``); :func:`tire_law` maps the name to
the class and :func:`tire_for_vehicle` builds the tire of one wheel from the vehicle's data::

    vehicle = vehdyn.load_vehicle("sedan").replace(tires__model="fiala")
    front = vehdyn.tire.tire_for_vehicle(vehicle, "front")

``"magic_formula"`` resolves lazily to :class:`vehdyn.tire.magic_formula.MagicFormula` (built from
the vehicle's ``.tir`` file), so the registry imports the Magic Formula only when it is asked for.
Users register their own laws with :func:`register_tire_law`.
"""

from __future__ import annotations

import functools
import importlib
import math
import os
from typing import NamedTuple

from vehdyn.errors import ParameterError
from vehdyn.units import GRAVITY
from vehdyn.tire.base import TireModel

__all__ = ["tire_law", "tire_law_names", "register_tire_law", "tire_for_vehicle", "vehicle_tire_data",
           "VehicleTireData"]

# name -> "module:Class" (resolved on first use) or the class itself
_LAWS: dict[str, object] = {
    "linear": "vehdyn.tire.linear:LinearTire",
    "brush": "vehdyn.tire.brush:BrushTire",
    "fiala": "vehdyn.tire.fiala:FialaTire",
    "dugoff": "vehdyn.tire.dugoff:DugoffTire",
    "magic_formula": "vehdyn.tire.magic_formula:MagicFormula",
}


def tire_law_names() -> tuple[str, ...]:
    """The registered law names.

    Returns
    -------
    tuple of str
        Sorted: ``"brush"``, ``"dugoff"``, ``"fiala"``, ``"linear"``, ``"magic_formula"`` and
        the names given to :func:`register_tire_law`.

    Examples
    --------
    >>> from vehdyn.tire import tire_law_names
    >>> tire_law_names()
    ('brush', 'dugoff', 'fiala', 'linear', 'magic_formula')
    """
    return tuple(sorted(_LAWS))


def register_tire_law(name: str, law) -> None:
    """Register a tire law under a name, so that a vehicle file's ``tires.model`` can name it.

    Parameters
    ----------
    name : str
        The name, snake_case (``"my_brush"``).
    law : type or str
        A :class:`TireModel` subclass, or a ``"module:Class"`` string imported on first use. The
        class should have ``from_vehicle(vehicle, axle)`` or ``from_tir(path)`` for
        :func:`tire_for_vehicle`.

    Raises
    ------
    ParameterError
        If ``name`` is not snake_case or is already taken by another law.
    """
    if not isinstance(name, str) or not name.replace("_", "").isalnum() or name.lower() != name:
        raise ParameterError(f"tire law name must be a snake_case string, got {name!r}", key="name", value=name)
    if name in _LAWS and _LAWS[name] is not law:
        raise ParameterError(f"tire law {name!r} is already registered ({_LAWS[name]!r})", key="name", value=name)
    if not isinstance(law, str) and not (isinstance(law, type) and issubclass(law, TireModel)):
        raise ParameterError(f"tire law {name!r} must be a TireModel subclass or a 'module:Class' string, "
                             f"got {law!r}", key=name, value=law)
    _LAWS[name] = law


def tire_law(name: str) -> type:
    """The class of a tire law by name.

    Parameters
    ----------
    name : str
        ``"linear"``, ``"brush"``, ``"fiala"``, ``"dugoff"``, ``"magic_formula"`` or a registered
        name.

    Returns
    -------
    type
        The :class:`TireModel` subclass.

    Raises
    ------
    ParameterError
        For an unknown name (listing the known ones) or a law whose module cannot be imported.
    """
    try:
        law = _LAWS[name]
    except (KeyError, TypeError):
        raise ParameterError(f"unknown tire law {name!r}; the laws are {list(tire_law_names())}",
                             key="tires.model", value=name) from None
    if isinstance(law, str):
        module_name, _, class_name = law.partition(":")
        try:
            module = importlib.import_module(module_name)
        except ImportError as exc:
            raise ParameterError(f"tire law {name!r} is not available: {exc}", key="tires.model",
                                 value=name) from None
        law = getattr(module, class_name)
    return law


class VehicleTireData(NamedTuple):
    """What a vehicle file says about one of its tires (per tire, not per axle).

    Attributes
    ----------
    cornering_stiffness : float
        Half the axle's cornering stiffness [N/rad].
    static_load : float
        Static load of one tire of the axle [N].
    mu : float
        Peak friction coefficient [-].
    contact_half_length : float
        Half the chord of the unloaded tire circle at the static deflection,
        ``sqrt(2 R delta - delta^2)`` with ``delta = F_z / k_z`` [m].
    relaxation_length : float
        The axle's lateral relaxation length [m] (0 when the file gives none).
    """

    cornering_stiffness: float
    static_load: float
    mu: float
    contact_half_length: float
    relaxation_length: float


def vehicle_tire_data(vehicle, axle: str = "front") -> VehicleTireData:
    """Per-tire data of a vehicle's axle, for building a tire law.

    Parameters
    ----------
    vehicle : vehdyn.Vehicle
        The vehicle.
    axle : {"front", "rear"}
        The axle.

    Returns
    -------
    VehicleTireData
        Per-tire cornering stiffness, static load, friction, contact half length, relaxation
        length.

    Raises
    ------
    ParameterError
        For an axle other than ``"front"`` or ``"rear"``.
    """
    if axle not in ("front", "rear"):
        raise ParameterError(f"axle must be 'front' or 'rear', got {axle!r}", key="axle", value=axle)
    tires = vehicle.tires
    front_load, rear_load = vehicle.static_axle_loads(GRAVITY)
    load = (front_load if axle == "front" else rear_load) / 2.0
    stiffness = (tires.front_cornering_stiffness if axle == "front" else tires.rear_cornering_stiffness) / 2.0
    deflection = min(load / tires.vertical_stiffness, tires.rolling_radius)
    half_length = math.sqrt(2.0 * tires.rolling_radius * deflection - deflection * deflection)
    relaxation = tires.front_relaxation_length if axle == "front" else tires.rear_relaxation_length
    return VehicleTireData(stiffness, load, tires.friction_coefficient, half_length, relaxation)


@functools.lru_cache(maxsize=16)
def _from_tir(law, path: str, mtime_ns: int, size: int) -> TireModel:
    """``law.from_tir(path)``, read once per version of the file (a sweep builds a model per
    variant: parsing the file each time cost more than the variant's compiled run). The law is
    shared by the models built from it (its coefficients are immutable)."""
    return law.from_tir(path)


def tire_for_vehicle(vehicle, axle: str = "front", model: str | None = None) -> TireModel:
    """The tire law of one wheel of ``vehicle``'s ``axle``.

    Parameters
    ----------
    vehicle : vehdyn.Vehicle
        The vehicle; its ``tires.model`` names the law unless ``model`` is given.
    axle : {"front", "rear"}
        The axle.
    model : str, optional
        A law name overriding ``vehicle.tires.model``.

    Returns
    -------
    TireModel
        Built by the law's ``from_vehicle(vehicle, axle)`` where it has one, else (the Magic
        Formula) from the vehicle's ``.tir`` file with ``from_tir`` (read once per version of
        the file).

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.tire import tire_for_vehicle
    >>> sedan = vehdyn.load_vehicle("sedan")
    >>> type(tire_for_vehicle(sedan, "front", model="fiala")).__name__
    'FialaTire'
    """
    law = tire_law(model if model is not None else vehicle.tires.model)
    if hasattr(law, "from_vehicle"):
        return law.from_vehicle(vehicle, axle)
    if hasattr(law, "from_tir"):
        path = vehicle.tir_path()
        try:
            stat = os.stat(path)
        except OSError:  # from_tir names the file
            return law.from_tir(path)
        return _from_tir(law, str(path), stat.st_mtime_ns, stat.st_size)
    raise ParameterError(f"tire law {law.__name__} can be built neither from a vehicle nor from a .tir file",
                         key="tires.model", value=vehicle.tires.model)
