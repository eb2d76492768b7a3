"""Road friction for the single-track model: the Magic Formula's friction scaling factors.

A Magic Formula tire is put on a road of another friction by its scaling factors LMUX and LMUY
(Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 4.3.2: "the friction coefficients ...
scaled by lambda_mu, e.g. for a road of lower friction"): the peak forces scale, the slip
stiffnesses stay. The tire stays a :class:`~vehdyn.tire.MagicFormula`, so the compiled
single-track backend still runs it. (The full vehicle has its own ``friction(X, Y)`` callable.)
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError

__all__ = ["road_friction_tire"]


def road_friction_tire(tire, ratio: float):
    """``tire`` (a MagicFormula) with LMUX and LMUY multiplied by ``ratio`` [-].

    Parameters
    ----------
    tire : vehdyn.tire.MagicFormula
    ratio : float
        Road friction relative to the tire's own (> 0): mu_road / mu_tire.

    Returns
    -------
    MagicFormula
        A new tire; ``tire`` is unchanged.
    """
    from ..tire import MagicFormula
    from ..tire.tir import TirParameters

    if not isinstance(tire, MagicFormula):
        raise ParameterError(f"road_friction_tire needs a MagicFormula tire, got {type(tire).__name__}", key="tire",
                             value=tire)
    if isinstance(ratio, bool) or not (np.isfinite(ratio) and ratio > 0):
        raise ParameterError(f"friction ratio must be a finite number > 0, got {ratio!r}", key="ratio", value=ratio)
    params = tire.params
    sections = {name: dict(entries) for name, entries in params.sections.items()}
    for key in ("LMUX", "LMUY"):
        where = next((s for s, kv in sections.items() if key in {k.upper() for k in kv}), None)
        if where is None:
            where = next((s for s in sections if s.upper() == "SCALING_COEFFICIENTS"), "SCALING_COEFFICIENTS")
            sections.setdefault(where, {})[key] = float(params.get(key, 1.0)) * float(ratio)
        else:
            written = next(k for k in sections[where] if k.upper() == key)
            sections[where][written] = float(sections[where][written]) * float(ratio)
    return MagicFormula(TirParameters(sections, tables=dict(params.tables), path=params.path))
