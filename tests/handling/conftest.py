"""Shared fixtures of the handling tests: the reference cases copied into tests/data."""

import json
from pathlib import Path

import numpy as np
import pytest

_CASES = Path(__file__).resolve().parent.parent / "data" / "handling_reference_cases.json"


def _load():
    with _CASES.open(encoding="utf-8") as fh:
        return {c["id"]: c for c in json.load(fh)["cases"]}


@pytest.fixture(scope="session")
def reference_case():
    """``reference_case("A-SS-ABE")`` -> the case dict (inputs/expected as [value, unit, ...])."""
    cases = _load()
    return cases.__getitem__


@pytest.fixture(scope="session")
def case_bicycle():
    """``case_bicycle(case, speed)`` -> LinearBicycle from a case's m, Iz, lf, lr, Cf_axle, Cr_axle."""
    from vehdyn.handling import LinearBicycle

    def build(case, speed=20.0, yaw_inertia=None):
        i = {k: v[0] for k, v in case["inputs"].items()}
        iz = i["Iz"] if yaw_inertia is None else yaw_inertia
        return LinearBicycle.from_parameters(mass=i["m"], yaw_inertia=iz, a=i["lf"], b=i["lr"],
                                             front_cornering_stiffness=i["Cf_axle"],
                                             rear_cornering_stiffness=i["Cr_axle"], speed=speed)

    return build


def printed_rounding(value: float) -> float:
    """Relative rounding error of a number printed with the digits of its shortest repr."""
    if value == 0:
        return 0.0
    mantissa = repr(float(value)).lower().split("e")[0].lstrip("-").replace(".", "").lstrip("0")
    digits = max(len(mantissa), 1)
    return 0.5 * 10.0 ** (np.floor(np.log10(abs(value))) - digits + 1) / abs(value)


@pytest.fixture(scope="session")
def approx_case():
    """``approx_case(expected_entry, abs_tol=None)``: pytest.approx with the case's tolerance.

    The tolerance is the case's relative tolerance or the rounding of its printed digits, whichever
    is larger (a few cases print 6-7 digits but state 1e-9).
    """

    def build(expected, abs_tol=None, rel=None):
        value, _unit, case_rel = expected[:3]
        tol = max(case_rel, 1.01 * printed_rounding(value)) if rel is None else rel
        if value == 0 and abs_tol is None:
            abs_tol = 1e-12
        return pytest.approx(value, rel=tol, abs=abs_tol)

    return build
