r"""The understeer budget: a vehicle's understeer gradient as the sum of its terms (Gillespie's Table 6.1).

Steer equation of a steady turn (SAE, axle law F_i = F_0i - C_i alpha_i with F_0i every force the
axle makes at zero slip, delta_i,c every steer the axle adds by itself)::

    delta - L r / u = alpha_r - alpha_f - (delta_f,c - delta_r,c)

so, per unit lateral acceleration,

    K = (F_f - F_0f) / C_f - (F_r - F_0r) / C_r - d(delta_f,c - delta_r,c) / d(a_y)

with the axle forces F_f = W_f a_y / g, F_r = W_r a_y / g fixed by the lateral and yaw balance
alone. Every term below is one source of F_0i, delta_i,c or C_i, and since the forces are fixed
by statics the terms add up exactly (in the linear limit a_y -> 0).
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.units import GRAVITY

__all__ = ["understeer_budget", "vehicle_roll_understeer", "plot_understeer_budget"]

_GILLESPIE = "Gillespie 1992, ch. 6, Table 6.1"
_ROWS = (
    ("weight_distribution", "W_f / C_f - W_r / C_r", _GILLESPIE + ", eq. 6-15; Milliken 1995, ch. 5"),
    ("lateral_load_transfer", "-2 C''_f dN_f^2 / C_f + 2 C''_r dN_r^2 / C_r: second order in a_y, 0 in the linear "
     "limit", _GILLESPIE + "; Pacejka 2012, sec. 1.3"),
    ("camber_thrust", "-(C_gf / C_f) dgamma_f/dA + (C_gr / C_r) dgamma_r/dA, gamma_i = phi + g_i (T_i / 2) phi_si",
     _GILLESPIE),
    ("roll_steer", "(eps_f - eps_r) RG, RG the roll per g (steady_roll)", _GILLESPIE),
    ("lateral_force_compliance_steer", "-c_f W_f + c_r W_r", _GILLESPIE + " (A_f W_f - A_r W_r, A = -c)"),
    ("aligning_moment_compliance_steer", "+e_f t_f W_f - e_r t_r W_r (M_z = -t F_y)", _GILLESPIE),
    ("steering_system_compliance", "(t_m + t_f) W_f / K_ss, K_ss = N^2 k_c (hand-wheel referred only)",
     _GILLESPIE + " (W_f (r + p) / K_ss)"),
)

_PACEJKA = "Pacejka 2012, sec. 1.3 and 4.3"
_AT_SPEED_ROWS = (
    ("law_cornering_stiffness", "W_f / C*_f - W_r / C*_r - (W_f / C_f - W_r / C_r), C*_i the law's at the static loads",
     _PACEJKA + "; " + _GILLESPIE),
    ("aero_load_transfer", "-(W_f / g) dN_f C*_f' / C*_f^2 + (W_r / g) dN_r C*_r' / C*_r^2 (x g), dN_f = -X - Z_f, "
     "dN_r = X - Z_r, X = (F_D h_s + m g h theta_Z) / (L - m g h c_theta), c_theta = (1/k_sf + 1/k_sr + 2/k_t) / "
     "(2 L)", "Gillespie 1992, ch. 2 (longitudinal load transfer); " + _PACEJKA + " (load sensitivity)"),
    ("drag_roll_pitch", "-(M / L)(1 / C*_f + 1 / C*_r) g, M = -RG X L + theta (T_f dN_yf + T_r dN_yr) per a_y",
     "Milliken 1995, ch. 18 (roll moments); this module's derivation (issue 28, NOTES B.3)"),
    ("ply_steer_load_transfer", "(-k_f dN_yf / C*_f + k_r dN_yr / C*_r) g, k_i = dF_y0,i/d(dN_yi) of the axle's "
     "two wheels (ply steer, conicity; one the law's mirror image)", _GILLESPIE + "; " + _PACEJKA),
    ("rolling_resistance_couple", "-(M / L)(1 / C*_f + 1 / C*_r) g, M = -(T_f f'_f dN_yf + T_r f'_r dN_yr), "
     "f'_i = -dM_y/dF_z / R_e", "Gillespie 1992, ch. 4 (rolling resistance); " + _PACEJKA),
    ("front_longitudinal_force_steer", "-F_xf (L / u^2 + K*) g / C*_f, F_xf = p (F_D + R_f + R_r) - R_f, "
     "R_i = -2 M_y,i / R_e", "Gillespie 1992, ch. 6 (steady-state cornering)"),
    ("ply_steer_steer_couple", "-(M / L)(1 / C*_f + 1 / C*_r) g, M = -(T_f / 2)(L / u^2 + K*)(F_y0,fl - F_y0,fr) per "
     "a_y: the front wheels' zero-slip forces (opposite on mirror-image tires) turned by the steer",
     _PACEJKA + " (ply steer); Gillespie 1992, ch. 6"),
    ("drive_slip", "-(W_f / C*_f^2)(C_f,kappa - C*_f) + (W_r / C*_r^2)(C_r,kappa - C*_r), C_i,kappa the law's at "
     "the slip ratio of the axle's F_x", _PACEJKA + " (combined slip)"),
)


def _at_speed_rows(vehicle, speed, gravity, tires):
    """The full vehicle's speed- and law-dependent rows [rad/g] (:func:`understeer_budget`), by name."""
    from vehdyn.handling.axle_tires import cornering_stiffness, wheel_loads, wheel_slip_ratio
    from vehdyn.handling.roll_balance import steady_roll

    m, G, s, t, aero = vehicle.mass, vehicle.geometry, vehicle.suspension, vehicle.tires, vehicle.aero
    L = G.wheelbase
    W = vehicle.static_axle_loads(gravity)  # the axle forces' distribution F_i = W_i a_y / g
    T = (G.front_track, G.rear_track)
    axles = ("front", "rear")
    law = tuple(None if tires is None else tires[i] for i in range(2))
    step = 20.0  # [N] load step of the load derivatives (central differences)

    def stiffness(i, wheel_load, kappa=0.0):
        return cornering_stiffness(vehicle, axles[i], law[i], wheel_load=wheel_load, slip_ratio=kappa, speed=speed)

    def wheel(i, side, wheel_load, kappa=0.0):
        return wheel_loads(vehicle, axles[i], side, wheel_load, kappa, 0.0, 0.0, speed, law[i])

    # aerodynamic loads: drag F_D at the sprung CG, lift Z_i on the axles; the pitch theta of the springs
    # and tires in series, with the gravity moment m g h theta of the pitched body
    q = 0.5 * aero.air_density * aero.frontal_area * speed**2
    drag, lift = q * aero.drag_coefficient, (q * aero.front_lift_coefficient, q * aero.rear_lift_coefficient)
    e = (1 / s.front_spring_rate + 1 / t.vertical_stiffness, 1 / s.rear_spring_rate + 1 / t.vertical_stiffness)
    c_theta = (e[0] + e[1]) / (2 * L)
    theta_lift = (lift[0] * e[0] - lift[1] * e[1]) / (2 * L)
    X = (drag * m.sprung_cg_height + m.mass * gravity * m.cg_height * theta_lift) / (L - m.mass * gravity
                                                                                   * m.cg_height * c_theta)
    theta = c_theta * X + theta_lift  # nose up [rad]
    N = (W[0] - X - lift[0], W[1] + X - lift[1])  # the running axle loads

    static = tuple(stiffness(i, W[i] / 2) for i in range(2))
    C = tuple(stiffness(i, N[i] / 2) for i in range(2))  # the law's, at the running loads
    file_C = (t.front_cornering_stiffness, t.rear_cornering_stiffness)
    K_law = (W[0] / C[0] - W[1] / C[1]) / gravity  # [rad/(m/s^2)]
    rows = {"law_cornering_stiffness": W[0] / static[0] - W[1] / static[1] - (W[0] / file_C[0] - W[1] / file_C[1]),
            "aero_load_transfer": W[0] / C[0] - W[1] / C[1] - (W[0] / static[0] - W[1] / static[1])}

    roll = steady_roll(vehicle, gravity=gravity)
    transfer = roll.load_transfer  # dN_yi per a_y, the outer wheels' gain
    flexibility = 1 / C[0] + 1 / C[1]
    yaw = -roll.roll_gradient * X * L + theta * (T[0] * transfer[0] + T[1] * transfer[1])
    rows["drag_roll_pitch"] = -gravity * yaw / L * flexibility

    # the axle's force at zero slip under the transfer (SAE, a right turn: the left wheel gains dN_y)
    k, rolling, rolling_slope = [], [], []
    for i in range(2):
        half = N[i] / 2
        fy0 = [(-wheel(i, side, half + step)[1] + wheel(i, side, half - step)[1]) / (2 * step)
               for side in ("left", "right")]  # dF_y,SAE/dF_z of each wheel
        k.append(fy0[0] - fy0[1])
        my = [wheel(i, "left", half + sign * step)[2] for sign in (1, 0, -1)]
        rolling.append(-2 * my[1] / t.rolling_radius)  # R_i [N], both wheels
        rolling_slope.append(-(my[0] - my[2]) / (2 * step) / t.rolling_radius)  # f'_i [-]
    rows["ply_steer_load_transfer"] = gravity * (-k[0] * transfer[0] / C[0] + k[1] * transfer[1] / C[1])
    couple = -(T[0] * rolling_slope[0] * transfer[0] + T[1] * rolling_slope[1] * transfer[1])
    rows["rolling_resistance_couple"] = -gravity * couple / L * flexibility

    # the axles' longitudinal forces in the steady run: the drive torque (share p in front) against drag
    # and rolling resistance; the free-rolling or driven front wheels' F_x turns with the steer
    p = vehicle.driveline.front_drive_fraction
    thrust = drag + rolling[0] + rolling[1]
    fx = (p * thrust - rolling[0], (1 - p) * thrust - rolling[1])
    steer = L / speed**2 + K_law  # the steer angle per a_y [rad/(m/s^2)]
    rows["front_longitudinal_force_steer"] = -gravity * fx[0] * steer / C[0]
    # the front wheels' forces at zero slip (SAE) along the steered wheels' x: a yaw couple
    ply = [-wheel(0, side, N[0] / 2)[1] for side in ("left", "right")]
    rows["ply_steer_steer_couple"] = gravity * (T[0] / 2) * steer * (ply[0] - ply[1]) / L * flexibility
    kappa = []
    for i in range(2):
        try:
            kappa.append(wheel_slip_ratio(vehicle, axles[i], N[i] / 2, fx[i] / 2, speed, law[i]))
        except ParameterError as error:
            raise ParameterError(f"understeer_budget at speed = {speed} m/s needs the {axles[i]} tire law's "
                                 f"longitudinal force ({fx[i] / 2:.4g} N per wheel to hold the speed): {error}",
                                 key="tires", value=law[i]) from error
    C_kappa = tuple(stiffness(i, N[i] / 2, kappa[i]) for i in range(2))
    rows["drive_slip"] = -W[0] * (C_kappa[0] - C[0]) / C[0]**2 + W[1] * (C_kappa[1] - C[1]) / C[1]**2
    return rows


