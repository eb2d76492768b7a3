"""Magic Formula rolling radius, vertical model, contact patch and carcass stiffness.

MF 6.1/6.2: Besselink, Schmeitz, Pacejka, "An improved Magic Formula/Swift tyre model that can
handle inflation pressure changes", Vehicle System Dynamics 48 (2010) sup1, eqs. 1–19 (free and
effective rolling radius, vertical stiffness, contact patch, relaxation lengths) and Pacejka
(2012) eq. A3.3; MF 6.2: the MF-Tyre/MF-Swift 6.2 equation manual (loaded radius as the root of
Fz(Rl)); MF 5.2: the MF-Tyre 5.2 manual (contact length, relaxation lengths). Implemented as
MFeval 4.3.1 does, including its iteration rules. Like :mod:`~vehdyn.tire.mf_forces`, every
function takes ``xp`` (numpy or the float namespace of :mod:`vehdyn.tire._mf_ops`).
"""

from __future__ import annotations

import math
import sys

__all__ = [
    "rolling_radius",
    "loaded_radius_mf61",
    "loaded_radius_mf62",
    "contact_patch",
    "carcass_stiffness",
]

_EPS = sys.float_info.epsilon
_RADIUS_TOLERANCE = 1e-9  # [m], MFeval's convergence test on Re


def _free_radius(c, omega):
    """Free rolling radius R_omega [m] with centrifugal growth (Besselink 2010 eq. 1)."""
    r0 = c.UNLOADED_RADIUS
    return r0 * (c.Q_RE0 + c.Q_V1 * ((omega * r0) / c.LONGVL) ** 2)


def rolling_radius(xp, c, fz, kappa, vx, dpi, omega, omega_given):
    r"""Effective rolling radius Re, free radius R_omega and wheel spin omega.

    .. math::

        R_e = R_\Omega - \frac{F_{z0}}{C_z} \left(D_{reff} \arctan\left(B_{reff}
        \frac{F_z}{F_{z0}}\right) + F_{reff} \frac{F_z}{F_{z0}}\right), \qquad
        R_\Omega = R_0 \left(q_{re0} + q_{V1} \left(\frac{\Omega R_0}{V_0}\right)^2\right)

    Re = R_omega - Fz0/Cz*(DREFF*atan(BREFF*Fz/Fz0) + FREFF*Fz/Fz0) (Besselink 2010 eq. 7),
    Cz = VERTICAL_STIFFNESS*(1 + PFZ1*dpi). Without a measured spin, omega = (1 + kappa)*vx/Re
    (book eq. 2.5) is found by fixed-point iteration from Re = 0.965*R0, each point iterated until
    its own Re changes by less than 1e-9 m (MFeval's rule applied per point; MFeval stops the
    whole batch when any point converges, see the reference README). With a given omega, MFeval
    adds eps to it (to avoid R_omega = 0); so does this function.

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    fz : float or ndarray
        Load [N] (negative already set to 0, not clamped).
    kappa : float or ndarray
        Input slip ratio [-].
    vx : float or ndarray
        Forward speed [m/s].
    dpi : float or ndarray
        Relative pressure change [-] (eq. 4.E2b).
    omega : float or ndarray
        Wheel spin [rad/s], used if ``omega_given``, else estimated.
    omega_given : bool
        Whether ``omega`` is measured (one flag for the whole call).

    Returns
    -------
    re, r_omega, omega : float or ndarray
        Effective rolling radius [m], free rolling radius [m], wheel spin [rad/s]; ``re`` is NaN
        at points a compiled loop has not converged (its caller finishes them).

    References
    ----------
    .. [1] I. J. M. Besselink, A. J. C. Schmeitz and H. B. Pacejka, "An improved Magic
       Formula/Swift tyre model that can handle inflation pressure changes", Vehicle System
       Dynamics 48 (sup1), 337-352, 2010, eqs. 1 and 7.
    .. [2] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, eq. 2.5.
    """
    cz = c.VERTICAL_STIFFNESS * (1 + c.PFZ1 * dpi)
    deflection_term = (c.FNOMIN / cz) * (c.DREFF * xp.atan(c.BREFF * (fz / c.FNOMIN))
                                         + c.FREFF * (fz / c.FNOMIN))
    if omega_given:
        spin = omega + _EPS
        r_omega = _free_radius(c, spin)
        return r_omega - deflection_term, r_omega, spin
    points = (fz, kappa, vx, dpi)
    re = xp.full_broadcast(c.UNLOADED_RADIUS * 0.965, points)
    re_old = xp.full_broadcast(c.UNLOADED_RADIUS, points)
    omega = xp.full_broadcast(0.0, points)
    r_omega = xp.full_broadcast(_free_radius(c, 0.0), points)
    speed = kappa * vx + vx
    active = xp.abs(re_old - re) > _RADIUS_TOLERANCE
    # at most MFeval's 100 steps; a compiled vectorized loop (xp.iterate_to_convergence False) takes fewer
    for _ in range(xp.radius_iterations):
        if not xp.any(active):
            break
        omega_new = speed / re
        r_omega_new = _free_radius(c, omega_new)
        re_new = r_omega_new - deflection_term
        if xp.all(active):
            re_old, omega, r_omega, re = re, omega_new, r_omega_new, re_new
        else:  # points that have converged keep their values (MFeval's single-point result)
            re_old = xp.where(active, re, re_old)
            omega = xp.where(active, omega_new, omega)
            r_omega = xp.where(active, r_omega_new, r_omega)
            re = xp.where(active, re_new, re)
        active = xp.abs(re_old - re) > _RADIUS_TOLERANCE
    if not xp.iterate_to_convergence:  # NaN: not converged yet, the caller finishes the point
        re = xp.where(active, math.nan, re)
    return re, r_omega, omega


