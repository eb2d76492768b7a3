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
   - batched compiled (``vehdyn.simulate_many``: the variants' ``simulate`` calls grouped into one
     compiled batch, each variant with its own step-size control, bitwise its single run) on 1
     and 2 threads, at the reference's tolerance;
   - work-precision of one compiled batch of a batch model (``SingleTrack.variants`` with array
     parameters, ``_compiled_ode.solve_batch``: states only, the metric is a state) at rtol 1e-8
     to 1e-3, with the full model by RK45 and by the stiff BDF (the tire-lag modes hold RK45 at
     its stability limit), and without tire lag (the model a sine steer at constant speed could
     use: its "max diff" is then the model's error against the full reference, "to own model"
     the solver's share, against that model's own runs at rtol 1e-8), with the rhs calls per
     variant; and the same batch through ``vehdyn.simulate`` (outputs included);
   - shared step: blocks of 16 variants integrated as one system by the same compiled RK45 (one
     step size per block, chosen on the r.m.s. error of all its states);
   - ``vehdyn.sweep.run`` of a ``Scene`` (the same steer, mass varied, ``model="SingleTrack"``: the
     planner resolves that name to its first admissible match, the rung "SingleTrack(linear
     tires)"): one variant at a time (chunks of 1, as before batching) and batched;
   - ``vehdyn.sweep.run`` with ``executor="processes"`` (2 workers) and on a Dask ``LocalCluster``
     (2 workers, 1 thread each), per-variant compiled runs, 125 variants per task, 8 tasks or
     more, each engine timed twice in turn (pool, Dask, pool, Dask; the best of each).

   The metric is the peak yaw rate; "max diff" is the largest relative difference to the
   reference single runs of the same variants. Rows are timed on subsets of the N variants
   ("variants run") and scaled; each work-precision row is the best of three runs (wall and CPU
   time each). The work-precision rows also give the process's CPU time per
   variant and CPU/wall: on a machine shared with other sessions (Linux autogroup scheduling) a
   session gets one fair share whatever its thread count, so the CPU time per variant is what
   compares across loads; 2 cores / that time is the rate of two free cores.
2. Ride: N quarter cars (sprung mass, spring rate and damping varied) on an ISO 8608 class B road
   at 25 m/s, r.m.s. body acceleration by the Lyapunov route: a loop of
   ``vehdyn.ride.random_vibration`` against ``vehdyn.sweep.vectorized`` functions: one batched
   Kronecker solve per chunk (numpy ``linalg.solve`` on a stack of 16x16 systems), and the
   4x4 Lyapunov equation's closed form for this input (the variance integral of a 4th-order
   transfer function).

Issue 17's goal for batched compiled on both cores (>= 2,000 variants/s) is printed after the table.
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
WORK_PRECISION_REPEATS = 3


def _model():
    return handling.SingleTrack(BASE)


def _inputs(model):
    """Closed-form sine steer (exact at every stage) and the drive force that holds the speed."""
    from vehdyn.procedures import sine_steer

    drag = float(model.parameters.drag_factor) * SPEED**2
    return {"front_steer_angle": sine_steer(AMPLITUDE, 0.5), "rear_longitudinal_force": drag}


def _call(mass_factor, cg_shift, rtol=1e-8, model=None):
    """The ``simulate`` call of one variant, as (args, kwargs) (compiled backend, RK45), from
    ``model`` (default: built anew, as a loop of single runs does)."""
    model = _model() if model is None else model
    p = model.parameters
    m = model.variants(mass=p.mass * mass_factor, yaw_inertia=p.yaw_inertia * mass_factor, a=p.a - cg_shift,
                       b=p.b + cg_shift)
    return (m, T, _inputs(m)), dict(x0=m.straight_running(SPEED), method="RK45", rtol=rtol, atol=rtol * 1e-2)


