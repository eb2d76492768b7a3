"""The layers agree: the full vehicle reduces to the ride, lateral-yaw-roll and bicycle models.

Linear tires (:meth:`LinearTire.from_vehicle`, stiffness proportional to load, so that lateral load
transfer leaves an axle's cornering stiffness unchanged), no tire lag, operating points from
:meth:`FullVehicle.trim`.
"""

import numpy as np
import pytest

from vehdyn import ParameterError
from vehdyn.full_vehicle import CORNERS, FullVehicle
from vehdyn.handling import LateralYawRoll, LinearBicycle, steady_roll
from vehdyn.ride import FullCar
from vehdyn.units import GRAVITY


def _nearest_errors(reference, eigenvalues):
    """Relative distance of each reference eigenvalue to the nearest of ``eigenvalues``."""
    return np.array([np.min(np.abs(eigenvalues - r)) / abs(r) for r in reference])


def _eigenvalues(model, speed):
    x0, u0 = model.trim(speed)
    return np.linalg.eigvals(model.linearize(x0, u0).A)


def _second_order_eigenvalues(M, C, K):
    n = M.shape[0]
    return np.linalg.eigvals(np.block([[np.zeros((n, n)), np.eye(n)],
                                       [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]]))


def test_trim_holds_every_derivative(sedan, linear_tires):
    model = FullVehicle(sedan)  # Magic Formula tires, tire lag
    for ay in (0.0, 4.0):
        x0, u0 = model.trim(20.0, lateral_acceleration=ay)
        d = model.rhs(0.0, x0, u0)
        moving = [model.index(n) for n in ("x", "y", "yaw_angle")]
        rest = np.delete(d, moving)
        assert np.max(np.abs(rest)) < 1e-9 * GRAVITY / sedan.tires.rolling_radius
        y = dict(zip(model.output_names, model.output(0.0, x0, u0)))
        assert y["speed"] == pytest.approx(20.0, rel=1e-12)
        assert y["lateral_acceleration"] == pytest.approx(ay, rel=1e-9, abs=1e-9)
    x0, u0 = model.trim(20.0, radius=100.0)  # the sprung CG's heading turns at V / R
    assert model.rhs(0.0, x0, u0)[model.index("yaw_angle")] == pytest.approx(0.2, rel=1e-9)


