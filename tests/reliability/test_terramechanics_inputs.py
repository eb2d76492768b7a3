"""Terramechanics: solver settings that cannot produce the answer are refused or say so in the status,
bad numbers get a ParameterError naming the argument and the value, memory stays bounded.

Independent references: the wheel's own vertical equilibrium read back through
:meth:`RigidWheel.supported_load` (the load the soil carries at the solved sinkage, no root find),
and the same points solved in one piece and in chunks.
"""

import numpy as np
import pytest

from vehdyn import ParameterError
from vehdyn.tire.terramechanics import FlexibleWheel, RigidWheel, SoftSoilTire, SoftSoilTireGeometry, load_soil
from vehdyn.tire.terramechanics import wong_reece


@pytest.fixture(scope="module")
def wheel():
    return RigidWheel(radius=0.3, width=0.2, soil=load_soil("dry_sand"))


def _refused(call, key, value_text):
    with pytest.raises(ParameterError) as info:
        call()
    message = str(info.value)
    assert info.value.key == key, message
    assert key.split(".")[-1] in message and value_text in message, message
    return info.value


# ---------------------------------------------------------------------------- solver settings
@pytest.mark.parametrize("value, text", [(0, "0"), (-1, "-1"), (2.5, "2.5"), (float("nan"), "nan"), ("10", "'10'")])
def test_iterations_that_cannot_iterate_are_refused(wheel, value, text):
    """max_iterations=0 returned status "ok" with zero sinkage: no iteration was made at all."""
    _refused(lambda: wheel.solve(1500.0, 0.2, max_iterations=value), "max_iterations", text)


def test_too_few_iterations_say_unconverged_and_enough_meet_the_equilibrium(wheel):
    """One Illinois iteration cannot meet the vertical equilibrium: the status says so; the default
    meets it, read back by the stress integral at the solved sinkage (no root find)."""
    loads = np.array([500.0, 1500.0, 3000.0])
    rough = wheel.solve(loads, 0.2, max_iterations=1)
    assert list(rough.status) == ["unconverged"] * 3
    assert not rough.converged.any()
    solved = wheel.solve(loads, 0.2)
    assert list(solved.status) == ["ok"] * 3 and solved.converged.all()
    carried = wheel.supported_load(solved.sinkage, 0.2)
    np.testing.assert_allclose(carried, loads, rtol=1e-9)
    assert np.max(np.abs(wheel.supported_load(rough.sinkage, 0.2) / loads - 1.0)) > 1e-3
    assert list(wheel.solve([1e7, 1000.0], 0.2, max_iterations=1).status) == ["stuck", "unconverged"]


@pytest.mark.parametrize("value, text", [(0, "0"), (-3, "-3"), (1.5, "1.5"), (10**7, "10000000"), (True, "True")])
def test_quadrature_nodes_are_checked(wheel, value, text):
    """nodes=10**7 tried to allocate 728 TiB; 0 and 1.5 raised numpy's own errors."""
    _refused(lambda: wheel.solve(1500.0, 0.2, nodes=value), "nodes", text)


@pytest.mark.parametrize("value, text", [(0, "0"), (-1, "-1"), (float("nan"), "nan"), (2.0, "2.0"), ("a", "'a'")])
def test_tolerance_is_checked(wheel, value, text):
    """rtol <= 0, NaN or 2 were taken as they came (a NaN tolerance never converges, 2 accepts anything)."""
    _refused(lambda: wheel.solve(1500.0, 0.2, rtol=value), "rtol", text)


def test_flexible_wheel_checks_its_nodes_and_reports_the_elastic_mode_converged():
    tire = FlexibleWheel(geometry=SoftSoilTireGeometry(radius=0.35, width=0.25, inflation_pressure=50e3),
                         soil=load_soil("dry_sand"))
    _refused(lambda: tire.solve(1500.0, 0.2, nodes=0), "nodes", "0")
    result = tire.solve(np.array([200.0, 1500.0, 6000.0]), 0.2)
    assert list(result.mode) == ["rigid", "elastic", "elastic"]  # soft enough to flatten under load
    assert result.converged.all() and list(result.status) == ["ok"] * 3
    rigid = tire.rigid_wheel.solve(200.0, 0.2)
    assert float(result.sinkage[0]) == float(rigid.sinkage)  # the rigid mode is the rigid wheel's


def test_many_points_are_solved_in_chunks_with_the_same_numbers(wheel, monkeypatch):
    """The stress arrays are (points x nodes): a large request is split so that memory stays bounded.
    The split must not change a number (each point's iteration is its own)."""
    loads = np.linspace(200.0, 4000.0, 37)
    slips = np.linspace(-0.5, 0.8, 37)
    whole = wheel.solve(loads, slips, 0.05)
    monkeypatch.setattr(wong_reece, "_CHUNK_VALUES", 5 * 2 * wong_reece.QUADRATURE_NODES)  # 5 points a chunk
    pieces = wheel.solve(loads, slips, 0.05)
    for name in ("sinkage", "drawbar_pull", "torque", "lateral_force", "entry_angle"):
        np.testing.assert_array_equal(getattr(pieces, name), getattr(whole, name), err_msg=name)
    assert list(pieces.status) == list(whole.status)


# ---------------------------------------------------------------------------- numbers
@pytest.mark.parametrize("value, text", [("1000", "'1000'"), (True, "True"), (None, "None"), ([1.0, "a"], "'a'")])
def test_loads_that_are_not_numbers_are_refused(wheel, value, text):
    """A string load of "1000" was read as 1000 N."""
    _refused(lambda: wheel.solve(value, 0.2), "load", text)


def test_numpy_scalars_are_numbers():
    """np.float32 radii were refused as 'not a number'; they give the wheel of the same float."""
    soil = load_soil("dry_sand")
    single = RigidWheel(radius=np.float32(0.3), width=np.float64(0.2), soil=soil)
    plain = RigidWheel(radius=float(np.float32(0.3)), width=0.2, soil=soil)
    assert type(single.radius) is float and single.radius == plain.radius
    a, b = single.solve(np.float32(1500.0), np.float32(0.2)), plain.solve(1500.0, float(np.float32(0.2)))
    assert float(a.sinkage) == float(b.sinkage)


def test_soft_soil_tire_names_an_unknown_wheel_option():
    """An unknown option raised FlexibleWheel.__init__'s TypeError."""
    geometry = SoftSoilTireGeometry(radius=0.35, width=0.25, inflation_pressure=150e3)
    _refused(lambda: SoftSoilTire(geometry, load_soil("dry_sand"), max_iterations=0), "max_iterations", "0")
    error = _refused(lambda: SoftSoilTire(geometry, load_soil("dry_sand"), bogus=1), "bogus", "1")
    assert "c1" in str(error) and "rebound" in str(error)


def test_the_adaptive_reference_names_a_load_the_soil_cannot_carry(wheel):
    """brentq's 'f(a) and f(b) must have different signs' for a wheel that sinks to its axle; the
    solver calls the same load stuck."""
    from vehdyn.tire.terramechanics.reference import adaptive_solve

    assert wheel.solve(1e7, 0.2).status == "stuck"
    _refused(lambda: adaptive_solve(wheel, 1e7, 0.2), "load", "10000000.0")
    _refused(lambda: adaptive_solve(wheel, 1500.0, 0.2, epsrel=0.0), "epsrel", "0.0")