def one_run(mass_factor, cg_shift):
    """Peak yaw rate of one variant (compiled backend, RK45 rtol 1e-8)."""
    args, kwargs = _call(mass_factor, cg_shift)
    res = vehdyn.simulate(*args, **kwargs)
    return {"peak_yaw_rate": float(np.max(np.abs(res["yaw_rate"])))}


def many_runs(design, rtol=1e-8, threads=None):
    """Peak yaw rates of the variants of ``design`` through ``vehdyn.simulate_many`` (one compiled batch)."""
    base = _model()  # built once: every variant is its parameters (SingleTrack.variants)
    calls = [_call(mf, cs, rtol, base) for mf, cs in design.itertuples(index=False)]
    results = vehdyn.simulate_many(calls, threads=threads)
    return np.array([np.max(np.abs(r.states[2])) for r in results])  # state 2: yaw rate


def batch_states(design, rtol=1e-8, threads=None, tire_lag=True, method="RK45"):
    """Peak yaw rates and rhs calls per variant of one compiled batch of a batch model
    (``SingleTrack.variants`` with array parameters; states only: the metric is a state)."""
    from vehdyn.simulation import compiled as _compiled_ode
    from vehdyn.simulation._inputs import _sample_inputs

    base = handling.SingleTrack(BASE, tire_lag=tire_lag)
    m = _batch_model(base, design)
    n = len(design)
    inputs = _inputs(m)
    table = _compiled_ode.input_table(m, inputs, T, _sample_inputs(m, inputs, T), "foh")
    x0 = np.repeat(base.straight_running(SPEED)[:, None], n, axis=1)
    y, report = _compiled_ode.solve_batch(m.compiled_batch(n), T, x0, table, method, rtol, rtol * 1e-2,
                                          threads=threads)
    return np.max(np.abs(y[:, m.state_names.index("yaw_rate")]), axis=1), float(np.mean(report[:, 2]))


def batch_simulate(design, rtol=1e-5):
    """Peak yaw rates of the same batch through ``vehdyn.simulate`` (states, inputs and outputs)."""
    base = _model()
    m = _batch_model(base, design)
    x0 = np.repeat(base.straight_running(SPEED)[:, None], len(design), axis=1)
    res = vehdyn.simulate(m, T, _inputs(m), x0=x0, method="RK45", rtol=rtol, atol=rtol * 1e-2)
    return np.max(np.abs(res["yaw_rate"]), axis=0)


def _batch_model(base, design):
    p = base.parameters
    mf, cs = design["mass_factor"].to_numpy(), design["cg_shift"].to_numpy()
    return base.variants(mass=p.mass * mf, yaw_inertia=p.yaw_inertia * mf, a=p.a - cs, b=p.b + cs)


def _chunk_rhs(t, x, u, args, dxdt):
    """The rhs of a block of variants stacked into one state vector (shared step size)."""
    batch, n, count = args
    for i in range(count):
        _rhs(t, x[i * n:(i + 1) * n], u, _pick(batch, i), dxdt[i * n:(i + 1) * n])


def shared_step_runs(design, block=16, rtol=1e-8):
    """Peak yaw rates with one step size per block of ``block`` variants (the compiled RK45 on the
    stacked system: its error norm is the r.m.s. over every state of the block)."""
    from vehdyn.simulation import compiled as _compiled_ode
    from vehdyn.simulation._inputs import _sample_inputs

    model = _model()
    u = _sample_inputs(model, _inputs(model), T)
    table = _compiled_ode.input_table(model, _inputs(model), T, u, "foh")
    peaks = []
    for k in range(0, len(design), block):
        calls = [_call(mf, cs, rtol, model) for mf, cs in design.iloc[k:k + block].itertuples(index=False)]
        batch = type(model).compiled_batch_of([c[0][0] for c in calls])
        rhs = _compiled_ode.compiled_copy(_chunk_rhs, f"bench_chunk_rhs_{batch.key}", _rhs=batch.rhs,
                                          _pick=batch.pick)
        y0 = np.concatenate([c[1]["x0"] for c in calls])
        y, _ = _compiled_ode.solve(rhs, f"bench_chunk_{batch.key}", (batch.batch, model.n_states, len(calls)), T,
                                   y0, table, "RK45", rtol, rtol * 1e-2)
        peaks.extend(np.max(np.abs(y[2::model.n_states]), axis=1))
    return np.array(peaks)


