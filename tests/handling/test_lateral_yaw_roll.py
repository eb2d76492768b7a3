"""LateralYawRoll against B-3DOF-2, B-ROLLGRAD-BF, the bicycle limit, the roll-gradient closed form and an
independent kinetic-energy computation of its mass matrix."""

import numpy as np
import pytest

import vehdyn
from vehdyn import conventions
from vehdyn.handling import LateralYawRoll, LinearBicycle, lateral_yaw_roll_parameters, roll_gradient

BASE = dict(mass=1500.0, sprung_mass=1350.0, yaw_inertia=2500.0, sprung_roll_inertia=400.0, a=1.1, b=1.6,
            roll_arm=0.45, front_cornering_stiffness=110e3, rear_cornering_stiffness=120e3, roll_stiffness=55e3,
            roll_damping=3500.0)


def _iso_tensor_to_sae(tensor):
    """Inertia tensor from ISO 8855 to SAE axes: apply the y/z flip to columns and rows."""
    cols = np.array([conventions.iso8855_to_sae(*c) for c in np.asarray(tensor).T]).T
    return np.array([conventions.iso8855_to_sae(*r) for r in cols])


def test_b3dof2_eigenvalues_and_roll_gain(reference_case, approx_case):
    case = reference_case("B-3DOF-2")
    i = {k: v[0] for k, v in case["inputs"].items()}
    e = case["expected"]
    # the case writes I_xz in ISO axes (z up); SAE's z points down, so the product changes sign
    iso = np.array([[i["Ixx_about_roll_axis"], 0, -i["Ixz"]], [0, 1.0, 0], [-i["Ixz"], 0, i["Iz"]]])
    ixz_sae = -_iso_tensor_to_sae(iso)[0, 2]
    # roll steer is a steer angle (about z) per roll angle (about x, same in both): it changes sign
    eps_f = float(conventions.steer_angle_iso8855_to_sae(i["eps_f_roll_steer"]))
    eps_r = float(conventions.steer_angle_iso8855_to_sae(i["eps_r_roll_steer"]))
    model = LateralYawRoll.from_parameters(
        mass=i["m"], sprung_mass=i["ms"], yaw_inertia=i["Iz"], sprung_roll_inertia=i["Ixs_sprung_roll_inertia_about_sprung_CG"],
        a=i["lf"], b=i["lr"], roll_arm=i["h_sprungCG_above_roll_axis"], front_cornering_stiffness=i["Cf_axle"],
        rear_cornering_stiffness=i["Cr_axle"], roll_stiffness=i["Kphi_total"], roll_damping=i["Cphi_total"],
        roll_yaw_product=ixz_sae, front_roll_steer=eps_f, rear_roll_steer=eps_r, gravity=i["g"], speed=i["u"])
    # README pitfall 9: I_x about the roll axis = I_xs + m_s h^2
    assert model.parameters.roll_inertia == pytest.approx(i["Ixx_about_roll_axis"], rel=1e-12)
    eig = model.poles()
    eig = eig[eig.imag > 0]
    eig = eig[np.argsort(-eig.real)]
    assert eig[0].real == approx_case(e["eig_pair1_real"])
    assert eig[0].imag == approx_case(e["eig_pair1_imag"])
    assert eig[1].real == approx_case(e["eig_pair2_real"])
    assert eig[1].imag == approx_case(e["eig_pair2_imag"])
    phi_per_delta_sae = model.dc_gain()[model.index("roll_angle", "outputs"), 0]
    # roll (about x) keeps its sign, the steer angle flips: phi/delta changes sign
    phi_per_delta_iso = phi_per_delta_sae / float(conventions.steer_angle_sae_to_iso8855(1.0))
    assert phi_per_delta_iso == approx_case(e["phi/delta_ss"])
    # the case's note: I_xz changes the transients, not the steady state
    no_ixz = LateralYawRoll(model.parameters.replace(roll_yaw_product=0.0), i["u"])
    np.testing.assert_allclose(no_ixz.dc_gain(), model.dc_gain(), rtol=1e-10, atol=1e-12)
    assert not np.allclose(np.sort_complex(no_ixz.poles()), np.sort_complex(model.poles()))


def test_published_roll_gradient(reference_case, approx_case):
    """B-ROLLGRAD-BF (Barton & Fieldhouse 2018, eq. 3.18): the model's steady roll per a_y equals it."""
    case = reference_case("B-ROLLGRAD-BF")
    i = {k: v[0] for k, v in case["inputs"].items()}
    e = case["expected"]
    model = LateralYawRoll.from_parameters(**dict(BASE, sprung_mass=i["ms"], roll_arm=i["d_CG_above_roll_axis"],
                                                  roll_stiffness=i["Kphi_total"], mass=1450.0), speed=20.0)
    assert model.roll_gradient() == approx_case(e["roll_gradient"])
    assert model.roll_gradient_deg_per_g() == approx_case(e["roll_gradient_deg_per_g"])
    closed = i["ms"] * i["d_CG_above_roll_axis"] / (i["Kphi_total"] - i["ms"] * i["g"] * i["d_CG_above_roll_axis"])
    dc = model.dc_gain()[:, 0]
    roll_per_ay = dc[model.index("roll_angle", "outputs")] / dc[model.index("lateral_acceleration", "outputs")]
    # SAE: a right turn (a_y > 0) rolls the body left side down (phi < 0)
    assert roll_per_ay == pytest.approx(-closed, rel=1e-10)


