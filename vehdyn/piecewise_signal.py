"""Input signals defined piece by piece in closed form, exact in numpy and in compiled code.

A :class:`PiecewiseSignal` is a sum of pieces; piece k is active on ``start_k <= t < end_k``::

    value_k(t) = offset_k + slope_k (t - start_k) + amplitude_k sin(omega_k (t - start_k) + phase_k)

and zero outside. Steps, ramps, sines, dwells and their combinations (the steer inputs of
:mod:`vehdyn.procedures`) are such sums. The signal is a vectorized callable ``u(t)`` for
:func:`vehdyn.simulate`; besides, its :attr:`~PiecewiseSignal.pieces` table and
:attr:`~PiecewiseSignal.breakpoints` (where it or its derivative may jump) let both backends --
the compiled one (:mod:`vehdyn.simulation.compiled`) and numpy's ``solve_ivp`` methods
(:meth:`~PiecewiseSignal.value_at`) -- evaluate it exactly at every stage of an adaptive step and
end steps on its breakpoints, instead of interpolating its samples. :func:`piece_value` is the one
formula all use (written over an ``xp`` namespace, see :mod:`vehdyn.tire._mf_ops`).
"""

from __future__ import annotations

import math

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["PiecewiseSignal", "piece_value", "PIECE_COLUMNS"]

PIECE_COLUMNS = ("start", "end", "offset", "slope", "amplitude", "omega", "phase")
"""Columns of :attr:`PiecewiseSignal.pieces`: start, end [s], offset [unit], slope [unit/s],
amplitude [unit], omega [rad/s], phase [rad]."""


def piece_value(xp, piece, t):
    """Value of one piece (a row of :data:`PIECE_COLUMNS`) at ``t``, ignoring its time window."""
    tau = t - piece[0]
    return piece[2] + piece[3] * tau + piece[4] * xp.sin(piece[5] * tau + piece[6])


class PiecewiseSignal:
    """A sum of closed-form pieces (see the module docstring), callable as ``u(t)`` on arrays.

    Parameters
    ----------
    pieces : array_like, shape (n_pieces, 7)
        Rows of :data:`PIECE_COLUMNS`; ``end`` may be ``inf``; pieces must not overlap.
    """

    def __init__(self, pieces):
        table = np.atleast_2d(np.asarray(pieces, dtype=float))
        if table.ndim != 2 or table.shape[1] != len(PIECE_COLUMNS):
            raise ParameterError(f"pieces must have shape (n, {len(PIECE_COLUMNS)}) with columns {PIECE_COLUMNS}, "
                                 f"got {table.shape}", key="pieces", value=table.shape)
        finite = np.isfinite(np.delete(table, 1, axis=1)).all() and not np.isnan(table[:, 1]).any()
        if not finite or np.any(table[:, 1] <= table[:, 0]):
            raise ParameterError("pieces need finite values (end may be inf) and end > start", key="pieces",
                                 value=table)
        table = table[np.argsort(table[:, 0])]
        if np.any(table[1:, 0] < table[:-1, 1]):
            raise ParameterError("pieces overlap", key="pieces", value=table)
        self.pieces = np.ascontiguousarray(table)
        self._rows = tuple(tuple(float(v) for v in row) for row in table)  # for value_at: plain floats

    def value_at(self, t: float, t_ref: float | None = None) -> float:
        """The value at one instant ``t`` [s], a float (the numpy solvers' per-stage call, without
        the array overhead of calling the signal).

        With ``t_ref`` the piece is the one active at ``t_ref`` (zero if none), its formula evaluated
        at ``t``: between two breakpoints the signal is one smooth formula, which a step ending on
        the next breakpoint must see up to its end (the compiled backend's rule, too).
        """
        ref = t if t_ref is None else t_ref
        for piece in self._rows:
            if piece[0] <= ref < piece[1]:
                return piece_value(math, piece, t)
        return 0.0

    @property
    def breakpoints(self) -> np.ndarray:
        """Sorted finite times [s] where a piece begins or ends."""
        edges = self.pieces[:, :2].ravel()
        return np.unique(edges[np.isfinite(edges)])

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        value = np.zeros(t.shape)
        for piece in self.pieces:
            inside = (t >= piece[0]) & (t < piece[1])
            value = np.where(inside, piece_value(np, piece, t), value)
        return value

    def __repr__(self) -> str:
        return f"PiecewiseSignal({len(self.pieces)} pieces, breakpoints {self.breakpoints.tolist()})"
