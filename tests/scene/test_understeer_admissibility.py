"""The ladder never picks a rung that drops a term of the vehicle's understeer budget: each term a
rung does not carry (roll steer, camber thrust, compliance steer) makes it inadmissible, with the
field and value named in the reason."""

import pytest

import vehdyn
from vehdyn.scene.standard import standard_scenes

# what each handling rung carries (vehdyn.scene.registry: refuse_dropped_terms in each builder)
CARRIES = {
    "SteadyState": {"compliance_steer"},
    "LinearBicycle": {"compliance_steer"},
    "LinearBicycle+lag": {"compliance_steer"},
    "LateralYawRoll": {"roll_steer", "compliance_steer"},
    "LateralYawRoll+lag": {"roll_steer", "compliance_steer"},
    "SingleTrack(linear tires)": {"compliance_steer"},
    "SingleTrack": {"compliance_steer"},
    "SingleTrack+LLT": {"roll_steer", "camber_thrust", "compliance_steer"},
    "SingleTrack+roll": {"roll_steer", "camber_thrust", "compliance_steer"},
    "FullVehicle": {"roll_steer", "camber_thrust", "compliance_steer"},
    "FullVehicle(linearized)": {"roll_steer", "camber_thrust", "compliance_steer"},
}
TERMS = {
    "roll_steer": ("suspension.front_roll_steer", {"suspension__front_roll_steer": 0.05}),
    "camber_thrust": ("suspension.front_camber_gain", {"suspension__front_camber_gain": 0.5}),
    "compliance_steer": ("suspension.rear_lateral_force_compliance_steer",
                         {"suspension__rear_lateral_force_compliance_steer": 5e-7}),
}


@pytest.mark.parametrize("term", list(TERMS))
def test_a_rung_that_drops_a_term_is_not_admissible(term):
    field, change = TERMS[term]
    vehicle = vehdyn.load_vehicle("sedan").replace(**change)
    scene = standard_scenes("sedan")["lane_change_60"].replace(vehicle=vehicle)
    plan = vehdyn.plan(scene)
    rows = {r.rung.name: r for r in plan.rows}
    for name, carries in CARRIES.items():
        row = rows[name]
        if term in carries:
            assert row.reason is None or field not in str(row.reason), name
        else:
            assert not row.admissible, name
            assert field in row.reason and "understeer budget" in row.reason, (name, row.reason)
    assert term in CARRIES[plan.chosen.rung.name]


def test_the_shipped_sedan_is_refused_by_no_rung_for_a_term():
    plan = vehdyn.plan(standard_scenes("sedan")["lane_change_60"])
    assert not any("understeer budget" in str(r.reason) for r in plan.rows)


def test_full_vehicle_carries_compliance_steer():
    """Once refused by name, now carried (tests/full_vehicle/test_compliance_steer.py measures it)."""
    from vehdyn.full_vehicle import FullVehicle

    vehicle = vehdyn.load_vehicle("sedan").replace(suspension__front_aligning_moment_compliance_steer=2e-5)
    assert "compliance_steer_angle_front_left" in FullVehicle(vehicle).output_names
