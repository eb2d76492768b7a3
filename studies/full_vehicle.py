"""Full vehicle: load transfer, the handling limit, rollover, split-mu braking and cornering on a rough road.

The full vehicle (vehdyn.full_vehicle.FullVehicle: a 6-DOF sprung body on four corners with wheel
hop, wheel spin and Magic Formula tires with combined slip, each the shipped vehicle's own .tir)
shows what the models below it leave out. Lateral load transfer: per axle, against lateral
acceleration, split into the elastic part (through springs and anti-roll bars) and the geometric
part (through the roll centres), against the closed form of Milliken & Milliken (1995, ch. 18) with
the tire compliance and the rolled CG kept; the sedan with its roll centres raised to 8 cm front and
15 cm rear (the shipped files put them on the ground, where the geometric part vanishes). The
handling limit: steady turns at 20 m/s (FullVehicle.trim, continued to the last equilibrium)
against the nonlinear single track with the same tires, which has no lateral load transfer; the
Magic Formula's peak force grows less than in proportion to the load, so the transfer lowers each
axle's peak force. Rollover: the NHTSA fishhook (720 deg/s hand-wheel ramps to 6.5 times the steer
of 0.3 g, 250 ms dwell; NHTSA 2013) at the protocol's highest speed, 50 mph, for each shipped
vehicle with its CG raised step by step: whether and when both wheels of one side leave the road
and the lateral acceleration then, against the static stability factor SSF = T / 2h (the
rigid vehicle's threshold, in g) and the quasi-static threshold of a vehicle whose body rolls on its
suspension (Gillespie 1992, sec. 9). Split-mu braking: mu 0.9 under the left wheels, 0.2 under the
right, each wheel braked below locking (an ideal individual-wheel ABS): the yaw moment of the
unequal braking forces turns the vehicle towards the high-friction side; a counter-steer from the
closed form of a yaw moment balanced by the axle side forces holds it straight. Cornering on a
rough road: a steady 0.6 g turn at 20 m/s with the steer of the flat-road trim held, on two
parallel ISO 8608 class-D tracks. The
single track (flat road) misses that the fluctuating loads lower the mean lateral force (the tire
force is concave in the load); the ride model (FullCar, same road) misses that the lateral forces
fluctuate with the loads and roll the body.
"""

from __future__ import annotations

import numpy as np

import vehdyn
from vehdyn.full_vehicle import CORNERS, FullVehicle
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.simulation.compiled import numba_available

G = vehdyn.units.GRAVITY
#: the trims' residuals from the car's compiled code, which the study's runs compile anyway (the study with
#: its code cached: 26.7 -> 13.3 s); the same equations within a few ulps (the trims move by ~1e-14, relative)
TRIM = {"backend": "compiled"} if numba_available() else {}
MPH = 0.44704  # [m/s]
VEHICLES = ("sedan", "compact", "van")


def _outputs(model, x, u) -> dict:
    return dict(zip(model.output_names, model.output(0.0, x, u)))


# ---------------------------------------------------------------------------------------- load transfer
def closed_form_load_transfer(model, ay):
    """Steady lateral load transfer per axle (N_outer - N_inner) / 2 [N]: elastic and geometric parts.

    The closed form of :func:`vehdyn.handling.steady_roll` (stated in the FullVehicle docstring;
    Milliken & Milliken 1995, ch. 18, with the rolled CG, the tires' compliance and the unsprung
    masses' lateral inertia taken by the tires in the share lambda_i of the vehicle file), linear in
    a_y: elastic part K_i phi_si / T_i through springs and bars; geometric part the rest, through the
    links (m_si h_i (a_y + g phi) / T_i) and the unsprung masses' direct part
    (m_ui lambda_i h_u (a_y + g phi) / T_i).
    Returns (roll angle magnitude [rad], elastic (front, rear), geometric (front, rear)) per a_y.
    """
    from vehdyn.handling import steady_roll

    roll = steady_roll(model.vehicle, gravity=model.gravity)
    ay = np.atleast_1d(np.asarray(ay, dtype=float))
    elastic = np.outer(ay, roll.elastic_transfer)
    geometric = np.outer(ay, np.add(roll.geometric_transfer, roll.unsprung_transfer))
    return roll.roll_gradient * ay, elastic, geometric


