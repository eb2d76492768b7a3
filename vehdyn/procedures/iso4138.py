"""ISO 4138:2012 steady-state circular driving: the constant-radius test (sec. 6.2).

The steady state on a circle of given radius with growing speed, from
:func:`~vehdyn.handling.nonlinear_handling_diagram`.
"""

from __future__ import annotations
import numpy as np

__all__ = ["constant_radius_test"]


def constant_radius_test(model, radius: float, *, driven_axle: str = "rear", step: float = 0.25):
    """ISO 4138 constant-radius test of a SingleTrack model: steady turns on ``radius`` [m] to the limit.

    Parameters
    ----------
    model : SingleTrack
    radius : float
        Circle radius [m], > 0.
    driven_axle : {"rear", "front"}
    step : float
        Lateral-acceleration step of the continuation [m/s^2] (halved near the limit), at least its
        resolution 0.01 m/s^2.

    Returns
    -------
    pandas.DataFrame
        Indexed by lateral acceleration [m/s^2]: steer angle, sideslip, speed and the understeer
        gradient d(delta)/d(a_y) [rad/(m/s^2)] (on a constant radius the kinematic steer L/R is
        constant, so the whole slope is understeer; ISO 4138 sec. 8).
    """
    from vehdyn.handling.nonlinear_steady_state import nonlinear_handling_diagram
    from vehdyn.params.checks import finite_number

    radius = finite_number(radius, "radius", positive=True)
    diagram = nonlinear_handling_diagram(model, radius=radius, driven_axle=driven_axle, step=step)
    frame = diagram.to_frame()
    frame["understeer_gradient"] = np.gradient(diagram.steer_angle, diagram.lateral_acceleration) \
        if diagram.steer_angle.size > 1 else np.nan
    frame.attrs["units"]["understeer_gradient"] = "rad/(m/s^2)"
    frame.attrs["limit_lateral_acceleration"] = diagram.limit_lateral_acceleration
    return frame
