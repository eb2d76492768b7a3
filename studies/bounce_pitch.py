"""Bounce and pitch: modes, nodes and Olley's flat-ride check for the shipped vehicles.

Each shipped vehicle as a 4-DOF half car (vehdyn.ride.BouncePitch(vehicle)) and as a 7-DOF
full car with anti-roll bars (vehdyn.ride.FullCar(vehicle)). The study lists the labelled modes
(body bounce, pitch, roll, wheel hop and tramp) with their damping, draws the two body modes of each
car in side view with their centres of rotation (the bounce and pitch centres), checks Olley's
flat-ride criteria, and shows the wheelbase filtering of the body response at 20 m/s — exact delay
against the 6th-order Padé state-space model.
"""

import numpy as np

import vehdyn
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.ride import (BouncePitch, FullCar, bounce_pitch_centres, olley_criteria, road_frequency_response,
                         ride_modes, with_wheelbase_delay)


def run(study: Study) -> None:
    import pandas as pd

    names = vehdyn.shipped_vehicles("passenger_car")
    # ---------------------------------------------------------------- labelled modes of the full cars
    frames = []
    for name in names:
        df = ride_modes(FullCar(vehdyn.load_vehicle(name))).to_frame()
        df = df[["undamped_frequency_hz", "natural_frequency_hz", "damping_ratio"]].copy()
        df.insert(0, "vehicle", name)
        frames.append(df.reset_index().set_index(["vehicle", "mode"]))
    modes = pd.concat(frames)
    modes.attrs["units"] = {"undamped_frequency_hz": "Hz", "natural_frequency_hz": "Hz", "damping_ratio": "-"}
    study.table(modes, "full_car_modes", caption="Full-car (7-DOF) modes of the shipped vehicles, labelled by where "
                "their kinetic energy lies; natural frequency and damping ratio from the damped model")

    # ---------------------------------------------------------------- centres and Olley
    rows = []
    fig, axes = new_figure(len(names), 1, height_per_row=2.0, width=7.0)
    for ax, name in zip(axes[:, 0], names):
        v = vehdyn.load_vehicle(name)
        bp = BouncePitch(v)
        fc = FullCar(v)
        c = bounce_pitch_centres(bp)
        o = olley_criteria(bp, roll_frequency_hz=olley_criteria(fc).roll_frequency_hz)
        two = bounce_pitch_centres(BouncePitch(v, unsprung=False))
        rows.append({"vehicle": name, "bounce_hz": c.bounce_frequency_hz, "pitch_hz": c.pitch_frequency_hz,
                     "roll_hz": o.roll_frequency_hz, "bounce_hz_2dof": two.bounce_frequency_hz,
                     "pitch_hz_2dof": two.pitch_frequency_hz, "bounce_centre_m": c.bounce_centre,
                     "pitch_centre_m": c.pitch_centre, "spring_centre_m": c.spring_centre,
                     "dynamic_index": c.dynamic_index, "front_rate_lower_by_pct": o.front_rate_lower_by,
                     "bounce_to_pitch": o.bounce_to_pitch_ratio, "olley_1_front_softer": o.front_softer,
                     "olley_2_close": o.frequencies_close, "olley_3_below_1_3hz": o.below_limit,
                     "olley_4_roll_matched": o.roll_matched})
        # side view of the two body modes: body line from rear axle to front axle, node marked
        p = bp.parameters
        x = np.linspace(-p.b - 0.5, p.a + 0.5, 50)
        ma = bp.modal_analysis()
        dof = ma.dof
        for k, (label, node, style) in enumerate((("bounce", c.bounce_centre, "-"), ("pitch", c.pitch_centre, "--"))):
            freq = c.bounce_frequency_hz if label == "bounce" else c.pitch_frequency_hz
            k_mode = int(np.argmin(np.abs(ma.natural_frequency_hz - freq)))
            z, th = ma.shapes[dof.index("sprung_displacement"), k_mode], ma.shapes[dof.index("pitch_angle"), k_mode]
            y = z + x * th
            y = y / np.max(np.abs(y)) * 0.25
            ax.plot(x, y, style, label=f"{label} {freq:.2f} Hz")
            if abs(node) < 8:
                ax.plot([node], [0.0], "o", color=ax.lines[-1].get_color())
        ax.axvline(p.a, color="k", lw=0.8)
        ax.axvline(-p.b, color="k", lw=0.8)
        ax.axhline(0.0, color="grey", lw=0.5)
        ax.set_ylabel(f"{name}\nbody lift [-]", fontsize=8)
        ax.legend(fontsize=7, loc="upper left")
        ax.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("x ahead of the sprung CG [m] (vertical lines: axles; dots: mode centres)")
    fig.tight_layout()
    study.figure(fig, "body_modes", caption="Bounce and pitch mode shapes (normalized body lift along the car) and "
                 "their centres of rotation")
    table = pd.DataFrame(rows).set_index("vehicle")
    table.attrs["units"] = {"bounce_hz": "Hz", "pitch_hz": "Hz", "roll_hz": "Hz", "bounce_hz_2dof": "Hz",
                            "pitch_hz_2dof": "Hz", "bounce_centre_m": "m ahead of CG", "pitch_centre_m": "m ahead of CG",
                            "spring_centre_m": "m ahead of CG", "dynamic_index": "-", "front_rate_lower_by_pct": "%",
                            "bounce_to_pitch": "-"}
    study.table(table, "olley", caption="Bounce and pitch centres and Olley's flat-ride criteria (4-DOF half car; "
                "roll frequency from the full car)", floatfmt="{:.4g}")

    # ---------------------------------------------------------------- wheelbase filtering: exact vs Padé
    speed = 20.0
    f = np.logspace(-0.5, 1.3, 150 if study.quick else 400)
    w = 2 * np.pi * f
    bp = BouncePitch(vehdyn.load_vehicle("sedan"))
    outputs = ["sprung_acceleration_front", "sprung_acceleration_rear"]
    exact = road_frequency_response(bp, w, speed=speed, outputs=outputs)
    pade = with_wheelbase_delay(bp, speed, order=6)
    fr = pade.frequency_response(w, outputs=outputs, inputs=["road_displacement", "road_velocity"])
    approx = fr.response[:, 0] + 1j * w * fr.response[:, 1]
    fig, axes = new_figure(2, 1, sharex=True, height_per_row=2.6)
    for k, out in enumerate(outputs):
        axes[k, 0].loglog(f, np.abs(exact.response[k, 0]), label="exact delay")
        axes[k, 0].loglog(f, np.abs(approx[k]), "--", label="Padé order 6")
        axes[k, 0].set_ylabel(f"|{out.replace('sprung_acceleration_', '')} body acc. / z_r|\n[(m/s^2)/m]", fontsize=8)
        axes[k, 0].grid(True, which="both", alpha=0.3)
    tau = bp.wheelbase / speed
    for ax in axes[:, 0]:
        ax.axvline((1.6 * 6 - 2.3) / tau / (2 * np.pi), color="grey", lw=0.8, ls=":")
    axes[0, 0].legend(fontsize=7)
    axes[0, 0].set_title(f"sedan at {speed:g} m/s: wheelbase filtering (dotted: Padé error 1e-2 limit)", fontsize=9)
    axes[-1, 0].set_xlabel("frequency [Hz]")
    fig.tight_layout()
    study.figure(fig, "wheelbase_filtering", caption="Body acceleration above the axles per unit road elevation: exact "
                 "delay (frequency domain) against the Padé state-space model")
    ok = f < (1.6 * 6 - 2.3) / tau / (2 * np.pi)
    err = np.max(np.abs(approx[:, ok] - exact.response[:, 0, ok]) / np.abs(exact.response[:, 0, ok]).max(axis=1,
                                                                                                         keepdims=True))
    fails = [r for r in rows if not (r["olley_2_close"] and r["olley_3_below_1_3hz"])]
    study.text(f"Finding: the Padé model's response stays within {100 * err:.2g} % (of the peak) of the exact-delay "
               f"response below {(1.6 * 6 - 2.3) / tau / (2 * np.pi):.1f} Hz. The 4-DOF body frequencies are within "
               f"{100 * max(abs(r['bounce_hz'] / r['bounce_hz_2dof'] - 1) for r in rows):.1f} % of the 2-DOF ride-rate "
               f"model's. {len(fails)} of {len(rows)} shipped vehicles miss Olley's frequency criteria (2) or (3): their body "
               f"frequencies span {min(min(r['bounce_hz'], r['pitch_hz']) for r in rows):.2f} to "
               f"{max(max(r['bounce_hz'], r['pitch_hz']) for r in rows):.2f} Hz against Olley's 1.3 Hz limit, and "
               "their roll modes sit well above bounce and pitch.")


if __name__ == "__main__":
    Study.main(run, __file__)