def load_transfer(study: Study) -> None:
    import pandas as pd

    sedan = vehdyn.load_vehicle("sedan")
    vehicle = sedan.replace(geometry__front_roll_centre_height=0.08, geometry__rear_roll_centre_height=0.15,
                            aero__drag_coefficient=0.0)  # no drag: the drive force shifts no load
    model = FullVehicle(vehicle, tire_lag=False)
    ays = np.arange(0.0, 0.61, 0.2 if study.quick else 0.05) * G
    rows = []
    tracks = (vehicle.geometry.front_track, vehicle.geometry.rear_track)
    stiff = (vehicle.front_roll_stiffness, vehicle.rear_roll_stiffness)
    for ay in ays:
        y = _outputs(model, *model.trim(20.0, lateral_acceleration=float(ay), **TRIM))
        row = {"lateral_acceleration": ay, "roll_angle": -y["roll_angle"]}
        for i, axle in enumerate(("front", "rear")):
            total = 0.5 * (y[f"normal_load_{axle}_left"] - y[f"normal_load_{axle}_right"])
            # elastic: spring and bar forces, -K_i (s_left - s_right) / T_i^2 (travel: extension +)
            travel = y[f"suspension_travel_{axle}_left"] - y[f"suspension_travel_{axle}_right"]
            elastic = -stiff[i] * travel / tracks[i] ** 2
            row.update({f"{axle}_total": total, f"{axle}_elastic": elastic, f"{axle}_geometric": total - elastic})
        rows.append(row)
    frame = pd.DataFrame(rows)
    fine = np.linspace(0.0, ays[-1], 61)
    phi, elastic, geometric = closed_form_load_transfer(model, fine)
    phi_k, elastic_k, geometric_k = closed_form_load_transfer(model, ays)

    fig, axes = new_figure(1, 3, width=13.0, height_per_row=3.8)
    for i, axle in enumerate(("front", "rear")):
        ax = axes[0, i]
        for part, closed, color in (("total", elastic[:, i] + geometric[:, i], "k"), ("elastic", elastic[:, i], "C0"),
                                    ("geometric", geometric[:, i], "C1")):
            ax.plot(fine / G, closed, "-", color=color, lw=1.0, label=f"{part}, closed form")
            ax.plot(frame.lateral_acceleration / G, frame[f"{axle}_{part}"], "o", color=color, ms=4,
                    label=f"{part}, FullVehicle.trim")
        ax.set_xlabel("lateral acceleration [g]")
        ax.set_ylabel("lateral load transfer (N_outer - N_inner) / 2 [N]")
        ax.set_title(f"{axle} axle (roll centre {(0.08, 0.15)[i] * 100:.0f} cm)", fontsize=9)
        ax.legend(fontsize=6)
        ax.grid(True, alpha=0.3)
    ax = axes[0, 2]
    ax.plot(fine / G, np.degrees(phi), "k-", lw=1.0, label="closed form")
    ax.plot(frame.lateral_acceleration / G, np.degrees(frame.roll_angle), "o", ms=4, label="FullVehicle.trim")
    ax.set_xlabel("lateral acceleration [g]")
    ax.set_ylabel("body roll angle, out of the turn [deg]")
    ax.set_title("roll", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    study.figure(fig, "lateral_load_transfer",
                 caption="Sedan, roll centres raised to 8/15 cm, Magic Formula tires, 20 m/s, drag off: per-axle "
                         "lateral "
                         "load transfer from the trimmed full vehicle (points; elastic part from the suspension travel "
                         "and the axle's roll stiffness, geometric part the rest) against the closed form (lines)")
    err = {}
    for i, axle in enumerate(("front", "rear")):
        for part, closed in (("total", elastic_k[:, i] + geometric_k[:, i]), ("elastic", elastic_k[:, i]),
                             ("geometric", geometric_k[:, i])):
            model_values = frame[f"{axle}_{part}"].to_numpy()[1:]
            err[f"{axle}_{part}"] = float(np.max(np.abs(model_values / closed[1:] - 1.0)))
    err["roll_angle"] = float(np.max(np.abs(frame.roll_angle.to_numpy()[1:] / phi_k[1:] - 1.0)))
    table = pd.DataFrame({"largest relative difference": err})
    study.table(table, "load_transfer_check",
                caption="Full vehicle against the closed form over 0.05 to 0.6 g: largest relative difference")
    study.text(
        f"The trimmed full vehicle's load transfer follows the closed form within {100 * max(err.values()):.2g} % "
        "up to "
        "0.6 g, part by part. The geometric part (through the roll centres, and the unsprung masses' lateral "
        "inertia taken by the tires) grows with the roll-centre height and reaches the tires without rolling the "
        "body; the elastic part is split between the axles by their roll stiffness. "
        "Both grow almost linearly: the rolled CG (phi times the sprung CG height above the roll axis) and the "
        "tire compliance bend them only slightly upwards.")


# ---------------------------------------------------------------------------------------- handling limit
def _continuation(model, speed, step):
    """Steady turns from a_y = step upwards, each started from the last; halving the step at the
    first failure twice. Returns a_y [m/s^2], steer [rad], outputs list."""
    from vehdyn import ParameterError

    points, previous, ay = [], None, step
    for _ in range(3):
        while True:
            try:
                previous = model.trim(speed, lateral_acceleration=float(ay), guess=previous, **TRIM)
            except ParameterError:
                break
            points.append((ay, previous))
            ay += step
        step *= 0.5
        ay = points[-1][0] + step if points else step
    return points


def handling_limit(study: Study) -> None:
    import pandas as pd

    from vehdyn.handling import SingleTrack, nonlinear_handling_diagram

    speed = 20.0
    names = ("sedan",) if study.quick else VEHICLES
    step = 1.0 if study.quick else 0.5
    fig, axes = new_figure(1, 2, width=11.5, height_per_row=3.8)
    rows = []
    for name in names:
        vehicle = vehdyn.load_vehicle(name)
        single = nonlinear_handling_diagram(SingleTrack(vehicle, tire_lag=False, wheel_spin=True), speed=speed,
                                            step=step / 2, tolerance=0.05)
        full = FullVehicle(vehicle, tire_lag=False)
        points = _continuation(full, speed, step)
        ay = np.array([p[0] for p in points])
        steer = np.array([p[1][1][full.index("front_steer_angle", "inputs")] for p in points])
        line = axes[0, 0].plot(single.lateral_acceleration / G, np.degrees(single.steer_angle), "--", lw=1.0,
                               label=f"{name}: single track")[0]
        axes[0, 0].plot(ay / G, np.degrees(steer), "o-", ms=3, color=line.get_color(), label=f"{name}: full vehicle")
        limit = _outputs(full, *points[-1][1])
        transfer = [0.5 * abs(limit[f"normal_load_{a}_left"] - limit[f"normal_load_{a}_right"])
                    for a in ("front", "rear")]
        static = full.static_loads()
        rows.append({"vehicle": name, "limit_single_track": single.limit_lateral_acceleration / G,
                     "limit_full_vehicle": ay[-1] / G,
                     "front_transfer_at_limit": transfer[0] / static["normal_load_front_left"],
                     "rear_transfer_at_limit": transfer[1] / static["normal_load_rear_left"]})
    axes[0, 0].set_xlabel("lateral acceleration [g]")
    axes[0, 0].set_ylabel("front steer angle [deg]")
    axes[0, 0].set_title(f"handling diagram at {speed:g} m/s, Magic Formula tires", fontsize=9)
    axes[0, 0].legend(fontsize=6)
    axes[0, 0].grid(True, alpha=0.3)
    # why: the axle's peak side force under load transfer, from the tire law itself
    sedan = FullVehicle(vehdyn.load_vehicle("sedan"), tire_lag=False)
    alpha = np.radians(np.linspace(0.5, 20.0, 80))
    for axle, tire, corner in (("front", sedan.front_tire, "front_left"), ("rear", sedan.rear_tire, "rear_left")):
        n0 = sedan.static_loads()[f"normal_load_{corner}"]
        share = np.linspace(0.0, 0.95, 20)

        def peak(load):
            return np.max(np.abs(tire.forces(np.full_like(alpha, load), 0.0 * alpha, alpha, 0.0 * alpha,
                                             np.full_like(alpha, speed)).fy))

        ratio = [(peak(n0 * (1 + d)) + peak(n0 * (1 - d))) / (2 * peak(n0)) for d in share]
        axes[0, 1].plot(share, ratio, label=f"sedan {axle} axle (static {n0:.0f} N per tire)")
    for row in rows:
        if row["vehicle"] == "sedan":
            axes[0, 1].axvline(row["front_transfer_at_limit"], color="C0", ls=":", lw=0.8)
            axes[0, 1].axvline(row["rear_transfer_at_limit"], color="C1", ls=":", lw=0.8)
    axes[0, 1].set_xlabel("lateral load transfer Delta N / N_static [-]")
    axes[0, 1].set_ylabel("axle peak side force / its value without transfer [-]")
    axes[0, 1].set_title("Magic Formula: peak force of two tires at N +- Delta N\n(dotted: the sedan at its limit)",
                         fontsize=9)
    axes[0, 1].legend(fontsize=7)
    axes[0, 1].grid(True, alpha=0.3)
    fig.tight_layout()
    study.figure(fig, "handling_diagram",
                 caption="Steady turns up to the last equilibrium: the full vehicle (trim) against the nonlinear "
                         "single "
                         "track with the same tires; right: how load transfer lowers an axle's peak side force")
    frame = pd.DataFrame(rows).set_index("vehicle")
    frame.attrs["units"] = {"limit_single_track": "g", "limit_full_vehicle": "g", "front_transfer_at_limit": "-",
                            "rear_transfer_at_limit": "-"}
    study.table(frame, "handling_limits", caption=f"Limit lateral acceleration at {speed:g} m/s and the lateral "
                                                  "load transfer there (relative to the static wheel load)")
    study.text(
        "At small lateral acceleration the full vehicle steers as the single track (the same tires, a load "
        "transfer that leaves the axle's cornering stiffness nearly unchanged). Towards the limit the transfer "
        "grows to more than half the wheel load: the Magic Formula's friction falls with load, so the outer tire "
        "gains less than the inner one loses, the axle's peak side force drops (right panel) and the full vehicle "
        "needs more steer and runs out of equilibria earlier, by "
        + ", ".join(f"{r['vehicle']} {100 * (1 - r['limit_full_vehicle'] / r['limit_single_track']):.0f} %"
                    for r in rows) + ".")


# ---------------------------------------------------------------------------------------- rollover
def raised(vehicle, dh):
    """``vehicle`` with its CG raised by ``dh`` [m] (the sprung mass carries the change)."""
    m = vehicle.mass
    return vehicle.replace(mass__cg_height=m.cg_height + dh,
                           mass__sprung_cg_height=m.sprung_cg_height + dh * m.mass / m.sprung_mass)


def fishhook(model, speed, *, rtol=1e-4):
    """NHTSA fishhook (2013): 720 deg/s hand-wheel ramps to +-A, A = 6.5 x the steer of 0.3 g at the
    speed, 250 ms dwell at +A, then 3 s at -A (here 1 s: the lift comes within 0.5 s of the reversal).
    Drive torques of the straight trim held. When the vehicle rolls over (SimulationError: the roll
    angle leaves the model's domain), the run up to 50 ms before, with ``rolled_over`` set to that time."""
    x0, u0 = model.trim(speed, **TRIM)
    _, u1 = model.trim(speed, lateral_acceleration=0.3 * G, **TRIM)
    k = model.index("front_steer_angle", "inputs")
    amplitude = 6.5 * u1[k]
    rate = np.radians(720.0) / model.vehicle.steering.ratio
    t1 = amplitude / rate
    t2 = t1 + 0.25
    t3 = t2 + 2 * amplitude / rate
    t = np.linspace(0.0, t3 + 1.0, int((t3 + 1.0) * 100) + 1)
    steer = np.where(t < t1, rate * t, np.where(t < t2, amplitude, np.maximum(amplitude - rate * (t - t2), -amplitude)))
    inputs = {**dict(zip(model.input_names, u0)), "front_steer_angle": steer}
    try:
        return vehdyn.simulate(model, t, inputs, x0=x0, method="RK45", rtol=rtol, atol=rtol * 1e-2)
    except vehdyn.SimulationError as exc:
        # rolled over: the run up to shortly before, to see the two-wheel lift
        t = t[t < exc.time - 0.05]
        result = vehdyn.simulate(model, t, {k: (v[:t.size] if np.ndim(v) else v) for k, v in inputs.items()},
                                 x0=x0, method="RK45", rtol=rtol, atol=rtol * 1e-2)
        result.rolled_over = exc.time
        return result


def two_wheel_lift(result):
    """First time both wheels of one side carry no load, and the lateral acceleration then (or None)."""
    for side in ("left", "right"):
        both = ((np.asarray(result[f"normal_load_front_{side}"]) <= 0)
                & (np.asarray(result[f"normal_load_rear_{side}"]) <= 0))
        if np.any(both):
            k = int(np.argmax(both))
            return float(result.time[k]), float(result["lateral_acceleration"][k])
    return None


def quasi_static_threshold(vehicle):
    """Rollover threshold of a vehicle whose body rolls on its suspension [g] (Gillespie 1992, eq. 9-7
    with the sprung mass share): the moment of the weight about the outer contact line,
    m g (T/2 - (m_s/m) (h_s - h_r) phi), balances m a_y h with phi = R a_y, R the roll gradient."""
    from vehdyn.handling import roll_gradient

    m, geo = vehicle.mass, vehicle.geometry
    track = 0.5 * (geo.front_track + geo.rear_track)
    h_r = 0.5 * (geo.front_roll_centre_height + geo.rear_roll_centre_height)
    R = roll_gradient(vehicle)
    return 0.5 * track / (m.cg_height + G * R * m.sprung_mass / m.mass * (m.sprung_cg_height - h_r))


def rollover(study: Study) -> None:
    import pandas as pd

    raises = (0.15,) if study.quick else (0.0, 0.05, 0.1, 0.15)
    speed = 50.0 * MPH  # the protocol's highest speed
    rows, example = [], None
    for name in VEHICLES:
        for dh in raises:
            vehicle = raised(vehdyn.load_vehicle(name), dh)
            model = FullVehicle(vehicle)
            m, geo = vehicle.mass, vehicle.geometry
            result = fishhook(model, speed, rtol=1e-3 if study.quick else 1e-4)
            lift = two_wheel_lift(result)
            rows.append({"vehicle": name, "cg_height": m.cg_height, "SSF": 0.25 * (geo.front_track + geo.rear_track)
                         / m.cg_height, "quasi_static_threshold": quasi_static_threshold(vehicle),
                         "peak_ay_before_lift": float(np.max(np.abs(
                             result["lateral_acceleration"][result.time <= (lift[0] if lift else np.inf)]))) / G,
                         "two_wheel_lift_time": lift[0] if lift else np.nan,
                         "ay_at_lift": abs(lift[1]) / G if lift else np.nan,
                         "rolled_over": getattr(result, "rolled_over", None) is not None})
            if lift and (example is None or (name == "van" and example[0] != "van")):
                example = (name, dh, result, model)
    frame = pd.DataFrame(rows)

    fig, axes = new_figure(1, 2, width=12.0, height_per_row=4.0)
    ax = axes[0, 0]
    s = np.linspace(0.8, 1.4, 20)
    ax.plot(s, s, "k-", lw=1.0, label="rigid vehicle: a_y = SSF g")
    markers = dict(zip(VEHICLES, "osD"))
    for i, name in enumerate(VEHICLES):
        sub = frame[frame.vehicle == name].sort_values("SSF")
        ax.plot(sub.SSF, sub.quasi_static_threshold, ":+", color=f"C{i}", lw=1.0, ms=8,
                label=f"{name}: quasi-static, body roll")
        lifted = sub[~sub.ay_at_lift.isna()]
        ax.plot(lifted.SSF, lifted.ay_at_lift, markers[name], color=f"C{i}", label=f"{name}: fishhook, two wheels lift")
        kept = sub[sub.ay_at_lift.isna()]
        ax.plot(kept.SSF, kept.peak_ay_before_lift, markers[name], color=f"C{i}", mfc="none",
                label=f"{name}: fishhook, no lift (peak a_y)")
    ax.set_xlabel("static stability factor SSF = T / 2h [-]")
    ax.set_ylabel("lateral acceleration [g]")
    ax.set_title("rollover threshold (CG raised in steps)", fontsize=9)
    ax.legend(fontsize=6)
    ax.grid(True, alpha=0.3)
    ax = axes[0, 1]
    if example is not None:
        name, dh, result, model = example
        for sfx, style in zip(CORNERS, ("-", "--", "-", "--")):
            ax.plot(result.time, result[f"normal_load{sfx}"] / 1e3, style, lw=1.0, label=f"normal load {sfx[1:]}")
        ax.set_ylabel("tire normal load [kN]")
        ax.set_xlabel("time [s]")
        twin = ax.twinx()
        twin.plot(result.time, result["lateral_acceleration"] / G, "k", lw=0.8, label="lateral acceleration")
        twin.set_ylabel("lateral acceleration [g] (black)")
        ax.set_title(f"{name}, CG +{100 * dh:.0f} cm, fishhook at 50 mph"
                     + (" (rolls over)" if getattr(result, "rolled_over", None) else ""), fontsize=9)
        ax.legend(fontsize=6, loc="lower left")
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    study.figure(fig, "rollover_threshold",
                 caption="NHTSA fishhook at 50 mph: lateral acceleration when both wheels of one side leave the road "
                         "(filled; open: the peak of a run without lift) against the static stability factor; right: "
                         "the tire loads of one run")
    frame = frame.set_index(["vehicle", "cg_height"])
    frame.attrs["units"] = {"SSF": "g", "quasi_static_threshold": "g", "peak_ay_before_lift": "g",
                            "two_wheel_lift_time": "s", "ay_at_lift": "g", "cg_height": "m"}
    study.table(frame, "rollover", caption="Fishhook at 50 mph with the CG raised: two-wheel lift (time and lateral "
                                           "acceleration then; rolled_over: the run ended leaving the model's roll "
                                           "domain) against SSF and the quasi-static threshold")
    lifted = frame[~frame.ay_at_lift.isna()]
    nominal = frame.groupby(level="vehicle").head(1)  # the file's CG height (raise 0)
    text = ("Two wheels lift well below the rigid vehicle's threshold SSF g: the body rolls out of the turn and "
            "moves the CG towards the outer wheels (the quasi-static line), and in the fishhook's reversal it swings "
            "through from the first turn's roll. ")
    if len(lifted):
        below = int((lifted.ay_at_lift < lifted.quasi_static_threshold).sum())
        text += (f"Where two wheels lifted ({len(lifted)} of {len(frame)} runs, {int(lifted.rolled_over.sum())} of "
                 f"them rolling over), the lateral acceleration then was {lifted.ay_at_lift.min():.2f} to "
                 f"{lifted.ay_at_lift.max():.2f} g, {100 * (1 - (lifted.ay_at_lift / lifted.SSF).max()):.0f} to "
                 f"{100 * (1 - (lifted.ay_at_lift / lifted.SSF).min()):.0f} % below SSF and in {below} of "
                 f"{len(lifted)} runs below the quasi-static threshold. ")
    safe = [v for v in VEHICLES if raises[0] == 0.0 and np.isnan(nominal.loc[v].ay_at_lift.iloc[0])]
    if safe:
        text += (f"At their file CG heights ({', '.join(safe)}) no wheel pair lifts: the tires (mu about 0.94, "
                 "falling with load) saturate first and the vehicle slides rather than rolls; raising the CG lowers "
                 "SSF towards the tire limit until the fishhook lifts two wheels.")
    study.text(text)


# ---------------------------------------------------------------------------------------- split-mu braking
def split_mu(study: Study) -> None:
    import pandas as pd

    vehicle = vehdyn.load_vehicle("sedan")
    mu = vehicle.tires.friction_coefficient
    speed = 25.0
    duration = 0.9  # at ~1 s the uncorrected vehicle's right wheels reach the high-friction half
    rtol = 1e-4 if study.quick else 1e-6

    def friction(X, Y):
        return np.where(np.asarray(Y) > 0.0, 0.2, 0.9) / mu  # SAE: Y > 0 right of the start heading

    model = FullVehicle(vehicle, friction=friction)
    x0, u0 = model.trim(speed)  # numpy: a friction callable has no compiled form
    t = np.linspace(0.0, duration, int(duration * 200) + 1)
    onset = 0.1
    ramp = np.clip((t - onset) / 0.1, 0.0, 1.0)
    # an ideal individual-wheel ABS: each wheel braked below the torque that would lock it on its own
    # road, mu N R (static load; 80 % front, which gains load, and 30 % rear: brake proportioning)
    static, radius = model.static_loads(), vehicle.tires.rolling_radius
    brakes = {f"brake_torque{s}": (0.8 if "front" in s else 0.3) * (0.9 if "left" in s else 0.2)
              * static[f"normal_load{s}"] * radius * ramp for s in CORNERS}
    plain = vehdyn.simulate(model, t, brakes, x0=x0, method="RK45", rtol=rtol, atol=rtol * 1e-2)
    # counter-steer: the yaw moment of the braking forces F_x = -T_b / R (no wheel locks),
    # M_z = (T/2) sum (F_x,left - F_x,right) (SAE: z down, left wheels at y = -T/2; yaw right +), held by
    # side forces with no yaw rate and no lateral acceleration: F_yf = -F_yr = -M_z / L, so
    # delta = F_yf / C_f - F_yr / C_r = -(M_z / L) (1 / C_f + 1 / C_r) (SAE F_y = -C alpha, alpha_f =
    # beta - delta, alpha_r = beta; axle cornering stiffnesses C)
    geo, L = vehicle.geometry, vehicle.wheelbase
    tracks = {"front": geo.front_track, "rear": geo.rear_track}
    mz = sum(0.5 * tracks[axle] * (brakes[f"brake_torque_{axle}_right"][-1] - brakes[f"brake_torque_{axle}_left"][-1])
             / radius for axle in tracks)
    counter = -mz / L * (1.0 / vehicle.tires.rear_cornering_stiffness + 1.0 / vehicle.tires.front_cornering_stiffness)
    k = (t > onset + 0.2) & (t < onset + 0.5)  # braking established, before the vehicle yaws far
    moment = sum(0.5 * tracks[axle]
                 * (plain[f"longitudinal_force_{axle}_left"] - plain[f"longitudinal_force_{axle}_right"])
                 for axle in tracks)
    mz_model = float(np.mean(moment[k]))
    steer = u0[model.index("front_steer_angle", "inputs")] + counter * ramp
    corrected = vehdyn.simulate(model, t, {**brakes, "front_steer_angle": steer}, x0=x0, method="RK45", rtol=rtol,
                                atol=rtol * 1e-2)
    fig, axes = new_figure(2, 2, width=11.5, height_per_row=3.0)
    for result, label, style in ((plain, "no steering correction", "-"),
                                 (corrected, f"counter-steer {np.degrees(counter):.2f} deg", "--")):
        axes[0, 0].plot(t, np.degrees(result["yaw_rate"]), style, label=label)
        axes[0, 1].plot(result["x"], result["y"], style, label=label)
        axes[1, 1].plot(t, result["longitudinal_acceleration"] / G, style, label=label)
    for sfx in CORNERS:
        axes[1, 0].plot(t, plain[f"longitudinal_force{sfx}"] / 1e3, label=sfx[1:])
    axes[0, 0].set_ylabel("yaw rate [deg/s] (SAE: + right)")
    axes[0, 1].set_xlabel("X [m]")
    axes[0, 1].set_ylabel("Y [m] (SAE: + right; mu 0.2 for Y > 0)")
    axes[0, 1].invert_yaxis()
    axes[1, 0].set_ylabel("braking force (no correction) [kN]")
    axes[1, 1].set_ylabel("longitudinal acceleration [g]")
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6)
    for ax in axes[1]:
        ax.set_xlabel("time [s]")
    axes[0, 0].set_xlabel("time [s]")
    fig.tight_layout()
    study.figure(fig, "split_mu_braking",
                 caption=f"Sedan braking from {speed:g} m/s on split mu (0.9 left, 0.2 right), "
                         "each wheel below its lock torque (ideal individual-wheel ABS): yaw, path, braking forces "
                         "and deceleration")
    rows = []
    for result, label in ((plain, "no correction"), (corrected, "counter-steer")):
        rows.append({"run": label, "yaw_rate_end": np.degrees(result["yaw_rate"][-1]),
                     "heading_end": np.degrees(result["yaw_angle"][-1]), "lateral_offset_end": result["y"][-1],
                     "mean_deceleration": -np.mean(result["longitudinal_acceleration"][t > onset + 0.2]) / G})
    frame = pd.DataFrame(rows).set_index("run")
    frame.attrs["units"] = {"yaw_rate_end": "deg/s", "heading_end": "deg", "lateral_offset_end": "m",
                            "mean_deceleration": "g"}
    study.table(frame, "split_mu", caption=f"Split-mu braking after {duration:g} s; counter-steer "
                                           f"{np.degrees(counter):.2f} deg from the closed form (yaw moment "
                                           f"{mz:.0f} N m from the brake torques; {mz_model:.0f} N m "
                                           "from the model's braking forces)")
    study.text(
        f"The low-friction (right) wheels brake with about 0.2/0.9 of the left wheels' force; the braking forces' yaw "
        f"moment ({mz:.0f} N m from the brake torques, {mz_model:.0f} N m in the model between 0.3 and 0.6 s; "
        "SAE: negative yaws left) "
        f"turns the vehicle towards the high-friction side: {frame.heading_end.iloc[0]:.1f} deg of heading and "
        f"{frame.yaw_rate_end.iloc[0]:.0f} deg/s after {duration:g} s, and growing, because the side forces that "
        "could hold it come from tires on mu 0.2 or already busy braking. A steer of "
        f"{np.degrees(counter):.2f} deg (to the right), from the side forces that balance that moment with no yaw "
        f"rate, leaves {frame.heading_end.iloc[1]:.1f} deg: the driver (or ESC) has to counter-steer by about a "
        "degree within a few tenths of a second.")


