"""`vehdyn compile` and vehdyn.warm_up(): the shipped models' compiled code built ahead of time, after
which an auto call runs compiled from its first call; unknown names are one line naming them."""

import numpy as np
import pytest

import vehdyn
from vehdyn.cli import main, shipped_runs
from vehdyn.simulation import _background

pytest.importorskip("numba")


@pytest.fixture
def builds(tmp_path, monkeypatch):
    monkeypatch.setenv(_background.DIR_ENV, str(tmp_path / "builds"))
    _background._READY.clear()
    yield
    _background._READY.clear()


@pytest.mark.compiled_vs_numpy  # within the integrator's tolerance, not ulps
def test_compile_builds_a_model_that_auto_then_runs_compiled(builds, capsys, monkeypatch):
    assert main(["compile", "lift_off"]) == 0
    captured = capsys.readouterr()
    assert "lift_off" in captured.out and "total" in captured.out and "1/1" in captured.err
    _background._READY.clear()  # as in a new process: the build record alone says it is built
    monkeypatch.setenv(_background.ENV, "1")
    model, t, inputs, x0 = shipped_runs(["lift_off"])["lift_off"]()
    auto = vehdyn.simulate(model, t, inputs, x0=x0)
    assert auto.backend == "compiled" and "in the cache" in auto.backend_reason
    assert not _background._CHILDREN
    numpy_run = vehdyn.simulate(model, t, inputs, x0=x0, backend="numpy")
    scale = np.max(np.abs(numpy_run.outputs), axis=1, keepdims=True) + 1e-12
    assert np.max(np.abs(auto.outputs - numpy_run.outputs) / scale) < 1e-3  # rtol 1e-6 runs, lift-off kinks


def test_warm_up_reports_each_model_and_its_progress(builds):
    calls = []
    seconds = vehdyn.warm_up(["lift_off"], progress=False)
    assert list(seconds) == ["lift_off"] and seconds["lift_off"] > 0
    vehdyn.cli.warm_up(["lift_off"], progress=lambda i, n, name: calls.append((i, n, name)))
    assert calls == [(0, 1, "lift_off"), (1, 1, "done")]


def test_an_unknown_model_is_one_line_naming_it(capsys):
    assert main(["compile", "single_track", "bicycle9"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("vehdyn compile:") and "'bicycle9'" in err and "single_track" in err


def test_every_shipped_run_is_the_model_it_names():
    from vehdyn.full_vehicle import FullVehicle
    from vehdyn.handling import SingleTrack
    from vehdyn.interconnect import ClosedLoop
    from vehdyn.ride import LiftOff

    kinds = {"single_track": SingleTrack, "single_track_linear": SingleTrack, "single_track_wheel_spin": SingleTrack,
             "full_vehicle": FullVehicle, "abs": ClosedLoop, "esc": ClosedLoop, "driver": ClosedLoop,
             "lift_off": LiftOff}
    runs = shipped_runs()
    assert set(runs) == set(kinds)
    for name, make in runs.items():
        model, t, inputs, x0 = make()
        assert isinstance(model, kinds[name]), name
        assert model.compiled_rhs() is not None, name
