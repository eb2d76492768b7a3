"""Numerics at the edges (issue 20, items 5-7): lightly damped resonances in the PSD route of the random
response, the steady state of the single-track tire lag at low speed, one realizability check for inertia
tensors, and the frequencies of the ISO 2631-1 weighting factor.

Each compares with something independent: the Lyapunov covariance (exact, no frequency grid), the model
without tire lag and the kinematic slip, the triangle inequality of principal moments drawn for the test,
and the analog weighting's high-pass limit at 0 Hz.
"""

import dataclasses

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn.handling import SingleTrack
from vehdyn.mechanics import InertiaTensor, MassProperties, RigidBody6DOF
from vehdyn.ride import WEIGHTINGS, BouncePitch, FullCar, QuarterCar, random_response, weighting_factor

SEDAN = vehdyn.load_vehicle("sedan")


# --------------------------------------------------------------------------- PSD route vs Lyapunov
def damping_ratios(model):
    lam = model.poles()
    return -lam.real / np.abs(lam)


def assert_psd_within_its_bound(model, speed=20.0, **kw):
    """The Lyapunov r.m.s. (exact) lies within the PSD route's stated error bound, and the bound is tight."""
    exact = random_response(model, "C", speed, **kw)
    psd = random_response(model, "C", speed, method="psd", **kw)
    finite = np.isfinite(exact.rms)
    assert np.array_equal(finite, np.isfinite(psd.rms))  # the same outputs are unbounded
    gap = np.abs(psd.rms[finite] - exact.rms[finite])
    assert np.all(gap <= psd.error[finite]), (gap / psd.error[finite]).max()
    nonzero = finite & (psd.rms > 0)  # roll on identical tracks is 0 within its rounding bound
    assert np.all(psd.error[nonzero] <= 1e-5 * psd.rms[nonzero])  # not an honest-but-useless bound
    return exact, psd


@pytest.mark.parametrize("damping", [1e-6, 0.1, 1.0])
def test_psd_resolves_a_nearly_undamped_quarter_car(damping):
    """The issue's case: c = 1e-6 N s/m (zeta 2e-10) reported 751 +- 315 m/s^2 against the exact 24,288."""
    car = QuarterCar.from_parameters(sprung_mass=250.0, unsprung_mass=35.0, spring_rate=16e3, damping=damping,
                                     tire_stiffness=160e3)
    exact, psd = assert_psd_within_its_bound(car)
    assert psd["sprung_acceleration"] == pytest.approx(exact["sprung_acceleration"], rel=1e-6)
    if damping == 1e-6:
        assert exact["sprung_acceleration"] == pytest.approx(24288, rel=1e-4)


@settings(max_examples=40, deadline=None)
@given(zeta=st.floats(-4.0, 0.0).map(lambda e: 10.0**e), tire_damping=st.sampled_from([0.0, 50.0]))
def test_quarter_car_psd_within_its_bound_of_lyapunov_for_damping_ratios_1e_4_to_1(zeta, tire_damping):
    ms, ks = 300.0, 16e3
    car = QuarterCar.from_parameters(sprung_mass=ms, unsprung_mass=40.0, spring_rate=ks,
                                     damping=2 * zeta * np.sqrt(ks * ms), tire_stiffness=190e3,
                                     tire_damping=tire_damping)
    assert 0.5 * zeta <= damping_ratios(car).min() <= 2 * zeta  # the least damped mode: about zeta
    assert_psd_within_its_bound(car)


def half_car(scale):
    return BouncePitch.from_parameters(mass=1200.0, pitch_inertia=1800.0, a=1.2, b=1.5, front_spring_rate=30000.0,
                                       rear_spring_rate=32000.0, front_damping=2500.0 * scale,
                                       rear_damping=2400.0 * scale, front_unsprung_mass=40.0, rear_unsprung_mass=40.0,
                                       front_tire_stiffness=200000.0, rear_tire_stiffness=200000.0)