def loaded_radius_mf61(xp, c, fz, fx, fy, dpi, omega, r_omega):
    """Deflection rho, loaded radius Rl and vertical stiffness Fz/rho, MF 6.1 / 5.2.

    Solves Fz = (Q_FZ1*rho/R0 + Q_FZ2*(rho/R0)^2)*(1 + Q_V2*R0/V0*|omega| - (Q_FCX*Fx/Fz0)^2
    - (Q_FCY*Fy/Fz0)^2)*(1 + PFZ1*dpi)*Fz0 (Pacejka 2012 eq. A3.3) for rho, with
    Q_FZ1 = sqrt((Cz0*R0/Fz0)^2 - 4*Q_FZ2); Rl = R_omega - rho. ``fz`` is the load raised to FZMIN
    (limit mode). At fz = 0 rho is reported as 1e-6 m (MFeval's guard against 0/0 in Fz/rho);
    where a positive load is so small that rho underflows to 0, Cz is the slope at rho = 0.

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    fz : float or ndarray
        Load [N] (raised to FZMIN in limit mode).
    fx, fy : float or ndarray
        Combined-slip forces [N].
    dpi : float or ndarray
        Relative pressure change [-].
    omega : float or ndarray
        Wheel spin [rad/s].
    r_omega : float or ndarray
        Free rolling radius [m] (:func:`rolling_radius`).

    Returns
    -------
    rho, loaded_radius, stiffness : float or ndarray
        Deflection [m], loaded radius [m], vertical stiffness Fz/rho [N/m].

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, eq. A3.3.
    """
    r0, fz0 = c.UNLOADED_RADIUS, c.FNOMIN
    q_fz1 = math.sqrt((c.VERTICAL_STIFFNESS * r0 / fz0) ** 2 - 4 * c.Q_FZ2)
    external = (1 + c.Q_V2 * (r0 / c.LONGVL) * xp.abs(omega) - (c.Q_FCX * fx / fz0) ** 2
                - (c.Q_FCY * fy / fz0) ** 2) * (1 + c.PFZ1 * dpi) * fz0
    a, b, cc = c.Q_FZ2, q_fz1, -(fz / external)
    if a != 0:
        x = (-b + xp.sqrt(b**2 - 4 * a * cc)) / (2 * a)
    else:  # linear load-deflection law (MFeval would divide by zero)
        x = -cc / b
    rho_free = xp.fmax(x * r0, 0.0)
    loaded = xp.fmax(r_omega - rho_free, 0.0)
    rho = xp.where(fz == 0, 1e-6, rho_free)
    # a load so small that rho underflows to 0: the stiffness is the slope at rho = 0
    stiffness = xp.where(rho > 0, xp.div_ieee(fz, rho), q_fz1 * external / r0)
    return rho, loaded, stiffness


def _load_mf62(xp, c, gamma, omega, r_omega, dpi, radius, fx, fy):
    """Vertical load [N] and deflection [m] at a given loaded radius (MF 6.2 manual)."""
    r0, fz0 = c.UNLOADED_RADIUS, c.FNOMIN
    q_fz1 = math.sqrt((c.VERTICAL_STIFFNESS * r0 / fz0) ** 2 - 4 * c.Q_FZ2)
    ratio = radius / r_omega
    camber_shift = (c.Q_FYS1 + c.Q_FYS2 * ratio + c.Q_FYS3 * ratio**2) * gamma
    rho_free = xp.fmax(r_omega - radius, 0.0)
    tread_width = (1.075 - 0.5 * c.ASPECT_RATIO) * c.WIDTH
    rho_gamma = xp.div_ieee(((c.Q_CAM1 * radius + c.Q_CAM2 * radius**2) * gamma) ** 2 * (tread_width / 8)
                            * xp.abs(xp.tan(gamma)), ((c.Q_CAM1 * r_omega + c.Q_CAM2 * r_omega**2) * gamma) ** 2) \
        - (c.Q_CAM3 * rho_free * xp.abs(gamma))
    rho_gamma = xp.where(xp.isnan(rho_gamma), 0.0, rho_gamma)
    rho = xp.fmax(rho_free + rho_gamma, 1e-12)
    correction = (1 + c.Q_V2 * (r0 / c.LONGVL) * xp.abs(omega) - ((c.Q_FCX * fx) / fz0) ** 2
                  - (xp.pow(rho / r0, c.Q_FCY2) * (c.Q_FCY * (fy - camber_shift) / fz0)) ** 2) * (1 + c.PFZ1 * dpi)
    return correction * (q_fz1 * (rho / r0) + c.Q_FZ2 * (rho / r0) ** 2) * fz0, rho


