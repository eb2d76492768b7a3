"""The Wong-Reece equations point by point with adaptive quadrature: a slow reference.

The textbook implementation of :mod:`~vehdyn.tire.terramechanics.wong_reece`: the stresses as
scalar functions of the angle written from the equations (the rear region's mapped angle computed
explicitly), integrated by ``scipy.integrate.quad`` on each side of theta_m, and the entry angle
found by ``scipy.optimize.brentq``, one slip at a time. The tests check the vectorized Gauss
quadrature against it and ``benchmarks/bench_terramechanics.py`` uses it as the baseline and the
error reference. scipy is imported on use.
"""

from __future__ import annotations

import math
import warnings

__all__ = ["stress_functions", "adaptive_integrals", "adaptive_solve"]


def stress_functions(wheel, theta1: float, slip: float):
    """The Wong-Reece stresses of a wheel as scalar functions of the angle, and their integral.

    Parameters
    ----------
    wheel : RigidWheel
        The wheel and its soil.
    theta1 : float
        Entry angle [rad].
    slip : float
        s [-] in [-1, 1].

    Returns
    -------
    sigma, tau : callable
        Normal and shear stress [Pa] at an angle theta [rad].
    integral : callable
        ``integral(f, epsrel=1e-12)``: the adaptive quadrature of f over the contact arc (split
        at theta_m).
    """
    from scipy.integrate import quad

    soil, r, b = wheel.soil, wheel.radius, wheel.width
    k = soil.k_c / b + soil.k_phi
    tan_phi = math.tan(soil.friction_angle)
    tm = min(max(wheel.c1 + wheel.c2 * slip, 0.0), 1.0) * theta1
    t2 = -wheel.rebound * theta1

    def sigma(t):
        e = t if t >= tm else theta1 - (t - t2) / (tm - t2) * (theta1 - tm)
        return k * (r * max(math.cos(e) - math.cos(theta1), 0.0)) ** soil.n

    def tau(t):
        if slip >= 0:
            j = r * ((theta1 - t) - (1 - slip) * (math.sin(theta1) - math.sin(t)))
        else:
            j = r * ((1 + slip) * (theta1 - t) - (math.sin(theta1) - math.sin(t)))
        return math.copysign((soil.cohesion + sigma(t) * tan_phi) * (1 - math.exp(-abs(j) / soil.shear_modulus)), j)

    def integral(f, epsrel=1e-12):
        pieces = [(t2, tm), (tm, theta1)] if tm > t2 else [(tm, theta1)]
        return sum(quad(f, a, c, epsabs=0, epsrel=epsrel, limit=200)[0] for a, c in pieces)

    return sigma, tau, integral


def adaptive_integrals(wheel, theta1: float, slip: float, epsrel: float = 1e-12):
    """The stress integrals of a wheel at one entry angle, by adaptive quadrature.

    Parameters
    ----------
    wheel : RigidWheel
        The wheel and its soil.
    theta1 : float
        Entry angle [rad].
    slip : float
        s [-].
    epsrel : float
        Relative tolerance of ``scipy.integrate.quad`` [-].

    Returns
    -------
    tuple of float
        ``(W, H, R, T)``: vertical load, thrust, motion resistance [N] and torque [N*m].
    """
    r, b = wheel.radius, wheel.width
    sigma, tau, integral = stress_functions(wheel, theta1, slip)
    return (r * b * integral(lambda t: sigma(t) * math.cos(t) + tau(t) * math.sin(t), epsrel),
            r * b * integral(lambda t: tau(t) * math.cos(t), epsrel),
            r * b * integral(lambda t: sigma(t) * math.sin(t), epsrel),
            r * r * b * integral(tau, epsrel))


def adaptive_solve(wheel, load: float, slip: float, epsrel: float = 1e-10):
    """Steady state of one (load, slip) by brentq on the entry angle: the slow reference.

    Parameters
    ----------
    wheel : RigidWheel
        The wheel and its soil.
    load : float
        Vertical load W [N].
    slip : float
        s [-].
    epsrel : float
        Relative tolerance of the quadrature [-].

    Returns
    -------
    tuple of float
        ``(sinkage [m], drawbar pull [N])``.

    Raises
    ------
    ParameterError
        For a load the soil cannot carry before the sinkage reaches the radius (the bracket of the
        root has no sign change: :meth:`RigidWheel.solve` reports such a wheel as stuck), and for a
        tolerance ``epsrel`` outside (0, 0.1].
    """
    from scipy.optimize import brentq

    from vehdyn.errors import ParameterError
    from vehdyn.params.checks import finite_number

    load = finite_number(load, "load", positive=True)
    epsrel = finite_number(epsrel, "epsrel", positive=True, maximum=0.1)
    with warnings.catch_warnings():  # quad's round-off notice near 1e-10 on the kinked integrands
        warnings.simplefilter("ignore")
        bracket = (1e-9, 0.5 * math.pi)
        if adaptive_integrals(wheel, bracket[1], slip, epsrel)[0] < load:
            raise ParameterError(f"load = {load!r} N is more than the soil carries before the sinkage reaches the "
                                 "radius: the wheel is stuck (RigidWheel.solve reports it so)", key="load", value=load)
        theta1 = brentq(lambda t: adaptive_integrals(wheel, t, slip, epsrel)[0] - load, *bracket, xtol=1e-13)
        _, thrust, resistance, _ = adaptive_integrals(wheel, theta1, slip, epsrel)
    return wheel.radius * (1 - math.cos(theta1)), thrust - resistance
