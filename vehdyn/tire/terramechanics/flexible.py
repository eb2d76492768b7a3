"""Flexible (pneumatic) tire on soft soil: rigid or elastic mode, flat-section contact.

A tire behaves as a rigid wheel when the soil is soft enough that the ground pressure under a
rigid wheel of the same size stays below the tire's own stiffness, expressed as the inflation
pressure p_i plus the carcass-stiffness pressure p_c (Bekker 1969; Wong 2008, sec. 2.7)::

    p_gcr = (k_c / b + k_phi) z0^n,   z0 = Bekker's rigid-wheel sinkage (bekker.rigid_wheel_sinkage)
    rigid mode    if p_i + p_c >= p_gcr     (the Wong-Reece rigid wheel, vehdyn RigidWheel)
    elastic mode  if p_i + p_c <  p_gcr     (the tire flattens on the soil)

In the elastic mode the flat section carries the load at the uniform pressure ``p = p_i + p_c``,
so that (Wong 2008, sec. 2.7, and sec. 2.4 for the thrust of a uniform contact)::

    z   = (p / k)^(1/n)                                 sinkage (stuck if >= r; then z = r)
    l   = W / (b p),   A = b l                          flat contact length and area
    R_c = b k z^(n+1) / (n+1)  (= b p z / (n+1))        compaction resistance
    j   = s x                                           shear displacement at x behind the leading edge
    H   = sgn(s) (A c + W tan phi) [1 - K / (|s| l) (1 - exp(-|s| l / K))]   thrust
    DP  = H - R_c,    T = H r

(the torque arm is taken as the unloaded radius r). The side force in the elastic mode is that of
the same uniform contact (:func:`~vehdyn.tire.terramechanics.lateral.flat_side_force`).

References
----------
M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press, 1969.
J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.4 and 2.7.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from vehdyn.params.base import ParameterSet, parameter
from vehdyn.tire.terramechanics.bekker import checked_array, rigid_wheel_sinkage
from vehdyn.tire.terramechanics.lateral import flat_side_force, mobilized_fraction
from vehdyn.tire.terramechanics.soil import Soil
from vehdyn.tire.terramechanics.wong_reece import (QUADRATURE_NODES, RigidWheel, WheelSoilResult, check_slip,
                                                   check_solver_settings, efficiency, travel_ratio)

__all__ = ["SoftSoilTireGeometry", "FlexibleWheel", "critical_ground_pressure"]


def critical_ground_pressure(soil: Soil, load, diameter, width):
    r"""Ground pressure under a rigid wheel at Bekker's static sinkage.

    .. math::

        p_{gcr} = \left(\frac{k_c}{b} + k_\phi\right) z_0^n

    with z0 of :func:`~vehdyn.tire.terramechanics.rigid_wheel_sinkage`. A tire whose inflation
    plus carcass pressure exceeds it runs as a rigid wheel.

    Parameters
    ----------
    soil : Soil
        The soil.
    load : array_like
        Normal load W [N].
    diameter : array_like
        Wheel diameter D [m].
    width : array_like
        Wheel width b [m].

    Returns
    -------
    float or ndarray
        p_gcr [Pa].

    References
    ----------
    .. [1] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.7.
    """
    z0 = np.asarray(rigid_wheel_sinkage(soil, load, diameter, width))
    out = soil.modulus(width) * z0**soil.n
    return float(out) if np.ndim(out) == 0 else out


@dataclasses.dataclass(frozen=True, kw_only=True)
class SoftSoilTireGeometry(ParameterSet):
    """Size and stiffness of a tire for soft soil.

    Parameters
    ----------
    radius : float
        Unloaded radius r [m].
    width : float
        Section width b [m].
    inflation_pressure : float, optional
        p_i [Pa]; None: a rigid wheel.
    carcass_pressure : float
        p_c [Pa], the carcass stiffness expressed as a pressure (default 0).
    """

    radius: float = parameter("m", "unloaded radius r", gt=0)
    width: float = parameter("m", "section width b", gt=0)
    inflation_pressure: float = parameter("Pa", "inflation pressure p_i", default=None, gt=0)
    carcass_pressure: float = parameter("Pa", "carcass stiffness pressure p_c", default=0.0, ge=0)

    @property
    def stiffness_pressure(self) -> float:
        """p_i + p_c [Pa] (inf for a rigid wheel)."""
        return math.inf if self.inflation_pressure is None else self.inflation_pressure + self.carcass_pressure


@dataclasses.dataclass(frozen=True, kw_only=True)
class FlexibleWheel(ParameterSet):
    r"""A pneumatic tire on soil in the rigid or elastic mode.

    The tire runs as a rigid wheel (:class:`~vehdyn.tire.terramechanics.RigidWheel`) while its
    inflation plus carcass pressure p = p_i + p_c stays at least the critical ground pressure
    (:func:`critical_ground_pressure`), else it flattens on the soil and carries the load on a
    flat section at the uniform pressure p:

    .. math::

        z = (p / k)^{1/n}, \qquad l = \frac{W}{b p}, \qquad
        R_c = \frac{b k z^{n+1}}{n + 1}

        H = \operatorname{sgn}(s) (A c + W \tan\phi)
        \left[1 - \frac{K}{|s| l} \left(1 - e^{-|s| l / K}\right)\right], \quad A = b l,
        \qquad DP = H - R_c, \qquad T = H r

    (k = k_c / b + k_phi; the torque arm taken as the unloaded radius r; stuck if z >= r). The
    side force in the elastic mode is that of the same uniform contact
    (:func:`~vehdyn.tire.terramechanics.lateral.flat_side_force`).

    Parameters
    ----------
    geometry : SoftSoilTireGeometry
        Radius, width, inflation and carcass pressures.
    soil : Soil
        The soil.
    c1, c2 : float
        The rigid mode's maximum-stress angle coefficients [-] (see
        :class:`~vehdyn.tire.terramechanics.RigidWheel`).
    rebound : float
        The rigid mode's exit over entry angle [-].

    References
    ----------
    .. [1] M. G. Bekker, *Introduction to Terrain-Vehicle Systems*, University of Michigan Press,
       1969.
    .. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.4 (thrust of a
       uniform contact) and 2.7 (rigid and elastic modes of a tire).

    Examples
    --------
    >>> import numpy as np
    >>> from vehdyn.tire.terramechanics import FlexibleWheel, SoftSoilTireGeometry, load_soil, plate_sinkage
    >>> loam = load_soil("sandy_loam")
    >>> tire = FlexibleWheel(geometry=SoftSoilTireGeometry(radius=0.32, width=0.205, inflation_pressure=1e5),
    ...                      soil=loam)
    >>> r = tire.solve([1000.0, 4000.0], 0.2)                  # loads [N], slip [-]
    >>> r.mode.tolist()
    ['rigid', 'elastic']
    >>> bool(np.isclose(r.sinkage[1], plate_sinkage(loam, 1e5, 0.205), rtol=1e-12))   # z = (p / k)^(1/n)
    True
    """

    geometry: SoftSoilTireGeometry
    soil: Soil
    c1: float = parameter("-", "maximum-stress angle coefficient c1", default=0.43, ge=0, le=1)
    c2: float = parameter("-", "maximum-stress angle slip coefficient c2", default=0.32, ge=0, le=1)
    rebound: float = parameter("-", "exit over entry angle (rebound)", default=0.0, ge=0, le=1)

    @property
    def rigid_wheel(self) -> RigidWheel:
        """The :class:`RigidWheel` of the same size on the same soil (the rigid mode)."""
        cached = self.__dict__.get("_rigid")
        if cached is None:
            cached = RigidWheel(radius=self.geometry.radius, width=self.geometry.width, soil=self.soil, c1=self.c1,
                                c2=self.c2, rebound=self.rebound)
            object.__setattr__(self, "_rigid", cached)
        return cached

    def elastic(self, load) -> np.ndarray:
        """Where the tire runs in the elastic (flattened) mode.

        Parameters
        ----------
        load : array_like
            Normal load W [N], >= 0.

        Returns
        -------
        ndarray of bool
            True where p_i + p_c < the critical ground pressure at the load (never for a rigid
            wheel, ``inflation_pressure=None``).
        """
        w = checked_array("load", load, ge=0.0)
        g = self.geometry
        if g.inflation_pressure is None:
            return np.zeros(w.shape, dtype=bool)
        return g.stiffness_pressure < critical_ground_pressure(self.soil, np.maximum(w, 1e-9), 2.0 * g.radius,
                                                               g.width)

    def solve(self, load, slip, slip_angle=None, *, nodes: int = QUADRATURE_NODES) -> WheelSoilResult:
        """Steady state at given loads, slips and slip angles (see :meth:`RigidWheel.solve`).

        Parameters
        ----------
        load : array_like
            Normal load W [N], >= 0.
        slip : array_like
            s [-] in [-1, 1].
        slip_angle : array_like, optional
            alpha [rad] (ISO-W) for the side force.
        nodes : int
            Gauss-Legendre nodes per sub-interval of the rigid mode's arc, 1 to
            :data:`~vehdyn.tire.terramechanics.wong_reece.MAX_QUADRATURE_NODES`.

        Returns
        -------
        WheelSoilResult
            Of the broadcast shape; ``mode`` says which mode each point ran in.
        """
        nodes = check_solver_settings(nodes, 1e-10, 1)[0]
        w = checked_array("load", load, ge=0.0)
        s = check_slip(slip)
        a = None if slip_angle is None else checked_array("slip_angle", slip_angle)
        arrays = np.broadcast_arrays(w, s) if a is None else np.broadcast_arrays(w, s, a)
        shape = arrays[0].shape
        flat = [np.ascontiguousarray(v, dtype=float).reshape(-1) for v in arrays]
        elastic = self.elastic(flat[0])
        rigid = ~elastic
        fields = [f.name for f in dataclasses.fields(WheelSoilResult)]
        out = {name: np.zeros(flat[0].size) for name in fields}
        out["stuck"] = np.zeros(flat[0].size, dtype=bool)
        out["converged"] = np.ones(flat[0].size, dtype=bool)  # the elastic mode is a closed form
        out["mode"] = np.where(elastic, "elastic", "rigid")
        for mask, part in ((rigid, self._solve_rigid), (elastic, self._solve_elastic)):
            if np.any(mask):
                result = part(*(v[mask] for v in flat), nodes=nodes) if a is not None else \
                    part(flat[0][mask], flat[1][mask], None, nodes=nodes)
                for name in fields:
                    if name != "mode" and getattr(result, name) is not None:
                        out[name][mask] = getattr(result, name)
        return WheelSoilResult(**{k: v.reshape(shape) for k, v in out.items()})

    def _solve_rigid(self, load, slip, slip_angle, *, nodes):
        return self.rigid_wheel.solve(load, slip, slip_angle, nodes=nodes)

    def _solve_elastic(self, load, slip, slip_angle, *, nodes):
        g, soil = self.geometry, self.soil
        p = g.stiffness_pressure
        b = g.width
        k = soil.modulus(b)
        plate = (p / k) ** (1.0 / soil.n)
        stuck = np.full(load.shape, plate >= g.radius)  # the flat section would lie above the axle
        z = np.full(load.shape, min(plate, g.radius))  # forces of a stuck tire at z = r, as the rigid wheel's
        length = load / (b * p)
        limit = b * length * soil.cohesion + load * math.tan(soil.friction_angle)  # A c + W tan(phi)
        thrust = np.sign(slip) * limit * mobilized_fraction(np.abs(slip) * length / soil.shear_modulus)
        resistance = b * k * z ** (soil.n + 1.0) / (soil.n + 1.0)
        drawbar = thrust - resistance
        torque = thrust * g.radius
        lateral = np.zeros_like(load)
        if slip_angle is not None:
            lateral = flat_side_force(soil, b, load, length, z, travel_ratio(slip), slip_angle)
        zero = np.zeros_like(load)
        return WheelSoilResult(load=load, slip=slip, sinkage=z, entry_angle=zero, exit_angle=zero,
                               max_stress_angle=zero, drawbar_pull=drawbar, thrust=thrust, motion_resistance=resistance,
                               torque=torque, tractive_efficiency=efficiency(drawbar, torque, g.radius, slip),
                               lateral_force=lateral, stuck=stuck, mode=np.full(load.shape, "elastic"))
