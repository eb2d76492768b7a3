"""Reading and writing ``.tir`` tire property files (MSC/TNO "TeimOrbit" format).

A ``.tir`` file is a list of ``[SECTION]`` headers followed by ``KEY = value`` lines; ``$`` starts a
comment (also after a value), ``!`` starts a comment line, values are numbers or ``'quoted'``
strings, and a few legacy sections (``[SHAPE]``) hold tables whose lines have no ``=``. Files are
read as UTF-8 (a byte-order mark, UTF-8 or UTF-16, is accepted) or, failing that, Latin-1.

:func:`read_tir` keeps every key verbatim, grouped by section, converts the dimensional
parameters to SI once according to ``[UNITS]``, and fills the parameters a Magic Formula
evaluation needs but the file lacks with MFeval 4.3.1's documented defaults
(:data:`MFEVAL_DEFAULTS`), listing them in :attr:`TirParameters.defaulted`.
:func:`write_tir` writes a file that :func:`read_tir` reads back to equal values (numbers are
written with ``repr``, i.e. exactly).

Version detection (Magic Formula variant of the file):

* ``FITTYP = 6`` or ``21`` -> ``"5.2"``; ``61`` -> ``"6.1"``; ``62`` -> ``"6.2"``;
* no ``FITTYP`` but ``PROPERTY_FILE_FORMAT = 'PAC2002'`` (or ``'MF_05'``) -> ``"5.2"``;
* anything else -> ``None`` (the file is read, but :class:`vehdyn.tire.MagicFormula` refuses it).

Checks (:class:`~vehdyn.TirFileError` naming the key, its value as written and its line). Every
coefficient is checked, not only those the model reads first, and the values the file lacks take
part with their defaults:

* every number is finite (``nan``, ``inf`` and overflowing literals such as ``1e999`` are refused;
  a single NaN coefficient makes every force NaN, an infinite one clamps or saturates silently);
* ``0 <= FZMIN < FZMAX``: the load range clamps Fz (FZMAX, and FZMIN in the moments); loads are
  compressive, and an empty or inverted range clamps every load to one value;
* ``ALPMIN < 0 < ALPMAX`` and ``KPUMIN < 0 < KPUMAX``: with limits on, slip is clipped to these
  ranges, so a range without 0 turns straight free rolling into a slip angle or a drive/brake
  slip (a tire that steers or drives itself);
* ``CAMMIN <= 0 <= CAMMAX`` (both 0 allowed: a file fitted without camber) and
  ``0 <= PRESMIN <= PRESMAX`` (equal: fitted at one pressure), for the same reason;
* ``PDX1 > 0`` and ``PDY1 > 0``: the friction coefficients mu_x, mu_y at FNOMIN (Pacejka 2012,
  eqs. 4.E13 and 4.E23, marked > 0), and ``LMUX >= 0``, ``LMUY >= 0``, their scaling factors
  (0 switches the force off). The pure-slip force comes out the same with a negative D = mu Fz
  only because B = K/(C D) flips with it; the friction outputs ``mux``/``muy`` and the
  combined-slip side force shift S_Vyk = mu_y Fz (R_VY1 + ...) do not, so a negative value is a
  sign error that shows only under combined slip;
* ``QCZ1 > 0``: the shape factor C_t of the pneumatic trail (eq. 4.E41, marked > 0). The trail
  itself is even in C_t (a cosine), but the curvature E_t contains atan(B_t C_t alpha_t)
  (eq. 4.E44), so with QEZ4/QEZ5 a negative C_t mirrors the trail's asymmetry: a different M_z;
* ``LFZO > 0``: Fz0' = LFZO*FNOMIN divides every load term.

Every rule holds for the shipped files and the MFeval reference files. Sign rules that the
equations do not need are not enforced: the shape factors PCX1 and PCY1 (the book asks C > 0)
give the same forces and moments with the opposite sign, since B = K/(C D) flips too and every
other use is of the product B C. The positivity of FNOMIN,
UNLOADED_RADIUS, LONGVL, NOMPRES, VXLOW and VERTICAL_STIFFNESS is checked by
:class:`~vehdyn.tire.MagicFormula` (a :class:`~vehdyn.ParameterError`). A file of a known version
that lacks whole sections (:attr:`TirParameters.missing_sections`, e.g. a truncated file) is read
with MFeval's defaults for them and a :class:`~vehdyn.VehdynWarning`; ``strict=True`` makes it an
error.
"""

from __future__ import annotations

import math
import numbers
import os
import sys
import warnings
from pathlib import Path
from types import MappingProxyType
from collections.abc import Mapping

from vehdyn._atomic import atomic_write
from vehdyn.errors import TirFileError, VehdynWarning

__all__ = ["TirParameters", "read_tir", "write_tir", "check_sections", "MFEVAL_DEFAULTS", "VERSION_BY_FITTYP",
           "STANDARD_SECTIONS", "REQUIRED_SECTIONS"]

VERSION_BY_FITTYP = {6: "5.2", 21: "5.2", 61: "6.1", 62: "6.2"}
"""Magic Formula version for each supported ``FITTYP`` value."""

_PAC2002_FORMATS = {"PAC2002", "MF_05"}

# Sections whose body is a table (lines without '='), skipped by the parser and kept verbatim.
_TABLE_SECTIONS = {"SHAPE"}
# Header keys that describe the file, not the tire.
_IGNORED_KEYS = {"FILE_TYPE", "FILE_VERSION", "FILE_FORMAT"}

