"""Road friction for the single-track model: the Magic Formula's friction scaling factors.

A Magic Formula tire is put on a road of another friction by its scaling factors LMUX and LMUY
(Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 4.3.2: "the friction coefficients ...
scaled by lambda_mu, e.g. for a road of lower friction"): the peak forces scale, the slip
stiffnesses stay. The tire stays a :class:`~vehdyn.tire.MagicFormula`, so the compiled
single-track backend still runs it. (The full vehicle has its own ``friction(X, Y)`` callable.)
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["road_friction_tire"]


def road_friction_tire(tire, friction: float, load: float):
    """``tire`` (a MagicFormula) on a road where its peak friction at ``load`` is ``friction``.

    LMUX is multiplied by ``friction`` / (the tire's peak longitudinal friction at ``load``) and
    LMUY by ``friction`` / (its peak lateral friction), both from
    :func:`vehdyn.tire.characteristic_values`; the slip stiffnesses stay.

    Parameters
    ----------
    tire : vehdyn.tire.MagicFormula
    friction : float
        Peak friction coefficient mu [-] of the road-tire pair (> 0).
    load : float
        Normal load of one tire [N] at which the peak is ``friction`` (> 0).

    Returns
    -------
    MagicFormula
        A new tire; ``tire`` is unchanged.
    """
    from vehdyn.tire import MagicFormula, characteristic_values
    from vehdyn.tire.tir import TirParameters

    if not isinstance(tire, MagicFormula):
        raise ParameterError(f"road_friction_tire needs a MagicFormula tire, got {type(tire).__name__}", key="tire",
                             value=tire)
    for name, value in (("friction", friction), ("load", load)):
        if isinstance(value, bool) or not (np.isfinite(value) and value > 0):
            raise ParameterError(f"{name} must be a finite number > 0, got {value!r}", key=name, value=value)
    peaks = characteristic_values(tire, [float(load)]).iloc[0]
    ratios = {"LMUX": friction / float(peaks["peak_longitudinal_friction"]),
              "LMUY": friction / float(peaks["peak_lateral_friction"])}
    params = tire.params
    sections = {name: dict(entries) for name, entries in params.sections.items()}
    for key, ratio in ratios.items():
        where = next((s for s, kv in sections.items() if key in {k.upper() for k in kv}), None)
        if where is None:
            where = next((s for s in sections if s.upper() == "SCALING_COEFFICIENTS"), "SCALING_COEFFICIENTS")
            sections.setdefault(where, {})[key] = float(params.get(key, 1.0)) * ratio
        else:
            written = next(k for k in sections[where] if k.upper() == key)
            sections[where][written] = float(sections[where][written]) * ratio
    return MagicFormula(TirParameters(sections, tables=dict(params.tables), path=params.path))
