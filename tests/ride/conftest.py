"""Shared helpers of the ride tests: the reference cases copied to tests/data (see its source note), and
ride models built directly with LinearModel.from_second_order (independent of vehdyn.ride's model classes)."""

import json
from pathlib import Path

import numpy as np
import pytest

import vehdyn

_DATA = Path(__file__).resolve().parent.parent / "data" / "ride_reference_cases.json"


def load_case(case_id: str) -> dict:
    for case in json.loads(_DATA.read_text()):
        if case["id"] == case_id:
            return case
    raise KeyError(case_id)


@pytest.fixture
def case():
    return load_case


@pytest.fixture(scope="session")
def cases():
    """All ride reference cases by id."""
    return {c["id"]: c for c in json.loads(_DATA.read_text())}


def printed_resolution(value: float) -> float:
    """Half a unit in the last printed digit of ``value``, relative (the cases print 7 significant digits)."""
    text = repr(float(value)).lower()
    mantissa, _, exponent = text.partition("e")
    digits = mantissa.replace("-", "").replace(".", "").lstrip("0")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    if mantissa.endswith(".0"):
        return 0.0  # a whole number: exact, keep the case's tolerance
    absolute = 0.5 * 10.0 ** (-decimals + (int(exponent) if exponent else 0))
    return absolute / abs(value) if value and digits else 0.0


def check(actual, expected_entry, label=""):
    """Compare with a reference entry [value, unit, rel_tolerance].

    The tolerance is the case's, or the resolution of the printed value where that is coarser
    (several cases print 7 significant digits with a 1e-9 tolerance).
    """
    value, unit, rtol = expected_entry
    rtol = max(rtol, printed_resolution(value))
    assert actual == pytest.approx(value, rel=rtol), f"{label}: {actual} vs {value} {unit} (rtol {rtol})"


def quarter_car(ms, mu, ks, cs, kt, ct=0.0):
    """Quarter car: states sprung/unsprung displacement and velocity; inputs road displacement and velocity.

    ms zs'' = -ks (zs - zu) - cs (zs' - zu'); mu zu'' = ks (zs - zu) + cs (zs' - zu') - kt (zu - zr) - ct (zu' - zr').
    Outputs: sprung acceleration, suspension travel zs - zu, tire deflection zu - zr, dynamic tire load kt (zr - zu)
    + ct (zr' - zu').
    """
    M = np.diag([ms, mu])
    C = np.array([[cs, -cs], [-cs, cs + ct]])
    K = np.array([[ks, -ks], [-ks, ks + kt]])
    F = np.array([[0.0, 0.0], [kt, ct]])
    acc = -np.linalg.solve(M, np.hstack([K, C]))[0]
    acc_in = np.linalg.solve(M, F)[0]
    Cout = np.array([acc, [1.0, -1.0, 0, 0], [0, 1.0, 0, 0], [0, -kt, 0, -ct]])
    Dout = np.array([acc_in, [0, 0], [-1.0, 0], [kt, ct]])
    return vehdyn.LinearModel.from_second_order(
        M, C, K, F, dof=["sprung_displacement", "unsprung_displacement"],
        inputs=["road_displacement", "road_velocity"],
        outputs=["sprung_acceleration", "suspension_travel", "tire_deflection", "dynamic_tire_load"],
        output_matrix=Cout, feedthrough=Dout, name="quarter car")


def half_car(m=1200.0, iy=1800.0, a=1.2, b=1.5, muf=40.0, mur=40.0, kf=30000.0, kr=32000.0, cf=2500.0, cr=2400.0,
             ktf=200000.0, ktr=200000.0):
    """4-DOF bounce-pitch half car (heave z up, pitch theta nose up), front/rear road displacement inputs.

    Outputs: sprung acceleration at the CG, pitch acceleration, front and rear suspension travel, front and rear
    dynamic tire load.
    """
    # q = [z, theta, zuf, zur]; front suspension deflection z - a theta - zuf, rear z + b theta - zur
    Tf = np.array([1.0, -a, -1.0, 0.0])
    Tr = np.array([1.0, b, 0.0, -1.0])
    K = kf * np.outer(Tf, Tf) + kr * np.outer(Tr, Tr)
    K[2, 2] += ktf
    K[3, 3] += ktr
    C = cf * np.outer(Tf, Tf) + cr * np.outer(Tr, Tr)
    M = np.diag([m, iy, muf, mur])
    F = np.zeros((4, 2))
    F[2, 0], F[3, 1] = ktf, ktr
    Minv = np.linalg.inv(M)
    acc = -Minv @ np.hstack([K, C])
    acc_in = Minv @ F
    Cout = np.vstack([acc[0], acc[1], np.r_[Tf, 0, 0, 0, 0], np.r_[Tr, 0, 0, 0, 0],
                      [0, 0, -ktf, 0, 0, 0, 0, 0], [0, 0, 0, -ktr, 0, 0, 0, 0]])
    Dout = np.vstack([acc_in[0], acc_in[1], [0, 0], [0, 0], [ktf, 0], [0, ktr]])
    return vehdyn.LinearModel.from_second_order(
        M, C, K, F, dof=["sprung_displacement", "pitch_angle", "unsprung_displacement_front",
                         "unsprung_displacement_rear"],
        inputs=["road_displacement_front", "road_displacement_rear"],
        outputs=["sprung_acceleration", "pitch_acceleration", "suspension_travel_front", "suspension_travel_rear",
                 "dynamic_tire_load_front", "dynamic_tire_load_rear"],
        output_matrix=Cout, feedthrough=Dout, name="half car")


@pytest.fixture(scope="session")
def models():
    """Factories ``models.quarter_car(...)`` and ``models.half_car(...)``."""
    from types import SimpleNamespace

    return SimpleNamespace(quarter_car=quarter_car, half_car=half_car)
