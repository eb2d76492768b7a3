"""Sweep throughput: variants per second of each engine, and the largest difference to single runs.

Run: ``python benchmarks/bench_sweep.py [N]`` (N = 10,000 variants by default). Prints, from one
run on this machine:

1. Handling: N variants of a 10-s sine steer (0.5 Hz, 2 deg road-wheel amplitude, 100 km/h) of
   ``vehdyn.handling.SingleTrack`` with the sedan's Magic Formula tires, mass (+-10 %, yaw inertia
   with it) and CG position (+-5 cm) varied (a Latin hypercube). The cornering stiffness of a
   Magic Formula tire lives in the tire file, not among the model's batch parameters, so it is
   not varied here. Engines:

   - a loop of single ``simulate`` calls (compiled backend, RK45 rtol 1e-8: the reference),
     timed on a subset and scaled;
   - in-process batched numpy: one ``simulate`` of a batch model (``SingleTrack.variants`` with
     array parameters, ``"rk4"`` on the 10-ms grid) - the trailing batch axis of DESIGN §3. Its
     numpy right-hand side with the Magic Formula costs milliseconds per call even for small
     batches, so it is timed on one batch of 100;
   - ``vehdyn.sweep`` with ``executor="processes"`` (2 workers) and on a Dask ``LocalCluster``
     (2 workers, 1 thread each), per-variant compiled runs, 125 variants per task, on a subset.

   The metric is the peak yaw rate; "max diff" is the largest relative difference to the
   reference single runs of the same variants.
2. Ride: N quarter cars (sprung mass, spring rate and damping varied) on an ISO 8608 class B road
   at 25 m/s, r.m.s. body acceleration by the Lyapunov route: a loop of
   ``vehdyn.ride.random_response`` against one batched Kronecker solve per chunk of a
   ``vehdyn.sweep.vectorized`` function (numpy ``linalg.solve`` on a stack of 16x16 systems).

The batched compiled integrator (SIMD across variants, ``prange`` over chunks) asked for in issue
17 is not built: its rows say so.
"""

from __future__ import annotations

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import vehdyn  # noqa: E402
from vehdyn import handling  # noqa: E402

SPEED = 100 / 3.6
T = np.linspace(0.0, 10.0, 1001)
AMPLITUDE = np.deg2rad(2.0)
BASE = vehdyn.load_vehicle("sedan")


def _model():
    return handling.SingleTrack(BASE)


def _inputs(model):
    """Closed-form sine steer (exact at every stage) and the drive force that holds the speed."""
    from vehdyn.handling.maneuvers import sine_steer

    drag = float(model.parameters.drag_factor) * SPEED**2
    return {"front_steer_angle": sine_steer(AMPLITUDE, 0.5), "rear_longitudinal_force": drag}


def one_run(mass_factor, cg_shift):
    """Peak yaw rate of one variant (compiled backend, RK45 rtol 1e-8)."""
    model = _model()
    p = model.parameters
    m = model.variants(mass=p.mass * mass_factor, yaw_inertia=p.yaw_inertia * mass_factor, a=p.a - cg_shift,
                       b=p.b + cg_shift)
    res = vehdyn.simulate(m, T, _inputs(m), x0=m.straight_running(SPEED), method="RK45", rtol=1e-8, atol=1e-10)
    return {"peak_yaw_rate": float(np.max(np.abs(res["yaw_rate"])))}


def batched_run(mass_factor, cg_shift):
    """Peak yaw rates of a batch (numpy, rk4 on the 10-ms output grid, trailing batch axis)."""
    model = _model()
    p = model.parameters
    mf, cs = np.asarray(mass_factor, dtype=float), np.asarray(cg_shift, dtype=float)
    m = model.variants(mass=p.mass * mf, yaw_inertia=p.yaw_inertia * mf, a=p.a - cs, b=p.b + cs)
    x0 = np.repeat(model.straight_running(SPEED)[:, None], mf.size, axis=1)
    res = vehdyn.simulate(m, T, _inputs(m), x0=x0, method="rk4")
    return {"peak_yaw_rate": np.max(np.abs(res["yaw_rate"]), axis=0)}  # signals are (time, variant)


