"""check_validity: the Magic Formula's validity conditions on a grid spanning the data.

Each condition is checked against an independent reading of the same property from the model:
the friction coefficients, stiffnesses and trail of MagicFormula.evaluate, the forces' sign, and
E <= 1 through the forces with and without the model's E <= 1 clamp (limits=True / False).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from vehdyn.errors import ParameterError, VehdynWarning
from vehdyn.tire import BrushTire, MagicFormula, fit_magic_formula
from vehdyn.tire.fitting import CONDITIONS, ValidityGrid, check_validity
from vehdyn.tire.fitting.synthetic import sample_tire
from vehdyn.tire.fitting.validity import GridStates, trail

from .conftest import shipped_tire

SHIPPED = ("MagicFormula61_Parameters", "MagicFormula62_Parameters", "MagicFormula52_Parameters", "mf_185_80R14")


def _changed(tire, **values):
    """``tire`` with coefficients replaced (the record the evaluation uses)."""
    other = MagicFormula.__new__(MagicFormula)
    other.__dict__.update(tire.__dict__, _c=tire._c._replace(**values))
    return other


def _grid(tire):
    data = sample_tire(tire, slip_angles=np.radians(np.linspace(-15, 15, 13)), slip_ratios=np.linspace(-0.3, 0.3, 13),
                       cambers=np.radians([-3.0, 0.0, 3.0]))
    return ValidityGrid.from_data(data, tire), data


@pytest.mark.parametrize("name", SHIPPED)
def test_shipped_tires_are_valid_on_their_test_program(name):
    tire = shipped_tire(name)
    grid, _ = _grid(tire)
    table = check_validity(tire, grid)
    assert list(table.index) == list(CONDITIONS) and table["ok"].all(), table[~table["ok"]]
    assert (table["violations"] == 0).all() and (table["worst"] <= 0).all()


@pytest.mark.parametrize("name", SHIPPED)
def test_the_trail_written_here_is_the_models(name):
    """The trail's factors are restated for the conditions; built into the trail they give the
    aligning moment's trail of MagicFormula.evaluate at every grid point."""
    tire = shipped_tire(name)
    grid, _ = _grid(tire)
    s = GridStates(tire._c, grid).sweep
    expected = tire.evaluate(s.fz, 0.0, s.alpha, s.gamma, grid.speed).trail
    np.testing.assert_allclose(trail(tire._c, s), expected, rtol=1e-12, atol=1e-15 * np.max(np.abs(expected)))


def _clamped(tire, grid):
    """Forces differ with and without the E <= 1 clamp somewhere on the grid (pure and combined slip)."""
    f, g, a, k = (x.ravel() for x in np.meshgrid(grid.loads, grid.cambers, grid.slip_angles, grid.slip_ratios,
                                                 indexing="ij"))
    on, off = tire.forces(f, k, a, g, grid.speed), tire.forces(f, k, a, g, grid.speed, limits=False)
    return any(not np.allclose(getattr(on, o), getattr(off, o), rtol=1e-12, atol=1e-9) for o in ("fx", "fy", "mz"))


@pytest.mark.parametrize("condition, change", [
    ("Ex <= 1", {"PEX1": 1.2}),
    ("Ey <= 1", {"PEY1": 1.3}),
    ("Et <= 1", {"QEZ1": 1.5}),
    ("Exa <= 1", {"REX1": 1.5}),
    ("Eyk <= 1", {"REY1": 1.5}),
])
def test_curvature_factors_above_one_are_found(condition, change):
    """An E > 1 is what the model clamps: the forces differ with and without the clamp exactly when
    the condition fails."""
    tire = shipped_tire("MagicFormula61_Parameters")
    grid, _ = _grid(tire)
    assert not _clamped(tire, grid)
    broken = _changed(tire, **change)
    table = check_validity(broken, grid)
    assert list(table.index[~table["ok"]]) == [condition]
    assert _clamped(broken, grid)


