"""Driver in the loop: McRuer's crossover model and MacAdam's optimal preview driver on the sedan.

The driver-vehicle loop is cut at the road-wheel steer and analysed with python-control
(vehdyn.driver.driver_loop_margins): the nonlinear single track linearized in straight running,
the driver's linear gains on the previewed path error, its delay (6th-order Pade) and its
neuromuscular lag (0.1 s). Two drivers:

* crossover (vehdyn.driver.CrossoverDriver): a gain on the lateral error 1 s ahead; in the table
  its gain is re-adjusted at every speed for a crossover frequency of 2.5 rad/s (McRuer's
  adjustment rule), in the figure it keeps the gain tuned at 20 m/s;
* optimal preview (vehdyn.driver.OptimalPreviewDriver, MacAdam 1981): a linear bicycle as
  internal model at the speed, a 1 s preview window after its delay.

The table lists the margins against speed at a delay of 0.15 s and, for the crossover driver,
McRuer's phase margin pi/2 - omega_c tau_e of the ideal loop omega_c e^(-tau_e s)/s with
tau_e = tau + atan(omega_c T_N)/omega_c: how far the car's loop is from the crossover form. The
figure maps the phase margin over speed and delay; the loop is stable inside the zero contour
(checked against the closed-loop poles).
"""

import numpy as np

import vehdyn
from vehdyn.driver import CrossoverDriver, OptimalPreviewDriver, driver_loop_margins
from vehdyn.handling import SingleTrack
from vehdyn.plotting import new_figure
from vehdyn.report import Study

PREVIEW, LAG, CROSSOVER = 1.0, 0.1, 2.5


def run(study: Study) -> None:
    import pandas as pd

    car = vehdyn.load_vehicle("sedan")
    model = SingleTrack(car)
    path_x = np.linspace(-100.0, 2000.0, 50)
    path_y = np.zeros_like(path_x)
    speeds = [10.0, 20.0, 30.0] if study.quick else [10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0]
    delays = [0.0, 0.2, 0.4] if study.quick else [0.0, 0.1, 0.2, 0.3, 0.4]
    if study.full:
        speeds, delays = list(np.arange(8.0, 45.1, 2.5)), list(np.round(np.arange(0.0, 0.451, 0.025), 3))

    rows = []
    for speed in speeds:
        crossover = CrossoverDriver.tuned(model, speed, path_x, path_y, crossover_frequency=CROSSOVER,
                                          preview_time=PREVIEW, delay=0.15, neuromuscular_lag=LAG)
        optimal = OptimalPreviewDriver(path_x, path_y, vehicle=car, speed=speed, preview_time=PREVIEW, delay=0.15,
                                       neuromuscular_lag=LAG)
        for label, driver in (("crossover", crossover), ("optimal preview", optimal)):
            m = driver_loop_margins(model, driver, speed)
            wc = m["crossover_frequency"]
            tau_e = driver.delay + np.arctan(wc * LAG) / wc
            rows.append({"driver": label, "speed": speed, "crossover_frequency": wc,
                         "phase_margin_deg": np.degrees(m["phase_margin"]),
                         "mcruer_phase_margin_deg": np.degrees(np.pi / 2 - wc * tau_e),
                         "gain_margin": m["gain_margin"], "stable": m["stable"]})
    frame = pd.DataFrame(rows).set_index(["driver", "speed"])
    frame.attrs["units"] = {"speed": "m/s", "crossover_frequency": "rad/s", "phase_margin_deg": "deg",
                            "mcruer_phase_margin_deg": "deg", "gain_margin": "-"}
    study.table(frame, "margins", caption="Driver-vehicle loop margins against speed (delay 0.15 s, lag 0.1 s; "
                "crossover driver re-tuned to 2.5 rad/s at each speed)")

    fixed = CrossoverDriver.tuned(model, 20.0, path_x, path_y, crossover_frequency=CROSSOVER, preview_time=PREVIEW,
                                  delay=0.15, neuromuscular_lag=LAG)
    fig, axes = new_figure(1, 2, width=11.0, height_per_row=3.8)
    for k, label in enumerate(("crossover (gain tuned at 20 m/s)", "optimal preview (MacAdam)")):
        pm = np.empty((len(delays), len(speeds)))
        stable = np.empty_like(pm, dtype=bool)
        for j, speed in enumerate(speeds):
            for i, delay in enumerate(delays):
                if k == 0:
                    driver = CrossoverDriver(path_x, path_y, gain=fixed.gain, preview_time=PREVIEW, delay=delay,
                                             neuromuscular_lag=LAG)
                else:
                    driver = OptimalPreviewDriver(path_x, path_y, vehicle=car, speed=speed, preview_time=PREVIEW,
                                                  delay=delay, neuromuscular_lag=LAG)
                m = driver_loop_margins(model, driver, speed)
                pm[i, j], stable[i, j] = np.degrees(m["phase_margin"]), m["stable"]
        ax = axes[0, k]
        levels = np.arange(-90, 91, 15)
        filled = ax.contourf(speeds, delays, np.clip(pm, -90, 90), levels=levels, cmap="RdYlGn")
        ax.contour(speeds, delays, pm, levels=[0.0], colors="k", linewidths=1.5)
        ax.plot(np.repeat(speeds, len(delays)).reshape(len(speeds), -1).T[~stable],
                np.repeat(np.array(delays)[:, None], len(speeds), 1)[~stable], "kx", ms=4, label="closed loop unstable")
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("speed [m/s]")
        if k == 0:
            ax.set_ylabel("driver delay [s]")
        ax.legend(fontsize=7, loc="upper right")
        fig.colorbar(filled, ax=ax, label="phase margin [deg]")
    study.figure(fig, "stable_region", caption="Phase margin of the driver-vehicle loop over speed and driver delay "
                 "(sedan, preview 1 s, lag 0.1 s); black line: zero margin, crosses: unstable closed loop")


if __name__ == "__main__":
    Study.main(run, __file__)
