"""Magic Formula forces: pure and combined slip Fx, Fy, with turn slip (MF 5.2, 6.1, 6.2).

Equations of Pacejka, *Tire and Vehicle Dynamics*, 3rd ed. (2012), section 4.3.2 and the
appendix of chapter 4 (eqs. 4.E1–4.E67) and the turn-slip extension (eqs. 4.75–4.106), as MFeval
4.3.1 implements them (ISO-W axes, no SAE sign changes). Every function takes ``xp`` (numpy or
the scalar namespace of :mod:`vehdyn.tire._mf_ops`), the coefficient set ``c`` and the state
``s`` of one evaluation (post-processed inputs and the quantities computed so far).

The state ``s`` carries: ``fz`` (load after the FZMAX clamp) [N], ``kappa`` [-], ``alpha``,
``gamma`` [rad] (after limits and low-speed reduction), ``alpha_star``, ``gamma_star`` (eqs. 4.E3,
4.E4 or the plain angles), ``vx`` [m/s], ``dfz``, ``dpi`` (eqs. 4.E2a, b), ``low_speed``
(smooth low-speed factor, 1 above VXLOW), ``phi`` [1/m] (spin, turn-slip mode) and the flags
``limits`` and ``turn_slip`` (a :class:`vehdyn.tire.magic_formula.MFState`). Results travel in
named tuples, so that numba can compile these functions unchanged (see :mod:`vehdyn.tire._mf_numba`).
"""

from __future__ import annotations

from collections import namedtuple

from vehdyn.tire._mf_ops import cos_atan, sign_nonzero

__all__ = [
    "longitudinal_pure",
    "lateral_pure",
    "longitudinal_combined",
    "lateral_combined_factor",
    "lateral_combined",
    "turn_slip_spin",
]

_EPSILON = 1e-6  # MFeval's singularity guard (book eq. 4.E6a, epsilon_x = epsilon_y = epsilon_K)


def turn_slip_spin(xp, c, alpha, vx, phit, gamma, dfz, omega):
    """Spin phi of the turn-slip model and the camber reduction eps_gamma (book 4.75, 4.76, 4.90).

    MFeval's sign: phi = -phit' - (1 - eps_g)*omega*sin(gamma)/Vc' (book eq. 4.76 without its
    leading minus, for z-up road axes), Vc' = |V| replaced by VXLOW*sign(Vx) below VXLOW.

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    alpha, gamma : float or ndarray
        Slip and inclination angles after the limits and low-speed rules [rad].
    vx : float or ndarray
        Forward speed [m/s].
    phit : float or ndarray
        Turn slip [1/m].
    dfz : float or ndarray
        Normalized load increment [-] (eq. 4.E2a).
    omega : float or ndarray
        Wheel spin [rad/s].

    Returns
    -------
    phi : float or ndarray
        Spin [1/m].
    eps_gamma : float or ndarray
        Camber reduction factor [-] (eq. 4.90).

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 4.3.2.3 (eqs. 4.75, 4.76, 4.90).
    """
    v_sy = -xp.tan(alpha) * xp.abs(vx)
    speed = xp.sqrt(vx**2 + v_sy**2)
    eps_gamma = c.PECP1 * (1 + c.PECP2 * dfz)
    below = xp.abs(vx) < c.VXLOW
    protected = xp.where(below, c.VXLOW * xp.where(vx < 0, -1.0, 1.0), speed)
    yaw_rate = -phit * protected
    phi = (1 / protected) * (yaw_rate - (1 - eps_gamma) * omega * xp.sin(gamma))
    return phi, eps_gamma