@settings(max_examples=12, deadline=None)
@given(scale=st.floats(-3.5, 0.6).map(lambda e: 10.0**e), speed=st.sampled_from([5.0, 20.0, 40.0]))
def test_half_car_psd_within_its_bound_of_lyapunov_with_the_exact_delay(scale, speed):
    """Front/rear delay; damping scaled so that the least damped mode has zeta from ~7e-5 to ~0.9."""
    car = half_car(scale)
    assert 5e-5 < damping_ratios(car).min() < 1.0
    assert_psd_within_its_bound(car, speed)


@pytest.mark.parametrize("scale", [1e-4, 1e-2, 1.0])
@pytest.mark.parametrize("coherence", ["identical", "independent"])
def test_full_car_psd_within_its_bound_of_lyapunov(scale, coherence):
    base = FullCar(SEDAN)
    p = dataclasses.asdict(base.parameters)
    car = FullCar.from_parameters(**{**p, "front_damping": p["front_damping"] * scale,
                                     "rear_damping": p["rear_damping"] * scale})
    assert damping_ratios(car).min() < 0.3 * max(scale, 1e-3) + 0.01
    assert_psd_within_its_bound(car, track_coherence=coherence)


# --------------------------------------------------------------------------- SingleTrack tire lag at low speed
MODELS = {(spin, lag): SingleTrack(SEDAN, wheel_spin=spin, tire_lag=lag) for spin in (False, True)
          for lag in (False, True)}


def operating_point(model, speed, steer=0.1, yaw=0.04):
    """(x, u) at ``speed`` turning (yaw rate ``yaw`` * speed: slip angles of ~0.05 rad, or beyond the
    peak force, sliding, at ``yaw=0.2``), wheels slipping 2 % / -1 %, the tire deflections relaxed to the
    slips (rates zero): a steady state of the tire, computed from the wheel-centre velocities."""
    p = model.parameters
    v, r = 0.01 * speed, yaw * speed
    states = {"longitudinal_velocity": speed, "lateral_velocity": v, "yaw_rate": r}
    wheel = {"front": 1.02 * speed / p.rolling_radius, "rear": 0.99 * speed / p.rolling_radius}
    if model.wheel_spin:
        states.update({f"{axle}_wheel_speed": w for axle, w in wheel.items()})
    if model.tire_lag:
        for axle, lateral, delta in (("front", v + p.a * r, steer), ("rear", v - p.b * r, 0.0)):
            vx = speed * np.cos(delta) + lateral * np.sin(delta)
            vy = -speed * np.sin(delta) + lateral * np.cos(delta)
            if speed == 0:
                continue  # parked: deflections zero
            states[f"{axle}_lateral_deflection"] = getattr(p, f"{axle}_lateral_relaxation_length") * vy / abs(vx)
            if model.wheel_spin:
                states[f"{axle}_longitudinal_deflection"] = (getattr(p, f"{axle}_longitudinal_relaxation_length")
                                                             * -(vx - wheel[axle] * p.rolling_radius) / abs(vx))
    return model.state_vector(states), model.input_vector(front_steer_angle=steer)


@pytest.mark.parametrize("yaw", [0.04, 0.2])
@pytest.mark.parametrize("wheel_spin", [False, True])
@pytest.mark.parametrize("speed", [0.5, 0.7, 1.0, 1.5, 2.0, 3.0, -1.0])
def test_tire_lag_leaves_the_steady_state_unchanged_at_low_speed(wheel_spin, speed, yaw):
    """With the deflections at their steady values, the model with tire lag gives the forces and body
    accelerations of the model without it (exact slips above 0.5 m/s, where the regularized speed is |V_x|);
    before, the low-speed damping made the tire up to 26 % stiffer there (28 % in the forces at 1 m/s)."""
    lag, plain = MODELS[wheel_spin, True], MODELS[wheel_spin, False]
    x_lag, u_lag = operating_point(lag, speed, yaw=yaw)
    x_plain, u_plain = operating_point(plain, speed, yaw=yaw)
    rates = lag.rhs(0.0, x_lag, u_lag)
    deflections = [i for i, name in enumerate(lag.state_names) if name.endswith("_deflection")]
    assert np.max(np.abs(rates[deflections])) < 1e-15  # a steady state of the tire
    body = [lag.index(name) for name in plain.state_names]
    expected = plain.rhs(0.0, x_plain, u_plain)
    np.testing.assert_allclose(rates[body], expected, rtol=1e-12, atol=1e-12 * np.max(np.abs(expected)))
    np.testing.assert_allclose(lag.output(0.0, x_lag, u_lag), plain.output(0.0, x_plain, u_plain), rtol=1e-12,
                               atol=1e-9)