# --- MFeval 4.3.1 readTIR defaults -------------------------------------------------------------
# Values MFeval uses for a parameter that the file does not define (MFeval 4.3.1, readTIR.m).
# Several are not neutral (QSY3, QSY4, QSY7, QSY8, RBX1, RBX2, RVY4, PKY4, Q_FZ2, FZMIN, FZMAX),
# so a file that omits them is evaluated with these values, exactly as MFeval does.
_COMMON_DEFAULTS = dict(
    FITTYP=0, TYRESIDE="LEFT", LONGVL=16.7, VXLOW=1.0, ROAD_INCREMENT=0.01, ROAD_DIRECTION=1,
    PROPERTY_FILE_FORMAT="default", USER_SUB_ID=815, N_TIRE_STATES=4, USE_MODE=124,
    HMAX_LOCAL=2.5e-4, TIME_SWITCH_INTEG=0.1,
    UNLOADED_RADIUS=0.3135, WIDTH=0.205, ASPECT_RATIO=0.6, RIM_RADIUS=0.1905, RIM_WIDTH=0.152,
    INFLPRES=220000.0, NOMPRES=220000.0,
    MASS=9.3, IXX=0.391, IYY=0.736, BELT_MASS=7.0, BELT_IXX=0.34, BELT_IYY=0.6, GRAVITY=-9.81,
    FNOMIN=4000.0, VERTICAL_STIFFNESS=200000.0, VERTICAL_DAMPING=50.0, MC_CONTOUR_A=0.5,
    MC_CONTOUR_B=0.5, BREFF=8.4, DREFF=0.27, FREFF=0.07, Q_RE0=1.0, Q_V1=0.0, Q_V2=0.0,
    Q_FZ2=1.0e-4, Q_FCX=0.0, Q_FCY=0.0, Q_CAM=0.0, PFZ1=0.0, BOTTOM_OFFST=0.01,
    BOTTOM_STIFF=2000000.0,
    LONGITUDINAL_STIFFNESS=300000.0, LATERAL_STIFFNESS=100000.0, YAW_STIFFNESS=5000.0,
    FREQ_LONG=80.0, FREQ_LAT=40.0, FREQ_YAW=50.0, FREQ_WINDUP=70.0, DAMP_LONG=0.04,
    DAMP_LAT=0.04, DAMP_YAW=0.04, DAMP_WINDUP=0.04, DAMP_RESIDUAL=0.002, DAMP_VLOW=0.001,
    Q_BVX=0.0, Q_BVT=0.0, PCFX1=0.0, PCFX2=0.0, PCFX3=0.0, PCFY1=0.0, PCFY2=0.0, PCFY3=0.0,
    PCMZ1=0.0,
    Q_RA1=0.5, Q_RA2=1.0, Q_RB1=1.0, Q_RB2=-1.0, ELLIPS_SHIFT=0.8, ELLIPS_LENGTH=1.0,
    ELLIPS_HEIGHT=1.0, ELLIPS_ORDER=1.8, ELLIPS_MAX_STEP=0.025, ELLIPS_NWIDTH=10,
    ELLIPS_NLENGTH=10,
    PRESMIN=10000.0, PRESMAX=1000000.0, FZMIN=100.0, FZMAX=10000.0, KPUMIN=-1.5, KPUMAX=1.5,
    ALPMIN=-1.5, ALPMAX=1.5, CAMMIN=-0.175, CAMMAX=0.175,
    LFZO=1.0, LCX=1.0, LMUX=1.0, LEX=1.0, LKX=1.0, LHX=1.0, LVX=1.0, LCY=1.0, LMUY=1.0,
    LEY=1.0, LKY=1.0, LHY=1.0, LVY=1.0, LTR=1.0, LRES=1.0, LXAL=1.0, LYKA=1.0, LVYKA=1.0,
    LS=1.0, LKYC=1.0, LKZC=1.0, LVMX=1.0, LMX=1.0, LMY=1.0, LMP=1.0,
    PCX1=1.65, PDX1=1.3, PDX2=-0.15, PDX3=0.0, PEX1=0.0, PEX2=0.0, PEX3=0.0, PEX4=0.0,
    PKX1=20.0, PKX2=0.0, PKX3=0.0, PHX1=0.0, PHX2=0.0, PVX1=0.0, PVX2=0.0, PPX1=0.0, PPX2=0.0,
    PPX3=0.0, PPX4=0.0, RBX1=20.0, RBX2=15.0, RBX3=0.0, RCX1=1.0, REX1=0.0, REX2=0.0, RHX1=0.0,
    QSX1=0.0, QSX2=0.0, QSX3=0.0, QSX4=5.0, QSX5=1.0, QSX6=10.0, QSX7=0.0, QSX8=0.0, QSX9=0.4,
    QSX10=0.0, QSX11=5.0, QSX12=0.0, QSX13=0.0, QSX14=0.0, PPMX1=0.0,
    PCY1=1.3, PDY1=1.1, PDY2=-0.15, PDY3=0.0, PEY1=0.0, PEY2=0.0, PEY3=0.0, PEY4=0.0, PEY5=0.0,
    PKY1=-20.0, PKY2=1.0, PKY3=0.0, PKY4=2.0, PKY5=0.0, PKY6=-1.0, PKY7=0.0, PHY1=0.0, PHY2=0.0,
    PVY1=0.0, PVY2=0.0, PVY3=0.0, PVY4=0.0, PPY1=0.0, PPY2=0.0, PPY3=0.0, PPY4=0.0, PPY5=0.0,
    RBY1=10.0, RBY2=10.0, RBY3=0.0, RBY4=0.0, RCY1=1.0, REY1=0.0, REY2=0.0, RHY1=0.0, RHY2=0.0,
    RVY1=0.0, RVY2=0.0, RVY3=0.0, RVY4=20.0, RVY5=2.0, RVY6=10.0,
    QSY1=0.01, QSY2=0.0, QSY3=4.0e-4, QSY4=4.0e-5, QSY5=0.0, QSY6=0.0, QSY7=0.85, QSY8=-0.4,
    QBZ1=10.0, QBZ2=0.0, QBZ3=0.0, QBZ4=0.0, QBZ5=0.0, QBZ9=10.0, QBZ10=0.0, QCZ1=1.1,
    QDZ1=0.12, QDZ2=0.0, QDZ3=0.0, QDZ4=0.0, QDZ6=0.0, QDZ7=0.0, QDZ8=-0.05, QDZ9=0.0,
    QDZ10=0.0, QDZ11=0.0, QEZ1=0.0, QEZ2=0.0, QEZ3=0.0, QEZ4=0.0, QEZ5=0.0, QHZ1=0.0, QHZ2=0.0,
    QHZ3=0.0, QHZ4=0.0, PPZ1=0.0, PPZ2=0.0, SSZ1=0.0, SSZ2=0.0, SSZ3=0.0, SSZ4=0.0,
    PDXP1=0.4, PDXP2=0.0, PDXP3=0.0, PKYP1=1.0, PDYP1=0.4, PDYP2=0.0, PDYP3=0.0, PDYP4=0.0,
    PHYP1=1.0, PHYP2=0.15, PHYP3=0.0, PHYP4=-4.0, PECP1=0.5, PECP2=0.0, QDTP1=10.0,
    QCRP1=0.2, QCRP2=0.1, QBRP1=0.1, QDRP1=1.0,
)
_MF62_DEFAULTS = dict(
    FUNCTION_NAME="default", SWITCH_INTEG=0, Q_FCY2=0.0, Q_CAM1=0.0, Q_CAM2=0.0, Q_CAM3=0.0,
    Q_FYS1=0.0, Q_FYS2=0.0, Q_FYS3=0.0, ENV_C1=0.0, ENV_C2=0.0,
)
_MF52_DEFAULTS = dict(
    Q_A1=0.0, Q_A2=0.0, PHY3=0.0, PTX1=0.0, PTX2=0.0, PTX3=0.0, PTY1=0.0, PTY2=0.0, LSGKP=1.0,
    LSGAL=1.0,
)
MFEVAL_DEFAULTS: Mapping[str, float | str] = MappingProxyType(
    {**_COMMON_DEFAULTS, **_MF62_DEFAULTS, **_MF52_DEFAULTS})
