"""One way to close a loop: a controller model wrapped around a plant model, all names kept.

:class:`ClosedLoop` connects a controller :class:`~vehdyn.Model` to a plant :class:`~vehdyn.Model`
by signal NAME, with two rules:

* a controller **input** named like a plant input is the *demand* of that input (the driver's or
  the user's value, still an input of the closed loop under its own name); any other controller
  input is **feedback**, read from the plant state of that name or, failing that, the plant output;
* a controller **output** named like a plant input *replaces* that plant input (the command the
  actuator applies). The closed loop outputs it as ``<name>_after_<controller>`` (controller
  in snake case: ``abs``, ``esc``, ``traction_control``).

So ``ClosedLoop(SingleTrack(car, wheel_spin=True), ABS(car))`` has the plant's inputs (the brake
torques are the driver's demand), the plant's states followed by the controller's, and the
plant's outputs followed by ``front_brake_torque_after_abs``, ``rear_brake_torque_after_abs``. A
closed loop is itself a ``Model``: it simulates (with a batch axis where the plant has one),
linearizes (central differences through :meth:`vehdyn.Model.linearize`, every name kept) and can
be closed again by a second controller (ESC around ABS around the car).

The controller's outputs must not depend on its feedback inputs (only on its states and the
demands): otherwise the loop would be algebraic. The constructor checks it by evaluating the
controller's output at two different feedback values.

"""

from __future__ import annotations

import re

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import Model
from vehdyn.signals import Signal

__all__ = ["ClosedLoop"]


def _snake(name: str) -> str:
    """CamelCase -> snake_case, acronyms kept together (ABS -> abs, TractionControl -> traction_control)."""
    return re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", name).lower()