def test_heave_pitch_and_wheel_hop_modes_are_the_full_car_s(sedan, linear_tires):
    """Heave, pitch and the in-phase wheel hops match :class:`FullCar` once the two couplings the
    full vehicle adds are put into the full car's matrices:

    * gravity's pitch moment on the pitched body, -m_s g h_s theta (its forces reach the body at the
      contact points, h_s below the CG): 4 % of the pitch stiffness;
    * the pitch inertia of what moves fore and aft with the body's pitch: the unsprung masses,
      m_u (h_s - h_u)^2, and the wheel spins that follow their contact points, 4 I_w (h_s / R_e)^2.

    Without them the heave and pitch eigenvalues differ by 1.5 % and 2.1 %. The roll mode and the
    anti-phase (roll) wheel hop couple with the lateral motion: compared with LateralYawRoll below.

    The anti-phase hops also feel the unsprung masses' lateral inertia through the linkage
    (:func:`vehdyn.full_vehicle.corner.unsprung_jacking`, kappa_c = -lambda h_u / y_c with the roll
    centres on the ground): a roll acceleration p' moves the wheel centres sideways by -p' z_w
    (z_w = h_s - h_u below the CG), whose inertia force -m_u (-p' z_w) passes kappa_c times itself to
    the wheel (up) and the opposite to the body at y_c. In FullCar's coordinates (wheel up, roll
    right side down) that is the mass-matrix coupling

        M[wheel_c, roll] += m_uc lambda h_u z_w / y_c,      M[roll, roll] += lambda h_u z_w m_u

    which is zero for lambda = 0 (parallel links: the FullCar of the file) and with it the
    anti-phase hops of lambda = 1 (the default) come back to FullCar's within 1e-3 and 2 % (without
    it: 2.4e-3 and 3 %). The heave, pitch and in-phase hop modes have no roll: unchanged by lambda.
    """
    model = FullVehicle(sedan, *linear_tires(sedan), tire_lag=False)
    full = _eigenvalues(model, 20.0)
    car = FullCar(sedan)
    reference = np.linalg.eigvals(car.A)
    heave_pitch = [e for e in reference if abs(e) < 12 and e.imag > 0]
    assert len(heave_pitch) == 2
    raw = _nearest_errors(heave_pitch, full)
    assert np.all(raw > 0.01) and np.all(raw < 0.025)  # the couplings matter at the 1-2 % level
    for lam in (0.0, 1.0):
        vehicle = sedan.replace(suspension__front_unsprung_transfer_fraction=lam,
                                suspension__rear_unsprung_transfer_fraction=lam)
        m_lam = FullVehicle(vehicle, *linear_tires(vehicle), tire_lag=False)
        full_lam = _eigenvalues(m_lam, 20.0)
        M, C, K = car.mass_matrix.copy(), car.damping_matrix.copy(), car.stiffness_matrix.copy()
        h_u = m_lam.unsprung_cg_height
        z_w = sedan.mass.sprung_cg_height - h_u
        for c, (y_c, m_u) in enumerate(zip(m_lam.corner_y, m_lam.unsprung_masses)):
            M[3 + c, 2] += m_u * lam * h_u * z_w / y_c
        M[2, 2] += lam * h_u * z_w * sedan.mass.unsprung_mass
        hops = [e for e in _second_order_eigenvalues(M, C, K) if abs(e) > 60 and e.imag > 0]
        assert len(hops) == 4
        hop_errors = np.sort(_nearest_errors(hops, full_lam))
        assert np.all(hop_errors[:3] < 1e-3)  # in-phase hops and one anti-phase hop
        assert hop_errors[3] < 0.02  # the other anti-phase hop rolls the body (lateral coupling)
        if lam == 1.0:  # the coupling is what moved them: without it the anti-phase hops are off
            plain = [e for e in reference if abs(e) > 60 and e.imag > 0]
            assert np.sort(_nearest_errors(plain, full_lam))[2] > 2e-3
        else:  # heave and pitch do not see lambda (the model above is lambda = 1)
            for e in heave_pitch:
                assert full_lam[np.argmin(abs(full_lam - e))] == pytest.approx(full[np.argmin(abs(full - e))],
                                                                               rel=1e-9)

    M, C, K = car.mass_matrix.copy(), car.damping_matrix.copy(), car.stiffness_matrix.copy()
    m, h_s = model.sprung_mass, sedan.mass.sprung_cg_height
    K[1, 1] -= m * GRAVITY * h_s
    M[1, 1] += (sedan.mass.unsprung_mass * (h_s - model.unsprung_cg_height) ** 2
                + 4 * sedan.tires.wheel_spin_inertia * (h_s / sedan.tires.rolling_radius) ** 2)
    corrected = [e for e in _second_order_eigenvalues(M, C, K) if abs(e) < 12 and e.imag > 0]
    assert np.all(_nearest_errors(corrected, full) < 1e-3)


def _grounded(vehicle, height):
    """``vehicle`` with its sprung CG ``height`` [m] above the ground and the unsprung masses at half
    of it (the total CG where they put it): the test configuration that switches off every coupling
    the full vehicle adds to :class:`FullCar`. Each of them has the sprung CG's height above the
    contact points as its lever:

    * gravity's moment on the pitched or rolled body, m_s g h_s theta (the loads act at the contact
      points, h_s below the CG; sedan: 4.0 % of the pitch, 11 % of the roll stiffness);
    * the unsprung masses' fore-aft and sideways inertia, m_u (h_s - h_u)^2 (0.9 % of the sprung pitch
      inertia, 6.8 % of the roll inertia);
    * the tires' longitudinal slip: pitching about the CG moves the contact points fore and aft by
      h_s theta, which spins the wheels (4 I_w (h_s / R_e)^2, 1.4 % of the pitch inertia, as a rigid
      wheel; through the slip stiffness a lag that leaves 1e-4 to 7e-4 in the eigenvalues);
    * the tires' lateral slip: rolling about the CG moves the contact points sideways by h_s phi, so
      that roll couples with the lateral and yaw motion (the roll mode 41 % off FullCar's at 20 m/s:
      compared with LateralYawRoll instead);
    * the anti-dive and anti-squat lines (slope f h / L; 0 in the shipped files) and the drag's
      pitch moment (drag times h_s);
    * the drive force against the drag, whose pitch moment has the CG's height above the road as
      its lever, which heave, pitch and the road under the wheels change (the tires' forces act at
      the contact points on the road): without drag no drive force is needed.

    The roll centres stay (on the ground in the file); no roll steer, no camber gains.
    """
    m = vehicle.mass
    return vehicle.replace(mass__sprung_cg_height=height, aero__drag_coefficient=0.0,
                           mass__cg_height=(m.sprung_mass * height + m.unsprung_mass * 0.5 * height) / m.mass)