def longitudinal_pure(xp, c, s):
    r"""Pure longitudinal slip force Fx0 (book eqs. 4.E9–4.E18, turn slip 4.105–4.106).

    .. math::

        F_{x0} = D_x \sin[C_x \arctan\{B_x \kappa_x - E_x (B_x \kappa_x - \arctan B_x \kappa_x)\}]
        + S_{Vx}, \qquad \kappa_x = \kappa + S_{Hx}

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    s : MFState
        The state of the evaluation (module docstring; :class:`vehdyn.tire.magic_formula.MFState`).

    Returns
    -------
    fx0, mux, kxk
        Force [N] (sign flipped for vx < 0), friction coefficient [-] (0 at fz = 0) and slip
        stiffness Kxk = Bx*Cx*Dx [N].

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 4.3.2 (eqs. 4.E9-4.E18) and 4.3.3 (turn slip, eqs. 4.105, 4.106).
    """
    dfz, dpi = s.dfz, s.dpi
    if s.turn_slip:
        b_xp = c.PDXP1 * (1 + c.PDXP2 * dfz) * cos_atan(xp, c.PDXP3 * s.kappa)  # 4.106
        zeta1 = cos_atan(xp, b_xp * c.UNLOADED_RADIUS * s.phi)  # 4.105
    else:
        zeta1 = 1.0
    cx = c.PCX1 * c.LCX  # 4.E11
    mux = (c.PDX1 + c.PDX2 * dfz) * (1 + c.PPX3 * dpi + c.PPX4 * dpi**2) \
        * (1 - c.PDX3 * s.gamma**2) * c.LMUX  # 4.E13
    if xp.any(s.fz == 0):
        mux = xp.where(s.fz == 0, 0.0, mux)
    dx = mux * s.fz * zeta1  # 4.E12
    kxk = s.fz * (c.PKX1 + c.PKX2 * dfz) * xp.exp(c.PKX3 * dfz) \
        * (1 + c.PPX1 * dpi + c.PPX2 * dpi**2) * c.LKX  # 4.E15
    bx = kxk / (cx * dx + _EPSILON * sign_nonzero(xp, dx))  # 4.E16
    shx = (c.PHX1 + c.PHX2 * dfz) * c.LHX * s.low_speed  # 4.E17
    svx = s.fz * (c.PVX1 + c.PVX2 * dfz) * c.LVX * c.LMUX * zeta1 * s.low_speed  # 4.E18
    kappa_x = s.kappa + shx  # 4.E10
    ex = (c.PEX1 + c.PEX2 * dfz + c.PEX3 * dfz**2) * (1 - c.PEX4 * xp.sign(kappa_x)) * c.LEX  # 4.E14
    if s.limits:
        ex = xp.minimum(ex, 1.0)
    bk = bx * kappa_x
    fx0 = dx * xp.sin(cx * xp.atan(bk - ex * (bk - xp.atan(bk)))) + svx  # 4.E9
    fx0 = fx0 * s.reverse
    return fx0, mux, kxk


LateralPure = namedtuple("LateralPure", "fy0 muy kya shy svy by cy zeta2")
LateralPure.__doc__ = "Intermediate results of :func:`lateral_pure` needed by the aligning moment."


