"""The model's domain (:attr:`vehdyn.Model.domain`): the first state of a run outside it."""

from __future__ import annotations

import numpy as np


def _domain_bounds(model):
    """[(state index, name, low, high)] of the model's :attr:`~vehdyn.Model.domain`."""
    domain = getattr(model, "domain", None) or {}
    return [(model.state_names.index(name), name, float(low), float(high)) for name, (low, high) in domain.items()]


def _domain_violation(model, t, x):
    """The first (over time, then over the domain's states) accepted state outside the model's domain,
    as the model's :meth:`~vehdyn.Model.domain_error`, or None. ``x``: (n, n_t, ...) or (n, ...) at ``t``."""
    bounds = _domain_bounds(model)
    if not bounds:
        return None
    x = np.asarray(x)
    t = np.atleast_1d(np.asarray(t, dtype=float))
    xs = x.reshape(x.shape[0], t.size, -1)
    first = None
    for i, name, low, high in bounds:
        values = xs[i]
        outside = ~((values >= low) & (values <= high))
        if np.any(outside):
            k, member = np.argwhere(outside)[0]
            if first is None or k < first[0]:
                first = (int(k), name, float(values[k, member]))
    if first is None:
        return None
    return model.domain_error(first[1], first[2], float(t[first[0]]))