@pytest.mark.parametrize("speed", [0.1, 0.25, 0.5, 1.0, 1.9])
def test_steady_slip_with_tire_lag_is_the_kinematic_slip(speed):
    """At every speed (also below 0.5 m/s, where the model without lag uses its regularized speed) the
    slip angle the law sees in the tire's steady state is atan(V_y / |V_x|) of the wheel centre."""
    model = MODELS[False, True]
    x, u = operating_point(model, speed)
    y = model.output(0.0, x, u)
    p = model.parameters
    v, r = x[model.index("lateral_velocity")], x[model.index("yaw_rate")]
    rear = np.arctan((v - p.b * r) / speed)
    assert y[model.index("rear_slip_angle", "outputs")] == pytest.approx(rear, rel=1e-13)


def test_the_low_speed_damping_is_kept_at_standstill():
    """Parked, the deflection rate is the slip velocity V_y, so the damping is Pacejka's (2012, eq. 8.126 at
    V_x = 0): the law sees tan(alpha) = rho / sigma + V_y / v_l."""
    model = MODELS[False, True]
    sigma = model.parameters.rear_lateral_relaxation_length
    x = model.state_vector(lateral_velocity=0.02, rear_lateral_deflection=0.1 * sigma)
    y = model.output(0.0, x, model.input_vector())
    assert y[model.index("rear_slip_angle", "outputs")] == pytest.approx(np.arctan(0.1 + 0.02 / 2.0), rel=1e-13)
    # at 1 m/s (w = 1/2) a deflection off its steady value is damped by w (rate) / v_l, rate = -|V_x| drho / sigma
    x, u = operating_point(model, 1.0)
    i = model.index("rear_lateral_deflection")
    before = model.output(0.0, x, u)[model.index("rear_slip_angle", "outputs")]
    x[i] += 0.01 * sigma
    after = model.output(0.0, x, u)[model.index("rear_slip_angle", "outputs")]
    assert np.tan(after) - np.tan(before) == pytest.approx(0.01 * (1 - 0.5 * 1.0 / 2.0), rel=1e-9)


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("wheel_spin", [False, True])
def test_compiled_low_speed_equations_equal_the_numpy_ones(wheel_spin):
    pytest.importorskip("numba")
    model = MODELS[wheel_spin, True]
    compiled = model.compiled_rhs()
    rng = np.random.default_rng(3)
    for speed in (0.0, 0.3, 0.5, 1.0, 1.7, -0.8):
        x, u = operating_point(model, speed)
        x = x + 1e-3 * rng.standard_normal(x.size) * (np.abs(x) + 1e-3)  # off the steady state: damping active
        dxdt = np.empty(model.n_states)
        compiled.rhs(0.0, x, u, compiled.args, dxdt)
        expected = model.rhs(0.0, x, u)
        np.testing.assert_allclose(dxdt, expected, rtol=1e-12, atol=1e-12 * np.max(np.abs(expected)))


# --------------------------------------------------------------------------- one inertia check for both classes
def verdicts(matrix):
    """(RigidBody6DOF accepts, MassProperties accepts) the 3x3 ``matrix``, with the errors' keys."""
    out = []
    for build in (lambda: RigidBody6DOF(mass=1.0, inertia=matrix), lambda: MassProperties(1.0, inertia=matrix)):
        try:
            build()
            out.append(True)
        except vehdyn.ParameterError as error:
            out.append(error.key)
    return out


rotations = st.lists(st.floats(-1.0, 1.0), min_size=4, max_size=4).filter(lambda q: np.linalg.norm(q) > 0.1)