def lateral_pure(xp, c, s, gamma_star, turn_slip):
    r"""Pure lateral slip force Fy0 (book eqs. 4.E19–4.E30; turn slip 4.77–4.89).

    .. math::

        F_{y0} = D_y \sin[C_y \arctan\{B_y \alpha_y - E_y (B_y \alpha_y - \arctan B_y \alpha_y)\}]
        + S_{Vy}, \qquad \alpha_y = \alpha^* + S_{Hy}

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    s : MFState
        The state of the evaluation (module docstring; :class:`vehdyn.tire.magic_formula.MFState`).
    gamma_star : float or array
        Inclination used in the force equations [rad] (``s.gamma_star``, or 0 for the
        camber-free force the aligning moment needs, book eq. 4.E74).
    turn_slip : bool
        Whether the turn-slip factors apply.

    Returns
    -------
    LateralPure
        ``fy0`` [N], ``muy`` [-], ``kya`` [N/rad], ``shy`` [rad], ``svy`` [N], ``by`` [1/rad],
        ``cy`` [-] and ``zeta2`` [-]: the force and the intermediate results the aligning moment
        needs.

    Notes
    -----
    MF 5.2 uses SHy = (PHY1 + PHY2*dfz)*LHY + PHY3*gamma*LKYC (MF-Tyre 5.2 manual) and keeps it in
    turn-slip mode; MF 6.x uses eq. 4.E27 (with zeta0 = 0 and zeta4 of eq. 4.84 under turn slip).

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 4.3.2 (eqs. 4.E19-4.E30) and 4.3.3 (turn slip, eqs. 4.77-4.89).
    """
    dfz, dpi, fz, fz0p = s.dfz, s.dpi, s.fz, c.Fz0_prime
    r0 = c.UNLOADED_RADIUS
    if turn_slip:
        phi = s.phi
        zeta3 = cos_atan(xp, c.PKYP1 * r0**2 * phi**2)  # 4.79
        b_yp = c.PDYP1 * (1 + c.PDYP2 * dfz) * cos_atan(xp, c.PDYP3 * xp.tan(s.alpha))  # 4.78
        r_phi = r0 * xp.abs(phi)
        zeta2 = cos_atan(xp, b_yp * (r_phi + c.PDYP4 * xp.sqrt(r_phi)))  # 4.77
    else:
        zeta2 = zeta3 = 1.0
    pressure_k = 1 + c.PPY2 * dpi
    kya = c.PKY1 * fz0p * (1 + c.PPY1 * dpi) * (1 - c.PKY3 * xp.abs(gamma_star)) * xp.sin(
        c.PKY4 * xp.atan((fz / fz0p) / ((c.PKY2 + c.PKY5 * gamma_star**2) * pressure_k))
    ) * zeta3 * c.LKY  # 4.E25
    svy_gamma = fz * (c.PVY3 + c.PVY4 * dfz) * gamma_star * c.LKYC * c.LMUY * zeta2  # 4.E28
    if c.is_mf52:
        shy = (c.PHY1 + c.PHY2 * dfz) * c.LHY + c.PHY3 * gamma_star * c.LKYC
    else:
        kyg0 = fz * (c.PKY6 + c.PKY7 * dfz) * (1 + c.PPY5 * dpi) * c.LKYC  # 4.E30
        kya_p = kya + _EPSILON * sign_nonzero(xp, kya)  # 4.E39
        if turn_slip:
            kya0 = c.PKY1 * fz0p * (1 + c.PPY1 * dpi) * xp.sin(
                c.PKY4 * xp.atan((fz / fz0p) / (c.PKY2 * pressure_k))) * zeta3 * c.LKY
            kya0_p = kya0 + _EPSILON * sign_nonzero(xp, kya0)
            sign_vx = xp.sign(s.vx)
            c_hyp = c.PHYP1  # 4.85
            d_hyp = (c.PHYP2 + c.PHYP3 * dfz) * sign_vx  # 4.86
            e_hyp = min(c.PHYP4, 1.0) if s.limits else c.PHYP4  # 4.87
            b_hyp = xp.div(kyg0 / (1 - s.eps_gamma), c_hyp * d_hyp * kya0_p)  # 4.88, 4.89
            arg = b_hyp * r0 * s.phi
            shy_p = d_hyp * xp.sin(c_hyp * xp.atan(arg - e_hyp * (arg - xp.atan(arg)))) * sign_vx  # 4.80
            shy_p = xp.where(d_hyp == 0, 0.0, shy_p)  # vx = 0: DHyp = 0, the limit (MFeval: 0*inf = NaN)
            zeta4 = 1 + shy_p - svy_gamma / kya_p  # 4.84
            shy = (c.PHY1 + c.PHY2 * dfz) * c.LHY + zeta4 - 1  # 4.E27 with zeta0 = 0
        else:
            # 4.E27 with zeta0 = zeta4 = 1, summed as MFeval does (the + 1 - 1 rounds)
            shy = (c.PHY1 + c.PHY2 * dfz) * c.LHY + (kyg0 * gamma_star - svy_gamma) / kya_p + 1.0 - 1.0
    svy = fz * (c.PVY1 + c.PVY2 * dfz) * c.LVY * c.LMUY * zeta2 + svy_gamma  # 4.E29
    svy = svy * s.low_speed
    shy = shy * s.low_speed
    alpha_y = s.alpha_star + shy  # 4.E20
    cy = c.PCY1 * c.LCY  # 4.E21
    muy = (c.PDY1 + c.PDY2 * dfz) * (1 + c.PPY3 * dpi + c.PPY4 * dpi**2) \
        * (1 - c.PDY3 * gamma_star**2) * c.LMUY  # 4.E23
    dy = muy * fz * zeta2  # 4.E22
    ey = (c.PEY1 + c.PEY2 * dfz) * (1 + c.PEY5 * gamma_star**2
                                    - (c.PEY3 + c.PEY4 * gamma_star) * sign_nonzero(xp, alpha_y)) * c.LEY  # 4.E24
    if s.limits:
        ey = xp.minimum(ey, 1.0)
    by = kya / (cy * dy + _EPSILON * sign_nonzero(xp, dy))  # 4.E26
    ba = by * alpha_y
    fy0 = dy * xp.sin(cy * xp.atan(ba - ey * (ba - xp.atan(ba)))) + svy  # 4.E19
    if s.alpha_star_mode:
        fy0 = fy0 * s.reverse
    if xp.any(fz == 0):
        muy = xp.where(fz == 0, 0.0, muy)
    return LateralPure(fy0, muy, kya, shy, svy, by, cy, zeta2)