@pytest.mark.parametrize("height", [1e-4, 1e-7])
def test_full_car_is_the_full_vehicle_with_its_cg_on_the_ground(sedan, linear_tires, height):
    """Straight running at 20 m/s (wheel spin there; no drag, so no drive force: see :func:`_grounded`)
    linearized: with the CG heights going to zero (:func:`_grounded`) all seven FullCar
    modes -- heave, pitch, roll and the four wheel hops -- and the frequency responses from each
    road input to heave acceleration, pitch, roll and suspension travel converge on FullCar's in
    proportion to the height: to 1e-6 at 0.1 um. What is left at 0.1 um is the linearization's
    finite-difference error (1e-7)."""
    vehicle = _grounded(sedan, height)
    model = FullVehicle(vehicle, *linear_tires(vehicle), tire_lag=False)
    x0, u0 = model.trim(20.0)
    linear = model.linearize(x0, u0)
    car = FullCar(vehicle)
    reference = [e for e in np.linalg.eigvals(car.A) if e.imag > 0]
    assert len(reference) == 7
    errors = _nearest_errors(reference, np.linalg.eigvals(linear.A))
    bound = max(height / 1.0, 1e-6)  # 1 per metre of height (the roll mode: 0.13, responses 0.43), >= 1e-6
    assert np.all(errors < bound)
    omega = np.array([1.0, 8.0, 15.0, 60.0, 200.0])  # through heave/pitch, roll and wheel hop
    outputs = ["sprung_acceleration", "pitch_angle", "roll_angle", "suspension_travel_front_left",
               "suspension_travel_rear_right"]
    for corner in CORNERS:
        responses = []
        for system in (linear, car):
            inputs = [f"road_displacement{corner}", f"road_velocity{corner}"]
            H = system.frequency_response(omega, outputs=outputs, inputs=inputs).response
            responses.append(H[:, 0, :] + 1j * omega * H[:, 1, :])  # the road's velocity is its rate
        assert np.max(np.abs(responses[0] - responses[1]) / np.abs(responses[1])) < bound


@pytest.mark.parametrize("speed", [10.0, 20.0, 30.0])
def test_lateral_yaw_roll_modes_are_lateral_yaw_roll_s(reduced, linear_tires, speed):
    """With the full vehicle's additions made negligible (``reduced``: no drag, whose load transfer
    through the drive force shifts the axles' cornering stiffness; stiff tires vertically; light
    unsprung masses, which move with the body in its x-y plane here, their lateral inertia passed
    through the linkage (``unsprung_transfer_fraction``), and stay in the non-rolling frame in
    LateralYawRoll; light wheel spin) the lateral, yaw and roll eigenvalues are LateralYawRoll's to
    0.2 %."""
    model = FullVehicle(reduced, *linear_tires(reduced), tire_lag=False)
    reference = np.linalg.eigvals(LateralYawRoll(reduced, speed).A)
    assert np.all(_nearest_errors(reference, _eigenvalues(model, speed)) < 2e-3)


def test_steady_cornering_yaw_rate_gain_is_the_bicycle_s(sedan, linear_tires):
    """0.3 g at 20 m/s: r / delta equals the linear bicycle's u / (L + K u^2) (drag off, so that the
    drive force shifts no load between the axles; the roll centres on the ground and no roll steer,
    as in the file)."""
    vehicle = sedan.replace(aero__drag_coefficient=0.0)
    model = FullVehicle(vehicle, *linear_tires(vehicle), tire_lag=False)
    x0, u0 = model.trim(20.0, lateral_acceleration=0.3 * GRAVITY)
    gain = x0[model.index("yaw_rate")] / u0[model.index("front_steer_angle", "inputs")]
    bicycle = LinearBicycle(vehicle, 20.0)
    dc = bicycle.D - bicycle.C @ np.linalg.solve(bicycle.A, bicycle.B)  # steady-state gains of the bicycle
    expected = dc[bicycle.index("yaw_rate", "outputs"), bicycle.index("front_steer_angle", "inputs")]
    assert gain == pytest.approx(expected, rel=0.01)


