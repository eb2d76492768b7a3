"""Pacejka's Magic Formula tire model (MF 5.2 / PAC2002, MF 6.1, MF 6.2) from ``.tir`` files.

:class:`MagicFormula` evaluates steady-state forces, moments and the auxiliary quantities
(rolling radii, deflection, contact patch, stiffnesses, relaxation lengths) exactly as MFeval
4.3.1 (M. Furlan, MATLAB File Exchange #63618) does with ``mfeval(tir, inputs, useMode)``: the
keyword switches ``limits``, ``alpha_star`` and ``turn_slip`` are MFeval's three ``useMode``
digits (hundreds 1/2, tens 2/1, units 2/1). Axis system ISO-W (TYDEX W) as in the ``.tir`` file:
kappa > 0 drives, Fz is a positive load, the coefficients are used as written (``TYRESIDE`` is
not mirrored, no SAE conversion; :mod:`vehdyn.conventions` converts for vehicle models).

The equations are those of Pacejka, *Tire and Vehicle Dynamics*, 3rd ed. (2012), chapter 4
(4.E1–4.E78, turn slip 4.75–4.106) with MFeval's substitutions from Besselink et al. (2010) and
the TNO MF-Tyre manuals; they live in :mod:`~vehdyn.tire.mf_forces`,
:mod:`~vehdyn.tire.mf_moments` and :mod:`~vehdyn.tire.mf_vertical`. This module handles inputs
(limits, low-speed rules), vectorization and the result record.

Two backends run the same equation functions: numpy (vectorized, in chunks of ``CHUNK_SIZE``
points; single points on Python floats) and, optionally, numba (``backend="numba"``, and
``"auto"`` for large calls; numba is imported and the loops compiled on first use into vectorized
machine code, 3-4.5x faster, see :mod:`vehdyn.tire._mf_numba`). Both are tested
against every MFeval reference row and against each other (1e-12).

Where MFeval's results are not finite vehdyn returns something else, on purpose:

* turn-slip aligning moment at phit = 0 or with zero camber stiffness Kzgr0 (MFeval: NaN/-Inf),
  see :func:`vehdyn.tire.mf_moments.aligning_moment`;
* MF 6.2 loaded radius where the vertical equation Fz(Rl) = Fz has no root (MFeval: Rl = NaN
  with rho = 1e-12 m, Cz = 1e16 N/m): rho, Rl and Cz are all NaN. This happens at large |Fy|
  and, with camber, below the load that the camber deflection term alone produces;
* MFeval's ``instKya`` (a finite difference between consecutive input rows) is not returned;
* MFeval iterates omega/Re on the whole batch and stops when any row converges; vehdyn iterates
  each point to convergence (MFeval's single-row result), so no output depends on other points.

Inputs that are not finite: NaN in every output at exactly those points, on both backends, as for
every tire law (see :mod:`vehdyn.tire.base`); the compiled loops never see them (the points are
set to a neutral operating point before the call and overwritten after). Bools raise
:class:`~vehdyn.ParameterError`.

Domain: any finite inputs with |alpha| < pi/2. With ``limits=True`` (the default) every output
is finite there, including vx = 0, fz = 0 and loads above FZMAX (except the MF 6.2 geometry
noted above); with ``limits=False`` the equations are evaluated as written, outside the file's
fitted ranges.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import repeat
from pathlib import Path
from collections import namedtuple

import numpy as np

from vehdyn.simulation.compiled import numba_available
from vehdyn.errors import ParameterError, TirFileError
from vehdyn.params import data_path
from vehdyn.tire._common import NAN_FORCES, broadcast_shape, finite_scalars, float_input, nan_at, neutralize, nonfinite_points
from vehdyn.tire._mf_ops import NumpyOps, ScalarOps, sign_nonzero
from vehdyn.tire.base import TireForces, TireModel
from vehdyn.tire.mf_forces import lateral_combined, lateral_pure, longitudinal_combined, longitudinal_pure, turn_slip_spin
from vehdyn.tire.mf_moments import aligning_moment, overturning_moment, rolling_resistance_moment
from vehdyn.tire.mf_vertical import carcass_stiffness, contact_patch, loaded_radius_mf61, loaded_radius_mf62, rolling_radius
from vehdyn.tire.tir import MFEVAL_DEFAULTS, TirParameters, read_tir

__all__ = ["MagicFormula", "MagicFormulaOutputs", "load_tire"]

CHUNK_SIZE = 8192
"""Points evaluated per numpy pass (keeps the ~100 temporaries of a pass in cache)."""

SMALL_BATCH = 8
"""Up to this many points, :meth:`MagicFormula.forces` evaluates point by point on floats."""

BACKEND = "auto"
"""Default ``backend`` of :meth:`MagicFormula.evaluate` and :meth:`MagicFormula.forces`: ``"auto"``
(numba for calls of at least ``AUTO_NUMBA_MIN_POINTS`` points when numba is installed, else numpy),
``"numpy"`` or ``"numba"``."""

AUTO_NUMBA_MIN_POINTS = 100_000
"""With ``backend="auto"``, calls of at least this many points run compiled (when numba is
installed). The compiled loops are 3-4.5x faster than numpy per point (``benchmarks/bench_tire.py``),
but the first compiled call of a process loads them from numba's on-disk cache (~1 s) or, the very
first time, compiles them (~30 s per loop); smaller calls therefore stay on numpy."""

NUMBA_PARALLEL = False
"""Whether the numba backend splits a call into one block per core, evaluated in threads; False: one core."""

_OUTPUTS = (
    ("fx", "N", "longitudinal force"),
    ("fy", "N", "lateral force"),
    ("fz", "N", "vertical load as given (negative set to 0, not clamped)"),
    ("mx", "N*m", "overturning moment"),
    ("my", "N*m", "rolling resistance moment"),
    ("mz", "N*m", "self-aligning moment"),
    ("kappa", "-", "slip ratio after the low-speed reduction (not clamped)"),
    ("alpha", "rad", "slip angle as given (0 where vx = 0)"),
    ("gamma", "rad", "inclination angle as given"),
    ("phit", "1/m", "turn slip after post-processing (limit mode: phit*cos(alpha), low-speed, reverse)"),
    ("vx", "m/s", "longitudinal speed"),
    ("pressure", "Pa", "inflation pressure used (clamped to PRESMIN..PRESMAX in limit mode)"),
    ("effective_radius", "m", "effective rolling radius Re"),
    ("deflection", "m", "vertical deflection rho"),
    ("contact_length", "m", "contact patch length 2a"),
    ("trail", "m", "pneumatic trail t"),
    ("mux", "-", "longitudinal friction coefficient"),
    ("muy", "-", "lateral friction coefficient (|muy| in limit mode)"),
    ("omega", "rad/s", "wheel spin (given, or (1 + kappa)*vx/Re)"),
    ("loaded_radius", "m", "loaded radius Rl"),
    ("contact_width", "m", "contact patch width 2b"),
    ("residual_torque", "N*m", "residual aligning torque Mzr"),
    ("cx", "N/m", "longitudinal carcass stiffness"),
    ("cy", "N/m", "lateral carcass stiffness"),
    ("cz", "N/m", "vertical stiffness Fz/rho"),
    ("kya", "N/rad", "cornering stiffness of the pure-slip lateral force"),
    ("sigma_x", "m", "longitudinal relaxation length"),
    ("sigma_y", "m", "lateral relaxation length"),
    ("kxk", "N", "longitudinal slip stiffness"),
)


@dataclass(frozen=True)
class MagicFormulaOutputs:
    """Everything :meth:`MagicFormula.evaluate` returns (MFeval's outputs 1–30 except instKya).

    Each field is a numpy array of the broadcast input shape (SI units, ISO-W axes); ``units``
    maps each name to its unit and ``descriptions`` to its meaning; ``out["fy"]`` is ``out.fy``.
    ``to_frame()`` gives a pandas DataFrame.

    Attributes
    ----------
    fx : ndarray
        Longitudinal force [N].
    fy : ndarray
        Lateral force [N].
    fz : ndarray
        Vertical load as given (negative set to 0, not clamped) [N].
    mx : ndarray
        Overturning moment [N*m].
    my : ndarray
        Rolling resistance moment [N*m].
    mz : ndarray
        Self-aligning moment [N*m].
    kappa : ndarray
        Slip ratio after the low-speed reduction (not clamped) [-].
    alpha : ndarray
        Slip angle as given (0 where vx = 0) [rad].
    gamma : ndarray
        Inclination angle as given [rad].
    phit : ndarray
        Turn slip after post-processing (limit mode: phit*cos(alpha), low-speed, reverse) [1/m].
    vx : ndarray
        Longitudinal speed [m/s].
    pressure : ndarray
        Inflation pressure used (clamped to PRESMIN..PRESMAX in limit mode) [Pa].
    effective_radius : ndarray
        Effective rolling radius Re [m].
    deflection : ndarray
        Vertical deflection rho [m].
    contact_length : ndarray
        Contact patch length 2a [m].
    trail : ndarray
        Pneumatic trail t [m].
    mux : ndarray
        Longitudinal friction coefficient [-].
    muy : ndarray
        Lateral friction coefficient (|muy| in limit mode) [-].
    omega : ndarray
        Wheel spin (given, or (1 + kappa)*vx/Re) [rad/s].
    loaded_radius : ndarray
        Loaded radius Rl [m].
    contact_width : ndarray
        Contact patch width 2b [m].
    residual_torque : ndarray
        Residual aligning torque Mzr [N*m].
    cx : ndarray
        Longitudinal carcass stiffness [N/m].
    cy : ndarray
        Lateral carcass stiffness [N/m].
    cz : ndarray
        Vertical stiffness Fz/rho [N/m].
    kya : ndarray
        Cornering stiffness of the pure-slip lateral force [N/rad].
    sigma_x : ndarray
        Longitudinal relaxation length [m].
    sigma_y : ndarray
        Lateral relaxation length [m].
    kxk : ndarray
        Longitudinal slip stiffness [N].
    """

    fx: np.ndarray
    fy: np.ndarray
    fz: np.ndarray
    mx: np.ndarray
    my: np.ndarray
    mz: np.ndarray
    kappa: np.ndarray
    alpha: np.ndarray
    gamma: np.ndarray
    phit: np.ndarray
    vx: np.ndarray
    pressure: np.ndarray
    effective_radius: np.ndarray
    deflection: np.ndarray
    contact_length: np.ndarray
    trail: np.ndarray
    mux: np.ndarray
    muy: np.ndarray
    omega: np.ndarray
    loaded_radius: np.ndarray
    contact_width: np.ndarray
    residual_torque: np.ndarray
    cx: np.ndarray
    cy: np.ndarray
    cz: np.ndarray
    kya: np.ndarray
    sigma_x: np.ndarray
    sigma_y: np.ndarray
    kxk: np.ndarray

    units = {name: unit for name, unit, _ in _OUTPUTS}
    descriptions = {name: text for name, _, text in _OUTPUTS}

    def __getitem__(self, name: str) -> np.ndarray:
        if name not in self.units:
            raise KeyError(f"no output {name!r}; outputs are {', '.join(self.units)}")
        return getattr(self, name)

    def keys(self):
        """The output names, in MFeval's order.

        Returns
        -------
        tuple of str
        """
        return tuple(self.units)

    @property
    def forces(self) -> TireForces:
        """The forces and moments as :class:`TireForces`."""
        return TireForces(self.fx, self.fy, self.fz, self.mx, self.my, self.mz)

    def to_frame(self):
        """All outputs as a pandas DataFrame.

        Returns
        -------
        pandas.DataFrame
            One row per point (inputs flattened), one column per output, ``attrs["units"]``.
        """
        import pandas as pd

        frame = pd.DataFrame({name: np.ravel(getattr(self, name)) for name in self.units})
        frame.attrs["units"] = dict(self.units)
        return frame


class MagicFormula(TireModel):
    r"""Magic Formula tire (MF 5.2, 6.1, 6.2) defined by a ``.tir`` parameter set.

    Steady-state forces and moments in ISO-W (TYDEX) axes, as MFeval 4.3.1 computes them. Pure
    slip (Pacejka 2012, sec. 4.3.2):

    .. math::

        F_{x0} = D_x \sin\left[C_x \arctan\left\{B_x \kappa_x - E_x \left(B_x \kappa_x
        - \arctan B_x \kappa_x\right)\right\}\right] + S_{Vx}, \quad
        \kappa_x = \kappa + S_{Hx} \qquad \text{(4.E9, 4.E10)}

        F_{y0} = D_y \sin\left[C_y \arctan\left\{B_y \alpha_y - E_y \left(B_y \alpha_y
        - \arctan B_y \alpha_y\right)\right\}\right] + S_{Vy}, \quad
        \alpha_y = \alpha^* + S_{Hy} \qquad \text{(4.E19, 4.E20)}

        D_x = \mu_x F_z \zeta_1, \quad B_x = \frac{K_{x\kappa}}{C_x D_x + \varepsilon_x},
        \quad D_y = \mu_y F_z \zeta_2, \quad B_y = \frac{K_{y\alpha}}{C_y D_y + \varepsilon_y}
        \qquad \text{(4.E12, 4.E16, 4.E22, 4.E26)}

    with the load and pressure increments :math:`df_z = (F_z - F_{z0}')/F_{z0}'`,
    :math:`F_{z0}' = \lambda_{Fz0} F_{z0}` and :math:`dp_i = (p_i - p_{i0})/p_{i0}` (4.E1, 4.E2a,
    4.E2b; the pressure terms from Besselink et al. 2010) in every coefficient, e.g.
    :math:`\mu_x = (p_{Dx1} + p_{Dx2} df_z)(1 + p_{px3} dp_i + p_{px4} dp_i^2)(1 - p_{Dx3}
    \gamma^2) \lambda_{\mu x}` (4.E13) and :math:`K_{y\alpha} = p_{Ky1} F_{z0}' (1 + p_{py1}
    dp_i)(1 - p_{Ky3} |\gamma^*|) \sin[p_{Ky4} \arctan\{(F_z/F_{z0}') / ((p_{Ky2} + p_{Ky5}
    \gamma^{*2})(1 + p_{py2} dp_i))\}] \zeta_3 \lambda_{Ky\alpha}` (4.E25); the zeta factors
    are 1 without turn slip. Combined slip weights the pure-slip forces:

    .. math::

        F_x = G_{x\alpha} F_{x0}, \quad
        G_{x\alpha} = \frac{\cos[C_{x\alpha} \arctan\{B_{x\alpha} \alpha_S
        - E_{x\alpha} (B_{x\alpha} \alpha_S - \arctan B_{x\alpha} \alpha_S)\}]}{G_{x\alpha 0}}
        \qquad \text{(4.E50, 4.E51)}

        F_y = G_{y\kappa} F_{y0} + S_{Vy\kappa} \qquad \text{(4.E58, 4.E59)}

    and the aligning moment is the moment of the side force about the pneumatic trail, the
    residual torque and the moment of the longitudinal force:

    .. math::

        M_z = -t \, F_y' + M_{zr} + s F_x, \quad
        t = D_t \cos[C_t \arctan\{B_t \alpha_{t,eq} - E_t (B_t \alpha_{t,eq}
        - \arctan B_t \alpha_{t,eq})\}] \cos\alpha', \quad
        M_{zr} = D_r \cos[C_r \arctan B_r \alpha_{r,eq}] \qquad \text{(4.E71--4.E75)}

    (MF 6.x: :math:`F_y' = G_{y\kappa} F_{y0}(\gamma = 0)`; MF 5.2: :math:`F_y - S_{Vy\kappa}`).
    The overturning and rolling-resistance moments, the effective and loaded radii, the contact
    patch, the carcass stiffnesses and the relaxation lengths follow the TNO forms MFeval uses;
    every equation, with its number, is in :mod:`~vehdyn.tire.mf_forces`,
    :mod:`~vehdyn.tire.mf_moments` and :mod:`~vehdyn.tire.mf_vertical`. Turn slip (the zeta
    factors, ``turn_slip=True``): eqs. 4.75-4.106.

    Parameters
    ----------
    params : TirParameters
        As returned by :func:`vehdyn.tire.read_tir`.

    Attributes
    ----------
    params : TirParameters
    version : str
        ``"5.2"``, ``"6.1"`` or ``"6.2"``.

    Raises
    ------
    TirFileError
        If the file names no supported Magic Formula version (FITTYP 6, 21, 61, 62 or
        PROPERTY_FILE_FORMAT = 'PAC2002').
    ParameterError
        If a coefficient the model uses is not a number, or FNOMIN, UNLOADED_RADIUS, LONGVL,
        NOMPRES, VXLOW or VERTICAL_STIFFNESS is not positive.

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       ch. 4: sec. 4.3.2 (the Magic Formula, eqs. 4.E1-4.E78) and sec. 4.3.3 (turn slip,
       eqs. 4.75-4.106); appendix 3 (MF-Tyre parameters, eq. A3.3).
    .. [2] I. J. M. Besselink, A. J. C. Schmeitz and H. B. Pacejka, "An improved Magic
       Formula/Swift tyre model that can handle inflation pressure changes", Vehicle System
       Dynamics 48 (sup1), 337-352, 2010 (MF 6.1: pressure terms, rolling radius, vertical
       stiffness, contact patch, relaxation lengths).
    .. [3] TNO Automotive, *MF-Tyre/MF-Swift 6.2 Equation Manual* (MF 6.2: the loaded radius).
    .. [4] TNO Automotive, *MF-Tyre User Manual*, version 5.2, 2001 (MF 5.2 / PAC2002).
    .. [5] M. Furlan, *MFeval* 4.3.1, MATLAB File Exchange #63618 (the reference implementation
       vehdyn is validated against).

    Examples
    --------
    >>> import numpy as np
    >>> import vehdyn
    >>> from vehdyn.tire import MagicFormula
    >>> tire = MagicFormula.from_tir(vehdyn.data_path("tires", "MagicFormula61_Parameters.tir"))
    >>> out = tire.evaluate(fz=4000.0, kappa=0.05, alpha=np.linspace(-0.2, 0.2, 41), vx=20.0)
    >>> out.fy.shape, out.mz.shape   # one value per slip angle; every MFeval output likewise
    ((41,), (41,))
    """

    name = "magic_formula"

    def __init__(self, params: TirParameters):
        if not isinstance(params, TirParameters):
            raise TypeError(f"MagicFormula needs TirParameters (from read_tir), got {type(params).__name__}")
        if params.version is None:
            fittyp = params.get("FITTYP")
            raise TirFileError(f"no supported Magic Formula version (FITTYP = {fittyp!r}, PROPERTY_FILE_FORMAT = "
                               f"{params.get('PROPERTY_FILE_FORMAT')!r}); supported: FITTYP 6, 21 (MF 5.2), 61, 62 "
                               f"or PROPERTY_FILE_FORMAT = 'PAC2002'", path=params.path)
        self.params = params
        self.version = params.version
        self._c = _coefficients(params)

    @property
    def coefficients(self) -> MFCoefficients:
        """The numbers :func:`forces_kernel` reads (the file's coefficients, SI, MFeval's defaults)."""
        return self._c

    @classmethod
    def from_tir(cls, path, *, strict: bool = False) -> MagicFormula:
        """Read a ``.tir`` file and build the model (see :func:`vehdyn.tire.read_tir`).

        Parameters
        ----------
        path : str or os.PathLike
            The ``.tir`` file (units as its ``[UNITS]`` section says; converted to SI once).
        strict : bool
            A file that lacks whole sections of its version (e.g. truncated) gives a
            :class:`~vehdyn.VehdynWarning` naming them; ``strict=True`` raises
            :class:`~vehdyn.TirFileError` instead.

        Returns
        -------
        MagicFormula

        Raises
        ------
        TirFileError
            If the file cannot be read, is malformed, breaks a rule of :mod:`vehdyn.tire.tir`, or
            names no supported version.

        Examples
        --------
        >>> import vehdyn
        >>> from vehdyn.tire import MagicFormula
        >>> tire = MagicFormula.from_tir(vehdyn.data_path("tires", "MagicFormula61_Parameters.tir"))
        >>> tire.version, tire.nominal_load, tire.unloaded_radius     # MF version, FNOMIN [N], R0 [m]
        ('6.1', 6752.0, 0.3943)
        """
        return cls(read_tir(path, strict=strict))

    def __repr__(self) -> str:
        where = f", {self.params.path!r}" if self.params.path else ""
        return f"MagicFormula(MF {self.version}, FNOMIN={self._c.FNOMIN:g} N{where})"

    @property
    def nominal_load(self) -> float:
        """FNOMIN [N]."""
        return self._c.FNOMIN

    @property
    def unloaded_radius(self) -> float:
        """UNLOADED_RADIUS [m]."""
        return self._c.UNLOADED_RADIUS

    # ------------------------------------------------------------------------------------------
    def evaluate(self, fz, kappa, alpha, gamma=0.0, vx=None, pressure=None, phit=0.0, omega=None, *,
                 limits=True, alpha_star=False, turn_slip=False, backend=None) -> MagicFormulaOutputs:
        """Steady-state evaluation with every output MFeval returns.

        Parameters
        ----------
        fz : array_like
            Vertical load [N] (negative values are taken as 0).
        kappa : array_like
            Longitudinal slip ratio [-], ISO-W (> 0 driving, -1 locked wheel).
        alpha : array_like
            Slip angle [rad], ISO-W.
        gamma : array_like
            Inclination angle [rad].
        vx : array_like, optional
            Longitudinal speed of the wheel centre [m/s]; default the file's LONGVL.
        pressure : array_like, optional
            Inflation pressure [Pa]; default the file's INFLPRES (no effect in MF 5.2).
        phit : array_like
            Turn slip [1/m] (path curvature); used only with ``turn_slip=True``.
        omega : array_like, optional
            Wheel spin [rad/s]; default estimated as (1 + kappa)*vx/Re.
        limits : bool
            MFeval useMode hundreds digit 1: clamp inputs to the file's ranges, low-speed rules
            below VXLOW, curvature factors E <= 1. False is digit 2.
        alpha_star : bool
            useMode tens digit 2: alpha* = tan(alpha)*sign(vx), gamma* = sin(gamma) (book
            eqs. 4.E3, 4.E4). False (digit 1, TNO MF-Tyre): alpha* = alpha, gamma* = gamma.
        turn_slip : bool
            useMode units digit 2: include turn slip and spin (book eqs. 4.75–4.106).
        backend : {None, "auto", "numpy", "numba"}
            ``"numpy"``: vectorized, chunked numpy (single points on Python floats). ``"numba"``:
            the same equations compiled by numba into one per-point loop that LLVM vectorizes
            (optional dependency; compiled on first use and cached on disk). ``"auto"``: numba for calls of at least
            ``AUTO_NUMBA_MIN_POINTS`` points when numba is installed, else numpy. None: the
            module-level ``BACKEND``.

        Returns
        -------
        MagicFormulaOutputs
            Arrays of the broadcast shape of the inputs (0-d arrays for a single point, which is
            evaluated on Python floats, without numpy's per-call overhead). NaN in every output at
            the points where an input is NaN or infinite (see :mod:`vehdyn.tire.base`).

        Raises
        ------
        ParameterError
            If an input is a bool or not numeric, the shapes do not broadcast, or the backend is
            unknown or unavailable.

        Examples
        --------
        One operating point of MFeval's reference set (``useMode`` 111), and MFeval 4.3.1's
        outputs there, -2657.2063246679 N and 1845.0603422270 N:

        >>> import vehdyn
        >>> from vehdyn.tire import MagicFormula
        >>> tire = MagicFormula.from_tir(vehdyn.data_path("tires", "MagicFormula61_Parameters.tir"))
        >>> out = tire.evaluate(fz=3376.0, kappa=-0.4, alpha=-0.3, vx=16.7, pressure=2.6e5)
        >>> round(float(out.fx), 6), round(float(out.fy), 6)           # [N]
        (-2657.206325, 1845.060342)
        >>> out.units["mz"], out.units["sigma_y"]
        ('N*m', 'm')
        """
        c = self._c
        point = (fz, kappa, alpha, gamma, c.LONGVL if vx is None else vx, c.INFLPRES if pressure is None else pressure,
                 phit, omega)
        explicit_numba = backend == "numba" or (backend is None and BACKEND == "numba")
        backend = _backend(backend)
        one_point = not explicit_numba and all(v is None or _is_number(v) for v in point)
        if one_point:  # a non-finite input goes to the array path, which returns NaN there
            given = point if omega is not None else point[:7]
            one_point = math.isfinite(sum(given)) or finite_scalars(*given)
        if one_point:
            # one operating point: float arithmetic (no numpy call overhead); numpy if a float op fails
            fz, kappa, alpha, gamma, vx, pressure, phit, omega = (None if v is None else float(v) for v in point)
            try:
                out = _full_kernel(ScalarOps, c, fz, kappa, alpha, gamma, phit, vx, pressure,
                                   0.0 if omega is None else omega, omega is not None, limits, alpha_star, turn_slip)
                return MagicFormulaOutputs(*(np.asarray(v, dtype=float) for v in out))
            except (ArithmeticError, ValueError):
                pass
        arrays = self._inputs(*point)
        switches = (limits, alpha_star, turn_slip)
        return MagicFormulaOutputs(*self._run(arrays, switches, full=True, backend=backend))

    def forces(self, fz, kappa, alpha, gamma=0.0, vx=None, *, limits=True, alpha_star=False,
               backend=None) -> TireForces:
        """Forces and moments only (no turn slip, no rolling-radius iteration).

        Same conventions and switches as :meth:`evaluate` (vx defaults to LONGVL, the pressure is
        INFLPRES). A call with scalar inputs returns floats; unless ``backend="numba"`` is asked
        for, scalar inputs and up to ``SMALL_BATCH`` points (a vehicle's wheels) are evaluated
        point by point on Python floats, which beats both array backends' call overhead. Points
        with a NaN or infinite input are NaN in every field, bools raise ParameterError.
        """
        c = self._c
        vx = c.LONGVL if vx is None else vx
        explicit_numba = backend == "numba" or (backend is None and BACKEND == "numba")
        backend = _backend(backend)
        scalar = all(_is_number(v) for v in (fz, kappa, alpha, gamma, vx))
        if scalar and not explicit_numba:
            if not (math.isfinite(fz + kappa + alpha + gamma + vx) or finite_scalars(fz, kappa, alpha, gamma, vx)):
                return NAN_FORCES
            return TireForces(*self._forces_at_point(float(fz), float(kappa), float(alpha), float(gamma), float(vx),
                                                     limits, alpha_star))
        arrays = self._inputs(fz, kappa, alpha, gamma, vx, c.INFLPRES, 0.0, None)
        shape = arrays["shape"]
        if scalar:  # compiled on request: floats all the same
            return TireForces(*(float(v) for v in self._run(arrays, (limits, alpha_star), full=False,
                                                            backend=backend)))
        n = math.prod(shape)
        if not explicit_numba and 0 < n <= SMALL_BATCH:
            # a few wheels: float arithmetic beats numpy's call overhead
            points = [a.reshape(-1).tolist() if a.shape == shape else [a.item()] * n if a.size == 1
                      else np.broadcast_to(a, shape).reshape(-1).tolist()
                      for a in (arrays[k] for k in ("fz", "kappa", "alpha", "gamma", "vx"))]
            skips = repeat(False) if arrays["bad"] is None else arrays["bad"].reshape(-1).tolist()
            values = [NAN_FORCES if skip else self._forces_at_point(*p, limits, alpha_star)
                      for skip, p in zip(skips, zip(*points))]
            return TireForces(*(np.array(v, dtype=float).reshape(shape) for v in zip(*values)))
        return TireForces(*self._run(arrays, (limits, alpha_star), full=False, backend=backend))

    def _forces_at_point(self, fz, kappa, alpha, gamma, vx, limits, alpha_star):
        """Forces at one point on Python floats; numpy (IEEE inf/nan) where floats raise."""
        c = self._c
        try:
            out = forces_kernel(ScalarOps, c, fz, kappa, alpha, gamma, vx, c.INFLPRES, limits, alpha_star)
        except (ArithmeticError, ValueError):  # a 0/0 or x/0: numpy gives MFeval's values
            arrays = self._inputs(fz, kappa, alpha, gamma, vx, c.INFLPRES, 0.0, None)
            out = self._run(arrays, (limits, alpha_star), full=False, backend="numpy")
        return tuple(float(v) for v in out)

    # ------------------------------------------------------------------------------------------
    def _inputs(self, fz, kappa, alpha, gamma, vx, pressure, phit, omega):
        """The inputs as float arrays (None: not given), their broadcast ``shape`` and the mask
        ``bad`` of the points where one is not finite (None if nowhere)."""
        c = self._c
        values = [fz, kappa, alpha, gamma, c.LONGVL if vx is None else vx,
                  c.INFLPRES if pressure is None else pressure, phit, omega]
        converted = [None if v is None else float_input(name, v) for name, v in zip(_INPUT_NAMES, values)]
        shape = broadcast_shape(converted, _INPUT_NAMES)
        arrays = dict(zip(_INPUT_NAMES, converted))
        arrays["shape"] = shape
        arrays["bad"] = nonfinite_points(converted, shape)
        return arrays

    def _run(self, arrays, switches, full, backend):
        """All points of ``arrays`` (from :meth:`_inputs`) through the full or the forces kernel:
        a tuple of output arrays of the broadcast shape."""
        shape = arrays.pop("shape")
        bad = arrays.pop("bad")
        if bad is not None:  # the equations see a neutral point there; NaN is written over it below
            neutral = (0.0, 0.0, 0.0, 0.0, self._c.LONGVL, self._c.INFLPRES, 0.0, 0.0)
            arrays = dict(zip(_INPUT_NAMES, neutralize([arrays[k] for k in _INPUT_NAMES], bad, neutral)))
            return nan_at(bad, self._run({**arrays, "shape": shape, "bad": None}, switches, full, backend))
        n = math.prod(shape)
        names = _FULL_INPUTS if full else _FORCES_INPUTS
        # inputs of one value stay 0-d / length 1 (constant terms cost one op; no copies)
        flat = [None if arrays[k] is None else (arrays[k].reshape(()) if arrays[k].size == 1
                                                 else np.broadcast_to(arrays[k], shape).reshape(-1)) for k in names]
        if full:  # omega: given, or estimated (a placeholder value and the flag)
            switches = (flat[-1] is not None, *switches)
            flat[-1] = np.zeros(()) if flat[-1] is None else flat[-1]
        if backend == "auto":
            backend = _auto_backend(n)
        if backend == "numba" and n > 0:
            from vehdyn.tire import _mf_numba

            outputs = _mf_numba.run(self._c, flat, switches, full, n, parallel=NUMBA_PARALLEL)
            return tuple(row.reshape(shape) for row in outputs)
        kernel = _full_kernel if full else forces_kernel
        result = None
        with np.errstate(all="ignore"):
            for start in range(0, max(n, 1), CHUNK_SIZE):
                part = slice(start, min(start + CHUNK_SIZE, n))
                out = kernel(NumpyOps, self._c, *(a if a.ndim == 0 else a[part] for a in flat), *switches)
                if result is None:
                    result = tuple(np.empty(n) for _ in out)
                for target, value in zip(result, out):
                    target[part] = value
        return tuple(v.reshape(shape) for v in result)


_INPUT_NAMES = ("fz", "kappa", "alpha", "gamma", "vx", "pressure", "phit", "omega")
_FULL_INPUTS = ("fz", "kappa", "alpha", "gamma", "phit", "vx", "pressure", "omega")
_FORCES_INPUTS = ("fz", "kappa", "alpha", "gamma", "vx", "pressure")


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _backend(backend) -> str:
    """Check ``backend`` (None: the module's ``BACKEND``): ``"auto"``, ``"numpy"`` or ``"numba"``.

    ``"auto"`` is resolved per call by :func:`_auto_backend` once the number of points is known.
    """
    backend = BACKEND if backend is None else backend
    if backend == "numba":
        if not numba_available():
            raise ParameterError("backend='numba' needs the optional package numba (pip install vehdyn[fast])",
                                 key="backend", value=backend)
        return backend
    if backend in ("numpy", "auto"):
        return backend
    raise ParameterError(f"backend must be 'auto', 'numpy' or 'numba', got {backend!r}", key="backend",
                         value=backend)


def _auto_backend(n: int) -> str:
    """numba for n >= ``AUTO_NUMBA_MIN_POINTS`` points if it imports, else numpy.

    On the development machine (2-core Xeon with AVX-512) the compiled loop, vectorized 8 points
    wide, beats the chunked numpy passes 3-4.5x at 1e5 points and more (``benchmarks/bench_tire.py``);
    below the threshold the one-time cost of loading the compiled code would dominate.
    """
    if n < AUTO_NUMBA_MIN_POINTS or not numba_available():
        return "numpy"
    try:
        from vehdyn.tire import _mf_numba  # noqa: F401
    except ImportError:  # installed but broken: numpy gives the same results
        return "numpy"
    return "numba"


def load_tire(path, *, strict: bool = False) -> MagicFormula:
    """Load a Magic Formula tire from a ``.tir`` file, or a shipped one by name.

    Parameters
    ----------
    path : str or pathlib.Path
        A file path, or the stem of a file in vehdyn's ``data/tires`` (``"MagicFormula61_Parameters"``,
        ``"MagicFormula62_Parameters"``, ``"MagicFormula52_Parameters"``, ``"mf_185_80R14"``).
    strict : bool
        Raise instead of warning when the file lacks whole sections (see :meth:`MagicFormula.from_tir`).

    Returns
    -------
    MagicFormula

    Examples
    --------
    >>> from vehdyn.tire import load_tire
    >>> load_tire("mf_185_80R14").version
    '5.2'
    """
    candidate = Path(path)
    if not candidate.exists() and candidate.suffix == "" and len(candidate.parts) == 1:
        shipped = data_path("tires", candidate.name + ".tir")
        if shipped.exists():
            candidate = shipped
    return MagicFormula.from_tir(candidate, strict=strict)


# ----------------------------------------------------------------------------------------------
_POSITIVE = ("FNOMIN", "UNLOADED_RADIUS", "LONGVL", "NOMPRES", "VXLOW", "VERTICAL_STIFFNESS")


_FLAGS = ("Fz0_prime", "is_mf52", "is_mf62", "mx_draft_form")
MFCoefficients = namedtuple("MFCoefficients", sorted(
    key for key, value in MFEVAL_DEFAULTS.items() if not isinstance(value, str)) + list(_FLAGS))
MFCoefficients.__doc__ = """The numeric ``.tir`` coefficients (SI, MFeval's defaults where missing) as floats, plus
Fz0' = LFZO*FNOMIN (eq. 4.E1) and the version flags (1.0/0.0). One float tuple type for every file,
so the compiled backend compiles once for all tires."""


def _coefficients(params: TirParameters) -> MFCoefficients:
    values = {}
    for key in MFCoefficients._fields[:-len(_FLAGS)]:
        value = params.values.get(key, MFEVAL_DEFAULTS[key])
        if isinstance(value, str):  # a string where a number is needed
            raise ParameterError(f"{key} must be a number, got {value!r}", key=key, value=value)
        values[key] = float(value)
    for key in _POSITIVE:
        if not values[key] > 0:
            raise ParameterError(f"{key} must be > 0, got {values[key]!r}", key=key, value=values[key])
    values["Fz0_prime"] = values["LFZO"] * values["FNOMIN"]  # 4.E1
    values["is_mf52"] = float(params.version == "5.2")
    values["is_mf62"] = float(params.version == "6.2")
    values["mx_draft_form"] = float(any(values[f"QSX{i}"] for i in (12, 13, 14))
                                    and any(values[f"QSX{i}"] for i in range(1, 12)))
    return MFCoefficients(**values)


MFState = namedtuple("MFState", (
    "limits", "turn_slip", "alpha_star_mode", "low_speed", "reverse", "fz", "fz_input", "fz_moment", "kappa",
    "kappa_input", "alpha", "gamma", "phit", "vx", "pressure", "dpi", "dfz", "alpha_star", "gamma_star",
    "camber_free", "cos_alpha_prime", "phi", "eps_gamma"))
MFState.__doc__ = """Post-processed inputs of one evaluation and the quantities every equation shares
(see :mod:`vehdyn.tire.mf_forces`)."""


def _pass_inputs(xp, c, fz, kappa, alpha, gamma, phit, vx, pressure, omega, omega_given, limits, alpha_star, turn_slip,
                 full):
    """The inputs of one pass after the limits and low-speed rules, as an :class:`MFState`, and
    (re, r_omega, spin, fz_low, kappa_output, alpha_input, gamma_input) for :func:`_full_kernel`."""
    fz = xp.maximum(fz, 0.0)
    reverse = xp.where(vx < 0, -1.0, 1.0)  # MFeval flips Fx0, My (and Fy0 with alpha*) when vx < 0
    fz_input, kappa_input, alpha_input, gamma_input = fz, kappa, alpha, gamma
    if limits:
        vxlow = c.VXLOW
        if turn_slip or full:  # (forces alone do not use phit)
            phit = phit * xp.cos(alpha)
        is_low = xp.abs(vx) <= vxlow
        if xp.any(is_low):
            low_speed = xp.where(is_low, 1 - 0.5 * (1 + xp.cos(math.pi * (vx / vxlow))), 1.0)
            linear = xp.where(is_low, xp.abs(vx / vxlow), 1.0)
            kappa = kappa * linear
            phit = phit * linear
        else:
            low_speed = 1.0
        kappa_output = kappa
        phit = phit * reverse
        if xp.any(xp.abs(vx) < vxlow):  # else no point is slow: |vx| + |tan(alpha) vx| >= |vx|
            speed_sum = xp.abs(vx) + xp.abs(xp.tan(alpha) * vx)
            slow = speed_sum < vxlow
            if xp.any(slow):
                alpha = xp.where(slow, alpha * (speed_sum / vxlow), alpha)
        alpha = xp.clip(alpha, c.ALPMIN, c.ALPMAX)
        gamma = xp.clip(gamma, c.CAMMIN, c.CAMMAX)
        fz = xp.minimum(fz, c.FZMAX)
        fz_low = xp.maximum(fz, c.FZMIN)
        fz_moment = xp.where(fz <= 0, 0.0, fz_low) if xp.any(fz <= 0) else fz_low
        pressure = xp.clip(pressure, c.PRESMIN, c.PRESMAX)
        kappa = xp.clip(kappa, c.KPUMIN, c.KPUMAX)
    else:
        low_speed = 1.0
        kappa_output = kappa
        fz_low = fz_moment = fz
    dpi = (pressure - c.NOMPRES) / c.NOMPRES  # 4.E2b
    dfz = (fz - c.Fz0_prime) / c.Fz0_prime  # 4.E2a
    if alpha_star:
        alpha_s = xp.tan(alpha) * xp.sign(vx)  # 4.E3
        gamma_s = xp.sin(gamma)  # 4.E4
    else:
        alpha_s, gamma_s = alpha, gamma
    vc = xp.sqrt(vx**2 + (xp.tan(alpha) * xp.abs(vx)) ** 2)
    # cos(alpha') with alpha' = acos(vx/Vc') (4.E6, 4.E6a); |vx/Vc'| <= 1, so cos(acos(v)) = v
    cos_alpha_prime = vx / (vc + 1e-6 * sign_nonzero(xp, vc))
    if turn_slip or full:
        re, r_omega, spin = rolling_radius(xp, c, fz_input, kappa_input, vx, dpi, omega, omega_given)
    else:  # not needed
        re = r_omega = spin = 0.0
    if turn_slip:
        phi, eps_gamma = turn_slip_spin(xp, c, alpha, vx, phit, gamma, dfz, spin)
    else:
        phi = eps_gamma = 0.0
    s = MFState(limits=limits, turn_slip=turn_slip, alpha_star_mode=alpha_star, low_speed=low_speed,
                reverse=reverse, fz=fz, fz_input=fz_input, fz_moment=fz_moment, kappa=kappa,
                kappa_input=kappa_input, alpha=alpha, gamma=gamma, phit=phit, vx=vx, pressure=pressure, dpi=dpi,
                dfz=dfz, alpha_star=alpha_s, gamma_star=gamma_s, camber_free=not xp.any(gamma_s != 0),
                cos_alpha_prime=cos_alpha_prime, phi=phi, eps_gamma=eps_gamma)
    return s, (re, r_omega, spin, fz_low, kappa_output, alpha_input, gamma_input)


def _forces_pass(xp, c, fz, kappa, alpha, gamma, phit, vx, pressure, omega, omega_given, limits, alpha_star, turn_slip,
                 full):
    """Inputs (limits, low-speed rules), forces and moments of one pass on arrays or floats.

    Returns the six forces and moments and what :func:`_full_pass` needs besides.
    """
    s, (re, r_omega, spin, fz_low, kappa_output, alpha_input, gamma_input) = _pass_inputs(
        xp, c, fz, kappa, alpha, gamma, phit, vx, pressure, omega, omega_given, limits, alpha_star, turn_slip, full)
    fx0, mux, kxk = longitudinal_pure(xp, c, s)
    pure = lateral_pure(xp, c, s, s.gamma_star, turn_slip)
    fx = longitudinal_combined(xp, c, s, fx0)
    fy, gyk, svyk = lateral_combined(xp, c, s, pure)
    mz = aligning_moment(xp, c, s, pure, fy, fx, kxk, gyk, svyk)
    forces = (fx, fy, s.fz_input, overturning_moment(xp, c, s, fy), rolling_resistance_moment(xp, c, s, fx), mz.mz)
    extras = (s, pure, mz, mux, kxk, re, r_omega, spin, fz_low, kappa_output, alpha_input, gamma_input)
    return forces, extras


def forces_kernel(xp, c, fz, kappa, alpha, gamma, vx, pressure, limits, alpha_star):
    r"""Forces and moments without turn slip or rolling radius: what :meth:`MagicFormula.forces` evaluates.

    The public kernel of the law for models written over an ``xp`` namespace
    (:mod:`vehdyn.tire.kernels`): the pure-slip forces weighted by the combined-slip factors,

    .. math::

        F_x = G_{x\alpha} F_{x0},\quad F_y = G_{y\kappa} F_{y0} + S_{Vy\kappa},\quad
        F_0 = D \sin(C \arctan(B x - E (B x - \arctan B x))) + S_V

    Parameters
    ----------
    xp : namespace
        :data:`vehdyn.tire.kernels.NUMPY`, ``SCALAR`` or the compiled namespace.
    c : MFCoefficients or record
        The law's coefficients (a ``MagicFormula``'s named tuple, or a record with its field names).
    fz : float or ndarray
        Normal load [N] (negative counts as 0).
    kappa : float or ndarray
        Slip ratio [-] (ISO-W).
    alpha : float or ndarray
        Slip angle [rad] (ISO-W).
    gamma : float or ndarray
        Inclination angle [rad] (ISO-W).
    vx : float or ndarray
        Forward speed of the wheel centre [m/s] (negative rolling backwards).
    pressure : float or ndarray
        Inflation pressure [Pa] (``c.INFLPRES`` for the file's own).
    limits : bool
        The file's input limits and MFeval's low-speed rules (``True`` in ``MagicFormula``).
    alpha_star : bool
        MFeval's ``useMode`` tens digit 2: alpha* = tan(alpha) sign(V_x), gamma* = sin(gamma).

    Returns
    -------
    tuple
        (F_x [N], F_y [N], F_z [N], M_x [N*m], M_y [N*m], M_z [N*m]), ISO-W.

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 4.3.2, eq. 4.E9-4.E78.
    """
    return _forces_pass(xp, c, fz, kappa, alpha, gamma, 0.0, vx, pressure, 0.0, False, limits, alpha_star, False,
                        False)[0]


def lateral_force_kernel(xp, c, fz, alpha, vx, pressure):
    r"""Fy [N] of :func:`forces_kernel` at kappa = 0 and gamma = 0 (``limits=True``,
    ``alpha_star=False``), without the longitudinal force and the moments: what a vehicle model in
    force mode (longitudinal forces as inputs, no wheel spin) takes from the law.

    At kappa = 0 the combined-slip Fy = Gyk Fy0 + SVyk (book eq. 4.E58) is Fy0: Gyk (4.E59) divides
    two equal numbers (kappa_s = kappa + SHyk = SHyk, 4.E61) and SVyk (4.E66) is sin(atan(0)) = 0,
    so the pure-slip force is the combined one up to rounding (the test compares them).

    .. math::

        F_y = F_{y0}(\alpha) = D_y \sin(C_y \arctan(B_y \alpha_y - E_y (B_y \alpha_y
        - \arctan B_y \alpha_y))) + S_{Vy}

    Parameters
    ----------
    xp : namespace
        :data:`vehdyn.tire.kernels.NUMPY`, ``SCALAR`` or the compiled namespace.
    c : MFCoefficients or record
        The law's coefficients.
    fz : float or ndarray
        Normal load [N].
    alpha : float or ndarray
        Slip angle [rad] (ISO-W).
    vx : float or ndarray
        Forward speed of the wheel centre [m/s].
    pressure : float or ndarray
        Inflation pressure [Pa].

    Returns
    -------
    float or ndarray
        F_y [N] (ISO-W).

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 4.3.2, eq. 4.E19-4.E30.
    """
    s = _pass_inputs(xp, c, fz, 0.0, alpha, 0.0, 0.0, vx, pressure, 0.0, False, True, False, False, False)[0]
    return lateral_pure(xp, c, s, s.gamma_star, False).fy0


def _full_kernel(xp, c, fz, kappa, alpha, gamma, phit, vx, pressure, omega, omega_given, limits, alpha_star,
                 turn_slip):
    """Every output of :meth:`MagicFormula.evaluate`, in the order of ``MagicFormulaOutputs``
    (``omega`` is used if ``omega_given``, else estimated)."""
    forces, extras = _forces_pass(xp, c, fz, kappa, alpha, gamma, phit, vx, pressure, omega, omega_given, limits,
                                  alpha_star, turn_slip, True)
    fx, fy, fz_input, mx, my, mz = forces
    s, pure, moment, mux, kxk, re, r_omega, spin, fz_low, kappa_output, alpha_input, gamma_input = extras
    if c.is_mf62:
        rho, loaded, cz = loaded_radius_mf62(xp, c, fz_input, s.fz, s.gamma, fx, fy, s.dpi, spin, r_omega)
    else:
        rho, loaded, cz = loaded_radius_mf61(xp, c, fz_low, fx, fy, s.dpi, spin, r_omega)
    half_length, half_width = contact_patch(xp, c, fz_input, s.dpi)
    cx, cy, sigma_x, sigma_y = carcass_stiffness(xp, c, s.fz, s.gamma, s.dpi, kxk, pure.kya)
    vx = s.vx
    alpha_out = xp.where(vx == 0, 0.0, alpha_input) if xp.any(vx == 0) else alpha_input
    muy = xp.abs(pure.muy) if limits else pure.muy
    return (fx, fy, fz_input, mx, my, mz, kappa_output, alpha_out, gamma_input, s.phit, vx, s.pressure, re, rho,
            2 * half_length, moment.trail, mux, muy, spin, loaded, 2 * half_width, moment.residual, cx, cy, cz,
            pure.kya, sigma_x, sigma_y, kxk)
