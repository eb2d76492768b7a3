"""One corner: suspension spring, damper and anti-roll bar, roll-centre and anti-pitch linkage
forces, tire vertical compliance and camber.

Corners are numbered 0 front left, 1 front right, 2 rear left, 3 rear right (:data:`CORNERS`,
the suffixes of :class:`vehdyn.ride.FullCar`). Signs follow the ride models: vertical
displacements up from static equilibrium; ``suspension_travel`` s = z_body - z_wheel (extension,
rebound +); ``normal_load`` the positive tire load.

Suspension (per corner, compressive force F_s on body and wheel)::

    F_s = F_s0 - k_s s - c_s s' + F_arb,     F_arb = -/+ (K_arb / T^2)(s_left - s_right)  (left/right)

with F_s0 the static share of the sprung weight (so that the state zero is the static
equilibrium), k_s, c_s the wheel rate and damping and K_arb the bar's roll stiffness over track T
(as :class:`vehdyn.ride.FullCar`).

Linkage (jacking) forces: the tire's horizontal force reaches the body along the line from the
contact point to the axle's roll centre (height h_rc on the centre line) and, for the longitudinal
force, along the side-view line of slope tan(beta) = f h / L (f the anti-dive or anti-squat
fraction, h the CG height, L the wheelbase). On the body (SAE z, down +)::

    F_J = (h_rc / y_i) L_y + e_i f (h / L) L_x,      e_i = +1 front, -1 rear

with (L_x, L_y) the force the contact point passes to the body in body x, y and y_i = +-T/2 the
corner's lateral position; the wheel feels -F_J. A lateral force applied this way has no roll
moment about the roll centre: the axle's lateral load transfer splits into the geometric part
L_y h_rc / T and the elastic part through springs and bars (Milliken & Milliken, *Race Car Vehicle
Dynamics*, 1995, ch. 17-18; Gillespie, *Fundamentals of Vehicle Dynamics*, 1992, ch. 7-8).

The unsprung masses' lateral force W_y (their d'Alembert force and the body-y component of their
weight) reaches the body through the linkage as the tire's force does, at the roll centre; the
part lambda of its moment about the roll centre, W_y lambda h_u (h_u the unsprung CG height), is
taken by the tire loads directly instead of the springs: one more jacking force on the body, the
opposite on the wheel::

    F_Ju = kappa_i W_y,      kappa_i = (h_rc - lambda h_u) / y_i

with lambda the axle's ``unsprung_transfer_fraction`` (:class:`vehdyn.params.Suspension`): 1 a
beam or swing axle, the textbook's treatment (Milliken & Milliken 1995, ch. 18; Gillespie 1992,
ch. 7), (T/2)/d for an independent suspension whose front-view swing arm is d long, 0 parallel
equal-length links (the carrier keeps the body's orientation and passes the moment to the body as
a couple; with the roll centre on the ground no vertical force).

Tire normal load from the tire's compression delta = delta_0 + z_road - z_wheel::

    F_z = max(k_t delta + c_t delta', 0) where delta > 0, else 0

never negative: a lifted wheel carries nothing and its tire forces vanish.

Camber (rotation about the body x axis, the same in SAE and ISO-W): when the vehicle file gives
camber gains g [rad/m], gamma_i = phi + e_side g (-s) with e_side = +1 right, -1 left (the wheel
plane rolls with the body, and bump travel -s changes the camber, top outward +); without gains the
wheels stay upright to the road (gamma = 0).
"""

from __future__ import annotations

__all__ = ["CORNERS", "SIDES", "suspension_travel", "suspension_forces", "normal_load", "jacking_force",
           "unsprung_jacking", "camber"]

#: Signal-name suffixes of the corners, in order.
CORNERS = ("_front_left", "_front_right", "_rear_left", "_rear_right")
#: +1 right, -1 left, per corner.
SIDES = (-1.0, 1.0, -1.0, 1.0)


def suspension_travel(R, z, u, v, w, p, q, r, x_i, y_i, z_i, wheel, wheel_rate):
    """Travel s = z_body - z_wheel and its rate of a corner whose spring sits at body point (x_i, y_i, z_i).

    Parameters
    ----------
    R : sequence
        The body-to-earth rotation (R[2] its third row) [-].
    z : float or ndarray
        The sprung CG's earth z (down) from static [m].
    u, v, w : float or ndarray
        Body velocities of the sprung CG [m/s].
    p, q, r : float or ndarray
        Body rates [rad/s].
    x_i, y_i, z_i : float
        The spring's body point from the sprung CG [m].
    wheel : float or ndarray
        The wheel's vertical displacement (up) [m].
    wheel_rate : float or ndarray
        Its rate [m/s].

    Returns
    -------
    tuple
        (travel [m], travel rate [m/s]), rebound positive.
    """
    R20, R21, R22 = R[2][0], R[2][1], R[2][2]
    body_up = -(z + R20 * x_i + R21 * y_i + R22 * z_i - z_i)
    vx, vy, vz = u + q * z_i - r * y_i, v + r * x_i - p * z_i, w + p * y_i - q * x_i
    body_up_rate = -(R20 * vx + R21 * vy + R22 * vz)
    return body_up - wheel, body_up_rate - wheel_rate