def vehicle_roll_understeer(vehicle, gravity: float = GRAVITY, tires=None) -> tuple[float, float]:
    r"""The roll-steer and camber-thrust terms of the understeer gradient [rad/g].

    .. math::

        K_{roll\,steer} = (\varepsilon_f - \varepsilon_r) RG, \qquad
        K_{camber} = -\frac{C_{\gamma f}}{C_f} \frac{d\gamma_f}{dA} + \frac{C_{\gamma r}}{C_r} \frac{d\gamma_r}{dA},
        \quad \frac{d\gamma_i}{dA} = -\left(RG + g_i \frac{T_i}{2} RG_{si}\right)

    RG the body's roll per g and RG_si its roll on axle i's springs (:func:`vehdyn.handling.steady_roll`,
    the full vehicle's), eps_i the roll steer [rad/rad] (SAE, applied to the body roll as the full vehicle
    does), g_i the camber gain [rad/m], C_gamma,i the axle's SAE camber stiffness
    (:func:`vehdyn.handling.axle_tires.camber_stiffness`), C_i the file's axle cornering stiffness.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle.
    gravity : float, optional
        g [m/s^2].
    tires : tuple of TireModel, optional
        (front, rear) laws for the camber stiffness (default the vehicle's); read only with camber gains.

    Returns
    -------
    tuple of float
        (roll steer, camber thrust) [rad/g].
    """
    from vehdyn.handling.axle_tires import camber_stiffness
    from vehdyn.handling.roll_balance import steady_roll

    s, G = vehicle.suspension, vehicle.geometry
    gains = (s.front_camber_gain, s.rear_camber_gain)
    steer = s.front_roll_steer - s.rear_roll_steer
    if steer == 0.0 and gains == (None, None):
        return 0.0, 0.0
    roll = steady_roll(vehicle, gravity=gravity)
    rg = roll.roll_gradient * gravity
    camber = 0.0
    if gains != (None, None):
        C = (vehicle.tires.front_cornering_stiffness, vehicle.tires.rear_cornering_stiffness)
        T = (G.front_track, G.rear_track)
        for i, axle in enumerate(("front", "rear")):
            dgamma = -(rg + (gains[i] or 0.0) * T[i] / 2 * roll.suspension_roll_gradient[i] * gravity)
            c_gamma = camber_stiffness(vehicle, axle, None if tires is None else tires[i])
            camber += (-1.0 if i == 0 else 1.0) * c_gamma / C[i] * dgamma
    return float(steer * rg), float(camber)