def loaded_radius_mf62(xp, c, fz, fz_clamped, gamma, fx, fy, dpi, omega, r_omega):
    """Deflection, loaded radius and vertical stiffness of MF 6.2.

    The loaded radius is the root of Fz(Rl) = fz (MF 6.2 manual), found with MFeval's secant
    iteration (start 0.95*R0 and R0, at most 18 updates, tolerance FNOMIN*1e-6 N per point).
    Where the equation has no root (MFeval returns Rl = NaN, rho = 1e-12 m, Cz = 1e16 N/m), the
    three outputs are NaN here. The stiffness is fz_clamped/rho (MFeval: the FZMAX-clamped load).

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    fz : float or ndarray
        Load [N] to match.
    fz_clamped : float or ndarray
        The FZMAX-clamped load [N].
    gamma : float or ndarray
        Inclination angle [rad].
    fx, fy : float or ndarray
        Combined-slip forces [N].
    dpi : float or ndarray
        Relative pressure change [-].
    omega : float or ndarray
        Wheel spin [rad/s].
    r_omega : float or ndarray
        Free rolling radius [m].

    Returns
    -------
    rho, loaded_radius, stiffness : float or ndarray
        Deflection [m], loaded radius [m], vertical stiffness [N/m]; NaN without a root (and
        from a compiled vectorized loop, whose caller iterates the point).

    References
    ----------
    .. [1] TNO Automotive, *MF-Tyre/MF-Swift 6.2 Equation Manual* (the loaded radius).
    """
    if not xp.iterate_to_convergence:  # a compiled vectorized loop: the caller iterates the point (NaN)
        return math.nan, math.nan, math.nan
    points = (fz, gamma, fx, fy, dpi, omega, r_omega)
    r0, not_converged = xp.full_broadcast(c.UNLOADED_RADIUS, points), xp.full_broadcast(True, points)
    tolerance = c.FNOMIN * 1e-6

    def residual(radius):
        return _load_mf62(xp, c, gamma, omega, r_omega, dpi, radius, fx, fy)[0] - fz

    x0, x1 = r0 * 0.95, r0
    y0, y1 = residual(x0), residual(x1)
    x, y = x1, y1
    for _ in range(3, 21):
        trial = x1 - xp.div_ieee(x1 - x0, y1 - y0) * y1
        x = xp.where(not_converged, trial, x)
        y = residual(x)
        not_converged = not_converged & (xp.abs(y) > tolerance)
        if not xp.any(not_converged):
            break
        better = xp.abs(y1) < xp.abs(y0)
        x0 = xp.where(better, x1, x0)
        y0 = xp.where(better, y1, y0)
        x1, y1 = x, y
    loaded = x
    _, rho = _load_mf62(xp, c, gamma, omega, r_omega, dpi, loaded, fx, fy)
    rho = xp.where(fz_clamped == 0, 1e-6, rho)
    stiffness = fz_clamped / rho
    failed = xp.isnan(loaded) | (xp.abs(loaded) == math.inf) | (xp.abs(y) > tolerance) | xp.isnan(y)
    nan = math.nan
    return xp.where(failed, nan, rho), xp.where(failed, nan, loaded), xp.where(failed, nan, stiffness)


