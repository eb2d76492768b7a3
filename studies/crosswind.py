"""Crosswind sensitivity: a car driving through a zone of lateral wind, steering held and driver on.

Each shipped vehicle (nonlinear single-track model, Magic Formula tires with lag) drives straight
into a 20 m/s lateral wind blowing over a length of road, in the style of the ISO 12021 open-loop
test: the aerodynamic side force acts at the centre of pressure (side-force coefficient slope and
centre of pressure from the vehicle file's ``aero`` group: typical passenger-car values after
Hucho). With the steering wheel held, the car's answer is set by where the centre of pressure lies
against the neutral steer point: ahead of it (the usual case) the car yaws downwind and drifts
away from its path. With the preview driver steering, the lateral deviation stays small. The
linear bicycle's steady yaw rate per unit side force against the force's position shows the sign
change at the neutral steer point.

A caravan amplifies it: the compact towing the shipped caravan (exact linear car–trailer model
with the same side-force law on both bodies, steering held) against the compact alone —
frequency responses of yaw rate and lateral offset to the lateral wind, the same gust in time,
and the amplification against the caravan's side-force area and against speed up to the
critical speed, where the lightly damped snaking mode resonates with the gust.
"""

import numpy as np

import vehdyn
from vehdyn import handling, procedures
from vehdyn.handling import ArticulatedSingleTrack, LinearBicycle, LinearCarTrailer, trailer_crosswind_amplification
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.units import GRAVITY

VEHICLES = ("sedan", "compact", "van")
WIND = 20.0  # m/s
LENGTH = 40.0  # m