# ---------------------------------------------------------------------------------------- rough road
def rough_road(study: Study) -> None:
    import pandas as pd

    from vehdyn.ride import FullCar, road_inputs
    from vehdyn.road import synthesize_parallel_profiles

    vehicle = vehdyn.load_vehicle("sedan")
    speed, ay = 20.0, 0.6 * G
    duration = 1.5 if study.quick else 3.0
    rtol = 1e-4 if study.quick else 1e-5
    model = FullVehicle(vehicle)
    x0, u0 = model.trim(speed, lateral_acceleration=ay, **TRIM)
    flat = _outputs(model, x0, u0)
    track = 0.5 * (vehicle.geometry.front_track + vehicle.geometry.rear_track)
    length = 2.0 ** np.ceil(np.log2(speed * duration + vehicle.wheelbase + 10.0))
    left, right = synthesize_parallel_profiles("D", length, 0.05, track, seed=12)
    t = np.arange(0.0, duration + 1e-9, 0.05 / speed)
    fade = np.clip(t / 0.3, 0.0, 1.0)
    fade_rate = np.where(t < 0.3, 1.0 / 0.3, 0.0)
    road = road_inputs(FullCar(vehicle), t, speed, left.distance, left.elevation, right.elevation)
    for sfx in CORNERS:  # faded in: the trim starts on a flat road
        z = road[f"road_displacement{sfx}"]
        road[f"road_velocity{sfx}"] = fade * road[f"road_velocity{sfx}"] + fade_rate * z
        road[f"road_displacement{sfx}"] = fade * z
    rough = vehdyn.simulate(model, t, {**dict(zip(model.input_names, u0)), **road}, x0=x0, method="RK45",
                            rtol=rtol, atol=rtol * 1e-2, max_step=0.05 / speed)
    ride = vehdyn.simulate(FullCar(vehicle), t, road, method="RK45", rtol=1e-6, atol=1e-9)
    settled = t > 0.5
    # quasi-static: the tire law (ISO-W) at the run's loads and the trim's slips and camber, against at the
    # trim's loads; SAE F_y (the sign of the ratio's terms is the model's)
    from vehdyn.conventions import planar_tire_forces_iso_w_to_sae, planar_tire_slips_sae_to_iso_w

    quasi = []
    for c, sfx in enumerate(CORNERS):
        loads = np.append(rough[f"normal_load{sfx}"][settled], flat[f"normal_load{sfx}"])
        kappa, alpha = planar_tire_slips_sae_to_iso_w(flat[f"slip_ratio{sfx}"], flat[f"slip_angle{sfx}"])
        ones = np.ones_like(loads)
        fx, fy = model.corner_law_forces(c, loads, kappa * ones, alpha * ones, flat[f"camber_angle{sfx}"] * ones,
                                         speed * ones)
        fy = planar_tire_forces_iso_w_to_sae(fx, fy)[1]
        quasi.append((np.mean(fy[:-1]), fy[-1]))

    fig, axes = new_figure(2, 2, width=12.0, height_per_row=3.0)
    for sfx, color in zip(("_front_left", "_front_right"), ("C0", "C1")):
        axes[0, 0].plot(t, rough[f"normal_load{sfx}"] / 1e3, color=color, lw=0.7, label=f"{sfx[1:]}, class D")
        axes[0, 0].axhline(flat[f"normal_load{sfx}"] / 1e3, color=color, ls="--", lw=1.0, label=f"{sfx[1:]}, flat")
    axes[0, 0].set_ylabel("tire normal load [kN]")
    axes[0, 1].plot(t, rough["lateral_acceleration"] / G, lw=0.7, label="full vehicle, class D")
    axes[0, 1].axhline(flat["lateral_acceleration"] / G, color="k", ls="--", lw=1.0,
                       label="single track / flat-road trim")
    axes[0, 1].axhline(np.mean(rough["lateral_acceleration"][settled]) / G, color="C0", ls=":", lw=1.0,
                       label="full vehicle, mean after 0.5 s")
    axes[0, 1].set_ylabel("lateral acceleration [g]")
    roll = rough["roll_angle"]
    axes[1, 0].plot(t, np.degrees(roll - np.mean(roll[settled])), lw=0.7, label="full vehicle (about its mean)")
    axes[1, 0].plot(t, np.degrees(ride["roll_angle"]), lw=0.7, label="FullCar ride model (same road)")
    axes[1, 0].set_ylabel("roll angle fluctuation [deg]")
    # why the mean side force drops: the law's F_y against the load at the trim's slips (concave), the
    # steady point and the mean over the run's loads
    fs = speed / 0.05
    for c, sfx in ((0, "_front_left"), (2, "_rear_left")):
        kappa, alpha = planar_tire_slips_sae_to_iso_w(flat[f"slip_ratio{sfx}"], flat[f"slip_angle{sfx}"])
        n = np.linspace(0.0, 1.8 * flat[f"normal_load{sfx}"], 60)
        ones = np.ones_like(n)
        fy = planar_tire_forces_iso_w_to_sae(*model.corner_law_forces(
            c, n, kappa * ones, alpha * ones, flat[f"camber_angle{sfx}"] * ones, speed * ones))[1]
        color = "C0" if c == 0 else "C1"
        axes[1, 1].plot(n / 1e3, fy / 1e3, color=color, lw=1.0, label=f"{sfx[1:]}: law at the trim's slip")
        axes[1, 1].plot(flat[f"normal_load{sfx}"] / 1e3, quasi[c][1] / 1e3, "o", color=color, mfc="none",
                        label=f"{sfx[1:]}: steady load")
        axes[1, 1].plot(np.mean(rough[f"normal_load{sfx}"][settled]) / 1e3, quasi[c][0] / 1e3, "o", color=color,
                        label=f"{sfx[1:]}: mean over the run's loads")
    axes[1, 1].set_xlabel("tire normal load [kN]")
    axes[1, 1].set_ylabel("tire side force (SAE) [kN]")
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6)
    for ax in (axes[0, 0], axes[0, 1], axes[1, 0]):
        ax.set_xlabel("time [s]")
    fig.tight_layout()
    study.figure(fig, "rough_road_cornering",
                 caption=f"Sedan in a steady {ay / G:.1f} g turn at {speed:g} m/s, steer of the flat-road trim "
                         "held, on "
                         "two parallel ISO 8608 class-D tracks (faded in over 0.3 s)")
    lat = np.asarray(rough["lateral_acceleration"])[settled]

    def mean_and_error(signal):
        """Mean after 0.5 s and its standard error from the means of 0.25-s batches."""
        values = np.asarray(signal)[settled]
        batches = np.array_split(values, max(2, int(values.size / (0.25 * fs))))
        means = np.array([b.mean() for b in batches])
        return values.mean(), means.std(ddof=1) / np.sqrt(means.size)

    curvature, curvature_error = mean_and_error(rough["path_curvature"])

    def slip(signals, axle):
        return 0.5 * (np.asarray(signals[f"slip_angle_{axle}_left"]) + np.asarray(signals[f"slip_angle_{axle}_right"]))

    def ratio(pairs):
        return sum(q[0] for q in pairs) / sum(q[1] for q in pairs)

    rows = {"quasi-static side force ratio, front axle [-]": (1.0, ratio(quasi[:2]), np.nan),
            "quasi-static side force ratio, rear axle [-]": (1.0, ratio(quasi[2:]), np.nan),
            **{f"slip angle, {axle} axle mean [deg]": (np.degrees(slip(flat, axle)),
                                                       np.degrees(np.mean(slip(rough, axle)[settled])), np.nan)
               for axle in ("front", "rear")},
            "path curvature, mean [1/km]": (1e3 * flat["path_curvature"], 1e3 * curvature, np.nan),
            "path curvature, standard error of the mean [1/km]": (0.0, 1e3 * curvature_error, np.nan),
            "lateral acceleration, mean [g]": (flat["lateral_acceleration"] / G, np.mean(lat) / G, np.nan),
            "lateral acceleration, std [g]": (0.0, np.std(lat) / G, 0.0),
            "roll angle, mean [deg]": (np.degrees(flat["roll_angle"]), np.degrees(np.mean(roll[settled])), 0.0),
            "roll angle, std [deg]": (0.0, np.degrees(np.std(roll[settled])),
                                      np.degrees(np.std(np.asarray(ride["roll_angle"])[settled]))),
            "front-left load, std / static [-]": (0.0, np.std(rough["normal_load_front_left"][settled])
                                                  / flat["normal_load_front_left"], np.nan)}
    frame = pd.DataFrame(rows, index=["single track (flat)", "full vehicle (class D)", "FullCar (class D)"]).T
    study.table(frame, "rough_road", caption="What each model sees in the turn on the rough road (after 0.5 s; NaN: "
                                             "the model has no such signal)")
    ratio_f, ratio_r = rows["quasi-static side force ratio, front axle [-]"][1], rows[
        "quasi-static side force ratio, rear axle [-]"][1]
    study.text(
        f"On the rough road the tire loads fluctuate by {100 * rows['front-left load, std / static [-]'][1]:.0f} % "
        "(standard deviation of the front-left load). The tire force is concave in the load, so at the trim's slip "
        f"angles the mean side force of the fluctuating loads is {100 * (1 - ratio_f):.1f} % (front) and "
        f"{100 * (1 - ratio_r):.1f} % (rear) below the steady one: the single track, with steady loads, "
        "overestimates the grip of a turn on a bad road. In the run the axles make up for it with larger slip angles "
        f"(front {abs(rows['slip angle, front axle mean [deg]'][0]):.2f} -> "
        f"{abs(rows['slip angle, front axle mean [deg]'][1]):.2f} deg, rear "
        f"{abs(rows['slip angle, rear axle mean [deg]'][0]):.2f} -> "
        f"{abs(rows['slip angle, rear axle mean [deg]'][1]):.2f}"
        f" deg), and the path curvature at the held steer is {1e3 * curvature:.2f} +- {1e3 * curvature_error:.2f} "
        f"1/km against {1e3 * flat['path_curvature']:.2f} 1/km on the flat road (a {duration - 0.5:g}-s record of a "
        "random road). The ride model predicts the roll excited by the road "
        f"({np.degrees(np.std(np.asarray(ride['roll_angle'])[settled])):.2f} deg r.m.s.) but neither the steady "
        f"cornering roll ({np.degrees(flat['roll_angle']):.1f} deg) nor the roll of the side forces that fluctuate "
        f"with the loads and act above the roll axis: the full vehicle rolls {np.degrees(np.std(roll[settled])):.2f} "
        "deg r.m.s. about its mean, and its lateral acceleration fluctuates, where the ride model has no lateral "
        "motion at all.")


def run(study: Study) -> None:
    load_transfer(study)
    handling_limit(study)
    split_mu(study)
    rough_road(study)
    rollover(study)


if __name__ == "__main__":
    Study.main(run, __file__)
