"""What a vehicle model reads from its tire laws when it is built, and the road's friction argument.

Shared by the single-track, articulated and full-vehicle models (numpy, at construction; the
equations themselves are in :mod:`~vehdyn.components.tire_forces` and
:mod:`~vehdyn.components.tire_slip`):

* :func:`tire_characteristics` -- whether a law makes a lateral force at zero slip (ply steer,
  conicity: one tire of an axle is then its mirror image) and the slips at which its pure-slip
  forces peak (the limits of the tire deflections; Pacejka 2012, sec. 7.2 and 8.2; Rill 2012,
  sec. 3.10), remembered per law and load;
* :func:`mirrored_wheel` -- which wheel of an axle is the mirror image (a ``.tir`` file's
  ``TYRESIDE``);
* :func:`longitudinal_relaxation_lengths` -- sigma_x of each axle's tire;
* :func:`road_friction` and :func:`friction_at` -- the one way to put a model on a road of another
  friction: a constant ratio or a callable of the earth position, applied by similarity in the
  tire step (:mod:`~vehdyn.components.tire_forces`); :func:`friction_ratio` gives the ratio of a
  road whose peak friction coefficient is known.

References
----------
.. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, sec. 4.3.2
   (similarity), 7.2 and 8.2 (the deflection's limit at the peak slip).
.. [2] G. Rill, *Road Vehicle Dynamics: Fundamentals and Modeling*, CRC Press, 2012, sec. 3.10.
"""

from __future__ import annotations

import threading
import weakref
from collections import OrderedDict

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["CHARACTERISTICS_PER_TIRE", "tire_characteristics", "evaluate_characteristics", "mirrored_wheel",
           "longitudinal_relaxation_lengths", "road_friction", "friction_at", "friction_ratio"]

# tire_characteristics per tire law and load: tire -> OrderedDict(load -> result), the most recent
# CHARACTERISTICS_PER_TIRE loads of each law (a law is shared by the models built from one vehicle
# file, :func:`vehdyn.tire.registry.tire_for_vehicle`)
_CHARACTERISTICS = weakref.WeakKeyDictionary()
_CHARACTERISTICS_LOCK = threading.Lock()
CHARACTERISTICS_PER_TIRE = 256
"""How many loads :func:`tire_characteristics` remembers per law."""


def tire_characteristics(tire, load):
    """(ply steer, peak slips) of ``tire`` at ``load``: :func:`evaluate_characteristics`, remembered.

    The law evaluates 803 points (~1.2 ms for a Magic Formula: most of building a model); a sweep
    over speeds, manoeuvres or stiffnesses builds every model at the same loads, so the result is
    remembered per law and load (the most recent :data:`CHARACTERISTICS_PER_TIRE` loads). A law
    that cannot be a weak dictionary key is evaluated every time.

    Parameters
    ----------
    tire : TireModel
        The law of one tire.
    load : float
        Normal load of one tire [N].

    Returns
    -------
    tuple
        (ply steer: bool, (peak slip ratio [-], peak tan slip angle [-])).
    """
    load = float(load)
    try:
        with _CHARACTERISTICS_LOCK:
            memo = _CHARACTERISTICS.setdefault(tire, OrderedDict())
            hit = memo.get(load)
            if hit is not None:
                memo.move_to_end(load)
                return hit
    except TypeError:  # unhashable, or no weak reference to it
        return evaluate_characteristics(tire, load)
    result = evaluate_characteristics(tire, load)
    with _CHARACTERISTICS_LOCK:
        memo[load] = result
        while len(memo) > CHARACTERISTICS_PER_TIRE:
            memo.popitem(last=False)
    return result