def contact_patch(xp, c, fz, dpi):
    """Contact patch half length a [m] and half width b [m].

    MF 6.x: a = R0*(Q_RA2*Fz/(Cz*R0) + Q_RA1*sqrt(Fz/(Cz*R0))), b = W*(Q_RB2*Fz/(Cz*R0) +
    Q_RB1*(Fz/(Cz*R0))^(1/3)) (Besselink 2010 eqs. 9, 10); MF 5.2: a = R0*(Q_A2*Fz/Fz0 +
    Q_A1*sqrt(Fz/Fz0)), b = W/2, with MFeval's empirical Q_A1, Q_A2 when both are 0. The load is
    limited to the bottoming load (R0 - RIM_RADIUS - BOTTOM_OFFST)*Cz (MFeval).

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    fz : float or ndarray
        Load [N].
    dpi : float or ndarray
        Relative pressure change [-].

    Returns
    -------
    a, b : float or ndarray
        Half length and half width of the contact patch [m].

    References
    ----------
    .. [1] I. J. M. Besselink, A. J. C. Schmeitz and H. B. Pacejka, "An improved Magic
       Formula/Swift tyre model that can handle inflation pressure changes", Vehicle System
       Dynamics 48 (sup1), 337-352, 2010, eqs. 9, 10.
    .. [2] TNO Automotive, *MF-Tyre User Manual*, version 5.2, 2001.
    """
    r0, width, fz0 = c.UNLOADED_RADIUS, c.WIDTH, c.FNOMIN
    cz = c.VERTICAL_STIFFNESS * (1 + c.PFZ1 * dpi)
    bottoming = (r0 - fz / cz) - (c.RIM_RADIUS + c.BOTTOM_OFFST) < 0
    fz = xp.where(bottoming, (r0 - c.RIM_RADIUS - c.BOTTOM_OFFST) * cz, fz)
    if c.is_mf52:
        q_a1, q_a2 = c.Q_A1, c.Q_A2
        if q_a1 == 0 and q_a2 == 0:
            y = math.log10(r0 * (c.VERTICAL_STIFFNESS / fz0))
            q_a1 = -0.0388 * y**3 + 0.2509 * y**2 + -0.6283 * y + 0.6279
            q_a2 = 1.693 * q_a1**2
        a = r0 * (q_a2 * (fz / fz0) + q_a1 * xp.sqrt(fz / fz0))
        b = width / 2 + 0.0 * a
    else:
        load = fz / (cz * r0)
        a = r0 * (c.Q_RA2 * load + c.Q_RA1 * xp.sqrt(load))
        b = width * (c.Q_RB2 * load + c.Q_RB1 * xp.pow(load, 1 / 3))
    return a, b


def carcass_stiffness(xp, c, fz, gamma, dpi, kxk, kya):
    """Carcass stiffnesses Cx, Cy [N/m] and relaxation lengths sigma_x, sigma_y [m].

    Cx = cx0*(1 + PCFX1*dfz + PCFX2*dfz^2)*(1 + PCFX3*dpi), Cy likewise (Besselink 2010 eqs. 17,
    18); MF 6.x: sigma = |K/C| (eq. 19); MF 5.2: sigma_x = (PTX1 + PTX2*dfz)*exp(-PTX3*dfz)*
    LSGKP*R0*Fz/Fz0, sigma_y = PTY1*sin(2*atan(Fz/(PTY2*Fz0')))*(1 - PKY3*|gamma|)*R0*LFZO*LSGAL
    (MF-Tyre 5.2 manual).

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    fz : float or ndarray
        Load [N].
    gamma : float or ndarray
        Inclination angle [rad].
    dpi : float or ndarray
        Relative pressure change [-].
    kxk : float or ndarray
        Longitudinal slip stiffness [N].
    kya : float or ndarray
        Cornering stiffness [N/rad].

    Returns
    -------
    cx, cy, sigma_x, sigma_y : float or ndarray
        Longitudinal and lateral carcass stiffness [N/m], relaxation lengths [m].

    References
    ----------
    .. [1] I. J. M. Besselink, A. J. C. Schmeitz and H. B. Pacejka, "An improved Magic
       Formula/Swift tyre model that can handle inflation pressure changes", Vehicle System
       Dynamics 48 (sup1), 337-352, 2010, eqs. 17-19.
    .. [2] TNO Automotive, *MF-Tyre User Manual*, version 5.2, 2001.
    """
    dfz = (fz - c.Fz0_prime) / c.Fz0_prime
    cx = c.LONGITUDINAL_STIFFNESS * (1 + c.PCFX1 * dfz + c.PCFX2 * dfz**2) * (1 + c.PCFX3 * dpi)
    cy = c.LATERAL_STIFFNESS * (1 + c.PCFY1 * dfz + c.PCFY2 * dfz**2) * (1 + c.PCFY3 * dpi)
    if c.is_mf52:
        r0 = c.UNLOADED_RADIUS
        sigma_x = (c.PTX1 + c.PTX2 * dfz) * xp.exp(-c.PTX3 * dfz) * c.LSGKP * r0 * fz / c.FNOMIN
        sigma_y = c.PTY1 * xp.sin(2 * xp.atan(xp.div_ieee(fz, c.PTY2 * c.Fz0_prime))) \
            * (1 - c.PKY3 * xp.abs(gamma)) * r0 * c.LFZO * c.LSGAL
    else:
        sigma_x = xp.abs(xp.div_ieee(kxk, cx))
        sigma_y = xp.abs(xp.div_ieee(kya, cy))
    return cx, cy, sigma_x, sigma_y