def _design(n, seed=0):
    import scipy.stats as st

    return vehdyn.sweep.variants(samples={"mass_factor": st.uniform(0.9, 0.2), "cg_shift": st.uniform(-0.05, 0.1)},
                                 n=n, seed=seed)


# ---------------------------------------------------------------------- ride
def quarter_car_rms(sprung_mass, spring_rate, damping, unsprung_mass=40.0, tire_stiffness=2.0e5, road="B",
                    speed=25.0):
    """Reference: vehdyn.ride.random_response per variant."""
    from vehdyn.ride import QuarterCar, random_response

    qc = QuarterCar(sprung_mass=sprung_mass, unsprung_mass=unsprung_mass, spring_rate=spring_rate, damping=damping,
                    tire_stiffness=tire_stiffness)
    return {"rms_sprung_acceleration": random_response(qc, road, speed, outputs=["sprung_acceleration"])[
        "sprung_acceleration"]}


@vehdyn.sweep.vectorized
def quarter_car_rms_batched(sprung_mass, spring_rate, damping, unsprung_mass=40.0, tire_stiffness=2.0e5,
                            speed=25.0):
    """One Kronecker Lyapunov solve per variant, stacked: the road velocity of an ISO 8608 class B
    road (waviness 2, no cut-on) is white with intensity 2 pi Gd(n0) n0^2 V (ISO 8608)."""
    from vehdyn.ride import iso8608_class_value

    ms, k, c = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (sprung_mass, spring_rate, damping))
    n = ms.size
    # states: z_s - z_u, dz_s, z_u - z_r, dz_u; input: road velocity
    A = np.zeros((n, 4, 4))
    A[:, 0, 1], A[:, 0, 3] = 1.0, -1.0
    A[:, 1, 0], A[:, 1, 1], A[:, 1, 3] = -k / ms, -c / ms, c / ms
    A[:, 2, 3] = 1.0
    A[:, 3, 0], A[:, 3, 1], A[:, 3, 2], A[:, 3, 3] = k / unsprung_mass, c / unsprung_mass, \
        -tire_stiffness / unsprung_mass, -c / unsprung_mass
    # one-sided temporal PSD of the road velocity: (2 pi)^2 Gd(n0) n0^2 V, flat; white noise of
    # intensity q has the one-sided PSD 2 q
    intensity = 2 * np.pi**2 * iso8608_class_value("B") * 0.1**2 * speed
    Q = np.zeros((n, 4, 4))
    Q[:, 2, 2] = intensity
    eye = np.eye(4)
    K = eye[None, :, None, :, None] * A[:, None, :, None, :] + A[:, :, None, :, None] * eye[None, None, :, None, :]
    X = np.linalg.solve(K.reshape(n, 16, 16), -Q.reshape(n, 16, 1)).reshape(n, 4, 4)
    Crow = A[:, 1, :]  # sprung acceleration = row 2 of A times x
    var = np.einsum("ni,nij,nj->n", Crow, X, Crow)
    return {"rms_sprung_acceleration": np.sqrt(var)}