"""Every parameter MFeval 4.3.1 knows, with the value it uses when a file lacks it."""

# Parameters each version reads (MF 5.2 files never use the MF 6.2 vertical/camber parameters
# and the MF 6.x files never use the MF 5.2 contact-length and relaxation parameters).
_USED_BY_VERSION = {
    "5.2": set(_COMMON_DEFAULTS) | set(_MF52_DEFAULTS),
    "6.1": set(_COMMON_DEFAULTS),
    "6.2": set(_COMMON_DEFAULTS) | set(_MF62_DEFAULTS),
}

# --- Sections ------------------------------------------------------------------------------------
# The sections of the TNO/MSC layout and the parameters MFeval reads from each (MF 6.2 and MF 5.2
# files together). A section counts as present when the file defines any of its keys, in whatever
# section: MFeval, like vehdyn, reads the keys and ignores the section names.
STANDARD_SECTIONS: Mapping[str, tuple[str, ...]] = MappingProxyType({
    "MODEL": ("FITTYP", "TYRESIDE", "LONGVL", "VXLOW", "ROAD_INCREMENT", "ROAD_DIRECTION", "PROPERTY_FILE_FORMAT",
              "USER_SUB_ID", "N_TIRE_STATES", "USE_MODE", "HMAX_LOCAL", "TIME_SWITCH_INTEG", "FUNCTION_NAME",
              "SWITCH_INTEG"),
    "DIMENSION": ("UNLOADED_RADIUS", "WIDTH", "ASPECT_RATIO", "RIM_RADIUS", "RIM_WIDTH"),
    "OPERATING_CONDITIONS": ("INFLPRES", "NOMPRES"),
    "INERTIA": ("MASS", "IXX", "IYY", "BELT_MASS", "BELT_IXX", "BELT_IYY", "GRAVITY"),
    "VERTICAL": ("FNOMIN", "VERTICAL_STIFFNESS", "VERTICAL_DAMPING", "MC_CONTOUR_A", "MC_CONTOUR_B", "BREFF",
                 "DREFF", "FREFF", "Q_RE0", "Q_V1", "Q_V2", "Q_FZ2", "Q_FCX", "Q_FCY", "Q_CAM", "PFZ1", "Q_FCY2",
                 "Q_CAM1", "Q_CAM2", "Q_CAM3", "Q_FYS1", "Q_FYS2", "Q_FYS3", "BOTTOM_OFFST", "BOTTOM_STIFF",
                 "Q_A1", "Q_A2"),
    "STRUCTURAL": ("LONGITUDINAL_STIFFNESS", "LATERAL_STIFFNESS", "YAW_STIFFNESS", "FREQ_LONG", "FREQ_LAT",
                   "FREQ_YAW", "FREQ_WINDUP", "DAMP_LONG", "DAMP_LAT", "DAMP_YAW", "DAMP_WINDUP", "DAMP_RESIDUAL",
                   "DAMP_VLOW", "Q_BVX", "Q_BVT", "PCFX1", "PCFX2", "PCFX3", "PCFY1", "PCFY2", "PCFY3", "PCMZ1"),
    "CONTACT_PATCH": ("Q_RA1", "Q_RA2", "Q_RB1", "Q_RB2", "ELLIPS_SHIFT", "ELLIPS_LENGTH", "ELLIPS_HEIGHT",
                      "ELLIPS_ORDER", "ELLIPS_MAX_STEP", "ELLIPS_NWIDTH", "ELLIPS_NLENGTH", "ENV_C1", "ENV_C2"),
    "INFLATION_PRESSURE_RANGE": ("PRESMIN", "PRESMAX"),
    "VERTICAL_FORCE_RANGE": ("FZMIN", "FZMAX"),
    "LONG_SLIP_RANGE": ("KPUMIN", "KPUMAX"),
    "SLIP_ANGLE_RANGE": ("ALPMIN", "ALPMAX"),
    "INCLINATION_ANGLE_RANGE": ("CAMMIN", "CAMMAX"),
    "SCALING_COEFFICIENTS": ("LFZO", "LCX", "LMUX", "LEX", "LKX", "LHX", "LVX", "LCY", "LMUY", "LEY", "LKY", "LHY",
                             "LVY", "LTR", "LRES", "LXAL", "LYKA", "LVYKA", "LS", "LKYC", "LKZC", "LVMX", "LMX",
                             "LMY", "LMP", "LSGKP", "LSGAL"),
    "LONGITUDINAL_COEFFICIENTS": ("PCX1", "PDX1", "PDX2", "PDX3", "PEX1", "PEX2", "PEX3", "PEX4", "PKX1", "PKX2",
                                  "PKX3", "PHX1", "PHX2", "PVX1", "PVX2", "PPX1", "PPX2", "PPX3", "PPX4", "RBX1",
                                  "RBX2", "RBX3", "RCX1", "REX1", "REX2", "RHX1", "PTX1", "PTX2", "PTX3"),
    "OVERTURNING_COEFFICIENTS": ("QSX1", "QSX2", "QSX3", "QSX4", "QSX5", "QSX6", "QSX7", "QSX8", "QSX9", "QSX10",
                                 "QSX11", "QSX12", "QSX13", "QSX14", "PPMX1"),
    "LATERAL_COEFFICIENTS": ("PCY1", "PDY1", "PDY2", "PDY3", "PEY1", "PEY2", "PEY3", "PEY4", "PEY5", "PKY1", "PKY2",
                             "PKY3", "PKY4", "PKY5", "PKY6", "PKY7", "PHY1", "PHY2", "PHY3", "PVY1", "PVY2", "PVY3",
                             "PVY4", "PPY1", "PPY2", "PPY3", "PPY4", "PPY5", "RBY1", "RBY2", "RBY3", "RBY4", "RCY1",
                             "REY1", "REY2", "RHY1", "RHY2", "RVY1", "RVY2", "RVY3", "RVY4", "RVY5", "RVY6", "PTY1",
                             "PTY2"),
    "ROLLING_COEFFICIENTS": ("QSY1", "QSY2", "QSY3", "QSY4", "QSY5", "QSY6", "QSY7", "QSY8"),
    "ALIGNING_COEFFICIENTS": ("QBZ1", "QBZ2", "QBZ3", "QBZ4", "QBZ5", "QBZ9", "QBZ10", "QCZ1", "QDZ1", "QDZ2",
                              "QDZ3", "QDZ4", "QDZ6", "QDZ7", "QDZ8", "QDZ9", "QDZ10", "QDZ11", "QEZ1", "QEZ2",
                              "QEZ3", "QEZ4", "QEZ5", "QHZ1", "QHZ2", "QHZ3", "QHZ4", "PPZ1", "PPZ2", "SSZ1", "SSZ2",
                              "SSZ3", "SSZ4"),
    "TURNSLIP_COEFFICIENTS": ("PDXP1", "PDXP2", "PDXP3", "PKYP1", "PDYP1", "PDYP2", "PDYP3", "PDYP4", "PHYP1",
                              "PHYP2", "PHYP3", "PHYP4", "PECP1", "PECP2", "QDTP1", "QCRP1", "QCRP2", "QBRP1",
                              "QDRP1"),
})
"""The sections of a Magic Formula ``.tir`` file and the parameters each holds."""

