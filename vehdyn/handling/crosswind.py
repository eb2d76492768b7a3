"""Crosswind in the handling models: the wind input of the linear models and the steady yaw rate.

The side force and yaw moment are those of :mod:`vehdyn.components.aero`; the crosswind procedures
(gust, ISO 12021 sensitivity) are in :mod:`vehdyn.procedures.crosswind`.


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
column of :class:`~vehdyn.handling.LinearBicycle`'s ``wind_velocity_lateral``.

Which way the vehicle turns is set by where the centre of pressure lies against the neutral steer
point (NSP, the point where a side force makes no steady yaw rate,
:func:`~vehdyn.handling.neutral_steer_point`), x_n = (a C_f - b C_r) / (C_f + C_r) ahead of the CG.
The steady yaw rate under a side force F at x_p is (:func:`steady_state_crosswind_yaw_rate`)::

    r = F u (C_f + C_r) (x_p - x_n) / (C_f C_r L (L + K u^2))

with K the understeer gradient: a centre of pressure ahead of the NSP (the usual case, Wong 2008,
sec. 3.2) turns the vehicle downwind.
"""

from __future__ import annotations



from vehdyn.errors import ParameterError
from vehdyn.params import Vehicle

__all__ = ["steady_state_crosswind_yaw_rate", "optional_wind_input"]


def _vehicle(vehicle) -> Vehicle:
    if not isinstance(vehicle, Vehicle):
        raise ParameterError(f"vehicle must be a vehdyn Vehicle, got {type(vehicle).__name__}", key="vehicle",
                             value=vehicle)
    return vehicle


def optional_wind_input(crosswind: bool, B, D, inputs, phenomena):
    """A linear model's wind input (the last column of B and D): named and kept, or dropped.

    Parameters
    ----------
    crosswind : bool
        Keep the wind input.
    B, D : ndarray
        Input and feedthrough matrices whose last column is the response to the lateral wind
        w [m/s] (per unit w: [1/s, (m/s^2)/(m/s), ...] as the states and outputs need).
    inputs : sequence of Signal
        The model's other inputs (those of the other columns).
    phenomena : set of str
        The model's phenomena.

    Returns
    -------
    B, D : ndarray
        With the wind column, or without it when ``crosswind`` is false.
    inputs : tuple of Signal
        With ``wind_velocity_lateral`` [m/s] appended when ``crosswind`` is true.
    phenomena : set of str
        With ``"aero"`` added when ``crosswind`` is true.
    """
    from vehdyn.signals import Signal

    if not crosswind:
        return B[:, :-1], D[:, :-1], tuple(inputs), set(phenomena)
    wind = Signal("wind_velocity_lateral", "m/s", "lateral wind: the air's velocity along the vehicle's y axis "
                                                  "(toward +y)")
    return B, D, tuple(inputs) + (wind,), set(phenomena) | {"aero"}


def steady_state_crosswind_yaw_rate(vehicle_or_bicycle, speed, side_force, centre_of_pressure):
    """Steady yaw rate [rad/s] of the linear bicycle under a side force at a point, steer held at 0.

    r = F u (C_f + C_r) (x_p - x_n) / (C_f C_r L (L + K u^2)) (module docstring; solve the bicycle's
    two equilibrium equations with F_y = F at x_p). Positive (turning right, downwind for a wind
    toward +y) when the force acts ahead of the neutral steer point x_n.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (see :func:`~vehdyn.handling.bicycle_parameters`).
    speed : float or array_like
        Forward speed u [m/s], > 0.
    side_force : float or array_like
        F [N] (SAE y: positive toward the right).
    centre_of_pressure : float or array_like
        x_p [m] ahead of the CG (negative: behind it).

    Returns
    -------
    float or ndarray
        r [rad/s] (SAE: positive turning right).

    References
    ----------
    .. [1] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 3.2 (the
       aerodynamic side force and the vehicle's response to it).
    .. [2] W.-H. Hucho (ed.), *Aerodynamics of Road Vehicles*, 4th ed., SAE, 1998, sec. 4.4.
    """
    from vehdyn.handling.bicycle import bicycle_parameters, check_speed
    from vehdyn.handling.steady_state import neutral_steer_point

    p = bicycle_parameters(vehicle_or_bicycle)
    u = check_speed(speed)
    cf, cr, L = p.front_cornering_stiffness, p.rear_cornering_stiffness, p.wheelbase
    x_n = -neutral_steer_point(p).behind_cg
    return side_force * u * (cf + cr) * (centre_of_pressure - x_n) / (cf * cr * L * (L + p.understeer_gradient * u**2))


