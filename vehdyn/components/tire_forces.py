"""The tire-law step of a wheel or an axle, shared by the single-track and the full-vehicle models.

Written once over an ``xp`` namespace (:mod:`vehdyn.components.xp`): numpy arrays with a batch
axis, floats in numba-compiled code. Besides arithmetic it calls ``xp.tan``, ``xp.atan``,
``xp.maximum``, ``xp.minimum``, ``xp.sqrt``, ``xp.where``, ``xp.abs``, ``xp.tanh`` and the tire
hooks

``xp.tire_law(law, fz, kappa, alpha, gamma, vx)``
    ISO-W (F_x, F_y, M_y) [N, N, N*m] of one tire of ``law`` (numpy: ``law`` a
    :class:`~vehdyn.tire.TireModel`; compiled: a :class:`vehdyn.tire.compiled.TireLaw`);
``xp.tire_law_pair(law, fz_1, fz_2, kappa, alpha_1, alpha_2, gamma_1, gamma_2, vx)``
    the same for two tires at once (numpy: one call of the law on stacked arrays; compiled: two
    calls), a 6-tuple.

What the step adds to the law:

* **The mirror image.** A ``.tir`` file's law is the tire of the side it was measured on
  (``TYRESIDE``); the tire on the other side of the vehicle is its mirror image, (F_x, -F_y, M_y)
  at (-alpha, -gamma) (the convention of MF-Tyre and ADAMS property files). When the law makes a
  lateral force at zero slip (ply steer, conicity), an axle's two tires therefore differ, and an
  axle of two tires at half its load each (the single track) is the law's tire plus its mirror
  image: F_y = F_y(alpha) - F_y(-alpha), so that a vehicle with zero steer runs straight. Without
  such a force the two tires are the same law and the axle is twice one tire.
* **The road's friction by similarity** (Pacejka 2012, sec. 4.3.2, "similarity method"): on a
  road whose friction is mu times the law's own (mu the friction ratio),

  .. math::

      F(\\kappa, \\tan\\alpha) \\rightarrow \\mu\\,F(\\kappa / \\mu,\\ \\tan\\alpha / \\mu)

  which scales the peak forces and the slips at which they occur by mu and keeps the slip
  stiffnesses (dF/dkappa, dF/dtan(alpha) at zero slip) exactly, for every law alike. The
  rolling-resistance moment M_y comes from the tire's hysteresis, not from the road's grip, and
  is not scaled.
* **The conventions** (:mod:`vehdyn.conventions`): the vehicle equations' SAE slips in, SAE forces
  out; in force mode (no wheel spin) the longitudinal force is the demand clipped at the friction
  limit and the lateral force is reduced by the friction ellipse (Rajamani 2012, sec. 13.7); the
  rolling-resistance moment fades out at standstill (:func:`vehdyn.components.wheel.rolling_resistance_fade`).

References
----------
.. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, sec. 4.3.2
   (similarity, the friction scaling lambda_mu) and sec. 4.3.5 (rolling resistance).
.. [2] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, sec. 13.7.
"""

from __future__ import annotations

from vehdyn.components.tire_slip import contact_slips
from vehdyn.components.wheel import rolling_resistance_fade
from vehdyn.conventions import planar_tire_forces_iso_w_to_sae, planar_tire_slips_sae_to_iso_w

__all__ = ["tire_loads", "axle_tire_loads", "wheel_pair_tire_loads", "wheel_pair_aligning_moments", "tire_aligning_moment",
           "secant_compliance", "demanded_forces", "contact_loads"]


