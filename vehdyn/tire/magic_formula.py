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

Where MFeval's results are not finite vehdyn returns something else, on purpose:

* turn-slip aligning moment at phit = 0 or with zero camber stiffness Kzgr0 (MFeval: NaN/-Inf),
  see :func:`vehdyn.tire.mf_moments.aligning_moment`;
* MF 6.2 loaded radius where the vertical equation Fz(Rl) = Fz has no root (MFeval: Rl = NaN
  with rho = 1e-12 m, Cz = 1e16 N/m): rho, Rl and Cz are all NaN. This happens at large |Fy|
  and, with camber, below the load that the camber deflection term alone produces;
* MFeval's ``instKya`` (a finite difference between consecutive input rows) is not returned;
* MFeval iterates omega/Re on the whole batch and stops when any row converges; vehdyn iterates
  each point to convergence (MFeval's single-row result), so no output depends on other points.

Domain: any finite inputs with |alpha| < pi/2. With ``limits=True`` (the default) every output
is finite there, including vx = 0, fz = 0 and loads above FZMAX (except the MF 6.2 geometry
noted above); with ``limits=False`` the equations are evaluated as written, outside the file's
fitted ranges.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from ..errors import ParameterError, TirFileError
from ..params import data_path
from ._mf_ops import NumpyOps, ScalarOps, sign_nonzero
from .base import TireForces, TireModel
from .mf_forces import lateral_combined, lateral_pure, longitudinal_combined, longitudinal_pure, turn_slip_spin
from .mf_moments import aligning_moment, overturning_moment, rolling_resistance_moment
from .mf_vertical import carcass_stiffness, contact_patch, loaded_radius_mf61, loaded_radius_mf62, rolling_radius
from .tir import MFEVAL_DEFAULTS, TirParameters, read_tir

__all__ = ["MagicFormula", "MagicFormulaOutputs", "load_tire"]

CHUNK_SIZE = 8192
"""Points evaluated per numpy pass (keeps the ~100 temporaries of a pass in cache)."""

SMALL_BATCH = 8
"""Up to this many points, :meth:`MagicFormula.forces` evaluates point by point on floats."""

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
    maps each name to its unit. ``to_frame()`` gives a pandas DataFrame.
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
        return tuple(self.units)

    @property
    def forces(self) -> TireForces:
        """The forces and moments as :class:`TireForces`."""
        return TireForces(self.fx, self.fy, self.fz, self.mx, self.my, self.mz)

    def to_frame(self):
        """All outputs as a pandas DataFrame (one row per point, ``attrs["units"]``)."""
        import pandas as pd

        frame = pd.DataFrame({name: np.ravel(getattr(self, name)) for name in self.units})
        frame.attrs["units"] = dict(self.units)
        return frame


class MagicFormula(TireModel):
    """Magic Formula tire (MF 5.2, 6.1, 6.2) defined by a ``.tir`` parameter set.

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

    Examples
    --------
    >>> tire = MagicFormula.from_tir(vehdyn.data_path("tires", "MagicFormula61_Parameters.tir"))
    >>> out = tire.evaluate(fz=4000.0, kappa=0.05, alpha=np.linspace(-0.2, 0.2, 41), vx=20.0)
    >>> out.fy, out.mz, out.effective_radius  # doctest: +SKIP
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

    @classmethod
    def from_tir(cls, path) -> MagicFormula:
        """Read a ``.tir`` file and build the model (see :func:`vehdyn.tire.read_tir`)."""
        return cls(read_tir(path))

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
                 limits=True, alpha_star=False, turn_slip=False) -> MagicFormulaOutputs:
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

        Returns
        -------
        MagicFormulaOutputs
            Arrays of the broadcast shape of the inputs (0-d arrays for a single point, which is
            evaluated on Python floats, without numpy's per-call overhead).
        """
        c = self._c
        point = (fz, kappa, alpha, gamma, c.LONGVL if vx is None else vx, c.INFLPRES if pressure is None else pressure,
                 phit, omega)
        if all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)) for v in point):
            # one operating point: float arithmetic (no numpy call overhead); numpy if a float op fails
            fz, kappa, alpha, gamma, vx, pressure, phit, omega = (None if v is None else float(v) for v in point)
            try:
                out = _kernel(ScalarOps, c, fz, kappa, alpha, gamma, phit, vx, pressure, omega, limits, alpha_star,
                              turn_slip, True)
                return MagicFormulaOutputs(**{k: np.asarray(v, dtype=float) for k, v in out.items()})
            except (ArithmeticError, ValueError):
                pass
        arrays = self._inputs(*point)
        return MagicFormulaOutputs(**self._run(arrays, limits, alpha_star, turn_slip, full=True))

    def forces(self, fz, kappa, alpha, gamma=0.0, vx=None, *, limits=True, alpha_star=False) -> TireForces:
        """Forces and moments only (no turn slip, no rolling-radius iteration).

        Same conventions and switches as :meth:`evaluate` (vx defaults to LONGVL). A call with
        scalar inputs is evaluated on Python floats (no numpy overhead) and returns floats; up to
        ``SMALL_BATCH`` points (a vehicle's wheels) are evaluated the same way, point by point.
        """
        c = self._c
        vx = c.LONGVL if vx is None else vx
        scalar = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (fz, kappa, alpha, gamma, vx))
        if scalar:
            return TireForces(*self._forces_at_point(float(fz), float(kappa), float(alpha), float(gamma), float(vx),
                                                     limits, alpha_star))
        arrays = self._inputs(fz, kappa, alpha, gamma, vx, None, 0.0, None)
        shape = arrays["shape"]
        if 0 < math.prod(shape) <= SMALL_BATCH:  # a few wheels: float arithmetic beats numpy's call overhead
            points = np.broadcast_arrays(*(arrays[k] for k in ("fz", "kappa", "alpha", "gamma", "vx")))
            values = [self._forces_at_point(*map(float, p), limits, alpha_star)
                      for p in zip(*(np.ravel(a) for a in points))]
            return TireForces(*(np.array(v, dtype=float).reshape(shape) for v in zip(*values)))
        out = self._run(arrays, limits, alpha_star, False, full=False)
        return TireForces(*(out[k] for k in TireForces._fields))

    def _forces_at_point(self, fz, kappa, alpha, gamma, vx, limits, alpha_star):
        """Forces at one point on Python floats; numpy (IEEE inf/nan) where floats raise."""
        c = self._c
        try:
            out = _kernel(ScalarOps, c, fz, kappa, alpha, gamma, 0.0, vx, c.INFLPRES, None, limits, alpha_star,
                          False, False)
        except (ArithmeticError, ValueError):  # a 0/0 or x/0: numpy gives MFeval's values
            arrays = self._inputs(fz, kappa, alpha, gamma, vx, None, 0.0, None)
            out = self._run(arrays, limits, alpha_star, False, full=False)
        return tuple(float(out[k]) for k in TireForces._fields)

    # ------------------------------------------------------------------------------------------
    def _inputs(self, fz, kappa, alpha, gamma, vx, pressure, phit, omega):
        c = self._c
        names = ("fz", "kappa", "alpha", "gamma", "vx", "pressure", "phit", "omega")
        values = [fz, kappa, alpha, gamma, c.LONGVL if vx is None else vx,
                  c.INFLPRES if pressure is None else pressure, phit, omega]
        arrays = {}
        for name, value in zip(names, values):
            if value is None:
                arrays[name] = None
                continue
            try:
                arrays[name] = np.asarray(value, dtype=float)
            except (TypeError, ValueError):
                raise ParameterError(f"{name} must be numeric, got {value!r}", key=name, value=value) from None
        present = [a for a in arrays.values() if a is not None]
        try:
            shape = np.broadcast_shapes(*(a.shape for a in present))
        except ValueError:
            shapes = {k: a.shape for k, a in arrays.items() if a is not None}
            raise ParameterError(f"input shapes do not broadcast: {shapes}", key="shape", value=shapes) from None
        arrays["shape"] = shape
        return arrays

    def _run(self, arrays, limits, alpha_star, turn_slip, full):
        c = self._c
        shape = arrays.pop("shape")
        n = math.prod(shape)
        names = ("fz", "kappa", "alpha", "gamma", "phit", "vx", "pressure", "omega")
        # inputs of one value stay 0-d (numpy broadcasts them, and constant terms cost one op)
        flat = {}
        for k in names:
            a = arrays[k]
            flat[k] = None if a is None else (a.reshape(()) if a.size == 1 else np.broadcast_to(a, shape).reshape(-1))

        def chunk(a, part):
            return a if a is None or a.ndim == 0 else a[part]

        result = {}
        with np.errstate(all="ignore"):
            for start in range(0, max(n, 1), CHUNK_SIZE):
                part = slice(start, min(start + CHUNK_SIZE, n))
                out = _kernel(NumpyOps, c, *(chunk(flat[k], part) for k in names), limits, alpha_star, turn_slip, full)
                for k, v in out.items():
                    if k not in result:
                        result[k] = np.empty(n)
                    result[k][part] = v
        return {k: v.reshape(shape) for k, v in result.items()}