def rotation(q):
    w, x, y, z = np.asarray(q) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(moments=st.lists(st.floats(0.01, 10.0), min_size=3, max_size=3), q=rotations)
def test_rigid_body_and_mass_properties_accept_and_reject_the_same_tensors(moments, q):
    """Positive-definite tensors R diag(I1, I2, I3) R^T: realizable exactly when the principal moments
    drawn here satisfy the triangle inequality (largest <= sum of the others); both classes agree."""
    p = np.sort(moments)
    assume(abs(p[2] - p[0] - p[1]) > 1e-6 * p.sum())  # not on the equality (rounding decides there)
    R = rotation(q)
    matrix = R @ np.diag(moments) @ R.T
    matrix = 0.5 * (matrix + matrix.T)
    body, props = verdicts(matrix)
    if p[2] <= p[0] + p[1]:
        assert body is True and props is True
    else:
        assert body == "inertia" and props in ("ixx", "iyy", "izz", "ixy, ixz, iyz")


def test_the_issue_example_is_rejected_by_both():
    body, props = verdicts(np.diag([1.0, 1.0, 3.0]))
    assert (body, props) == ("inertia", "izz")
    with pytest.raises(vehdyn.ParameterError, match="batch member 1") as info:
        RigidBody6DOF(mass=[1.0, 1.0], inertia=np.stack([np.eye(3), np.diag([1.0, 1.0, 3.0])], axis=-1))
    assert info.value.key == "inertia"
    # the thin plate on the equality Izz = Ixx + Iyy is realizable, and invertible, so both accept it
    assert verdicts(np.diag([0.3, 0.7, 1.0])) == [True, True]
    assert isinstance(InertiaTensor(0.3, 0.7, 1.0), InertiaTensor)


# --------------------------------------------------------------------------- ISO 2631-1 weighting frequencies
@pytest.mark.parametrize("frequency, value, index", [
    (-1.0, -1.0, None), (float("nan"), None, None), (float("inf"), float("inf"), None),
    ([1.0, 2.0, -0.5, np.nan], -0.5, "2"), ([[1.0, 2.0], [np.nan, 3.0]], None, "(1, 0)"),
])
def test_weighting_factor_rejects_negative_and_non_finite_frequencies(frequency, value, index):
    with pytest.raises(vehdyn.ParameterError, match="frequency_hz") as info:
        weighting_factor("Wk", frequency)
    assert info.value.key == "frequency_hz"
    if value is None:
        assert np.isnan(info.value.value)
    else:
        assert info.value.value == value
    if index is not None:
        assert f"index {index}" in str(info.value)


@pytest.mark.parametrize("name", sorted(WEIGHTINGS))
def test_weighting_factor_is_zero_at_0_hz(name):
    """Every ISO 2631-1 weighting starts with the band-limiting high-pass |H_h| = f^2 / sqrt(f1^4 + f^4)
    (Q = 1/sqrt 2): 0 at 0 Hz, so 0 Hz is a valid frequency; below f1 the factor falls as f^2."""
    assert weighting_factor(name, 0.0) == 0.0
    f1 = WEIGHTINGS[name].f1
    low = weighting_factor(name, [1e-4 * f1, 2e-4 * f1])
    assert low[1] / low[0] == pytest.approx(4.0, rel=1e-6)


@settings(max_examples=60, deadline=None)
@given(values=st.lists(st.floats(0.0, 1e3), min_size=1, max_size=20), data=st.data(),
       bad=st.sampled_from([-1e-300, -1.0, -np.inf, np.inf, np.nan]))
def test_any_bad_frequency_is_named_with_its_index(values, data, bad):
    index = data.draw(st.integers(0, len(values) - 1))
    values[index] = bad
    with pytest.raises(vehdyn.ParameterError) as info:
        weighting_factor("Wd", np.array(values))
    assert info.value.key == "frequency_hz"
    assert f"at index {index}" in str(info.value)
    assert info.value.value == bad or (np.isnan(bad) and np.isnan(info.value.value))
