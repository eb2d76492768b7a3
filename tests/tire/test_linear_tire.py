"""Linear tire: forces proportional to slip (and load), ISO-W signs."""

import numpy as np
import pytest

from vehdyn import ParameterError
from vehdyn.tire import LinearTire


def test_forces_are_linear_in_slip():
    tire = LinearTire(cornering_stiffness=80000.0, slip_stiffness=120000.0, pneumatic_trail=0.03)
    kappa = np.array([-0.02, 0.0, 0.01])
    alpha = np.array([0.01, -0.03, 0.0])
    out = tire.forces(3000.0, kappa, alpha)
    np.testing.assert_allclose(out.fx, 120000.0 * kappa, rtol=1e-15)
    np.testing.assert_allclose(out.fy, -80000.0 * alpha, rtol=1e-15)  # alpha > 0 -> F_y < 0 (ISO-W)
    np.testing.assert_allclose(out.mz, 0.03 * 80000.0 * alpha, rtol=1e-15)  # self-aligning
    np.testing.assert_array_equal(out.mx, 0.0)


def test_slip_stiffness_defaults_to_cornering_stiffness():
    tire = LinearTire(cornering_stiffness=50000.0)
    assert tire.forces(2000.0, 0.01, 0.0).fx == pytest.approx(500.0, rel=1e-15)


def test_load_scaling_keeps_the_cornering_coefficient():
    tire = LinearTire(cornering_stiffness=60000.0, nominal_load=4000.0)
    fz = np.array([0.0, 2000.0, 4000.0, 8000.0])
    np.testing.assert_allclose(tire.forces(fz, 0.0, 0.01).fy / 0.01, -60000.0 * fz / 4000.0, rtol=1e-14)


def test_camber_stiffness_adds_camber_thrust():
    tire = LinearTire(cornering_stiffness=60000.0, camber_stiffness=-3000.0)
    assert tire.forces(4000.0, 0.0, 0.01, 0.02).fy == pytest.approx(-600.0 - 60.0, rel=1e-14)


def test_lift_off_gives_no_force():
    tire = LinearTire(cornering_stiffness=60000.0)
    out = tire.forces(np.array([-5.0, 0.0, 1.0]), 0.1, 0.1)
    np.testing.assert_array_equal(out.fy[:2], 0.0)
    np.testing.assert_array_equal(out.fz, [0.0, 0.0, 1.0])
    assert tire.forces(-5.0, 0.1, 0.1).fy == 0.0


def test_reverse_flips_fx_and_mz():
    tire = LinearTire(cornering_stiffness=60000.0, pneumatic_trail=0.02)
    f, r = tire.forces(4000.0, 0.01, 0.02, vx=3.0), tire.forces(4000.0, 0.01, 0.02, vx=-3.0)
    assert (r.fx, r.fy, r.mz) == pytest.approx((-f.fx, f.fy, -f.mz), rel=1e-15)


@pytest.mark.parametrize("field, value", [("cornering_stiffness", 0.0), ("slip_stiffness", -1.0),
                                          ("pneumatic_trail", -0.01), ("nominal_load", 0.0),
                                          ("camber_stiffness", float("nan"))])
def test_bad_parameters_raise(field, value):
    kwargs = dict(cornering_stiffness=60000.0)
    kwargs[field] = value
    with pytest.raises(ParameterError) as info:
        LinearTire(**kwargs)
    assert info.value.key == field
