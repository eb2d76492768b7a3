"""The metrics registry: families against closed forms, fixed names against the handling functions."""

import numpy as np
import pytest

import vehdyn
from vehdyn.sweep import metrics as m


def _run(signal, t):
    return m.Run(time=t, outputs={"x": signal}, units={"x": "m"})


def test_families_against_closed_forms():
    t = np.linspace(0.0, 2.0, 2001)[:-1]  # two whole periods, endpoint excluded
    run = _run(3.0 * np.sin(2 * np.pi * t) + 1.0, t)
    units = {"x": "m"}
    assert m.metric("rms_x", units).function(run) == pytest.approx(np.sqrt(1.0 + 9.0 / 2), rel=1e-12)
    assert m.metric("mean_x", units).function(run) == pytest.approx(1.0, abs=1e-12)
    assert m.metric("peak_x", units).function(run) == pytest.approx(4.0, rel=1e-9)
    assert m.metric("min_x", units).function(run) == pytest.approx(-2.0, rel=1e-9)
    assert m.metric("final_x", units).function(run) == run.outputs["x"][-1]
    assert m.metric("rms_x", units).unit == "m" and m.metric("overshoot_x", units).unit == "-"


def test_iso7401_metrics_match_step_response_metrics():
    scene = vehdyn.Scene(vehicle="sedan", manoeuvre="step_steer", speed=30.0, duration=3.0,
                         manoeuvre_parameters={"lateral_acceleration": 2.0}, outputs=("yaw_rate",))
    table = vehdyn.sweep.run(scene, grid={"speed": [30.0]}, model="LinearBicycle", progress=False,
                         metrics=["overshoot_yaw_rate", "response_time_yaw_rate", "steady_state_yaw_rate"])
    res = vehdyn.run(scene, model="LinearBicycle").result
    direct = vehdyn.procedures.step_response_metrics(res, "yaw_rate")
    assert table["overshoot_yaw_rate"].iloc[0] == float(direct.overshoot)
    assert table["response_time_yaw_rate"].iloc[0] == float(direct.response_time)
    # the linear bicycle's steady yaw rate is the steady-state gain times the steer
    gain = vehdyn.handling.steady_state_gains(scene.load_vehicle(), 30.0).yaw_rate
    steer = res["front_steer_angle"][-1]
    assert table["steady_state_yaw_rate"].iloc[0] == pytest.approx(gain * steer, rel=1e-3)


def test_vehicle_metrics_and_registration():
    sedan = vehdyn.load_vehicle("sedan")
    run = m.Run(time=np.zeros(1), outputs={}, vehicle=sedan, speed=20.0)
    assert m.metric("characteristic_speed").function(run) == vehdyn.handling.characteristic_speed(sedan)
    assert m.metric("understeer_gradient_deg_per_g").function(run) == \
        vehdyn.handling.understeer_gradient_deg_per_g(sedan)
    m.register_metric("wheelbase_test", lambda r: r.vehicle.wheelbase, "m", needs_run=False)
    try:
        assert m.metric("wheelbase_test").function(run) == sedan.wheelbase
        assert "wheelbase_test" in m.metric_names() and "rms_<signal>" in m.metric_names()
    finally:
        m.remove_metric("wheelbase_test")
    assert "wheelbase_test" not in m.metric_names()


def test_metric_errors():
    with pytest.raises(vehdyn.ParameterError, match="close matches: \\['rms_x'\\]"):
        m.metric("rms_y", {"x": "m"})
    with pytest.raises(vehdyn.ParameterError, match="identifier"):
        m.register_metric("bad name", lambda r: 0.0, "-")
    with pytest.raises(vehdyn.ParameterError, match="needs a vehicle"):
        m.metric("understeer_gradient").function(m.Run(time=np.zeros(1), outputs={}))
    with pytest.raises(vehdyn.ParameterError, match="no output 'y'"):
        m.Run(time=np.zeros(1), outputs={"x": np.zeros(1)}).signal("y")
