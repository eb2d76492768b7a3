"""Tire laws, slip, transients and tire plots (ISO-W axes of ``.tir`` files; see :mod:`vehdyn.conventions`).

Laws (each ``forces(fz, kappa, alpha, gamma=0.0, vx=...) -> TireForces``)
    :class:`LinearTire`, :class:`BrushTire`, :class:`FialaTire`, :class:`DugoffTire`
Registry (a vehicle file's ``tires.model``)
    :func:`tire_law`, :func:`tire_law_names`, :func:`register_tire_law`, :func:`tire_for_vehicle`
Slip and transients
    :func:`wheel_slip`, :func:`regularized_speed`, :func:`slip_velocities`, :func:`theoretical_slip`,
    :class:`TireRelaxation`, :func:`relaxation_lengths`
Plots
    :func:`plot_tire_characteristics`, :func:`characteristic_values`, :func:`describe_tire`
    (matplotlib and pandas imported on use)
"""

from .base import TireForces, TireModel
from .brush import BrushTire
from .dugoff import DugoffTire
from .fiala import FialaTire
from .linear import LinearTire
from .plots import characteristic_values, describe_tire, plot_tire_characteristics
from .registry import register_tire_law, tire_for_vehicle, tire_law, tire_law_names
from .relaxation import TireRelaxation, relaxation_lengths
from .slip import WheelSlip, regularized_speed, slip_velocities, theoretical_slip, wheel_slip

__all__ = [
    "TireForces",
    "TireModel",
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
]
