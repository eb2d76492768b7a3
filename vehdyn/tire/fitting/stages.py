"""The stages of a Magic Formula fit and the coefficients each stage owns.

The staged procedure of the literature (Pacejka 2012, sec. 4.3.2 and appendix 3; the TNO MF-Tyre
fitting practice; Besselink et al. 2010): each characteristic is fitted on the data that excite
it, first the pure-slip forces at the nominal load, then their load, camber and pressure
dependence, then the combined-slip weighting functions with the pure-slip forces held, then the
moments. Within a stage the steps are cumulative: the "load" step refits the "nominal"
coefficients together with the load coefficients on the zero-camber data at every load, and so on.
A step whose data do not vary (one load, no camber sweep, one pressure) is skipped and its
coefficients keep their start values (reported as not identifiable).

:data:`STAGES` is the ownership table: stage -> :class:`Stage` (outputs, needed columns, data
selection, steps with their coefficients). :func:`owned` gives the steps for one Magic Formula
version (MF 5.2 lacks the pressure terms, PEY5, PKY5-7 and has PHY3).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Stage", "STAGES", "STAGE_NAMES", "owned", "STEP_VARIATION", "TYPICAL_SIZE", "typical_size"]


@dataclass(frozen=True)
class Stage:
    """One stage of the fit.

    Parameters
    ----------
    name : str
        The stage's name.
    outputs : tuple of str
        Measured columns the stage fits (``fx``, ``fy``, ``mz``, ``mx``, ``my``).
    needs : tuple of str
        Columns the stage cannot do without.
    selection : str
        ``"pure_longitudinal"`` (alpha = 0), ``"pure_lateral"`` (kappa = 0), ``"combined"``
        (kappa non-zero: the slip-ratio sweeps at every slip angle, where the weighting functions and
        the kappa-induced side force act; the data must hold some points with both slips non-zero)
        or ``"all"``.
    steps : tuple of (str, tuple of str)
        ``(step, coefficients)``; step is ``"nominal"``, ``"load"``, ``"camber"`` or ``"pressure"``.
    """

    name: str
    outputs: tuple
    needs: tuple
    selection: str
    steps: tuple


STEP_VARIATION = {"load": "fz", "camber": "gamma", "pressure": "pressure"}
"""The column a step needs a sweep of."""

STAGES = {
    "pure_longitudinal": Stage(
        "pure_longitudinal", ("fx",), ("fz", "kappa", "fx"), "pure_longitudinal", (
            ("nominal", ("PCX1", "PDX1", "PEX1", "PEX4", "PKX1", "PHX1", "PVX1")),
            ("load", ("PDX2", "PEX2", "PEX3", "PKX2", "PKX3", "PHX2", "PVX2")),
            ("camber", ("PDX3",)),
            ("pressure", ("PPX1", "PPX2", "PPX3", "PPX4")),
        )),
    "pure_lateral": Stage(
        "pure_lateral", ("fy",), ("fz", "alpha", "fy"), "pure_lateral", (
            ("nominal", ("PCY1", "PDY1", "PEY1", "PEY3", "PKY1", "PHY1", "PVY1")),
            ("load", ("PDY2", "PEY2", "PKY2", "PKY4", "PHY2", "PVY2")),
            ("camber", ("PDY3", "PEY4", "PEY5", "PKY3", "PKY5", "PKY6", "PKY7", "PHY3", "PVY3", "PVY4")),
            ("pressure", ("PPY1", "PPY2", "PPY3", "PPY4", "PPY5")),
        )),
    "aligning": Stage(
        "aligning", ("mz",), ("fz", "alpha", "mz"), "pure_lateral", (
            ("nominal", ("QBZ1", "QBZ9", "QCZ1", "QDZ1", "QDZ6", "QEZ1", "QEZ4", "QHZ1")),
            ("load", ("QBZ2", "QBZ3", "QBZ10", "QDZ2", "QDZ7", "QEZ2", "QEZ3", "QHZ2")),
            ("camber", ("QBZ4", "QBZ5", "QDZ3", "QDZ4", "QDZ8", "QDZ9", "QDZ10", "QDZ11", "QEZ5", "QHZ3", "QHZ4")),
            ("pressure", ("PPZ1", "PPZ2")),
        )),
    "combined": Stage(
        "combined", ("fx", "fy", "mz"), ("fz", "kappa", "alpha"), "combined", (
            ("nominal", ("RBX1", "RBX2", "RCX1", "REX1", "RHX1", "RBY1", "RBY2", "RBY3", "RCY1", "REY1", "RHY1",
                         "RVY1", "RVY4", "RVY5", "RVY6", "SSZ1", "SSZ2")),
            ("load", ("REX2", "REY2", "RHY2", "RVY2", "SSZ4")),
            ("camber", ("RBX3", "RBY4", "RVY3", "SSZ3")),
        )),
    "overturning": Stage(
        "overturning", ("mx",), ("fz", "mx"), "all", (
            ("nominal", ("QSX1", "QSX3")),
            ("load", ("QSX4", "QSX5", "QSX6", "QSX8", "QSX9")),
            ("camber", ("QSX2", "QSX7", "QSX10", "QSX11")),
            ("pressure", ("PPMX1",)),
        )),
    "rolling_resistance": Stage(
        "rolling_resistance", ("my",), ("fz", "my"), "all", (
            ("nominal", ("QSY1", "QSY2")),
            ("load", ("QSY7",)),
            ("camber", ("QSY5", "QSY6")),
            ("pressure", ("QSY8",)),
        )),
}
"""Stage -> :class:`Stage`: the coefficient ownership table (each coefficient owned once)."""

STAGE_NAMES = tuple(STAGES)

_NOT_IN = {
    "5.2": {"PEY5", "PKY5", "PKY6", "PKY7", "PPX1", "PPX2", "PPX3", "PPX4", "PPY1", "PPY2", "PPY3", "PPY4", "PPY5",
            "PPZ1", "PPZ2", "PPMX1", "QSY5", "QSY6", "QSY7", "QSY8"},
    "6.1": {"PHY3"},
    "6.2": {"PHY3"},
}


def owned(stage: str, version: str):
    """The steps of a stage for one Magic Formula version.

    MF 5.2 has no pressure dependence (its pressure step is dropped), no PEY5, PKY5-PKY7 or
    QSY5-QSY8, and uses PHY3 for the camber shift; MF 6.x do not use PHY3.

    Parameters
    ----------
    stage : str
        A key of :data:`STAGES`.
    version : {"5.2", "6.1", "6.2"}
        The Magic Formula version.

    Returns
    -------
    tuple of (str, tuple of str)
        ``(step, coefficients)`` in order, without the coefficients the version lacks.
    """
    drop = _NOT_IN[version]
    steps = []
    for step, names in STAGES[stage].steps:
        kept = tuple(n for n in names if n not in drop)
        if kept:
            steps.append((step, kept))
    return tuple(steps)

TYPICAL_SIZE = {
    "PCX1": 2, "PDX1": 2, "PEX3": 2, "PEX4": 2, "PKX1": 40, "PKX2": 20, "PDX3": 9,
    "PCY1": 2, "PDY1": 2, "PEY3": 50, "PKY1": 30, "PKY2": 8, "PKY4": 3, "PDY3": 8, "PEY4": 700, "PEY5": 60,
    "PKY5": 50, "PKY6": 2, "PPY2": 2,
    "QBZ1": 20, "QBZ9": 200, "QCZ1": 2, "QEZ1": 4, "QEZ4": 2, "QBZ2": 3, "QBZ3": 2, "QBZ10": 20, "QEZ2": 2,
    "QEZ3": 2, "QBZ4": 2, "QBZ5": 4, "QDZ3": 2, "QDZ4": 30, "QDZ10": 2, "QDZ11": 5, "QEZ5": 100,
    "RBX1": 20, "RBX2": 20, "RCX1": 2, "REX1": 2, "RBY1": 30, "RBY2": 20, "RCY1": 2, "RVY4": 100, "RVY5": 2,
    "RVY6": 30, "REX2": 5, "RBX3": 700, "RBY4": 2000,
    "QSX2": 10, "QSX3": 2, "QSX4": 20, "QSX6": 10, "QSX8": 5, "QSX11": 5,
}
"""Typical magnitude of the coefficients whose size exceeds 1 [-]: the largest |value| among the
published parameter sets shipped in ``data/tires`` (the MF 6.1 and 5.2 example tires of MFeval,
Project Chrono's 185/80 R14) and MFeval's defaults, rounded up to one significant digit. Every other
fitted coefficient is of order 1 (the Magic Formula writes its load, camber and pressure terms as
dimensionless polynomials). The ridge of the fit measures a coefficient's change in these sizes."""


def typical_size(name: str) -> float:
    """Typical magnitude of a coefficient.

    Parameters
    ----------
    name : str
        Coefficient name (``"QBZ9"``).

    Returns
    -------
    float
        :data:`TYPICAL_SIZE` of it, else 1 [the coefficient's unit].
    """
    return float(TYPICAL_SIZE.get(name, 1.0))
