"""Active and semi-active quarter-car suspension: skyhook, groundhook, LQR, clipped semi-active damping.

* **Ideal skyhook / groundhook** (Karnopp, Crosby & Harwood, *J. Eng. Ind.* 96(2), 1974;
  Valášek et al., *Vehicle System Dynamics* 28, 1997): an actuator between body and wheel makes the
  force of a damper from the body to the inertial "sky", f = -c_sky z_s', or from the wheel to the
  ground, f = c_gnd z_u' (the wheel then feels -c_gnd z_u'); both at once is the hybrid.
  :func:`skyhook` and :func:`groundhook` return the closed loop as a :class:`~vehdyn.LinearModel`.
* **Semi-active** (Karnopp 1974; Sammier, Sename & Dugard, *Vehicle System Dynamics* 39, 2003):
  :class:`SemiActiveQuarterCar` is a damper whose coefficient varies between c_min and c_max and
  can only dissipate. It tracks the skyhook/groundhook force when that force is dissipative and
  falls to c_min when it is not ("clipped optimal"); a nonlinear :class:`~vehdyn.Model`.
* **LQR** (Hrovat, *Automatica* 33(10), 1997, sec. 3; Thompson, *Proc. IMechE* 190, 1976):
  full-state feedback f = -K x on the quarter car in relative coordinates (suspension travel,
  tire deflection, sprung and unsprung velocity; road velocity the disturbance) minimizing
  E[sum w_i y_i^2 + r f^2] with y the sprung acceleration, suspension travel and tire deflection
  (or any outputs). :func:`lqr_quarter_car` builds the weights over the outputs, exports the plant
  with :meth:`~vehdyn.LinearModel.to_control` and calls python-control's ``lqr``.
* **Comparison** on an ISO 8608 road (:class:`~vehdyn.ride.RoadSpectrum`; waviness 2, so the
  road velocity seen at speed V is white with one-sided PSD (2 pi n0)^2 G_d(n0) V [(m/s)^2/Hz],
  :meth:`~vehdyn.ride.RoadSpectrum.white_noise_gain`) with exact r.m.s. values from the Lyapunov
  equation of the model with the road's shaping filter appended
  (:func:`vehdyn.ride.random_vibration`, :func:`vehdyn.ride.stationary_covariance`; Newland,
  *Random Vibrations*, 3rd ed., 1993, ch. 7), ranked on comfort (r.m.s. sprung acceleration),
  suspension travel and road holding (r.m.s. dynamic tire load).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import LinearModel
from vehdyn.model import Model
from vehdyn.signals import Signal
from vehdyn.ride.quarter_car import QuarterCar
from vehdyn.ride.random_vibration import random_response
from vehdyn.road import RoadSpectrum

__all__ = [
    "relative_quarter_car",
    "skyhook",
    "groundhook",
    "SemiActiveQuarterCar",
    "LQRDesign",
    "lqr_quarter_car",
    "compare_suspensions",
]

#: The three measures of :func:`compare_suspensions`.
COMPARISON_OUTPUTS = ("sprung_acceleration", "suspension_travel", "dynamic_tire_load")


def _spectrum(road) -> RoadSpectrum:
    return road if isinstance(road, RoadSpectrum) else RoadSpectrum.from_class(road)


def _require_quarter_car(qc):
    if not isinstance(qc, QuarterCar):
        raise ParameterError(f"expected a vehdyn.ride.QuarterCar, got {type(qc).__name__}: build one from a vehicle, "
                             "QuarterCar(vehicle, axle='front'), or from numbers, QuarterCar.from_parameters(...)",
                             key="quarter_car", value=qc)


def _with_actuator(qc: QuarterCar) -> QuarterCar:
    return qc if qc.has_actuators else qc.replace(actuator=True)


def relative_quarter_car(qc: QuarterCar, actuator: bool = True) -> LinearModel:
    r"""The quarter car in relative coordinates, driven by the road velocity only.

    The road elevation drops out because every force depends on differences of displacements;
    so a white road velocity (an ISO 8608 road of waviness 2) gives a stationary state with finite
    covariance. Derived from ``qc``'s own matrices by the substitution (checked: the coefficient
    of z_r vanishes)

    .. math::

        z_s = x_1 - x_2 + z_r, \qquad z_u = z_r - x_2, \qquad
        x_1 = z_s - z_u \text{ (suspension travel)}, \quad x_2 = z_r - z_u \text{ (tire deflection)}

    Parameters
    ----------
    qc : QuarterCar
        The passive car.
    actuator : bool, optional
        Keep (add) the input ``actuator_force`` [N] (default True); False drops it.

    Returns
    -------
    LinearModel
        States ``suspension_travel`` [m], ``tire_deflection`` [m], ``sprung_velocity`` [m/s],
        ``unsprung_velocity`` [m/s]; inputs ``road_velocity`` [m/s] (and ``actuator_force``);
        the outputs of ``qc`` that do not depend on absolute position.
    """
    _require_quarter_car(qc)
    m = _with_actuator(qc) if actuator else qc.replace(actuator=False)
    i_zs, i_zu = m.index("sprung_displacement"), m.index("unsprung_displacement")
    i_vs, i_vu = m.index("sprung_velocity"), m.index("unsprung_velocity")
    n = m.n_states
    # x_abs = P x_rel + e z_r
    P = np.zeros((n, n))
    P[i_zs, 0], P[i_zs, 1] = 1.0, -1.0
    P[i_zu, 1] = -1.0
    P[i_vs, 2] = 1.0
    P[i_vu, 3] = 1.0
    e = np.zeros(n)
    e[[i_zs, i_zu]] = 1.0
    j_zr, j_vr = m.index("road_displacement", "inputs"), m.index("road_velocity", "inputs")
    others = [j for j in range(m.n_inputs) if j not in (j_zr, j_vr)]
    Pinv = np.linalg.inv(P)
    # x_rel' = Pinv (x_abs' - e z_r') ; x_abs' = A x_abs + B u
    A = Pinv @ m.A @ P
    road_term = Pinv @ (m.A @ e + m.B[:, j_zr])
    if np.abs(road_term).max() > 1e-9 * np.abs(A).max():
        raise AssertionError("relative_quarter_car: the road elevation does not drop out")  # pragma: no cover
    B = np.column_stack([Pinv @ (m.B[:, j_vr] - e)] + [Pinv @ m.B[:, j] for j in others])
    Cabs_zr = m.C @ e + m.D[:, j_zr]
    keep = [k for k in range(m.n_outputs) if abs(Cabs_zr[k]) <= 1e-9 * (1 + np.abs(m.C[k]).max())]
    C = (m.C @ P)[keep]
    D = np.column_stack([m.D[keep, j_vr]] + [m.D[keep, j] for j in others])
    states = [Signal("suspension_travel", "m", "suspension extension z_s - z_u"),
              Signal("tire_deflection", "m", "tire compression z_r - z_u"),
              m.states[i_vs], m.states[i_vu]]
    return LinearModel(A, B, C, D, states=states, inputs=[m.inputs[j_vr]] + [m.inputs[j] for j in others],
                       outputs=[m.outputs[k] for k in keep], name=f"{qc.name}_relative",
                       phenomena=qc.phenomena)


def _close_loop(model: LinearModel, gain: np.ndarray, actuator: str = "actuator_force", name: str = "") -> LinearModel:
    """Closed loop of ``model`` with ``actuator = gain @ x``; the actuator force becomes an output."""
    j = model.index(actuator, "inputs")
    rest = [k for k in range(model.n_inputs) if k != j]
    gain = np.asarray(gain, dtype=float).reshape(1, model.n_states)
    A = model.A + model.B[:, [j]] @ gain
    C = np.vstack([model.C + model.D[:, [j]] @ gain, gain])
    D = np.vstack([model.D[:, rest], np.zeros((1, len(rest)))])
    return LinearModel(A, model.B[:, rest], C, D, states=model.states, inputs=[model.inputs[k] for k in rest],
                       outputs=list(model.outputs) + [model.inputs[j]], name=name or model.name,
                       phenomena=model.phenomena)


def _hook_gain(model: LinearModel, sky: float, ground: float) -> np.ndarray:
    for name, c in (("skyhook_damping", sky), ("groundhook_damping", ground)):
        if not (np.isfinite(c) and c >= 0):
            raise ParameterError(f"{name} must be a non-negative number [N*s/m], got {c!r}", key=name, value=c)
    g = np.zeros(model.n_states)
    g[model.index("sprung_velocity")] = -sky
    g[model.index("unsprung_velocity")] = ground
    return g


def skyhook(model, skyhook_damping: float, groundhook_damping: float = 0.0) -> LinearModel:
    r"""Ideal skyhook (and optionally groundhook: the hybrid) active quarter car.

    Parameters
    ----------
    model : QuarterCar or LinearModel
        A :class:`QuarterCar` (an actuator is added; its passive damper is kept — use
        ``qc.replace(damping=0.0)`` for a pure skyhook) or a model with an ``actuator_force`` input
        and ``sprung_velocity``/``unsprung_velocity`` states (e.g. :func:`relative_quarter_car`).
    skyhook_damping : float
        c_sky [N*s/m], >= 0: actuator force -c_sky z_s' on the body.
    groundhook_damping : float, optional
        c_gnd [N*s/m], >= 0: actuator force -c_gnd z_u' on the wheel (default 0).

    Returns
    -------
    LinearModel
        The closed loop: the model's inputs without the actuator, its outputs and ``actuator_force``.

    Notes
    -----
    The actuator between body and wheel makes the force of dampers to the inertial "sky" and to
    the ground (positive extending the suspension: up on the body, down on the wheel):

    .. math::

        f = -c_{sky} \dot z_s + c_{gnd} \dot z_u

    References
    ----------
    .. [1] D. Karnopp, M. J. Crosby and R. A. Harwood, "Vibration control using semi-active force
       generators", *J. Eng. Ind.* 96(2), 1974, pp. 619-626.
    .. [2] M. Valášek, M. Novák, Z. Šika and O. Vaculín, "Extended ground-hook: new concept of
       semi-active control of truck's suspension", *Vehicle System Dynamics*, 1997.
    """
    base = _with_actuator(model) if isinstance(model, QuarterCar) else model
    gain = _hook_gain(base, float(skyhook_damping), float(groundhook_damping))
    return _close_loop(base, gain, name=f"{base.name}_skyhook")


def groundhook(model, groundhook_damping: float) -> LinearModel:
    """Ideal groundhook active quarter car: actuator force c_gnd z_u' up on the body, -c_gnd z_u' on the wheel.

    :func:`skyhook` with ``skyhook_damping=0``.

    Parameters
    ----------
    model : QuarterCar or LinearModel
        As for :func:`skyhook`.
    groundhook_damping : float
        c_gnd [N*s/m], >= 0.

    Returns
    -------
    LinearModel
        The closed loop: the model's inputs without the actuator, its outputs and ``actuator_force``.
    """
    base = _with_actuator(model) if isinstance(model, QuarterCar) else model
    return _close_loop(base, _hook_gain(base, 0.0, float(groundhook_damping)), name=f"{base.name}_groundhook")


class SemiActiveQuarterCar(Model):
    r"""Quarter car with a continuously variable, purely dissipative damper (clipped skyhook/groundhook).

    The damper's coefficient c is chosen at each instant to make the force of the ideal hybrid
    skyhook-groundhook law, f* = -c_sky z_s' + c_gnd z_u' (on the body; the wheel takes -f*), when
    that force opposes the suspension velocity, clipped to [c_min, c_max]; otherwise c = c_min.
    The damper force on the body is then f = -c (z_s' - z_u') with f (z_s' - z_u') <= 0 always.

    Parameters
    ----------
    quarter_car : QuarterCar
        Masses, spring and tire (its damping is replaced by the variable damper). Build it from a
        vehicle, ``QuarterCar(vehicle, axle="front")``, or from numbers,
        ``QuarterCar.from_parameters(...)``.
    skyhook_damping, groundhook_damping : float, optional
        c_sky, c_gnd [N*s/m] of the reference law, >= 0 (default 0).
    min_damping, max_damping : float
        Range of the damper [N*s/m], 0 <= c_min <= c_max.

    Notes
    -----
    The quarter car of :class:`QuarterCar` without its passive damper, the damper's force f on
    the body (its reaction on the wheel) set by the clipped hybrid law:

    .. math::

        f^* &= -c_{sky} \dot z_s + c_{gnd} \dot z_u, \qquad v_{rel} = \dot z_s - \dot z_u, \\
        c &= \begin{cases}
             \min\left(\max\left(-f^* / v_{rel}, c_{min}\right), c_{max}\right)
                 & f^* v_{rel} < 0 \\
             c_{min} & \text{otherwise}
             \end{cases}, \qquad
        f = -c \, v_{rel}

    so that f v_rel <= 0 always: the damper only dissipates.

    States, inputs and outputs as the :class:`QuarterCar`, plus outputs ``damper_force`` [N] (on
    the body, up +) and ``damper_coefficient`` [N*s/m]. ``rhs`` and ``output`` take a trailing
    batch axis. With c_min = c_max = c it is the passive quarter car of damping c.

    References
    ----------
    .. [1] D. Karnopp, M. J. Crosby and R. A. Harwood, "Vibration control using semi-active force
       generators", *J. Eng. Ind.* 96(2), 1974, pp. 619-626.
    .. [2] D. Sammier, O. Sename and L. Dugard, "Skyhook and H-infinity control of semi-active
       suspensions: some practical aspects", *Vehicle System Dynamics* 39, 2003.
    """

    phenomena = frozenset({"heave", "wheel_hop", "road_input"})

    def __init__(self, quarter_car: QuarterCar, *, skyhook_damping: float = 0.0, groundhook_damping: float = 0.0,
                 min_damping: float, max_damping: float):
        _require_quarter_car(quarter_car)
        for key, val in (("skyhook_damping", skyhook_damping), ("groundhook_damping", groundhook_damping),
                         ("min_damping", min_damping), ("max_damping", max_damping)):
            if not (isinstance(val, (int, float)) and np.isfinite(val) and val >= 0):
                raise ParameterError(f"{key} must be a non-negative number [N*s/m], got {val!r}", key=key, value=val)
        if max_damping < min_damping:
            raise ParameterError(f"max_damping = {max_damping} N*s/m is below min_damping = {min_damping} N*s/m",
                                 key="max_damping", value=max_damping)
        self.skyhook_damping = float(skyhook_damping)
        self.groundhook_damping = float(groundhook_damping)
        self.min_damping, self.max_damping = float(min_damping), float(max_damping)
        self.plant = quarter_car.replace(damping=0.0, actuator=True)
        j = self.plant.index("actuator_force", "inputs")
        road = [k for k in range(self.plant.n_inputs) if k != j]
        self._B_road, self._b_force = self.plant.B[:, road], self.plant.B[:, j]
        self._D_road, self._d_force = self.plant.D[:, road], self.plant.D[:, j]
        self._i_vs = self.plant.index("sprung_velocity")
        self._i_vu = self.plant.index("unsprung_velocity")
        self.declare(states=self.plant.states, inputs=[s for s in self.plant.inputs if s.name != "actuator_force"],
                     outputs=list(self.plant.outputs) + [
                         Signal("damper_force", "N", "semi-active damper force on the body (up +)"),
                         Signal("damper_coefficient", "N*s/m", "damping coefficient the damper is set to")])
        self.name = f"{quarter_car.name}_semi_active"

    def damper(self, x):
        """The damper's coefficient and force at the states ``x`` (class Notes).

        Parameters
        ----------
        x : ndarray
            States of the model [m, m/s], shape (4,) or (4, n_batch).

        Returns
        -------
        coefficient : ndarray
            c [N*s/m].
        force : ndarray
            f on the body [N] (up +; the wheel feels -f).
        """
        vs, vu = x[self._i_vs], x[self._i_vu]
        if np.ndim(vs) == 0 and np.isfinite(vs) and np.isfinite(vu):
            # one finite state (what an integrator's Python loop asks): the same law on floats, the
            # same operations, without numpy's per-call overhead on scalars
            vs, vu = float(vs), float(vu)
            rel = vs - vu
            target = -self.skyhook_damping * vs + self.groundhook_damping * vu
            c = self.min_damping
            if target * rel < 0:  # rel != 0
                c = min(max(-target / rel, self.min_damping), self.max_damping)
            return np.asarray(c), np.asarray(-c * rel)
        rel = vs - vu
        target = -self.skyhook_damping * vs + self.groundhook_damping * vu
        with np.errstate(divide="ignore", invalid="ignore"):
            wanted = np.where(rel != 0, -target / np.where(rel != 0, rel, 1.0), self.min_damping)
        dissipative = target * rel < 0
        c = np.where(dissipative, np.clip(wanted, self.min_damping, self.max_damping), self.min_damping)
        return c, -c * rel

    def rhs(self, t, x, u):
        x = np.asarray(x, dtype=float)
        _, force = self.damper(x)
        return self.plant.A @ x + self._B_road @ u + np.multiply.outer(self._b_force, force)

    def output(self, t, x, u):
        x = np.asarray(x, dtype=float)
        c, force = self.damper(x)
        y = self.plant.C @ x + self._D_road @ u + np.multiply.outer(self._d_force, force)
        return np.concatenate([y, force[None], c[None]], axis=0)


@dataclass(frozen=True)
class LQRDesign:
    """An LQR active suspension for the quarter car.

    Attributes
    ----------
    gain : ndarray, shape (n_states,)
        K in f = -K x over the states of ``plant`` [N/m, N*s/m].
    riccati : ndarray
        Solution S of the algebraic Riccati equation [units of the cost per unit state squared].
    closed_loop : LinearModel
        Input ``road_velocity``; the plant's outputs and ``actuator_force``.
    plant : LinearModel
        :func:`relative_quarter_car` with the actuator.
    weights : dict
        Output weights w_i [1/unit^2] and ``actuator_force`` weight r.
    poles : ndarray
        Closed-loop eigenvalues [1/s].
    """

    gain: np.ndarray
    riccati: np.ndarray
    closed_loop: LinearModel
    plant: LinearModel
    weights: dict
    poles: np.ndarray

    def cost(self, road, speed: float) -> float:
        """Expected cost E[sum w y^2 + r f^2] of the design on an ISO 8608 road.

        The road velocity is sigma w, w unit-intensity white noise (waviness 2;
        sigma = :meth:`~vehdyn.road.RoadSpectrum.white_noise_gain`), so the cost is
        sigma^2 b_w' S b_w.

        Parameters
        ----------
        road : RoadSpectrum, str or float
            A :class:`~vehdyn.road.RoadSpectrum`, an ISO 8608 class letter or Gd(n0) [m^3].
        speed : float
            Forward speed V [m/s].

        Returns
        -------
        float
            The expected cost [-] (in the units the weights make it).
        """
        sigma = _spectrum(road).white_noise_gain(speed)
        bw = self.plant.B[:, self.plant.index("road_velocity", "inputs")]
        return float(sigma**2 * bw @ self.riccati @ bw)


def lqr_quarter_car(qc: QuarterCar, weights: Mapping[str, float] | None = None, force_weight: float = 1e-8,
                    ) -> LQRDesign:
    r"""Design an LQR active suspension through ``to_control()`` and python-control's ``lqr``.

    Parameters
    ----------
    qc : QuarterCar
        The passive car; its spring and damper stay in parallel with the actuator.
    weights : mapping, optional
        Output weights ``{output name: w}`` [1/unit^2] of the cost
        J = E[sum w_i y_i^2 + r f^2]; outputs of :func:`relative_quarter_car`. Default
        ``{"sprung_acceleration": 1.0, "suspension_travel": 1e4, "tire_deflection": 1e5}``.
    force_weight : float
        r [1/N^2], > 0.

    Returns
    -------
    LQRDesign
        The gain, the Riccati solution, the closed loop and the plant.

    Notes
    -----
    Full-state feedback f = -K x on the states x of :func:`relative_quarter_car` minimizing

    .. math::

        J = E\left[\sum_i w_i y_i^2 + r f^2\right]
          = E\left[x^T Q x + f^T R f + 2 x^T N f\right], \qquad
        Q = C^T W C, \quad R = D^T W D + r, \quad N = C^T W D

    with y = C x + D f the weighted outputs (the sprung acceleration depends on f directly, hence
    the cross term). Full-state feedback needs the tire deflection, which a real car estimates
    rather than measures.

    References
    ----------
    .. [1] D. Hrovat, "Survey of advanced suspension developments and related optimal control
       applications", *Automatica* 33(10), 1997, pp. 1781-1817, sec. 3.
    """
    _require_quarter_car(qc)
    import control as ct

    weights = dict(weights or {"sprung_acceleration": 1.0, "suspension_travel": 1e4, "tire_deflection": 1e5})
    if not (np.isfinite(force_weight) and force_weight > 0):
        raise ParameterError(f"force_weight must be positive, got {force_weight!r}", key="force_weight",
                             value=force_weight)
    plant = relative_quarter_car(qc, actuator=True)
    for name, w in weights.items():
        if name not in plant.output_names:
            raise ParameterError(f"no output {name!r} to weight; outputs are {list(plant.output_names)}",
                                 key="weights", value=name)
        if not (np.isfinite(w) and w >= 0):
            raise ParameterError(f"weight of {name} must be a non-negative number, got {w!r}", key="weights", value=w)
    sys = plant.select(outputs=list(weights), inputs=["actuator_force"]).to_control()
    W = np.diag(list(weights.values()))
    C, D = np.asarray(sys.C), np.asarray(sys.D)
    Q = C.T @ W @ C
    R = D.T @ W @ D + force_weight
    N = C.T @ W @ D
    K, S, E = ct.lqr(sys, Q, R, N)
    K = np.asarray(K).reshape(-1)
    closed = _close_loop(plant, -K, name=f"{qc.name}_lqr")
    return LQRDesign(gain=K, riccati=np.asarray(S), closed_loop=closed, plant=plant,
                     weights={**weights, "actuator_force": float(force_weight)}, poles=np.asarray(E))


def compare_suspensions(systems: Mapping[str, LinearModel], road, speed: float, reference: str | None = None):
    """R.m.s. comfort, suspension travel and road holding of suspensions on the same ISO 8608 road.

    Parameters
    ----------
    systems : mapping
        ``{label: LinearModel}`` with a road input (``road_velocity``, or ``road_displacement`` and
        ``road_velocity``) and outputs ``sprung_acceleration``, ``suspension_travel`` and
        ``dynamic_tire_load`` (e.g. :func:`relative_quarter_car` closed by :func:`skyhook` or
        :func:`lqr_quarter_car`, ``relative_quarter_car(qc, False)``, or a :class:`QuarterCar`).
    road : RoadSpectrum, class letter or Gd(n0) [m^3]
        The road (:class:`~vehdyn.ride.RoadSpectrum`).
    speed : float
        [m/s].
    reference : str, optional
        Label whose values the ``*_ratio`` columns divide by (default: the first).

    Returns
    -------
    pandas.DataFrame
        One row per system: r.m.s. of the three measures (and of ``actuator_force`` where present),
        exact from :func:`vehdyn.ride.random_vibration` (Lyapunov route), and ratios to the
        reference; ``attrs["units"]``.
    """
    import pandas as pd

    spectrum = _spectrum(road)
    rows = {}
    for label, sys in systems.items():
        outs = list(COMPARISON_OUTPUTS) + (["actuator_force"] if "actuator_force" in sys.output_names else [])
        res = random_response(sys, spectrum, speed, outputs=outs)
        rows[label] = dict(zip(res.output_names, res.rms))
    df = pd.DataFrame(rows).T
    ref = reference if reference is not None else next(iter(systems))
    for col in COMPARISON_OUTPUTS:
        df[f"{col}_ratio"] = df[col] / df.loc[ref, col]
    df.index.name = "suspension"
    df.attrs["units"] = {"sprung_acceleration": "m/s^2", "suspension_travel": "m", "dynamic_tire_load": "N",
                         "actuator_force": "N", **{f"{c}_ratio": "-" for c in COMPARISON_OUTPUTS}}
    return df
