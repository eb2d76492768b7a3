"""Shared helpers for the ride tests: the reference cases copied to tests/data (see its source note)."""

import json
from pathlib import Path

import pytest

_DATA = Path(__file__).resolve().parent.parent / "data" / "ride_reference_cases.json"


def load_case(case_id: str) -> dict:
    for case in json.loads(_DATA.read_text()):
        if case["id"] == case_id:
            return case
    raise KeyError(case_id)


@pytest.fixture
def case():
    return load_case


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
