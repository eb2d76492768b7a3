r"""Lateral-yaw-roll model with tire lag and the tire law's parameters at the operating point.

:class:`LateralYawRollLag` is the linear model of a vehicle's lateral, yaw and roll motion at
constant speed that the full vehicle (:class:`vehdyn.full_vehicle.FullVehicle`) reduces to for
small steer about straight running, with every parameter derived from the same vehicle file and
tire law. It extends :class:`~vehdyn.handling.LateralYawRoll` (Segel's 3-DOF model; symbols and
derivation there) by:

* **Tire lag**: each axle's force follows a transient slip angle alpha' with
  d(alpha')/dt = (u / sigma)(alpha - alpha'), sigma the vehicle's relaxation lengths (Pacejka,
  *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 7.2.1; as :class:`~vehdyn.handling.LinearBicycle`
  with ``tire_lag``).
* **Cornering stiffness at the running loads**: C_i = -dF_y/d(alpha) of the axle's two tires from
  the tire law at the axle load of steady running at speed u -- the static load, minus the aero
  lift, with the load transfer h_s F_drag / L of the drive force that holds the speed against the
  drag (drag at the sprung CG height h_s, drive at the ground; Gillespie, *Fundamentals of Vehicle
  Dynamics*, 1992, eq. 2-18). Near neutral steer at speed the yaw gain changes by several percent.
* **Running slip ratios** (:func:`running_slip_ratios`): the stiffnesses below are taken at the
  slip ratio each axle runs at -- the drive force holding the speed on the driven wheels, the
  rolling-resistance moment M_y braking the others -- since a Magic Formula's lateral force
  depends on the slip ratio (its kappa-induced ply steer S_Vyk, Pacejka 2012, eq. 4.E67, and the
  combined-slip weighting).
* **Rolling resistance under lateral load transfer**: each wheel turns steadily, R_e F_x = T + M_y,
  with equal drive torques T on the two sides of an axle (an open differential, or none), so a
  load dF_z moved onto the left wheel makes F_x,left - F_x,right = 2 e_i dF_z / R_e (e_i = dM_y/dF_z
  of one tire, negative: the loaded wheel rolls harder) and the yaw moment T_i e_i dF_z / R_e
  (track T_i): the outer wheels hold the car back, about 1.4 % of the sedan's steady steer.
* **Ply steer under lateral load transfer**: the two tires of an axle are mirror images (a law with
  a lateral force at zero slip, as in :meth:`vehdyn.handling.SingleTrack.axle_law_forces`); their
  zero-slip forces cancel at equal loads, not under a load transfer dF_z onto the left wheel, which
  adds k_i dF_z with k_i = 2 dF_y0/dF_z (SAE y; F_y0 the law's force at zero slip) when the left
  wheel is the mirror image, -2 dF_y0/dF_z when the right one is (a ``.tir`` file with ``TYRESIDE =
  'LEFT'``, see ``SingleTrack._mirrored_wheel``). The elastic
  load transfer of axle i is dF_z = -(K_i phi + C_i p) / T_i (its roll stiffness and damping over
  its track), the geometric one F_i h_rc,i / T_i. The law's load sensitivity at equal and opposite
  load changes is of second order and left out.
* **Wheels rolling with the body**: the wheel carriers of the full vehicle keep the body's
  orientation, so the unsprung masses m_u swing with the roll at their height above the roll axis
  r_w - h_ra (wheel-centre height r_w, the rolling radius): they add m_u (r_w - h_ra) to the
  coupling m_s h and m_u (r_w - h_ra)^2 to the roll inertia and the pendulum term.
* **Compliance steer** (the vehicle's ``suspension.*_lateral_force_compliance_steer`` c_i and
  ``*_aligning_moment_compliance_steer`` e_i): each axle steers by delta_c,i = (c_i - e_i t_i) F_i,
  quasi-statically, with t_i the law's pneumatic trail at the running load (M_z = -t F_y, Gillespie
  1992, Table 6.1; Milliken & Milliken 1995, ch. 18). The force F_i is that of the lagged slip, so
  the compliance steer is explicit in the states; it enters the kinematic slip that the lag
  follows. With a linear law this is the model without compliance with the effective stiffness
  C_i / (1 - (c_i - e_i t_i) C_i) and the relaxation length sigma_i / (1 - (c_i - e_i t_i) C_i).
* **Lateral acceleration of the total CG**: a_y = (F_f + F_r) / m, what an accelerometer at the
  CG reads (the non-rolling frame's dv/dt + u r of :class:`LateralYawRoll` differs from it by
  m_s h dp/dt / m while the body rolls).

It leaves out what the full vehicle adds beyond small steer at constant speed: tire saturation,
the speed change, the pitch and heave motion and the wheels' spin. Roll centres are taken on the
ground by the shipped vehicles; with raised roll centres the full vehicle's wheel carriers still
move with the body, and the coupling of the unsprung masses above is an approximation.
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import LinearModel
from vehdyn.params import Vehicle
from vehdyn.signals import STEER_INPUTS, Signal
from vehdyn.units import GRAVITY
from vehdyn.handling.bicycle import linear_model_speed
from vehdyn.handling.lateral_yaw_roll import _OUTPUTS as _LYR_OUTPUTS, _STATES as _LYR_STATES, lateral_yaw_roll_parameters

__all__ = ["LateralYawRollLag", "running_axle_loads", "running_slip_ratios"]

# the states and outputs of LateralYawRoll, with the two transient slip angles and the lateral
# acceleration of the total CG
_STATES = _LYR_STATES + (
    Signal("front_transient_slip_angle", "rad", "front axle's lagged slip angle alpha'_f (SAE)"),
    Signal("rear_transient_slip_angle", "rad", "rear axle's lagged slip angle alpha'_r (SAE)"),
)
_OUTPUTS = (Signal("lateral_acceleration", "m/s^2", "lateral acceleration of the total CG, (F_f + F_r) / m"),) \
    + _LYR_OUTPUTS[1:]


def running_axle_loads(vehicle: Vehicle, speed: float, gravity: float = GRAVITY) -> tuple[float, float]:
    """Front and rear axle loads in steady straight running.

    The static loads minus each axle's aero lift, with h_s F_drag / L moved from the front to the
    rear axle by the drive force that holds the speed (drag at the sprung CG height h_s, the
    drive at the ground; Gillespie 1992, eq. 2-18).

    Parameters
    ----------
    vehicle : Vehicle
        Its masses, geometry and ``aero`` (drag and lift coefficients, frontal area, air density).
    speed : float
        Forward speed u [m/s].
    gravity : float, optional
        g [m/s^2] (default :data:`vehdyn.units.GRAVITY`).

    Returns
    -------
    front, rear : float
        Axle loads [N] (both wheels of the axle).
    """
    aero, geometry = vehicle.aero, vehicle.geometry
    front, rear = vehicle.static_axle_loads(gravity)
    half = 0.5 * aero.air_density * aero.frontal_area * speed**2
    shift = vehicle.mass.sprung_cg_height * half * aero.drag_coefficient / geometry.wheelbase
    return (front - half * aero.front_lift_coefficient - shift, rear - half * aero.rear_lift_coefficient + shift)


def running_slip_ratios(vehicle: Vehicle, tires, loads, speed: float) -> tuple[float, float]:
    """Front and rear longitudinal slip ratios of the wheels in steady straight running.

    Each wheel turns steadily, so R_e F_x = T + M_y (drive torque T, the law's rolling-resistance
    moment M_y, ISO-W): a wheel without drive torque brakes the car by F_x = M_y / R_e, and the drive
    torque, split by ``driveline.front_drive_fraction``, makes the four F_x add up to the drag. The
    slip ratio of each axle is the one at which the law gives that F_x at half the axle load
    (four steps of Newton's method on the law; M_y taken at the slip of the previous iterate).

    Parameters
    ----------
    vehicle : Vehicle
        Its rolling radius, ``aero`` (drag) and ``driveline.front_drive_fraction``.
    tires : sequence of two TireModel
        The laws of one front and one rear tire (ISO-W, as :mod:`vehdyn.tire` gives them).
    loads : sequence of two float
        Front and rear axle loads [N] (e.g. :func:`running_axle_loads`).
    speed : float
        Forward speed u [m/s].

    Returns
    -------
    front, rear : float
        Slip ratios kappa [-] (ISO-W: positive driving).
    """
    radius = vehicle.tires.rolling_radius
    aero = vehicle.aero
    drag = 0.5 * aero.air_density * aero.frontal_area * aero.drag_coefficient * speed**2
    share = vehicle.driveline.front_drive_fraction
    half = 0.5 * np.asarray(loads, dtype=float)
    kappa, step = np.zeros(2), 1e-5
    for _ in range(4):
        evaluated = [t.forces(np.full(2, fz), np.array([k, k + step]), np.zeros(2), 0.0, np.full(2, speed))
                     for t, fz, k in zip(tires, half, kappa)]
        my = np.array([2.0 * float(f.my[0]) for f in evaluated])  # per axle
        torque = drag * radius - my.sum()  # the drive torque of all four wheels
        target = 0.5 * (np.array([share, 1.0 - share]) * torque + my) / radius  # F_x per tire
        fx = np.array([float(f.fx[0]) for f in evaluated])
        slope = np.array([(float(f.fx[1]) - float(f.fx[0])) / step for f in evaluated])
        kappa = kappa + (target - fx) / slope
    return float(kappa[0]), float(kappa[1])


def _net_compliance_steer(vehicle, axle, stiffness, trail):
    """c_i - e_i t_i [rad/N] of an axle (``Suspension.compliance_steer``), checked
    against the axle's cornering stiffness at the running load: (c - e t) C >= 1 leaves no effective
    cornering stiffness (ParameterError naming the lateral-force field)."""
    net = vehicle.suspension.compliance_steer(axle, trail)
    if net * stiffness >= 1.0:
        key = f"suspension.{axle}_lateral_force_compliance_steer"
        raise ParameterError(f"{key} = {getattr(vehicle.suspension, key.partition('.')[2]):g} rad/N with the "
                             f"aligning-moment compliance and the trail {trail:.4g} m makes (c - e t) C = "
                             f"{net * stiffness:.6g} >= 1 at the running cornering stiffness {stiffness:.6g} N/rad: "
                             f"no effective cornering stiffness", key=key,
                             value=getattr(vehicle.suspension, key.partition(".")[2]))
    return net


def _axle_law(tire, axle_load, kappa=0.0):
    """(C, k, e, t): cornering stiffness [N/rad] of the axle's two tires, the SAE axle force per unit
    load moved onto the left wheel [N/N] (ply steer of mirrored tires), one tire's dM_y/dF_z [m]
    (rolling-resistance moment per load) and the pneumatic trail -dM_z/dF_y [m] (0 for a law without
    an aligning moment), from the law at half the axle load and the running slip ratio ``kappa``
    (central differences)."""
    from vehdyn.handling.single_track import SingleTrack

    load = 0.5 * float(axle_load)
    if load <= 0:
        raise ParameterError(f"axle load {axle_load} N at this speed (aero lift): no tire force", key="speed",
                             value=axle_load)
    step, dz = 1e-4, 0.01 * load
    fz = np.array([load, load, load + dz, load - dz])
    alpha = np.array([step, -step, 0.0, 0.0])
    out = tire.forces(fz, np.full(4, kappa), alpha, 0.0, np.full(4, 20.0))  # one batched call
    fy = np.asarray(out.fy, dtype=float)
    my = np.asarray(out.my, dtype=float)
    stiffness = abs(fy[0] - fy[1]) / step  # two tires: 2 |dF_y/d alpha|
    # 2 dF_y0/dF_z with the left wheel mirrored (SAE: the ISO-W axle force -F_y0(F + d) + F_y0(F - d)
    # flipped); the opposite sign where the law is a left tire and the right wheel is mirrored
    side = SingleTrack._mirrored_wheel(tire, SingleTrack._needs_mirror(tire, load))
    ply = {"left": 1.0, "right": -1.0, None: 0.0}[side] * (fy[2] - fy[3]) / dz
    rolling = (my[2] - my[3]) / (2.0 * dz)  # dM_y/dF_z of one tire [m]
    mz = getattr(out, "mz", None)
    trail = 0.0 if mz is None else -float(np.asarray(mz)[0] - np.asarray(mz)[1]) / float(fy[0] - fy[1])
    return stiffness, ply, rolling, trail


class LateralYawRollLag(LinearModel):
    r"""Lateral-yaw-roll model with tire lag, parameters from the tire law at the running loads.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle file: masses, inertias, geometry, suspension, tires (relaxation lengths,
        rolling radius), aero and driveline.
    speed : float
        Forward speed u [m/s] (the cornering stiffnesses are those of straight running at it),
        >= :data:`~vehdyn.handling.bicycle.LINEAR_MIN_SPEED`.
    front_tire, rear_tire : TireModel, optional
        Laws of one front and one rear tire; default the vehicle's
        (:func:`vehdyn.tire.tire_for_vehicle`).
    gravity : float, optional
        g [m/s^2] (default :data:`vehdyn.units.GRAVITY`).

    Attributes
    ----------
    cornering_stiffness : tuple of float
        (C_f, C_r), the axles' cornering stiffnesses at the running loads and slip ratios [N/rad].
    ply_steer_load_coefficient : tuple of float
        (k_f, k_r), the SAE axle force per unit load moved onto the left wheel [N/N].
    compliance_steer : tuple of float
        (c_f - e_f t_f, c_r - e_r t_r), the net compliance steer per unit axle force [rad/N].
    speed : float
        [m/s].
    mass_matrix : ndarray, shape (6, 6)
        M of M dx/dt = ... over the states.

    Notes
    -----
    :class:`~vehdyn.handling.LateralYawRoll` with the tire lag of each axle, the unsprung masses
    m_u rolling with the body at their height r_w - h_ra above the roll axis, and the axle forces
    and the rolling resistance's yaw moment under the lateral load transfer (derivation and
    assumptions in the module docstring):

    .. math::

        m (\dot v + u r) + c \dot p &= F_f + F_r, \qquad
        I_z \dot r - I_{xz} \dot p = a F_f - b F_r + \sum_i \frac{T_i e_i}{R_e} \Delta F_{z,i}, \\
        c (\dot v + u r) - I_{xz} \dot r + I_x' \dot p &= -(K_\phi - g c') \phi - C_\phi p,
        \qquad \dot\phi = p, \\
        \frac{\sigma_i}{u} \dot\alpha_i' + \alpha_i' &= \alpha_i - (c_i - e_i t_i) F_i, \qquad
        F_i = -C_i \alpha_i' + k_i \Delta F_{z,i}, \qquad
        \Delta F_{z,i} = -\frac{K_{\phi,i} \phi + C_{\phi,i} p}{T_i} + \frac{h_{rc,i}}{T_i} F_i, \\
        c &= m_s h + m_u (r_w - h_{ra}), \quad c' = m_s h \cos\theta + m_u (r_w - h_{ra}), \quad
        I_x' = I_x + m_u (r_w - h_{ra})^2, \quad a_y = \frac{F_f + F_r}{m}

    with alpha_i the kinematic slip angles of :class:`~vehdyn.handling.LateralYawRoll` (with roll
    steer), sigma_i the relaxation lengths, C_i the cornering stiffnesses of the tire law at the
    running axle load and slip ratio (:func:`running_axle_loads`, :func:`running_slip_ratios`),
    c_i - e_i t_i the net compliance steer per unit axle force (t_i the law's pneumatic trail at the
    running load), k_i the ply-steer force per unit load transfer of mirrored tires, e_i = dM_y/dF_z of one tire,
    T_i the tracks, h_rc,i the roll-centre heights, K_phi,i and C_phi,i the axles' roll stiffness
    and damping, R_e the rolling radius. With zero relaxation length the tire lag is that of a
    very short one (1 mm).

    States ``lateral_velocity``, ``yaw_rate``, ``roll_rate``, ``roll_angle``,
    ``front_transient_slip_angle``, ``rear_transient_slip_angle``; inputs ``front_steer_angle``,
    ``rear_steer_angle``; outputs as :class:`~vehdyn.handling.LateralYawRoll` with the lateral
    acceleration of the total CG.

    References
    ----------
    .. [1] L. Segel, "Theoretical prediction and experimental substantiation of the response of the
       automobile to steering control", Proc. IMechE Automobile Division, 1956 (the 3-DOF model).
    .. [2] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 7.2.1 (the relaxation-length tire lag) and eq. 4.E67 (the Magic Formula's
       kappa-induced ply steer S_Vyk).
    .. [3] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, eq. 2-18 (load transfer
       of the drive force).
    .. [4] G. Mastinu and M. Ploechl (eds.), *Road and Off-Road Vehicle System Dynamics Handbook*,
       CRC Press, 2014, sec. 20.5.
    """

    phenomena = frozenset({"lateral", "yaw", "roll", "tire_lag"})

    def __init__(self, vehicle: Vehicle, speed: float, *, front_tire=None, rear_tire=None,
                 gravity: float = GRAVITY):
        from vehdyn.tire import tire_for_vehicle

        if not isinstance(vehicle, Vehicle):
            raise ParameterError(f"vehicle must be a vehdyn Vehicle, got {type(vehicle).__name__}", key="vehicle",
                                 value=vehicle)
        u = linear_model_speed(speed, "LateralYawRollLag")
        p = lateral_yaw_roll_parameters(vehicle, gravity=gravity)
        g, s, masses = vehicle.geometry, vehicle.suspension, vehicle.mass
        tires = [tire_for_vehicle(vehicle, axle) if t is None else t
                 for axle, t in (("front", front_tire), ("rear", rear_tire))]
        loads = running_axle_loads(vehicle, u, gravity)
        slips = running_slip_ratios(vehicle, tires, loads, u)
        (cf, kf, ef, tf), (cr, kr, er, tr) = (_axle_law(t, load, k) for t, load, k in zip(tires, loads, slips))
        self.cornering_stiffness, self.ply_steer_load_coefficient = (cf, cr), (kf, kr)
        compliance = tuple(_net_compliance_steer(vehicle, axle, c, t)
                           for axle, c, t in (("front", cf, tf), ("rear", cr, tr)))
        self.compliance_steer = compliance
        sigma = [max(x, 1e-3) for x in (vehicle.tires.front_relaxation_length, vehicle.tires.rear_relaxation_length)]
        axis = g.front_roll_centre_height + (g.rear_roll_centre_height - g.front_roll_centre_height) \
            * g.sprung_cg_to_front_axle / g.wheelbase
        arm_u = vehicle.tires.rolling_radius - axis
        m_u = masses.front_unsprung_mass + masses.rear_unsprung_mass
        coupling = p.sprung_mass * p.roll_arm + m_u * arm_u
        roll_inertia = p.roll_inertia + m_u * arm_u**2
        pendulum = (p.sprung_mass * p.roll_arm * np.cos(p.roll_axis_inclination) + m_u * arm_u) * gravity
        if p.roll_stiffness <= pendulum:
            raise ParameterError(f"roll stiffness {p.roll_stiffness:.6g} N*m/rad does not exceed the pendulum term "
                                 f"{pendulum:.6g} N*m/rad", key="suspension", value=p.roll_stiffness)
        a, b, m = p.a, p.b, p.mass
        n = 6
        # kinematic slip angles alpha = S x + T delta (SAE), as LateralYawRoll
        S = np.zeros((2, n))
        S[0, :4] = [1.0 / u, a / u, 0.0, -p.front_roll_steer]
        S[1, :4] = [1.0 / u, -b / u, 0.0, -p.rear_roll_steer]
        T = -np.eye(2)
        # axle forces F_i = (-C_i alpha'_i + k_i dFz_el,i) / (1 - k_i h_rc,i / T_i)
        # and the yaw moment of the rolling resistance's left-right difference, track * e_i dF_z / R_e
        F_x, yaw_moment = np.zeros((2, n)), np.zeros(n)
        for i, (c, k, e, kroll, damping, track, rc) in enumerate((
                (cf, kf, ef, vehicle.front_roll_stiffness, s.front_damping, g.front_track, g.front_roll_centre_height),
                (cr, kr, er, vehicle.rear_roll_stiffness, s.rear_damping, g.rear_track, g.rear_roll_centre_height))):
            elastic = np.zeros(n)  # dF_z,el onto the left wheel
            elastic[3] = -kroll / track
            elastic[2] = -damping * track / 2.0  # C_phi,i / T_i with C_phi,i = c T^2 / 2
            F_x[i, 4 + i] = -c
            F_x[i] += k * elastic
            F_x[i] /= 1.0 - k * rc / track
            yaw_moment += track * e / vehicle.tires.rolling_radius * (elastic + F_x[i] * rc / track)
        M = np.eye(n)
        M[:4, :4] = [[m, 0.0, coupling, 0.0], [0.0, p.yaw_inertia, -p.roll_yaw_product, 0.0],
                     [coupling, -p.roll_yaw_product, roll_inertia, 0.0], [0.0, 0.0, 0.0, 1.0]]
        Q_x, Q_u = np.zeros((n, n)), np.zeros((n, 2))
        Q_x[0] = F_x[0] + F_x[1]
        Q_x[0, 1] -= m * u
        Q_x[1] = a * F_x[0] - b * F_x[1] + yaw_moment
        Q_x[2, 1] = -coupling * u
        Q_x[2, 2] = -p.roll_damping
        Q_x[2, 3] = -(p.roll_stiffness - pendulum)
        Q_x[3, 2] = 1.0
        # compliance steer delta_c,i = (c_i - e_i t_i) F_i, quasi-static and explicit in the states
        # (F_i is the lagged slip's force): it steers the kinematic slip that the tire lag follows
        S = S - np.array(compliance)[:, None] * F_x
        for i in range(2):
            rate = u / sigma[i]
            Q_x[4 + i] = rate * S[i]
            Q_x[4 + i, 4 + i] -= rate
            Q_u[4 + i] = rate * T[i]
        A, B = np.linalg.solve(M, Q_x), np.linalg.solve(M, Q_u)
        ay = (F_x[0] + F_x[1]) / m
        eye = np.eye(n)
        C = np.vstack([ay, eye[0] / u, eye[1], eye[0], eye[3], eye[2], S[0], S[1], ay / u**2, F_x[0], F_x[1]])
        D = np.vstack([np.zeros((6, 2)), T[0], T[1], np.zeros((3, 2))])
        self.speed = u
        self.mass_matrix = M
        super().__init__(A, B, C, D, states=_STATES, inputs=STEER_INPUTS, outputs=_OUTPUTS,
                         name=f"LateralYawRollLag at {u:g} m/s", phenomena=self.phenomena)

    def __repr__(self) -> str:
        return (f"<LateralYawRollLag at {self.speed:g} m/s: C_f={self.cornering_stiffness[0]:.6g}, "
                f"C_r={self.cornering_stiffness[1]:.6g} N/rad>")