@pytest.mark.parametrize("name", ["sedan", "compact", "van"])
def test_simulated_roll_gradient_of_shipped_vehicles(name):
    """Issue 5 item 6: simulate a step steer; phi / a_y at the end equals m_s h / (K_phi - m_s g h)."""
    vehicle = vehdyn.load_vehicle(name)
    model = LateralYawRoll(vehicle, 20.0)
    t = np.linspace(0.0, 8.0, 801)
    res = vehdyn.simulate(model, t, {"front_steer_angle": np.deg2rad(0.5)})
    p = model.parameters
    h = vehicle.mass.sprung_cg_height  # roll centres of the shipped vehicles are on the ground
    assert p.roll_arm == pytest.approx(h, rel=1e-12)
    kphi = vehicle.front_roll_stiffness + vehicle.rear_roll_stiffness
    closed = p.sprung_mass * h / (kphi - p.sprung_mass * 9.81 * h)
    assert res["roll_angle"][-1] / res["lateral_acceleration"][-1] == pytest.approx(-closed, rel=1e-6)
    assert roll_gradient(vehicle) == pytest.approx(closed, rel=1e-12)


def test_reduces_to_the_bicycle_without_roll_coupling():
    """m_s h = 0, I_xz = 0 and no roll steer: the lateral/yaw block is the bicycle model."""
    model = LateralYawRoll.from_parameters(**dict(BASE, roll_arm=0.0), speed=25.0)
    bike = LinearBicycle.from_parameters(mass=1500.0, yaw_inertia=2500.0, a=1.1, b=1.6,
                                         front_cornering_stiffness=110e3, rear_cornering_stiffness=120e3, speed=25.0)
    np.testing.assert_allclose(model.A[:2, :2], bike.A, rtol=1e-13)
    np.testing.assert_array_equal(model.A[:2, 2:], 0.0)
    omega = np.logspace(-1, 2, 30)
    names = ["yaw_rate", "lateral_acceleration", "sideslip_angle", "front_slip_angle", "rear_lateral_force"]
    a = model.frequency_response(omega, outputs=names)
    b = bike.frequency_response(omega, outputs=names)
    np.testing.assert_allclose(a.response, b.response, rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(model.bicycle().A, bike.A, rtol=1e-14)


def test_converges_to_the_bicycle_as_roll_stiffness_grows():
    bike = LinearBicycle.from_parameters(mass=1500.0, yaw_inertia=2500.0, a=1.1, b=1.6,
                                         front_cornering_stiffness=110e3, rear_cornering_stiffness=120e3, speed=25.0)
    omega = np.array([0.5, 3.0, 10.0])
    ref = bike.frequency_response(omega, outputs=["yaw_rate"])["yaw_rate", "front_steer_angle"]
    errors = []
    for kphi in (1e5, 1e6, 1e7):
        model = LateralYawRoll.from_parameters(**dict(BASE, roll_stiffness=kphi, roll_damping=0.05 * kphi), speed=25.0)
        h = model.frequency_response(omega, outputs=["yaw_rate"])["yaw_rate", "front_steer_angle"]
        errors.append(np.max(np.abs(h - ref) / np.abs(ref)))
    assert errors[0] > errors[1] > errors[2] and errors[2] < 1e-2


def test_roll_steer_understeer_gradient():
    """K_eff = K + (eps_f - eps_r) m_s h / (K_phi - m_s g h), checked against the model's own dc gain."""
    model = LateralYawRoll.from_parameters(**dict(BASE, front_roll_steer=0.1, rear_roll_steer=-0.05), speed=22.0)
    r_gain = model.dc_gain()[model.index("yaw_rate", "outputs"), 0]
    L, u = model.wheelbase, 22.0
    from_dc = (u / r_gain - L) / u**2  # r / delta = u / (L + K u^2)
    assert model.understeer_gradient() == pytest.approx(from_dc, rel=1e-10)
    # front roll steer out of the turn and rear roll steer into it both add understeer
    assert model.understeer_gradient() > model.parameters.bicycle_parameters().understeer_gradient


def _kinetic_energy(vehicle, v, r, p):
    """Kinetic energy at zero roll and zero forward speed of unsprung point masses at the axles and a
    rigid sprung mass rolling about the axis through the roll centres (3-D vectors, no small-angle algebra)."""
    ms, g = vehicle.mass, vehicle.geometry
    L = g.wheelbase
    x_s = g.a - g.sprung_cg_to_front_axle
    front = np.array([g.a, 0.0, -g.front_roll_centre_height])  # SAE: z down, heights negative
    rear = np.array([-g.b, 0.0, -g.rear_roll_centre_height])
    e = (front - rear) / np.linalg.norm(front - rear)
    cg = np.array([x_s, 0.0, -ms.sprung_cg_height])
    omega = np.array([0.0, 0.0, r]) + p * e
    vel_ref = np.array([0.0, v, 0.0])
    vel_cg = vel_ref + np.cross([0.0, 0.0, r], cg) + p * np.cross(e, cg - rear)
    jzz = ms.yaw_inertia - ms.sprung_mass * x_s**2 - ms.front_unsprung_mass * g.a**2 - ms.rear_unsprung_mass * g.b**2
    J = np.array([[ms.sprung_roll_inertia, 0, -ms.sprung_roll_yaw_product], [0, ms.sprung_pitch_inertia, 0],
                  [-ms.sprung_roll_yaw_product, 0, jzz]])
    T = 0.5 * ms.sprung_mass * vel_cg @ vel_cg + 0.5 * omega @ J @ omega
    rest = ms.mass - ms.sprung_mass - ms.front_unsprung_mass - ms.rear_unsprung_mass  # rounding of the data
    for mass, x in ((ms.front_unsprung_mass, g.a), (ms.rear_unsprung_mass, -g.b), (rest, 0.0)):
        T += 0.5 * mass * (v + r * x) ** 2
    assert L > 0
    return T


def test_mass_matrix_equals_hessian_of_the_kinetic_energy():
    """I_x, I_xz and m_s h of the Lagrange derivation, with an inclined roll axis and a sprung I_xz."""
    sedan = vehdyn.load_vehicle("sedan").replace(geometry__front_roll_centre_height=0.04,
                                                 geometry__rear_roll_centre_height=0.13,
                                                 mass__sprung_roll_yaw_product=25.0)
    model = LateralYawRoll(sedan, 20.0)
    assert model.parameters.roll_axis_inclination < 0  # the axis falls towards the front
    # T is quadratic in (v, r, p): its Hessian by exact second differences of a quadratic form
    H = np.zeros((3, 3))
    basis = np.eye(3)
    for i in range(3):
        for j in range(3):
            f = lambda z: _kinetic_energy(sedan, *z)  # noqa: E731
            H[i, j] = f(basis[i] + basis[j]) - f(basis[i]) - f(basis[j]) + f(np.zeros(3))
    # the shipped masses put the total CG within 1e-9 m of its stated position: m-v/r coupling ~1e-6
    np.testing.assert_allclose(model.mass_matrix[:3, :3], H, rtol=1e-12, atol=1e-5)


def test_lateral_yaw_roll_errors():
    with pytest.raises(vehdyn.ParameterError, match="roll_stiffness"):
        LateralYawRoll.from_parameters(**dict(BASE, roll_stiffness=5000.0), speed=20.0)
    with pytest.raises(vehdyn.ParameterError, match="sprung_mass"):
        LateralYawRoll.from_parameters(**dict(BASE, sprung_mass=2000.0), speed=20.0)
    with pytest.raises(vehdyn.ParameterError, match="roll_yaw_product"):
        LateralYawRoll.from_parameters(**dict(BASE, roll_yaw_product=2000.0), speed=20.0)
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        LateralYawRoll(vehdyn.load_vehicle("van"), 0.0)
    with pytest.raises(vehdyn.ParameterError, match="Vehicle"):
        LateralYawRoll("van", 10.0)
    with pytest.raises(vehdyn.ParameterError, match="yaw_inertia"):
        lateral_yaw_roll_parameters(vehdyn.load_vehicle("van").replace(mass__yaw_inertia=240.0,
                                                                       mass__pitch_inertia=800.0))


def test_tire_compliance_in_series_with_the_suspension():
    van = vehdyn.load_vehicle("van")
    stiff = lateral_yaw_roll_parameters(van)
    soft = lateral_yaw_roll_parameters(van, tire_compliance=True)
    g, kt = van.geometry, van.tires.vertical_stiffness

    def series(k_susp, track):
        k_tire = kt * track**2 / 2
        return 1.0 / (1.0 / k_susp + 1.0 / k_tire)

    expected = series(van.front_roll_stiffness, g.front_track) + series(van.rear_roll_stiffness, g.rear_track)
    assert stiff.roll_stiffness == pytest.approx(van.front_roll_stiffness + van.rear_roll_stiffness, rel=1e-14)
    assert soft.roll_stiffness == pytest.approx(expected, rel=1e-12)
    assert roll_gradient(van, tire_compliance=True) > roll_gradient(van)
