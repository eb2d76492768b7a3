r"""What the driver models share: the path and its preview, the steer stage (limit, delay, lag) and
the drivers' base class.

The preview: the driver looks ahead along the vehicle's heading by the preview distance
:math:`d = \max(|u| T_p, d_{min})` (:math:`T_p` the preview time) and measures the lateral offset
:math:`e` of the desired path from that preview point, in vehicle axes (SAE: positive when the
path lies to the right) (:func:`preview_offsets`).

The steer stage: every driver's command :math:`\delta_c` is limited to :math:`\pm\delta_{max}`,
delayed by the driver's reaction time :math:`\tau` (the Padé approximant of
:func:`vehdyn.interconnect.pade_delay`, states ``driver_delay_1..n``; none for :math:`\tau = 0`)
and lagged by the first-order neuromuscular lag :math:`T_N` (state ``driver_steer_angle``, the
road-wheel steer the driver applies, :func:`steer_rates`). The driver's steer output is that
state, so its output never depends on its feedback at the same instant.

The laws are written once, over numpy arrays (with a trailing batch axis) and floats: the
drivers' ``rhs`` call them with arrays, their compiled form (:mod:`vehdyn.driver._compiled_drivers`,
for a compiled :class:`~vehdyn.interconnect.ClosedLoop`) registers them with numba's
``register_jitable`` and calls them with floats.
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.interconnect import Controller, pade_delay
from vehdyn.signals import Signal

__all__ = ["preview_offsets", "heading_offsets", "delay_rates", "steer_rates"]


def preview_offsets(path_x, path_y, x, y, yaw_angle, distance):
    r"""Lateral offset of the path from the point ``distance`` ahead along the heading.

    .. math::

        e = \left[f(X + d\cos\psi) - (Y + d\sin\psi)\right]\cos\psi

    with :math:`f` the path :math:`Y(X)`, read at the preview point's earth :math:`X`. Broadcasts
    over ``distance`` and the batch; under numba, floats.

    Parameters
    ----------
    path_x, path_y : ndarray
        The desired path in earth axes [m] (SAE: y to the right), ``path_x`` strictly increasing.
    x, y : float or ndarray
        Earth position of the CG [m].
    yaw_angle : float or ndarray
        Heading psi [rad].
    distance : float or ndarray
        Preview distance d [m].

    Returns
    -------
    float or ndarray
        e [m] in vehicle axes (SAE: positive when the path lies to the right of the preview point).
    """
    return heading_offsets(path_x, path_y, x, y, np.cos(yaw_angle), np.sin(yaw_angle), distance)


def heading_offsets(path_x, path_y, x, y, cos_psi, sin_psi, distance):
    """:func:`preview_offsets` with the heading given by its cosine and sine (computed once for many distances).

    Parameters
    ----------
    path_x, path_y : ndarray
        The desired path in earth axes [m], ``path_x`` strictly increasing.
    x, y : float or ndarray
        Earth position of the CG [m].
    cos_psi, sin_psi : float or ndarray
        cos and sin of the heading psi [-].
    distance : float or ndarray
        Preview distance d [m].

    Returns
    -------
    float or ndarray
        e [m] in vehicle axes.
    """
    preview_x = x + distance * cos_psi
    preview_y = y + distance * sin_psi
    return (np.interp(preview_x, path_x, path_y) - preview_y) * cos_psi


def delay_rates(a, b, c, d, z, command, dz):
    r"""Rates of the delay's states into ``dz`` and the delayed command: a state space evaluated in loops.

    .. math::

        \dot z = A z + B \delta_c, \qquad \delta_d = C z + D \delta_c

    written as loops so that the same code runs on numpy rows (a batch axis) and, compiled, on floats.

    Parameters
    ----------
    a, b, c : ndarray
        A (n, n) [1/s], B (n,) [1/s], C (n,) [-] of the delay (:func:`vehdyn.interconnect.pade_delay`).
    d : float
        D [-].
    z : ndarray
        The delay's states (the first n rows are read) [rad].
    command : float or ndarray
        delta_c [rad].
    dz : ndarray
        Written: dz/dt in its first n rows [1/s].

    Returns
    -------
    float or ndarray
        delta_d [rad], the delayed command.
    """
    delayed = d * command
    for i in range(a.shape[0]):
        rate = b[i] * command
        for j in range(a.shape[0]):
            rate = rate + a[i, j] * z[j]
        dz[i] = rate
        delayed = delayed + c[i] * z[i]
    return delayed


def steer_rates(p, command, x, dxdt):
    r"""The driver's steer stage: the command limited, delayed (Padé) and lagged; rates into ``dxdt``.

    .. math::

        \dot z = A z + B \bar\delta_c, \qquad
        T_N \dot\delta = C z + D \bar\delta_c - \delta, \qquad
        \bar\delta_c = \min(\max(\delta_c, -\delta_{max}), \delta_{max})

    Parameters
    ----------
    p : namedtuple
        The driver's numbers (fields ``pade_a``, ``pade_b``, ``pade_c``, ``pade_d``,
        ``max_steer_angle`` [rad], ``lag`` T_N [s]).
    command : float or ndarray
        delta_c [rad].
    x : ndarray
        The driver's states: the delay's ``z`` then the steer delta [rad].
    dxdt : ndarray
        Written: their rates, dz/dt [1/s] and d(delta)/dt [rad/s].
    """
    n = p.pade_a.shape[0]
    limited = np.minimum(np.maximum(command, -p.max_steer_angle), p.max_steer_angle)
    delayed = delay_rates(p.pade_a, p.pade_b, p.pade_c, p.pade_d, x, limited, dxdt)
    dxdt[n] = (delayed - x[n]) / p.lag


def steer_output(p, x, u, y):
    """The steer the driver applies, ``front_steer_angle`` = the state ``driver_steer_angle``, into ``y[0]``."""
    y[0] = x[p.pade_a.shape[0]]


def _check_path(path_x, path_y):
    px, py = np.asarray(path_x, dtype=float), np.asarray(path_y, dtype=float)
    if px.ndim != 1 or px.shape != py.shape or px.size < 2:
        raise ParameterError(f"path_x and path_y must be 1-D arrays of the same length >= 2, got {px.shape} and "
                             f"{py.shape}", key="path_x", value=px.shape)
    if not (np.all(np.isfinite(px)) and np.all(np.isfinite(py))) or np.any(np.diff(px) <= 0):
        raise ParameterError("path_x must be finite and strictly increasing (path_y finite)", key="path_x", value=px)
    return np.ascontiguousarray(px), np.ascontiguousarray(py)


_FEEDBACK_UNITS = {"x": "m", "y": "m", "yaw_angle": "rad", "longitudinal_velocity": "m/s",
                   "lateral_velocity": "m/s", "yaw_rate": "rad/s"}


class _PathDriver(Controller):
    """Base of the drivers: a command law on the previewed path, then the steer stage (module docstring).

    A subclass sets ``feedback`` (the plant states it reads), ``_law_rhs`` and ``_law_output``
    (module functions ``(p, x, u, dxdt)`` and ``(p, x, u, y)`` of its law, written once), its
    ``numbers`` (the namedtuple they read) and calls :meth:`_setup`.
    """

    feedback = ("x", "y", "yaw_angle", "longitudinal_velocity")
    _lag_name = "neuromuscular_lag"
    _parameter_names: tuple = ("delay", "neuromuscular_lag", "preview_time", "minimum_preview_distance",
                               "max_steer_angle", "pade_order")
    _law_rhs = None
    _law_output = staticmethod(steer_output)

    def _setup(self, path_x, path_y, *, delay, lag, preview_time, minimum_preview_distance, max_steer_angle,
               pade_order, outputs=None, **gains):
        from vehdyn.params.checks import check_gains

        self.path_x, self.path_y = _check_path(path_x, path_y)
        owner, lag_name = type(self).__name__, self._lag_name
        values = check_gains(owner, positive=(lag_name, "preview_time", "max_steer_angle") + tuple(gains),
                             nonnegative=("delay", "minimum_preview_distance"), delay=delay,
                             preview_time=preview_time, minimum_preview_distance=minimum_preview_distance,
                             max_steer_angle=max_steer_angle, **{lag_name: lag}, **gains)
        if isinstance(pade_order, bool) or pade_order not in range(1, 11):
            raise ParameterError(f"{owner} pade_order must be an integer 1..10, got {pade_order!r}", key="pade_order",
                                 value=pade_order)
        for name, value in values.items():
            setattr(self, name, value)
        self.pade_order = int(pade_order)
        A, B, C, D = pade_delay(self.delay, self.pade_order)
        self._pade = (np.ascontiguousarray(A), np.ascontiguousarray(B[:, 0]), np.ascontiguousarray(C[0]),
                      float(D[0, 0]))
        n = A.shape[0]
        states = tuple(Signal(f"driver_delay_{k + 1}", "-", f"Pade state {k + 1} of the driver's delay")
                       for k in range(n))
        self.declare(states=states + (Signal("driver_steer_angle", "rad", "road-wheel steer applied by the driver"),),
                     inputs=tuple(Signal(name, _FEEDBACK_UNITS[name], f"{name} of the vehicle (feedback)")
                                  for name in self.feedback),
                     outputs=outputs or (Signal("front_steer_angle", "rad",
                                                "front road-wheel steer commanded by the driver"),))

    def named_parameters(self) -> dict:
        """The driver's named parameters (SI).

        Returns
        -------
        dict
            ``{name: value}`` of its gains, delay [s], lag [s], preview time [s], minimum preview
            distance [m], steer limit [rad] (and ``pade_order``, where it has a delay).
        """
        return {name: getattr(self, name) for name in self._parameter_names}

    def preview_distance(self, speed):
        """The preview distance d = max(|u| T_p, d_min).

        Parameters
        ----------
        speed : float or array_like
            Forward speed u [m/s].

        Returns
        -------
        float or ndarray
            d [m].
        """
        return np.maximum(np.abs(speed) * self.preview_time, self.minimum_preview_distance)

    def rhs(self, t, x, u):
        x = np.asarray(x, dtype=float)
        u = np.asarray(u, dtype=float)
        dxdt = np.empty(np.broadcast_shapes(x.shape, (x.shape[0],) + u.shape[1:]))
        type(self)._law_rhs(self.numbers, x, u, dxdt)
        return dxdt

    def output(self, t, x, u):
        x = np.asarray(x, dtype=float)
        u = np.asarray(u, dtype=float)
        y = np.empty((self.n_outputs,) + np.broadcast_shapes(x.shape[1:], u.shape[1:]))
        type(self)._law_output(self.numbers, x, u, y)
        return y

    def compiled_rhs(self):
        """The driver's law compiled by numba, for a compiled :class:`~vehdyn.interconnect.ClosedLoop`.

        The same functions as :meth:`rhs` and :meth:`output` (registered with numba's
        ``register_jitable``), called with floats (:mod:`vehdyn.driver._compiled_drivers`).

        Returns
        -------
        vehdyn.simulation.compiled.CompiledModel
            Compiled ``rhs`` and ``output``, their key and :attr:`numbers` as their arguments.
        """
        from vehdyn.driver import _compiled_drivers

        return _compiled_drivers.compiled_driver(self)
