"""Linear car–trailer model against an independent Lagrange derivation, the bicycle limit and closed forms."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import vehdyn
from vehdyn import ParameterError
from vehdyn.handling import (CarTrailerParameters, LinearBicycle, LinearCarTrailer, car_trailer_parameters,
                             trailer_crosswind_amplification)
from vehdyn.handling.car_trailer import EOM_TRUCK_TRAILER
from vehdyn.components.aero import trailer_wind_side_force_factor

# A labelled car–caravan set: the shipped "compact" towing the shipped "caravan". The caravan's
# numbers are typical values (data/trailers/caravan.toml says so line by line): no published
# measured car–caravan set could be confirmed while writing these tests.
SHIPPED = car_trailer_parameters(vehdyn.load_vehicle("compact"), vehdyn.load_trailer("caravan"))
# A PUBLISHED car–trailer set (every linear parameter stated by its source, nothing assumed; the source
# and its commits are in EOM_TRUCK_TRAILER's docstring): Minaker's EoM truck-and-trailer example. The numbers
# are checked here against the source's own lines, then the model against independent derivations.
MINAKER = EOM_TRUCK_TRAILER
# the textbook-style set of the LinearCarTrailer docstring
TEXTBOOK = CarTrailerParameters(mass=1500.0, yaw_inertia=2500.0, a=1.1, b=1.6, front_cornering_stiffness=110e3,
                                rear_cornering_stiffness=120e3, hitch_distance=2.6, trailer_mass=1200.0,
                                trailer_yaw_inertia=2500.0, trailer_hitch_to_cg=3.2, trailer_cg_to_axle=0.3,
                                trailer_cornering_stiffness=80e3)


def lagrange_mass_matrix(p: CarTrailerParameters) -> np.ndarray:
    """The mass matrix of the Lagrange derivation below over (v', r', theta'')."""
    m, iz, h = p.mass, p.yaw_inertia, p.hitch_distance
    mt, it, e = p.trailer_mass, p.trailer_yaw_inertia, p.trailer_hitch_to_cg
    return np.array([[m + mt, -mt * (h + e), mt * e],
                     [-mt * (h + e), iz + it + mt * (h + e) ** 2, -it - mt * (h + e) * e],
                     [mt * e, -it - mt * e * (h + e), it + mt * e * e]])


def lagrange_state_matrix(p: CarTrailerParameters, u: float) -> np.ndarray:
    """A of the car–trailer from Lagrange's equations in the car's body-fixed quasi-coordinates.

    Derived independently of the module's Newton–Euler form (Pacejka 2012, sec. 1.3.3, method):
    kinetic energy T = m (u^2 + v^2)/2 + I r^2/2 + m_t |V_t|^2/2 + I_t (r - theta')^2/2 with the
    trailer CG velocity in car axes V_t = (u - e sin(theta) r_t, v - h r - e cos(theta) r_t),
    r_t = r - theta'; equations d/dt dT/dv + r dT/du = Q_v, d/dt dT/dr - v dT/du + u dT/dv = Q_r,
    d/dt dT/dtheta' - dT/dtheta = Q_theta, with the generalized forces from the power of the three
    axle forces, linearized by hand:

      (m + m_t) v' - m_t (h + e) r' + m_t e theta'' + (m + m_t) u r = Y_f + Y_r + Y_t
      (I + I_t) r' - I_t theta'' - m_t (h + e)(v' - (h + e) r' + e theta'') - m_t u e theta'
          - m_t u ((h + e) r - e theta') = a Y_f - b Y_r - (h + l_t) Y_t
      -I_t (r' - theta'') + m_t e (v' - (h + e) r' + e theta'') + m_t u e r = l_t Y_t
    """
    m, iz, a, b, h = p.mass, p.yaw_inertia, p.a, p.b, p.hitch_distance
    mt, it, e, f = p.trailer_mass, p.trailer_yaw_inertia, p.trailer_hitch_to_cg, p.trailer_cg_to_axle
    lt = e + f

    def forces(x):
        v, r, th, dth = x
        yf = -p.front_cornering_stiffness * (v + a * r) / u
        yr = -p.rear_cornering_stiffness * (v - b * r) / u
        yt = -p.trailer_cornering_stiffness * (v - h * r + u * th - lt * (r - dth)) / u
        return yf, yr, yt

    M = lagrange_mass_matrix(p)

    def rest(x):  # right-hand sides minus the velocity terms of the left
        v, r, th, dth = x
        yf, yr, yt = forces(x)
        return np.array([yf + yr + yt - (m + mt) * u * r,
                         a * yf - b * yr - (h + lt) * yt + mt * u * e * dth + mt * u * ((h + e) * r - e * dth),
                         lt * yt - mt * u * e * r])

    A = np.zeros((4, 4))
    for j in range(4):
        z = np.linalg.solve(M, rest(np.eye(4)[j]))
        A[[0, 1, 3], j] = z
    A[2, 3] = 1.0
    return A


def independent_critical_speed(p, lo=0.5, hi=100.0):
    """Bisection on the largest real part of the complex eigenvalues of the Lagrange A."""
    def growth(u):
        lam = np.linalg.eigvals(lagrange_state_matrix(p, u))
        lam = lam[np.abs(lam.imag) > 1e-9]
        return lam.real.max() if lam.size else -np.inf

    grid = np.linspace(lo, hi, 400)
    g = np.array([growth(u) for u in grid])
    k = np.flatnonzero(g >= 0)[0]
    a, b = grid[k - 1], grid[k]
    for _ in range(200):
        mid = 0.5 * (a + b)
        if growth(mid) >= 0:
            b = mid
        else:
            a = mid
        if b - a < 1e-12:
            break
    return 0.5 * (a + b)


@pytest.mark.parametrize("params", [MINAKER, SHIPPED, TEXTBOOK], ids=["minaker_published", "compact_caravan",
                                                                      "textbook"])
def test_matrices_and_critical_speed_equal_the_lagrange_derivation(params):
    for u in (3.0, 17.0, 42.0):
        np.testing.assert_allclose(LinearCarTrailer(params, speed=u).A, lagrange_state_matrix(params, u),
                                   rtol=1e-10, atol=1e-10)
    model = LinearCarTrailer(params, speed=20.0)
    assert model.critical_speed() == pytest.approx(independent_critical_speed(params), rel=1e-6)
    # the snaking mode is undamped at the critical speed, damped below it, growing above
    vc = model.critical_speed()
    assert model.snaking_mode(vc).damping_ratio == pytest.approx(0.0, abs=1e-8)
    assert model.snaking_mode(0.95 * vc).damping_ratio > 0 > model.snaking_mode(1.05 * vc).damping_ratio


def hurwitz_critical_speed(p, lo=0.5, hi=100.0):
    """Critical speed from the characteristic polynomial alone (no eigenvalues): the Hopf point of a quartic.

    det(sI - A) = s^4 + a1 s^3 + a2 s^2 + a3 s + a4 (A from the Lagrange derivation above) has a pair of
    roots on the imaginary axis where the third Hurwitz determinant a1 a2 a3 - a3^2 - a1^2 a4 vanishes
    (Routh–Hurwitz; e.g. Pacejka 2012, sec. 1.3.3, uses the same criterion for the car–trailer).
    """
    from scipy.optimize import brentq

    def hurwitz3(u):
        _, a1, a2, a3, a4 = np.poly(lagrange_state_matrix(p, u))
        return a1 * a2 * a3 - a3**2 - a1**2 * a4

    grid = np.linspace(lo, hi, 400)
    h = np.array([hurwitz3(u) for u in grid])
    k = np.flatnonzero(h <= 0)[0]
    return brentq(hurwitz3, grid[k - 1], grid[k], xtol=1e-13, rtol=1e-15)


def test_published_set_is_the_source_text():
    # input_ex_truck_trailer(; a = 1.289, b = 2.885 - 1.289, cf = 80000, cr = 80000, m = 16975 / 9.81, Iz = 3508,
    # d = 2.7, ..., ct = 80000, mt = 2000, It = 3000) and truck_trailer.jl: e = 2.9, h = 0.1
    source = dict(a=1.289, b=2.885 - 1.289, front_cornering_stiffness=80000, rear_cornering_stiffness=80000,
                  mass=16975 / 9.81, yaw_inertia=3508, hitch_distance=2.7, trailer_cornering_stiffness=80000,
                  trailer_mass=2000, trailer_yaw_inertia=3000, trailer_hitch_to_cg=2.9, trailer_cg_to_axle=0.1)
    for name, value in source.items():
        assert getattr(MINAKER, name) == value, name
    assert MINAKER.wind_side_force_factor == MINAKER.trailer_wind_side_force_factor == 0.0


def test_published_set_critical_speed_equals_the_hurwitz_derivation():
    model = LinearCarTrailer(MINAKER, speed=10.0)
    vc = model.critical_speed()
    assert vc == pytest.approx(hurwitz_critical_speed(MINAKER), rel=1e-6)
    # at that speed the snaking pair sits on the imaginary axis at the Hurwitz frequency sqrt(a3 / a1)
    _, a1, _, a3, _ = np.poly(lagrange_state_matrix(MINAKER, vc))
    assert model.snaking_mode(vc).frequency_hz == pytest.approx(math.sqrt(a3 / a1) / (2 * math.pi), rel=1e-6)
    # this light-tongue-load set snakes inside the 0.4-40 m/s sweep of its source; its understeer gradient
    # from the closed form is small and positive (no divergence below the critical speed)
    assert 0.4 < vc < 40.0
    assert model.understeer_gradient > 0
    assert model.max_real_part(0.99 * vc) < 0 < model.max_real_part(1.01 * vc)


def test_vanishing_trailer_leaves_the_bicycle_eigenvalues():
    car = LinearBicycle.from_parameters(mass=1500.0, yaw_inertia=2500.0, a=1.1, b=1.6,
                                        front_cornering_stiffness=110e3, rear_cornering_stiffness=120e3, speed=25.0)
    light = dataclasses.replace(TEXTBOOK, trailer_mass=1e-6, trailer_yaw_inertia=1e-6)
    lam = np.linalg.eigvals(LinearCarTrailer(light, speed=25.0).A)
    for target in np.linalg.eigvals(car.A):
        assert np.min(np.abs(lam - target)) < 1e-6 * abs(target)
    # the rest: a massless trailer follows its hitch kinematically, theta decays at u / l_t
    rest = [x for x in lam if np.min(np.abs(np.linalg.eigvals(car.A) - x)) > 1e-3]
    assert min(rest, key=lambda x: abs(x + 25.0 / 3.5)) == pytest.approx(-25.0 / 3.5, rel=1e-6)
    # and the steady-state understeer gradient is the car's own
    assert LinearCarTrailer(light, speed=25.0).understeer_gradient == pytest.approx(
        car.bicycle_parameters.understeer_gradient, rel=1e-8)


def test_critical_speed_falls_with_tongue_load_and_rises_with_less_trailer_inertia():
    lt = TEXTBOOK.trailer_wheelbase
    by_tongue = [LinearCarTrailer(dataclasses.replace(TEXTBOOK, trailer_cg_to_axle=f, trailer_hitch_to_cg=lt - f),
                                  speed=20.0).critical_speed() for f in (0.1, 0.2, 0.3, 0.4)]
    assert np.all(np.diff(by_tongue) > 0), by_tongue  # more tongue load: higher critical speed
    by_inertia = [LinearCarTrailer(dataclasses.replace(TEXTBOOK, trailer_yaw_inertia=i), speed=20.0).critical_speed()
                  for i in (1500.0, 2500.0, 3500.0, 4500.0)]
    assert np.all(np.diff(by_inertia) < 0), by_inertia


def test_no_snaking_below_the_scan_limit_returns_inf():
    stiff = dataclasses.replace(TEXTBOOK, trailer_cg_to_axle=0.6, trailer_hitch_to_cg=2.9, trailer_yaw_inertia=1000.0)
    model = LinearCarTrailer(stiff, speed=20.0)
    assert model.critical_speed() == math.inf
    assert all(model.snaking_mode(u).damping_ratio > 0 for u in (5.0, 30.0, 60.0, 99.0))


@pytest.mark.parametrize("params", [SHIPPED, TEXTBOOK], ids=["compact_caravan", "textbook"])
def test_steady_state_gains_follow_the_closed_forms(params):
    u = 18.0
    model = LinearCarTrailer(params, speed=u)
    gain = model.dc_gain()[:, 0]
    out = {name: gain[k] for k, name in enumerate(model.output_names)}
    p = params
    L, lt, mh = p.wheelbase, p.trailer_wheelbase, p.trailer_mass * p.trailer_cg_to_axle / p.trailer_wheelbase
    # delta = L/R + K a_y  ->  1 / (a_y / delta) = L / u^2 + K
    K = 1.0 / out["lateral_acceleration"] - L / u**2
    K_closed = (p.mass * p.b - mh * (p.hitch_distance - p.b)) / (L * p.front_cornering_stiffness) \
        - (p.mass * p.a + mh * (p.a + p.hitch_distance)) / (L * p.rear_cornering_stiffness)
    assert K == pytest.approx(K_closed, rel=1e-9)
    assert model.understeer_gradient == pytest.approx(K_closed, rel=1e-12)
    # both bodies turn at the same rate; the trailer carries m_t a_y e / l_t, the hitch -m_t a_y f / l_t
    ay = out["lateral_acceleration"]
    assert out["trailer_yaw_rate"] == pytest.approx(out["yaw_rate"], rel=1e-12)
    assert out["trailer_lateral_acceleration"] == pytest.approx(ay, rel=1e-9)
    assert out["trailer_lateral_force"] == pytest.approx(p.trailer_mass * ay * p.trailer_hitch_to_cg / lt, rel=1e-9)
    assert out["hitch_lateral_force"] == pytest.approx(-mh * ay, rel=1e-9)
    theta_per_ay = (p.hitch_distance - p.b + lt) / u**2 + (p.mass * p.a + mh * (p.a + p.hitch_distance)) / (
        L * p.rear_cornering_stiffness) - p.trailer_mass * p.trailer_hitch_to_cg / (lt * p.trailer_cornering_stiffness)
    assert model.articulation_gain() == pytest.approx(theta_per_ay, rel=1e-9)


def test_low_speed_offtracking_equals_the_kinematic_trailer_on_a_circle():
    model = LinearCarTrailer(TEXTBOOK, speed=1.0)
    p = TEXTBOOK
    R, speed, d, lt = 12.0, 1.0, p.hitch_distance - p.b, p.trailer_wheelbase

    def rhs(t, y):  # trailer heading psi_t behind a hitch d behind a rear axle on a circle
        psi = speed * t / R
        hx, hy = R * np.sin(psi) - d * np.cos(psi), R - R * np.cos(psi) - d * np.sin(psi)
        vhx, vhy = speed * np.cos(psi) + d * np.sin(psi) * speed / R, speed * np.sin(psi) - d * np.cos(psi) * speed / R
        return [(-vhx * np.sin(y[0]) + vhy * np.cos(y[0])) / lt]

    sol = solve_ivp(rhs, (0, 400.0), [0.0], rtol=1e-11, atol=1e-12)
    t, psi_t = sol.t[-1], sol.y[0, -1]
    psi = speed * t / R
    hx, hy = R * np.sin(psi) - d * np.cos(psi), R - R * np.cos(psi) - d * np.sin(psi)
    ax, ay = hx - lt * np.cos(psi_t), hy - lt * np.sin(psi_t)
    radius = np.hypot(ax, ay - R)  # circle centre (0, R), turning right (SAE y right)
    assert model.low_speed_offtracking(R) == pytest.approx(R - radius, rel=1e-6)
    # and the steady articulation angle of the linear model at walking pace is the small-angle one
    assert model.articulation_gain() * speed**2 / R == pytest.approx((d + lt) / R, rel=2e-2)


def test_model_contract_and_names():
    model = LinearCarTrailer(vehdyn.load_vehicle("compact"), vehdyn.load_trailer("caravan"), 25.0)
    assert model.state_names == ("lateral_velocity", "yaw_rate", "articulation_angle", "articulation_rate")
    assert model.input_names == ("front_steer_angle",)
    for name in ("lateral_acceleration", "trailer_lateral_acceleration", "articulation_angle", "yaw_rate"):
        assert name in model.output_names
    assert model.linearize().A is not None
    np.testing.assert_array_equal(model.linearize().A, model.A)  # a linear model linearizes to its own matrices
    assert model.at_speed(30.0).speed == 30.0
    assert model.at_speed(30.0).critical_speed() == pytest.approx(model.critical_speed(), rel=1e-12)
    # a positive steer turns right: positive yaw rate and articulation angle in the steady state
    gain = model.dc_gain()[:, 0]
    assert gain[model.index("yaw_rate", "outputs")] > 0 and gain[model.index("articulation_angle", "outputs")] > 0


def test_trailer_cg_behind_its_axle_is_accepted_and_snakes_early():
    lt = TEXTBOOK.trailer_wheelbase
    behind = LinearCarTrailer(dataclasses.replace(TEXTBOOK, trailer_hitch_to_cg=lt + 0.3, trailer_cg_to_axle=-0.3),
                              speed=5.0)
    assert behind.car_trailer_parameters.hitch_mass < 0
    vc = behind.critical_speed()
    assert vc < 0.65 * LinearCarTrailer(TEXTBOOK, speed=5.0).critical_speed()
    assert behind.max_real_part(0.99 * vc) < 0 < behind.max_real_part(1.01 * vc)


@pytest.mark.parametrize("field, value", [
    ("mass", 0.0), ("trailer_mass", 0.0), ("trailer_yaw_inertia", 0.0), ("a", -1.0), ("trailer_hitch_to_cg", -0.5),
    ("hitch_distance", -1.2), ("trailer_cg_to_axle", -3.3), ("trailer_cornering_stiffness", -1.0)])
def test_bad_parameters_name_the_field(field, value):
    with pytest.raises(ParameterError) as err:
        LinearCarTrailer.from_parameters(**{**dataclasses.asdict(TEXTBOOK), field: value, "speed": 20.0})
    assert err.value.key == field and field in str(err.value)


def test_bad_speed_and_hitch_ahead_of_the_front_axle_from_files():
    car, caravan = vehdyn.load_vehicle("compact"), vehdyn.load_trailer("caravan")
    with pytest.raises(ParameterError, match="speed"):
        LinearCarTrailer(car, caravan, 0.0)
    with pytest.raises(ParameterError) as err:
        LinearCarTrailer(car, caravan.replace(hitch_behind_rear_axle=-3.0), 20.0)
    assert err.value.key == "hitch_behind_rear_axle"
    with pytest.raises(ParameterError) as err:
        LinearCarTrailer(car, "caravan", 20.0)
    assert err.value.key == "trailer"


# ----------------------------------------------------------------------------- crosswind on the combination
WINDY = dataclasses.replace(SHIPPED)  # the compact's and the caravan's wind numbers (car_trailer_parameters)


def test_shipped_combination_carries_both_bodies_wind_numbers():
    car, caravan = vehdyn.load_vehicle("compact"), vehdyn.load_trailer("caravan")
    assert WINDY.wind_side_force_factor == pytest.approx(
        0.5 * car.aero.air_density * car.aero.frontal_area * car.aero.side_force_coefficient_slope, rel=1e-14)
    assert WINDY.trailer_wind_side_force_factor == pytest.approx(
        0.5 * car.aero.air_density * caravan.frontal_area * caravan.side_force_coefficient_slope, rel=1e-14)
    assert WINDY.trailer_centre_of_pressure == caravan.centre_of_pressure_behind_hitch
    assert WINDY.trailer_wind_side_force_factor > 0 and WINDY.wind_side_force_factor > 0


def test_wind_input_column_equals_the_lagrange_generalized_forces():
    """The wind's generalized forces from its virtual power, independently of the Newton–Euler form.

    Car force F_c = k_c u w at x_p: Q = (F_c, x_p F_c, 0). Trailer force F_t = k_t u w at d_p behind the hitch,
    whose lateral velocity is v - h r - d_p (r - theta') + u theta: Q = (F_t, -(h + d_p) F_t, d_p F_t).
    """
    p = WINDY
    for u in (8.0, 22.0, 31.0):
        windy, plain = LinearCarTrailer(p, speed=u, crosswind=True), LinearCarTrailer(p, speed=u)
        assert windy.input_names == ("front_steer_angle", "wind_velocity_lateral")
        np.testing.assert_array_equal(windy.A, plain.A)
        np.testing.assert_array_equal(windy.B[:, :1], plain.B)
        fc, ft, dp = p.wind_side_force_factor * u, p.trailer_wind_side_force_factor * u, p.trailer_centre_of_pressure
        q = np.array([fc + ft, p.centre_of_pressure * fc - (p.hitch_distance + dp) * ft, dp * ft])
        z = np.linalg.solve(lagrange_mass_matrix(p), q)
        np.testing.assert_allclose(windy.B[:, 1], [z[0], z[1], 0.0, z[2]], rtol=1e-10, atol=1e-14)
    assert "aero" in windy.phenomena and windy.at_speed(12.0).input_names == windy.input_names


@pytest.mark.parametrize("dp", [1.5, 3.9, 4.6, 5.5])
def test_steady_wind_response_equals_the_closed_form(dp):
    p = dataclasses.replace(WINDY, trailer_centre_of_pressure=dp)
    u = 22.0
    model = LinearCarTrailer(p, speed=u, crosswind=True)
    gain = model.dc_gain()[:, model.index("wind_velocity_lateral", "inputs")]
    out = {name: gain[k] for k, name in enumerate(model.output_names)}
    cf, cr, L, lt, h = p.front_cornering_stiffness, p.rear_cornering_stiffness, p.wheelbase, p.trailer_wheelbase, \
        p.hitch_distance
    fc, ft = p.wind_side_force_factor * u, p.trailer_wind_side_force_factor * u
    # the trailer, in moment balance about the hitch, passes (l_t - d_p)/l_t of its wind force to the hitch
    ay = out["lateral_acceleration"]
    assert out["trailer_lateral_force"] == pytest.approx((p.trailer_hitch_to_cg * p.trailer_mass * ay - dp * ft) / lt,
                                                         rel=1e-9, abs=1e-9 * ft)
    assert out["hitch_lateral_force"] == pytest.approx(-p.hitch_mass * ay + ft * (lt - dp) / lt, rel=1e-9,
                                                       abs=1e-9 * ft)
    # the car: a bicycle under F_s at x_s with the combination's understeer gradient
    fs = fc + ft * (lt - dp) / lt
    xs = (p.centre_of_pressure * fc - h * ft * (lt - dp) / lt) / fs
    xn = (p.a * cf - p.b * cr) / (cf + cr)
    r = u * fs * (cf + cr) * (xs - xn) / (cf * cr * L * (L + p.understeer_gradient * u**2))
    assert out["yaw_rate"] == pytest.approx(r, rel=1e-9)
    assert ay == pytest.approx(u * r, rel=1e-9)
    assert out["trailer_yaw_rate"] == pytest.approx(r, rel=1e-9)


def test_weightless_windless_trailer_leaves_the_cars_wind_response():
    light = dataclasses.replace(WINDY, trailer_mass=1e-6, trailer_yaw_inertia=1e-6, trailer_wind_side_force_factor=0.0)
    amp = trailer_crosswind_amplification(light, speed=25.0)
    assert amp.steady_yaw_rate_ratio == pytest.approx(1.0, rel=1e-6)
    np.testing.assert_allclose(amp.combination_yaw_rate, amp.car_yaw_rate, rtol=1e-5)
    np.testing.assert_allclose(amp.combination_lateral_offset, amp.car_lateral_offset, rtol=1e-5)
    assert amp.peak_yaw_rate_ratio == pytest.approx(1.0, rel=1e-5)


def test_lateral_offset_gain_is_the_integrated_path():
    amp = trailer_crosswind_amplification(WINDY, speed=22.0, omega=[0.5, 2.0, 8.0])
    model = LinearCarTrailer(WINDY, speed=22.0, crosswind=True)
    fr = model.frequency_response(amp.omega, outputs=["lateral_velocity", "yaw_rate"], inputs=["wind_velocity_lateral"])
    s = 1j * amp.omega
    # y'' = v' + u r (small angles, straight path): Y = (V + u R / s) / s
    np.testing.assert_allclose(amp.combination_lateral_offset,
                               np.abs((fr.response[0, 0] + 22.0 * fr.response[1, 0] / s) / s), rtol=1e-12)
    np.testing.assert_allclose(amp.combination_yaw_rate, np.abs(fr.response[1, 0]), rtol=1e-12)


def test_amplification_grows_with_side_area_and_towards_the_critical_speed():
    caravan = vehdyn.load_trailer("caravan")
    car = vehdyn.load_vehicle("compact")
    by_area = [trailer_crosswind_amplification(car, caravan.replace(frontal_area=a), 80 / 3.6).peak_yaw_rate_ratio
               for a in (2.0, 4.0, 6.0, 8.0)]
    assert np.all(np.diff(by_area) > 0), by_area
    vc = LinearCarTrailer(car, caravan, 20.0).critical_speed()
    omega = np.linspace(0.5, 8.0, 1500)  # fine enough to catch the snaking resonance
    by_speed = [trailer_crosswind_amplification(car, caravan, q * vc, omega).peak_yaw_rate_ratio
                for q in (0.5, 0.7, 0.85, 0.95)]
    assert np.all(np.diff(by_speed) > 0), by_speed
    # the resonance peak sits at the snaking frequency and grows like 1 / damping ratio
    model = LinearCarTrailer(car, caravan, 0.95 * vc, crosswind=True)
    amp = trailer_crosswind_amplification(car, caravan, 0.95 * vc, omega)
    mode = model.snaking_mode()
    assert amp.omega[np.argmax(amp.combination_yaw_rate)] == pytest.approx(2 * np.pi * mode.frequency_hz, rel=0.03)


def test_crosswind_errors_name_the_parameter():
    with pytest.raises(ParameterError) as err:
        trailer_crosswind_amplification(WINDY, speed=20.0, omega=[1.0, -2.0])
    assert err.value.key == "omega"
    with pytest.raises(ParameterError) as err:
        trailer_crosswind_amplification(WINDY, speed=0.0)
    assert err.value.key == "speed"
    with pytest.raises(ParameterError) as err:
        trailer_wind_side_force_factor(vehdyn.load_trailer("caravan"), air_density=0.0)
    assert err.value.key == "air_density"
    with pytest.raises(ParameterError) as err:
        trailer_wind_side_force_factor("caravan")
    assert err.value.key == "trailer"
    with pytest.raises(ParameterError) as err:
        vehdyn.load_trailer("caravan").replace(frontal_area=-1.0)
    assert err.value.key == "frontal_area"
    with pytest.raises(ParameterError) as err:
        LinearCarTrailer.from_parameters(**{**dataclasses.asdict(TEXTBOOK), "trailer_wind_side_force_factor": -1.0,
                                            "speed": 20.0})
    assert err.value.key == "trailer_wind_side_force_factor"