def longitudinal_combined(xp, c, s, fx0):
    r"""Combined-slip longitudinal force (book eqs. 4.E50–4.E57).

    .. math::

        F_x = G_{x\alpha} F_{x0}, \qquad
        G_{x\alpha} = \frac{\cos[C_{x\alpha} \arctan\{B_{x\alpha} \alpha_S
        - E_{x\alpha} (B_{x\alpha} \alpha_S - \arctan B_{x\alpha} \alpha_S)\}]}{G_{x\alpha 0}}

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    s : MFState
        The state of the evaluation (module docstring; :class:`vehdyn.tire.magic_formula.MFState`).
    fx0 : float or ndarray
        Pure-slip force Fx0 [N] (:func:`longitudinal_pure`).

    Returns
    -------
    float or ndarray
        Fx [N].

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 4.3.2 (eqs. 4.E50-4.E57).
    """
    cxa = c.RCX1  # 4.E55
    exa = c.REX1 + c.REX2 * s.dfz  # 4.E56
    if s.limits:
        exa = xp.minimum(exa, 1.0)
    shxa = c.RHX1  # 4.E57
    bxa = (c.RBX1 + c.RBX3 * s.gamma_star**2) * cos_atan(xp, c.RBX2 * s.kappa) * c.LXAL  # 4.E54
    alpha_s = s.alpha_star + shxa  # 4.E53
    b0 = bxa * shxa
    gxa0 = xp.cos(cxa * xp.atan(b0 - exa * (b0 - xp.atan(b0))))  # 4.E52
    b1 = bxa * alpha_s
    gxa = xp.cos(cxa * xp.atan(b1 - exa * (b1 - xp.atan(b1)))) / gxa0  # 4.E51
    return gxa * fx0  # 4.E50


def lateral_combined_factor(xp, c, s):
    """Weighting function Gyk of combined slip (book eqs. 4.E59–4.E65).

    Parameters
    ----------
    xp : namespace
        Array operations: :class:`vehdyn.tire._mf_ops.NumpyOps`, ``ScalarOps`` or a compiled
        equivalent.
    c : MFCoefficients
        The ``.tir`` coefficients in SI (:class:`vehdyn.tire.magic_formula.MFCoefficients`).
    s : MFState
        The state of the evaluation (module docstring; :class:`vehdyn.tire.magic_formula.MFState`).

    Returns
    -------
    float or ndarray
        Gyk [-].

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 4.3.2 (eqs. 4.E59-4.E65).
    """
    shyk = c.RHY1 + c.RHY2 * s.dfz  # 4.E65
    eyk = c.REY1 + c.REY2 * s.dfz  # 4.E64
    if s.limits:
        eyk = xp.minimum(eyk, 1.0)
    cyk = c.RCY1  # 4.E63
    byk = (c.RBY1 + c.RBY4 * s.gamma_star**2) * cos_atan(xp, c.RBY2 * (s.alpha_star - c.RBY3)) * c.LYKA  # 4.E62
    kappa_s = s.kappa + shyk  # 4.E61
    b0 = byk * shyk
    gyk0 = xp.cos(cyk * xp.atan(b0 - eyk * (b0 - xp.atan(b0))))  # 4.E60
    b1 = byk * kappa_s
    return xp.cos(cyk * xp.atan(b1 - eyk * (b1 - xp.atan(b1)))) / gyk0  # 4.E59


def lateral_combined(xp, c, s, pure: LateralPure):
    """Combined-slip Fy = Gyk*Fy0 + SVyk (book eqs. 4.E58–4.E67).

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
        Pure lateral slip results (:func:`lateral_pure`).

    Returns
    -------
    fy, gyk, svyk
        Force [N], weighting function [-] and the kappa-induced side force SVyk [N] (after the
        low-speed reduction).

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 4.3.2 (eqs. 4.E58-4.E67).
    """
    dvyk = pure.muy * s.fz * (c.RVY1 + c.RVY2 * s.dfz + c.RVY3 * s.gamma_star) \
        * cos_atan(xp, c.RVY4 * s.alpha_star) * pure.zeta2  # 4.E67
    svyk = dvyk * xp.sin(c.RVY5 * xp.atan(c.RVY6 * s.kappa)) * c.LVYKA  # 4.E66
    gyk = lateral_combined_factor(xp, c, s)
    svyk = svyk * s.low_speed
    return gyk * pure.fy0 + svyk, gyk, svyk  # 4.E58

