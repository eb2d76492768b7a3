"""Car-trailer combinations and the articulated single track: every search range validated, bad
numbers named.

Independent reference: the eigenvalues of the linear combination at a speed (a critical speed is
where the snaking mode's real part changes sign).
"""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.handling import ArticulatedSingleTrack, LinearCarTrailer


@pytest.fixture(scope="module")
def sedan():
    return vehdyn.load_vehicle("sedan")


@pytest.fixture(scope="module")
def caravan():
    return vehdyn.load_trailer("caravan")


@pytest.fixture(scope="module")
def tail_heavy(sedan, caravan):
    """The caravan loaded 3.5 m behind its axle (a negative tongue load): it snakes from 8.6 m/s."""
    return LinearCarTrailer(sedan, caravan.replace(cg_to_axle=-3.5, hitch_to_cg=8.1), speed=20.0)


def _refused(call, key, value_text):
    with pytest.raises(ParameterError) as info:
        call()
    message = str(info.value)
    assert info.value.key == key, message
    assert key.split(".")[-1] in message and value_text in message, message
    return info.value


# ---------------------------------------------------------------------------- critical speed
@pytest.mark.parametrize("value, text", [(-10, "-10"), (0, "0"), (0.4, "0.4"), (float("inf"), "inf"),
                                         (float("nan"), "nan"), ("100", "'100'")])
def test_critical_speed_range_is_validated(sedan, caravan, value, text):
    """max_speed=-10 returned -4.6 m/s (a speed below the scan's start), inf and NaN raised
    LinAlgError from the eigenvalue solver, a string numpy's DTypePromotionError."""
    model = LinearCarTrailer(sedan, caravan, speed=20.0)
    _refused(lambda: model.critical_speed(max_speed=value), "max_speed", text)


@pytest.mark.parametrize("value, text", [(0, "0"), (-1, "-1"), (float("nan"), "nan"), ("a", "'a'")])
def test_critical_speed_tolerance_is_validated(tail_heavy, value, text):
    _refused(lambda: tail_heavy.critical_speed(xtol=value), "xtol", text)


def test_critical_speed_stays_within_its_range(tail_heavy):
    """Below 10.5 m/s the scan ran on to 10.5 m/s whatever max_speed was: with max_speed 8 m/s it
    found the snaking onset at 8.6 m/s. Within its range it finds the speed where the snaking mode's
    real part changes sign (the eigenvalues at either side), as the default range does."""
    onset = tail_heavy.critical_speed()
    assert 8.0 < onset < 9.0
    assert tail_heavy.critical_speed(max_speed=8.0) == np.inf
    assert tail_heavy.snaking_mode(8.0).eigenvalue.real < 0 < tail_heavy.snaking_mode(9.0).eigenvalue.real
    assert tail_heavy.critical_speed(max_speed=9.0) == pytest.approx(onset, abs=1e-8)
    assert tail_heavy.snaking_mode(onset - 1e-6).eigenvalue.real < 0 < tail_heavy.snaking_mode(onset + 1e-6).eigenvalue.real


# ---------------------------------------------------------------------------- articulated single track
@pytest.fixture(scope="module")
def articulated(sedan, caravan):
    return ArticulatedSingleTrack(sedan, caravan)


@pytest.mark.parametrize("value, text", [(0.0, "0.0"), (-5.0, "-5.0"), (float("nan"), "nan"), ("20", "'20'"),
                                         ([10.0, 20.0], "[10.0, 20.0]")])
def test_lateral_yaw_needs_one_forward_speed(articulated, value, text):
    """At 0 m/s (and backwards) the 'lateral-yaw block at straight running' was returned from the
    regularized slip angles, matrices of no model the docstring describes."""
    _refused(lambda: articulated.lateral_yaw(value), "speed", text)


@pytest.mark.parametrize("value, text", [(-1.0, "-1.0"), (0.0, "0.0"), (4.0, "4.0"), (float("nan"), "nan")])
def test_articulation_threshold_is_an_angle(articulated, value, text):
    """A threshold of -1 rad found a 'trailer swing' at t = 0 in straight running."""
    result = vehdyn.simulate(articulated, np.linspace(0.0, 0.2, 5), x0=articulated.straight_running(20.0))
    _refused(lambda: ArticulatedSingleTrack.articulation_event(result, threshold=value), "threshold", text)
    assert ArticulatedSingleTrack.articulation_event(result) is None  # straight running: no event


@pytest.mark.parametrize("result", [None, {"articulation_angle": [0.0, 1.0]}])
def test_articulation_event_needs_a_result(result):
    """None raised "'NoneType' object is not subscriptable"."""
    _refused(lambda: ArticulatedSingleTrack.articulation_event(result), "result", type(result).__name__)