def tire_loads(xp, law, fz, kappa, alpha, gamma, vx, mirror, friction, scaled):
    """ISO-W (F_x, F_y, M_y) of one tire: the law's own or its mirror image, on a road of another friction.

    .. math::

        (F_x, F_y, M_y) = (\\mu F_x^*, \\pm\\mu F_y^*, M_y^*),\\quad
        F^* = F(\\kappa / \\mu,\\ \\arctan(\\tan(\\pm\\alpha) / \\mu),\\ \\pm\\gamma)

    (the lower signs for the mirror image; mu = 1 without ``scaled``).

    Parameters
    ----------
    xp : namespace
        The equations' namespace (with ``tire_law``).
    law : TireModel or TireLaw
        The law (what ``xp.tire_law`` takes).
    fz : float or ndarray
        Normal load [N].
    kappa : float or ndarray
        Slip ratio [-] (ISO-W).
    alpha : float or ndarray
        Slip angle [rad] (ISO-W).
    gamma : float or ndarray
        Inclination angle [rad] (ISO-W).
    vx : float or ndarray
        Signed forward speed of the wheel centre [m/s].
    mirror : bool
        The tire is the law's mirror image.
    friction : float or ndarray
        The road's friction relative to the law's own, mu [-] (read only with ``scaled``).
    scaled : bool
        Apply ``friction`` (False: the law as it is, without an operation).

    Returns
    -------
    tuple
        (F_x [N], F_y [N], M_y [N*m]), ISO-W.
    """
    if scaled:
        kappa, alpha = kappa / friction, xp.atan(xp.tan(alpha) / friction)
    if mirror:
        alpha, gamma = -alpha, -gamma
    fx, fy, my = xp.tire_law(law, fz, kappa, alpha, gamma, vx)
    if mirror:
        fy = -fy
    if scaled:
        return friction * fx, friction * fy, my
    return fx, fy, my


def _similar(xp, kappa, alpha, friction, scaled):
    """The slips at which a law on a road of friction ratio ``friction`` is evaluated."""
    if scaled:
        return kappa / friction, xp.atan(xp.tan(alpha) / friction)
    return kappa, alpha


def _scaled_pair(w, mirror_first, mirror_second, friction, scaled):
    """A pair's forces with the mirror images' F_y negated and the friction applied."""
    fy1 = -w[1] if mirror_first else w[1]
    fy2 = -w[4] if mirror_second else w[4]
    if scaled:
        return friction * w[0], friction * fy1, w[2], friction * w[3], friction * fy2, w[5]
    return w[0], fy1, w[2], w[3], fy2, w[5]


def axle_tire_loads(xp, law, fz, kappa, alpha, vx, ply_steer, friction, scaled):
    """ISO-W (F_x, F_y, M_y) of an axle of two tires at half its load each, at the same slips.

    .. math::

        F = F_{\\text{tire}}(F_z / 2) + F_{\\text{mirror}}(F_z / 2) \\text{ with ply steer, else }
        2 F_{\\text{tire}}(F_z / 2)

    (:func:`tire_loads` for each, at zero inclination; the module docstring says why).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    law : TireModel or TireLaw
        The law of one tire.
    fz : float or ndarray
        Axle load [N].
    kappa : float or ndarray
        Slip ratio [-] (ISO-W).
    alpha : float or ndarray
        Slip angle [rad] (ISO-W).
    vx : float or ndarray
        Signed forward speed [m/s].
    ply_steer : bool
        The law makes a lateral force at zero slip: one tire is its mirror image.
    friction : float or ndarray
        Friction ratio mu [-].
    scaled : bool
        Apply ``friction``.

    Returns
    -------
    tuple
        (F_x [N], F_y [N], M_y [N*m]) of the axle, ISO-W.
    """
    load = 0.5 * fz
    if ply_steer:
        kappa, alpha = _similar(xp, kappa, alpha, friction, scaled)
        w = _scaled_pair(xp.tire_law_pair(law, load, load, kappa, alpha, -alpha, 0.0, 0.0, vx), False, True,
                         friction, scaled)
        return w[0] + w[3], w[1] + w[4], w[2] + w[5]
    fx, fy, my = tire_loads(xp, law, load, kappa, alpha, 0.0, vx, False, friction, scaled)
    return 2.0 * fx, 2.0 * fy, 2.0 * my


