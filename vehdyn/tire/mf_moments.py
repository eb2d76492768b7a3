"""Magic Formula moments: overturning Mx, rolling resistance My, aligning Mz (MF 5.2, 6.1, 6.2).

Pacejka, *Tire and Vehicle Dynamics*, 3rd ed. (2012), eqs. 4.E31–4.E49 and 4.E68–4.E78, turn
slip 4.91–4.104, with the substitutions MFeval 4.3.1 makes to match TNO MF-Tyre (noted at each
equation): trail and residual-torque factors from Besselink et al. (2010) eqs. A54–A60, the MF 6.x
rolling resistance of eq. A48, the TNO overturning-moment formula, and the empirical rules for
loads below FZMIN and for rolling near standstill. ISO-W axes; see :mod:`vehdyn.tire.mf_forces`
for the state ``s``.
"""

from __future__ import annotations

import math
from collections import namedtuple

from vehdyn.tire._mf_ops import cos_atan, sign_nonzero
from vehdyn.tire.mf_forces import _EPSILON, lateral_pure

__all__ = ["overturning_moment", "rolling_resistance_moment", "aligning_moment"]

_TWO_OVER_PI = 2.0 / math.pi


def overturning_moment(xp, c, s, fy):
    """Overturning moment Mx (TNO MF-Tyre equation manual form of book eq. 4.E69).

    Below FZMIN the load is replaced by Fz*(Fz/FZMIN)^2 (MFeval). When both QSX1–QSX11 and
    QSX12–QSX14 are non-zero, MFeval uses eq. 49 of Besselink's draft paper, as here.

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    s : MFState
        The state of the evaluation (module docstring; :class:`vehdyn.tire.magic_formula.MFState`).
    fy : float or ndarray
        Combined-slip lateral force [N].

    Returns
    -------
    float or ndarray
        Mx [N*m].

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, eq. 4.E69.
    .. [2] TNO Automotive, *MF-Tyre/MF-Swift 6.2 Equation Manual*.
    """
    fz = s.fz
    if c.FZMIN > 0 and xp.any(fz < c.FZMIN):
        fz = xp.where(fz < c.FZMIN, fz * (fz / c.FZMIN) ** 2, fz)
    fz0, r0, gamma = c.FNOMIN, c.UNLOADED_RADIUS, s.gamma
    if c.mx_draft_form:
        return r0 * fz * c.LMX * (
            c.QSX1 * c.LVMX - c.QSX2 * gamma * (1 + c.PPMX1 * s.dpi) - c.QSX12 * gamma * xp.abs(gamma)
            + c.QSX3 * fy / fz0
            + c.QSX4 * xp.cos(c.QSX5 * xp.atan((c.QSX6 * fz / fz0) ** 2))
            * xp.sin(c.QSX7 * gamma + c.QSX8 * xp.atan(c.QSX9 * fy / fz0))
            + c.QSX10 * xp.atan(c.QSX11 * fz / fz0) * gamma
        ) + r0 * fy * c.LMX * (c.QSX13 + c.QSX14 * xp.abs(gamma))
    return r0 * fz * c.LMX * (
        c.QSX1 * c.LVMX - c.QSX2 * gamma * (1 + c.PPMX1 * s.dpi) + c.QSX3 * (fy / fz0)
        + c.QSX4 * xp.cos(c.QSX5 * xp.atan((c.QSX6 * (fz / fz0)) ** 2))
        * xp.sin(c.QSX7 * gamma + c.QSX8 * xp.atan(c.QSX9 * (fy / fz0)))
        + c.QSX10 * xp.atan(c.QSX11 * (fz / fz0)) * gamma
    ) + r0 * c.LMX * (fy * (c.QSX13 + c.QSX14 * xp.abs(gamma)) - fz * c.QSX12 * gamma * xp.abs(gamma))


