"""One constructor convention for the ride models, as for the handling models.

``Model(vehicle, ...)`` builds from a :class:`vehdyn.Vehicle` (or the model's parameter set), and
``Model.from_parameters(...)`` from a textbook's numbers. The two routes give the same matrices;
a wrong first argument, or the numbers given the old way (``QuarterCar(sprung_mass=...)``), is a
ParameterError that says to call ``from_parameters``.
"""

import inspect

import numpy as np
import pytest

import vehdyn
from vehdyn.ride import BouncePitch, BouncePitchParameters, FullCar, FullCarParameters, QuarterCar, QuarterCarParameters

SEDAN = vehdyn.load_vehicle("sedan")

#: (model class, its parameter set, keyword options of the vehicle route)
MODELS = [
    (QuarterCar, QuarterCarParameters, {"axle": "front"}),
    (QuarterCar, QuarterCarParameters, {"axle": "rear", "actuator": True}),
    (BouncePitch, BouncePitchParameters, {}),
    (BouncePitch, BouncePitchParameters, {"unsprung": False, "actuators": True}),
    (FullCar, FullCarParameters, {}),
    (FullCar, FullCarParameters, {"cg_heights": True, "actuators": True}),
]


def _flag(model):
    return {"actuator" if isinstance(model, QuarterCar) else "actuators": model.has_actuators}


@pytest.mark.parametrize("cls,params,options", MODELS)
def test_the_vehicle_and_the_numbers_give_the_same_model(cls, params, options):
    """Round trip: the numbers the vehicle route found, given to from_parameters, give the same
    matrices (bitwise: the same floats through the same assembly), as does the parameter set."""
    from_vehicle = cls(SEDAN, **options)
    assert isinstance(from_vehicle.parameters, params)
    assert SEDAN.name in from_vehicle.name  # quarter_car_sedan_front, bounce_pitch_sedan, full_car_sedan
    numbers = cls.from_parameters(**from_vehicle.parameters.to_dict(), **_flag(from_vehicle))
    as_set = cls(from_vehicle.parameters, **_flag(from_vehicle))
    for other in (numbers, as_set):
        for matrix in "ABCD":
            np.testing.assert_array_equal(getattr(other, matrix), getattr(from_vehicle, matrix))
        assert other.parameters == from_vehicle.parameters
        assert other.state_names == from_vehicle.state_names and other.input_names == from_vehicle.input_names
    assert numbers.name == cls.from_parameters(**from_vehicle.parameters.to_dict()).name  # the default name


def test_quarter_car_from_a_vehicle_is_one_corner():
    """The corner's numbers from the vehicle file: half the axle's static share of the sprung mass
    (moment balance about the other axle), half the axle's unsprung mass, the corner's rates."""
    g, m = SEDAN.geometry, SEDAN.mass
    for axle, other in (("front", g.sprung_cg_to_rear_axle), ("rear", g.sprung_cg_to_front_axle)):
        p = QuarterCar(SEDAN, axle).parameters
        assert p.sprung_mass == pytest.approx(0.5 * m.sprung_mass * other / g.wheelbase, rel=1e-15)
        assert p.unsprung_mass == 0.5 * getattr(m, f"{axle}_unsprung_mass")
        assert p.spring_rate == getattr(SEDAN.suspension, f"{axle}_spring_rate")
        assert p.tire_stiffness == SEDAN.tires.vertical_stiffness


@pytest.mark.parametrize("cls", [QuarterCar, BouncePitch, FullCar])
def test_there_is_one_way_to_build_from_a_vehicle(cls):
    assert not hasattr(cls, "from_vehicle")
    assert list(inspect.signature(cls).parameters)[0] == "vehicle"


@pytest.mark.parametrize("cls", [QuarterCar, BouncePitch, FullCar])
@pytest.mark.parametrize("bad", [250.0, None, "sedan", {"sprung_mass": 250.0}],
                         ids=["number", "None", "name", "dict"])
def test_a_wrong_first_argument_says_how_to_call_the_model(cls, bad):
    with pytest.raises(vehdyn.ParameterError) as err:
        cls(bad)
    assert err.value.key == "vehicle" and err.value.value is bad
    message = str(err.value)
    assert f"{cls.__name__}.from_parameters(" in message and "Vehicle" in message
    if isinstance(bad, dict):
        assert f"{cls.__name__}.from_parameters(**parameters)" in message


@pytest.mark.parametrize("cls,numbers", [
    (QuarterCar, dict(sprung_mass=250.0, unsprung_mass=35.0, spring_rate=16e3, tire_stiffness=160e3)),
    (BouncePitch, dict(mass=1600.0, pitch_inertia=1444.0, a=1.3, b=1.6, front_spring_rate=38e3,
                       rear_spring_rate=34e3)),
])
def test_the_numbers_given_the_old_way_say_how_to_call_the_model(cls, numbers):
    """``QuarterCar(sprung_mass=...)`` was the old way: a ParameterError (not a TypeError) naming the
    first number and ``from_parameters``; the same numbers through from_parameters build the model."""
    with pytest.raises(vehdyn.ParameterError) as err:
        cls(**numbers)
    first = next(iter(numbers))
    assert err.value.key == first and err.value.value == numbers[first]
    assert f"{cls.__name__}.from_parameters(" in str(err.value)
    built = cls.from_parameters(**numbers).parameters.to_dict()
    assert {key: built[key] for key in numbers} == numbers


def test_numbers_given_positionally_say_how_to_call_the_model():
    with pytest.raises(vehdyn.ParameterError, match=r"QuarterCar\.from_parameters\(") as err:
        QuarterCar(250.0, 35.0, 16e3, 160e3)
    assert err.value.key == "vehicle"
    with pytest.raises(vehdyn.ParameterError, match=r"FullCar\.from_parameters\("):
        FullCar(SEDAN, True)  # the options are keywords


def test_from_parameters_names_a_missing_or_unknown_number():
    with pytest.raises(vehdyn.ParameterError) as err:
        BouncePitch.from_parameters(mass=1600.0)
    assert err.value.key == "pitch_inertia" and "missing" in str(err.value)
    with pytest.raises(vehdyn.ParameterError) as err:
        FullCar.from_parameters(**FullCar(SEDAN).parameters.to_dict(), front_toe=0.1)
    assert err.value.key == "front_toe"
    with pytest.raises(vehdyn.ParameterError) as err:
        QuarterCar.from_parameters(sprung_mass=250.0, unsprung_mass=35.0, spring_rate=-1.0, tire_stiffness=1e5)
    assert err.value.key == "spring_rate"


def test_the_axle_is_checked_and_replace_keeps_the_name():
    with pytest.raises(vehdyn.ParameterError) as err:
        QuarterCar(SEDAN, "middle")
    assert err.value.key == "axle"
    qc = QuarterCar(SEDAN, "rear")
    softer = qc.replace(damping=0.5 * qc.parameters.damping)
    assert softer.name == qc.name == "quarter_car_sedan_rear"
    assert softer.parameters.damping == 0.5 * qc.parameters.damping
    with pytest.raises(vehdyn.ParameterError) as err:
        qc.replace(dampnig=1.0)
    assert err.value.key == "dampnig"
