"""Interconnection of models by signal names: :class:`ClosedLoop` (a plant with a controller in
the loop: drivers and chassis controllers alike; :class:`Controller` is their base),
:func:`connect_in_series` (two linear models) and :func:`pade_delay` (a pure delay as a state space)."""

from vehdyn.interconnect.closed_loop import ClosedLoop, Controller
from vehdyn.interconnect.delay import pade_coefficients, pade_delay
from vehdyn.interconnect.series import connect_in_series

__all__ = ["ClosedLoop", "Controller", "connect_in_series", "pade_delay", "pade_coefficients"]
