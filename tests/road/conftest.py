"""Shared fixtures of the road tests: the ride reference cases (tests/data, see its source note) hold
the road cases too."""

import json
from pathlib import Path

import pytest

_DATA = Path(__file__).resolve().parent.parent / "data" / "ride_reference_cases.json"


@pytest.fixture(scope="session")
def cases():
    """All ride and road reference cases by id."""
    return {c["id"]: c for c in json.loads(_DATA.read_text())}
