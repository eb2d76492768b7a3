r"""The steady roll of a vehicle on its springs, anti-roll bars, roll centres and tires, in closed form.

One source for the roll gradient and the per-axle lateral load transfer that
:class:`~vehdyn.full_vehicle.FullVehicle` reaches in a steady turn (its tests hold it to this
closed form term by term) and that the understeer budget (:func:`vehdyn.handling.understeer_budget`)
reads for its roll-steer, camber and load-transfer rows.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.units import GRAVITY

__all__ = ["SteadyRoll", "steady_roll", "unsprung_cg_height"]


def unsprung_cg_height(vehicle) -> float:
    """Height h_u of the unsprung masses' CG that makes the file's total CG height: m h = m_s h_s + m_u h_u.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle (``mass.cg_height``, ``mass.sprung_cg_height``, the masses).

    Returns
    -------
    float
        h_u [m] (the full vehicle's wheel-centre height above the ground).

    Raises
    ------
    ParameterError
        If the vehicle has no unsprung mass, or h_u is outside (0, h_s).
    """
    m = vehicle.mass
    if m.unsprung_mass <= 0:
        raise ParameterError("the unsprung CG height needs unsprung masses > 0, got mass.front_unsprung_mass + "
                             f"mass.rear_unsprung_mass = {m.unsprung_mass} kg", key="mass.front_unsprung_mass",
                             value=m.front_unsprung_mass)
    sprung = m.mass - m.unsprung_mass
    h_u = (m.mass * m.cg_height - sprung * m.sprung_cg_height) / m.unsprung_mass
    if not 0.0 < h_u < m.sprung_cg_height:
        raise ParameterError(f"mass.cg_height = {m.cg_height} m puts the unsprung masses at {h_u:.4g} m "
                             f"(from m h = m_s h_s + m_u h_u), outside (0, mass.sprung_cg_height = "
                             f"{m.sprung_cg_height} m)", key="mass.cg_height", value=m.cg_height)
    return float(h_u)


@dataclasses.dataclass(frozen=True)
class SteadyRoll:
    """The steady roll of :func:`steady_roll` and its terms (magnitudes per unit lateral acceleration).

    Parameters
    ----------
    roll_gradient : float
        phi / a_y of the body (out of the turn) [rad/(m/s^2)].
    load_transfer : tuple of float
        (front, rear) Delta N_i / a_y, Delta N_i = (N_outer - N_inner) / 2 of one axle [N/(m/s^2)].
    suspension_roll_gradient, tire_roll_gradient : tuple of float
        (front, rear) phi_si / a_y, the body's roll on the axle's springs, and phi_ti / a_y, the
        axle's roll on its tires; phi = phi_si + phi_ti [rad/(m/s^2)].
    sprung_moment : float
        sum_i m_si (h_s - h_i) [kg*m].
    unsprung_spring_moment : float
        sum_i m_ui (1 - lambda_i) h_u, the unsprung masses' moment through the springs [kg*m].
    tire_roll_moment : float
        sum_i u_i G_i, the transfer that bypasses the springs rolling the axles on their tires [kg*m].
    series_roll_stiffness : float
        K_ser = sum_i K_i K_ti / (K_i + K_ti) [N*m/rad].
    gravity_stiffness : float
        g M, the gravity moment's loss of roll stiffness [N*m/rad].
    elastic_transfer, geometric_transfer, unsprung_transfer : tuple of float
        (front, rear) parts of Delta N_i / a_y: through the springs and bars, K_i phi_si / (T_i a_y);
        through the links, m_si h_i (1 + g phi / a_y) / T_i; the unsprung masses' direct part,
        m_ui lambda_i h_u (1 + g phi / a_y) / T_i [N/(m/s^2)].
    gravity : float
        g [m/s^2].
    """

    roll_gradient: float
    load_transfer: tuple
    suspension_roll_gradient: tuple
    tire_roll_gradient: tuple
    sprung_moment: float
    unsprung_spring_moment: float
    tire_roll_moment: float
    series_roll_stiffness: float
    gravity_stiffness: float
    elastic_transfer: tuple
    geometric_transfer: tuple
    unsprung_transfer: tuple
    gravity: float

    @property
    def roll_gradient_deg_per_g(self) -> float:
        """Roll gradient [deg/g]."""
        return float(np.rad2deg(self.roll_gradient * self.gravity))


def steady_roll(vehicle, *, gravity: float = GRAVITY, tire_compliance: bool = True) -> SteadyRoll:
    r"""Steady roll gradient and per-axle lateral load transfer, closed form (linear, small angles).

    Per axle i (front, rear): track T_i, roll-centre height h_i, suspension roll stiffness
    K_i = k_s,i T_i^2 / 2 + K_arb,i (springs and bar), tire roll stiffness K_ti = k_t T_i^2 / 2,
    mass carried m_i (m b / L, m a / L), unsprung m_ui, sprung m_si = m_i - m_ui, the unsprung
    masses' CG height h_u (:func:`unsprung_cg_height`) and lambda_i, the share of their lateral
    inertia's moment about the roll centre that the tires take directly
    (``suspension.*_unsprung_transfer_fraction``). With A = a_y + g phi (the lateral acceleration
    plus the body-y component of gravity of everything that leans with the body), the body's moment
    about the roll centres, the tire loads and the tires' deflection read

    .. math::

        \sum_i K_i \phi_{si} &= B A, \qquad
            B = \sum_i \left[ m_{si} (h_s - h_i) + m_{ui} (1 - \lambda_i) h_u \right] \\
        \Delta N_i T_i &= K_i \phi_{si} + G_i A, \qquad G_i = m_{si} h_i + m_{ui} \lambda_i h_u \\
        \phi &= \phi_{si} + \phi_{ti}, \qquad K_{ti} \phi_{ti} = \Delta N_i T_i

    whose solution is

    .. math::

        \frac{\phi}{a_y} = \frac{M}{K_{ser} - g M}, \qquad
        M = B + \sum_i u_i G_i, \quad u_i = \frac{K_i}{K_i + K_{ti}}, \quad
        K_{ser} = \sum_i \frac{K_i K_{ti}}{K_i + K_{ti}} \\
        \Delta N_i T_i = \frac{K_i K_{ti}}{K_i + K_{ti}} \phi + (1 - u_i) G_i A

    Terms: the sprung moment m_si (h_s - h_i); the unsprung masses' moment through the springs
    m_ui (1 - lambda_i) h_u; the tire compliance (K_ser, and u_i G_i: the axles roll on their tires
    under the transfer that bypasses the springs); the gravity moment g M; the roll centres h_i
    (geometric transfer m_si h_i). With lambda_i = 1 (the textbook) and rigid tires it is the
    familiar m_s h' / (K_phi - m_s g h') with h' the sprung CG's height over the roll axis.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle (masses, CG heights, tracks, roll centres, springs, bars, tire vertical
        stiffness, unsprung transfer fractions).
    gravity : float, optional
        g [m/s^2].
    tire_compliance : bool, optional
        False: rigid tires (the limit K_ti -> infinity: u_i = 0, K_ser = K_f + K_r).

    Returns
    -------
    SteadyRoll
        The roll gradient, the per-axle transfers and every term.

    Raises
    ------
    ParameterError
        If the vehicle rolls over on its springs (K_ser <= g M: no steady roll), or has no unsprung
        mass (:func:`unsprung_cg_height`).

    References
    ----------
    .. [1] Milliken, W. F. and Milliken, D. L., *Race Car Vehicle Dynamics*, SAE, 1995, ch. 18
       (lateral load transfer of an axle: elastic, geometric and unsprung parts).
    .. [2] Gillespie, T. D., *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 7 (suspension roll,
       roll gradient with the roll axis).

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.handling import steady_roll
    >>> round(steady_roll(vehdyn.load_vehicle("sedan")).roll_gradient, 4)
    0.0158
    """
    m, G, s = vehicle.mass, vehicle.geometry, vehicle.suspension
    L = G.wheelbase
    h_u = unsprung_cg_height(vehicle)
    h_s = m.sprung_cg_height
    m_i = (m.mass * G.b / L, m.mass * G.a / L)
    m_u = (m.front_unsprung_mass, m.rear_unsprung_mass)
    m_s = (m_i[0] - m_u[0], m_i[1] - m_u[1])
    T = (G.front_track, G.rear_track)
    K = (vehicle.front_roll_stiffness, vehicle.rear_roll_stiffness)
    h = (G.front_roll_centre_height, G.rear_roll_centre_height)
    lam = (s.front_unsprung_transfer_fraction, s.rear_unsprung_transfer_fraction)
    kt = vehicle.tires.vertical_stiffness
    if tire_compliance:
        Kt = tuple(kt * t * t / 2 for t in T)
        u = tuple(k / (k + k_t) for k, k_t in zip(K, Kt))
        K_ser = sum(k * k_t / (k + k_t) for k, k_t in zip(K, Kt))
    else:
        u, K_ser = (0.0, 0.0), sum(K)  # the limit K_ti -> infinity
    sprung = sum(ms * (h_s - hi) for ms, hi in zip(m_s, h))
    unsprung_spring = sum(mu * (1.0 - li) * h_u for mu, li in zip(m_u, lam))
    Gi = tuple(ms * hi + mu * li * h_u for ms, mu, hi, li in zip(m_s, m_u, h, lam))
    tire_moment = sum(ui * gi for ui, gi in zip(u, Gi))
    M = sprung + unsprung_spring + tire_moment
    if K_ser <= gravity * M:
        raise ParameterError(f"the roll stiffness in series with the tires, {K_ser:.6g} N*m/rad, does not exceed the "
                             f"gravity moment g M = {gravity * M:.6g} N*m/rad: the vehicle has no steady roll "
                             f"(suspension.front_spring_rate = {s.front_spring_rate} N/m)",
                             key="suspension.front_spring_rate", value=s.front_spring_rate)
    phi = M / (K_ser - gravity * M)
    A = 1.0 + gravity * phi
    # the body's roll on each axle's springs: phi_si = (K_ti phi - G_i A) / (K_i + K_ti)
    if tire_compliance:
        phi_s = tuple((k_t * phi - gi * A) / (k + k_t) for k, k_t, gi in zip(K, Kt, Gi))
    else:
        phi_s = (phi, phi)
    elastic = tuple(k * ps / t for k, ps, t in zip(K, phi_s, T))
    geometric = tuple(ms * hi * A / t for ms, hi, t in zip(m_s, h, T))
    unsprung = tuple(mu * li * h_u * A / t for mu, li, t in zip(m_u, lam, T))
    transfer = tuple(e + g_ + un for e, g_, un in zip(elastic, geometric, unsprung))
    return SteadyRoll(roll_gradient=float(phi), load_transfer=tuple(map(float, transfer)),
                      suspension_roll_gradient=tuple(map(float, phi_s)),
                      tire_roll_gradient=tuple(float(phi - p) for p in phi_s), sprung_moment=float(sprung),
                      unsprung_spring_moment=float(unsprung_spring), tire_roll_moment=float(tire_moment),
                      series_roll_stiffness=float(K_ser), gravity_stiffness=float(gravity * M),
                      elastic_transfer=tuple(map(float, elastic)), geometric_transfer=tuple(map(float, geometric)),
                      unsprung_transfer=tuple(map(float, unsprung)), gravity=float(gravity))
