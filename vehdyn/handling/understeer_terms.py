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
      is defined (a law with ply steer or conicity adds a first-order part at the static loads; not
      in the file's linear model).
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

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle.
    speed : float, optional
        Forward speed [m/s]. The linear budget does not depend on it; given, it is checked and kept
        in ``attrs`` (the full vehicle's speed-dependent terms, drag and rolling resistance, are not
        rows: compare at low speed or without drag).
    gravity : float, optional
        g [m/s^2].
    tires : tuple of TireModel, optional
        (front, rear) laws for the camber stiffness and the pneumatic trails (default the vehicle's).

    Returns
    -------
    pandas.DataFrame
        Index: the term; columns ``rad_per_g`` [rad/g], ``deg_per_g`` [deg/g], ``formula``,
        ``reference``, ``road_wheel`` (bool: in the road-wheel gradient). ``attrs``:
        ``road_wheel_total_deg_per_g``, ``hand_wheel_total_deg_per_g`` [deg/g], ``vehicle``, ``speed``.

    Raises
    ------
    ParameterError
        For a speed that is not a positive number, or a compliance without effective cornering
        stiffness (naming the field).

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
    frame = pd.DataFrame([{"term": name, "rad_per_g": float(values[name]), "deg_per_g": float(np.rad2deg(values[name])),
                           "formula": formula, "reference": reference,
                           "road_wheel": name != "steering_system_compliance"}
                          for name, formula, reference in _ROWS]).set_index("term")
    road = float(frame.loc[frame["road_wheel"], "deg_per_g"].sum())
    frame.attrs.update(road_wheel_total_deg_per_g=road,
                       hand_wheel_total_deg_per_g=float(frame["deg_per_g"].sum()),
                       vehicle=vehicle.name, speed=None if speed is None else float(speed))
    return frame


def plot_understeer_budget(budget, ax=None, measured=None):
    """Horizontal bars of an understeer budget in the textbook's form (understeer to the right).

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
    colours = [to_rgba("tab:blue" if v >= 0 else "tab:red", 1.0 if road else 0.45)
               for v, road in zip(values, budget["road_wheel"])]
    y = np.arange(len(names))[::-1]
    ax.barh(y, values, color=colours)
    ax.set_yticks(y, [n.replace("_", " ") + ("" if r else " (hand wheel)") for n, r in zip(names,
                                                                                       budget["road_wheel"])])
    ax.axvline(0.0, color="k", lw=0.8)
    road = budget.attrs["road_wheel_total_deg_per_g"]
    ax.axvline(road, color="k", ls="--", label=f"road-wheel total {road:.3f} deg/g")
    hand = budget.attrs["hand_wheel_total_deg_per_g"]
    ax.axvline(hand, color="0.5", ls=":", label=f"hand-wheel total {hand:.3f} deg/g")
    for k, (label, value) in enumerate((measured or {}).items()):
        ax.axvline(value, color=f"C{2 + k}", lw=1.0, alpha=0.8, label=f"{label} {value:.3f}")
    ax.set_xlabel("understeer gradient [deg/g] (understeer +)")
    ax.set_title(f"Understeer budget: {budget.attrs.get('vehicle', '')}")
    ax.legend(fontsize="x-small", loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=2, frameon=False)
    return ax