def load_tire(path) -> MagicFormula:
    """Load a Magic Formula tire from a ``.tir`` file, or a shipped one by name.

    Parameters
    ----------
    path : str or pathlib.Path
        A file path, or the stem of a file in vehdyn's ``data/tires`` (``"MagicFormula61_Parameters"``,
        ``"MagicFormula62_Parameters"``, ``"MagicFormula52_Parameters"``, ``"mf_185_80R14"``).
    """
    candidate = Path(path)
    if not candidate.exists() and candidate.suffix == "" and len(candidate.parts) == 1:
        shipped = data_path("tires", candidate.name + ".tir")
        if shipped.exists():
            candidate = shipped
    return MagicFormula.from_tir(candidate)


# ----------------------------------------------------------------------------------------------
_POSITIVE = ("FNOMIN", "UNLOADED_RADIUS", "LONGVL", "NOMPRES", "VXLOW", "VERTICAL_STIFFNESS")


def _coefficients(params: TirParameters) -> SimpleNamespace:
    values = {}
    for key, value in params.values.items():
        if isinstance(value, str):
            continue
        values[key] = float(value)
    for key, default in MFEVAL_DEFAULTS.items():
        if isinstance(default, str) or key in values:
            continue
        if key in params.values:  # a string where a number is needed
            raise ParameterError(f"{key} must be a number, got {params.values[key]!r}", key=key,
                                 value=params.values[key])
        values[key] = float(default)
    for key in _POSITIVE:
        if not values[key] > 0:
            raise ParameterError(f"{key} must be > 0, got {values[key]!r}", key=key, value=values[key])
    c = SimpleNamespace(**values)
    c.is_mf52 = params.version == "5.2"
    c.is_mf62 = params.version == "6.2"
    c.Fz0_prime = c.LFZO * c.FNOMIN  # 4.E1
    c.mx_draft_form = any((c.QSX12, c.QSX13, c.QSX14)) and any(
        getattr(c, f"QSX{i}") for i in range(1, 12))
    return c