_SECTIONS_MF52 = ("MODEL", "DIMENSION", "VERTICAL", "VERTICAL_FORCE_RANGE", "LONG_SLIP_RANGE", "SLIP_ANGLE_RANGE",
                  "INCLINATION_ANGLE_RANGE", "SCALING_COEFFICIENTS", "LONGITUDINAL_COEFFICIENTS",
                  "OVERTURNING_COEFFICIENTS", "LATERAL_COEFFICIENTS", "ROLLING_COEFFICIENTS", "ALIGNING_COEFFICIENTS")
_SECTIONS_MF6 = _SECTIONS_MF52 + ("OPERATING_CONDITIONS", "STRUCTURAL", "CONTACT_PATCH", "INFLATION_PRESSURE_RANGE",
                                  "TURNSLIP_COEFFICIENTS")
# The sections a file of each version must have for vehdyn not to warn. Not required: [MDI_HEADER]
# and [UNITS] (SI assumed, as MFeval), [INERTIA] (no steady-state output uses it); for MF 5.2 /
# PAC2002 also the MF 6 sections, which those files do not have (MFeval fills in its defaults).
REQUIRED_SECTIONS: Mapping[str, tuple[str, ...]] = MappingProxyType(
    {"5.2": _SECTIONS_MF52, "6.1": _SECTIONS_MF6, "6.2": _SECTIONS_MF6})
