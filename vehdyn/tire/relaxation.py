"""First-order tire relaxation: transient slips as named states that vehicle models embed.

A tire builds its force only after it has rolled about one relaxation length. The
single-contact-point transient model (Pacejka 2012, ch. 8; its string-model basis in ch. 5 and 7)
lets the slips that drive the steady-state law lag the kinematic slips::

    sigma_kappa d(kappa')/dt + |V_x| kappa' = -V_sx sign(V_x)
    sigma_alpha d(q')/dt     + |V_x| q'     =  V_sy                   q' = tan(alpha')

with ``V_sx``, ``V_sy`` the slip velocities and ``V_x`` the forward speed of the wheel
(:mod:`vehdyn.tire.slip`, ISO-W). In steady state ``kappa' = -V_sx / V_x`` and
``tan(alpha') = V_sy / |V_x|``, the definitions of :func:`vehdyn.tire.slip.wheel_slip`; the forces
follow from ``law.forces(fz, kappa', alpha')``. The equations divide by no speed, so they hold
through standstill, where ``sigma q'`` is the lateral deflection of a tire that acts as a spring.

Relaxation lengths are given, or computed at each instant from the normal load by the Magic Formula
of a ``.tir`` file, exactly as MFeval 4.3.1 computes them (Pacejka 2012, ch. 4 and 8): MF 6.1 / 6.2
``sigma_kappa = K_xkappa / C_x`` and ``sigma_alpha = |K_yalpha / C_y|`` (slip stiffness over carcass
stiffness), MF 5.2 / PAC2002 the ``PTX``/``PTY`` formulas. The equations live in one place,
:func:`vehdyn.tire.mf_vertical.carcass_stiffness`; :func:`relaxation_lengths` evaluates them through
:class:`~vehdyn.tire.MagicFormula` at zero slip (the stiffnesses do not depend on the slips; turn
slip not included).
"""

from __future__ import annotations

from collections.abc import Mapping
from os import PathLike

import numpy as np

from vehdyn.errors import ParameterError, TirFileError
from vehdyn.model import Model
from vehdyn.signals import Signal

__all__ = ["TireRelaxation", "relaxation_lengths"]

def _tir_value(key, value):
    """A mapping's value as the ``.tir`` reader gives it: strings are parsed as in a file."""
    from vehdyn.tire.tir import _parse_value

    if isinstance(value, str):
        try:
            return _parse_value(value, None, None)
        except TirFileError as error:
            raise ParameterError(f".tir parameter {key}: {error}", key=key, value=value) from None
    if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
        raise ParameterError(f".tir parameter {key} must be a number or a string, got {value!r}", key=key, value=value)
    return value


def _magic_formula(tire):
    """A :class:`~vehdyn.tire.MagicFormula` from a model, ``TirParameters``, a path or a mapping."""
    from vehdyn.tire.magic_formula import MagicFormula
    from vehdyn.tire.tir import TirParameters

    if isinstance(tire, MagicFormula):
        return tire
    if isinstance(tire, TirParameters):
        return MagicFormula(tire)
    if isinstance(tire, (str, PathLike)):
        return MagicFormula.from_tir(tire)
    if not isinstance(tire, Mapping):
        raise ParameterError(f"tire must be a MagicFormula, .tir parameters, a .tir path or a mapping of .tir keys, "
                             f"got {type(tire).__name__}", key="tire", value=tire)
    grouped = all(isinstance(v, Mapping) for v in tire.values())
    sections = {str(k): dict(v) for k, v in tire.items()} if grouped else {"PARAMETERS": dict(tire)}
    for entries in sections.values():
        for key, value in entries.items():
            entries[key] = _tir_value(key, value)
    try:
        return MagicFormula(TirParameters(sections))
    except TirFileError as error:  # an unsupported version, or a value the .tir checks refuse
        raise ParameterError(str(error), key=getattr(error, "key", "FITTYP"),
                             value=getattr(error, "value", sections)) from None


def relaxation_lengths(tire, fz, gamma=0.0, pressure=None, *, limits: bool = True):
    """Longitudinal and lateral relaxation lengths [m] of a Magic Formula tire, as MFeval.

    Parameters
    ----------
    tire : MagicFormula, TirParameters, path or mapping
        The tire: a model, what :func:`vehdyn.tire.read_tir` returns, a ``.tir`` path, or a mapping
        ``{KEY: value}`` of ``.tir`` values in SI (flat, or grouped by section); keys it lacks take
        MFeval's defaults (:data:`vehdyn.tire.tir.MFEVAL_DEFAULTS`), as in a file.
    fz : array_like
        Normal load [N]; negative values count as 0.
    gamma : array_like
        Inclination angle [rad].
    pressure : array_like, optional
        Inflation pressure [Pa] (MF 6.x); default ``INFLPRES``.
    limits : bool
        Clamp the inputs to the file's ranges (MFeval's useMode 1xx).

    Returns
    -------
    tuple of ndarray
        ``(sigma_kappa, sigma_alpha)`` [m], broadcast over the inputs (equations in the module
        docstring).
    """
    out = _magic_formula(tire).evaluate(fz, 0.0, 0.0, gamma, pressure=pressure, limits=limits)
    return np.broadcast_arrays(out.sigma_x, out.sigma_y)