def test_steady_cornering_roll_gradient(reduced, linear_tires):
    """phi / a_y = -m_s h' / (K_phi - m_s g h') (SAE: the body rolls out of the turn), K_phi the
    suspension roll stiffness (springs and bars), h' the sprung CG above the roll axis."""
    model = FullVehicle(reduced, *linear_tires(reduced), tire_lag=False)
    ay = 0.3 * GRAVITY
    x0, _ = model.trim(20.0, lateral_acceleration=ay)
    m_s, h = model.sprung_mass, reduced.mass.sprung_cg_height
    k_phi = reduced.front_roll_stiffness + reduced.rear_roll_stiffness
    expected = -m_s * h * ay / (k_phi - m_s * GRAVITY * h)
    assert x0[model.index("roll_angle")] == pytest.approx(expected, rel=0.01)


def test_steady_cornering_lateral_load_transfer_per_axle(sedan, linear_tires):
    """0.3 g with raised roll centres (geometric, elastic and unsprung parts all present): the
    per-axle transfer and the body roll match the closed form of :func:`vehdyn.handling.steady_roll`
    (linear: a single trim at 0.3 g is within 0.3 % of it; the gradients term by term to 0.05 % in
    ``test_steady_roll.py``)."""
    vehicle = sedan.replace(geometry__front_roll_centre_height=0.08, geometry__rear_roll_centre_height=0.15,
                            aero__drag_coefficient=0.0)
    model = FullVehicle(vehicle, *linear_tires(vehicle), tire_lag=False)
    ay = 0.3 * GRAVITY
    x0, u0 = model.trim(20.0, lateral_acceleration=ay)
    y = dict(zip(model.output_names, model.output(0.0, x0, u0)))
    transfer = ((y["normal_load_front_left"] - y["normal_load_front_right"]) / 2,
                (y["normal_load_rear_left"] - y["normal_load_rear_right"]) / 2)
    roll = steady_roll(vehicle)
    expected, phi = np.multiply(roll.load_transfer, ay), -roll.roll_gradient * ay
    np.testing.assert_allclose(transfer, expected, rtol=0.01)
    assert y["roll_angle"] == pytest.approx(phi, rel=0.01)
    # the geometric part is there: with the roll centres on the ground the front transfer differs
    ground = sedan.replace(aero__drag_coefficient=0.0)
    model0 = FullVehicle(ground, *linear_tires(ground), tire_lag=False)
    x1, u1 = model0.trim(20.0, lateral_acceleration=ay)
    y1 = dict(zip(model0.output_names, model0.output(0.0, x1, u1)))
    expected0 = np.multiply(steady_roll(ground).load_transfer, ay)
    assert (y1["normal_load_front_left"] - y1["normal_load_front_right"]) / 2 == pytest.approx(expected0[0], rel=0.01)
    assert abs(expected0[0] - expected[0]) > 0.05 * expected[0]


@pytest.mark.parametrize("anti_dive", [0.0, 0.5])
def test_straight_braking_load_transfer_and_pitch(sedan, linear_tires, anti_dive):
    """0.5 g braking (quasi-steady, drag off): the front axle gains m a_x h / L plus what the pitch
    and the wheels' spin add, the loads still carry the weight, and the body pitches by the spring
    and tire deflections under the load changes less the anti-dive linkage force.

    The two additions (each ~2 % of the transfer here): the body pitched by theta moves the sprung CG
    fore-aft over the wheel centres, which lie z_w below it in the body (suspension travel along
    body z), by z_w theta: the sprung weight's moment -m_s g z_w theta; the four wheels decelerate
    at a_x / R_e, and their spin angular momentum takes the moment -4 I_w a_x / R_e (Wong, *Theory
    of Ground Vehicles*, 4th ed., 2008, sec. 3.1.1, the rotating parts' inertia in braking)."""
    vehicle = sedan.replace(aero__drag_coefficient=0.0, suspension__front_anti_dive=anti_dive)
    model = FullVehicle(vehicle, *linear_tires(vehicle))
    ax = -0.5 * GRAVITY
    x0, u0 = model.trim(20.0, longitudinal_acceleration=ax)
    y = dict(zip(model.output_names, model.output(0.0, x0, u0)))
    static = model.static_loads()
    delta = {s: y[f"normal_load{s}"] - static[f"normal_load{s}"] for s in CORNERS}
    m, L, h = vehicle.mass.mass, vehicle.wheelbase, vehicle.mass.cg_height
    pitch, t = y["pitch_angle"], vehicle.tires
    transfer = (-m * ax * h - vehicle.mass.sprung_mass * GRAVITY * (vehicle.mass.sprung_cg_height - model.unsprung_cg_height) * pitch
                - 4 * t.wheel_spin_inertia * ax / t.rolling_radius) / L
    assert delta["_front_left"] + delta["_front_right"] == pytest.approx(transfer, rel=0.01)
    assert -(delta["_rear_left"] + delta["_rear_right"]) == pytest.approx(transfer, rel=0.015)
    assert sum(delta.values()) == pytest.approx(0.0, abs=2e-3 * m * GRAVITY)  # no lift from the braking forces
    assert y["longitudinal_acceleration"] == pytest.approx(ax, rel=1e-9)
    # pitch from the deflections: spring force change = load change - linkage force (anti-dive, front)
    s, kt = vehicle.suspension, vehicle.tires.vertical_stiffness
    jack = anti_dive * h / L * y["longitudinal_force_front_left"]  # body z force, down +; the wheel gets it up
    front = (delta["_front_left"] + jack) / s.front_spring_rate + delta["_front_left"] / kt
    rear = delta["_rear_left"] / s.rear_spring_rate + delta["_rear_left"] / kt
    expected = (rear - front) / L
    assert y["pitch_angle"] == pytest.approx(expected, rel=0.01)