def understeer_budget(vehicle, speed=None, *, gravity: float = GRAVITY, tires=None):
    r"""The understeer budget of a vehicle: one row per term, in deg/g, with its formula and reference.

    Rows (Gillespie 1992, ch. 6, Table 6.1; Milliken & Milliken 1995, ch. 5 and 18), W_i the static
    axle loads, C_i the axle cornering stiffnesses of the file, RG the roll per g of
    :func:`vehdyn.handling.steady_roll`:

    .. math::

        K = \underbrace{\frac{W_f}{C_f} - \frac{W_r}{C_r}}_{\text{weight distribution}}
          + \underbrace{0}_{\text{load transfer}}
          + K_{camber} + \underbrace{(\varepsilon_f - \varepsilon_r) RG}_{\text{roll steer}}
          \underbrace{- c_f W_f + c_r W_r}_{\text{lateral-force compliance}}
          + \underbrace{e_f t_f W_f - e_r t_r W_r}_{\text{aligning-moment compliance}}

    * ``weight_distribution``: W_f / C_f - W_r / C_r.
    * ``lateral_load_transfer``: the tires' load sensitivity under the transfer; Gillespie's term
      is quadratic in the load transfer, so 0 in the linear limit (a_y -> 0) in which the gradient
      is defined (a law with ply steer or conicity adds a first-order part: not in the file's linear
      model; the row ``ply_steer_load_transfer`` at a speed).
    * ``camber_thrust``: camber from roll and camber gains through the law's camber stiffness
      (:func:`vehicle_roll_understeer`).
    * ``roll_steer``: (eps_f - eps_r) RG.
    * ``lateral_force_compliance_steer``: -c_f W_f + c_r W_r (``suspension.*_lateral_force_compliance_steer``,
      delta_c = c F_y positive in the sense of the force).
    * ``aligning_moment_compliance_steer``: e_f t_f W_f - e_r t_r W_r (``suspension.*_aligning_moment_compliance_steer``,
      delta_c = e M_z, M_z = -t F_y; t_i the pneumatic trails,
      :func:`vehdyn.handling.axle_tires.pneumatic_trail`).
    * ``steering_system_compliance``: (t_m + t_f) W_f / K_ss (caster trail t_m, K_ss
      :attr:`vehdyn.params.Steering.road_wheel_stiffness`): the steering torque about the kingpins
      twists the column; it enters only a gradient measured against the hand-wheel angle / N
      (``road_wheel`` False), not the road-wheel gradient.

    The road-wheel rows sum to :func:`vehdyn.handling.understeer_gradient_deg_per_g` exactly (the
    linear bicycle carries the weight distribution and the compliance steer through its effective
    cornering stiffnesses C_i / (1 - (c_i - e_i t_i) C_i); the roll terms are added there for a
    Vehicle), and that is the full vehicle's gradient from its own steady trims at low lateral
    acceleration with linear tires (``tests/handling/test_understeer_budget.py``).

    The tires' aligning torque is not a row: as in Gillespie's Table 6.1 it acts through the
    steering and suspension compliances (the two compliance rows), not as a direct yaw moment;
    none of vehdyn's models applies M_z to the yaw balance (it would add +0.24 to +0.39 deg/g to the
    shipped cars in every rung).

    **At a speed** (``speed`` given) the rows that the full vehicle (:class:`vehdyn.full_vehicle.FullVehicle`)
    adds with its tire laws and its aerodynamics follow (``at_speed`` True), each from the laws'
    own forces and moments by central differences (:mod:`vehdyn.handling.axle_tires`) at the
    *running* axle loads N_i = W_i + dN_i (the static loads moved by drag and lift). W_i stay the
    static loads: the axle forces F_i = W_i a_y / g follow from the lateral and yaw balance alone.
    With C*_i the law's axle cornering stiffness at N_i, K* = (W_f / C*_f - W_r / C*_r) / g, RG the
    roll per unit a_y and dN_yi the per-axle lateral load transfer per unit a_y of
    :func:`vehdyn.handling.steady_roll`, T_i the tracks, R_e the rolling radius, u the speed:

    .. math::

        K_{C} &= \frac{W_f}{C^0_f} - \frac{W_r}{C^0_r} - \left(\frac{W_f}{C_f} - \frac{W_r}{C_r}\right)
            \quad (C^0_i \text{ the law's at the static loads}) \\
        K_{aero} &= \frac{W_f}{C^*_f} - \frac{W_r}{C^*_r} - \left(\frac{W_f}{C^0_f} - \frac{W_r}{C^0_r}\right)
            \approx -\frac{W_f\, dN_f\, C'_f}{C_f^2} + \frac{W_r\, dN_r\, C'_r}{C_r^2}, \quad
            dN_f = -X - Z_f,\ dN_r = X - Z_r \\
        X &= \frac{F_D h_s + m g h \theta_Z}{L - m g h c_\theta}, \quad
            c_\theta = \frac{1/k_{sf} + 1/k_{sr} + 2/k_t}{2 L}, \quad \theta = c_\theta X + \theta_Z \\
        K_{drag\,roll} &= -\frac{g M_1}{L}\left(\frac{1}{C^*_f} + \frac{1}{C^*_r}\right), \quad
            M_1 = -RG\, X L + \theta (T_f dN_{yf} + T_r dN_{yr}) \\
        K_{ply} &= g\left(-\frac{k_f dN_{yf}}{C^*_f} + \frac{k_r dN_{yr}}{C^*_r}\right), \quad
            k_i = \frac{\partial (F_{y0,i,outer} + F_{y0,i,inner})}{\partial\, dN_{yi}} \\
        K_{rr} &= -\frac{g M_2}{L}\left(\frac{1}{C^*_f} + \frac{1}{C^*_r}\right), \quad
            M_2 = -(T_f f'_f dN_{yf} + T_r f'_r dN_{yr}), \quad
            f'_i = -\frac{1}{R_e}\frac{\partial M_y}{\partial F_z} \\
        K_{F_x\delta} &= -\frac{g F_{xf}}{C^*_f}\left(\frac{L}{u^2} + K^*\right), \quad
            F_{xf} = p (F_D + R_f + R_r) - R_f, \quad R_i = -\frac{2 M_{y,i}}{R_e} \\
        K_{ply\,\delta} &= -\frac{g M_3}{L}\left(\frac{1}{C^*_f} + \frac{1}{C^*_r}\right), \quad
            M_3 = -\frac{T_f}{2}\left(\frac{L}{u^2} + K^*\right)(F_{y0,fl} - F_{y0,fr}) \\
        K_{\kappa} &= -\frac{W_f}{C^{*2}_f}(C_{f,\kappa} - C^*_f) + \frac{W_r}{C^{*2}_r}(C_{r,\kappa} - C^*_r)

    * ``law_cornering_stiffness``: the law's cornering stiffness at the static loads against the
      file's ``tires.*_cornering_stiffness`` (the file's numbers are rounded or fitted).
    * ``aero_load_transfer``: drag F_D = rho c_x A u^2 / 2 at the sprung CG height h_s and lift Z_i
      move the axle loads (X the longitudinal transfer with the gravity moment of the pitched body,
      springs k_si and tires k_t in series; theta_Z the lift's pitch) and so the law's cornering
      stiffnesses (first order: the load sensitivity C'_i = dC_i / dN_i).
    * ``drag_roll_pitch``: the drag acting on the rolled body (its CG carried h_s phi out of the turn
      from the drive forces at the ground yaws the car out of the turn) less the pitch's projection
      of the roll moment onto the yaw axis (Milliken 1995, ch. 18).
    * ``ply_steer_load_transfer``: the first-order part of the lateral load transfer row: the
      zero-slip lateral forces F_y0 of a law with ply steer or conicity change with the load, and
      the axle's two wheels are mirror images (:func:`vehdyn.handling.axle_tires.wheel_loads`), so
      the axle gains a force k_i dN_yi at zero slip (Pacejka 2012, sec. 4.3.2).
    * ``rolling_resistance_couple``: equal drive torques on the two wheels of an axle leave the
      outer (loaded) wheel with more rolling resistance: a yaw couple out of the turn.
    * ``front_longitudinal_force_steer``: the front axle's longitudinal force (rolling resistance;
      with a front drive share p = ``driveline.front_drive_fraction``, its drive) turned by the steer
      angle (L / u^2 + K*) a_y into a lateral force.
    * ``ply_steer_steer_couple``: the front wheels' opposite zero-slip forces of mirror-image tires,
      turned by the steer, make a yaw couple.
    * ``drive_slip``: the slip ratio at which each axle's law makes its longitudinal force lowers
      (combined slip) or raises its cornering stiffness.

    Their sum with the road-wheel rows, ``attrs["at_speed_total_deg_per_g"]``, is the full
    vehicle's gradient from its own steady trims (Richardson-extrapolated from a_y = +-0.1 and
    +-0.2 m/s^2): the three shipped cars with their Magic Formula tires and drag, 10 to 30 m/s,
    within 0.05 % (what is left is of second order in the drag, e.g. X^2 in the pitch and the
    drag's transfer of the roll moment; ``tests/handling/test_understeer_budget_at_speed.py``).
    With linear tires (``LinearTire.from_vehicle``: load-proportional cornering stiffness, no
    rolling resistance, no ply steer, no combined slip) the law's rows are 0 (to round-off) and only
    the drag rows remain: ``aero_load_transfer`` (C' = C / F_z0) and ``drag_roll_pitch``. The rows
    are those of the full vehicle; the linear rungs have none of them, the single track some
    (the fidelity ladder judges a rung by its error against the full vehicle).

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle.
    speed : float, optional
        Forward speed [m/s]. The linear rows do not depend on it; given, the full vehicle's
        speed- and law-dependent rows are added (``at_speed`` True).
    gravity : float, optional
        g [m/s^2].
    tires : tuple of TireModel, optional
        (front, rear) laws for the camber stiffness, the pneumatic trails and the rows at a speed
        (default the vehicle's own, :func:`vehdyn.tire.tire_for_vehicle`: the Magic Formula of its
        ``.tir`` where it has one).

    Returns
    -------
    pandas.DataFrame
        Index: the term; columns ``rad_per_g`` [rad/g], ``deg_per_g`` [deg/g], ``formula``,
        ``reference``, ``road_wheel`` (bool: in the road-wheel gradient), ``at_speed`` (bool: a row
        of the full vehicle at ``speed``). ``attrs``: ``road_wheel_total_deg_per_g`` (the linear
        road-wheel rows, = :func:`vehdyn.handling.understeer_gradient_deg_per_g`),
        ``hand_wheel_total_deg_per_g``, ``at_speed_total_deg_per_g`` (the road-wheel rows and the
        rows at the speed; None without a speed) [deg/g], ``vehicle``, ``speed`` [m/s].

    Raises
    ------
    ParameterError
        For a speed that is not a positive number, a compliance without effective cornering
        stiffness (naming the field), or (at a speed) a tire law that cannot make the longitudinal
        force that holds the speed (``tires``), or a vehicle without a steady roll
        (:func:`vehdyn.handling.steady_roll`).

    References
    ----------
    .. [1] Gillespie, T. D., *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 6, Table 6.1.
    .. [2] Milliken, W. F. and Milliken, D. L., *Race Car Vehicle Dynamics*, SAE, 1995, ch. 5 and 18.

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.handling import understeer_budget
    >>> budget = understeer_budget(vehdyn.load_vehicle("sedan"))
    >>> round(budget.attrs["road_wheel_total_deg_per_g"], 4)
    0.2998
    >>> at_speed = understeer_budget(vehdyn.load_vehicle("sedan"), speed=20.0)
    >>> round(at_speed.attrs["at_speed_total_deg_per_g"], 3)
    0.363
    """
    import pandas as pd

    from vehdyn.handling.axle_tires import pneumatic_trail
    from vehdyn.handling.bicycle import vehicle_compliance_steer

    if speed is not None:
        from vehdyn.params.checks import is_number

        if not is_number(speed) or not np.isfinite(speed) or speed <= 0:
            raise ParameterError(f"speed must be a positive number [m/s], got {speed!r}", key="speed", value=speed)
    s, t = vehicle.suspension, vehicle.tires
    W_f, W_r = vehicle.static_axle_loads(gravity)
    C_f, C_r = t.front_cornering_stiffness, t.rear_cornering_stiffness
    # trails only where a field needs them (the tire law is read then)
    need_front = s.front_aligning_moment_compliance_steer != 0.0
    need_rear = s.rear_aligning_moment_compliance_steer != 0.0
    trail_f = pneumatic_trail(vehicle, "front", None if tires is None else tires[0]) if need_front else 0.0
    trail_r = pneumatic_trail(vehicle, "rear", None if tires is None else tires[1]) if need_rear else 0.0
    vehicle_compliance_steer(vehicle, (trail_f, trail_r))  # the effective stiffness check
    roll_steer, camber = vehicle_roll_understeer(vehicle, gravity, tires)
    from vehdyn.handling.steering_system import steering_system_parameters

    steering = steering_system_parameters(vehicle)
    values = {
        "weight_distribution": W_f / C_f - W_r / C_r,
        "lateral_load_transfer": 0.0,
        "camber_thrust": camber,
        "roll_steer": roll_steer,
        "lateral_force_compliance_steer": -s.front_lateral_force_compliance_steer * W_f
        + s.rear_lateral_force_compliance_steer * W_r,
        "aligning_moment_compliance_steer": s.front_aligning_moment_compliance_steer * trail_f * W_f
        - s.rear_aligning_moment_compliance_steer * trail_r * W_r,
        "steering_system_compliance": (steering.caster_trail + steering.pneumatic_trail) * W_f
        / vehicle.steering.road_wheel_stiffness,
    }
    records = [{"term": name, "rad_per_g": float(values[name]), "deg_per_g": float(np.rad2deg(values[name])),
                "formula": formula, "reference": reference, "road_wheel": name != "steering_system_compliance",
                "at_speed": False} for name, formula, reference in _ROWS]
    if speed is not None:
        rows = _at_speed_rows(vehicle, float(speed), gravity, tires)
        records += [{"term": name, "rad_per_g": float(rows[name]), "deg_per_g": float(np.rad2deg(rows[name])),
                     "formula": formula, "reference": reference, "road_wheel": True, "at_speed": True}
                    for name, formula, reference in _AT_SPEED_ROWS]
    frame = pd.DataFrame(records).set_index("term")
    linear = ~frame["at_speed"]
    road = float(frame.loc[linear & frame["road_wheel"], "deg_per_g"].sum())
    at_speed = None if speed is None else road + float(frame.loc[frame["at_speed"], "deg_per_g"].sum())
    frame.attrs.update(road_wheel_total_deg_per_g=road,
                       hand_wheel_total_deg_per_g=float(frame.loc[linear, "deg_per_g"].sum()),
                       at_speed_total_deg_per_g=at_speed,
                       vehicle=vehicle.name, speed=None if speed is None else float(speed))
    return frame


