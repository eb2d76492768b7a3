"""Rigid wheel on deformable soil: the Wong-Reece stress distribution around the contact arc.

The wheel of radius r and width b touches the soil between the entry angle theta_1 (ahead of the
vertical, sinkage ``z = r (1 - cos theta_1)``) and the exit angle ``theta_2 = -rebound theta_1``
(behind it; 0 without rebound). The normal stress peaks at ``theta_m = (c1 + c2 s) theta_1``
(Wong and Reece 1967; c1 ~ 0.43, c2 ~ 0.32 for sand, measured on driven wheels; for braked wheels,
s < 0, the same line is extrapolated, clipped to 0 <= theta_m <= theta_1) and follows Bekker's law ahead of it and a
mirrored copy behind it, with ``k = k_c / b + k_phi``::

    sigma(theta) = k r^n (cos theta - cos theta_1)^n                      theta_m <= theta <= theta_1
    sigma(theta) = k r^n (cos theta* - cos theta_1)^n,
        theta* = theta_1 - (theta - theta_2) / (theta_m - theta_2) (theta_1 - theta_m)   theta_2 <= theta < theta_m

The shear stress follows Janosi and Hanamoto, ``tau = (c + sigma tan phi) (1 - exp(-|j| / K)) sgn j``,
with the shear displacement of the soil element that entered at theta_1::

    j(theta) = r [(theta_1 - theta) - (1 - s) (sin theta_1 - sin theta)]       driven, s = 1 - V / (r omega) in [0, 1]
    j(theta) = r [(1 + s) (theta_1 - theta) - (sin theta_1 - sin theta)]       braked, s = r omega / V - 1 in [-1, 0)

(s = 1: spinning in place; s = -1: locked). The braked form follows the soil element by the
wheel's rotation scaled to its travel: it is continuous with the driven form at s = 0 and gives
the locked wheel's sliding distance ``-r (sin theta_1 - sin theta)`` at s = -1. The wheel's forces are the stress integrals::

    W  = r b int (sigma cos theta + tau sin theta) d theta       vertical load (solved for theta_1)
    H  = r b int tau cos theta d theta                            thrust
    R  = r b int sigma sin theta d theta                          motion (compaction) resistance
    DP = H - R                                                    drawbar pull
    T  = r^2 b int tau d theta                                    driving torque

Tractive efficiency ``eta = DP V / (T omega)`` with ``V / (r omega) = 1 - s`` (driven) or
``1 / (1 + s)`` (braked), reported where DP > 0 and T > 0 (else 0).

Side force at the slip angle alpha: side shear plus sidewall bulldozing on the same arc, see
:mod:`~vehdyn.tire.terramechanics.lateral` (after Ishigami et al. 2007).

Numerics: Gauss-Legendre quadrature (fixed nodes, 16 per sub-interval) on each of
[theta_2, theta_m] and [theta_m, theta_1] (sigma has a kink at theta_m; the rear nodes map onto the
front nodes, so sigma is evaluated once), vectorized over every (load, slip) pair. Against adaptive
quadrature of the same equations (:mod:`~vehdyn.tire.terramechanics.reference`) the integrals agree
to 1e-6 for n >= 1 and 2e-4 at n = 0.11 (sigma ~ (theta_1 - theta)^n at the entry). The vertical
equilibrium is solved for all pairs at once by the Illinois (modified regula falsi) method in the
variable ``q = (z / r)^(n + 1/2)``, in which the supported load is nearly linear (about ten
iterations to a relative load error of 1e-10). A load that the wheel cannot carry before ``z = r``
(theta_1 = 90 degrees) leaves the wheel stuck: the result says so (``stuck``, ``status``) and holds
the forces at ``z = r``.

References
----------
J. Y. Wong and A. R. Reece, "Prediction of rigid wheel performance based on the analysis of
soil-wheel stresses, part I: performance of driven rigid wheels", J. Terramechanics 4(1), 81-98,
1967; "part II: performance of towed rigid wheels", J. Terramechanics 4(2), 7-25, 1967.
J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 2.7.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.base import ParameterSet, parameter
from vehdyn.tire.terramechanics.bekker import checked_array
from vehdyn.tire.terramechanics.lateral import arc_side_force
from vehdyn.tire.terramechanics.soil import Soil

__all__ = ["RigidWheel", "WheelSoilResult", "travel_ratio", "check_slip"]

#: Gauss-Legendre nodes per sub-interval of the contact arc.
QUADRATURE_NODES = 16
#: The most nodes per sub-interval :meth:`RigidWheel.solve` takes (the integrands are smooth but
#: for sigma's power at the entry: 16 nodes agree with adaptive quadrature to 1e-6, see above).
MAX_QUADRATURE_NODES = 1000
_STUCK_ANGLE = 0.5 * math.pi
_CHUNK_VALUES = 4_000_000  # stress samples (points x nodes) evaluated at once: ~32 MB per array


def check_solver_settings(nodes, rtol, max_iterations) -> tuple[int, float, int]:
    """``nodes``, ``rtol`` and ``max_iterations`` of a wheel's solve, checked; ParameterError naming a
    setting that cannot produce the answer (no node, no iteration, a tolerance that is not one)."""
    from vehdyn.params.checks import finite_number, whole_number

    nodes = whole_number(nodes, "nodes", minimum=1, maximum=MAX_QUADRATURE_NODES)
    rtol = finite_number(rtol, "rtol", positive=True, maximum=0.1)
    max_iterations = whole_number(max_iterations, "max_iterations", minimum=1)
    return nodes, rtol, max_iterations


def check_slip(slip):
    """A slip as a float array, checked.

    Parameters
    ----------
    slip : array_like
        s [-]: ``1 - V/(r omega)`` driven (>= 0), ``r omega/V - 1`` braked (< 0).

    Returns
    -------
    ndarray
        ``slip`` as floats.

    Raises
    ------
    ParameterError
        If a value is not finite or outside [-1, 1] (key ``slip``).
    """
    s = checked_array("slip", slip)
    bad = np.abs(s) > 1.0
    if np.any(bad):
        value = float(s[bad].flat[0]) if s.ndim else float(s)
        raise ParameterError(f"slip must be in [-1, 1] (driven s = 1 - V/(r omega), braked s = r omega/V - 1), "
                             f"got {value!r}", key="slip", value=value)
    return s


def travel_ratio(slip):
    """The travel ratio of a wheel at a slip.

    Parameters
    ----------
    slip : array_like
        s [-] in [-1, 1].

    Returns
    -------
    ndarray
        ``V / (r omega)`` [-]: ``1 - s`` driven (s >= 0), ``1 / (1 + s)`` braked (inf at s = -1,
        the locked wheel).
    """
    s = np.asarray(slip, dtype=float)
    with np.errstate(divide="ignore"):
        return np.where(s >= 0.0, 1.0 - s, 1.0 / np.maximum(1.0 + s, 0.0))


@dataclasses.dataclass(frozen=True)
class WheelSoilResult:
    """Steady state of a wheel on soil; every array has the broadcast shape of (load, slip).

    Attributes
    ----------
    load, slip : ndarray
        The inputs: W [N] and s [-].
    sinkage : ndarray
        z [m] (the radius where stuck).
    entry_angle, exit_angle, max_stress_angle : ndarray
        theta_1, theta_2, theta_m [rad].
    drawbar_pull, thrust, motion_resistance : ndarray
        DP = H - R, H, R [N] (+ forward).
    torque : ndarray
        Driving torque T [N*m] the soil resists (+ driving).
    tractive_efficiency : ndarray
        eta [-] (0 where DP <= 0 or T <= 0).
    lateral_force : ndarray
        F_y [N] at the given slip angle (ISO-W; 0 without one).
    stuck : ndarray of bool
        The soil cannot carry the load before the sinkage reaches the radius.
    mode : ndarray of str
        ``"rigid"``, or ``"elastic"`` for a flexible tire in its flat-contact mode [text, no
        unit]; ``"invalid"`` where :class:`SoftSoilTire` got a non-finite input.
    converged : ndarray of bool, optional
        The vertical equilibrium was met within ``rtol`` in ``max_iterations`` (the stuck points and
        the elastic mode's closed form count as converged); None: all converged.
    """

    load: np.ndarray
    slip: np.ndarray
    sinkage: np.ndarray
    entry_angle: np.ndarray
    exit_angle: np.ndarray
    max_stress_angle: np.ndarray
    drawbar_pull: np.ndarray
    thrust: np.ndarray
    motion_resistance: np.ndarray
    torque: np.ndarray
    tractive_efficiency: np.ndarray
    lateral_force: np.ndarray
    stuck: np.ndarray
    mode: np.ndarray
    converged: np.ndarray | None = None

    @property
    def status(self) -> np.ndarray:
        """``"ok"``, ``"stuck"`` or ``"unconverged"`` (the root find ran out of iterations: the
        sinkage and forces there are the last iterate's, not the equilibrium's) per point."""
        status = np.where(self.stuck, "stuck", "ok")
        if self.converged is not None:
            status = np.where(self.converged | self.stuck, status, "unconverged")
        return status


def efficiency(drawbar_pull, torque, radius, slip):
    """Tractive efficiency ``DP V / (T omega)`` [-] (0 where DP <= 0 or T <= 0)."""
    ok = (drawbar_pull > 0.0) & (torque > 0.0)
    ratio = np.where(ok, travel_ratio(np.where(ok, slip, 0.0)), 0.0)
    return np.where(ok, drawbar_pull * radius * ratio / np.where(ok, torque, 1.0), 0.0)


@dataclasses.dataclass(frozen=True, kw_only=True)
class RigidWheel(ParameterSet):
    r"""A rigid wheel on soil: the Wong-Reece stress distribution around the contact arc.

    The wheel touches the soil from the entry angle theta_1 (sinkage z = r (1 - cos theta_1))
    back to the exit angle theta_2 = -rebound theta_1. The normal stress follows Bekker's law
    ahead of the angle of maximum stress theta_m = (c1 + c2 s) theta_1 and a mirrored copy behind
    it; the shear stress follows Janosi and Hanamoto with the shear displacement j of the soil
    element that entered at theta_1:

    .. math::

        \sigma(\theta) = k r^n (\cos\theta - \cos\theta_1)^n \quad (\theta_m \le \theta
        \le \theta_1), \qquad
        \sigma(\theta) = k r^n (\cos\theta^* - \cos\theta_1)^n, \quad
        \theta^* = \theta_1 - \frac{\theta - \theta_2}{\theta_m - \theta_2} (\theta_1 - \theta_m)
        \quad (\theta_2 \le \theta < \theta_m)

        \tau = (c + \sigma \tan\phi) \left(1 - e^{-|j| / K}\right) \operatorname{sgn} j,
        \qquad j = r \left[(\theta_1 - \theta) - (1 - s)(\sin\theta_1 - \sin\theta)\right]
        \ \ (s \ge 0), \qquad
        j = r \left[(1 + s)(\theta_1 - \theta) - (\sin\theta_1 - \sin\theta)\right] \ \ (s < 0)

        W = r b \int_{\theta_2}^{\theta_1} (\sigma \cos\theta + \tau \sin\theta) \, d\theta,
        \quad H = r b \int \tau \cos\theta \, d\theta, \quad
        R = r b \int \sigma \sin\theta \, d\theta, \quad DP = H - R, \quad
        T = r^2 b \int \tau \, d\theta

    with k = k_c / b + k_phi; :meth:`solve` finds theta_1 from the vertical equilibrium W = load.
    Tractive efficiency eta = DP V / (T omega). The side force at a slip angle is that of
    :mod:`~vehdyn.tire.terramechanics.lateral` (Ishigami et al. 2007).

    Parameters
    ----------
    radius : float
        r [m].
    width : float
        b [m].
    soil : Soil
    c1, c2 : float
        Coefficients of the maximum-stress angle ``theta_m = (c1 + c2 s) theta_1`` [-]
        (Wong and Reece 1967 for sand: 0.43, 0.32). ``c1 = c2 = 0`` puts the maximum at the bottom
        as Bekker's closed forms assume.
    rebound : float
        Exit angle over entry angle, ``-theta_2 / theta_1`` [-] (0: no rebound, the default).

    Notes
    -----
    Gauss-Legendre quadrature with fixed nodes on each side of theta_m, vectorized over every
    (load, slip) pair; the module docstring gives its accuracy against adaptive quadrature
    (:mod:`~vehdyn.tire.terramechanics.reference`) and the root finder.

    References
    ----------
    .. [1] J. Y. Wong and A. R. Reece, "Prediction of rigid wheel performance based on the
       analysis of soil-wheel stresses, part I: performance of driven rigid wheels",
       J. Terramechanics 4(1), 81-98, 1967; "part II: performance of towed rigid wheels",
       J. Terramechanics 4(2), 7-25, 1967.
    .. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, ch. 2 (sec. 2.7).
    .. [3] Z. Janosi and B. Hanamoto, "The analytical determination of drawbar pull as a function
       of slip for tracked vehicles in deformable soils", 1st Int. Conf. Terrain-Vehicle Systems,
       Turin, 1961.

    Examples
    --------
    >>> import numpy as np
    >>> from vehdyn.tire.terramechanics import RigidWheel, load_soil, parabolic_wheel_sinkage
    >>> sand = load_soil("dry_sand")
    >>> wheel = RigidWheel(radius=0.3, width=0.2, soil=sand)
    >>> r = wheel.solve(1500.0, [0.0, 0.2, 0.5])                          # load [N], slips [-]
    >>> np.round(r.drawbar_pull, 1).tolist()                              # towed wheel: resistance [N]
    [-154.1, 36.2, 87.1]
    >>> bool(np.allclose(wheel.supported_load(r.sinkage, r.slip), 1500.0, rtol=1e-9))   # equilibrium
    True

    With the maximum stress at the bottom (c1 = c2 = 0) and no slip, the sinkage is close to that
    of the parabolic-arc closed form (z0 / D = 9 % here):

    >>> bottom = RigidWheel(radius=0.3, width=0.2, soil=sand, c1=0.0, c2=0.0).solve(1500.0, 0.0)
    >>> round(float(bottom.sinkage) * 1e3, 1), round(parabolic_wheel_sinkage(sand, 1500.0, 0.6, 0.2) * 1e3, 1)  # [mm]
    (54.9, 55.3)
    """

    radius: float = parameter("m", "wheel radius r", gt=0)
    width: float = parameter("m", "wheel width b", gt=0)
    soil: Soil
    c1: float = parameter("-", "maximum-stress angle coefficient c1", default=0.43, ge=0, le=1)
    c2: float = parameter("-", "maximum-stress angle slip coefficient c2", default=0.32, ge=0, le=1)
    rebound: float = parameter("-", "exit over entry angle (rebound)", default=0.0, ge=0, le=1)

    def check(self) -> None:
        # k = k_c / b + k_phi (checked > 0), and the factor k r^n of sigma, computed once
        object.__setattr__(self, "_stress_factor", self.soil.modulus(self.width) * self.radius**self.soil.n)

    # ------------------------------------------------------------------ stress integrals
    def _integrals(self, theta1, slip, tan_alpha=None, nodes=QUADRATURE_NODES, full=True):
        """Stress integrals for 1-D arrays theta1, slip.

        Returns W alone (``full=False``, the root find) or (W, H, R, T, F_y magnitude or None,
        theta_2, theta_m). The Gauss nodes of the rear interval map onto the front nodes in reverse
        order (theta* of a rear node is the mirror front node), so sigma is evaluated once.
        """
        soil, r, b = self.soil, self.radius, self.width
        x, w = _gauss(nodes)
        t1 = theta1[:, None]
        t2 = -self.rebound * t1
        tm = np.clip(self.c1 + self.c2 * slip, 0.0, 1.0)[:, None] * t1
        half_front = 0.5 * (t1 - tm)
        half_rear = 0.5 * (tm - t2)
        theta = np.concatenate([tm + half_front * (x + 1.0), t2 + half_rear * (x + 1.0)], axis=1)
        weight = np.concatenate([half_front * w, half_rear * w], axis=1)
        cos_t = np.cos(theta)
        sin_t = np.sin(theta)
        cos1 = np.cos(t1)
        depth = cos_t[:, :nodes] - cos1  # local sinkage / r of the front nodes
        np.maximum(depth, 0.0, out=depth)
        sigma_front = depth ** soil.n
        sigma_front *= self._stress_factor
        sigma = np.concatenate([sigma_front, sigma_front[:, ::-1]], axis=1)
        s = slip[:, None]
        driven = s >= 0.0
        j = (np.where(driven, 1.0, 1.0 + s) * r) * (t1 - theta)
        j -= (np.where(driven, 1.0 - s, 1.0) * r) * (np.sin(t1) - sin_t)
        strength = sigma * math.tan(soil.friction_angle)
        strength += soil.cohesion
        mobilized = np.abs(j)
        mobilized *= -1.0 / soil.shear_modulus
        np.expm1(mobilized, out=mobilized)
        tau = np.copysign(mobilized, j)  # |1 - exp(-|j|/K)| sgn j
        tau *= strength
        rb = r * b
        sw = sigma * weight
        tw = tau * weight
        load = rb * (np.einsum("ij,ij->i", sw, cos_t) + np.einsum("ij,ij->i", tw, sin_t))
        if not full:
            return load
        thrust = rb * np.einsum("ij,ij->i", tw, cos_t)
        resistance = rb * np.einsum("ij,ij->i", sw, sin_t)
        torque = r * rb * tw.sum(axis=1)
        side = None
        if tan_alpha is not None:
            side = arc_side_force(soil, r, b, theta, weight, strength, cos_t, t1, travel_ratio(s), tan_alpha)
        return load, thrust, resistance, torque, side, t2[:, 0], tm[:, 0]

    def _angle(self, q):
        """Entry angle for q = (z / r)^(n + 1/2) in [0, 1]."""
        z_over_r = q ** (1.0 / (self.soil.n + 0.5))
        return np.arccos(1.0 - z_over_r)

    def supported_load(self, sinkage, slip=0.0):
        """Vertical load the soil carries at a given sinkage and slip (no root find).

        Parameters
        ----------
        sinkage : array_like
            z [m], >= 0 (values above the radius count as the radius).
        slip : array_like
            s [-] in [-1, 1].

        Returns
        -------
        float or ndarray
            W [N], of the broadcast shape.
        """
        z = checked_array("sinkage", sinkage, ge=0.0)
        s = check_slip(slip)
        z, s = np.broadcast_arrays(z, s)
        theta1 = np.arccos(1.0 - np.minimum(z.ravel(), self.radius) / self.radius)
        out = self._integrals(theta1, s.ravel(), full=False).reshape(z.shape)
        return float(out) if out.ndim == 0 else out

    # ------------------------------------------------------------------ solve
    def solve(self, load, slip, slip_angle=None, *, nodes: int = QUADRATURE_NODES, rtol: float = 1e-10,
              max_iterations: int = 100) -> WheelSoilResult:
        """Steady state at the loads W [N] and slips s [-] (broadcast against each other).

        Parameters
        ----------
        load : array_like
            Vertical load W [N], >= 0.
        slip : array_like
            s in [-1, 1]: ``1 - V/(r omega)`` driven (>= 0), ``r omega/V - 1`` braked (< 0).
        slip_angle : array_like, optional
            alpha [rad] (ISO-W) for the side force; ``|alpha| < pi/2``.
        nodes : int
            Gauss-Legendre nodes per sub-interval of the arc, 1 to :data:`MAX_QUADRATURE_NODES`.
        rtol : float
            Relative tolerance of the vertical equilibrium [-], in (0, 0.1].
        max_iterations : int
            Iterations of the root find at most (>= 1); a point that has not met ``rtol`` by then
            has the status ``"unconverged"`` (about ten iterations reach 1e-10).

        Returns
        -------
        WheelSoilResult
            Of the broadcast shape; ``stuck`` where the soil cannot carry the load before the
            sinkage reaches the radius (the forces are then those at z = r); ``status``
            ``"ok"``, ``"stuck"`` or ``"unconverged"`` per point.

        Raises
        ------
        ParameterError
            A load, slip or slip angle out of range, or a ``nodes``, ``rtol`` or ``max_iterations``
            that cannot produce the answer.
        """
        nodes, rtol, max_iterations = check_solver_settings(nodes, rtol, max_iterations)
        w = checked_array("load", load, ge=0.0)
        s = check_slip(slip)
        arrays = [w, s]
        if slip_angle is not None:
            a = checked_array("slip_angle", slip_angle)
            if np.any(np.abs(a) >= 0.5 * math.pi):
                bad = float(a[np.abs(a) >= 0.5 * math.pi].flat[0]) if a.ndim else float(a)
                raise ParameterError(f"slip_angle must be in (-pi/2, pi/2) [rad], got {bad!r}", key="slip_angle",
                                     value=bad)
            arrays.append(a)
        arrays = np.broadcast_arrays(*arrays)
        shape = arrays[0].shape
        w, s = (np.ascontiguousarray(v, dtype=float).reshape(-1) for v in arrays[:2])
        tan_alpha = np.tan(arrays[2].reshape(-1)) if slip_angle is not None else None
        # in chunks, so that the (points x 2 nodes) stress arrays stay small however many points
        chunk = max(1, _CHUNK_VALUES // (2 * nodes))
        parts = [self._solve_flat(w[k:k + chunk], s[k:k + chunk],
                                  None if tan_alpha is None else tan_alpha[k:k + chunk], nodes, rtol, max_iterations)
                 for k in range(0, max(w.size, 1), chunk)]
        flat = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
        shaped = {k: v.reshape(shape) for k, v in flat.items()}
        return WheelSoilResult(**shaped, mode=np.full(shape, "rigid"))

    def _solve_flat(self, w, s, tan_alpha, nodes, rtol, max_iterations) -> dict:
        """The fields of a WheelSoilResult for 1-D arrays of loads and slips."""
        q, converged = self._root(w, s, nodes, rtol, max_iterations)
        stuck = q >= 1.0
        theta1 = self._angle(q)
        theta1[stuck] = _STUCK_ANGLE
        _, thrust, resistance, torque, side, t2, tm = self._integrals(theta1, s, tan_alpha, nodes)
        sinkage = self.radius * (1.0 - np.cos(theta1))
        sinkage[stuck] = self.radius
        drawbar = thrust - resistance
        lateral = np.zeros_like(drawbar) if side is None else side
        return dict(load=w, slip=s, sinkage=sinkage, entry_angle=theta1, exit_angle=t2, max_stress_angle=tm,
                    drawbar_pull=drawbar, thrust=thrust, motion_resistance=resistance, torque=torque,
                    tractive_efficiency=efficiency(drawbar, torque, self.radius, s), lateral_force=lateral,
                    stuck=stuck, converged=converged)

    def _root(self, load, slip, nodes, rtol, max_iterations):
        """q in [0, 1] with W(q) = load for every pair (Illinois); q = 1 where the wheel is stuck.
        Returns q and whether each point met ``rtol`` (or is stuck, or carries no load)."""
        lo = np.zeros_like(load)
        hi = np.ones_like(load)
        f_lo = -load
        f_hi = self._integrals(np.full_like(load, _STUCK_ANGLE), slip, None, nodes, full=False) - load
        stuck = f_hi < 0.0
        done = stuck | (load <= 0.0)
        q = np.where(stuck, 1.0, 0.0)
        tolerance = rtol * np.maximum(load, 1e-300)
        last = np.zeros(load.shape, dtype=np.int8)  # side kept last time: -1 lo, +1 hi
        for _ in range(max_iterations):
            if np.all(done):
                break
            denominator = f_hi - f_lo
            trial = np.where(done, q, (lo * f_hi - hi * f_lo) / np.where(denominator > 0.0, denominator, 1.0))
            trial = np.clip(trial, lo, hi)
            f = self._integrals(self._angle(trial), slip, None, nodes, full=False) - load
            converged = ~done & ((np.abs(f) <= tolerance) | (hi - lo <= 1e-15))
            q = np.where(done, q, trial)
            done = done | converged
            below = ~done & (f < 0.0)
            above = ~done & (f >= 0.0)
            # Illinois: halve the stale end's function value when the same end is kept twice
            f_hi = np.where(below & (last == -1), 0.5 * f_hi, f_hi)
            f_lo = np.where(above & (last == 1), 0.5 * f_lo, f_lo)
            lo = np.where(below, trial, lo)
            f_lo = np.where(below, f, f_lo)
            hi = np.where(above, trial, hi)
            f_hi = np.where(above, f, f_hi)
            last = np.where(below, -1, np.where(above, 1, last)).astype(np.int8)
        return q, done


_GAUSS_CACHE: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def _gauss(nodes: int):
    """Gauss-Legendre nodes and weights on [-1, 1] (cached)."""
    if nodes not in _GAUSS_CACHE:
        _GAUSS_CACHE[nodes] = np.polynomial.legendre.leggauss(int(nodes))
    return _GAUSS_CACHE[nodes]