def scene_sweep(design, batched, solver=None):
    """Peak yaw rates of the same variants as ``vehdyn.sweep.run`` of a Scene (mass by its dotted name)."""
    import pandas as pd

    from vehdyn.procedures import sine_steer
    from vehdyn.sweep.api import run_table

    scene = vehdyn.Scene(vehicle=BASE, manoeuvre=sine_steer(AMPLITUDE, 0.5), speed=SPEED, duration=10.0,
                         time_step=0.01, outputs=("yaw_rate",))
    mass = BASE.mass.mass * design["mass_factor"].to_numpy()
    table = pd.DataFrame({"vehicle.mass.mass": mass,  # the unsprung masses kept: the sprung mass takes the change
                          "vehicle.mass.sprung_mass": mass - (BASE.mass.mass - BASE.mass.sprung_mass)})
    out = run_table(scene, table, metrics=["peak_yaw_rate"], chunk_size=len(table) if batched else 1,
                    progress=False, model="SingleTrack", solver=solver)
    return out["peak_yaw_rate"].to_numpy()


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
    """Reference: vehdyn.ride.random_vibration per variant."""
    from vehdyn.ride import QuarterCar, random_response

    qc = QuarterCar.from_parameters(sprung_mass=sprung_mass, unsprung_mass=unsprung_mass, spring_rate=spring_rate,
                                    damping=damping, tire_stiffness=tire_stiffness)
    return {"rms_sprung_acceleration": random_response(qc, road, speed, outputs=["sprung_acceleration"])[
        "sprung_acceleration"]}


@vehdyn.sweep.vectorized
def quarter_car_rms_batched(sprung_mass, spring_rate, damping, unsprung_mass=40.0, tire_stiffness=2.0e5,
                            speed=25.0):
    """One Kronecker Lyapunov solve per variant, stacked: the road velocity of an ISO 8608 class B
    road (waviness 2, no cut-on) is white with intensity 2 pi Gd(n0) n0^2 V (ISO 8608)."""
    from vehdyn.road import iso8608_class_value

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


@vehdyn.sweep.vectorized
def quarter_car_rms_closed_form(sprung_mass, spring_rate, damping, unsprung_mass=40.0, tire_stiffness=2.0e5,
                                speed=25.0):
    """The same variance in closed form: the body acceleration over the road velocity is
    H(s) = s k_t (c s + k) / (m_s m_u s^4 + c (m_s + m_u) s^3 + (k (m_s + m_u) + k_t m_s) s^2 + c k_t s + k k_t),
    and the variance under white noise of intensity q is q I_4 with (1 / 2 pi) int |H(j w)|^2 dw
    = I_4 = (b_2^2 a_0 a_1 a_4 + b_1^2 a_0 a_3 a_4) / (2 a_0 a_4 (a_1 a_2 a_3 - a_0 a_3^2 - a_1^2 a_4))
    for H = (b_2 s^2 + b_1 s) / (a_4 s^4 + ... + a_0) (the table of integrals of James, Nichols &
    Phillips, *Theory of Servomechanisms*, 1947, sec. 7.9): the 4x4 Lyapunov equation solved once
    on paper."""
    from vehdyn.road import iso8608_class_value

    ms, k, c = (np.asarray(v, dtype=float) for v in (sprung_mass, spring_rate, damping))
    mu, kt = unsprung_mass, tire_stiffness
    a4, a3, a2, a1, a0 = ms * mu, c * (ms + mu), k * (ms + mu) + kt * ms, c * kt, k * kt
    b2, b1 = kt * c, kt * k
    integral = (b2**2 * a0 * a1 * a4 + b1**2 * a0 * a3 * a4) / (2 * a0 * a4 * (a1 * a2 * a3 - a0 * a3**2 - a1**2 * a4))
    intensity = 2 * np.pi**2 * iso8608_class_value("B") * 0.1**2 * speed
    return {"rms_sprung_acceleration": np.sqrt(intensity * integral)}


