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

Relaxation lengths are given, or computed at each instant from the normal load with the ``.tir``
file's values as MFeval 4.3.1 computes them (Pacejka 2012, ch. 4 and 8):

* MF 6.1 / 6.2 (``FITTYP`` 61, 62): ``sigma_kappa = K_xkappa / C_x`` and
  ``sigma_alpha = |K_yalpha / C_y|``, slip stiffness over carcass stiffness, with
  ``C_x = LONGITUDINAL_STIFFNESS (1 + PCFX1 dfz + PCFX2 dfz^2)(1 + PCFX3 dpi)`` (likewise ``C_y``),
  ``K_xkappa = F_z (PKX1 + PKX2 dfz) exp(PKX3 dfz)(1 + PPX1 dpi + PPX2 dpi^2) LKX`` and
  ``K_yalpha = PKY1 F_z0' (1 + PPY1 dpi)(1 - PKY3 |gamma|)
  sin(PKY4 atan(F_z / ((PKY2 + PKY5 gamma^2)(1 + PPY2 dpi) F_z0'))) LKY``;
* MF 5.2 / PAC2002 (``FITTYP`` 6 or 21): ``sigma_kappa = (PTX1 + PTX2 dfz) exp(-PTX3 dfz) LSGKP R_0
  F_z / F_z0`` and ``sigma_alpha = PTY1 sin(2 atan(F_z / (PTY2 F_z0'))) (1 - PKY3 |gamma|) R_0 LFZO
  LSGAL``,

where ``F_z0' = FNOMIN LFZO``, ``dfz = (F_z - F_z0') / F_z0'``, ``dpi = (p - NOMPRES) / NOMPRES``
and ``R_0 = UNLOADED_RADIUS`` (turn slip not included).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ..errors import ParameterError
from ..model import Model
from ..signals import Signal

__all__ = ["TireRelaxation", "relaxation_lengths", "tir_version"]

# MFeval's defaults for coefficients a file may lack (readTIR); the rest are required.
_DEFAULTS = {
    "LFZO": 1.0, "LKX": 1.0, "LKY": 1.0, "LSGKP": 1.0, "LSGAL": 1.0,
    "PKX2": 0.0, "PKX3": 0.0, "PPX1": 0.0, "PPX2": 0.0,
    "PKY3": 0.0, "PKY4": 2.0, "PKY5": 0.0, "PPY1": 0.0, "PPY2": 0.0,
    "PCFX1": 0.0, "PCFX2": 0.0, "PCFX3": 0.0, "PCFY1": 0.0, "PCFY2": 0.0, "PCFY3": 0.0,
    "PTX2": 0.0, "PTX3": 0.0,
}


def _flat_parameters(tir) -> dict:
    """Upper-case ``{KEY: value}`` from a flat or section-grouped mapping of ``.tir`` values."""
    if not isinstance(tir, Mapping):
        for attribute in ("params", "parameters"):
            inner = getattr(tir, attribute, None)
            if isinstance(inner, Mapping):
                tir = inner
                break
        else:
            to_dict = getattr(tir, "to_dict", None)
            tir = to_dict() if callable(to_dict) else tir
    if not isinstance(tir, Mapping):
        raise ParameterError(f"tir must be a mapping of .tir keys to values, got {type(tir).__name__}",
                             key="tir", value=tir)
    flat: dict = {}
    for key, value in tir.items():
        if isinstance(value, Mapping):
            flat.update({str(k).upper(): v for k, v in value.items()})
        else:
            flat[str(key).upper()] = value
    return flat


def _number(params: dict, key: str) -> float:
    if key in params:
        value = params[key]
    elif key in _DEFAULTS:
        return _DEFAULTS[key]
    else:
        raise ParameterError(f"the .tir parameters lack {key}, needed for the relaxation lengths",
                             key=key, value=None)
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ParameterError(f".tir parameter {key} must be a number, got {value!r}", key=key, value=value) from None


def tir_version(tir) -> str:
    """``"6.1"``, ``"6.2"`` or ``"5.2"`` from ``FITTYP`` (61, 62; 6 or 21) or ``PROPERTY_FILE_FORMAT``."""
    params = _flat_parameters(tir)
    fittyp = params.get("FITTYP")
    if fittyp is not None:
        try:
            code = int(float(fittyp))
        except (TypeError, ValueError):
            code = None
        versions = {61: "6.1", 62: "6.2", 6: "5.2", 21: "5.2"}
        if code in versions:
            return versions[code]
        raise ParameterError(f"FITTYP = {fittyp!r} is not a Magic Formula version vehdyn knows (61, 62, 6, 21)",
                             key="FITTYP", value=fittyp)
    if str(params.get("PROPERTY_FILE_FORMAT", "")).strip("'\" ").upper() == "PAC2002":
        return "5.2"
    raise ParameterError("the .tir parameters have neither FITTYP nor PROPERTY_FILE_FORMAT = 'PAC2002'",
                         key="FITTYP", value=None)


def relaxation_lengths(tir, fz, gamma=0.0, pressure=None, *, limits: bool = True):
    """Longitudinal and lateral relaxation lengths [m] from a ``.tir`` file's values, as MFeval.

    Parameters
    ----------
    tir : mapping
        ``{KEY: value}`` of the ``.tir`` file (flat, or grouped by section), e.g. what
        :func:`vehdyn.tire.read_tir` returns.
    fz : array_like
        Normal load [N]; negative values count as 0.
    gamma : array_like
        Inclination angle [rad].
    pressure : array_like, optional
        Inflation pressure [Pa] (MF 6.x); default ``INFLPRES`` or, lacking it, ``NOMPRES``.
    limits : bool
        Clamp ``fz`` to ``FZMAX``, ``gamma`` to ``[CAMMIN, CAMMAX]`` and the pressure to
        ``[PRESMIN, PRESMAX]`` where the file gives them (MFeval's useMode 1xx).

    Returns
    -------
    tuple of ndarray
        ``(sigma_kappa, sigma_alpha)`` [m], broadcast over the inputs (equations in the module
        docstring).
    """
    p = _flat_parameters(tir)
    version = tir_version(p)
    fz = np.maximum(np.asarray(fz, dtype=float), 0.0)
    gamma = np.asarray(gamma, dtype=float)
    if limits:
        if "FZMAX" in p:
            fz = np.minimum(fz, _number(p, "FZMAX"))
        if "CAMMIN" in p and "CAMMAX" in p:
            gamma = np.clip(gamma, _number(p, "CAMMIN"), _number(p, "CAMMAX"))
    nominal = _number(p, "FNOMIN") * _number(p, "LFZO")
    dfz = (fz - nominal) / nominal
    radius = _number(p, "UNLOADED_RADIUS")
    if version == "5.2":
        sigma_kappa = ((_number(p, "PTX1") + _number(p, "PTX2") * dfz) * np.exp(-_number(p, "PTX3") * dfz)
                       * _number(p, "LSGKP") * radius * fz / _number(p, "FNOMIN"))
        sigma_alpha = (_number(p, "PTY1") * np.sin(2.0 * np.arctan(fz / (_number(p, "PTY2") * nominal)))
                       * (1.0 - _number(p, "PKY3") * np.abs(gamma)) * radius * _number(p, "LFZO")
                       * _number(p, "LSGAL"))
        return np.broadcast_arrays(sigma_kappa, sigma_alpha)
    nominal_pressure = _number(p, "NOMPRES")
    if pressure is None:
        pressure = _number(p, "INFLPRES") if "INFLPRES" in p else nominal_pressure
    pressure = np.asarray(pressure, dtype=float)
    if limits and "PRESMIN" in p and "PRESMAX" in p:
        pressure = np.clip(pressure, _number(p, "PRESMIN"), _number(p, "PRESMAX"))
    dpi = (pressure - nominal_pressure) / nominal_pressure
    slip_stiffness = (fz * (_number(p, "PKX1") + _number(p, "PKX2") * dfz) * np.exp(_number(p, "PKX3") * dfz)
                      * (1.0 + _number(p, "PPX1") * dpi + _number(p, "PPX2") * dpi**2) * _number(p, "LKX"))
    cornering_stiffness = (
        _number(p, "PKY1") * nominal * (1.0 + _number(p, "PPY1") * dpi) * (1.0 - _number(p, "PKY3") * np.abs(gamma))
        * np.sin(_number(p, "PKY4") * np.arctan(
            fz / ((_number(p, "PKY2") + _number(p, "PKY5") * gamma**2) * (1.0 + _number(p, "PPY2") * dpi) * nominal)))
        * _number(p, "LKY"))
    carcass_x = (_number(p, "LONGITUDINAL_STIFFNESS") * (1.0 + _number(p, "PCFX1") * dfz + _number(p, "PCFX2") * dfz**2)
                 * (1.0 + _number(p, "PCFX3") * dpi))
    carcass_y = (_number(p, "LATERAL_STIFFNESS") * (1.0 + _number(p, "PCFY1") * dfz + _number(p, "PCFY2") * dfz**2)
                 * (1.0 + _number(p, "PCFY3") * dpi))
    return np.broadcast_arrays(slip_stiffness / carcass_x, np.abs(cornering_stiffness / carcass_y))


def _positive_length(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value) or value <= 0:
        raise ParameterError(f"{name} must be a finite number > 0 [m], got {value!r}", key=name, value=value)
    return float(value)


class TireRelaxation(Model):
    """First-order longitudinal and lateral relaxation of one tire (see the module docstring).

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

    Examples
    --------
    >>> lag = TireRelaxation(longitudinal_relaxation_length=0.3, lateral_relaxation_length=0.5)
    >>> lag.state_names
    ('transient_slip_ratio', 'transient_lateral_slip')
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
        tir : mapping
            The ``.tir`` file's values (flat or grouped by section).
        gamma, pressure
            Inclination [rad] and inflation pressure [Pa] at which the lengths are evaluated.
        minimum_length : float
            Floor [m] on the lengths (they vanish with the load), keeping the equations finite
            when a wheel lifts off.
        """
        model = cls.__new__(cls)
        flat = _flat_parameters(tir)
        relaxation_lengths(flat, 1.0, gamma, pressure)  # check the parameters now, not inside a solver
        model._tir = (flat, float(gamma), pressure, _positive_length("minimum_length", minimum_length))
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
        """``(sigma_kappa, sigma_alpha)`` [m] for the inputs ``u`` (constant unless built from a .tir)."""
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
        """``(sigma_kappa / |V_x|, sigma_alpha / |V_x|)`` [s] (``inf`` at standstill).

        ``normal_load`` [N] is needed (and only used) for a model built by :meth:`from_tir`.
        """
        speed = np.abs(np.asarray(forward_speed, dtype=float))
        if self._tir is not None and normal_load is None:
            raise ParameterError("time_constants: a relaxation model from a .tir file needs normal_load [N]",
                                 key="normal_load", value=None)
        sigma_kappa, sigma_alpha = self.lengths((None, None, None, np.asarray(normal_load, dtype=float)))
        with np.errstate(divide="ignore"):
            return sigma_kappa / speed, sigma_alpha / speed
