"""Measured tire data -> tire model: Magic Formula (staged), brush and linear fits.

:func:`fit_magic_formula` fits MF 5.2/6.1/6.2 stage by stage (:mod:`.stages` holds which stage owns
which coefficient) with the Magic Formula's validity conditions enforced on a grid spanning the
data (:mod:`.validity`), the combinations the data leave open held at the start values, and each
measured condition left out in turn to estimate the error between them (:mod:`.cross_validation`);
it returns a :class:`TireFit`. :func:`fit_brush` and :func:`fit_linear` fit the simple laws;
:func:`check_validity` checks any Magic Formula on any grid. scipy, pandas and matplotlib are
imported on use.
"""

from vehdyn.tire.fitting.magic_formula_fit import DEFAULT_BOUNDS, fit_magic_formula
from vehdyn.tire.fitting.result import StageResult, TireFit
from vehdyn.tire.fitting.simple_fits import fit_brush, fit_linear
from vehdyn.tire.fitting.stages import STAGE_NAMES, STAGES, owned
from vehdyn.tire.fitting.synthetic import sample_tire
from vehdyn.tire.fitting.validity import CONDITIONS, ValidityGrid, check_validity

__all__ = ["fit_magic_formula", "fit_brush", "fit_linear", "sample_tire", "TireFit", "StageResult", "STAGES",
           "STAGE_NAMES", "owned", "DEFAULT_BOUNDS", "check_validity", "ValidityGrid", "CONDITIONS"]