def test_magic_formula_handling_diagram_reaches_a_lower_limit_than_the_single_track(sedan):
    """Magic Formula tires at 20 m/s: at small a_y the full vehicle steers as the nonlinear single
    track (wheel spin, the same tires, no load transfer between sides); towards the limit the
    lateral load transfer lowers each axle's peak force (the law's force grows less than in
    proportion to the load), so the full vehicle needs more steer and its steady states end at a
    lower lateral acceleration."""
    from vehdyn.handling import SingleTrack
    from vehdyn.handling.nonlinear_steady_state import limit_lateral_acceleration, steady_state_cornering

    single = SingleTrack(sedan, wheel_spin=True)
    full = FullVehicle(sedan)
    previous, last, steer = None, 0.0, {}
    for ay in np.arange(0.5, 9.5, 0.5):
        try:
            previous = full.trim(20.0, lateral_acceleration=float(ay), guess=previous)
        except ParameterError:
            break
        last, steer[float(ay)] = float(ay), float(previous[1][0])
    limit = limit_lateral_acceleration(single, speed=20.0)
    assert 0.6 * limit < last < 0.9 * limit
    low = steady_state_cornering(single, lateral_acceleration=1.0, speed=20.0).steer_angle
    assert steer[1.0] == pytest.approx(low, rel=0.03)
    high = steady_state_cornering(single, lateral_acceleration=last, speed=20.0).steer_angle
    assert steer[last] > 1.3 * high


@pytest.mark.parametrize("speed", [5.0, 40.0])
def test_straight_running_is_stable_with_magic_formula_tires_and_lag(sedan, speed):
    """Every mode of straight running decays (the two drift modes of position/heading are zero),
    and none is faster than about 100 1/s: an explicit solver needs no tiny steps."""
    model = FullVehicle(sedan)
    eigenvalues = _eigenvalues(model, speed)
    assert np.all(eigenvalues.real < 1e-8)
    assert np.sum(np.abs(eigenvalues) < 1e-8) <= 3  # x, y, yaw angle
    assert np.min(eigenvalues.real) > -150.0


def _steady_wind_gains(model, speed):
    """Steady yaw rate [rad/s] and lateral acceleration [m/s^2] per m/s of lateral wind, from the
    linearization about straight running (steer and torques held; the earth position and heading,
    which drift, left out; without drag the speed's coast mode is neutral, so least squares)."""
    x0, u0 = model.trim(speed)
    linear = model.linearize(x0, u0)
    keep = [j for j, n in enumerate(model.state_names) if n not in ("x", "y", "yaw_angle")]
    wind = model.index("wind_velocity_lateral", "inputs")
    rows = [model.index(n, "outputs") for n in ("yaw_rate", "lateral_acceleration")]
    A, B = linear.A[np.ix_(keep, keep)], linear.B[keep, wind]
    steady = np.linalg.lstsq(A, -B, rcond=None)[0]
    assert np.max(np.abs(A @ steady + B)) < 1e-9 * np.max(np.abs(B))  # a true steady state
    return linear.C[np.ix_(rows, keep)] @ steady + linear.D[rows, wind]


