"""Analysis on top of the model contract: modal analysis, frequency response, work-precision."""

from .modal import Modes, SecondOrderModes, modal_analysis, state_space_modes
from .work_precision import DEFAULT_TOLERANCES, work_precision

__all__ = ["Modes", "SecondOrderModes", "modal_analysis", "state_space_modes", "work_precision", "DEFAULT_TOLERANCES"]