"""Sections a file of each Magic Formula version must define (see :attr:`TirParameters.missing_sections`)."""

# --- [UNITS] ------------------------------------------------------------------------------------
_UNIT_FACTORS = {
    "LENGTH": {"meter": 1.0, "metre": 1.0, "m": 1.0, "mm": 1e-3, "millimeter": 1e-3,
               "cm": 1e-2, "centimeter": 1e-2, "km": 1e3, "kilometer": 1e3, "inch": 0.0254,
               "in": 0.0254, "foot": 0.3048, "ft": 0.3048},
    "FORCE": {"newton": 1.0, "n": 1.0, "kn": 1e3, "kilo_newton": 1e3, "kilonewton": 1e3,
              "pound_force": 4.4482216152605, "lbf": 4.4482216152605,
              "kilogram_force": 9.80665, "kgf": 9.80665, "dyne": 1e-5},
    "ANGLE": {"radian": 1.0, "radians": 1.0, "rad": 1.0, "degree": math.pi / 180.0,
              "degrees": math.pi / 180.0, "deg": math.pi / 180.0},
    "MASS": {"kg": 1.0, "kilogram": 1.0, "gram": 1e-3, "g": 1e-3, "pound_mass": 0.45359237,
             "lbm": 0.45359237, "tonne": 1e3},
    "TIME": {"second": 1.0, "sec": 1.0, "s": 1.0, "millisecond": 1e-3, "ms": 1e-3,
             "minute": 60.0, "min": 60.0, "hour": 3600.0},
}
# Dimension of the parameters that carry units, as exponents of (LENGTH, FORCE, ANGLE, MASS, TIME).
# The Magic Formula coefficients themselves are dimensionless (they act on SI quantities).
_L, _F, _A, _M, _T = range(5)


def _dim(**exponents):
    vector = [0, 0, 0, 0, 0]
    for name, power in exponents.items():
        vector[{"L": _L, "F": _F, "A": _A, "M": _M, "T": _T}[name]] = power
    return tuple(vector)


_PARAMETER_DIMENSIONS = {
    **{k: _dim(L=1) for k in ("UNLOADED_RADIUS", "WIDTH", "RIM_RADIUS", "RIM_WIDTH",
                              "BOTTOM_OFFST", "ROAD_INCREMENT", "HMAX_LOCAL")},
    **{k: _dim(L=1, T=-1) for k in ("LONGVL", "VXLOW")},
    **{k: _dim(F=1) for k in ("FNOMIN", "FZMIN", "FZMAX")},
    **{k: _dim(F=1, L=-2) for k in ("INFLPRES", "NOMPRES", "PRESMIN", "PRESMAX")},
    **{k: _dim(F=1, L=-1) for k in ("VERTICAL_STIFFNESS", "BOTTOM_STIFF",
                                    "LONGITUDINAL_STIFFNESS", "LATERAL_STIFFNESS")},
    "YAW_STIFFNESS": _dim(F=1, L=1, A=-1),
    "VERTICAL_DAMPING": _dim(F=1, L=-1, T=1),
    **{k: _dim(A=1) for k in ("ALPMIN", "ALPMAX", "CAMMIN", "CAMMAX")},
    **{k: _dim(M=1) for k in ("MASS", "BELT_MASS")},
    **{k: _dim(M=1, L=2) for k in ("IXX", "IYY", "BELT_IXX", "BELT_IYY")},
    "GRAVITY": _dim(L=1, T=-2),
    **{k: _dim(T=-1) for k in ("FREQ_LONG", "FREQ_LAT", "FREQ_YAW", "FREQ_WINDUP")},
    "TIME_SWITCH_INTEG": _dim(T=1),
}