def main(n: int = 10_000) -> None:
    import pandas as pd

    print(f"bench_sweep: {n} variants, {os.cpu_count()} cores, numpy {np.__version__}\n")
    design = _design(n)
    subset = design.iloc[: max(20, n // 500)]
    rows = []

    # --- loop of single runs (reference) on a subset, scaled
    one_run(1.0, 0.0)  # load the compiled code
    start = time.perf_counter()
    ref = np.array([one_run(*r)["peak_yaw_rate"] for r in subset.itertuples(index=False)])
    loop_rate = len(subset) / (time.perf_counter() - start)
    rows.append(("loop of simulate (compiled RK45)", len(subset), loop_rate, 0.0))

    # --- batched numpy on one batch of the first variants (it is slow: see the module docstring)
    batch = design.iloc[: max(len(ref), 100)]
    start = time.perf_counter()
    peaks = batched_run(batch["mass_factor"].to_numpy(), batch["cg_shift"].to_numpy())["peak_yaw_rate"]
    rate = len(batch) / (time.perf_counter() - start)
    rows.append((f"batched numpy (rk4 10 ms, {len(batch)}/batch)", len(batch), rate,
                 np.max(np.abs(peaks[: len(ref)] / ref - 1))))
    rows.append(("batched compiled, 1 thread", 0, np.nan, np.nan))
    rows.append(("batched compiled, 2 threads", 0, np.nan, np.nan))

    # --- process pool and Dask through vehdyn.sweep, per-variant compiled runs, on a larger subset
    pool_set = design.iloc[: max(250, n // 40)]
    from vehdyn.sweep.api import run_table

    start = time.perf_counter()
    pool = run_table(one_run, pool_set, executor="processes", chunk_size=125, progress=False)
    pool_rate = len(pool_set) / (time.perf_counter() - start)
    rows.append(("vehdyn.sweep processes (2 workers)", len(pool_set), pool_rate,
                 np.max(np.abs(pool["peak_yaw_rate"].to_numpy()[: len(ref)] / ref - 1))))
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        rows.append(("vehdyn.sweep Dask LocalCluster (not installed)", 0, np.nan, np.nan))
    else:
        with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None, silence_logs=40) as cluster, \
                Client(cluster) as client:
            run_table(one_run, pool_set.iloc[:4], executor=client, chunk_size=2, progress=False)  # warm workers
            start = time.perf_counter()
            dask = run_table(one_run, pool_set, executor=client, chunk_size=125, progress=False)
            dask_rate = len(pool_set) / (time.perf_counter() - start)
        rows.append(("vehdyn.sweep Dask LocalCluster (2 workers)", len(pool_set), dask_rate,
                     np.max(np.abs(dask["peak_yaw_rate"].to_numpy()[: len(ref)] / ref - 1))))
    frame = pd.DataFrame(rows, columns=["engine", "variants run", "variants/s", "max diff to single runs"])
    frame["x loop"] = frame["variants/s"] / loop_rate
    print("Handling: 10-s sine steer, SingleTrack + Magic Formula, peak yaw rate")
    print(frame.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    if "dask_rate" in locals():
        print(f"Dask / process pool throughput: {dask_rate / pool_rate:.2f} (goal >= 0.75)")

    # --- ride
    import scipy.stats as st

    ride = vehdyn.sweep.variants(samples={"sprung_mass": st.uniform(250.0, 100.0),
                                          "spring_rate": st.uniform(1.5e4, 1.5e4),
                                          "damping": st.uniform(800.0, 1200.0)}, n=n, seed=3)
    sub = ride.iloc[: max(20, n // 50)]
    start = time.perf_counter()
    ref_ride = np.array([quarter_car_rms(*r)["rms_sprung_acceleration"] for r in sub.itertuples(index=False)])
    ride_loop = len(sub) / (time.perf_counter() - start)
    best, out = best_time(lambda: run_table(quarter_car_rms_batched, ride, chunk_size=n, progress=False), repeats=3)
    diff = np.max(np.abs(out["rms_sprung_acceleration"].to_numpy()[: len(sub)] / ref_ride - 1))
    print("\nRide: quarter car, class B at 25 m/s, r.m.s. body acceleration (Lyapunov)")
    print(f"  loop of random_response: {ride_loop:9.0f} variants/s ({len(sub)} run)")
    print(f"  vectorized sweep:        {n / best:9.0f} variants/s (x{n / best / ride_loop:.0f}; goal >= 50,000/s), "
          f"max diff {diff:.1e}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10_000)