def wheel_pair_tire_loads(xp, law, left_load, right_load, kappa, alpha, gamma, vx, mirror_left, mirror_right,
                          friction, scaled):
    """ISO-W (F_x, F_y, M_y) of the left, then the right tire of an axle at their own loads.

    :func:`tire_loads` for each: the one of ``mirror_left``, ``mirror_right`` that is set is the
    law's mirror image (a law with ply steer: the left tire for a right-side law, the right one for
    a ``TYRESIDE = 'LEFT'`` file), both at the same slips and inclination (the wheels of an axle
    lean together when the body rolls; the mirror image sees -alpha and -gamma).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    law : TireModel or TireLaw
        The law of one tire.
    left_load, right_load : float or ndarray
        Normal loads [N].
    kappa : float or ndarray
        Slip ratio [-] (ISO-W), both tires.
    alpha : float or ndarray
        Slip angle [rad] (ISO-W), both tires.
    gamma : float or ndarray
        Inclination angle [rad] (ISO-W, rotation about x), both tires (0.0: upright).
    vx : float or ndarray
        Signed forward speed [m/s].
    mirror_left, mirror_right : bool
        Which tire is the law's mirror image (neither without ply steer).
    friction : float or ndarray
        Friction ratio mu [-] (both tires).
    scaled : bool
        Apply ``friction``.

    Returns
    -------
    tuple
        (F_x left [N], F_y left [N], M_y left [N*m], F_x right [N], F_y right [N], M_y right [N*m]).
    """
    kappa, alpha = _similar(xp, kappa, alpha, friction, scaled)
    left_alpha = -alpha if mirror_left else alpha
    right_alpha = -alpha if mirror_right else alpha
    # 0.0 - gamma, not -gamma: an upright mirror image sees +0.0 as before
    left_gamma = 0.0 - gamma if mirror_left else gamma
    right_gamma = 0.0 - gamma if mirror_right else gamma
    w = xp.tire_law_pair(law, left_load, right_load, kappa, left_alpha, right_alpha, left_gamma, right_gamma, vx)
    return _scaled_pair(w, mirror_left, mirror_right, friction, scaled)


def tire_aligning_moment(xp, law, fz, kappa, alpha, gamma, vx, mirror, friction, scaled):
    r"""ISO-W aligning moment M_z [N*m] of one tire, as :func:`tire_loads` evaluates its forces.

    The hook ``xp.tire_law_aligning``; the mirror image's moment is negated (a mirror image is
    (F_x, -F_y, M_y, -M_z) at (-alpha, -gamma)), and on a road of friction ratio mu the moment
    scales as the forces do,

    .. math::

        M_z = \pm\mu M_z^*(\kappa / \mu,\ \arctan(\tan(\pm\alpha) / \mu),\ \pm\gamma)

    (the pneumatic trail at the similar slip times the scaled force; Pacejka 2012, sec. 4.3.2).

    Parameters
    ----------
    xp : namespace
        The equations' namespace (with ``tire_law_aligning``).
    law : TireModel or TireLaw
        The law.
    fz : float or ndarray
        Normal load [N].
    kappa : float or ndarray
        Slip ratio [-] (ISO-W).
    alpha : float or ndarray
        Slip angle [rad] (ISO-W).
    gamma : float or ndarray
        Inclination angle [rad] (ISO-W).
    vx : float or ndarray
        Signed forward speed [m/s].
    mirror : bool
        The tire is the law's mirror image.
    friction : float or ndarray
        Friction ratio mu [-].
    scaled : bool
        Apply ``friction``.

    Returns
    -------
    float or ndarray
        M_z [N*m], ISO-W.
    """
    kappa, alpha = _similar(xp, kappa, alpha, friction, scaled)
    if mirror:
        moment = -xp.tire_law_aligning(law, fz, kappa, -alpha, 0.0 - gamma, vx)
    else:
        moment = xp.tire_law_aligning(law, fz, kappa, alpha, gamma, vx)
    return friction * moment if scaled else moment