class TirParameters(Mapping):
    """The parameters of a ``.tir`` file.

    A read-only mapping ``{KEY: value}`` over :attr:`values` (flat, upper-case keys, SI, with the
    defaults), with the file's structure kept alongside.

    Attributes
    ----------
    sections : Mapping[str, Mapping[str, float | int | str]]
        Keys exactly as written in the file, grouped by section (values as read, before unit
        conversion). Sections keep the file's order.
    tables : Mapping[str, tuple[str, ...]]
        Raw lines of table sections such as ``[SHAPE]`` (not evaluated, kept for writing).
    values : Mapping[str, float | int | str]
        Flat view used by the models: every parameter of every section except ``[UNITS]``
        (names upper-cased, as ``.tir`` keys are case-insensitive), converted to SI, plus the
        defaults for the parameters the file lacks.
    defaulted : tuple[str, ...]
        Names of the parameters the file lacks and that took :data:`MFEVAL_DEFAULTS` values
        (only those the file's Magic Formula version uses).
    unknown : tuple[str, ...]
        Keys of the file that no Magic Formula version uses (kept in ``values``, not evaluated).
    units : Mapping[str, str]
        The ``[UNITS]`` section (``LENGTH``, ``FORCE``, ``ANGLE``, ``MASS``, ``TIME``).
    version : str or None
        ``"5.2"``, ``"6.1"``, ``"6.2"``, or None when the file names no supported version.
    path : str or None
        The file read, if any.
    lines : Mapping[str, int]
        Line of each key of :attr:`values` that the file defines (empty when built from a mapping).
    missing_sections : tuple[str, ...]
        Sections of :data:`REQUIRED_SECTIONS` for the file's version of which the file defines no
        key: all their coefficients are MFeval's defaults (a truncated or incomplete file).

    Raises
    ------
    TirFileError
        If a number is not finite or a range or sign rule of the module docstring is broken.
    """

    def __init__(self, sections, *, tables=None, path=None, lines=None):
        self.sections = MappingProxyType({s: MappingProxyType(dict(kv)) for s, kv in sections.items()})
        self.tables = MappingProxyType({s: tuple(lines) for s, lines in (tables or {}).items()})
        self.path = None if path is None else str(path)
        units = {}
        for section, entries in self.sections.items():
            if section.upper() == "UNITS":
                units.update({k.upper(): str(v) for k, v in entries.items()})
        self.units = MappingProxyType(units)
        flat, written, key_lines = {}, {}, {}
        for section, entries in self.sections.items():
            if section.upper() == "UNITS":
                continue
            for key, value in entries.items():
                name = key.upper()
                written[name] = value
                if lines and (section, key) in lines:
                    key_lines[name] = lines[(section, key)]
                flat[name] = _to_si(name, value, self.units, self.path)
        self.lines = MappingProxyType(key_lines)
        _check_finite(flat, written, key_lines, self.path)
        self.version = _detect_version(flat)
        used = _USED_BY_VERSION.get(self.version or "6.2", set(MFEVAL_DEFAULTS))
        defaulted = [k for k in MFEVAL_DEFAULTS if k in used and k not in flat]
        for key in defaulted:
            flat[key] = MFEVAL_DEFAULTS[key]
        _check_rules(flat, written, key_lines, self.path)
        self.values = MappingProxyType(flat)
        self.defaulted = tuple(defaulted)
        self.unknown = tuple(k for k in flat if k not in MFEVAL_DEFAULTS and k not in _IGNORED_KEYS)
        self.missing_sections = tuple(
            section for section in REQUIRED_SECTIONS.get(self.version, ())
            if not any(key in written for key in STANDARD_SECTIONS[section]))

    def __getitem__(self, key: str):
        return self.values[key]

    def __iter__(self):
        return iter(self.values)

    def __len__(self) -> int:
        return len(self.values)

    def to_dict(self) -> dict:
        """The flat SI values (with defaults) as a plain dict.

        Returns
        -------
        dict
            ``{KEY: value}``, as :attr:`values`.
        """
        return dict(self.values)

    def __eq__(self, other) -> bool:
        if not isinstance(other, TirParameters):
            return NotImplemented
        return ({s: dict(kv) for s, kv in self.sections.items()}
                == {s: dict(kv) for s, kv in other.sections.items()}
                and dict(self.tables) == dict(other.tables))

    __hash__ = None

    def __repr__(self) -> str:
        n = sum(len(kv) for kv in self.sections.values())
        where = f" from {self.path!r}" if self.path else ""
        return (f"TirParameters(version={self.version!r}, {n} keys in {len(self.sections)} sections,"
                f" {len(self.defaulted)} defaulted{where})")


