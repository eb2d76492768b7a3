"""The aerodynamic side force and yaw moment of a crosswind, shared by every vehicle model.

A lateral wind w (the air's velocity along the vehicle's y axis, SAE: positive blowing toward the
right, i.e. a wind from the left) meets a vehicle driving at forward speed u. The air flows past
the body at the resultant speed V_r and the aerodynamic sideslip angle beta_w::

    V_r^2 = u^2 + w^2,        beta_w = atan(w / |u|)

and makes a side force at the centre of pressure, a distance x_p ahead of the CG, hence a yaw
moment about the CG (Hucho, *Aerodynamics of Road Vehicles*, 4th ed., 1998, sec. 4.4; Wong,
*Theory of Ground Vehicles*, 4th ed., 2008, sec. 3.2)::

    F_w = 0.5 rho V_r^2 A C_Y' beta_w,        M_w = x_p F_w

with rho the air density, A the frontal (reference) area and C_Y' = dC_Y/d(beta_w) the
side-force coefficient slope (``vehicle.aero.side_force_coefficient_slope``). The centre of
pressure sits ``vehicle.aero.centre_of_pressure_from_front_axle`` times the wheelbase behind the
front axle: x_p = a - f_p L. SAE signs: a wind toward +y pushes the vehicle toward +y, and with
x_p > 0 yaws its nose toward +y, downwind. The force is linear in beta_w, as measured on cars up
to beta_w of about 20 degrees (Hucho 1998, sec. 4.4). The wind is taken in the vehicle's axes;
the aerodynamic sideslip from the vehicle's own lateral velocity and yaw rate is neglected (its
force is 0.5 rho u A C_Y' v, about 1 % of the tires' C v / u at highway speed, so the vehicle's
eigenvalues stay those of the model without wind).

Linearized about w = 0 (every wind-free state):  F_w = 0.5 rho A C_Y' u w = k_w u w, the input
column of the linear handling models' ``wind_velocity_lateral``.

References
----------
.. [1] W.-H. Hucho (ed.), *Aerodynamics of Road Vehicles*, 4th ed., SAE, 1998, sec. 4.4.
.. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 3.2.
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params import Vehicle
from vehdyn.params.checks import check_vehicle

__all__ = ["aero_side_force", "wind_side_force_factor", "trailer_wind_side_force_factor",
           "centre_of_pressure_ahead_of_cg"]


def aero_side_force(xp, side_force_factor, speed, wind_velocity_lateral):
    """Aerodynamic side force F_w = k_w (u^2 + w^2) atan(w / |u|) [N] (SAE y).

    Parameters
    ----------
    xp : namespace
        ``numpy`` or the compiled namespace of :mod:`~vehdyn.handling.single_track_equations`
        (needs ``atan2`` and ``abs``).
    side_force_factor : float or ndarray
        k_w = 0.5 rho A C_Y' [kg/m] (:func:`wind_side_force_factor`).
    speed : float or ndarray
        Forward speed u of the vehicle [m/s].
    wind_velocity_lateral : float or ndarray
        w [m/s], the air's velocity along the vehicle's y axis (positive toward the right).

    Returns
    -------
    float or ndarray
        F_w [N] (SAE y).
    """
    return side_force_factor * (speed * speed + wind_velocity_lateral * wind_velocity_lateral) * \
        xp.atan2(wind_velocity_lateral, xp.abs(speed))


def _side_force_factor(air_density: float, area: float, slope: float) -> float:
    """k_w = 0.5 rho A C_Y' [kg/m]: the one factor of the side-force law for every body."""
    return 0.5 * air_density * area * slope


def wind_side_force_factor(vehicle: Vehicle) -> float:
    """k_w = 0.5 rho A C_Y' of ``vehicle`` (its ``aero`` group).

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle.

    Returns
    -------
    float
        k_w [kg/m].
    """
    aero = check_vehicle("wind_side_force_factor", vehicle).aero
    return _side_force_factor(aero.air_density, aero.frontal_area, aero.side_force_coefficient_slope)


def trailer_wind_side_force_factor(trailer, air_density: float | None = None) -> float:
    """k_w,t = 0.5 rho A_t C_Y,t' [kg/m] of a :class:`~vehdyn.Trailer` (same law as the towing vehicle's).

    Parameters
    ----------
    trailer : Trailer
        Its ``frontal_area`` and ``side_force_coefficient_slope`` (0: no wind force on the trailer).
    air_density : float, optional
        rho [kg/m^3]; :func:`~vehdyn.handling.car_trailer_parameters` passes the towing vehicle's.
        Default: the vehicle files' standard air (``Aerodynamics.air_density``'s default, 20 degC).

    Returns
    -------
    float
        k_w,t [kg/m].
    """
    import dataclasses

    from vehdyn.params import Trailer
    from vehdyn.params.vehicle import Aerodynamics

    if air_density is None:
        air_density = next(f.default for f in dataclasses.fields(Aerodynamics) if f.name == "air_density")

    if not isinstance(trailer, Trailer):
        raise ParameterError(f"trailer must be a vehdyn Trailer, got {type(trailer).__name__}", key="trailer",
                             value=trailer)
    rho = float(air_density)
    if not (np.isfinite(rho) and rho > 0):
        raise ParameterError(f"air_density must be finite and positive [kg/m^3], got {air_density!r}",
                             key="air_density", value=air_density)
    return _side_force_factor(rho, trailer.frontal_area, trailer.side_force_coefficient_slope)


def centre_of_pressure_ahead_of_cg(vehicle: Vehicle) -> float:
    """x_p = a - f_p L: the aerodynamic centre of pressure ahead of the CG.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle.

    Returns
    -------
    float
        x_p [m] (negative: behind the CG).
    """
    v = check_vehicle("centre_of_pressure_ahead_of_cg", vehicle)
    return v.geometry.cg_to_front_axle - v.aero.centre_of_pressure_from_front_axle * v.geometry.wheelbase
