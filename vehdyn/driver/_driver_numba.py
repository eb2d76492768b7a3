"""The driver-vehicle loop's rhs for the compiled backend (numba), bound to a plant's compiled rhs.

Kept apart from :mod:`vehdyn.driver` so that the cached compiled code depends on this
source only. The laws are those of :class:`~vehdyn.driver.CrossoverDriver` (``kind`` 0) and
:class:`~vehdyn.driver.OptimalPreviewDriver` (``kind`` 1); ``args`` is built by
:meth:`vehdyn.handling.DrivenVehicle.compiled_rhs`.
"""

import math

import numpy as np


def driven_rhs(t, x, u, args, dxdt):  # pragma: no cover - compiled by numba (tested through simulate)
    """dx/dt of plant + driver for the compiled backend; ``_plant_rhs`` is bound to the plant's compiled rhs."""
    (plant_args, n_p, i_steer, ix, iy, ipsi, iu, iv, ir, kind, px, py, gain, tp, dmin, smax, pa, pb, pc, pd, tn,
     times, q, h0, h1, h2, delay) = args
    n_z = pa.shape[0]
    steer = x[n_p + n_z]
    up = u.copy()
    up[i_steer] = steer
    _plant_rhs(t, x[:n_p], up, plant_args, dxdt[:n_p])  # noqa: F821 (bound by compiled_copy)
    X, Y, psi, speed = x[ix], x[iy], x[ipsi], abs(x[iu])
    c, s = math.cos(psi), math.sin(psi)
    if kind == 0:
        d = max(speed * tp, dmin)
        command = gain * (np.interp(X + d * c, px, py) - (Y + d * s)) * c
    else:
        total = 0.0
        for k in range(times.size):
            d = max(speed * (delay + times[k]), dmin)
            offset = (np.interp(X + d * c, px, py) - (Y + d * s)) * c
            total += q[k] * (offset - h0[k] * x[iv] - h1[k] * x[ir] - h2[k] * steer)
        command = gain * total
    command = min(max(command, -smax), smax)
    delayed = pd * command
    for i in range(n_z):
        rate = pb[i] * command
        for j in range(n_z):
            rate += pa[i, j] * x[n_p + j]
        dxdt[n_p + i] = rate
        delayed += pc[i] * x[n_p + i]
    dxdt[n_p + n_z] = (delayed - steer) / tn