def run(study: Study) -> None:
    import pandas as pd

    speed = 100 / 3.6
    duration = 2.5 if study.quick else 4.0
    # --- time histories: driver off and on, every vehicle at 100 km/h
    fig, axes = new_figure(3, 1, width=7.0, height_per_row=2.4, sharex=True)
    rows = []
    for k, name in enumerate(VEHICLES):
        vehicle = vehdyn.load_vehicle(name)
        for driver in (False, True):
            m = procedures.crosswind_sensitivity(vehicle, speed, wind_speed=WIND, wind_length=LENGTH, driver=driver,
                                               duration=duration)
            res = m.result
            style = "--" if driver else "-"
            label = f"{name}{', driver' if driver else ', held'}"
            axes[0, 0].plot(res["x"], res["wind_velocity_lateral"], style, color=f"C{k}", label=label)
            axes[1, 0].plot(res["x"], np.rad2deg(res["yaw_rate"]), style, color=f"C{k}")
            axes[2, 0].plot(res["x"], res["y"], style, color=f"C{k}")
            rows.append({"vehicle": name, "driver": driver, "centre_of_pressure_m": m.centre_of_pressure,
                         "neutral_steer_point_m": m.neutral_steer_point,
                         "peak_yaw_rate_deg_s": np.rad2deg(m.peak_yaw_rate),
                         "peak_lateral_acceleration_g": m.peak_lateral_acceleration / GRAVITY,
                         "lateral_deviation_at_exit_m": m.lateral_deviation_at_exit,
                         "lateral_deviation_end_m": m.lateral_deviation,
                         "max_lateral_deviation_m": m.max_lateral_deviation})
    axes[0, 0].set_ylabel("lateral wind [m/s]")
    axes[1, 0].set_ylabel("yaw rate [deg/s]")
    axes[2, 0].set_ylabel("lateral deviation y [m]")
    axes[2, 0].set_xlabel("distance travelled x [m]")
    axes[0, 0].legend(fontsize=7, ncol=3)
    for ax in axes[:, 0]:
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    study.figure(fig, "crosswind_time_histories",
                 caption=f"{WIND:g} m/s lateral wind over {LENGTH:g} m at 100 km/h; solid: steering held, "
                         "dashed: preview driver holding the path y = 0 (SAE: y to the right, downwind)")

    # --- deviation against speed, steering held
    speeds = np.array([20.0, 30.0, 40.0]) if study.quick else np.linspace(15.0, 45.0, 7)
    fig, axes = new_figure(1, 2, width=10.0, height_per_row=3.2)
    sweep = []
    for k, name in enumerate(VEHICLES):
        vehicle = vehdyn.load_vehicle(name)
        dev, yaw = [], []
        for u in speeds:
            m = procedures.crosswind_sensitivity(vehicle, float(u), wind_speed=WIND, wind_length=LENGTH,
                                               duration=2.0)
            dev.append(m.lateral_deviation)
            yaw.append(np.rad2deg(m.peak_yaw_rate))
            sweep.append({"vehicle": name, "speed": float(u), "lateral_deviation_2s_m": m.lateral_deviation,
                          "peak_yaw_rate_deg_s": yaw[-1]})
        axes[0, 0].plot(speeds * 3.6, dev, "-o", ms=3, color=f"C{k}", label=name)
        axes[0, 1].plot(speeds * 3.6, yaw, "-o", ms=3, color=f"C{k}", label=name)
    axes[0, 0].set_ylabel("lateral deviation 2 s after entry [m]")
    axes[0, 1].set_ylabel("peak yaw rate [deg/s]")
    for ax in axes[0]:
        ax.set_xlabel("speed [km/h]")
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.tight_layout()
    study.figure(fig, "crosswind_vs_speed", caption=f"Steering held: response to the {WIND:g} m/s wind zone "
                                                     "against speed")

    # --- the neutral steer point explains the sign: linear bicycle, side force at x_p
    fig, axes = new_figure(1, 1, width=7.0, height_per_row=3.4)
    ax = axes[0, 0]
    for k, name in enumerate(VEHICLES):
        vehicle = vehdyn.load_vehicle(name)
        L, a = vehicle.wheelbase, vehicle.geometry.cg_to_front_axle
        fraction = np.linspace(-0.1, 1.1, 61)
        x_p = a - fraction * L
        r = handling.steady_state_crosswind_yaw_rate(vehicle, speed, 1000.0, x_p)
        ax.plot(fraction, np.rad2deg(r), color=f"C{k}", label=name)
        nsp = handling.neutral_steer_point(vehicle).from_front_axle / L
        ax.axvline(nsp, color=f"C{k}", ls=":", lw=1)
        f_p = vehicle.aero.centre_of_pressure_from_front_axle
        r_p = handling.steady_state_crosswind_yaw_rate(vehicle, speed, 1000.0, a - f_p * L)
        ax.plot([f_p], [np.rad2deg(r_p)], "o", color=f"C{k}")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel("position of the side force behind the front axle / wheelbase [-]")
    ax.set_ylabel("steady yaw rate per 1 kN side force [deg/s]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    study.figure(fig, "neutral_steer_point_and_centre_of_pressure",
                 caption="Linear bicycle at 100 km/h, steering held: steady yaw rate under a 1 kN side force "
                         "(toward +y) against where it acts; dotted: neutral steer point, dot: the vehicle "
                         "file's centre of pressure")

    table = pd.DataFrame(rows).set_index(["vehicle", "driver"])
    table.attrs["units"] = {"centre_of_pressure_m": "m ahead of CG", "neutral_steer_point_m": "m ahead of CG",
                            "peak_yaw_rate_deg_s": "deg/s", "peak_lateral_acceleration_g": "g",
                            "lateral_deviation_at_exit_m": "m", "lateral_deviation_end_m": "m",
                            "max_lateral_deviation_m": "m"}
    study.table(table, "crosswind_metrics", caption=f"Wind zone {WIND:g} m/s over {LENGTH:g} m at 100 km/h, "
                                                    f"{duration:g} s after entry")
    sweep_table = pd.DataFrame(sweep).set_index(["vehicle", "speed"])
    sweep_table.attrs["units"] = {"speed": "m/s", "lateral_deviation_2s_m": "m", "peak_yaw_rate_deg_s": "deg/s"}
    study.table(sweep_table, "crosswind_vs_speed", caption="Steering held, against speed")
    held = table.xs(False, level="driver")["max_lateral_deviation_m"]
    steered = table.xs(True, level="driver")["max_lateral_deviation_m"]
    study.text("Every shipped vehicle has its centre of pressure (from the vehicle file) ahead of its neutral "
               "steer point, so the wind yaws it downwind and, with the steering held, it drifts "
               + ", ".join(f"{held[n]:.2f} m ({n})" for n in VEHICLES)
               + " from its path within the run; the preview driver keeps it within "
               + ", ".join(f"{steered[n]:.2f} m" for n in VEHICLES)
               + ". A centre of pressure behind the neutral steer point would turn the vehicle into the wind "
               "instead (the curve's sign change).")
    _trailer_amplification(study)