def _kernel(xp, c, fz, kappa, alpha, gamma, phit, vx, pressure, omega, limits, alpha_star, turn_slip, full):
    """One evaluation pass on arrays (numpy) or floats (``ScalarOps``); returns a dict of outputs."""
    fz = xp.maximum(fz, 0.0)
    reverse = xp.where(vx < 0, -1.0, 1.0)  # MFeval flips Fx0, My (and Fy0 with alpha*) when vx < 0
    fz_input, kappa_input, alpha_input, gamma_input = fz, kappa, alpha, gamma
    if limits:
        vxlow = c.VXLOW
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
    s = SimpleNamespace(limits=limits, turn_slip=turn_slip, alpha_star_mode=alpha_star, low_speed=low_speed,
                        reverse=reverse,
                        fz=fz, fz_input=fz_input, fz_moment=fz_moment, kappa=kappa, kappa_input=kappa_input,
                        alpha=alpha, gamma=gamma, phit=phit, vx=vx, pressure=pressure)
    s.dpi = (pressure - c.NOMPRES) / c.NOMPRES  # 4.E2b
    s.dfz = (fz - c.Fz0_prime) / c.Fz0_prime  # 4.E2a
    if alpha_star:
        s.alpha_star = xp.tan(alpha) * xp.sign(vx)  # 4.E3
        s.gamma_star = xp.sin(gamma)  # 4.E4
    else:
        s.alpha_star, s.gamma_star = alpha, gamma
    s.camber_free = not xp.any(s.gamma_star != 0)
    vc = xp.sqrt(vx**2 + (xp.tan(alpha) * xp.abs(vx)) ** 2)
    # cos(alpha') with alpha' = acos(vx/Vc') (4.E6, 4.E6a); |vx/Vc'| <= 1, so cos(acos(v)) = v
    s.cos_alpha_prime = vx / (vc + 1e-6 * sign_nonzero(xp, vc))
    if turn_slip or full:
        re, r_omega, omega = rolling_radius(xp, c, fz_input, kappa_input, vx, s.dpi, omega)
    if turn_slip:
        s.phi, s.eps_gamma = turn_slip_spin(xp, c, s, omega)
    fx0, mux, kxk = longitudinal_pure(xp, c, s)
    pure = lateral_pure(xp, c, s, s.gamma_star, turn_slip)
    fx = longitudinal_combined(xp, c, s, fx0)
    fy, gyk, svyk = lateral_combined(xp, c, s, pure)
    mz = aligning_moment(xp, c, s, pure, fy, fx, kxk, gyk, svyk)
    out = dict(fx=fx, fy=fy, fz=fz_input, mx=overturning_moment(xp, c, s, fy),
               my=rolling_resistance_moment(xp, c, s, fx), mz=mz.mz)
    if not full:
        return out
    if c.is_mf62:
        rho, loaded, cz = loaded_radius_mf62(xp, c, fz_input, fz, gamma, fx, fy, s.dpi, omega, r_omega)
    else:
        rho, loaded, cz = loaded_radius_mf61(xp, c, fz_low, fx, fy, s.dpi, omega, r_omega)
    half_length, half_width = contact_patch(xp, c, fz_input, s.dpi)
    cx, cy, sigma_x, sigma_y = carcass_stiffness(xp, c, fz, gamma, s.dpi, kxk, pure.kya)
    out.update(
        kappa=kappa_output, alpha=xp.where(vx == 0, 0.0, alpha_input) if xp.any(vx == 0) else alpha_input,
        gamma=gamma_input, phit=phit, vx=vx,
        pressure=pressure, effective_radius=re, deflection=rho, contact_length=2 * half_length, trail=mz.trail,
        mux=mux, muy=xp.abs(pure.muy) if limits else pure.muy, omega=omega, loaded_radius=loaded,
        contact_width=2 * half_width, residual_torque=mz.residual, cx=cx, cy=cy, cz=cz, kya=pure.kya,
        sigma_x=sigma_x, sigma_y=sigma_y, kxk=kxk,
    )
    return out
