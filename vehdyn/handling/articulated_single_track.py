"""Nonlinear articulated single track: a towing vehicle and a trailer, any tire law, through standstill.

Two rigid bodies in the road plane joined by a hitch (a pin: ball coupling or fifth wheel), each
axle lumped on the centre line as in :class:`~vehdyn.handling.SingleTrack`, whose tire machinery
(tire laws through :mod:`vehdyn.tire`, ISO-W/SAE conversion, relaxation states, the low-speed
damping and the sliding limit of the deflections, the friction ellipse of force mode) is reused
here unchanged: see :mod:`vehdyn.handling.single_track` for those equations and their references.

Geometry and signs as in :mod:`vehdyn.handling.car_trailer` (SAE axes on each body): hitch h
behind the towing vehicle's CG (``vehicle.geometry.b + trailer.hitch_behind_rear_axle``), trailer
CG e behind the hitch, trailer axle f behind the trailer CG, l_t = e + f, articulation angle
theta = psi - psi_t (towing vehicle's yaw minus the trailer's), trailer yaw rate r_t = r - dtheta/dt.

Unit vectors of the trailer in the towing vehicle's axes: t = (cos theta, -sin theta) (forward),
n = (sin theta, cos theta) (right). Accelerations (towing vehicle's axes)::

    a_1 = (du/dt - v r,  dv/dt + u r)                                  towing-vehicle CG
    a_h = a_1 + (h r^2, -h dr/dt)                                     hitch
    a_t = a_h - e (dr_t/dt) n + e r_t^2 t                             trailer CG

Newton–Euler of both bodies with the hitch force H (of the trailer on the towing vehicle; the
trailer feels -H), F_1, M_1 the tire (and drag, external) force and moment on the towing vehicle,
F_t the trailer's axle force (X_t along t, Y_t along n) plus an external force at its CG::

    m a_1 = F_1 + H,          I dr/dt     = M_1 - h H_y
    m_t a_t = F_t - H,        I_t dr_t/dt = -e (H . n) - f Y_t + M_t,ext

Eliminating H leaves four equations linear in (du/dt, dv/dt, dr/dt, dr_t/dt), solved at every
call (a 4 x 4 system per batch member); H is then an output. For small angles at constant speed
this is exactly :class:`~vehdyn.handling.LinearCarTrailer` (tested to 1e-6 with linear tires).
References: Ellis, *Vehicle Dynamics*, 1969, ch. 10; Pacejka, *Tire and Vehicle Dynamics*, 3rd
ed., 2012, sec. 1.3.3; Karnopp, *Vehicle Dynamics, Stability, and Control*, 2nd ed., 2013, ch. 9.

Trailer axle velocity in the trailer's axes (exact)::

    V_x = u cos(theta) - (v - h r) sin(theta),     V_y = u sin(theta) + (v - h r) cos(theta) - l_t r_t

Normal loads: the trailer's static tongue load F_zh = m_t g f / l_t rests on the hitch and moves
load between the towing vehicle's axles (front -F_zh (h - b)/L, rear +F_zh (h + a)/L), then the
towing vehicle's own quasi-static longitudinal load transfer of SingleTrack acts on top; the
trailer axle carries m_t g e / l_t. Not modelled: the trailer's pitch and the load transfer
through the hitch height under braking (both bodies' longitudinal inertia forces act at ground
level here) and roll.

Crosswind (input ``wind_velocity_lateral`` w, the air's velocity along the towing vehicle's y axis):
the side-force law of :mod:`vehdyn.handling.crosswind` on each body, F_w(u, w) on the towing vehicle
at its centre of pressure x_p (as :class:`~vehdyn.handling.SingleTrack`) and F_w(V_x, w cos(theta))
on the trailer (its own forward speed and the wind's component across it) along n at its centre of
pressure d_p behind the hitch (``trailer.centre_of_pressure_behind_hitch``), which adds
-(d_p - e) F_wt to the trailer's moment about its CG. Linearized it is the wind input of
:class:`~vehdyn.handling.LinearCarTrailer` (``crosswind=True``).

Longitudinal input is force mode only (axle forces ``front_longitudinal_force``,
``rear_longitudinal_force``, ``trailer_longitudinal_force`` in wheel axes), clipped at mu F_z,
with the friction ellipse taking lateral force away (SingleTrack's force mode). A braking demand
beyond the friction limit (demand < -mu F_z) locks the axle: it then slides, and its force is
the Coulomb friction force against its sliding velocity V = (V_x, V_y) in wheel axes,
-mu F_z V / sqrt(|V|^2 + v_s^2) with v_s = :data:`LOCKED_SLIDING_SPEED` (Wong, *Theory of Ground
Vehicles*, 4th ed., 2008, sec. 1.4: a locked tire cannot resist sideways sliding better than its
sliding friction). The locked axle's braking force therefore also acts sideways as the axle
slides out, vanishes at standstill (no backward push) and leaves the axle no cornering grip: what
makes a tractor jackknife (locked drive axle) or a trailer swing out (locked trailer axle). Wheel
spin states (SingleTrack's ``wheel_spin=True``) are not offered here. The locked axle's tire
deflection keeps following its kinematic law while the axle slides; when the lock is released
that deflection's force acts at once (a short transient, not a sliding-to-rolling model).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import Model
from vehdyn.params import Trailer, Vehicle
from vehdyn.signals import Signal
from vehdyn.units import GRAVITY
from vehdyn.handling import single_track_equations as eq
from vehdyn.components.aero import aero_side_force, trailer_wind_side_force_factor
from vehdyn.components.planar import position_rates
from vehdyn.components.tire_forces import axle_tire_loads
from vehdyn.components.tire_slip import deflection_rate
from vehdyn.components.tire_setup import tire_characteristics
from vehdyn.components.xp import stack as _stack
from vehdyn.handling.single_track import SingleTrack

__all__ = ["ArticulatedSingleTrack", "ArticulationEvent", "LOCKED_SLIDING_SPEED"]


class ArticulationEvent(NamedTuple):
    """The first moment the articulation angle leaves its safe range in a simulation.

    Parameters
    ----------
    kind : str
        ``"jackknife"`` (the towing vehicle yaws faster than the trailer) or ``"trailer_swing"``.
    time : float
        [s].
    articulation_angle : float
        [rad] at that time.
    yaw_rate : float
        Of the towing vehicle [rad/s].
    trailer_yaw_rate : float
        [rad/s].
    """

    kind: str
    """``"jackknife"`` (the towing vehicle yaws faster than the trailer) or ``"trailer_swing"``"""
    time: float
    """[s]"""
    articulation_angle: float
    """[rad] at that time"""
    yaw_rate: float
    """towing vehicle [rad/s]"""
    trailer_yaw_rate: float
    """[rad/s]"""


_STATE_NAMES = ("longitudinal_velocity", "lateral_velocity", "yaw_rate", "x", "y", "yaw_angle", "articulation_angle",
                "articulation_rate", "front_lateral_deflection", "rear_lateral_deflection",
                "trailer_lateral_deflection")
_INPUT_NAMES = ("front_steer_angle", "front_longitudinal_force", "rear_longitudinal_force",
                "trailer_longitudinal_force", "external_lateral_force", "external_yaw_moment",
                "trailer_external_lateral_force", "trailer_external_yaw_moment", "wind_velocity_lateral")


LOCKED_SLIDING_SPEED = 0.1
"""[m/s]: the Coulomb force of a locked axle, -mu F_z V / sqrt(|V|^2 + v_s^2), is regularized within it."""


def _lock(forces, demand, limit, vx, vy):
    """(fx, fy, alpha, kappa) of an axle, with the locked-axle sliding force where the braking demand exceeds
    the friction limit: -mu F_z V / |V| (wheel axes, regularized within :data:`LOCKED_SLIDING_SPEED`)."""
    locked = demand < -limit
    if not np.any(locked):
        return forces
    scale = limit / np.sqrt(vx * vx + vy * vy + LOCKED_SLIDING_SPEED**2)
    return (np.where(locked, -scale * vx, forces[0]), np.where(locked, -scale * vy, forces[1])) + tuple(forces[2:])


class ArticulatedSingleTrack(Model):
    r"""Towing vehicle and trailer in the road plane, nonlinear tires, through standstill.

    Parameters
    ----------
    vehicle : Vehicle
        The towing vehicle (car or tractor).
    trailer : Trailer
        The trailer (caravan, drawbar trailer or semitrailer), placed by its
        ``hitch_behind_rear_axle``.
    front_tire, rear_tire : TireModel, optional
        Laws of ONE tire of the towing vehicle's axles (default: the vehicle's law, as in
        :class:`SingleTrack`).
    trailer_tire : TireModel, optional
        Law of ONE trailer tire (the axle force is twice the tire's at half the axle load; mirrored
        as in :class:`SingleTrack` when the law has a force at zero slip). Default: a Fiala tire
        with half the trailer's axle cornering stiffness and its friction coefficient.
    tire_lag : bool
        Tire deflection (relaxation) states on all three axles (default True; needed for low speed
        and standstill). The trailer's needs ``trailer.relaxation_length > 0``.
    low_speed_damping_speed : float
        v_l [m/s] of the low-speed tire damping (SingleTrack's; default 2).
    gravity : float
        g [m/s^2] (default :data:`vehdyn.units.GRAVITY`).

    Signals
    -------
    states
        ``longitudinal_velocity``, ``lateral_velocity``, ``yaw_rate``, ``x``, ``y``, ``yaw_angle`` of
        the towing vehicle (as SingleTrack), ``articulation_angle`` [rad], ``articulation_rate``
        [rad/s]; with tire lag ``front_lateral_deflection``, ``rear_lateral_deflection``,
        ``trailer_lateral_deflection`` [m].
    inputs
        ``front_steer_angle`` [rad]; ``front_longitudinal_force``, ``rear_longitudinal_force``,
        ``trailer_longitudinal_force`` [N] (wheel axes, + driving, - braking);
        ``external_lateral_force`` [N], ``external_yaw_moment`` [N*m] at the towing vehicle's CG;
        ``trailer_external_lateral_force``, ``trailer_external_yaw_moment`` at the trailer's CG
        (trailer axes), e.g. wind.
    outputs
        See :attr:`outputs`: accelerations, yaw rates, slips, axle forces and loads of both
        bodies, the hitch force (``hitch_longitudinal_force``, ``hitch_lateral_force``: of the
        trailer on the towing vehicle, towing vehicle's axes) and the positions.

    Notes
    -----
    Two rigid bodies joined by a pin hitch h behind the towing vehicle's CG, each axle lumped on
    the centre line, its forces from the shared tire step of :mod:`vehdyn.components` (two tires at
    half the axle load, the single track's force mode and relaxation). With u, v,
    r the towing vehicle's velocities and yaw rate (its axes), theta the articulation angle,
    r_t = r - dtheta/dt the trailer's yaw rate, t = (cos theta, -sin theta) and
    n = (sin theta, cos theta) the trailer's forward and right unit vectors in the towing
    vehicle's axes, H the hitch force of the trailer on the towing vehicle, F_1, M_1 the tire,
    drag, wind and external forces and moment on the towing vehicle, F_t the trailer's axle force
    (X_t along t, Y_t along n) plus its external and wind forces:

    .. math::

        a_1 &= (\dot u - v r, \; \dot v + u r), \qquad
        a_h = a_1 + (h r^2, \; -h \dot r), \qquad
        a_t = a_h - e \dot r_t \, n + e r_t^2 \, t, \\
        m a_1 &= F_1 + H, \qquad I \dot r = M_1 - h H_y, \\
        m_t a_t &= F_t - H, \qquad
        I_t \dot r_t = -e (H \cdot n) - f Y_t + M_{t,ext} - (d_p - e) F_{wt}, \\
        V_{x,t} &= u \cos\theta - (v - h r) \sin\theta, \qquad
        V_{y,t} = u \sin\theta + (v - h r) \cos\theta - l_t r_t

    (e the trailer CG behind the hitch, f its axle behind its CG, l_t = e + f, d_p its centre of
    pressure behind the hitch, V_t the trailer axle's velocity in its axes). Eliminating H leaves
    four equations linear in (du/dt, dv/dt, dr/dt, dr_t/dt), solved at every call. The trailer's
    static tongue load m_t g f / l_t moves load between the towing vehicle's axles; a braking
    demand beyond mu F_z locks an axle, whose force is then the Coulomb friction against its
    sliding velocity, -mu F_z V / sqrt(|V|^2 + v_s^2), v_s = :data:`LOCKED_SLIDING_SPEED`. For
    small angles at constant speed with linear tires this is :class:`~vehdyn.handling.LinearCarTrailer`
    (tested to 1e-6). Assumptions and the crosswind law in the module docstring.

    References
    ----------
    .. [1] J. R. Ellis, *Vehicle Dynamics*, Business Books, 1969, ch. 10 (articulated vehicles).
    .. [2] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       sec. 1.3.3 (the car–trailer combination).
    .. [3] D. Karnopp, *Vehicle Dynamics, Stability, and Control*, 2nd ed., CRC Press, 2013, ch. 9.
    .. [4] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley, 2008, sec. 1.4 (a locked tire
       slides: no better sideways grip than its sliding friction).
    """

    def __init__(self, vehicle: Vehicle, trailer: Trailer, front_tire=None, rear_tire=None, trailer_tire=None, *,
                 tire_lag: bool = True, low_speed_damping_speed: float = 2.0, gravity: float = GRAVITY):
        if not isinstance(trailer, Trailer):
            raise ParameterError(f"trailer must be a vehdyn Trailer (see vehdyn.load_trailer), got "
                                 f"{type(trailer).__name__}", key="trailer", value=trailer)
        # the towing vehicle's tires, relaxation lengths and constants: a SingleTrack of its own
        self.tractor = SingleTrack(vehicle, front_tire, rear_tire, tire_lag=tire_lag,
                                   low_speed_damping_speed=low_speed_damping_speed, gravity=gravity)
        self.vehicle, self.trailer, self.tire_lag = vehicle, trailer, bool(tire_lag)
        self.front_tire, self.rear_tire = self.tractor.front_tire, self.tractor.rear_tire
        g = vehicle.geometry
        self.hitch_distance = g.b + trailer.hitch_behind_rear_axle
        if self.hitch_distance <= -g.a:
            raise ParameterError(f"trailer.hitch_behind_rear_axle = {trailer.hitch_behind_rear_axle} m puts the hitch "
                                 f"at or ahead of the towing vehicle's front axle (wheelbase {g.wheelbase} m)",
                                 key="hitch_behind_rear_axle", value=trailer.hitch_behind_rear_axle)
        if self.tire_lag and trailer.relaxation_length <= 0:
            raise ParameterError("tire_lag needs a positive trailer.relaxation_length, got "
                                 f"{trailer.relaxation_length}", key="relaxation_length",
                                 value=trailer.relaxation_length)
        from vehdyn.tire import FialaTire, TireModel

        if trailer_tire is None:
            trailer_tire = FialaTire(cornering_stiffness=trailer.cornering_stiffness / 2,
                                     mu=trailer.friction_coefficient)
        if not isinstance(trailer_tire, TireModel):
            raise ParameterError(f"trailer_tire must be a vehdyn.tire.TireModel, got {type(trailer_tire).__name__}",
                                 key="trailer_tire", value=trailer_tire)
        self.trailer_tire = trailer_tire
        self.gravity = float(gravity)
        # the trailer's k_w with the towing vehicle's air density (vehdyn.handling.crosswind)
        self._trailer_wind_factor = trailer_wind_side_force_factor(trailer, vehicle.aero.air_density)
        half_load = 0.5 * trailer.static_axle_load(self.gravity)
        self._trailer_mirrored, self._trailer_peak = tire_characteristics(trailer_tire, half_load)
        self._declare_signals()

    # ------------------------------------------------------------------ signals
    def _declare_signals(self):
        by_name = {s.name: s for s in self.tractor.states}
        states = [by_name[n] for n in _STATE_NAMES[:6]]
        states += [Signal("articulation_angle", "rad", "towing vehicle's yaw angle minus the trailer's (+ right turn)"),
                   Signal("articulation_rate", "rad/s", "d/dt of the articulation angle")]
        if self.tire_lag:
            states += [by_name["front_lateral_deflection"], by_name["rear_lateral_deflection"],
                       Signal("trailer_lateral_deflection", "m",
                              "lateral deflection of the trailer tires' contact point (relaxation state)")]
        inputs = [Signal("front_steer_angle", "rad", "road-wheel steer angle of the front axle (SAE, + right)")]
        inputs += [Signal(f"{axle}_longitudinal_force", "N", f"longitudinal force demand of the {axle} axle in wheel "
                          "axes (+ driving, - braking; clipped at mu F_z)") for axle in ("front", "rear", "trailer")]
        inputs += [Signal("external_lateral_force", "N", "lateral force at the towing vehicle's CG (SAE y)"),
                   Signal("external_yaw_moment", "N*m", "yaw moment on the towing vehicle (SAE z)"),
                   Signal("trailer_external_lateral_force", "N", "lateral force at the trailer's CG (trailer y)"),
                   Signal("trailer_external_yaw_moment", "N*m", "yaw moment on the trailer (SAE z)"),
                   Signal("wind_velocity_lateral", "m/s", "lateral wind: the air's velocity along the towing "
                          "vehicle's y axis (toward +y), on both bodies at their centres of pressure")]
        outputs = [
            Signal("lateral_acceleration", "m/s^2", "lateral acceleration of the towing vehicle's CG, dv/dt + u r"),
            Signal("trailer_lateral_acceleration", "m/s^2", "lateral acceleration of the trailer's CG (trailer axes)"),
            Signal("articulation_angle", "rad", "towing vehicle's yaw angle minus the trailer's"),
            Signal("yaw_rate", "rad/s", "yaw rate r of the towing vehicle"),
            Signal("trailer_yaw_rate", "rad/s", "yaw rate of the trailer, r - dtheta/dt"),
            Signal("articulation_rate", "rad/s", "d/dt of the articulation angle"),
            Signal("lateral_velocity", "m/s", "body-frame lateral velocity v of the towing vehicle"),
            Signal("sideslip_angle", "rad", "sideslip of the towing vehicle at its CG, atan2(v, |u|)"),
            Signal("front_slip_angle", "rad", "front slip angle acting in the tire law (SAE)"),
            Signal("rear_slip_angle", "rad", "rear slip angle acting in the tire law (SAE)"),
            Signal("trailer_slip_angle", "rad", "trailer slip angle acting in the tire law (SAE, trailer axes)"),
            Signal("front_lateral_force", "N", "front axle lateral force (wheel axes)"),
            Signal("rear_lateral_force", "N", "rear axle lateral force (wheel axes)"),
            Signal("trailer_lateral_force", "N", "trailer axle lateral force (trailer axes)"),
            Signal("hitch_lateral_force", "N", "lateral force of the trailer on the towing vehicle (its y axis)"),
            Signal("hitch_longitudinal_force", "N", "longitudinal force of the trailer on the towing vehicle "
                                                    "(its x axis; negative: the trailer pulls back)"),
            Signal("longitudinal_acceleration", "m/s^2", "longitudinal acceleration of the towing vehicle, du/dt - v r"),
            Signal("longitudinal_velocity", "m/s", "body-frame forward velocity u of the towing vehicle"),
            Signal("speed", "m/s", "speed of the towing vehicle's CG"),
            Signal("front_longitudinal_force", "N", "front axle longitudinal force (wheel axes)"),
            Signal("rear_longitudinal_force", "N", "rear axle longitudinal force (wheel axes)"),
            Signal("trailer_longitudinal_force", "N", "trailer axle longitudinal force (trailer axes)"),
            Signal("front_normal_load", "N", "normal load of the front axle"),
            Signal("rear_normal_load", "N", "normal load of the rear axle (with the tongue load)"),
            Signal("trailer_normal_load", "N", "normal load of the trailer axle"),
            Signal("x", "m", "earth-fixed X of the towing vehicle's CG"),
            Signal("y", "m", "earth-fixed Y of the towing vehicle's CG (SAE)"),
            Signal("yaw_angle", "rad", "heading of the towing vehicle"),
            Signal("trailer_yaw_angle", "rad", "heading of the trailer, psi - theta"),
            Signal("trailer_axle_x", "m", "earth-fixed X of the trailer axle"),
            Signal("trailer_axle_y", "m", "earth-fixed Y of the trailer axle (SAE)"),
        ]
        self.declare(states=states, inputs=inputs, outputs=outputs)
        self._state_index = [self.state_names.index(n) if n in self.state_names else -1 for n in _STATE_NAMES]
        phenomena = {"longitudinal", "lateral", "yaw", "load_transfer", "tire_saturation", "aero"}
        if self.tire_lag:
            phenomena.add("tire_lag")
        self.phenomena = frozenset(phenomena)

    # ------------------------------------------------------------------ the equations
    def axle_law_forces(self, axle, fz, kappa, alpha, vx):
        """ISO-W axle forces from the law of one tire at half the load (:meth:`SingleTrack.axle_law_forces`).

        Parameters
        ----------
        axle : int
            0 front, 1 rear (the towing vehicle's), 2 the trailer's.
        fz : float or ndarray
            Axle normal load [N].
        kappa : float or ndarray
            Longitudinal slip ratio [-] (ISO-W).
        alpha : float or ndarray
            Slip angle [rad] (ISO-W).
        vx : float or ndarray
            Longitudinal speed of the wheel centre [m/s].

        Returns
        -------
        fx, fy : ndarray
            The axle's longitudinal and lateral forces [N] (ISO-W, both tires).
        """
        if axle == 2:
            fx, fy, _ = axle_tire_loads(eq.NUMPY, self.trailer_tire, fz, kappa, alpha, vx, self._trailer_mirrored, 1.0,
                                        False)
            return fx, fy
        return self.tractor.axle_law_forces(axle, fz, kappa, alpha, vx)

    def _evaluate(self, x, u):
        """Everything the equations give at x, u (numpy, optional batch axis), as a dict."""
        xp = eq.NUMPY
        x = np.asarray(x, dtype=float)
        u = np.asarray(u, dtype=float)
        lon, lat, r, _X, _Y, psi, theta, dtheta, rho_f, rho_r, rho_t = (eq._at(x, i) for i in self._state_index)
        steer, ff, fr, ft, ext_f, ext_m, ext_tf, ext_tm, wind = (u[i] for i in range(9))
        k = self.tractor._constants()
        p = self.tractor.parameters
        tr = self.trailer
        a, b, h = p.a, p.b, self.hitch_distance
        e, f = tr.hitch_to_cg, tr.cg_to_axle
        lt = e + f
        # the trailer's axle as the "front" axle of its own constants
        kt = k._replace(friction_coefficient=tr.friction_coefficient, front_ply_steer=float(self._trailer_mirrored))
        sigma_t = tr.relaxation_length if tr.relaxation_length > 0 else 1.0
        peak_kappa_t, peak_tan_t = self._trailer_peak
        r_t = r - dtheta
        # wheel-centre velocities in wheel axes
        cd, sd = np.cos(steer), np.sin(steer)
        vxf, vyf = lon * cd + (lat + a * r) * sd, -lon * sd + (lat + a * r) * cd
        vxr, vyr = lon, lat - b * r
        ct, st = np.cos(theta), np.sin(theta)
        hitch_lat = lat - h * r
        vxt, vyt = lon * ct - hitch_lat * st, lon * st + hitch_lat * ct - lt * r_t
        # deflection rates (0 without tire lag)
        zero = 0.0 * lon
        rate_f = rate_r = rate_t = zero
        if self.tire_lag:
            rate_f = deflection_rate(xp, vyf, vxf, rho_f, p.front_lateral_relaxation_length,
                                        k.front_peak_tan_slip_angle)
            rate_r = deflection_rate(xp, vyr, vxr, rho_r, p.rear_lateral_relaxation_length,
                                        k.rear_peak_tan_slip_angle)
            rate_t = deflection_rate(xp, vyt, vxt, rho_t, sigma_t, peak_tan_t)
        # normal loads: the tongue load enters as a (negative) lift at each axle of the towing vehicle
        tongue = tr.tongue_load(p.gravity)
        wheelbase = a + b
        lift_f = p.front_lift_factor * lon * lon + tongue * (h - b) / wheelbase
        lift_r = p.rear_lift_factor * lon * lon - tongue * (a + h) / wheelbase
        fz_f, fz_r = eq.normal_loads(xp, k, ff * cd + fr, lift_f, lift_r)
        fz_t = tr.static_axle_load(p.gravity) + zero
        tires = (self.tractor.front_tire, self.tractor.rear_tire)
        front = eq.axle_loads(xp, tires, 0, k, fz_f, vxf, vyf, zero, rho_f, zero, rate_f, zero,
                              p.front_lateral_relaxation_length, p.front_longitudinal_relaxation_length,
                              k.front_peak_slip_ratio, k.front_peak_tan_slip_angle, ff, 1.0)[:4]
        rear = eq.axle_loads(xp, tires, 1, k, fz_r, vxr, vyr, zero, rho_r, zero, rate_r, zero,
                             p.rear_lateral_relaxation_length, p.rear_longitudinal_relaxation_length,
                             k.rear_peak_slip_ratio, k.rear_peak_tan_slip_angle, fr, 1.0)[:4]
        trail = eq.axle_loads(xp, (self.trailer_tire,), 0, kt, fz_t, vxt, vyt, zero, rho_t, zero, rate_t, zero, sigma_t,
                              1.0, peak_kappa_t, peak_tan_t, ft, 1.0)[:4]
        front = _lock(front, ff, k.friction_coefficient * fz_f, vxf, vyf)
        rear = _lock(rear, fr, k.friction_coefficient * fz_r, vxr, vyr)
        trail = _lock(trail, ft, tr.friction_coefficient * fz_t, vxt, vyt)
        # crosswind on both bodies: one law (vehdyn.handling.crosswind), each at its centre of pressure
        wind_car = aero_side_force(xp, p.wind_side_force_factor, lon, wind)
        wind_trailer = aero_side_force(xp, self._trailer_wind_factor, lon * ct - hitch_lat * st, wind * ct)
        # forces on the towing vehicle (its axes) and on the trailer (along t, n)
        X1 = front[0] * cd - front[1] * sd + rear[0] - p.drag_factor * lon * np.abs(lon)
        Y1 = front[0] * sd + front[1] * cd + rear[1] + ext_f + wind_car
        M1 = a * (front[0] * sd + front[1] * cd) - b * rear[1] + ext_m + p.centre_of_pressure * wind_car
        Xt, Yt = trail[0], trail[1] + ext_tf + wind_trailer
        F3x, F3y = Xt * ct + Yt * st, -Xt * st + Yt * ct
        m1, i1, m2, i2 = p.mass, p.yaw_inertia, tr.mass, tr.yaw_inertia
        # a_t = P z + q over z = [du/dt, dv/dt, dr/dt, dr_t/dt]; t = (ct, -st), n = (st, ct)
        qx = -lat * r + h * r * r + e * r_t * r_t * ct
        qy = lon * r - e * r_t * r_t * st
        one, nil = 1.0 + zero, zero
        P0 = (one, nil, nil, -e * st + zero)
        P1 = (nil, one, -h + zero, -e * ct + zero)
        nP = tuple(st * P0[j] + ct * P1[j] for j in range(4))
        rows = [[m1 * (j == 0) + m2 * P0[j] for j in range(4)],
                [m1 * (j == 1) + m2 * P1[j] for j in range(4)],
                [i1 * (j == 2) - h * m2 * P1[j] for j in range(4)],
                [i2 * (j == 3) - e * m2 * nP[j] for j in range(4)]]
        rhs = [X1 + F3x + m1 * lat * r - m2 * qx,
               Y1 + F3y - m1 * lon * r - m2 * qy,
               M1 - h * F3y + h * m2 * qy,
               -e * Yt - f * trail[1] + ext_tm - (tr.centre_of_pressure_behind_hitch - e) * wind_trailer
               + e * m2 * (st * qx + ct * qy)]
        if np.ndim(lon) == 0:  # one vehicle: plain 4 x 4
            z = np.linalg.solve(np.array(rows, dtype=float), np.array(rhs, dtype=float))
        else:  # batch: (n, 4, 4) systems
            shape = np.shape(lon)
            M = np.stack([np.stack([np.broadcast_to(c, shape) for c in row], axis=-1) for row in rows], axis=-2)
            R = np.stack([np.broadcast_to(c, shape) for c in rhs], axis=-1)
            z = np.linalg.solve(M, R[..., None])[..., 0]
        du, dv, dr, drt = (z[..., j] for j in range(4))
        atx = du + P0[3] * drt + qx
        aty = dv - h * dr + P1[3] * drt + qy
        return dict(lon=lon, lat=lat, r=r, psi=psi, theta=theta, dtheta=dtheta, r_t=r_t, du=du, dv=dv, dr=dr, drt=drt,
                    front=front, rear=rear, trail=trail, fz=(fz_f, fz_r, fz_t), rates=(rate_f, rate_r, rate_t),
                    hitch=(F3x - m2 * atx, F3y - m2 * aty), trailer_lateral_acceleration=st * atx + ct * aty,
                    X=_X, Y=_Y, lt=lt, h=h)

    def rhs(self, t, x, u):
        """State derivatives (equations in the module docstring)."""
        s = self._evaluate(x, u)
        position = position_rates(eq.NUMPY, s["lon"], s["lat"], s["psi"])
        d = {"longitudinal_velocity": s["du"], "lateral_velocity": s["dv"], "yaw_rate": s["dr"],
             "x": position[0], "y": position[1],
             "yaw_angle": s["r"], "articulation_angle": s["dtheta"], "articulation_rate": s["dr"] - s["drt"],
             "front_lateral_deflection": s["rates"][0], "rear_lateral_deflection": s["rates"][1],
             "trailer_lateral_deflection": s["rates"][2]}
        return _stack([d[n] for n in self.state_names])

    def output(self, t, x, u):
        """Outputs (see :attr:`outputs`)."""
        s = self._evaluate(x, u)
        lon, lat, r = s["lon"], s["lat"], s["r"]
        psi_t = s["psi"] - s["theta"]
        # trailer axle: hitch (h behind the CG) then l_t along the trailer's heading
        hx = s["X"] - s["h"] * np.cos(s["psi"]) - s["lt"] * np.cos(psi_t)
        hy = s["Y"] - s["h"] * np.sin(s["psi"]) - s["lt"] * np.sin(psi_t)
        front, rear, trail = s["front"], s["rear"], s["trail"]
        return _stack([s["dv"] + lon * r, s["trailer_lateral_acceleration"], s["theta"], r, s["r_t"], s["dtheta"], lat,
                       np.arctan2(lat, np.abs(lon)), front[2], rear[2], trail[2], front[1], rear[1], trail[1],
                       s["hitch"][1], s["hitch"][0], s["du"] - lat * r, lon, np.sqrt(lon * lon + lat * lat),
                       front[0], rear[0], trail[0], s["fz"][0], s["fz"][1], s["fz"][2], s["X"], s["Y"], s["psi"],
                       psi_t, hx, hy])

    # ------------------------------------------------------------------ operating points and analysis
    def straight_running(self, speed: float, **states) -> np.ndarray:
        """State vector of straight running, trailer in line, tires relaxed.

        Parameters
        ----------
        speed : float
            Forward speed u [m/s].
        **states
            Other states by name [their units] (default 0).

        Returns
        -------
        ndarray
            The state vector [SI units].
        """
        return self.state_vector({"longitudinal_velocity": speed, **states})

    def lateral_yaw(self, speed: float, *, crosswind: bool = False):
        """The lateral–yaw–articulation block of the linearization at straight running.

        Parameters
        ----------
        speed : float
            Forward speed u [m/s] of the straight running linearized about.
        crosswind : bool, optional
            Keep the input ``wind_velocity_lateral`` (default False).

        Returns
        -------
        LinearModel
            States ``lateral_velocity``, ``yaw_rate``, ``articulation_angle``,
            ``articulation_rate`` (and the lateral deflections with tire lag), input
            ``front_steer_angle`` (and ``wind_velocity_lateral``), the fifteen outputs of
            :class:`~vehdyn.handling.LinearCarTrailer` in its order. With linear tires and no tire
            lag its matrices are those of LinearCarTrailer (with the same ``crosswind``).
        """
        from vehdyn.handling.bicycle import linear_model_speed
        from vehdyn.model import LinearModel

        speed = linear_model_speed(speed, "ArticulatedSingleTrack.lateral_yaw")
        full = self.linearize(self.straight_running(speed), self.input_vector())
        names = ["lateral_velocity", "yaw_rate", "articulation_angle", "articulation_rate"]
        if self.tire_lag:
            names += ["front_lateral_deflection", "rear_lateral_deflection", "trailer_lateral_deflection"]
        keep = [self.index(n) for n in names]
        inputs = [self.index(n, "inputs") for n in ("front_steer_angle",) + (("wind_velocity_lateral",)
                                                                              if crosswind else ())]
        from vehdyn.handling.car_trailer import _OUTPUTS

        outputs = [self.index(s.name, "outputs") for s in _OUTPUTS]
        return LinearModel(full.A[np.ix_(keep, keep)], full.B[np.ix_(keep, inputs)], full.C[np.ix_(outputs, keep)],
                           full.D[np.ix_(outputs, inputs)], states=[self.states[j] for j in keep],
                           inputs=[self.inputs[j] for j in inputs], outputs=[self.outputs[j] for j in outputs],
                           name=f"ArticulatedSingleTrack lateral-yaw at {speed:g} m/s")

    @staticmethod
    def articulation_event(result, threshold: float = np.radians(45.0)) -> ArticulationEvent | None:
        """The first time the articulation angle leaves its safe range in a simulation.

        Classified by which body turns faster at that moment: ``"jackknife"`` when the towing
        vehicle's yaw rate is the larger (it swings round towards the trailer, as after a locked
        drive axle), ``"trailer_swing"`` when the trailer's is (it swings out, as after a locked
        trailer axle).

        Parameters
        ----------
        result : SimulationResult
            A simulation of this model (outputs ``articulation_angle``, ``yaw_rate``,
            ``trailer_yaw_rate``).
        threshold : float, optional
            |articulation angle| beyond which the combination is out of control [rad], in
            (0, pi] (default 45 degrees).

        Returns
        -------
        ArticulationEvent or None
            The first sample beyond the threshold; None if it is never reached.
        """
        from vehdyn.params.checks import finite_number

        threshold = finite_number(threshold, "threshold", positive=True, maximum=np.pi)
        needed = ("articulation_angle", "yaw_rate", "trailer_yaw_rate")
        if not (hasattr(result, "time") and all(name in result for name in needed)):
            raise ParameterError(f"result must be a SimulationResult of an ArticulatedSingleTrack (with "
                                 f"{', '.join(needed)}), got {type(result).__name__}", key="result",
                                 value=type(result).__name__)
        theta = np.asarray(result["articulation_angle"])
        beyond = np.flatnonzero(np.abs(theta) > threshold)
        if beyond.size == 0:
            return None
        i = beyond[0]
        r, r_t = float(result["yaw_rate"][i]), float(result["trailer_yaw_rate"][i])
        kind = "jackknife" if abs(r) > abs(r_t) else "trailer_swing"
        return ArticulationEvent(kind, float(result.time[i]), float(theta[i]), r, r_t)

    def __repr__(self) -> str:
        return (f"<ArticulatedSingleTrack {self.vehicle.name!r} + {self.trailer.name!r}: tires "
                f"{type(self.front_tire).__name__}/{type(self.rear_tire).__name__}/{type(self.trailer_tire).__name__}, "
                f"tire_lag={self.tire_lag}, {self.n_states} states>")