def test_friction_trail_stiffness_and_weighting_signs_are_found():
    tire = shipped_tire("MagicFormula61_Parameters")
    grid, _ = _grid(tire)
    f, g = (x.ravel() for x in np.meshgrid(grid.loads, grid.cambers, indexing="ij"))
    cases = {
        "Dy > 0": ({"PDY2": -2.5}, lambda t: t.evaluate(f, 0.0, 0.0, g, grid.speed, limits=False).muy),
        "Dx > 0": ({"PDX2": -2.5}, lambda t: t.evaluate(f, 0.0, 0.0, g, grid.speed, limits=False).mux),
        "Kya sign": ({"PKY3": 25.0}, lambda t: -t.evaluate(f, 0.0, 0.0, g, grid.speed, limits=False).kya),
        "Kxk sign": ({"PKX2": -60.0}, lambda t: t.evaluate(f, 0.0, 0.0, g, grid.speed, limits=False).kxk),
        "trail > 0": ({"QDZ1": -0.05}, lambda t: t.evaluate(f, 0.0, 0.0, g, grid.speed, limits=False).trail),
    }
    for condition, (change, independent) in cases.items():
        broken = _changed(tire, **change)
        table = check_validity(broken, grid)
        assert condition in set(table.index[~table["ok"]]), condition
        assert np.any(independent(broken) < 0) and np.all(independent(tire) > 0), condition
        row = table.loc[condition]  # the worst point is a violating one
        at = broken.evaluate(row["fz"], 0.0, 0.0, row["gamma"], grid.speed, limits=False)  # (limits: |mu|)
        value = {"Dy > 0": at.muy, "Dx > 0": at.mux, "Kya sign": -at.kya, "Kxk sign": at.kxk, "trail > 0": at.trail}
        assert value[condition] < 0, condition
    # Gxa < 0: combined-slip Fx of the other sign than the pure-slip Fx at large slip angles
    broken = _changed(tire, RCX1=2.6)
    assert "Gxa > 0" in set(check_validity(broken, grid).index[~check_validity(broken, grid)["ok"]])
    combined = broken.forces(tire.nominal_load, 0.2, math.radians(15.0)).fx
    assert combined * broken.forces(tire.nominal_load, 0.2, 0.0).fx < 0
    assert "Cx > 0" in set(check_validity(_changed(tire, PCX1=-1.0), grid).query("not ok").index)


def test_grid_spans_the_data():
    tire = shipped_tire("MagicFormula61_Parameters")
    grid, data = _grid(tire)
    assert grid.loads.min() == data["fz"].min() and grid.loads.max() == data["fz"].max() and grid.loads.size == 9
    assert grid.cambers.min() == pytest.approx(math.radians(-3.0)) and 0.0 in grid.cambers
    assert grid.slip_angles.max() == pytest.approx(math.radians(15.0)) and 0.0 in grid.slip_angles
    assert grid.pressures.tolist() == [tire._c.INFLPRES] and grid.speed == pytest.approx(data["vx"].iloc[0])
    assert grid.points() == grid.loads.size * grid.cambers.size
    with pytest.raises(ParameterError, match="needs the data's loads"):
        ValidityGrid.from_data({"alpha": [0.1]})


def test_bad_arguments():
    tire = shipped_tire("MagicFormula61_Parameters")
    with pytest.raises(ParameterError, match="needs a MagicFormula, got BrushTire"):
        check_validity(BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0), data={"fz": [1.0]})
    with pytest.raises(ParameterError, match="needs a grid or the data"):
        check_validity(tire)


def test_the_penalties_keep_a_noisy_fit_valid():
    """MF 5.2 tire, 3 % noise: without the penalties the fitted curvature factor of Fy exceeds 1
    between the measured conditions (the forces differ with and without the model's E <= 1 clamp);
    with them every condition holds, by the same independent check."""
    from .test_tire_fitting_between import valid_everywhere

    truth = shipped_tire("MagicFormula52_Parameters")
    data = sample_tire(truth, slip_angles=np.radians(np.linspace(-15, 15, 13)), slip_ratios=np.linspace(-0.3, 0.3, 13),
                       cambers=np.radians([-3.0, 0.0, 3.0]), combined_angles=[], noise=0.03, seed=2)
    fits = {}
    for validity in (False, True):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", VehdynWarning)
            fits[validity] = fit_magic_formula(data, version="5.2", stages=("pure_longitudinal", "pure_lateral"),
                                               cross_validation=False, validity=validity)
    assert "Ey <= 1" in set(fits[False].violations.index)
    assert any("E <= 1" in text for text in valid_everywhere(fits[False].tire, data))
    assert len(fits[True].violations) == 0 and valid_everywhere(fits[True].tire, data) == []