class ClosedLoop(Model):
    """``plant`` with ``controller`` in the loop, connected by signal names (module docstring).

    Parameters
    ----------
    plant : Model
        The vehicle model (e.g. :class:`~vehdyn.handling.SingleTrack`), or another ClosedLoop.
    controller : Model
        Inputs: demands (names of plant inputs) and feedback (names of plant states or outputs);
        outputs: names of plant inputs that it commands.

    Raises
    ------
    ParameterError
        If the plant lacks signals the controller needs (the message names the missing inputs),
        if a controller output is not a plant input, if state names clash, or if the controller's
        outputs depend on its feedback (an algebraic loop).
    """

    def __init__(self, plant: Model, controller: Model):
        for label, model in (("plant", plant), ("controller", controller)):
            if not isinstance(model, Model):
                raise ParameterError(f"ClosedLoop {label} must be a vehdyn Model, got {type(model).__name__}",
                                     key=label, value=model)
        p_in, p_states, p_out = plant.input_names, plant.state_names, plant.output_names
        c_name = type(controller).__name__
        missing = [n for n in controller.input_names if n not in p_in and n not in p_states and n not in p_out]
        missing += [n for n in controller.output_names if n not in p_in and n not in missing]
        if missing:
            hint = ""
            if getattr(controller, "corners", None) is False and "brake_torque_front_left" in p_in:
                hint = f"; for a plant with one signal per wheel build {c_name}(vehicle, corners=True)"
            raise ParameterError(f"{c_name} cannot be attached to {type(plant).__name__}: missing inputs {missing} "
                                 f"(the plant's inputs are {list(p_in)}, its states {list(p_states)}){hint}",
                                 key="missing_inputs", value=missing)
        clash = sorted(set(p_states) & set(controller.state_names))
        if clash:
            raise ParameterError(f"{c_name} states {clash} clash with the plant's", key="states", value=clash)
        self.plant, self.controller = plant, controller
        self._np = plant.n_states
        c_in = controller.input_names
        self._demand = [(k, plant.index(n, "inputs")) for k, n in enumerate(c_in) if n in p_in]
        self._fb_state = [(k, plant.index(n)) for k, n in enumerate(c_in) if n not in p_in and n in p_states]
        self._fb_output = [(k, plant.index(n, "outputs")) for k, n in enumerate(c_in)
                           if n not in p_in and n not in p_states]
        self._command = [plant.index(n, "inputs") for n in controller.output_names]
        self.declare(states=tuple(plant.states) + tuple(controller.states), inputs=tuple(plant.inputs),
                     outputs=tuple(plant.output_signals) + tuple(
                         Signal(f"{s.name}_after_{_snake(c_name)}", s.unit, f"{s.name} applied by {c_name}")
                         for s in controller.output_signals))
        self.phenomena = frozenset(plant.phenomena)
        self._check_not_algebraic()

    def _check_not_algebraic(self):
        c = self.controller
        feedback = [k for k, _ in self._fb_state + self._fb_output]
        if not feedback:
            return
        xc = np.zeros(c.n_states)
        u1 = np.zeros(c.n_inputs)
        u2 = u1.copy()
        u2[feedback] = 1.0 + np.arange(len(feedback))
        y1, y2 = np.asarray(c.output(0.0, xc, u1), float), np.asarray(c.output(0.0, xc, u2), float)
        if not np.allclose(y1, y2, rtol=0.0, atol=1e-12):
            raise ParameterError(f"{type(c).__name__} outputs depend on its feedback inputs: the loop would be "
                                 "algebraic (outputs must depend on the controller's states and demands only)",
                                 key="controller", value=type(c).__name__)

    # ------------------------------------------------------------------ evaluation
    def _split(self, t, x, u):
        """(plant states, plant inputs, controller states, controller inputs, commands)."""
        x = np.asarray(x, dtype=float)
        u = np.asarray(u, dtype=float)
        batch = x.shape[1:]
        if u.shape[1:] != batch:
            u = np.broadcast_to(u.reshape(u.shape[:1] + (1,) * len(batch)) if u.ndim == 1 else u,
                                u.shape[:1] + batch)
        xp, xc = x[:self._np], x[self._np:]
        c = self.controller
        uc = np.zeros((c.n_inputs,) + batch)
        for k, j in self._demand:
            uc[k] = u[j]
        command = np.asarray(c.output(t, xc, uc), dtype=float).reshape((c.n_outputs,) + batch)
        up = np.array(u, dtype=float, copy=True)
        up[self._command] = command
        for k, j in self._fb_state:
            uc[k] = xp[j]
        if self._fb_output:
            yp = np.asarray(self.plant.output(t, xp, up), dtype=float)
            for k, j in self._fb_output:
                uc[k] = yp[j]
        return xp, up, xc, uc, command

    def rhs(self, t, x, u):
        """Plant and controller state derivatives, stacked."""
        xp, up, xc, uc, _ = self._split(t, x, u)
        dp = np.asarray(self.plant.rhs(t, xp, up), dtype=float)
        dc = np.asarray(self.controller.rhs(t, xc, uc), dtype=float).reshape((self.controller.n_states,)
                                                                             + dp.shape[1:])
        return np.concatenate([dp, dc])

    def output(self, t, x, u):
        """Plant outputs, then the commands the controller applies (``<input>_after_<controller>``)."""
        xp, up, _, _, command = self._split(t, x, u)
        return np.concatenate([np.asarray(self.plant.output(t, xp, up), dtype=float), command])

    def compiled_rhs(self):
        """The loop compiled by numba for ``simulate(..., backend="compiled")`` (see :meth:`vehdyn.Model.compiled_rhs`).

        Compiled when both the plant and the controller have a compiled rhs and output (the
        SingleTrack and FullVehicle with their compiled tire laws; ABS, TractionControl, ESC; an
        inner ClosedLoop of those): the same sequence as :meth:`rhs`, with the controllers' laws
        from the same source (:mod:`vehdyn.interconnect._compiled_loop`). None otherwise, so that
        ``backend="auto"`` runs numpy; the plant's :class:`~vehdyn.ParameterError` (a configuration
        without a compiled form) passes through.
        """
        from vehdyn.interconnect import _compiled_loop

        return _compiled_loop.compiled_loop(self)

    def __repr__(self) -> str:
        return f"<ClosedLoop {type(self.controller).__name__} around {self.plant!r}>"
