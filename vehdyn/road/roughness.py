"""International Roughness Index (ASTM E1926; Sayers, Gillespie & Paterson, World Bank Technical
Paper 46, 1986)
    The golden-car quarter car (k_t/m_s = 653 s^-2, k_s/m_s = 63.3 s^-2, m_u/m_s = 0.15,
    c_s/m_s = 6.0 s^-1) at 80 km/h over the profile smoothed by a 250 mm moving average; IRI is the
    mean rectified suspension velocity divided by the speed (m/m), quoted in m/km. See :func:`iri`.

References
----------
.. [1] ASTM E1926-08, *Standard Practice for Computing International Roughness Index of Roads from
   Longitudinal Profile Measurements*, ASTM International.
.. [2] M. W. Sayers, T. D. Gillespie and W. D. O. Paterson, *Guidelines for Conducting and
   Calibrating Road Roughness Measurements*, World Bank Technical Paper 46, 1986.
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.checks import positive_number as _positive
from vehdyn.road.profile import RoadProfile

__all__ = ["GOLDEN_CAR", "golden_car", "iri"]


GOLDEN_CAR = {"tire_stiffness_ratio": 653.0, "spring_stiffness_ratio": 63.3, "mass_ratio": 0.15,
              "damping_ratio": 6.0, "speed": 80.0 / 3.6}
"""ASTM E1926 golden-car constants: k_t/m_s [1/s^2], k_s/m_s [1/s^2], m_u/m_s [-], c_s/m_s [1/s], speed [m/s]."""

_IRI_BASE_LENGTH = 0.25  # moving-average base length [m] (ASTM E1926)
_IRI_INIT_LENGTH = 11.0  # initialization length [m] (ASTM E1926; 0.5 s at 80 km/h)


def golden_car():
    r"""The IRI golden car per unit sprung mass as a :class:`~vehdyn.LinearModel` (ASTM E1926).

    States ``sprung_displacement``, ``unsprung_displacement`` [m], ``sprung_velocity``,
    ``unsprung_velocity`` [m/s]; input ``road_displacement`` [m]; output ``suspension_velocity``
    zs' - zu' [m/s]. With the ratios of :data:`GOLDEN_CAR` (sprung mass 1, no tire damping):

    .. math::

        \ddot z_s = -\frac{k_s}{m_s}(z_s - z_u) - \frac{c_s}{m_s}(\dot z_s - \dot z_u), \qquad
        \frac{m_u}{m_s}\ddot z_u = \frac{k_s}{m_s}(z_s - z_u) + \frac{c_s}{m_s}(\dot z_s - \dot z_u)
        - \frac{k_t}{m_s}(z_u - z_r)

    the quarter car of :class:`vehdyn.ride.QuarterCar` with these parameters (the tests hold the
    two to each other).

    Returns
    -------
    LinearModel
        The golden car (4 states, 1 input, 1 output).

    References
    ----------
    .. [1] ASTM E1926-08, sec. 8 (the golden-car equations and constants).
    """
    from vehdyn.model import LinearModel
    from vehdyn.signals import Signal

    g = GOLDEN_CAR
    k1, k2, mu, c = g["tire_stiffness_ratio"], g["spring_stiffness_ratio"], g["mass_ratio"], g["damping_ratio"]
    A = np.array([[0.0, 0.0, 1.0, 0.0],
                  [0.0, 0.0, 0.0, 1.0],
                  [-k2, k2, -c, c],
                  [k2 / mu, -(k1 + k2) / mu, c / mu, -c / mu]])
    B = np.array([[0.0], [0.0], [0.0], [k1 / mu]])
    C = np.array([[0.0, 0.0, 1.0, -1.0]])
    states = (Signal("sprung_displacement", "m", "golden car's sprung mass, up"),
              Signal("unsprung_displacement", "m", "golden car's unsprung mass, up"),
              Signal("sprung_velocity", "m/s", "golden car's sprung mass, up"),
              Signal("unsprung_velocity", "m/s", "golden car's unsprung mass, up"))
    return LinearModel(A, B, C, np.zeros((1, 1)), states=states,
                       inputs=(Signal("road_displacement", "m", "road elevation under the wheel, up"),),
                       outputs=(Signal("suspension_velocity", "m/s", "zs' - zu', rebound positive"),),
                       name="IRI golden car")


def iri(profile: RoadProfile | np.ndarray, spacing: float | None = None, *, smoothing: bool = True) -> float:
    r"""International Roughness Index [m/km] of a longitudinal profile (ASTM E1926).

    Parameters
    ----------
    profile : RoadProfile or array_like
        Elevation [m] on a uniform grid (then give ``spacing`` [m]).
    spacing : float, optional
        Sample spacing [m] for an array profile.
    smoothing : bool
        Apply the 250 mm moving average of the standard (for spacings below 0.25 m).

    Returns
    -------
    float
        IRI in m/km (= mm/m, the unit in which it is always reported; 1000 x the mean rectified
        slope in m/m).

    Notes
    -----
    The golden car (:func:`golden_car`) runs at 80 km/h over the smoothed profile, which is taken
    as linear between samples (the standard's constant-slope assumption; exact first-order-hold
    discretization). Initial state: both masses at the first elevation, both velocities V times the
    mean slope of the first 11 m. IRI = mean over the samples after the first of |zs' - zu'| / V:

    .. math::

        \mathrm{IRI} = \frac{1000}{N V} \sum_{k=1}^{N} |\dot z_s(t_k) - \dot z_u(t_k)| \quad [\text{m/km}]

    References
    ----------
    .. [1] ASTM E1926-08, *Standard Practice for Computing International Roughness Index of Roads
       from Longitudinal Profile Measurements*, ASTM International.
    .. [2] M. W. Sayers, T. D. Gillespie and W. D. O. Paterson, *Guidelines for Conducting and
       Calibrating Road Roughness Measurements*, World Bank Technical Paper 46, 1986.

    Examples
    --------
    The golden car is linear, so the IRI grows as the square root of Gd(n0): the profiles of
    classes A and C with the same phases differ by a factor sqrt(16) = 4.

    >>> from vehdyn.road import iri, synthesize_profile
    >>> smooth = iri(synthesize_profile("A", length=1000.0, spacing=0.25, seed=1))
    >>> rough = iri(synthesize_profile("C", length=1000.0, spacing=0.25, seed=1))
    >>> round(smooth, 2), round(rough / smooth, 9)                  # [m/km], [-]
    (2.16, 4.0)
    """
    from vehdyn.simulation import simulate

    if isinstance(profile, RoadProfile):
        z, dx = profile.elevation, profile.spacing
    else:
        z = np.asarray(profile, dtype=float)
        if spacing is None:
            raise ParameterError("spacing [m] is needed with an array profile", key="spacing", value=None)
        dx = _positive(spacing, "spacing")
        if z.ndim != 1 or not np.all(np.isfinite(z)):
            raise ParameterError("profile must be a 1-D array of finite elevations", key="profile", value=z.shape)
    if smoothing and dx < _IRI_BASE_LENGTH:
        k = max(1, int(round(_IRI_BASE_LENGTH / dx)))
        c = np.cumsum(np.concatenate([[0.0], z]))
        z = (c[k:] - c[:-k]) / k
    n_init = int(round(_IRI_INIT_LENGTH / dx))
    if z.size <= n_init + 1:
        raise ParameterError(f"profile of {z.size * dx:g} m is shorter than the {_IRI_INIT_LENGTH:g} m the IRI "
                             "initialization needs", key="profile", value=z.size * dx)
    V = GOLDEN_CAR["speed"]
    car = golden_car()
    v0 = V * (z[n_init] - z[0]) / (n_init * dx)
    x0 = {"sprung_displacement": z[0], "unsprung_displacement": z[0], "sprung_velocity": v0, "unsprung_velocity": v0}
    t = np.arange(z.size) * dx / V
    res = simulate(car, t, {"road_displacement": z}, x0=x0, method="exact", hold="foh")
    return float(1000.0 * np.mean(np.abs(res["suspension_velocity"][1:])) / V)