def _positive_length(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value) or value <= 0:
        raise ParameterError(f"{name} must be a finite number > 0 [m], got {value!r}", key=name, value=value)
    return float(value)


class TireRelaxation(Model):
    r"""First-order longitudinal and lateral relaxation of one tire.

    The single-contact-point transient model: the slips that drive the steady-state law lag the
    kinematic slips by a relaxation length,

    .. math::

        \sigma_\kappa \frac{d\kappa'}{dt} + |V_x| \kappa' = -V_{sx} \operatorname{sgn} V_x,
        \qquad
        \sigma_\alpha \frac{dq'}{dt} + |V_x| q' = V_{sy}, \qquad q' = \tan\alpha'

    (ISO-W; V_sx = V_x - omega R_e, V_sy the slip velocities of :func:`vehdyn.tire.slip_velocities`).
    In steady state kappa' = -V_sx / V_x and tan(alpha') = V_sy / |V_x|, the slips of
    :func:`vehdyn.tire.wheel_slip`; no speed is divided by, so the equations hold through
    standstill, where sigma q' is the lateral deflection of a tire acting as a spring. The forces
    follow from ``law.forces(fz, kappa', alpha')``. From a ``.tir`` file the lengths follow the
    load: MF 6.x :math:`\sigma_\kappa = K_{x\kappa} / C_x`, :math:`\sigma_\alpha = |K_{y\alpha} / C_y|`
    (Besselink et al. 2010), MF 5.2 the PTX/PTY formulas (:func:`relaxation_lengths`).

    Parameters
    ----------
    longitudinal_relaxation_length, lateral_relaxation_length : float
        ``sigma_kappa`` and ``sigma_alpha`` [m], > 0.
    prefix : str
        Put before every signal name, so that a vehicle model can embed one per wheel
        (``prefix="front_left_"`` gives ``front_left_transient_slip_ratio``).

    Signals
    -------
    states
        ``transient_slip_ratio`` kappa' [-], ``transient_lateral_slip`` tan(alpha') [-].
    inputs
        ``forward_speed`` V_x [m/s], ``longitudinal_slip_velocity`` V_sx [m/s],
        ``lateral_slip_velocity`` V_sy [m/s] (ISO-W); plus ``normal_load`` F_z [N] for a model made
        by :meth:`from_tir`, whose lengths follow the load.
    outputs
        ``transient_slip_ratio`` kappa' [-], ``transient_slip_angle`` alpha' [rad].

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, ch. 7
       (single-contact-point transient tire models) and ch. 8 (their applications); the
       string-model basis in ch. 5.
    .. [2] I. J. M. Besselink, A. J. C. Schmeitz and H. B. Pacejka, "An improved Magic
       Formula/Swift tyre model that can handle inflation pressure changes", Vehicle System
       Dynamics 48 (sup1), 337-352, 2010 (relaxation lengths from slip and carcass stiffness).

    Examples
    --------
    >>> import numpy as np
    >>> from vehdyn.tire import TireRelaxation
    >>> lag = TireRelaxation(longitudinal_relaxation_length=0.3, lateral_relaxation_length=0.5)
    >>> lag.state_names
    ('transient_slip_ratio', 'transient_lateral_slip')
    >>> np.sort(lag.linearize(u0=[20.0, 0.0, 0.0]).modes().eigenvalues.real).tolist()   # -V_x / sigma [1/s]
    [-66.66666666666667, -40.0]
    """

    phenomena = frozenset({"tire_lag"})

    def __init__(self, longitudinal_relaxation_length: float, lateral_relaxation_length: float, *,
                 prefix: str = ""):
        self.longitudinal_relaxation_length = _positive_length("longitudinal_relaxation_length",
                                                               longitudinal_relaxation_length)
        self.lateral_relaxation_length = _positive_length("lateral_relaxation_length", lateral_relaxation_length)
        self._tir = None
        self._declare(prefix, load_input=False)

    @classmethod
    def from_tir(cls, tir, *, gamma: float = 0.0, pressure=None, minimum_length: float = 0.01,
                 prefix: str = "") -> "TireRelaxation":
        """Relaxation whose lengths follow the input ``normal_load`` through :func:`relaxation_lengths`.

        Parameters
        ----------
        tir : MagicFormula, TirParameters, path or mapping
            The tire (see :func:`relaxation_lengths`).
        gamma : float
            Inclination at which the lengths are evaluated [rad].
        pressure : float, optional
            Inflation pressure at which the lengths are evaluated [Pa] (default the file's
            INFLPRES).
        minimum_length : float
            Floor [m] on the lengths (they vanish with the load), keeping the equations finite
            when a wheel lifts off.
        prefix : str
            Put before every signal name (see the class).

        Returns
        -------
        TireRelaxation
            With the extra input ``normal_load`` [N].

        Raises
        ------
        ParameterError
            If the tire cannot be built or ``minimum_length`` is not > 0.
        """
        model = cls.__new__(cls)
        tire = _magic_formula(tir)
        relaxation_lengths(tire, 1.0, gamma, pressure)  # check the parameters now, not inside a solver
        model._tir = (tire, float(gamma), pressure, _positive_length("minimum_length", minimum_length))
        model.longitudinal_relaxation_length = model.lateral_relaxation_length = None
        model._declare(prefix, load_input=True)
        return model

    def _declare(self, prefix: str, load_input: bool) -> None:
        self.prefix = prefix
        inputs = [Signal(prefix + "forward_speed", "m/s", "forward speed V_x of the wheel centre (ISO-W)"),
                  Signal(prefix + "longitudinal_slip_velocity", "m/s", "V_sx = V_x - omega R_e (ISO-W)"),
                  Signal(prefix + "lateral_slip_velocity", "m/s", "V_sy, lateral slip velocity (ISO-W, y left)")]
        if load_input:
            inputs.append(Signal(prefix + "normal_load", "N", "normal load F_z setting the relaxation lengths"))
        self.declare(
            states=[Signal(prefix + "transient_slip_ratio", "-", "kappa', the lagged slip ratio"),
                    Signal(prefix + "transient_lateral_slip", "-", "tan(alpha'), the lagged lateral slip")],
            inputs=inputs,
            outputs=[Signal(prefix + "transient_slip_ratio", "-", "kappa', the lagged slip ratio"),
                     Signal(prefix + "transient_slip_angle", "rad", "alpha', the lagged slip angle")],
        )

    def lengths(self, u):
        """The relaxation lengths at given inputs.

        Parameters
        ----------
        u : sequence of array_like
            The inputs in the model's order (forward speed [m/s], slip velocities [m/s] and, for
            a model from a ``.tir`` file, the normal load [N]; only the load is read).

        Returns
        -------
        sigma_kappa, sigma_alpha : float or ndarray
            [m]: constant unless built by :meth:`from_tir`, then at the load, floored at
            ``minimum_length``.
        """
        if self._tir is None:
            return self.longitudinal_relaxation_length, self.lateral_relaxation_length
        params, gamma, pressure, floor = self._tir
        sigma_kappa, sigma_alpha = relaxation_lengths(params, u[3], gamma, pressure)
        return np.maximum(sigma_kappa, floor), np.maximum(sigma_alpha, floor)

    def rhs(self, t, x, u):
        slip_ratio, lateral_slip = x
        forward_speed, slip_velocity_x, slip_velocity_y = u[0], u[1], u[2]
        sigma_kappa, sigma_alpha = self.lengths(u)
        speed = np.abs(forward_speed)
        direction = np.where(forward_speed < 0.0, -1.0, 1.0)
        return np.stack([(-slip_velocity_x * direction - speed * slip_ratio) / sigma_kappa,
                         (slip_velocity_y - speed * lateral_slip) / sigma_alpha])

    def output(self, t, x, u):
        slip_ratio, lateral_slip = x
        return np.stack([np.asarray(slip_ratio, dtype=float), np.arctan(lateral_slip)])

    def jacobian(self, t, x, u):
        """Exact ``(A, B, C, D)`` for constant lengths (away from ``V_x = 0``); ``None`` from a .tir."""
        if self._tir is not None:
            return None
        slip_ratio, lateral_slip = np.asarray(x, dtype=float)
        forward_speed = float(u[0])
        sigma_kappa, sigma_alpha = self.lengths(u)
        direction = -1.0 if forward_speed < 0.0 else 1.0
        speed = abs(forward_speed)
        A = np.diag([-speed / sigma_kappa, -speed / sigma_alpha])
        B = np.array([[-direction * slip_ratio / sigma_kappa, -direction / sigma_kappa, 0.0],
                      [-direction * lateral_slip / sigma_alpha, 0.0, 1.0 / sigma_alpha]])
        C = np.diag([1.0, 1.0 / (1.0 + lateral_slip**2)])
        D = np.zeros((2, 3))
        return A, B, C, D

    def time_constants(self, forward_speed, normal_load=None):
        """Time constants of the relaxation at a forward speed.

        Parameters
        ----------
        forward_speed : float or array_like
            V_x [m/s].
        normal_load : float or array_like, optional
            F_z [N]; needed (and only used) for a model built by :meth:`from_tir`.

        Returns
        -------
        tuple of float or ndarray
            ``(sigma_kappa / |V_x|, sigma_alpha / |V_x|)`` [s] (``inf`` at standstill).

        Raises
        ------
        ParameterError
            For a model from a ``.tir`` file without ``normal_load``.
        """
        speed = np.abs(np.asarray(forward_speed, dtype=float))
        if self._tir is not None and normal_load is None:
            raise ParameterError("time_constants: a relaxation model from a .tir file needs normal_load [N]",
                                 key="normal_load", value=None)
        sigma_kappa, sigma_alpha = self.lengths((None, None, None, np.asarray(normal_load, dtype=float)))
        with np.errstate(divide="ignore"):
            return sigma_kappa / speed, sigma_alpha / speed
