"""Analysis on top of the model contract: modal analysis, frequency response, work-precision."""

from .modal import Modes, SecondOrderModes, modal_analysis, state_space_modes

__all__ = ["Modes", "SecondOrderModes", "modal_analysis", "state_space_modes"]
