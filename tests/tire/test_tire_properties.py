"""Property tests (hypothesis) of every tire law: friction bound, odd symmetry, scalar/array agreement, finiteness.

Documented domain: any finite load (negative = lift-off), slip ratio, camber and speed (including
0), slip angle in (-pi/2, pi/2).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vehdyn.tire import BrushTire, DugoffTire, FialaTire, LinearTire

LAWS = {
    "brush": BrushTire(contact_half_length=0.09, tread_stiffness=4.0e6, mu=1.0),
    "brush_sliding": BrushTire(contact_half_length=0.07, tread_stiffness=8.0e6, mu=1.1, mu_sliding=0.8),
    "fiala": FialaTire(cornering_stiffness=60000.0, mu=0.9, slip_stiffness=90000.0, contact_half_length=0.08),
    "dugoff": DugoffTire(cornering_stiffness=70000.0, slip_stiffness=100000.0, mu=0.95,
                         speed_friction_reduction=0.01, pneumatic_trail=0.03),
    "linear": LinearTire(cornering_stiffness=60000.0, slip_stiffness=80000.0, pneumatic_trail=0.02,
                         nominal_load=4000.0),
}
SATURATING = [name for name in LAWS if name != "linear"]  # the linear law has no friction limit
# laws whose longitudinal force is a function of the practical slip ratio (odd in kappa); the
# brush and Dugoff laws use the theoretical slip kappa / (1 + kappa) instead
PRACTICAL_SLIP = ["fiala", "linear"]

loads = st.floats(-1000.0, 30000.0)
positive_loads = st.floats(1.0, 30000.0)
slip_ratios = st.floats(-5.0, 5.0)
slip_angles = st.floats(-1.5707, 1.5707)
cambers = st.floats(-0.3, 0.3)
speeds = st.one_of(st.just(0.0), st.floats(-60.0, 60.0))
SETTINGS = settings(max_examples=60, deadline=None)


@pytest.mark.parametrize("name", SATURATING)
@SETTINGS
@given(fz=loads, kappa=slip_ratios, alpha=slip_angles, vx=speeds)
def test_force_within_friction_circle(name, fz, kappa, alpha, vx):
    law = LAWS[name]
    out = law.forces(fz, kappa, alpha, 0.0, vx)
    assert math.hypot(out.fx, out.fy) <= law.mu * max(fz, 0.0) * (1 + 1e-12) + 1e-9


@pytest.mark.parametrize("name", list(LAWS))
@SETTINGS
@given(fz=positive_loads, kappa=slip_ratios, alpha=slip_angles, vx=speeds)
def test_side_force_and_moment_odd_in_slip_angle(name, fz, kappa, alpha, vx):
    law = LAWS[name]
    plus, minus = law.forces(fz, kappa, alpha, 0.0, vx), law.forces(fz, kappa, -alpha, 0.0, vx)
    assert minus.fy == pytest.approx(-plus.fy, rel=1e-12, abs=1e-9)
    assert minus.mz == pytest.approx(-plus.mz, rel=1e-12, abs=1e-9)
    assert minus.fx == pytest.approx(plus.fx, rel=1e-12, abs=1e-9)


@pytest.mark.parametrize("name", PRACTICAL_SLIP)
@SETTINGS
@given(fz=positive_loads, kappa=slip_ratios, alpha=slip_angles, vx=speeds)
def test_longitudinal_force_odd_in_slip_ratio(name, fz, kappa, alpha, vx):
    law = LAWS[name]
    plus, minus = law.forces(fz, kappa, alpha, 0.0, vx), law.forces(fz, -kappa, alpha, 0.0, vx)
    assert minus.fx == pytest.approx(-plus.fx, rel=1e-12, abs=1e-9)


THEORETICAL_SLIP = {"brush": LAWS["brush"], "brush_sliding": LAWS["brush_sliding"],
                    # without the speed-dependent friction, which depends on the practical slip
                    "dugoff": DugoffTire(cornering_stiffness=70000.0, slip_stiffness=100000.0, mu=0.95)}


@pytest.mark.parametrize("name", list(THEORETICAL_SLIP))
@SETTINGS
@given(fz=positive_loads, kappa=st.floats(-0.45, 5.0), vx=speeds)
def test_longitudinal_force_odd_in_theoretical_slip(name, fz, kappa, vx):
    # kappa' = -kappa / (1 + 2 kappa) has the opposite theoretical slip: kappa'/(1+kappa') = -kappa/(1+kappa)
    law = THEORETICAL_SLIP[name]
    mirrored = -kappa / (1.0 + 2.0 * kappa)
    plus, minus = law.forces(fz, kappa, 0.0, 0.0, vx), law.forces(fz, mirrored, 0.0, 0.0, vx)
    assert minus.fx == pytest.approx(-plus.fx, rel=1e-9, abs=1e-8)


@pytest.mark.parametrize("name", list(LAWS))
@SETTINGS
@given(fz=loads, kappa=slip_ratios, alpha=slip_angles, gamma=cambers, vx=speeds)
def test_scalar_and_array_calls_agree(name, fz, kappa, alpha, gamma, vx):
    law = LAWS[name]
    scalar = law.forces(fz, kappa, alpha, gamma, vx)
    array = law.forces(np.array([fz, fz]), np.array([kappa, kappa]), alpha, gamma, np.array([vx, 1.0]))
    assert all(isinstance(v, float) for v in scalar)
    for s, a in zip(scalar, array):
        assert a.shape == (2,)
        assert a[0] == pytest.approx(s, rel=1e-12, abs=1e-9)


@pytest.mark.parametrize("name", list(LAWS))
@SETTINGS
@given(fz=loads, kappa=slip_ratios, alpha=slip_angles, gamma=cambers, vx=speeds)
def test_finite_for_finite_inputs(name, fz, kappa, alpha, gamma, vx):
    out = LAWS[name].forces(np.array([fz, 0.0]), np.array([kappa, kappa]), alpha, gamma, np.array([vx, 0.0]))
    for value in out:
        assert np.all(np.isfinite(value))


@pytest.mark.parametrize("name", list(LAWS))
def test_broadcasting_shapes(name):
    out = LAWS[name].forces(np.array([[2000.0], [4000.0]]), np.linspace(-0.2, 0.2, 5), 0.05)
    assert all(v.shape == (2, 5) for v in out)