def _is_real(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _coefficient_error(message, key, value, path, line) -> TirFileError:
    """A TirFileError that also carries the offending ``key`` and ``value`` as attributes."""
    error = TirFileError(message, path=path, line=line)
    error.key, error.value = key, value
    return error


def _check_finite(flat, written, lines, path) -> None:
    """Every number of the file (after unit conversion) must be finite."""
    for key, value in flat.items():
        if _is_real(value) and not math.isfinite(value):
            shown = written[key]
            extra = "" if shown is value or not math.isfinite(shown) else f" ({value!r} in SI units)"
            raise _coefficient_error(f"{key} = {shown!r}{extra} is not a finite number", key, shown, path,
                                     lines.get(key))


# (key, bound, comparison) per sign rule; the reasons are in the module docstring
_SIGN_RULES = (("PDX1", ">"), ("PDY1", ">"), ("QCZ1", ">"), ("LFZO", ">"), ("LMUX", ">="), ("LMUY", ">="))


def _check_rules(flat, written, lines, path) -> None:
    """The range and sign rules of the module docstring, on the values with their defaults."""

    def number(key):
        value = flat.get(key)
        return float(value) if _is_real(value) else None  # strings: MagicFormula reports them

    def show(key, blamed):  # "KEY = value", with the line of a key other than the one the error points at
        if key not in written:
            return f"{key} = {flat[key]!r} (MFeval's default; the file does not set it)"
        return f"{key} = {written[key]!r}" + (f" (line {lines[key]})" if key in lines and key != blamed else "")

    def fail(blamed, template, *keys):
        message = template.format(*(show(k, blamed) for k in keys))
        raise _coefficient_error(message, blamed, written.get(blamed, flat.get(blamed)), path, lines.get(blamed))

    for low, high, what in (("FZMIN", "FZMAX", "vertical load"), ("ALPMIN", "ALPMAX", "slip angle"),
                            ("KPUMIN", "KPUMAX", "slip ratio"), ("CAMMIN", "CAMMAX", "inclination angle"),
                            ("PRESMIN", "PRESMAX", "inflation pressure")):
        a, b = number(low), number(high)
        if a is None or b is None:
            continue
        if low == "FZMIN" and not b > 0:
            fail(high, "{}: the largest load of the range must be > 0", high)
        if low in ("FZMIN", "PRESMIN") and not a >= 0:
            fail(low, f"{{}}: the smallest {what} of the range must be >= 0", low)
        strict = low in ("FZMIN", "ALPMIN", "KPUMIN")
        if (a >= b) if strict else (a > b):
            blamed = low if low in written or high not in written else high
            fail(blamed, f"{{}} must be {'<' if strict else '<='} {{}}: the {what} range is "
                         f"{'empty or ' if strict else ''}inverted", low, high)
        if low in ("ALPMIN", "KPUMIN") and not a < 0 < b:
            fail(high if a < 0 else low, f"the {what} range must contain 0 inside (free rolling): {{}}, {{}}",
                 low, high)
        if low == "CAMMIN" and not a <= 0 <= b:
            fail(high if a <= 0 else low, f"the {what} range must contain 0: {{}}, {{}}", low, high)
    for key, relation in _SIGN_RULES:
        value = number(key)
        if value is not None and not (value > 0 if relation == ">" else value >= 0):
            fail(key, f"{{}} must be {relation} 0 (see vehdyn.tire.tir: the sign rules)", key)


def _to_si(key, value, units, path):
    dimension = _PARAMETER_DIMENSIONS.get(key)
    if dimension is None or isinstance(value, str) or not units:
        return value
    factor = 1.0
    for quantity, power in zip(("LENGTH", "FORCE", "ANGLE", "MASS", "TIME"), dimension):
        if power == 0 or quantity not in units:
            continue
        unit = units[quantity].strip().lower()
        table = _UNIT_FACTORS[quantity]
        if unit not in table:
            raise TirFileError(f"unknown {quantity} unit {units[quantity]!r} in [UNITS] "
                               f"(known: {', '.join(sorted(table))})", path=path)
        factor *= table[unit] ** power
    return value * factor if factor != 1.0 else value


def _detect_version(flat):
    fittyp = flat.get("FITTYP")
    if fittyp is not None and not isinstance(fittyp, str):
        return VERSION_BY_FITTYP.get(int(fittyp)) if float(fittyp).is_integer() else None
    fmt = str(flat.get("PROPERTY_FILE_FORMAT", "")).strip().upper()
    return "5.2" if fmt in _PAC2002_FORMATS else None


def _parse_value(text: str, path, line_number):
    text = text.strip()
    if text.startswith("'") or text.startswith('"'):
        quote = text[0]
        end = text.find(quote, 1)
        if end < 0:
            raise TirFileError(f"unterminated string {text!r}", path=path, line=line_number)
        if text[end + 1:].strip():
            raise TirFileError(f"unexpected text after string: {text!r}", path=path, line=line_number)
        return text[1:end]
    if not text:
        raise TirFileError("missing value after '='", path=path, line=line_number)
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        raise TirFileError(f"value {text!r} is neither a number nor a quoted string",
                           path=path, line=line_number) from None


def _strip_comment(line: str) -> str:
    """Drop a trailing ``$`` comment that is not inside a quoted string."""
    quote = None
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "$":
            return line[:i]
    return line


def parse_tir(text: str, path=None) -> TirParameters:
    """Parse the text of a ``.tir`` file (see :func:`read_tir`; a leading byte-order mark is skipped)."""
    sections: dict[str, dict] = {}
    tables: dict[str, list[str]] = {}
    lines: dict[tuple[str, str], int] = {}
    current = None
    if text.startswith("\ufeff"):
        text = text[1:]
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("$") or line.startswith("!"):
            continue
        if line.startswith("["):
            end = line.find("]")
            name = line[1:end].strip() if end > 0 else ""
            if end < 0 or not name or _strip_comment(line[end + 1:]).strip():
                raise TirFileError(f"malformed section header {line!r}", path=path, line=number)
            current = name
            if current.upper() in _TABLE_SECTIONS:
                tables.setdefault(current, [])
            else:
                sections.setdefault(current, {})
            continue
        if current in tables:
            tables[current].append(raw.rstrip("\r\n"))
            continue
        body = _strip_comment(raw)
        if "=" not in body:
            if current is not None and not sections.get(current) and (line.startswith("{")):
                # An unknown table section (first body line is a '{...}' header): keep it raw.
                sections.pop(current, None)
                tables[current] = [raw.rstrip("\r\n")]
                continue
            raise TirFileError(f"expected 'KEY = value', found {line!r}", path=path, line=number)
        if current is None:
            raise TirFileError("parameter before the first [SECTION] header", path=path, line=number)
        key, _, value_text = body.partition("=")
        key = key.strip()
        if not key or not key.replace("_", "").isalnum():
            raise TirFileError(f"invalid parameter name {key!r}", path=path, line=number)
        if key in sections[current]:
            raise TirFileError(f"{key} defined twice in [{current}]", path=path, line=number)
        sections[current][key] = _parse_value(value_text, path, number)
        lines[(current, key)] = number
    if not sections:
        raise TirFileError("no [SECTION] with parameters found", path=path)
    return TirParameters(sections, tables=tables, path=path, lines=lines)


def read_tir(path, *, strict: bool = False) -> TirParameters:
    """Read a ``.tir`` tire property file.

    Parameters
    ----------
    path : str or pathlib.Path
        The file (UTF-8 with or without a byte-order mark, UTF-16 with one, or Latin-1).
    strict : bool
        Raise instead of warning when the file lacks whole sections.

    Returns
    -------
    TirParameters
        Keys verbatim by section, the SI flat view with defaults, the defaulted names and the
        detected Magic Formula version.

    Raises
    ------
    TirFileError
        If the file cannot be read, a line is malformed, or a value breaks a rule of the module
        docstring (the message gives the key, the value and the line); with ``strict=True`` also
        if sections are missing.

    Warns
    -----
    VehdynWarning
        If the file lacks whole sections of its version (:attr:`TirParameters.missing_sections`):
        their coefficients take MFeval's defaults.

    Notes
    -----
    The values of :attr:`TirParameters.values` are in SI (N, m, rad, Pa, kg, s) and the ISO-W
    (TYDEX W) axes of the file: coefficients are used as written (``TYRESIDE`` is not mirrored).

    References
    ----------
    .. [1] TNO Automotive, *MF-Tyre/MF-Swift 6.2 Equation Manual* and *MF-Tyre User Manual* 5.2
       (the TeimOrbit ``.tir`` format and its keys).
    .. [2] M. Furlan, *MFeval* 4.3.1, MATLAB File Exchange #63618 (the defaults of missing keys).

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.tire import read_tir
    >>> params = read_tir(vehdyn.data_path("tires", "MagicFormula61_Parameters.tir"))
    >>> params.version, params["FNOMIN"], params["UNLOADED_RADIUS"]    # SI: [N], [m]
    ('6.1', 6752, 0.3943)
    >>> params.units["LENGTH"], len(params.defaulted)
    ('meter', 0)
    """
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise TirFileError(f"cannot read the file ({exc.strerror})", path=str(path)) from None
    params = parse_tir(_decode(data, str(path)), path=str(path))
    check_sections(params, strict)
    return params


def _decode(data: bytes, path) -> str:
    """The text of a file: UTF-16 or UTF-8 by their byte-order mark, else UTF-8, else Latin-1."""
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return data.decode("utf-16")
        except UnicodeDecodeError as exc:
            raise TirFileError(f"not valid UTF-16 after its byte-order mark ({exc.reason})", path=path) from None
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")  # older tools write Latin-1 comments (every byte is valid)


def check_sections(params: TirParameters, strict: bool = False) -> None:
    """Warn (or, ``strict``, raise :class:`TirFileError`) when ``params`` lacks whole sections.

    The message names the missing sections and counts the coefficients that take MFeval's
    defaults because of them.

    Parameters
    ----------
    params : TirParameters
        Parameters read from a file (:attr:`TirParameters.missing_sections`).
    strict : bool
        Raise instead of warning.

    Raises
    ------
    TirFileError
        With ``strict=True``, if sections are missing.

    Warns
    -----
    VehdynWarning
        Without ``strict``, if sections are missing.
    """
    missing = params.missing_sections
    if not missing:
        return
    defaulted = set(params.defaulted)
    count = sum(key in defaulted for section in missing for key in STANDARD_SECTIONS[section])
    names = ", ".join(f"[{section}]" for section in missing)
    message = (f"the MF {params.version} file lacks {len(missing)} section{'s' if len(missing) > 1 else ''} "
               f"({names}): {count} coefficients take MFeval's defaults (a truncated file?)")
    if strict:
        raise TirFileError(message, path=params.path)
    where = f"{params.path}: " if params.path else ""
    warnings.warn(where + message + "; strict=True makes this an error", VehdynWarning, stacklevel=_user_stacklevel())


def _user_stacklevel() -> int:
    """The ``stacklevel`` that points a warning at the first caller outside vehdyn."""
    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    frame, level = sys._getframe(1), 1
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(package + os.sep):
        frame, level = frame.f_back, level + 1
    return level


def _format_value(value) -> str:
    if isinstance(value, str):
        return f"'{value}'"
    if isinstance(value, bool):
        return str(int(value))
    if isinstance(value, int):
        return str(value)
    return repr(float(value))


def write_tir(params: TirParameters | Mapping[str, Mapping], path) -> Path:
    """Write parameters to a ``.tir`` file that :func:`read_tir` reads back to equal values.

    Parameters
    ----------
    params : TirParameters or mapping of section name to mapping of key to value
        What to write: the file's sections as read (values in the file's units, not the SI view;
        defaults are not written), table sections included.
    path : str or pathlib.Path
        Destination. Written atomically (:mod:`vehdyn._atomic`): a temporary file beside it is
        moved over it once complete, so an interrupted or failed write (disk full, an exception)
        leaves the previous file, or none, never a truncated one.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    TirFileError
        If a value breaks a rule of the module docstring (:func:`read_tir` would refuse the file).

    Notes
    -----
    The text is Latin-1, as older tools expect, unless a string needs UTF-8.
    """
    if isinstance(params, TirParameters):
        sections, tables = params.sections, params.tables
    else:
        sections, tables = params, {}
        TirParameters(sections)  # refuse to write what read_tir would refuse (non-finite numbers, rules)
    path = Path(path)
    encoding = "latin-1"
    try:
        for text in _texts(sections, tables):
            text.encode("latin-1")
    except UnicodeEncodeError:
        encoding = "utf-8"
    with atomic_write(path, "w", encoding=encoding) as handle:
        for line in _tir_lines(sections, tables):
            handle.write(line + "\n")
    return path


def _texts(sections, tables):
    """Every piece of text :func:`_tir_lines` writes besides numbers."""
    for section, entries in sections.items():
        yield section
        for key, value in entries.items():
            yield key
            if isinstance(value, str):
                yield value
    for section, rows in tables.items():
        yield section
        yield from rows


def _tir_lines(sections, tables):
    """The lines of the ``.tir`` text of ``sections`` and ``tables`` (generated while writing)."""
    yield "$ written by vehdyn.tire.write_tir"
    for section in list(sections) + [t for t in tables if t not in sections]:
        yield f"[{section}]"
        if section in tables:
            yield from tables[section]
            continue
        for key, value in sections[section].items():
            yield f"{key:<25}= {_format_value(value)}"
