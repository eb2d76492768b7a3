"""FullVehicle.trim(..., backend="compiled"): the residuals from the car's compiled code give the operating
point of the numpy residuals, to the rounding of the two codes (the same equations, compiled math against
numpy's), for straight running, a steady turn, a turn of given radius and quasi-steady braking; the result is
a steady state of the numpy equations; bad input names backend."""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.full_vehicle import FullVehicle

pytest.importorskip("numba")

CAR = FullVehicle(vehdyn.load_vehicle("sedan"))
CASES = ({}, {"lateral_acceleration": 4.0}, {"radius": -60.0}, {"longitudinal_acceleration": -3.0})


@pytest.mark.parametrize("case", CASES, ids=["straight", "turn", "radius", "braking"])
def test_compiled_residuals_give_the_numpy_operating_point(case):
    x_numpy, u_numpy = CAR.trim(20.0, **case)
    x_compiled, u_compiled = CAR.trim(20.0, backend="compiled", **case)
    # the solver stops at a relative derivative of 1e-9; the two codes differ by ulps: measured 3e-14
    assert np.max(np.abs(x_compiled - x_numpy) / (np.abs(x_numpy) + 1e-3)) < 1e-10
    assert np.max(np.abs(u_compiled - u_numpy) / (np.abs(u_numpy) + 1e-6)) < 1e-10
    # and the body's attitude is steady by the numpy equations (braking: the velocities fall with the speed)
    d = CAR.rhs(0.0, x_compiled, u_compiled)
    steady = [CAR.index(name) for name in ("roll_angle", "pitch_angle", "roll_rate", "pitch_rate")]
    assert np.max(np.abs(d[steady])) < 1e-9


@pytest.mark.parametrize("backend", ["fast", "", None, 1, "NUMPY"])
def test_a_bad_backend_is_named(backend):
    with pytest.raises(ParameterError) as error:
        CAR.trim(20.0, backend=backend)
    assert error.value.key == "backend"


def test_compiled_refuses_a_car_without_compiled_code():
    """A road friction given as a Python function has no compiled form: the model's own error, naming it."""
    car = FullVehicle(vehdyn.load_vehicle("sedan"), friction=lambda X, Y: np.ones_like(np.asarray(X)))
    with pytest.raises(ParameterError) as error:
        car.trim(20.0, backend="compiled")
    assert error.value.key == "friction"
    car.trim(20.0)  # numpy trims it


def test_compiled_without_numba_is_named(monkeypatch):
    """Without numba installed, "compiled" names backend (not an ImportError from deep inside)."""
    from vehdyn.simulation import compiled

    monkeypatch.setattr(compiled, "_NUMBA_AVAILABLE", False)
    with pytest.raises(ParameterError) as error:
        CAR.trim(20.0, backend="compiled")
    assert error.value.key == "backend"
    assert "numba" in str(error.value)