def rolling_resistance_moment(xp, c, s, fx):
    """Rolling resistance moment My (MF 6.x: Besselink 2010 eq. A48; MF 5.2: MF-Tyre manual).

    Negative when rolling forwards (ISO-W). Uses the unclamped load (``s.fz_input``) reduced to
    Fz^2/FZMIN below FZMIN, the input speed and the input slip ratio. Near zero wheel speed
    (MFeval's empirical rule), with h = VXLOW/|vx| - 1 and l = -1 - VXLOW - h, My is multiplied
    by sin(pi/2*(kappa + 1)/(h + 1)) for l <= kappa <= h, flips sign for kappa < l, and is 0 at
    vx = 0; it flips sign for vx < 0.

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    s : MFState
        The state of the evaluation (module docstring; :class:`vehdyn.tire.magic_formula.MFState`).
    fx : float or ndarray
        Combined-slip longitudinal force [N].

    Returns
    -------
    float or ndarray
        My [N*m].

    References
    ----------
    .. [1] I. J. M. Besselink, A. J. C. Schmeitz and H. B. Pacejka, "An improved Magic
       Formula/Swift tyre model that can handle inflation pressure changes", Vehicle System
       Dynamics 48 (sup1), 337-352, 2010, eq. A48.
    .. [2] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, eq. 4.E70 (MF 5.2 form).
    """
    fz = s.fz_input
    if c.FZMIN > 0 and xp.any(fz < c.FZMIN):
        fz = xp.where(fz < c.FZMIN, fz * (fz / c.FZMIN), fz)
    vx, kappa = s.vx, s.kappa_input
    fz0, v0 = c.FNOMIN, c.LONGVL
    speed_terms = c.QSY1 + c.QSY2 * (fx / fz0) + c.QSY3 * xp.abs(vx / v0) + c.QSY4 * (vx / v0) ** 4
    if c.is_mf52:
        my = -c.UNLOADED_RADIUS * fz * c.LMY * speed_terms
    else:
        my = -c.UNLOADED_RADIUS * fz0 * c.LMY * (
            speed_terms + (c.QSY5 + c.QSY6 * (fz / fz0)) * s.gamma**2
        ) * (xp.pow(fz / fz0, c.QSY7) * xp.pow(s.pressure / c.NOMPRES, c.QSY8))
    my = my * s.reverse
    high = xp.div(c.VXLOW, xp.abs(vx)) - 1
    low = -1 - c.VXLOW - high
    in_ramp = (kappa >= low) & (kappa <= high)
    if xp.any(in_ramp):
        my = xp.where(in_ramp, my * xp.sin(((math.pi / 2) * (kappa + 1)) / (high + 1)), my)
    if xp.any(kappa < low):
        my = xp.where(kappa < low, -my, my)
    return xp.where(vx == 0, 0.0, my) if xp.any(vx == 0) else my


AligningMoment = namedtuple("AligningMoment", "mz trail residual")
AligningMoment.__doc__ = "Aligning moment Mz [N*m], pneumatic trail t [m] and residual torque Mzr [N*m]."


