"""Every engine gives bitwise the same metrics for the same variants."""

import concurrent.futures as cf

import numpy as np
import pytest
import scipy.stats as st

import vehdyn
from vehdyn.sweep import run


@pytest.fixture(scope="module")
def scene():
    return vehdyn.Scene(vehicle="sedan", manoeuvre="sine_steer", speed=25.0, duration=1.5,
                        manoeuvre_parameters={"lateral_acceleration": 3.0, "frequency": 1.0},
                        outputs=("yaw_rate", "lateral_acceleration"))


def _args(scene):
    # one invalid variant (negative mass) rides along in every engine
    return dict(grid={"vehicle.mass.mass": [1500.0, -1.0, 1650.0],
                      "vehicle.tires.front_cornering_stiffness": [6.0e4, 9.0e4]},
                metrics=["peak_yaw_rate", "rms_lateral_acceleration", "understeer_gradient"],
                chunk_size=2, progress=False, model="SingleTrack")


@pytest.fixture(scope="module")
def reference(scene):
    return run(scene, **_args(scene))


def _same(a, b):
    assert a.columns.equals(b.columns) and a.index.equals(b.index)
    for c in a.columns:
        if c == "error":
            assert list(a[c]) == list(b[c])
        else:  # bitwise, NaN where NaN: every engine runs the same code on this machine (its processes,
            # threads and Dask workers inherit numpy's SIMD dispatch; a cluster of other CPUs would not)
            x, y = a[c].to_numpy(), b[c].to_numpy()
            assert x.tobytes() == y.tobytes(), c


def test_reference_is_consistent(reference):
    assert (reference["error"].notna() == (reference["vehicle.mass.mass"] < 0)).all()
    assert reference.loc[reference["error"].isna(), "peak_yaw_rate"].gt(0).all()


@pytest.mark.parametrize("engine", ["processes", "threads", "executor"])
def test_pool_engines_are_bitwise_identical(scene, reference, engine):
    if engine == "executor":
        with cf.ThreadPoolExecutor(max_workers=2) as pool:
            table = run(scene, executor=pool, **_args(scene))
    else:
        table = run(scene, executor=engine, **_args(scene))
    _same(table, reference)


def test_dask_local_cluster_is_bitwise_identical(scene, reference):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as client:
        table = run(scene, executor=client, **_args(scene))
        # the chunks ran on the workers, not here
        assert len(client.scheduler_info()["workers"]) == 2
    _same(table, reference)


def test_not_an_executor_is_refused(scene):
    with pytest.raises(vehdyn.ParameterError, match="executor"):
        run(scene, grid={"speed": [20.0]}, executor=object(), progress=False)


def test_samples_identical_across_engines(scene):
    args = dict(samples={"speed": st.uniform(15.0, 15.0)}, n=4, seed=7, metrics=["peak_yaw_rate"],
                chunk_size=1, progress=False, model="SingleTrack")
    a = run(scene, **args)
    b = run(scene, executor="processes", **args)
    _same(a, b)
    assert np.all(np.diff(a["speed"].to_numpy()) != 0)


def test_batched_chunk_is_bitwise_the_one_at_a_time_runs(scene):
    """A chunk's scenes run as one compiled batch (simulate_many) and give bitwise each variant's own run."""
    from vehdyn.sweep.engines import ChunkTask
    from vehdyn.sweep.targets import SceneTarget, simulation_call

    target = SceneTarget(scene, "SingleTrack")
    names = ["speed", "vehicle.mass.mass", "vehicle.mass.yaw_inertia"]
    rows = [(22.0, 1500.0, 1900.0), (28.0, 1650.0, 2050.0), (25.0, -5.0, 2000.0), (25.0, 1450.0, 1950.0)]
    metrics = ["peak_yaw_rate", "rms_lateral_acceleration", "final_yaw_rate"]
    params = dict(zip(names, rows[0]))
    setup = target.setup(params)
    args, kwargs = simulation_call(setup.run)  # the ladder's SingleTrack runs through simulate
    assert kwargs["method"] == "RK45" and args[0] is setup.model
    batched = ChunkTask(target, names, metrics)(list(range(4)), rows)
    alone = [ChunkTask(target, names, metrics)([i], [r]) for i, r in enumerate(rows)]
    for i, frame in enumerate(alone):  # bitwise: one compiled loop, each variant with its own step control
        for c in metrics:
            assert batched[c].to_numpy()[i].tobytes() == frame[c].to_numpy()[0].tobytes(), (i, c)
        assert batched["error"][i] == frame["error"][0]
    assert "ParameterError" in batched["error"][2] and batched["error"].isna().sum() == 3
    result = vehdyn.simulate_many([simulation_call(setup.run)])[0]
    assert "batch of 1" in result.method_reason
    assert simulation_call(lambda: 1.0) is None and simulation_call(print) is None


def test_solver_options_replace_the_rungs_own_in_every_variant(scene):
    """``solver=`` changes the method and tolerance of each variant's simulate call (a round trip:
    the sweep's metric = a direct simulate of the rung with those options, bitwise) and costs
    the metric only the solver's error (against the rung's own tight RK45)."""
    import numpy as np

    from vehdyn.sweep.targets import SceneTarget, simulation_call

    grid = {"vehicle.mass.mass": [1450.0, 1600.0]}
    tight = vehdyn.sweep.run(scene, grid=grid, metrics=["peak_yaw_rate"], model="SingleTrack", progress=False)
    loose = vehdyn.sweep.run(scene, grid=grid, metrics=["peak_yaw_rate"], model="SingleTrack", progress=False,
                         solver={"method": "BDF", "rtol": 1e-5})
    target = SceneTarget(scene, "SingleTrack", {"method": "BDF", "rtol": 1e-5})
    setup = target.setup({"vehicle.mass.mass": 1600.0})
    args, kwargs = simulation_call(setup.run)
    assert target.call(setup)[1]["rtol"] == 1e-5 and target.call(setup)[1]["method"] == "BDF"
    kwargs.update(method="BDF", rtol=1e-5, atol=1e-7)
    direct = vehdyn.simulate(*args, **kwargs)
    assert "compiled BDF" in direct.message
    assert loose["peak_yaw_rate"].iloc[1] == np.max(np.abs(direct["yaw_rate"]))  # both the compiled BDF
    assert np.allclose(loose["peak_yaw_rate"], tight["peak_yaw_rate"], rtol=1e-4)
    assert not np.array_equal(loose["peak_yaw_rate"], tight["peak_yaw_rate"])


@pytest.mark.parametrize("solver, match", [({"tolerance": 1e-5}, "tolerance"), ({"method": "Euler"}, "Euler"),
                                           ({"rtol": -1.0}, "rtol"), ("BDF", "mapping")])
def test_bad_solver_options_are_named(scene, solver, match):
    with pytest.raises(vehdyn.ParameterError, match=match) as info:
        vehdyn.sweep.run(scene, grid={"speed": [20.0]}, model="SingleTrack", progress=False, solver=solver)
    assert info.value.key == "solver"
    with pytest.raises(vehdyn.ParameterError, match="Scene") as info:
        vehdyn.sweep.run(lambda speed: {"v": speed}, grid={"speed": [20.0]}, progress=False, solver={"rtol": 1e-5})
    assert info.value.key == "solver"
