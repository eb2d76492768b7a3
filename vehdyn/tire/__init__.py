"""Tire models in the ISO-W (TYDEX) axis system of ``.tir`` files.

API index
---------
Files
    :func:`read_tir`, :func:`write_tir`, :class:`TirParameters` (``.defaulted``, ``.version``)
Magic Formula (MF 5.2 / PAC2002, 6.1, 6.2; validated against MFeval 4.3.1)
    :class:`MagicFormula` (``from_tir``, ``evaluate``, ``forces``), :class:`MagicFormulaOutputs`,
    :func:`load_tire`
Interface of every tire law
    :class:`TireModel`, :class:`TireForces`
"""

from .base import TireForces, TireModel
from .magic_formula import MagicFormula, MagicFormulaOutputs, load_tire
from .tir import TirParameters, read_tir, write_tir

__all__ = [
    "TireForces",
    "TireModel",
    "MagicFormula",
    "MagicFormulaOutputs",
    "load_tire",
    "TirParameters",
    "read_tir",
    "write_tir",
]
