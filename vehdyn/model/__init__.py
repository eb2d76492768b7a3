"""The model contract: :class:`Model` (named states, inputs and outputs, ``rhs(t, x, u)`` and
``output(t, x, u)`` with a trailing batch axis), :class:`LinearModel` (exact matrices, modes,
frequency response, python-control and scipy export) and modal analysis (:class:`Modes`)."""

from vehdyn.model.base import PHENOMENA, Model, float_array, signal_vector
from vehdyn.model.linear import LinearModel
from vehdyn.model.modal import Modes, SecondOrderModes, modal_analysis, state_space_modes

__all__ = ["Model", "LinearModel", "PHENOMENA", "Modes", "SecondOrderModes", "modal_analysis", "state_space_modes",
           "float_array", "signal_vector"]
