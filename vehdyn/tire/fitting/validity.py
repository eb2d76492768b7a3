"""Validity conditions of the Magic Formula on a dense grid: :func:`check_validity`, :class:`ValidityGrid`.

A Magic Formula curve ``D sin(C atan(B x - E (B x - atan(B x))))`` has its textbook shape only when
its factors keep their signs (Pacejka 2012, sec. 4.3.1-4.3.2): the peak D and the shape factor C
positive, the curvature factor E <= 1 (for E > 1 the curve folds back: the argument of the sine
stops growing with slip), and the stiffness B C D of the sign of the tire's slope at zero. The
factors are polynomials in the load increment dfz, the camber and the pressure increment dpi, so a
coefficient set that satisfies the conditions at the measured loads and cambers may break them
between or beside them. These conditions are checked here on a grid that fills the span of the
data (every load, camber, pressure and slip between the smallest and the largest measured), for:

==========================  ======================================================================
condition                   quantity (book equation)
==========================  ======================================================================
``Cx > 0``, ``Cy > 0``      shape factors of the pure-slip forces (4.E11, 4.E21)
``Dx > 0``, ``Dy > 0``      friction coefficients mu_x, mu_y (4.E13, 4.E23): the peaks' sign
``Kxk sign``, ``Kya sign``  slip and cornering stiffness keep the sign of PKX1 and PKY1 (4.E15, 4.E25)
``Ex <= 1``, ``Ey <= 1``    curvature factors, both slip signs (4.E14, 4.E24)
``Ct > 0``, ``Dt > 0``      shape factor and peak of the pneumatic trail (4.E41, 4.E42 / A60)
``trail > 0``               pneumatic trail at small slip, |alpha| <= 2 deg (4.E33, 4.E73)
``Et <= 1``                 curvature factor of the trail over the slip angles (4.E44)
``Cxa > 0``, ``Cyk > 0``    shape factors of the combined-slip weighting functions (4.E55, 4.E63)
``Exa <= 1``, ``Eyk <= 1``  their curvature factors (4.E56, 4.E64)
``Gxa > 0``, ``Gyk > 0``    the weighting functions themselves over the slip span (4.E51, 4.E59)
==========================  ======================================================================

:func:`fit_magic_formula <vehdyn.tire.fitting.fit_magic_formula>` adds these conditions (with a
small margin) to the least-squares problem of every step as penalties, and reports what remains on
:attr:`TireFit.validity <vehdyn.tire.fitting.TireFit.validity>`. The friction coefficients, slip
stiffness, cornering stiffness and weighting functions come from the model's own equations
(:mod:`vehdyn.tire.mf_forces`); the curvature factors and the trail's factors, which the model does
not return, are written here once more, and a test holds them to the model's trail and forces.

References
----------
H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012: sec. 4.3.1 (the
Magic Formula and the meaning of B, C, D, E; E <= 1), sec. 4.3.2 and the appendix of chapter 4
(eqs. 4.E1-4.E78).
I. J. M. Besselink, A. J. C. Schmeitz, H. B. Pacejka, "An improved Magic Formula/Swift tyre model
that can handle inflation pressure changes", *Vehicle System Dynamics* 48 (2010), 337-352, eqs.
A58, A60 (the trail's Bt and Dt as vehdyn evaluates them).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.tire._mf_ops import NumpyOps
from vehdyn.tire.mf_forces import lateral_combined_factor, lateral_pure, longitudinal_combined, longitudinal_pure

__all__ = ["ValidityGrid", "check_validity", "CONDITIONS", "TRAIL_SMALL_SLIP"]

TRAIL_SMALL_SLIP = math.radians(2.0)
"""|alpha| [rad] up to which the pneumatic trail must be positive."""

CONDITIONS = {
    "Cx > 0": ("longitudinal", "shape factor of Fx0 (4.E11)"),
    "Dx > 0": ("longitudinal", "friction coefficient mu_x, the sign of the peak of Fx0 (4.E13)"),
    "Kxk sign": ("longitudinal", "slip stiffness Kxk of the sign of PKX1 (4.E15)"),
    "Ex <= 1": ("longitudinal", "curvature factor of Fx0, both slip signs (4.E14)"),
    "Cy > 0": ("lateral", "shape factor of Fy0 (4.E21)"),
    "Dy > 0": ("lateral", "friction coefficient mu_y, the sign of the peak of Fy0 (4.E23)"),
    "Kya sign": ("lateral", "cornering stiffness Kya of the sign of PKY1 (4.E25)"),
    "Ey <= 1": ("lateral", "curvature factor of Fy0, both slip signs (4.E24)"),
    "Ct > 0": ("trail", "shape factor of the pneumatic trail (4.E41)"),
    "Dt > 0": ("trail", "peak of the pneumatic trail (4.E42, Besselink A60)"),
    "trail > 0": ("trail", "pneumatic trail at |alpha| <= TRAIL_SMALL_SLIP (4.E33)"),
    "Et <= 1": ("trail", "curvature factor of the pneumatic trail over the slip angles (4.E44)"),
    "Cxa > 0": ("combined_x", "shape factor of Gxa (4.E55)"),
    "Exa <= 1": ("combined_x", "curvature factor of Gxa (4.E56)"),
    "Gxa > 0": ("combined_x", "weighting function of Fx in combined slip (4.E51)"),
    "Cyk > 0": ("combined_y", "shape factor of Gyk (4.E63)"),
    "Eyk <= 1": ("combined_y", "curvature factor of Gyk (4.E64)"),
    "Gyk > 0": ("combined_y", "weighting function of Fy in combined slip (4.E59)"),
}
"""Condition -> (family, what it bounds). Each condition is a quantity g that must be <= 0 (see
:func:`check_validity`); the family says which coefficients move it."""

_FAMILY_OF_COEFFICIENT = (
    (re.compile(r"P[A-Z]X\d+$"), "longitudinal"),
    (re.compile(r"P[A-Z]Y\d+$"), "lateral"),
    (re.compile(r"(Q[BCDEH]Z\d+|PPZ1)$"), "trail"),
    (re.compile(r"R[A-Z]X\d+$"), "combined_x"),
    (re.compile(r"R[A-Z]Y\d+$"), "combined_y"),
)

MARGINS = {"E": 0.01, "C": 0.01, "D": 0.01, "K": 0.1, "trail": 1e-3, "G": 0.01}
"""Margins the fit keeps from each kind of bound (in the units of g: E and C, D [friction
coefficient], K [stiffness per load, 1/rad or -], trail [over the unloaded radius], G [-])."""


def families(names):
    """The condition families the coefficients ``names`` move.

    Parameters
    ----------
    names : iterable of str
        Coefficient names (``"PDY1"``, ``"QEZ5"``, ...).

    Returns
    -------
    set of str
        Families of :data:`CONDITIONS` (``"longitudinal"``, ``"lateral"``, ``"trail"``,
        ``"combined_x"``, ``"combined_y"``) whose quantities depend on any of them.
    """
    found = set()
    for name in names:
        for pattern, family in _FAMILY_OF_COEFFICIENT:
            if pattern.match(name):
                found.add(family)
    return found


@dataclass(frozen=True)
class ValidityGrid:
    """Where the validity conditions are checked: every combination of these values.

    Parameters
    ----------
    loads : ndarray
        Normal loads [N].
    cambers : ndarray
        Inclination angles [rad].
    pressures : ndarray
        Inflation pressures [Pa] (one value: the tire's nominal pressure when the data have none).
    slip_angles : ndarray
        Slip angles [rad] (the trail's curvature and the combined-slip weighting functions).
    slip_ratios : ndarray
        Slip ratios [-] (the combined-slip weighting functions).
    speed : float
        Forward speed [m/s] of every point.
    """

    loads: np.ndarray
    cambers: np.ndarray
    pressures: np.ndarray
    slip_angles: np.ndarray
    slip_ratios: np.ndarray
    speed: float

    @classmethod
    def from_data(cls, data, tire=None, *, n_loads=9, n_cambers=9, n_pressures=5, n_slips=13):
        """The grid that fills the span of measured data.

        Parameters
        ----------
        data : pandas.DataFrame or mapping of str to array_like
            Canonical columns (:func:`vehdyn.tire.read_tire_data`): ``fz`` [N] and, where present,
            ``gamma``, ``alpha`` [rad], ``kappa`` [-], ``pressure`` [Pa], ``vx`` [m/s].
        tire : MagicFormula, optional
            Supplies the pressure and speed where the data have none (INFLPRES, LONGVL).
        n_loads, n_cambers, n_pressures, n_slips : int
            Points of each axis between the smallest and the largest value of the data (the zero
            camber and the zero slips are added when inside the span).

        Returns
        -------
        ValidityGrid
        """
        def column(name):
            if name not in data:
                return None
            values = np.asarray(data[name], dtype=float).ravel()
            values = values[np.isfinite(values)]
            return values if values.size else None

        c = None if tire is None else tire._c
        fz = column("fz")
        if fz is None:
            raise ParameterError("the validity grid needs the data's loads (column 'fz')", key="fz", value=None)

        def span(values, n, default, add_zero=False):
            if values is None:
                return np.array([default], dtype=float)
            low, high = float(values.min()), float(values.max())
            points = np.linspace(low, high, n) if high > low else np.array([low])
            if add_zero and low < 0.0 < high:
                points = np.union1d(points, [0.0])
            return points

        loads = span(fz, n_loads, 0.0)
        loads = loads[loads > 0] if np.any(loads > 0) else np.array([float(fz.max())])
        speed = column("vx")
        return cls(loads=loads, cambers=span(column("gamma"), n_cambers, 0.0, True),
                   pressures=span(column("pressure"), n_pressures, 0.0 if c is None else c.INFLPRES),
                   slip_angles=span(column("alpha"), n_slips, 0.0, True),
                   slip_ratios=span(column("kappa"), n_slips, 0.0, True),
                   speed=float(np.median(speed)) if speed is not None else (16.7 if c is None else c.LONGVL))

    def points(self) -> int:
        """Number of load-camber-pressure combinations.

        Returns
        -------
        int
            Loads times cambers times pressures [-].
        """
        return self.loads.size * self.cambers.size * self.pressures.size


def _coarse(values):
    """Every other value of a sorted axis, keeping both ends and zero."""
    if values.size <= 5:
        return values
    kept = values[::2]
    extra = [values[-1]] + ([0.0] if values[0] < 0.0 < values[-1] else [])
    return np.union1d(kept, extra)


def _state(c, fz, kappa, alpha, gamma, vx, pressure):
    from vehdyn.tire.magic_formula import _pass_inputs

    with np.errstate(all="ignore"):
        return _pass_inputs(NumpyOps, c, fz, kappa, alpha, gamma, 0.0, vx, pressure, 0.0, False, True, False, False,
                            False)[0]


class GridStates:
    """The Magic Formula states (post-processed inputs) of a :class:`ValidityGrid`, computed once.

    The state depends on the coefficient record only through fields a fit does not change (FNOMIN,
    NOMPRES, the ranges), so one instance serves every candidate coefficient set of a fit.

    Parameters
    ----------
    c : MFCoefficients
        A coefficient record of the tire (``MagicFormula._c``).
    grid : ValidityGrid
        Where to evaluate.

    Attributes
    ----------
    plain : MFState
        Every load x camber x pressure at zero slip.
    sweep : MFState
        The same at every slip angle of the grid (the trail's curvature).
    small : MFState
        The same at the slip angles 0, +-1/2 and +-1 times :data:`TRAIL_SMALL_SLIP` (those within
        the grid's span).
    combined : MFState
        Every other load, camber, slip angle and slip ratio of the grid at the middle pressure.
    """

    def __init__(self, c, grid: ValidityGrid):
        self.grid = grid
        f, g, p = (a.ravel() for a in np.meshgrid(grid.loads, grid.cambers, grid.pressures, indexing="ij"))
        self.base = (f, g, p)
        n = f.size
        zero = np.zeros(n)
        self.plain = _state(c, f, zero, zero, g, np.full(n, grid.speed), p)
        alphas = grid.slip_angles
        small = TRAIL_SMALL_SLIP * np.array([-1.0, -0.5, 0.0, 0.5, 1.0])
        small = small[(small >= min(alphas.min(), 0.0)) & (small <= max(alphas.max(), 0.0))]
        self.sweep = self._product(c, f, g, p, alphas)
        self.small = self._product(c, f, g, p, small)
        # combined slip: loads x cambers x slip angles x slip ratios at the nominal pressure, every
        # other value of each axis (the weighting functions are smooth; 13^2 x 17^2 points would cost
        # more than the data)
        f2, g2, a2, k2 = (a.ravel() for a in np.meshgrid(_coarse(grid.loads), _coarse(grid.cambers), _coarse(alphas),
                                                           _coarse(grid.slip_ratios), indexing="ij"))
        pressure = float(np.median(grid.pressures))
        self.combined = _state(c, f2, k2, a2, g2, np.full(f2.size, grid.speed), np.full(f2.size, pressure))

    def _product(self, c, f, g, p, alphas):
        m = alphas.size
        return _state(c, np.repeat(f, m), np.zeros(f.size * m), np.tile(alphas, f.size), np.repeat(g, m),
                      np.full(f.size * m, self.grid.speed), np.repeat(p, m))


def trail_factors(c, s):
    """The factors of the pneumatic trail at state ``s``, as the aligning moment evaluates them.

    Parameters
    ----------
    c : MFCoefficients
        The coefficient record.
    s : MFState
        Post-processed inputs (:class:`GridStates`).

    Returns
    -------
    dt : ndarray
        Peak Dt [m] (A60: 4.E42, 4.E43 with the pressure and camber terms).
    bt : ndarray
        Stiffness factor Bt [1/rad] (A58: 4.E40).
    ct : float
        Shape factor Ct [-] (4.E41).
    et : ndarray
        Curvature factor Et [-] (4.E44), before the E <= 1 limit.
    sht : ndarray
        Horizontal shift SHt [rad] (4.E35).

    Notes
    -----
    :func:`vehdyn.tire.mf_moments.aligning_moment` does not return these; they are written here
    once more (without turn slip), and a test holds :func:`trail` built from them to the model's
    trail on every shipped tire.

    References
    ----------
    H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, eqs. 4.E34-4.E44.
    I. J. M. Besselink, A. J. C. Schmeitz, H. B. Pacejka, *Vehicle System Dynamics* 48 (2010), eqs.
    A58, A60.
    """
    xp, dfz, gamma, gamma_star = NumpyOps, s.dfz, s.gamma, s.gamma_star
    dt = (c.QDZ1 + c.QDZ2 * dfz) * (1 - c.PPZ1 * s.dpi) * (1 + c.QDZ3 * gamma + c.QDZ4 * gamma**2) \
        * s.fz_moment * (c.UNLOADED_RADIUS / c.Fz0_prime) * c.LTR  # A60
    bt = (c.QBZ1 + c.QBZ2 * dfz + c.QBZ3 * dfz**2) * (1 + c.QBZ4 * gamma + c.QBZ5 * xp.abs(gamma)) \
        * c.LKY / c.LMUY  # A58
    ct = c.QCZ1  # 4.E41
    sht = c.QHZ1 + c.QHZ2 * dfz + (c.QHZ3 + c.QHZ4 * dfz) * gamma_star  # 4.E35
    alpha_t = s.alpha_star + sht  # 4.E34
    et = (c.QEZ1 + c.QEZ2 * dfz + c.QEZ3 * dfz**2) \
        * (1 + (c.QEZ4 + c.QEZ5 * gamma_star) * (2 / math.pi) * xp.atan(bt * ct * alpha_t))  # 4.E44
    return dt, bt, ct, et, sht


def trail(c, s):
    """Pneumatic trail at state ``s``, zero slip ratio.

    .. math:: t = D_t \\cos\\big(C_t \\arctan(B_t \\alpha_t - E_t (B_t \\alpha_t - \\arctan B_t \\alpha_t))\\big)
              \\cos\\alpha'

    Parameters
    ----------
    c : MFCoefficients
        The coefficient record.
    s : MFState
        Post-processed inputs.

    Returns
    -------
    ndarray
        The trail t [m] (book eq. 4.E33 with the factors of :func:`trail_factors`, Et limited to 1,
        scaled by LFZO and the low-speed factor as eq. 4.E73 in vehdyn's aligning moment).

    References
    ----------
    H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, eqs. 4.E33, 4.E73.
    """
    xp = NumpyOps
    dt, bt, ct, et, sht = trail_factors(c, s)
    et = xp.minimum(et, 1.0)
    bta = bt * (s.alpha_star + sht)
    return dt * xp.cos(ct * xp.atan(bta - et * (bta - xp.atan(bta)))) * s.cos_alpha_prime * c.LFZO * s.low_speed


def conditions(c, states: GridStates, names=None, signs=None):
    """The conditions' quantities g (valid where g <= 0) on the grid of ``states``.

    Parameters
    ----------
    c : MFCoefficients
        The coefficient record (``MagicFormula._c`` or a fit's candidate).
    states : GridStates
        The grid's states.
    names : collection of str, optional
        Conditions to evaluate (keys of :data:`CONDITIONS`); default all.
    signs : (float, float), optional
        Signs the slip and cornering stiffness must keep; default those of PKX1 and PKY1.

    Returns
    -------
    dict of str to ndarray
        Condition name -> g, in the units of :data:`MARGINS`, one value per grid point the
        condition is checked at (non-finite values replaced by 1e3: a violation).
    """
    xp = NumpyOps
    sx, sy = (math.copysign(1.0, c.PKX1), math.copysign(1.0, c.PKY1)) if signs is None else signs
    s, sc = states.plain, states.combined
    memo = {}

    def once(key, compute):
        if key not in memo:
            memo[key] = compute()
        return memo[key]

    def longitudinal():
        return once("longitudinal", lambda: longitudinal_pure(xp, c, s))

    def lateral():
        return once("lateral", lambda: lateral_pure(xp, c, s, s.gamma_star, False))

    def ey():
        g = s.gamma_star
        e0 = (c.PEY1 + c.PEY2 * s.dfz) * c.LEY  # 4.E24 at sign(alpha_y) = +-1
        odd = c.PEY3 + c.PEY4 * g
        return np.concatenate([e0 * (1 + c.PEY5 * g**2 - odd), e0 * (1 + c.PEY5 * g**2 + odd)]) - 1.0

    def ex():
        e0 = (c.PEX1 + c.PEX2 * s.dfz + c.PEX3 * s.dfz**2) * c.LEX  # 4.E14 at sign(kappa_x) = +-1
        return np.concatenate([e0 * (1 - c.PEX4), e0 * (1 + c.PEX4)]) - 1.0

    quantity = {
        "Cx > 0": lambda: np.array([-c.PCX1 * c.LCX]),
        "Dx > 0": lambda: -longitudinal()[1],
        "Kxk sign": lambda: -sx * longitudinal()[2] / s.fz,
        "Ex <= 1": ex,
        "Cy > 0": lambda: np.array([-c.PCY1 * c.LCY]),
        "Dy > 0": lambda: -lateral().muy,
        "Kya sign": lambda: -sy * lateral().kya / s.fz,
        "Ey <= 1": ey,
        "Ct > 0": lambda: np.array([-c.QCZ1]),
        "Dt > 0": lambda: -trail_factors(c, s)[0] / c.UNLOADED_RADIUS,
        "trail > 0": lambda: -trail(c, states.small) / c.UNLOADED_RADIUS,
        "Et <= 1": lambda: trail_factors(c, states.sweep)[3] - 1.0,
        "Cxa > 0": lambda: np.array([-c.RCX1]),
        "Exa <= 1": lambda: (c.REX1 + c.REX2 * s.dfz) - 1.0,  # 4.E56
        "Gxa > 0": lambda: -longitudinal_combined(xp, c, sc, 1.0),
        "Cyk > 0": lambda: np.array([-c.RCY1]),
        "Eyk <= 1": lambda: (c.REY1 + c.REY2 * s.dfz) - 1.0,  # 4.E64
        "Gyk > 0": lambda: -lateral_combined_factor(xp, c, sc),
    }
    out = {}
    with np.errstate(all="ignore"):
        for name in CONDITIONS if names is None else names:
            value = np.asarray(quantity[name](), dtype=float)
            out[name] = np.where(np.isfinite(value), value, 1e3)
    return out


def _margin(name):
    kind = name.split()[0]
    if kind.startswith("E"):
        return MARGINS["E"]
    if kind.startswith("C"):
        return MARGINS["C"]
    if kind.startswith("D"):
        return MARGINS["D"]
    if kind.startswith("K"):
        return MARGINS["K"]
    if kind == "trail":
        return MARGINS["trail"]
    return MARGINS["G"]


class Penalty:
    """The validity conditions of one fitting step as least-squares residuals.

    ``residuals(c)`` holds, per condition of the families the step's coefficients move, ``weight``
    times the 2-norm of ``max(0, g + margin)`` over the grid: zero while the condition holds with
    its margin (:data:`MARGINS`) everywhere. One row per condition adds to the sum of squares what
    one row per grid point would, and keeps the least-squares problem as small as the data's.

    Parameters
    ----------
    states : GridStates
        The grid's states.
    names : sequence of str
        The coefficients the step varies.
    weight : float
        Weight of the rows [-] (the fit uses 100 times the square root of the step's data values).
    signs : (float, float)
        Signs the slip and cornering stiffness must keep (those of PKX1 and PKY1 at the step's start).
    """

    NEAR = 1e-3
    """A condition whose g + margin stays below -NEAR at a point cannot be reached by the finite
    differences of a Jacobian there: its columns are zero and it is not evaluated again."""

    def __init__(self, states: GridStates, names, weight, signs):
        self.states, self.weight, self.signs = states, float(weight), signs
        which = families(names)
        self.names = [name for name, (family, _) in CONDITIONS.items() if family in which]
        self.moved_by = {name: [k for k in self.names if CONDITIONS[k][0] in families([name])] for name in names}
        self.near = set(self.names)

    def residuals(self, c, base=None, coefficient=None):
        """The penalty residuals at coefficient record ``c``.

        Parameters
        ----------
        c : MFCoefficients
            The candidate coefficients.
        base : ndarray, optional
            The residuals of the last full evaluation, at a record that differs from ``c`` in
            ``coefficient`` alone by a finite-difference step: then only the conditions that
            coefficient moves and that were near their bound (:attr:`NEAR`) are evaluated again.
        coefficient : str, optional
            The coefficient that differs (with ``base``).

        Returns
        -------
        ndarray
            One value per condition of the step's families [-].
        """
        if not self.names:
            return np.zeros(0)
        if base is None:
            names, out = self.names, np.zeros(len(self.names))
        else:
            names, out = [n for n in self.moved_by[coefficient] if n in self.near], base.copy()
            if not names:
                return out
        values = conditions(c, self.states, names, self.signs)
        if base is None:
            self.near = {n for n, v in values.items() if float(np.max(v)) + _margin(n) > -self.NEAR}
        for i, name in enumerate(self.names):
            if name in values:
                out[i] = self.weight * np.linalg.norm(np.maximum(values[name] + _margin(name), 0.0))
        return out


def _where(name, states, index):
    """The grid point (fz [N], gamma [rad], pressure [Pa], alpha [rad], kappa [-]) of value ``index``
    of condition ``name``; for Ex and Ey, kappa and alpha hold the slip's sign (+1 for the first half
    of the values, -1 for the second); NaN for the shape factors (one value, no grid)."""
    if name.split()[0] in ("Cx", "Cy", "Ct", "Cxa", "Cyk"):
        return (math.nan,) * 5
    states_of = {"trail > 0": states.small, "Et <= 1": states.sweep, "Gxa > 0": states.combined,
                 "Gyk > 0": states.combined}
    s = states_of.get(name, states.plain)
    sign = 0.0
    if name in ("Ex <= 1", "Ey <= 1"):  # both slip signs, one after the other
        sign = 1.0 if index < s.fz.size else -1.0
        index %= s.fz.size
    alpha = sign if name == "Ey <= 1" else float(np.broadcast_to(s.alpha, s.fz.shape)[index])
    kappa = sign if name == "Ex <= 1" else float(np.broadcast_to(s.kappa, s.fz.shape)[index])
    return (float(s.fz[index]), float(np.broadcast_to(s.gamma, s.fz.shape)[index]),
            float(np.broadcast_to(s.pressure, s.fz.shape)[index]), alpha, kappa)


def check_validity(tire, grid=None, *, data=None, signs=None):
    """Check the Magic Formula validity conditions of ``tire`` on a dense grid.

    Parameters
    ----------
    tire : MagicFormula
        The tire (e.g. :attr:`TireFit.tire`).
    grid : ValidityGrid, optional
        Where to check; default :meth:`ValidityGrid.from_data` of ``data``.
    data : pandas.DataFrame or mapping, optional
        Measured data whose span makes the grid (when ``grid`` is None).
    signs : (float, float), optional
        Signs [-] (+1 or -1) the slip and cornering stiffness must keep; default those of PKX1 and
        PKY1.

    Returns
    -------
    pandas.DataFrame
        One row per condition (:data:`CONDITIONS`): ``family``, ``points`` checked, ``worst``
        (the largest g; the condition holds where g <= 0; E - 1 for the curvature factors, minus the
        friction coefficient, minus the stiffness per load [1/rad or -], minus the trail over the
        unloaded radius, minus the weighting function), ``violations`` (points with g > 0),
        ``ok`` and the grid point of the worst value (``fz`` [N], ``gamma``, ``alpha`` [rad],
        ``kappa`` [-], ``pressure`` [Pa]; for Ex and Ey, ``kappa`` and ``alpha`` hold the slip's sign).

    Raises
    ------
    ParameterError
        If neither ``grid`` nor ``data`` is given, or ``tire`` is not a Magic Formula.

    References
    ----------
    H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 4.3.1-4.3.2, eqs. 4.E11-4.E78.
    """
    import pandas as pd

    if not hasattr(tire, "_c"):
        raise ParameterError(f"check_validity needs a MagicFormula, got {type(tire).__name__}", key="tire",
                             value=type(tire).__name__)
    if grid is None:
        if data is None:
            raise ParameterError("check_validity needs a grid or the data whose span makes one", key="grid",
                                 value=None)
        grid = ValidityGrid.from_data(data, tire)
    states = GridStates(tire._c, grid)
    values = conditions(tire._c, states, signs=signs)
    rows = []
    for name, g in values.items():
        worst = int(np.argmax(g))
        fz, gamma, pressure, alpha, kappa = _where(name, states, worst)
        rows.append({"condition": name, "family": CONDITIONS[name][0], "points": int(g.size),
                     "worst": float(g[worst]), "violations": int(np.count_nonzero(g > 0)),
                     "ok": bool(np.all(g <= 0)), "fz": fz, "gamma": gamma, "alpha": alpha, "kappa": kappa,
                     "pressure": pressure})
    return pd.DataFrame(rows).set_index("condition")