def _bicycle_wind_gains(vehicle, speed):
    bicycle = LinearBicycle(vehicle, speed, crosswind=True)
    return bicycle.select(["yaw_rate", "lateral_acceleration"], ["wind_velocity_lateral"]).dc_gain()[:, 0]


@pytest.mark.parametrize("speed", [10.0, 20.0, 30.0])
def test_crosswind_gains_are_the_bicycle_s(sedan, linear_tires, speed):
    """The steady yaw rate and lateral acceleration per m/s of lateral wind (side force at the centre
    of pressure, the law of :mod:`vehdyn.handling.crosswind`) equal LinearBicycle(crosswind=True)'s:

    * without drag to 1e-9 (the wind's roll moment shifts load between sides, which linear tires
      with stiffness proportional to load do not feel);
    * with the sedan's drag within 3 %: the drag acts at the sprung CG's height and the drive force
      at the ground, so the axle loads shift by D h_s / L to the rear, and with them the axles'
      cornering stiffnesses (0.5 %, 0.7 %, -2.8 % at 10, 20, 30 m/s; the gains are small
      differences, the centre of pressure lying near the neutral steer point). The bicycle with its
      cornering stiffnesses shifted so is within 0.5 %; and with the CG on the ground (drag kept)
      the difference vanishes (1e-6): it is the heights' alone.
    """
    drag_free = sedan.replace(aero__drag_coefficient=0.0)
    model = FullVehicle(drag_free, *linear_tires(drag_free), tire_lag=False)
    np.testing.assert_allclose(_steady_wind_gains(model, speed), _bicycle_wind_gains(drag_free, speed), rtol=1e-9)

    model = FullVehicle(sedan, *linear_tires(sedan), tire_lag=False)
    gains = _steady_wind_gains(model, speed)
    np.testing.assert_allclose(gains, _bicycle_wind_gains(sedan, speed), rtol=0.03)
    aero, tires, m = sedan.aero, sedan.tires, sedan.mass
    shift = 0.5 * aero.air_density * aero.drag_coefficient * aero.frontal_area * speed**2 * m.sprung_cg_height \
        / sedan.wheelbase
    front_load = m.mass * GRAVITY * sedan.geometry.b / sedan.wheelbase
    shifted = sedan.replace(
        tires__front_cornering_stiffness=tires.front_cornering_stiffness * (1 - shift / front_load),
        tires__rear_cornering_stiffness=tires.rear_cornering_stiffness * (1 + shift / (m.mass * GRAVITY - front_load)))
    np.testing.assert_allclose(gains, _bicycle_wind_gains(shifted, speed), rtol=0.005)
    grounded = _grounded(sedan, 1e-6)
    model = FullVehicle(grounded, *linear_tires(grounded), tire_lag=False)
    np.testing.assert_allclose(_steady_wind_gains(model, speed), _bicycle_wind_gains(grounded, speed), rtol=1e-6)


@pytest.mark.parametrize("ay", [2.0, 6.0])
def test_tire_loads_carry_the_weight_in_a_steady_turn(sedan, ay):
    """Magic Formula tires, 0.2 and 0.6 g at 22 m/s (body rolled 2 and 6 deg): the tires' side forces
    lie in the road plane, so the four normal loads carry the weight less the aero lift whatever the
    roll (applied along the rolled body's y axis they would lift the car by sum F_y sin(phi): 5.8 %
    of the weight at 0.6 g: 10.10 kN against 10.73 kN)."""
    model = FullVehicle(sedan)
    x0, u0 = model.trim(22.0, lateral_acceleration=ay)
    y = dict(zip(model.output_names, model.output(0.0, x0, u0)))
    assert abs(y["roll_angle"]) > np.radians(1.5) * ay / 2.0
    loads = sum(y[f"normal_load{s}"] for s in CORNERS)
    a = sedan.aero
    lift = 0.5 * a.air_density * a.frontal_area * (a.front_lift_coefficient + a.rear_lift_coefficient) * x0[0] ** 2
    # to second order in the roll: the wheels travel along the body's z axis, taken as vertical
    # (W (1 - cos phi) = 0.5 % at 0.1 rad)
    assert loads == pytest.approx(sedan.mass.mass * GRAVITY - lift, rel=5e-3)