def evaluate_characteristics(tire, load):
    """(ply steer, peak slips) of ``tire`` at ``load`` from one call of the law.

    Its slip-ratio sweep, slip-angle sweep and zero-slip point side by side (a numpy law's call
    costs its overhead, not its points). Ply steer: the law's |F_y| at zero slip exceeds 1e-9 of
    the load. The peak slips: the slip ratio and tan slip angle at which the law's pure-slip forces
    peak; the tire deflection cannot grow beyond what the peak force needs, past it the contact
    patch slides. A law without a peak (linear) gives slip ratio 1 and slip angle 80 degrees.

    Parameters
    ----------
    tire : TireModel
        The law of one tire.
    load : float
        Normal load [N].

    Returns
    -------
    tuple
        (ply steer: bool, (peak slip ratio [-], peak tan slip angle [-]), each at least 0.01).
    """
    grid = np.linspace(0.0, 1.0, 401)
    angles = np.linspace(0.0, np.radians(80.0), 401)
    zeros = np.zeros(grid.size + angles.size + 1)
    kappa, alpha = zeros.copy(), zeros.copy()
    kappa[:grid.size] = grid
    alpha[grid.size:-1] = angles
    f = tire.forces(np.full(zeros.size, float(load)), kappa, alpha, 0.0, 20.0)
    fx = np.abs(np.asarray(f.fx)[:grid.size])
    fy = np.abs(np.asarray(f.fy)[grid.size:-1])
    ply_steer = abs(float(np.asarray(f.fy)[-1])) > 1e-9 * max(float(load), 1.0)
    kx = grid[np.argmax(fx >= (1 - 1e-9) * fx.max())]
    ay = angles[np.argmax(fy >= (1 - 1e-9) * fy.max())]
    return ply_steer, (max(float(kx), 0.01), max(float(np.tan(ay)), 0.01))


def mirrored_wheel(tire, ply_steer: bool):
    """The wheel of an axle that is the mirror image of ``tire``'s law: ``"left"``, ``"right"`` or None.

    A ``.tir`` file's ``TYRESIDE`` names the side of the vehicle (or test bench) the tire was
    mounted on when it was measured; the file's law is that wheel's, and a tire of the same make on
    the other side is its mirror image, (F_x, -F_y, M_y) at (-alpha, -gamma) (the convention of
    MF-Tyre and ADAMS property files; MFeval and :class:`~vehdyn.tire.MagicFormula` evaluate the law
    as written). So a ``'LEFT'`` file (the shipped mf_185_80R14.tir) mirrors the right wheel, a
    ``'RIGHT'`` file the left one; a law without ``TYRESIDE`` (other tire laws) is taken as a
    right tire. At equal wheel loads the axle force is the same either way; under a lateral load
    transfer the ply-steer part of it changes sign with the side. Every model that tells the
    wheels apart decides here.

    Parameters
    ----------
    tire : TireModel
        The law.
    ply_steer : bool
        The law makes a lateral force at zero slip (:func:`tire_characteristics`); without it the
        two wheels are the same law.

    Returns
    -------
    str or None
        ``"left"``, ``"right"``, or None without ply steer.
    """
    if not ply_steer:
        return None
    params = getattr(tire, "params", None)
    side = str(params.get("TYRESIDE", "RIGHT")).strip().strip("'\"").upper() if params is not None else "RIGHT"
    return "right" if side == "LEFT" else "left"


def longitudinal_relaxation_lengths(vehicle, tires, given, lateral, gravity):
    """sigma_x [m] of the front and rear tires.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle (its static axle loads).
    tires : dict
        ``{"front": TireModel, "rear": TireModel}``.
    given : float or (float, float) or None
        The lengths asked for [m]; None: for a Magic Formula its own value at half the static axle
        load (:func:`vehdyn.tire.relaxation_lengths`, K_xkappa / C_x), for other laws ``lateral``.
    lateral : (float, float)
        The lateral relaxation lengths [m] (the fallback).
    gravity : float
        [m/s^2].

    Returns
    -------
    tuple
        (front [m], rear [m]).

    Raises
    ------
    ParameterError
        For a given length that is not a finite number > 0.
    """
    if given is not None:
        values = np.broadcast_to(np.asarray(given, dtype=float), (2,))
        if not np.all(np.isfinite(values)) or np.any(values <= 0):
            raise ParameterError(f"longitudinal_relaxation_length must be > 0 [m], got {given!r}",
                                 key="longitudinal_relaxation_length", value=given)
        return float(values[0]), float(values[1])
    from vehdyn.tire import MagicFormula, relaxation_lengths

    lengths = []
    for axle, load, fallback in zip(("front", "rear"), vehicle.static_axle_loads(gravity), lateral):
        tire = tires[axle]
        sigma = float(relaxation_lengths(tire, 0.5 * load)[0]) if isinstance(tire, MagicFormula) else fallback
        lengths.append(sigma if np.isfinite(sigma) and sigma > 0 else fallback)
    return tuple(lengths)