def plot_understeer_budget(budget, ax=None, measured=None):
    """Horizontal bars of an understeer budget in the textbook's form (understeer to the right).

    The linear rows blue (understeer) and red (oversteer), the hand-wheel-only row pale, the rows at
    a speed cyan and orange; the road-wheel (dashed), hand-wheel (dotted) and at-speed (dash-dotted)
    totals as vertical lines.

    Parameters
    ----------
    budget : pandas.DataFrame
        :func:`understeer_budget`'s result.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default a new figure).
    measured : dict, optional
        Gradients measured by models, ``{label: deg_per_g}`` [deg/g], drawn as vertical lines.

    Returns
    -------
    matplotlib.axes.Axes
        The axes.
    """
    from matplotlib.colors import to_rgba

    from vehdyn.plotting import new_figure

    if ax is None:
        _, axes = new_figure(height_per_row=3.6)
        ax = axes[0, 0]
    names = list(budget.index)
    values = budget["deg_per_g"].to_numpy()
    at_speed = budget["at_speed"].to_numpy() if "at_speed" in budget else np.zeros(len(names), bool)
    colours = [to_rgba(("tab:cyan" if v >= 0 else "tab:orange") if fast else ("tab:blue" if v >= 0 else "tab:red"),
                       1.0 if road else 0.45) for v, road, fast in zip(values, budget["road_wheel"], at_speed)]
    y = np.arange(len(names))[::-1]
    ax.barh(y, values, color=colours)
    labels = [n.replace("_", " ") + ("" if r else " (hand wheel)") + (" (at speed)" if fast else "")
              for n, r, fast in zip(names, budget["road_wheel"], at_speed)]
    ax.set_yticks(y, labels)
    ax.axvline(0.0, color="k", lw=0.8)
    road = budget.attrs["road_wheel_total_deg_per_g"]
    ax.axvline(road, color="k", ls="--", label=f"road-wheel total {road:.3f} deg/g")
    hand = budget.attrs["hand_wheel_total_deg_per_g"]
    ax.axvline(hand, color="0.5", ls=":", label=f"hand-wheel total {hand:.3f} deg/g")
    total = budget.attrs.get("at_speed_total_deg_per_g")
    if total is not None:
        ax.axvline(total, color="k", ls="-.", label=f"at {budget.attrs['speed']:g} m/s {total:.3f} deg/g")
    for k, (label, value) in enumerate((measured or {}).items()):
        ax.axvline(value, color=f"C{2 + k}", lw=1.0, alpha=0.8, label=f"{label} {value:.3f}")
    ax.set_xlabel("understeer gradient [deg/g] (understeer +)")
    ax.set_title(f"Understeer budget: {budget.attrs.get('vehicle', '')}")
    ax.legend(fontsize="x-small", loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=2, frameon=False)
    return ax