def wheel_pair_aligning_moments(xp, law, left_load, right_load, kappa, alpha, gamma, vx, mirror_left, mirror_right,
                                friction, scaled):
    """ISO-W aligning moments M_z of the left, then the right tire of an axle, as :func:`wheel_pair_tire_loads`.

    :func:`tire_aligning_moment` of each.

    Parameters
    ----------
    xp : namespace
        The equations' namespace (with ``tire_law_aligning``).
    law : TireModel or TireLaw
        The law of one tire.
    left_load, right_load : float or ndarray
        Normal loads [N].
    kappa : float or ndarray
        Slip ratio [-] (ISO-W), both tires.
    alpha : float or ndarray
        Slip angle [rad] (ISO-W), both tires.
    gamma : float or ndarray
        Inclination angle [rad] (ISO-W), both tires.
    vx : float or ndarray
        Signed forward speed [m/s].
    mirror_left, mirror_right : bool
        Which tire is the law's mirror image.
    friction : float or ndarray
        Friction ratio mu [-].
    scaled : bool
        Apply ``friction``.

    Returns
    -------
    tuple
        (M_z left [N*m], M_z right [N*m]), ISO-W.
    """
    return (tire_aligning_moment(xp, law, left_load, kappa, alpha, gamma, vx, mirror_left, friction, scaled),
            tire_aligning_moment(xp, law, right_load, kappa, alpha, gamma, vx, mirror_right, friction, scaled))


def secant_compliance(xp, first, second, step, slope):
    r"""The compliance steer delta = g(delta) from two evaluations of g: at 0 and at a first ``step``.

    .. math::

        \delta = \frac{g(0)}{1 - s'},\qquad s' = \min\left(\frac{g(\delta_1) - g(0)}{\delta_1},\ 0.9\right)

    the root of the chord through (0, g(0)) and (delta_1, g(delta_1)) (the secant method): exact
    for g linear in delta, else in error by the chord's departure from g between delta_1 and delta
    (second order in delta - delta_1). Where delta_1 is 0 (no force) the slope is ``slope``; s' is
    held below 0.9 (beyond, the force would steer the wheel further than its slip). g(delta) =
    c F_y + e M_z of a wheel or axle steered by delta more (compliance steer, issue 28).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    first, second : float or ndarray
        g(0) and g(delta_1) [rad].
    step : float or ndarray
        delta_1 [rad].
    slope : float or ndarray
        The slope to take where delta_1 = 0 [-].

    Returns
    -------
    float or ndarray
        delta [rad].
    """
    moved = xp.abs(step) > 1e-12
    chord = xp.where(moved, (second - first) / xp.where(moved, step, 1.0), slope)
    return first / (1.0 - xp.minimum(chord, 0.9))


def demanded_forces(xp, k, fz, fx, fy, force_demand, friction):
    """Force mode (no wheel spin): F_x the demand clipped at the friction limit, F_y of the law
    reduced by the friction ellipse (Rajamani 2012, sec. 13.7).

    .. math::

        F_x = \\min(\\max(F_{x,d}, -\\mu_r \\mu F_z), \\mu_r \\mu F_z),\\quad
        F_y = F_y^{\\text{law}} \\sqrt{1 - (F_x / (\\mu_r \\mu F_z))^2}

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : namedtuple
        The model's constants; read: ``friction_coefficient`` mu [-] (the law's own) and
        ``friction_scaled`` (bool: the road's friction ratio mu_r applies).
    fz : float or ndarray
        Normal load [N].
    fx : float or ndarray
        The law's F_x [N] (replaced).
    fy : float or ndarray
        The law's F_y at zero slip ratio [N].
    force_demand : float or ndarray
        The longitudinal force asked for [N].
    friction : float or ndarray
        mu_r [-].

    Returns
    -------
    tuple
        (F_x [N], F_y [N]).
    """
    mu = k.friction_coefficient
    if k.friction_scaled:
        mu = mu * friction
    limit = mu * xp.maximum(fz, 0.0)
    fx = xp.minimum(xp.maximum(force_demand, -limit), limit)
    safe = xp.where(limit > 0, limit, 1.0)
    return fx, fy * xp.sqrt(xp.maximum(1.0 - (fx / safe) ** 2, 0.0))


