"""Shared helpers of the tire tests."""

from __future__ import annotations

import functools

from hypothesis import strategies as st

import vehdyn
from vehdyn.tire import MagicFormula


@functools.cache
def shipped_tire(name: str) -> MagicFormula:
    """A shipped .tir file's MagicFormula (built once per test session)."""
    return MagicFormula.from_tir(vehdyn.data_path("tires", name + ".tir"))


def mf_domain(name):
    """Strategy for one operating point (fz, kappa, alpha, gamma, vx, phit) in the documented
    domain of MagicFormula with limits on, for the shipped file ``name``."""
    c = shipped_tire(name)._c
    return st.tuples(
        st.one_of(st.just(0.0), st.floats(0.0, 1.5 * c.FZMAX)),  # fz
        st.one_of(st.just(0.0), st.just(-1.0), st.floats(-2.0, 2.0)),  # kappa
        st.one_of(st.just(0.0), st.floats(-1.5, 1.5)),  # alpha
        st.one_of(st.just(0.0), st.floats(-0.4, 0.4)),  # gamma
        st.one_of(st.just(0.0), st.floats(-2 * c.VXLOW, 2 * c.VXLOW), st.floats(-60.0, 60.0)),  # vx
        st.one_of(st.just(0.0), st.floats(-0.5, 0.5)),  # phit
    )