def aligning_moment(xp, c, s, pure, fy, fx, kxk, gyk, svyk):
    r"""Aligning moment of combined slip (book eqs. 4.E31–4.E49, 4.E71–4.E78; MFeval's forms).

    .. math::

        M_z = -t F_y' + M_{zr} + s F_x, \qquad
        t = D_t \cos[C_t \arctan\{B_t \alpha_{t,eq} - E_t (B_t \alpha_{t,eq}
        - \arctan B_t \alpha_{t,eq})\}] \cos\alpha', \qquad
        M_{zr} = D_r \cos[C_r \arctan B_r \alpha_{r,eq}]

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    s : MFState
        The state of the evaluation (module docstring; :class:`vehdyn.tire.magic_formula.MFState`).
    pure : LateralPure
        Pure lateral slip results at the actual camber.
    fy, fx : float or ndarray
        Combined-slip forces [N].
    kxk : float or ndarray
        Longitudinal slip stiffness [N].
    gyk : float or ndarray
        Combined-slip weighting Gyk [-].
    svyk : float or ndarray
        kappa-induced side force SVyk [N].

    Returns
    -------
    AligningMoment
        ``mz`` [N*m], ``trail`` t [m] and ``residual`` Mzr [N*m].

    Notes
    -----
    * The trail and residual torque use the load raised to FZMIN (limit mode), the trail peak Dt
      uses QDZ3*gamma (not |gamma|) and the slope Bt uses QBZ4, QBZ5 (Besselink 2010 A58, A60);
      the equivalent slip angles use tan (A54, A55) and the arm s uses FNOMIN (A56); t is scaled
      by LFZO (TNO). MF 6.x: Mz' = -t*Gyk*Fy0(gamma = 0); MF 5.2: Mz' = -t*(Fy - SVyk).
    * Turn slip: Cr = zeta7 = 2/pi*acos(Mzp90/|Drp|) (MF-Tyre manual). MFeval evaluates this as
      written, which gives NaN at phit = 0 (0/0), -Inf or NaN when the camber stiffness Kzgr0 is
      0 (x/0) and a complex value when the ratio exceeds 1. vehdyn takes the phit -> 0 limit of
      the ratio at phit = 0 and limits it to [-1, 1] (|ratio| > 1: Cr = 0, i.e. Mzr = Dr, or
      Cr = 2 where Gyk < 0), so Mz stays finite and continuous; wherever MFeval's value is finite
      and real, the two agree. Where the turn-slip factors DHyp or DDrp are 0 (vx = 0, no load)
      vehdyn uses their limits SHyp = 0 and Drp = 0, where MFeval's 0*Inf gives NaN.

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 4.3.2 (eqs. 4.E31-4.E49,
       4.E71-4.E78) and 4.3.3 (turn slip, eqs. 4.91-4.104).
    .. [2] I. J. M. Besselink, A. J. C. Schmeitz and H. B. Pacejka, "An improved Magic
       Formula/Swift tyre model that can handle inflation pressure changes", Vehicle System
       Dynamics 48 (sup1), 337-352, 2010, eqs. A54-A60.
    """
    r0, fz0p = c.UNLOADED_RADIUS, c.Fz0_prime
    dfz, gamma, gamma_star, alpha_star = s.dfz, s.gamma, s.gamma_star, s.alpha_star
    fz = s.fz_moment
    # --- pure-slip trail and residual torque factors (book 4.E33-4.E47) ---
    sht = c.QHZ1 + c.QHZ2 * dfz + (c.QHZ3 + c.QHZ4 * dfz) * gamma_star  # 4.E35
    kya_p = pure.kya + _EPSILON * sign_nonzero(xp, pure.kya)  # 4.E39
    alpha_r = alpha_star + (pure.shy + pure.svy / kya_p)  # 4.E37, 4.E38
    alpha_t = alpha_star + sht  # 4.E34
    if s.turn_slip:
        zeta5 = cos_atan(xp, c.QDTP1 * r0 * s.phi)  # 4.91
        zeta6 = cos_atan(xp, c.QBRP1 * r0 * s.phi)  # 4.102
    else:
        zeta5 = zeta6 = 1.0
    dt = (c.QDZ1 + c.QDZ2 * dfz) * (1 - c.PPZ1 * s.dpi) * (1 + c.QDZ3 * gamma + c.QDZ4 * gamma**2) \
        * fz * (r0 / fz0p) * c.LTR * zeta5  # A60 (4.E42, 4.E43)
    bt = (c.QBZ1 + c.QBZ2 * dfz + c.QBZ3 * dfz**2) * (1 + c.QBZ4 * gamma + c.QBZ5 * xp.abs(gamma)) \
        * c.LKY / c.LMUY  # A58 (4.E40)
    ct = c.QCZ1  # 4.E41
    et = (c.QEZ1 + c.QEZ2 * dfz + c.QEZ3 * dfz**2) \
        * (1 + (c.QEZ4 + c.QEZ5 * gamma_star) * (2 / math.pi) * xp.atan(bt * ct * alpha_t))  # 4.E44
    if s.limits:
        et = xp.minimum(et, 1.0)
    if s.turn_slip:
        mzp_inf = c.QCRP1 * xp.abs(pure.muy) * r0 * fz * xp.sqrt(fz / fz0p) * c.LMP  # 4.95
        mzp_inf = xp.where(mzp_inf < 0, 1e-6, mzp_inf)
        c_drp = c.QDRP1  # 4.96
        d_drp = mzp_inf / math.sin(0.5 * math.pi * c_drp)  # 4.94
        kzgr0 = fz * r0 * (c.QDZ8 * c.QDZ9 * dfz + (c.QDZ10 + c.QDZ11 * dfz * xp.abs(gamma))) * c.LKZC  # 4.99
        b_drp = xp.div(kzgr0, c_drp * d_drp * (1 - s.eps_gamma))
        drp = d_drp * xp.sin(c_drp * xp.atan(b_drp * r0 * s.phit))
        drp = xp.where(d_drp == 0, 0.0, drp)  # no load or no friction: the limit (MFeval: 0*NaN)
        mzp90 = mzp_inf * _TWO_OVER_PI * xp.atan(c.QCRP2 * r0 * xp.abs(s.phit)) * gyk  # 4.103
        ratio = xp.div(mzp90, xp.abs(drp))
        ratio_at_zero_phit = xp.div(mzp_inf * _TWO_OVER_PI * c.QCRP2 * gyk * xp.abs(1 - s.eps_gamma),
                                    xp.abs(kzgr0))
        # the limit phit -> 0 (0/0) and where it is exact to the last bit: with x = |b_drp r0 phit|
        # and |Q_CRP2 r0 phit| below 1e-8, atan(x) = x (1 - x^2/3) is x to 3e-17, and the quotient of
        # two denormals (phit ~ 5e-324) carries no digit at all (numba and numpy then disagreed by 0.1 %)
        small = xp.abs(s.phit) * r0 * xp.maximum(xp.abs(b_drp), abs(c.QCRP2)) < 1e-8
        ratio = xp.where(small, ratio_at_zero_phit, ratio)
        ratio = xp.where(xp.isnan(ratio), ratio_at_zero_phit, ratio)
        ratio = xp.where(xp.isnan(ratio), 1.0, xp.maximum(xp.minimum(ratio, 1.0), -1.0))
        cr = _TWO_OVER_PI * xp.acos(ratio)  # zeta7
        zeta8 = 1 + drp
        zeta0 = 0.0
    else:
        cr, zeta8, zeta0 = 1.0, 1.0, 1.0
    dr = fz * r0 * ((c.QDZ6 + c.QDZ7 * dfz) * c.LRES * pure.zeta2
                    + ((c.QDZ8 + c.QDZ9 * dfz) * (1 + c.PPZ2 * s.dpi)
                       + (c.QDZ10 + c.QDZ11 * dfz) * xp.abs(gamma_star)) * gamma_star * c.LKZC * zeta0) \
        * c.LMUY * xp.sign(s.vx) * xp.cos(alpha_star) + zeta8 - 1  # 4.E47 (MFeval adds zeta8 - 1)
    br = (c.QBZ9 * c.LKY / c.LMUY + c.QBZ10 * pure.by * pure.cy) * zeta6  # 4.E45
    # --- combined slip (A54-A56, 4.E71-4.E75) ---
    kappa_term = (kxk / kya_p) ** 2 * s.kappa**2
    alpha_r_eq = xp.atan(xp.sqrt(xp.tan(alpha_r) ** 2 + kappa_term)) * xp.sign(alpha_r)  # A54
    alpha_t_eq = xp.atan(xp.sqrt(xp.tan(alpha_t) ** 2 + kappa_term)) * xp.sign(alpha_t)  # A55
    arm = r0 * (c.SSZ1 + c.SSZ2 * (fy / c.FNOMIN) + (c.SSZ3 + c.SSZ4 * dfz) * gamma) * c.LS  # A56
    if s.turn_slip:
        residual = dr * xp.cos(cr * xp.atan(br * alpha_r_eq)) * s.low_speed  # 4.E75
    else:  # Cr = 1
        residual = dr * cos_atan(xp, br * alpha_r_eq) * s.low_speed
    bta = bt * alpha_t_eq
    trail = dt * xp.cos(ct * xp.atan(bta - et * (bta - xp.atan(bta)))) * s.cos_alpha_prime \
        * c.LFZO * s.low_speed  # 4.E73
    if c.is_mf52:
        mz = -trail * (fy - svyk) + residual + arm * fx
    else:
        if s.camber_free:
            fy0_flat = pure.fy0
        else:
            fy0_flat = lateral_pure(xp, c, s, 0.0, s.turn_slip).fy0
        mz = -trail * (gyk * fy0_flat) + residual + arm * fx  # 4.E71, 4.E72, 4.E74
    return AligningMoment(mz, trail, residual)