def road_friction(friction):
    """The ``friction`` argument of a vehicle model, checked: None, a constant ratio or a callable.

    The road's friction relative to the tire law's own, mu [-] (0.5: a road on which every peak
    force is half the law's), applied to every tire by similarity in the tire step
    (:mod:`~vehdyn.components.tire_forces`): F(kappa, tan alpha) -> mu F(kappa / mu, tan(alpha) / mu).

    Parameters
    ----------
    friction : None, float or callable
        None or 1.0: the law as it is. A number > 0: one ratio everywhere. A callable
        ``friction(X, Y) -> ratio`` of the earth position [m] (arrays in, arrays of ratios > 0
        out; e.g. a split-mu road), evaluated at each wheel's contact point (numpy backend only).

    Returns
    -------
    None, float or callable
        None for the law as it is, else the ratio as a float or the callable.

    Raises
    ------
    ParameterError
        For anything else, or a ratio that is not a finite number > 0.
    """
    if friction is None:
        return None
    if callable(friction):
        return friction
    if isinstance(friction, (bool, np.bool_)) or not isinstance(friction, (int, float, np.integer, np.floating)) \
            or not (np.isfinite(friction) and friction > 0):
        raise ParameterError(f"friction must be None, a ratio > 0 [-] or a callable friction(X, Y) -> ratio, got "
                             f"{friction!r}", key="friction", value=friction)
    return None if float(friction) == 1.0 else float(friction)


def friction_at(friction, X, Y):
    """The ratio of a callable ``friction`` at earth positions, checked > 0.

    Parameters
    ----------
    friction : callable
        ``friction(X, Y) -> ratio`` (:func:`road_friction`).
    X, Y : float or ndarray
        Earth positions [m].

    Returns
    -------
    ndarray
        The ratio [-].

    Raises
    ------
    ParameterError
        Where the ratio is not a finite number > 0.
    """
    value = np.asarray(friction(X, Y), dtype=float)
    if not np.all(np.isfinite(value) & (value > 0)):
        raise ParameterError(f"friction(X, Y) must be > 0 under every wheel, got {float(np.min(value))!r}",
                             key="friction", value=float(np.min(value)))
    return value


def friction_ratio(tire, friction: float, load: float, direction: str = "longitudinal") -> float:
    """The road friction ratio at which ``tire``'s peak friction at ``load`` is ``friction``.

    The models' ``friction`` argument is relative to the tire law's own friction; a road is often
    known by its peak friction coefficient mu instead (0.9 dry asphalt, 0.5 wet, 0.2 snow). The
    ratio is mu over the law's peak friction coefficient F_peak / F_z at ``load``
    (:func:`vehdyn.tire.characteristic_values`): by similarity every peak scales by the ratio, so
    the law's peak at ``load`` becomes mu exactly, at other loads its load sensitivity stays.

    Parameters
    ----------
    tire : TireModel
        The law.
    friction : float
        The road's peak friction coefficient mu [-] (> 0).
    load : float
        The normal load of one tire [N] at which the peak is ``friction`` (> 0), e.g. half the
        static axle load.
    direction : str
        ``"longitudinal"`` (braking and driving, the default) or ``"lateral"``: which peak.

    Returns
    -------
    float
        The ratio [-].

    Raises
    ------
    ParameterError
        For a friction or load that is not a finite number > 0, or another direction.
    """
    from vehdyn.tire import characteristic_values

    for name, value in (("friction", friction), ("load", load)):
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)) \
                or not (np.isfinite(value) and value > 0):
            raise ParameterError(f"{name} must be a finite number > 0, got {value!r}", key=name, value=value)
    if direction not in ("longitudinal", "lateral"):
        raise ParameterError(f"direction must be 'longitudinal' or 'lateral', got {direction!r}", key="direction",
                             value=direction)
    peak = float(characteristic_values(tire, [float(load)]).iloc[0][f"peak_{direction}_friction"])
    return float(friction) / peak
