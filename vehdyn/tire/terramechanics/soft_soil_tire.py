"""A tire law on soft soil for the vehicle models: :class:`SoftSoilTire`.

It wraps :class:`~vehdyn.tire.terramechanics.FlexibleWheel` (rigid mode: Wong-Reece; elastic mode:
flat-section contact) behind the :class:`~vehdyn.tire.TireModel` interface, so that
:class:`~vehdyn.handling.SingleTrack` and the other vehicle models run on sand, loam, clay or snow.

Slip mapping (ISO-W slip ratio ``kappa = (omega r - V) / V`` to the terramechanics slip s)::

    s = kappa / (1 + kappa)     kappa >= 0   (driven: s = 1 - V / (r omega))
    s = max(kappa, -1)          kappa <  0   (braked: s = r omega / V - 1)

``F_x`` is the drawbar pull (thrust minus motion resistance: the net horizontal soil force on the
wheel), signed with the rolling direction like the road laws; ``F_y`` the side force of the
flexible wheel (ISO-W: negative for a positive slip angle). The rolling-resistance moment
``M_y = r F_x - T`` (T the soil's torque on the wheel, so that ``-T = -r F_x + M_y``; <= 0 rolling
forwards, like the Magic Formula's) carries the part of the soil torque that ``F_x r`` does not.
:class:`~vehdyn.handling.SingleTrack` closes its wheel-spin balance with it
(``2 I_w d(omega)/dt = T_drive - ... - R_e F_x + M_y``), so that with ``R_e = r`` a free-rolling wheel
settles at zero soil torque, the towed wheel, and the vehicle feels its motion resistance; a model
that used ``F_x r`` alone would let a free-rolling wheel settle at zero drawbar pull instead. ``M_x = M_z = 0``. :meth:`SoftSoilTire.evaluate` gives sinkage,
motion resistance, torque, mode and the stuck status.

Inputs that are not finite give NaN at those points, as for every tire law (:mod:`vehdyn.tire.base`):
every force and moment, and in :meth:`SoftSoilTire.evaluate` every number of the result (``stuck``
False and ``mode`` ``"invalid"`` there); bools raise :class:`~vehdyn.ParameterError`.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.tire._common import all_scalars, broadcast_inputs, rolling_direction
from vehdyn.tire.base import TireForces, TireModel
from vehdyn.tire.terramechanics.flexible import FlexibleWheel, SoftSoilTireGeometry
from vehdyn.tire.terramechanics.soil import Soil
from vehdyn.tire.terramechanics.wong_reece import WheelSoilResult

__all__ = ["SoftSoilTire", "SoftSoilTireGeometry", "slip_from_kappa"]

_MAX_SLIP_ANGLE = 0.5 * math.pi - 1e-6
_WHEEL_OPTIONS = frozenset({"c1", "c2", "rebound"})  # the fields of FlexibleWheel a SoftSoilTire passes on


def slip_from_kappa(kappa):
    """Terramechanics slip from the ISO-W slip ratio.

    Parameters
    ----------
    kappa : array_like
        Slip ratio kappa = (omega r - V) / V [-] (ISO-W, MFeval's).

    Returns
    -------
    ndarray
        s [-] in [-1, 1]: ``kappa / (1 + kappa)`` driven (kappa >= 0, s = 1 - V / (r omega)),
        ``max(kappa, -1)`` braked (s = r omega / V - 1).
    """
    k = np.asarray(kappa, dtype=float)
    return np.where(k >= 0.0, k / (1.0 + np.abs(k)), np.maximum(k, -1.0))


class SoftSoilTire(TireModel):
    r"""A tire on deformable soil with the :class:`~vehdyn.tire.TireModel` interface.

    A :class:`~vehdyn.tire.terramechanics.FlexibleWheel` (rigid mode: Wong-Reece; elastic mode:
    flat-section contact) behind the interface of the road tire laws, so that the vehicle models
    run on sand, loam, clay or snow. With the terramechanics slip s of the ISO-W slip ratio and
    the wheel's drawbar pull DP, torque T and side force:

    .. math::

        s = \begin{cases} \kappa / (1 + \kappa) & \kappa \ge 0 \\
        \max(\kappa, -1) & \kappa < 0 \end{cases}, \qquad
        F_x = DP \operatorname{sgn} V_x, \qquad
        M_y = (r \, DP - T) \operatorname{sgn} V_x, \qquad M_x = M_z = 0

    and F_y the flexible wheel's side force (ISO-W: negative for a positive slip angle). M_y
    carries the part of the soil torque that r F_x does not, so that a model closing the wheel
    spin balance with ``-R_e F_x + M_y`` lets a free-rolling wheel settle at zero soil torque (the
    towed wheel, which feels its motion resistance). Camber has no effect.

    Parameters
    ----------
    tire_geometry : SoftSoilTireGeometry
        Radius, width, inflation and carcass pressures.
    soil : Soil
        The soil.
    **wheel_options
        ``c1``, ``c2``, ``rebound`` of :class:`FlexibleWheel`.

    Raises
    ------
    ParameterError
        If ``tire_geometry`` or ``soil`` is of the wrong type, or a wheel option is out of range.

    References
    ----------
    .. [1] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, ch. 2 (sec. 2.4, 2.7).
    .. [2] J. Y. Wong and A. R. Reece, "Prediction of rigid wheel performance based on the
       analysis of soil-wheel stresses", parts I and II, J. Terramechanics 4(1), 81-98, and 4(2),
       7-25, 1967.
    .. [3] M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press,
       1969.
    .. [4] G. Ishigami, A. Miwa, K. Nagatani and K. Yoshida, "Terramechanics-based model for
       steering maneuver of planetary exploration rovers on loose soil", J. Field Robotics 24(3),
       233-250, 2007 (the side force).

    Examples
    --------
    >>> from vehdyn.tire.terramechanics import SoftSoilTire, SoftSoilTireGeometry, load_soil
    >>> tire = SoftSoilTire(SoftSoilTireGeometry(radius=0.32, width=0.205, inflation_pressure=2.2e5),
    ...                     load_soil("dry_sand"))
    >>> f = tire.forces(4000.0, 0.2, 0.0)                  # load [N], slip ratio [-], slip angle [rad]
    >>> state = tire.evaluate(4000.0, 0.2)
    >>> str(state.mode), f.fx == float(state.drawbar_pull)   # F_x is the drawbar pull
    ('rigid', True)
    >>> bool(abs(f.my - (0.32 * f.fx - float(state.torque))) < 1e-9)   # M_y = r DP - T [N m]
    True
    """

    name = "soft_soil"

    def __init__(self, tire_geometry: SoftSoilTireGeometry, soil: Soil, **wheel_options):
        if not isinstance(tire_geometry, SoftSoilTireGeometry):
            raise ParameterError(f"tire_geometry must be a SoftSoilTireGeometry, got {type(tire_geometry).__name__}",
                                 key="tire_geometry", value=tire_geometry)
        if not isinstance(soil, Soil):
            raise ParameterError(f"soil must be a Soil, got {type(soil).__name__}", key="soil", value=soil)
        unknown = sorted(set(wheel_options) - _WHEEL_OPTIONS)
        if unknown:
            raise ParameterError(f"SoftSoilTire: unknown wheel option {unknown[0]!r} = {wheel_options[unknown[0]]!r}; "
                                 f"the options are {sorted(_WHEEL_OPTIONS)}", key=unknown[0],
                                 value=wheel_options[unknown[0]])
        self.wheel = FlexibleWheel(geometry=tire_geometry, soil=soil, **wheel_options)
        self.tire_geometry = tire_geometry
        self.soil = soil

    def __repr__(self) -> str:
        return f"SoftSoilTire({self.tire_geometry!r}, soil={self.soil.name!r})"

    def evaluate(self, fz, kappa, alpha=0.0, vx=10.0) -> WheelSoilResult:
        """The wheel's steady state: sinkage, drawbar pull, motion resistance, torque, mode, stuck.

        Parameters
        ----------
        fz : array_like
            Normal load [N].
        kappa : array_like
            ISO-W slip ratio [-].
        alpha : array_like
            Slip angle [rad] (ISO-W), clipped just inside +-pi/2.
        vx : array_like
            Forward speed [m/s]: only its sign, and only for the input check (the forces of the
            result are for rolling forwards).

        Returns
        -------
        WheelSoilResult
            Of the broadcast shape; NaN (``stuck`` False, ``mode`` ``"invalid"``) where an input
            is not finite.
        """
        return self._evaluate(fz, kappa, alpha, 0.0, vx)

    def _evaluate(self, fz, kappa, alpha, gamma, vx) -> WheelSoilResult:
        """:meth:`evaluate`, with ``gamma`` (no effect) taking part in the shape and the input check."""
        (fz, kappa, alpha, _, vx), bad = broadcast_inputs(fz, kappa, alpha, gamma, vx)
        result = self.wheel.solve(fz, slip_from_kappa(kappa), np.clip(alpha, -_MAX_SLIP_ANGLE, _MAX_SLIP_ANGLE))
        if bad is None:
            return result
        invalid = {"stuck": False, "mode": "invalid", "converged": True}
        return dataclasses.replace(result, **{
            f.name: np.where(bad, invalid.get(f.name, np.nan), np.broadcast_to(getattr(result, f.name), bad.shape))
            for f in dataclasses.fields(result)})

    def forces(self, fz, kappa, alpha, gamma=0.0, vx=10.0) -> TireForces:
        """Steady-state forces (ISO-W); see :meth:`vehdyn.tire.TireModel.forces` and the module
        docstring. Camber has no effect."""
        scalar = all_scalars(fz, kappa, alpha, gamma, vx)
        result = self._evaluate(fz, kappa, alpha, gamma, vx)
        direction = rolling_direction(np.asarray(vx, dtype=float))
        fx = result.drawbar_pull * direction
        fy = result.lateral_force
        my = (self.tire_geometry.radius * result.drawbar_pull - result.torque) * direction
        load = result.load
        zero = load * 0.0  # NaN where an input was not finite (load is NaN there)
        if scalar:
            return TireForces(float(fx), float(fy), float(load), float(zero), float(my), float(zero))
        fx = np.broadcast_to(fx, load.shape).astype(float)
        return TireForces(fx, np.asarray(fy, dtype=float), load, zero, np.broadcast_to(my, load.shape).astype(float),
                          zero.copy())