def _trailer_amplification(study: Study) -> None:
    """The compact with and without the shipped caravan: linear models, wind on both bodies."""
    import pandas as pd
    from scipy.integrate import cumulative_trapezoid

    from vehdyn.procedures import wind_zone_signal

    car, caravan = vehdyn.load_vehicle("compact"), vehdyn.load_trailer("caravan")
    vc = LinearCarTrailer(car, caravan, 20.0).critical_speed()
    speeds = (80 / 3.6, 100 / 3.6)
    omega = np.logspace(-1, np.log10(30.0), 300)

    # --- frequency responses: yaw rate and lateral offset per m/s of wind, car alone and towing
    fig, axes = new_figure(1, 2, width=11.0, height_per_row=3.6)
    for k, u in enumerate(speeds):
        amp = trailer_crosswind_amplification(car, caravan, u, omega)
        hz = omega / (2 * np.pi)
        axes[0, 0].loglog(hz, np.rad2deg(amp.car_yaw_rate), ":", color=f"C{k}", label=f"compact, {u * 3.6:.0f} km/h")
        axes[0, 0].loglog(hz, np.rad2deg(amp.combination_yaw_rate), "-", color=f"C{k}",
                          label=f"compact + caravan, {u * 3.6:.0f} km/h")
        axes[0, 1].loglog(hz, amp.car_lateral_offset, ":", color=f"C{k}")
        axes[0, 1].loglog(hz, amp.combination_lateral_offset, "-", color=f"C{k}")
    axes[0, 0].set_ylabel("|yaw rate / wind| [(deg/s)/(m/s)]")
    axes[0, 1].set_ylabel("|lateral offset / wind| [m/(m/s)]")
    for ax in axes[0]:
        ax.set_xlabel("wind frequency [Hz]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    study.figure(fig, "trailer_crosswind_frequency_response",
                 caption="Steering held, lateral wind on both bodies (linear side-force law): the caravan "
                         "(solid) against the car alone (dotted); the peak is the caravan's snaking mode")

    # --- a gust in time: the same wind on both bodies (uniform in space), linear models
    u, wind, length = 80 / 3.6, 10.0, 40.0
    t = np.linspace(0.0, 6.0, 1201)
    gust = wind_zone_signal(u, wind, length, car.wheelbase, start=0.5)
    fig, axes = new_figure(2, 1, width=7.0, height_per_row=2.6, sharex=True)
    rows = []
    for label, model, style in (("compact", LinearBicycle(car, u, crosswind=True), ":"),
                                ("compact + caravan", LinearCarTrailer(car, caravan, u, crosswind=True), "-")):
        res = vehdyn.simulate(model, t, {"wind_velocity_lateral": gust})
        r, v = res["yaw_rate"], res["lateral_velocity"]
        psi = cumulative_trapezoid(r, t, initial=0.0)
        y = cumulative_trapezoid(v + u * psi, t, initial=0.0)  # small angles, straight path
        axes[0, 0].plot(t, np.rad2deg(r), style, color="k", label=label)
        axes[1, 0].plot(t, y, style, color="k")
        row = {"model": label, "peak_yaw_rate_deg_s": float(np.rad2deg(r[np.argmax(np.abs(r))])),
               "lateral_offset_end_m": float(y[-1]), "max_lateral_offset_m": float(np.max(np.abs(y)))}
        if "articulation_angle" in res.output_names:
            th = res["articulation_angle"]
            row["peak_articulation_deg"] = float(np.rad2deg(th[np.argmax(np.abs(th))]))
        rows.append(row)
    axes[0, 0].set_ylabel("yaw rate [deg/s]")
    axes[1, 0].set_ylabel("lateral offset of the car [m]")
    axes[1, 0].set_xlabel("time [s]")
    axes[0, 0].legend(fontsize=8)
    for ax in axes[:, 0]:
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    study.figure(fig, "trailer_crosswind_gust",
                 caption=f"{wind:g} m/s gust lasting {length:g} m of travel at 80 km/h, the same wind on both "
                         "bodies at once (uniform in space), steering held, linear models")
    gust_table = pd.DataFrame(rows).set_index("model")
    gust_table.attrs["units"] = {"peak_yaw_rate_deg_s": "deg/s", "lateral_offset_end_m": "m",
                                 "max_lateral_offset_m": "m", "peak_articulation_deg": "deg"}
    study.table(gust_table, "trailer_crosswind_gust", caption=f"{wind:g} m/s gust at 80 km/h, steering held, "
                                                              f"{t[-1]:g} s")

    # --- amplification against the caravan's side-force area and against speed
    areas = np.linspace(0.0, 10.0, 21)
    ratio_speeds = np.array([0.4, 0.6, 0.8, 0.9, 0.95]) * vc
    fine = np.linspace(0.5, 10.0, 800)
    by_area = [trailer_crosswind_amplification(car, caravan.replace(frontal_area=a), 80 / 3.6, fine) for a in areas]
    by_speed = [trailer_crosswind_amplification(car, caravan, float(s_), fine) for s_ in ratio_speeds]
    fig, axes = new_figure(1, 2, width=11.0, height_per_row=3.4)
    axes[0, 0].plot(areas, [a.peak_yaw_rate_ratio for a in by_area], "-o", ms=3, label="peak |r/w|, any frequency")
    axes[0, 0].plot(areas, [abs(a.steady_yaw_rate_ratio) for a in by_area], "-s", ms=3, label="|steady r/w|")
    axes[0, 0].axvline(caravan.frontal_area, color="k", ls=":", lw=1)
    axes[0, 0].set_xlabel("caravan reference area (side-force coefficient slope fixed) [m^2]")
    axes[0, 1].plot(ratio_speeds * 3.6, [a.peak_yaw_rate_ratio for a in by_speed], "-o", ms=3)
    axes[0, 1].axvline(vc * 3.6, color="k", ls=":", lw=1)
    axes[0, 1].set_xlabel("speed [km/h] (dotted: critical speed)")
    for ax in axes[0]:
        ax.set_ylabel("combination / car alone [-]")
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.tight_layout()
    study.figure(fig, "trailer_crosswind_amplification",
                 caption="Yaw-rate response to lateral wind of the compact with the caravan over that of the "
                         "compact alone: against the caravan's side-force area at 80 km/h, and against speed")
    amp_table = pd.DataFrame({"speed_kmh": ratio_speeds * 3.6,
                              "peak_yaw_rate_ratio": [a.peak_yaw_rate_ratio for a in by_speed],
                              "steady_yaw_rate_ratio": [a.steady_yaw_rate_ratio for a in by_speed]}).set_index(
        "speed_kmh")
    amp_table.attrs["units"] = {"speed_kmh": "km/h", "peak_yaw_rate_ratio": "-", "steady_yaw_rate_ratio": "-"}
    study.table(amp_table, "trailer_crosswind_amplification", caption="Compact + caravan over compact alone")
    at80 = trailer_crosswind_amplification(car, caravan, 80 / 3.6, fine)
    study.text(
        f"Towing the caravan, the compact's yaw-rate response to lateral wind peaks {at80.peak_yaw_rate_ratio:.1f} "
        f"times higher than alone at 80 km/h, at the caravan's snaking frequency; the steady yaw rate under a "
        f"constant wind is {at80.steady_yaw_rate_ratio:+.1f} times the car's (negative: the caravan, whose wind "
        f"force acts ahead of its axle, passes part of it to the hitch behind the car's rear axle and turns the car "
        f"into the wind). Against the caravan's side-force area the ratio first falls, from "
        f"{by_area[0].peak_yaw_rate_ratio:.1f} with no wind on the caravan (its mass alone) to "
        f"{min(a.peak_yaw_rate_ratio for a in by_area):.1f} near "
        f"{areas[int(np.argmin([a.peak_yaw_rate_ratio for a in by_area]))]:g} m^2, where the force the caravan "
        f"passes to the hitch cancels the car's own downwind yaw, then grows about linearly (to "
        f"{by_area[-1].peak_yaw_rate_ratio:.1f} at {areas[-1]:g} m^2); it grows as the speed nears the critical speed "
        f"{vc * 3.6:.0f} km/h ({by_speed[-1].peak_yaw_rate_ratio:.0f} at 95 % of it), where the snaking mode's "
        "damping vanishes. The caravan's aerodynamic numbers are assumed (data/trailers/caravan.toml).")

    # --- the nonlinear wind-zone test with the caravan: ArticulatedSingleTrack, driver off and on
    rows = []
    for wind_speed in (10.0, 20.0):
        for label, model in (("compact", None), ("compact + caravan", ArticulatedSingleTrack(car, caravan))):
            for driver in (False, True):
                m = procedures.crosswind_sensitivity(car, 80 / 3.6, wind_speed=wind_speed, wind_length=LENGTH,
                                                   driver=driver, duration=3.0, model=model)
                row = {"wind_m_s": wind_speed, "model": label, "driver": driver,
                       "peak_yaw_rate_deg_s": np.rad2deg(m.peak_yaw_rate),
                       "peak_lateral_acceleration_g": m.peak_lateral_acceleration / GRAVITY,
                       "max_lateral_deviation_m": m.max_lateral_deviation}
                if model is not None:
                    row["max_articulation_deg"] = float(np.rad2deg(np.max(np.abs(m.result["articulation_angle"]))))
                rows.append(row)
    table = pd.DataFrame(rows).set_index(["wind_m_s", "model", "driver"])
    table.attrs["units"] = {"wind_m_s": "m/s", "peak_yaw_rate_deg_s": "deg/s", "peak_lateral_acceleration_g": "g",
                            "max_lateral_deviation_m": "m", "max_articulation_deg": "deg"}
    study.table(table, "trailer_crosswind_zone", caption=f"Nonlinear wind-zone test at 80 km/h ({LENGTH:g} m zone, "
                                                         "3 s): SingleTrack alone, ArticulatedSingleTrack with the "
                                                         "caravan (side-force law on both bodies)")
    combo20 = table.loc[(20.0, "compact + caravan", False)]
    study.text(
        "In the nonlinear wind-zone test (Magic Formula tires on the car, Fiala on the caravan) the caravan again "
        "turns the car into the wind; at 10 m/s the preview driver holds the combination within "
        f"{table.loc[(10.0, 'compact + caravan', True), 'max_lateral_deviation_m']:.2f} m. At 20 m/s "
        f"(aerodynamic sideslip 42 deg, beyond the about 20 deg up to which the linear side-force law is measured) "
        f"the combination with the steering held reaches {abs(combo20['peak_lateral_acceleration_g']):.2f} g and "
        f"{abs(combo20['peak_yaw_rate_deg_s']):.0f} deg/s: the car's tires saturate; with the driver steering "
        f"against it the caravan swings out to "
        f"{table.loc[(20.0, 'compact + caravan', True), 'max_articulation_deg']:.0f} deg of articulation.")


if __name__ == "__main__":
    Study.main(run, __file__)