def contact_loads(xp, k, law, fz, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection, lateral_rate,
                  longitudinal_rate, lateral_length, longitudinal_length, peak_slip_ratio, peak_tan_slip_angle,
                  force_demand, gamma, axle, mirror, friction):
    """The tire step of a wheel (``axle`` False) or of a lumped axle (``axle`` True), SAE in and out.

    The slips of :func:`~vehdyn.components.tire_slip.contact_slips`, turned to ISO-W; the law
    through :func:`tire_loads` (one tire at ``fz``) or :func:`axle_tire_loads` (two tires at
    ``fz / 2``); the forces turned back to SAE wheel axes; in force mode :func:`demanded_forces`;
    the rolling-resistance moment faded out at standstill.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : namedtuple
        The model's constants; read: ``tire_lag``, ``wheel_spin``, ``friction_scaled`` (bools),
        ``rolling_radius`` [m], ``low_speed_damping_speed`` [m/s], ``brake_regularization_speed``
        [rad/s], ``friction_coefficient`` [-].
    law : TireModel or TireLaw
        The law of one tire.
    fz : float or ndarray
        Normal load of the wheel or axle [N].
    vx, vy : float or ndarray
        Velocity of the wheel centre in wheel axes (SAE) [m/s].
    wheel_speed : float or ndarray
        Spin omega [rad/s].
    lateral_deflection, longitudinal_deflection : float or ndarray
        rho_y, rho_x [m].
    lateral_rate, longitudinal_rate : float or ndarray
        Their rates [m/s].
    lateral_length, longitudinal_length : float or ndarray
        Relaxation lengths [m].
    peak_slip_ratio, peak_tan_slip_angle : float or ndarray
        The slips of the law's peak forces on this road [-].
    force_demand : float or ndarray
        Force mode's longitudinal force demand [N] (unused with wheel spin).
    gamma : float or ndarray
        Inclination angle [rad] (ISO-W; 0 for a lumped axle).
    axle : bool
        A lumped axle of two tires (``mirror``: the law has ply steer) rather than one tire
        (``mirror``: this tire is the law's mirror image).
    mirror : bool
        See ``axle``.
    friction : float or ndarray
        The road's friction ratio mu [-] (read where ``k.friction_scaled``).

    Returns
    -------
    tuple
        (F_x [N], F_y [N]) in SAE wheel axes, (alpha SAE [rad], kappa [-]) acting in the law, and
        M_y [N*m] (ISO-W, about the axis of forward spin; 0 in force mode).
    """
    alpha, kappa, direction, speed = contact_slips(
        xp, k, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection, lateral_rate, longitudinal_rate,
        lateral_length, longitudinal_length, peak_slip_ratio, peak_tan_slip_angle)
    kappa_iso, alpha_iso = planar_tire_slips_sae_to_iso_w(kappa, alpha)
    signed_speed = direction * xp.maximum(speed, 1e-3)
    if axle:
        fx_iso, fy_iso, my = axle_tire_loads(xp, law, fz, kappa_iso, alpha_iso, signed_speed, mirror, friction,
                                             k.friction_scaled)
    else:
        fx_iso, fy_iso, my = tire_loads(xp, law, fz, kappa_iso, alpha_iso, gamma, signed_speed, mirror, friction,
                                        k.friction_scaled)
    fx, fy = planar_tire_forces_iso_w_to_sae(fx_iso, fy_iso)
    if not k.wheel_spin:
        fx, fy = demanded_forces(xp, k, fz, fx, fy, force_demand, friction)
        my = 0.0 * my
    return fx, fy, alpha, kappa, my * rolling_resistance_fade(xp, k, wheel_speed)