def suspension_forces(k, travel, travel_rate):
    """Compressive suspension forces F_s of the four corners: springs, dampers and anti-roll bars.

    Parameters
    ----------
    k : Constants
        The model's constants (:class:`vehdyn.full_vehicle.assembly.Constants`).
    travel : tuple
        The four travels [m].
    travel_rate : tuple
        Their rates [m/s].

    Returns
    -------
    tuple
        F_s [N] in corner order.
    """
    f = (k.spring_preload[0] - k.spring_rate[0] * travel[0] - k.damping[0] * travel_rate[0],
         k.spring_preload[1] - k.spring_rate[1] * travel[1] - k.damping[1] * travel_rate[1],
         k.spring_preload[2] - k.spring_rate[2] * travel[2] - k.damping[2] * travel_rate[2],
         k.spring_preload[3] - k.spring_rate[3] * travel[3] - k.damping[3] * travel_rate[3])
    front = k.antiroll_rate[0] * (travel[0] - travel[1])
    rear = k.antiroll_rate[1] * (travel[2] - travel[3])
    return f[0] - front, f[1] + front, f[2] - rear, f[3] + rear


def normal_load(xp, k, c, wheel, wheel_rate, road, road_rate):
    """Tire normal load of corner ``c`` (>= 0; 0 when the wheel is off the ground).

    Parameters
    ----------
    xp : namespace
        The equations' namespace (:mod:`vehdyn.components.xp`).
    k : Constants
        The model's constants (:class:`vehdyn.full_vehicle.assembly.Constants`).
    c : int
        The corner (0 FL, 1 FR, 2 RL, 3 RR).
    wheel : float or ndarray
        The wheel's vertical displacement (up) [m].
    wheel_rate : float or ndarray
        Its rate [m/s].
    road : float or ndarray
        The road's elevation under the wheel [m].
    road_rate : float or ndarray
        Its rate [m/s].

    Returns
    -------
    float or ndarray
        F_z [N].
    """
    deflection = k.static_tire_deflection[c] + road - wheel
    force = k.tire_stiffness[c] * deflection + k.tire_damping[c] * (road_rate - wheel_rate)
    return xp.where(deflection > 0.0, xp.maximum(force, 0.0), 0.0)


def jacking_force(k, c, link_x, link_y):
    """Linkage (jacking) force F_J on the body of corner ``c`` (module docstring).

    Parameters
    ----------
    k : Constants
        The model's constants (:class:`vehdyn.full_vehicle.assembly.Constants`).
    c : int
        The corner.
    link_x, link_y : float or ndarray
        The force the contact passes to the body in body x and y [N].

    Returns
    -------
    float or ndarray
        F_J [N] (SAE z, down +).
    """
    return k.roll_centre_height[c] / k.corner_y[c] * link_y + k.anti_pitch[c] * link_x


def unsprung_jacking(roll_centre_height, transfer_fraction, unsprung_cg_height, corner_y):
    """kappa_i = (h_rc - lambda h_u) / y_i of the module docstring.

    Parameters
    ----------
    roll_centre_height : float
        h_rc of the corner's axle [m].
    transfer_fraction : float
        lambda of the axle [-].
    unsprung_cg_height : float
        h_u [m].
    corner_y : float
        y_i, the corner's lateral position from the sprung CG (right +) [m].

    Returns
    -------
    float
        kappa_i [-]: vertical force on the body (SAE z, down +) per unit lateral force (SAE y) of
        the unsprung mass.
    """
    return (roll_centre_height - transfer_fraction * unsprung_cg_height) / corner_y


def camber(k, c, roll, travel):
    """Inclination angle of corner ``c``'s wheel: the body's roll less the camber gain on the travel.

    Parameters
    ----------
    k : Constants
        The model's constants (:class:`vehdyn.full_vehicle.assembly.Constants`).
    c : int
        The corner.
    roll : float or ndarray
        Roll angle [rad].
    travel : float or ndarray
        The corner's travel [m].

    Returns
    -------
    float or ndarray
        gamma [rad] (rotation about x, SAE = ISO-W).
    """
    return k.camber_on * (roll - SIDES[c] * k.camber_gain[c] * travel)