def main(n: int = 10_000) -> None:
    import pandas as pd

    load = os.getloadavg()
    print(f"bench_sweep: {n} variants, {os.cpu_count()} cores, numpy {np.__version__}, load average {load[0]:.2f}\n")
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

    # --- batched compiled (simulate_many), 1 and 2 threads, at the reference's tolerance: bitwise
    compiled_set = design.iloc[: max(len(ref), n // 20)]
    many_runs(compiled_set.iloc[:2])  # compile
    rates = {}
    for threads in (1, 2):
        start = time.perf_counter()
        peaks = many_runs(compiled_set, threads=threads)
        rates["many", threads] = len(compiled_set) / (time.perf_counter() - start)
        rows.append((f"simulate_many RK45 rtol 1e-08, {threads} thread{'s' if threads > 1 else ''}", len(compiled_set),
                     rates["many", threads], np.max(np.abs(peaks[: len(ref)] / ref - 1))))

    # --- work-precision of one compiled batch (states only), full model and without tire lag
    wp, cpu_per_variant, errors, own_errors = [], {}, {}, {}
    runs = {("RK45", True): ((1e-8, 2), (1e-6, 2), (1e-5, 1), (1e-5, 2), (1e-4, 2), (1e-3, 2)),
            ("BDF", True): ((1e-6, 2), (1e-5, 1), (1e-5, 2), (3e-5, 2), (1e-4, 2)),
            ("RK45", False): ((1e-8, 2), (1e-5, 1), (1e-5, 2), (1e-4, 2), (1e-3, 2))}
    # each model's own reference (its compiled runs at rtol 1e-8: bitwise its single runs), for the
    # solver's share of the difference; the full model's is ``ref``
    own_ref = {True: ref, False: batch_states(compiled_set.iloc[: len(ref)], 1e-8, tire_lag=False)[0]}
    for (method, tire_lag), settings in runs.items():
        batch_states(compiled_set.iloc[:2], tire_lag=tire_lag, method=method)  # compile
        for rtol, threads in settings:
            wall = cpu = np.inf
            for _ in range(WORK_PRECISION_REPEATS):  # the best of a few: this machine's timings vary by 1.5x
                start, cpu_start = time.perf_counter(), time.process_time()
                peaks, nfev = batch_states(compiled_set, rtol, threads, tire_lag, method)
                wall, cpu = min(wall, time.perf_counter() - start), min(cpu, time.process_time() - cpu_start)
            key = method, tire_lag, rtol
            rates[key + (threads,)] = len(compiled_set) / wall
            cpu_per_variant[key] = min(cpu_per_variant.get(key, np.inf), cpu / len(compiled_set))
            errors[key] = np.max(np.abs(peaks[: len(ref)] / ref - 1))
            own_errors[key] = np.max(np.abs(peaks[: len(ref)] / own_ref[tire_lag] - 1))
            wp.append(("full" if tire_lag else "no tire lag", method, rtol, threads, nfev, len(compiled_set) / wall,
                       cpu / wall, 1e6 * cpu / len(compiled_set), errors[key], own_errors[key]))
    start = time.perf_counter()
    peaks = batch_simulate(compiled_set)
    rows.append(("simulate of the batch model, RK45 rtol 1e-05 (outputs incl.), 2 threads", len(compiled_set),
                 len(compiled_set) / (time.perf_counter() - start), np.max(np.abs(peaks[: len(ref)] / ref - 1))))
    shared_set = compiled_set.iloc[: max(len(ref), 64)]
    shared_step_runs(shared_set.iloc[:16])  # compile
    start = time.perf_counter()
    peaks = shared_step_runs(shared_set)
    rows.append(("shared step (16/block) RK45 rtol 1e-08, 1 thread", len(shared_set),
                 len(shared_set) / (time.perf_counter() - start), np.max(np.abs(peaks[: len(ref)] / ref - 1))))

    # --- vehdyn.sweep.run of a Scene: one variant at a time (before) and batched (after)
    scene_set = design.iloc[: max(len(ref), 40)]
    scene_sweep(scene_set.iloc[:2], batched=True)
    scene_sweep(scene_set.iloc[:2], batched=True, solver={"method": "BDF", "rtol": 1e-5})
    for batched, solver in ((False, None), (True, None), (True, {"method": "BDF", "rtol": 1e-5})):
        start = time.perf_counter()
        peaks = scene_sweep(scene_set, batched=batched, solver=solver)
        wall = time.perf_counter() - start
        if solver is None:
            tight = peaks
        label = f"vehdyn.sweep.run of a Scene, {'batched' if batched else 'one at a time'} (linear tires)"
        if solver is not None:
            label += ", solver BDF rtol 1e-5 (diff to its RK45 1e-8)"
        rows.append((label, len(scene_set), len(scene_set) / wall,
                     np.nan if solver is None else np.max(np.abs(peaks / tight - 1))))

    # --- process pool and Dask through vehdyn.sweep.run, per-variant compiled runs, 125 variants per task, in turn
    pool_set = design.iloc[: max(1000, n // 10)]
    from vehdyn.sweep.api import run_table

    def timed(executor):
        start = time.perf_counter()
        table = run_table(one_run, pool_set, executor=executor, chunk_size=125, progress=False)
        return len(pool_set) / (time.perf_counter() - start), table

    try:
        from distributed import Client, LocalCluster
    except ImportError:
        Client = None
    if Client is None:
        pool_rate, pool = timed("processes")
        rows.append(("vehdyn.sweep.run processes (2 workers)", len(pool_set), pool_rate,
                     np.max(np.abs(pool["peak_yaw_rate"].to_numpy()[: len(ref)] / ref - 1))))
        rows.append(("vehdyn.sweep.run Dask LocalCluster (not installed)", 0, np.nan, np.nan))
    else:
        with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None, silence_logs=40) as cluster, \
                Client(cluster) as client:
            run_table(one_run, pool_set.iloc[:4], executor=client, chunk_size=2, progress=False)  # warm workers
            (pool_rate, pool), (dask_rate, dask) = timed("processes"), timed(client)
            pool_rate, dask_rate = max(pool_rate, timed("processes")[0]), max(dask_rate, timed(client)[0])
        rows.append(("vehdyn.sweep.run processes (2 workers)", len(pool_set), pool_rate,
                     np.max(np.abs(pool["peak_yaw_rate"].to_numpy()[: len(ref)] / ref - 1))))
        rows.append(("vehdyn.sweep.run Dask LocalCluster (2 workers)", len(pool_set), dask_rate,
                     np.max(np.abs(dask["peak_yaw_rate"].to_numpy()[: len(ref)] / ref - 1))))
    frame = pd.DataFrame(rows, columns=["engine", "variants run", "variants/s", "max diff to single runs"])
    frame["x loop"] = frame["variants/s"] / loop_rate
    print(f"load average before the run: {load[0]:.2f}, after the handling rows: {os.getloadavg()[0]:.2f}")
    print("Handling: 10-s sine steer, SingleTrack + Magic Formula, peak yaw rate")
    print(frame.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    print(f"\nWork-precision, one compiled batch of {len(compiled_set)} variants (states only); max diff to the "
          "full model's single runs at rtol 1e-8")
    print(pd.DataFrame(wp, columns=["model", "method", "rtol", "threads", "rhs calls/variant", "variants/s",
                                    "CPU/wall", "CPU us/variant", "max diff", "to own model"]).to_string(
        index=False, float_format=lambda v: f"{v:.3g}"))
    from _timing import compiled_rhs_call_time

    rhs_time = {}
    for tire_lag in (True, False):
        m = handling.SingleTrack(BASE, tire_lag=tire_lag)
        x = m.straight_running(SPEED)
        u = np.zeros(m.n_inputs)
        u[m.input_names.index("front_steer_angle")] = AMPLITUDE
        rhs_time[tire_lag] = compiled_rhs_call_time(m, x, u)
        print(f"compiled rhs call ({'full' if tire_lag else 'no tire lag'}): {1e9 * rhs_time[tire_lag]:.0f} ns")
    print("CPU/wall: the share of the cores the run got (with kernel.sched_autogroup_enabled = 1 a session gets one "
          "fair share whatever its thread count, so under other sessions' load 2 threads cannot show their gain).")
    for tire_lag, bound in ((True, 1e-5), (True, 1e-4), (False, 1e-4)):
        # the cheapest run of the model whose peak yaw rates are within ``bound`` of its own reference
        within = [key for key in cpu_per_variant if key[1] == tire_lag and own_errors[key] <= bound]
        best = min(within, key=lambda key: cpu_per_variant[key])
        rate_2 = max(rate for key, rate in rates.items() if key[:3] == best and key[3] == 2)
        label = "Full model" if tire_lag else f"No tire lag ({errors[best]:.1e} off the full model)"
        print(f"{label}, max diff <= {bound:g}: cheapest {best[0]} at rtol {best[2]:g} ({own_errors[best]:.1e}): "
              f"{1e3 * cpu_per_variant[best]:.2f} ms CPU per variant = {2 / cpu_per_variant[best]:.0f} variants/s on "
              f"two free cores, {rate_2:.0f}/s measured on 2 threads (goal >= 2,000: "
              f"{'met' if rate_2 >= 2000 else 'missed'})")
        # where that time goes: the rhs calls at the measured cost of one call, and the rest (the method)
        calls = next(row[4] for row in wp if row[0] == ("full" if tire_lag else "no tire lag") and row[1] == best[0]
                     and row[2] == best[2])
        in_rhs = calls * rhs_time[tire_lag]
        print(f"  of which {calls:.0f} rhs calls x {1e9 * rhs_time[tire_lag]:.0f} ns = {1e3 * in_rhs:.2f} ms, the method "
              f"{1e3 * (cpu_per_variant[best] - in_rhs):.2f} ms; 2,000/s on two free cores needs <= 1 ms per variant "
              f"and thread")
    print(f"2 threads / 1 thread at rtol 1e-5: RK45 {rates['RK45', True, 1e-5, 2] / rates['RK45', True, 1e-5, 1]:.2f}, "
          f"BDF {rates['BDF', True, 1e-5, 2] / rates['BDF', True, 1e-5, 1]:.2f}; simulate_many at rtol 1e-8 "
          f"{rates['many', 2] / rates['many', 1]:.2f}")
    if Client is not None:
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
    print("\nRide: quarter car, class B at 25 m/s, r.m.s. body acceleration (Lyapunov)")
    print(f"  loop of random_response:    {ride_loop:11.0f} variants/s ({len(sub)} run)")
    for label, function in (("vectorized Kronecker solve", quarter_car_rms_batched),
                            ("vectorized closed form", quarter_car_rms_closed_form)):
        best, out = best_time(lambda: run_table(function, ride, chunk_size=n, progress=False), repeats=3)
        diff = np.max(np.abs(out["rms_sprung_acceleration"].to_numpy()[: len(sub)] / ref_ride - 1))
        print(f"  {label + ':':27} {n / best:11.0f} variants/s (x{n / best / ride_loop:.0f}; goal >= 50,000/s), "
              f"max diff {diff:.1e}")
    print(f"load average at the end: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10_000)
