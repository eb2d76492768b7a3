"""Tire models in the ISO-W (TYDEX) axis system of ``.tir`` files (see :mod:`vehdyn.conventions`).

API index
---------
Files
    :func:`read_tir`, :func:`write_tir`, :class:`TirParameters` (``.defaulted``, ``.version``)
Magic Formula (MF 5.2 / PAC2002, 6.1, 6.2; validated against MFeval 4.3.1)
    :class:`MagicFormula` (``from_tir``, ``evaluate``, ``forces``), :class:`MagicFormulaOutputs`,
    :func:`load_tire`
Other laws (each ``forces(fz, kappa, alpha, gamma=0.0, vx=...) -> TireForces``)
    :class:`LinearTire`, :class:`BrushTire`, :class:`FialaTire`, :class:`DugoffTire`
Interface of every tire law
    :class:`TireModel`, :class:`TireForces`
Registry (a vehicle file's ``tires.model``)
    :func:`tire_law`, :func:`tire_law_names`, :func:`register_tire_law`, :func:`tire_for_vehicle`
Slip and transients
    :func:`wheel_slip`, :func:`regularized_speed`, :func:`slip_velocities`, :func:`theoretical_slip`,
    :class:`TireRelaxation`, :func:`relaxation_lengths`
Soft soil (terramechanics: Bekker, Janosi-Hanamoto, Wong-Reece; see :mod:`vehdyn.tire.terramechanics`)
    :class:`SoftSoilTire` (a tire law on a :class:`~vehdyn.tire.terramechanics.Soil`), the subpackage
    ``terramechanics``
Measured data and fitting (scipy, pandas imported on use)
    :func:`read_tire_data`, :func:`fit_magic_formula`, :func:`fit_brush`, :func:`fit_linear`,
    :class:`TireFit`
Plots
    :func:`plot_tire_characteristics`, :func:`characteristic_values`, :func:`describe_tire`
    (matplotlib and pandas imported on use)
"""

from vehdyn.tire.base import TireForces, TireModel
from vehdyn.tire.brush import BrushTire
from vehdyn.tire.dugoff import DugoffTire
from vehdyn.tire.fiala import FialaTire
from vehdyn.tire.linear import LinearTire
from vehdyn.tire.magic_formula import MagicFormula, MagicFormulaOutputs, load_tire
from vehdyn.tire.plots import characteristic_values, describe_tire, plot_tire_characteristics
from vehdyn.tire.registry import register_tire_law, tire_for_vehicle, tire_law, tire_law_names
from vehdyn.tire.relaxation import TireRelaxation, relaxation_lengths
from vehdyn.tire.slip import WheelSlip, regularized_speed, slip_velocities, theoretical_slip, wheel_slip
from vehdyn.tire.tir import TirParameters, read_tir, write_tir
from vehdyn.tire import terramechanics
from vehdyn.tire.terramechanics import SoftSoilTire
from vehdyn.tire.tire_data import read_tire_data
from vehdyn.tire.fitting import TireFit, fit_brush, fit_linear, fit_magic_formula

__all__ = [
    "TireForces",
    "TireModel",
    "MagicFormula",
    "MagicFormulaOutputs",
    "load_tire",
    "TirParameters",
    "read_tir",
    "write_tir",
    "LinearTire",
    "BrushTire",
    "FialaTire",
    "DugoffTire",
    "tire_law",
    "tire_law_names",
    "register_tire_law",
    "tire_for_vehicle",
    "WheelSlip",
    "wheel_slip",
    "regularized_speed",
    "slip_velocities",
    "theoretical_slip",
    "TireRelaxation",
    "relaxation_lengths",
    "plot_tire_characteristics",
    "describe_tire",
    "characteristic_values",
    "terramechanics",
    "SoftSoilTire",
    "read_tire_data",
    "fit_magic_formula",
    "fit_brush",
    "fit_linear",
    "TireFit",
]
