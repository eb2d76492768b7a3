"""Analysis on top of the model contract: modal analysis, frequency response, work-precision."""

from vehdyn.analysis.modal import Modes, SecondOrderModes, modal_analysis, state_space_modes
from vehdyn.analysis.work_precision import DEFAULT_TOLERANCES, work_precision

__all__ = ["Modes", "SecondOrderModes", "modal_analysis", "state_space_modes", "work_precision", "DEFAULT_TOLERANCES"]
