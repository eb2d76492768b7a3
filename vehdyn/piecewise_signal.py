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
    r"""Value of one piece (a row of :data:`PIECE_COLUMNS`) at ``t``, ignoring its time window.

    The one formula every backend evaluates (numpy, plain floats through :mod:`math`, numba):

    .. math::

        v(t) = c + s\,\tau + A \sin(\omega \tau + \varphi), \qquad \tau = t - t_0.

    Parameters
    ----------
    xp : module
        The namespace whose ``sin`` is used: :mod:`numpy` for arrays, :mod:`math` for floats (and
        in compiled code).
    piece : sequence of float
        One row ``(start, end, offset, slope, amplitude, omega, phase)``: start :math:`t_0` and end
        [s], offset :math:`c` [unit], slope :math:`s` [unit/s], amplitude :math:`A` [unit],
        :math:`\omega` [rad/s], :math:`\varphi` [rad].
    t : float or ndarray
        Time [s].

    Returns
    -------
    float or ndarray
        The piece's value at ``t`` [the signal's unit].
    """
    tau = t - piece[0]
    return piece[2] + piece[3] * tau + piece[4] * xp.sin(piece[5] * tau + piece[6])


class PiecewiseSignal:
    r"""A sum of closed-form pieces, callable as ``u(t)`` on arrays.

    Piece k is active on :math:`t_{0,k} \le t < t_{1,k}` and zero outside:

    .. math::

        u(t) = \sum_k \mathbb{1}_{[t_{0,k},\, t_{1,k})}(t)\,
        \left(c_k + s_k (t - t_{0,k}) + A_k \sin\left(\omega_k (t - t_{0,k}) + \varphi_k\right)\right).

    :func:`vehdyn.simulate` evaluates it exactly at every stage of an adaptive step and ends steps
    on its :attr:`breakpoints`, on numpy's ``solve_ivp`` methods and on the compiled backend alike.

    Parameters
    ----------
    pieces : array_like, shape (n_pieces, 7)
        Rows of :data:`PIECE_COLUMNS` [s, s, unit, unit/s, unit, rad/s, rad]: start, end (may be
        ``inf``), offset, slope, amplitude, angular frequency, phase; pieces must not overlap.

    Attributes
    ----------
    pieces : ndarray
        The rows, sorted by start [the units of :data:`PIECE_COLUMNS`].

    See Also
    --------
    vehdyn.procedures.step_steer, vehdyn.procedures.sine_with_dwell : the standard steer inputs,
        built as PiecewiseSignals.

    Examples
    --------
    A step of 0.02 rad reached by a ramp from 0.5 s to 0.65 s (ISO 7401's step steer): the ramp
    is one piece, the held value another.

    >>> import numpy as np
    >>> from vehdyn import PiecewiseSignal
    >>> steer = PiecewiseSignal([[0.5, 0.65, 0.0, 0.02 / 0.15, 0.0, 0.0, 0.0],
    ...                          [0.65, np.inf, 0.02, 0.0, 0.0, 0.0, 0.0]])
    >>> steer(np.array([0.0, 0.575, 1.0])).round(6)
    array([0.  , 0.01, 0.02])
    >>> steer.breakpoints
    array([0.5 , 0.65])
    >>> round(steer.value_at(0.6), 12)
    0.013333333333
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
        """The value at one instant, a float (the numpy solvers' per-stage call, without the array
        overhead of calling the signal).

        With ``t_ref`` the piece is the one active at ``t_ref`` (zero if none), its formula evaluated
        at ``t``: between two breakpoints the signal is one smooth formula, which a step ending on
        the next breakpoint must see up to its end (the compiled backend's rule, too).

        Parameters
        ----------
        t : float
            Time [s].
        t_ref : float, optional
            Time [s] whose active piece gives the formula (default: ``t``).

        Returns
        -------
        float
            The value [the signal's unit].
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
