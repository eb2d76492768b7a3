"""The chassis controllers in a ClosedLoop: they need a vehicle; the ESC loop inside its deadband
linearizes to the car alone. (The loop itself -- names, the block formula, batches, algebraic loops,
missing inputs, nesting -- is tested once, in tests/interconnect/test_closed_loop.py.)"""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.chassis import ABS, ESC
from vehdyn.handling import SingleTrack
from vehdyn.interconnect import ClosedLoop


@pytest.mark.parametrize("controller", [ABS, ESC])
def test_controllers_need_a_vehicle(controller):
    with pytest.raises(ParameterError, match="vehicle must be a vehdyn Vehicle"):
        controller("sedan")


def test_linearized_esc_loop_inside_its_deadband_is_the_car():
    car = vehdyn.load_vehicle("sedan")
    plant = SingleTrack(car)
    loop = ClosedLoop(plant, ESC(car))
    x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(20.0))))
    lin = loop.linearize(x0)
    alone = plant.linearize(plant.straight_running(20.0))
    n = plant.n_states
    assert lin.state_names == loop.state_names and lin.output_names == loop.output_names
    np.testing.assert_allclose(lin.A[:n, :n], alone.A, rtol=1e-5, atol=1e-6)
    # the hydraulic channels are first-order lags of -1 / tau, decoupled from the car at this point
    np.testing.assert_allclose(np.diag(lin.A)[n:], -1.0 / 0.1, rtol=1e-6)
    np.testing.assert_allclose(lin.A[n:, :n], 0.0, atol=1e-9)
