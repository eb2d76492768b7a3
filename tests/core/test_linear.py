"""LinearModel: linearization round trips, exports, frequency response, modes."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import vehdyn
from vehdyn import LinearModel, Model, ParameterError
from vehdyn.interconnect import connect_in_series


def random_stable_model(seed, n, m, p):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(n, n))
    A -= (np.max(np.linalg.eigvals(A).real) + 0.5) * np.eye(n)
    return LinearModel(A, rng.normal(size=(n, m)), rng.normal(size=(p, n)), rng.normal(size=(p, m)),
                       states=[f"state_{i}" for i in range(n)], inputs=[f"input_{i}" for i in range(m)],
                       outputs=[f"output_{i}" for i in range(p)])


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**31), n=st.integers(1, 6), m=st.integers(1, 3), p=st.integers(1, 3))
def test_linearize_round_trip(seed, n, m, p):
    model = random_stable_model(seed, n, m, p)
    lin = model.linearize()
    for a, b in ((lin.A, model.A), (lin.B, model.B), (lin.C, model.C), (lin.D, model.D)):  # its own matrices
        np.testing.assert_array_equal(a, b)
    assert lin.state_names == model.state_names and lin.output_names == model.output_names

    # and through the finite-difference path of the Model base class: exact to rounding
    class Wrapped(Model):
        states, inputs, outputs = model.states, model.inputs, model.outputs

        def rhs(self, t, x, u):
            return model.A @ x + model.B @ u

        def output(self, t, x, u):
            return model.C @ x + model.D @ u

    x0 = np.random.default_rng(seed).normal(size=n)
    fd = Wrapped().linearize(x0, np.ones(m))
    # rounding bound of the difference quotient: eps |f| / h, |f| <~ (sum |M|) (|x| + |u|)
    scale = max(np.abs(M).sum(axis=1).max() for M in (model.A, model.B, model.C, model.D))
    tol = 1e-9 * scale * (1 + np.abs(x0).max())
    for a, b in ((fd.A, model.A), (fd.B, model.B), (fd.C, model.C), (fd.D, model.D)):
        np.testing.assert_allclose(a, b, rtol=0, atol=tol)


class Pendulum(Model):
    states = ("angle", "angle_rate")
    inputs = ("torque",)
    outputs = ("angle", "tip_height")

    def rhs(self, t, x, u):
        angle, rate = x
        (torque,) = u
        return np.stack([rate, -9.81 * np.sin(angle) - 0.3 * rate + torque])

    def output(self, t, x, u):
        angle, rate = x
        return np.stack([angle, -np.cos(angle)])


def test_finite_difference_linearization_against_analytic():
    lin = Pendulum().linearize([0.7, 0.2], [0.1])
    np.testing.assert_allclose(lin.A, [[0, 1], [-9.81 * np.cos(0.7), -0.3]], rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(lin.B, [[0], [1]], atol=1e-12)
    np.testing.assert_allclose(lin.C, [[1, 0], [np.sin(0.7), 0]], rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(lin.x_op, [0.7, 0.2])
    np.testing.assert_allclose(lin.y_op, [0.7, -np.cos(0.7)])


def test_control_export_keeps_names_and_linearization_agrees():
    import control as ct

    model = Pendulum()
    sys = model.to_control()
    assert list(sys.state_labels) == ["angle", "angle_rate"]
    assert list(sys.input_labels) == ["torque"] and list(sys.output_labels) == ["angle", "tip_height"]
    x0, u0 = [0.7, 0.2], [0.1]
    ct_lin = ct.linearize(sys, x0, u0)
    ours = model.linearize(x0, u0)
    # python-control uses a one-sided difference with step 1e-6: agreement to its accuracy
    for a, b in ((ct_lin.A, ours.A), (ct_lin.B, ours.B), (ct_lin.C, ours.C), (ct_lin.D, ours.D)):
        np.testing.assert_allclose(a, b, rtol=1e-5, atol=1e-5)
    ss = ours.to_control()
    assert list(ss.state_labels) == ["angle", "angle_rate"] and list(ss.output_labels) == ["angle", "tip_height"]
    back = LinearModel.from_control(ss)
    np.testing.assert_array_equal(back.A, ours.A)
    assert back.output_names == ours.output_names


def test_to_scipy_matches():
    m = random_stable_model(3, 3, 2, 2)
    s = m.to_scipy()
    np.testing.assert_array_equal(s.A, m.A)
    np.testing.assert_array_equal(s.D, m.D)


def test_frequency_response_matches_python_control():
    import control as ct

    m = random_stable_model(7, 4, 2, 3)
    omega = np.logspace(-2, 3, 1000)
    fr = m.frequency_response(omega)
    ref = ct.frequency_response(m.to_control(), omega)
    H = ref.magnitude * np.exp(1j * ref.phase)
    np.testing.assert_allclose(fr.response, H, rtol=1e-10, atol=1e-12)
    assert fr["output_1", "input_0"].shape == (1000,)
    df = fr.to_frame()
    assert ("output_1", "input_0", "magnitude") in df.columns


def test_frequency_response_of_first_order_closed_form():
    m = LinearModel([[-2.0]], [[2.0]], states=["level"], inputs=["drive"])
    w = np.array([0.0, 2.0, 20.0])
    h = m.frequency_response(w)["level", "drive"]
    np.testing.assert_allclose(h, 2.0 / (1j * w + 2.0), rtol=1e-15)
    np.testing.assert_allclose(m.frequency_response(w).phase[0, 0, 1], -np.pi / 4, rtol=1e-14)


def two_dof():
    """m1 = m2 = m, springs k to ground on each side and k between: w1 = sqrt(k/m), w2 = sqrt(3k/m)."""
    m, k = 2.0, 800.0
    M = np.diag([m, m])
    K = np.array([[2 * k, -k], [-k, 2 * k]])
    return M, K, m, k


def test_modes_of_two_dof_against_closed_form():
    M, K, m, k = two_dof()
    c = 0.01 * K  # proportional damping: zeta_i = 0.01 w_i / 2
    model = LinearModel.from_second_order(M, c, K, dof=["left_displacement", "right_displacement"])
    assert model.state_names == ("left_displacement", "right_displacement", "left_velocity", "right_velocity")
    w = np.sqrt([k / m, 3 * k / m])
    modes = model.modes()
    np.testing.assert_allclose(modes.natural_frequency, w, rtol=1e-12)
    np.testing.assert_allclose(modes.damping_ratio, 0.01 * w / 2, rtol=1e-12)
    np.testing.assert_allclose(modes.natural_frequency_hz, w / (2 * np.pi), rtol=1e-12)
    # in-phase then anti-phase displacement shapes
    s0, s1 = modes.shape(0), modes.shape(1)
    assert np.isclose(s0["left_displacement"] / s0["right_displacement"], 1.0)
    assert np.isclose(s1["left_displacement"] / s1["right_displacement"], -1.0)
    modal = model.modal_analysis()
    np.testing.assert_allclose(modal.natural_frequency, w, rtol=1e-12)
    np.testing.assert_allclose(modal.shapes.T @ M @ modal.shapes, np.eye(2), atol=1e-12)
    np.testing.assert_allclose(modal.shapes[:, 0], np.array([1, 1]) / np.sqrt(2 * m), rtol=1e-12)
    assert modal.proportional
    np.testing.assert_allclose(modal.damping_ratio, 0.01 * w / 2, rtol=1e-12)
    assert modes.to_frame().attrs["units"]["natural_frequency_hz"] == "Hz"


def test_non_proportional_damping_is_flagged():
    M, K, m, k = two_dof()
    modal = vehdyn.model.modal_analysis(M, K, np.diag([10.0, 0.0]))
    assert not modal.proportional


def test_connect_in_series_matches_control_series():
    import control as ct

    up = LinearModel([[-1.0]], [[1.0]], [[2.0]], [[0.5]], states=["filter_state"], inputs=["noise"],
                     outputs=["force"])
    down = LinearModel([[0, 1], [-4, -0.4]], [[0], [1]], states=["position", "position_velocity"], inputs=["force"])
    both = connect_in_series(up, down)
    ref = ct.series(up.to_control(), down.to_control())
    w = np.logspace(-1, 2, 50)
    np.testing.assert_allclose(both.frequency_response(w, outputs=["position"]).response[0, 0],
                               ct.frequency_response(ref[0, 0], w).complex, rtol=1e-10)
    assert both.input_names == ("noise",) and "force" in both.output_names


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"A": [[1.0, 2.0]]}, r"A must have shape \(1, 1\)"),
        ({"A": [[np.nan]]}, r"A\[0, 0\] is not finite"),
        ({"B": [[1.0], [2.0]]}, "B must have shape"),
        ({"states": ["Bad.Name"]}, "not snake_case"),
        ({"states": ["x"], "inputs": ["x", "x"]}, "appears twice"),
    ],
)
def test_linear_model_rejects_bad_matrices(kwargs, match):
    args = {"A": [[-1.0]], "B": [[1.0]], "states": ["level"], "inputs": ["drive"]}
    args.update(kwargs)
    with pytest.raises(ParameterError, match=match):
        LinearModel(args.pop("A"), args.pop("B"), **args)


def test_from_second_order_rejects_bad_mass_matrix():
    with pytest.raises(ParameterError, match="positive definite"):
        LinearModel.from_second_order(np.diag([1.0, -1.0]), np.zeros((2, 2)), np.eye(2), dof=["q_one", "q_two"])
    with pytest.raises(ParameterError, match="symmetric"):
        LinearModel.from_second_order([[1.0, 0.2], [0.0, 1.0]], np.zeros((2, 2)), np.eye(2), dof=["q_one", "q_two"])


def test_unknown_phenomenon_is_rejected():
    with pytest.raises(ParameterError, match="unknown entries"):
        class Bad(Model):
            phenomena = frozenset({"teleportation"})
