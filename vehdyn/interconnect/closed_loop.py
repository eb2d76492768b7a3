"""One way to close a loop: a controller model wrapped around a plant model, all names kept.

:class:`ClosedLoop` connects a controller :class:`~vehdyn.Model` -- a driver of
:mod:`vehdyn.driver`, a chassis controller of :mod:`vehdyn.chassis`, or a user's model -- to a
plant :class:`~vehdyn.Model` by signal NAME, with three rules:

* a controller **input** named like a plant input is the *demand* of that input (the driver's or
  the user's value, still an input of the closed loop under its own name); any other controller
  input is **feedback**, read from the plant state of that name or, failing that, the plant output;
* a controller **output** named like a plant input *replaces* that plant input (the command the
  actuator applies). The closed loop outputs it as ``<name>_after_<controller>`` (controller
  in snake case: ``abs``, ``esc``, ``traction_control``, ``preview_driver``);
* a plant input that the controller commands and does not read as a demand (a driver's steer) is
  no longer an input of the closed loop.

A closed loop is itself a ``Model``: it simulates (with a batch axis where the plant has one),
linearizes (central differences through :meth:`vehdyn.Model.linearize`, every name kept), compiles
when its plant and controller do, and can be closed again by a second controller (ESC around ABS
around the car, a driver around that).

The controller's outputs may depend on its states, its demands and its feedback from plant
STATES (a state does not depend on the input at the same instant: the preview driver's speed law
``F = m k_u (u_target - u)``), but not on feedback from plant OUTPUTS, which may depend on the
plant's inputs: that loop would be algebraic. The constructor checks it by evaluating the
controller's output at two different values of its output feedback.
"""

from __future__ import annotations

import re

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import Model
from vehdyn.signals import Signal

__all__ = ["ClosedLoop", "Controller"]


def _snake(name: str) -> str:
    """CamelCase -> snake_case, acronyms kept together (ABS -> abs, TractionControl -> traction_control)."""
    return re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", name).lower()


class ClosedLoop(Model):
    r"""``plant`` with ``controller`` in the loop, connected by signal names (module docstring).

    With the plant :math:`\dot x_p = f_p(t, x_p, u_p)`, :math:`y_p = h_p(t, x_p, u_p)` and the
    controller :math:`\dot x_c = f_c(t, x_c, u_c)`, :math:`y_c = h_c(t, x_c, u_c)`, the loop is

    .. math::

        u_c &= (d,\; x_p^{\mathrm{fb}},\; y_p^{\mathrm{fb}}), \qquad
        u_p = P u + S y_c, \\
        \dot x &= \begin{pmatrix} f_p(t, x_p, u_p) \\ f_c(t, x_c, u_c) \end{pmatrix}, \qquad
        y = \begin{pmatrix} h_p(t, x_p, u_p) \\ y_c \end{pmatrix}

    with :math:`d` the demands (loop inputs the controller reads), :math:`x_p^{\mathrm{fb}}` and
    :math:`y_p^{\mathrm{fb}}` the plant states and outputs it reads, :math:`S` the selection of
    the commanded plant inputs and :math:`P` that of the plant inputs left to the loop. The loop
    is well posed (not algebraic) when :math:`\partial h_c / \partial y_p^{\mathrm{fb}} = 0`:
    :math:`y_c` is then evaluated first, from :math:`x_c`, :math:`d` and :math:`x_p`, then
    :math:`u_p`, :math:`y_p` and the rates (the well-posedness condition of an interconnection,
    Åström & Murray 2021, sec. 3.3 and 9.1; the by-name connection as in python-control's
    ``interconnect``).

    Parameters
    ----------
    plant : Model
        The vehicle model (e.g. :class:`~vehdyn.handling.SingleTrack`), or another ClosedLoop.
    controller : Model
        Inputs: demands (names of plant inputs) and feedback (names of plant states or outputs);
        outputs: names of plant inputs that it commands.
    plant_backend : {"numpy", "compiled"}, optional
        How the loop's :meth:`rhs` and :meth:`output` (numpy, or any loop that cannot compile as a
        whole: a controller in Python such as :class:`~vehdyn.optimal.PathTrackingNMPC`) evaluate
        the plant: its numpy equations (default), or its compiled code called point by point
        (:func:`vehdyn.simulation.compiled.point_by_point`; the plant's code is compiled or loaded
        when the loop is built), the same equations within a few ulps at a fraction of the cost
        (the full vehicle: about 2 ms a call on numpy, tens of microseconds compiled). A loop that
        compiles as a whole (``backend="compiled"``/``"auto"``) is not affected.

    Raises
    ------
    ParameterError
        If the plant lacks signals the controller needs (the message names the missing inputs),
        if a controller output is not a plant input, if state names clash, or if the controller's
        outputs depend on its feedback from plant outputs (an algebraic loop); for a
        ``plant_backend`` that is not one of the two, or ``"compiled"`` with a plant without
        compiled code (naming it).

    Signals
    -------
    states
        The plant's states, then the controller's.
    inputs
        The plant's inputs, without those the controller commands and does not read.
    outputs
        The plant's outputs, then ``<input>_after_<controller>`` for every command.

    References
    ----------
    .. [1] K. J. Åström and R. M. Murray, *Feedback Systems: An Introduction for Scientists and
       Engineers*, 2nd ed., Princeton University Press, 2021, sec. 3.3 (block diagrams and
       interconnection) and sec. 9.1 (the loop transfer function).
    .. [2] S. Fuller, B. Greiner, J. Moore, R. Murray, R. van Paassen and R. Yorke, "The Python
       Control Systems Library (python-control)", 60th IEEE Conference on Decision and Control,
       2021, pp. 4875-4881 (``interconnect``: systems connected by signal names).

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn.chassis import ABS
    >>> from vehdyn.handling import SingleTrack
    >>> from vehdyn.interconnect import ClosedLoop
    >>> car = vehdyn.load_vehicle("sedan")
    >>> loop = ClosedLoop(SingleTrack(car, wheel_spin=True), ABS(car))
    >>> loop.state_names[-2:]
    ('front_abs_brake_torque', 'rear_abs_brake_torque')
    >>> loop.output_names[-1]
    'rear_brake_torque_after_abs'
    """

    def __init__(self, plant: Model, controller: Model, *, plant_backend: str = "numpy"):
        for label, model in (("plant", plant), ("controller", controller)):
            if not isinstance(model, Model):
                raise ParameterError(f"ClosedLoop {label} must be a vehdyn Model, got {type(model).__name__}",
                                     key=label, value=model)
        from vehdyn.simulation.compiled import backend_option

        backend_option(plant_backend, "plant_backend")
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
        commanded_only = set(controller.output_names) - set(c_in)
        self._passed = [j for j, n in enumerate(p_in) if n not in commanded_only]
        loop_inputs = [p_in[j] for j in self._passed]
        self._demand = [(k, loop_inputs.index(n)) for k, n in enumerate(c_in) if n in p_in]
        self._fb_state = [(k, plant.index(n)) for k, n in enumerate(c_in) if n not in p_in and n in p_states]
        self._fb_output = [(k, plant.index(n, "outputs")) for k, n in enumerate(c_in)
                           if n not in p_in and n not in p_states]
        self._command = [plant.index(n, "inputs") for n in controller.output_names]
        self.declare(states=tuple(plant.states) + tuple(controller.states),
                     inputs=tuple(plant.inputs[j] for j in self._passed),
                     outputs=tuple(plant.output_signals) + tuple(
                         Signal(f"{s.name}_after_{_snake(c_name)}", s.unit, f"{s.name} applied by {c_name}")
                         for s in controller.output_signals))
        self.phenomena = frozenset(plant.phenomena)
        self.plant_backend = plant_backend
        self._plant_functions()  # the plant's compiled code compiled or loaded now, its errors raised here
        self._check_not_algebraic()

    def _plant_functions(self):
        """The plant's (rhs, output) as ``plant_backend`` says (the compiled pair built once)."""
        if self.plant_backend == "numpy":
            return self.plant.rhs, self.plant.output
        functions = self.__dict__.get("_point_by_point")
        if functions is None:
            from vehdyn.simulation.compiled import point_by_point

            try:
                functions = point_by_point(self.plant)
            except ParameterError as exc:
                raise ParameterError(f"plant_backend='compiled': {exc}", key="plant_backend",
                                     value=self.plant_backend) from exc
            self._point_by_point = functions
        return functions

    def _check_not_algebraic(self):
        c = self.controller
        feedback = [k for k, _ in self._fb_output]
        if not feedback:
            return
        xc = np.zeros(c.n_states)
        u1 = np.zeros(c.n_inputs)
        u2 = u1.copy()
        u2[feedback] = 1.0 + np.arange(len(feedback))
        y1, y2 = np.asarray(c.output(0.0, xc, u1), float), np.asarray(c.output(0.0, xc, u2), float)
        if not np.allclose(y1, y2, rtol=0.0, atol=1e-12):
            names = [c.input_names[k] for k in feedback]
            raise ParameterError(f"{type(c).__name__} outputs depend on its feedback inputs {names}, which are plant "
                                 "outputs: the loop would be algebraic (outputs may depend on the controller's "
                                 "states, its demands and plant states only)", key="controller",
                                 value=type(c).__name__)

    # ------------------------------------------------------------------ evaluation
    def _split(self, t, x, u):
        """(plant states, plant inputs, controller states, controller inputs, commands).

        The order of :class:`ClosedLoop`'s equations: demands and state feedback, the commands,
        the plant's inputs, then the output feedback (the compiled loop follows it).
        """
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
        for k, j in self._fb_state:
            uc[k] = xp[j]
        command = np.asarray(c.output(t, xc, uc), dtype=float).reshape((c.n_outputs,) + batch)
        if len(self._passed) == self.plant.n_inputs:
            up = np.array(u, dtype=float, copy=True)
        else:
            up = np.zeros((self.plant.n_inputs,) + batch)
            up[self._passed] = u
        up[self._command] = command
        if self._fb_output:
            yp = np.asarray(self._plant_functions()[1](t, xp, up), dtype=float)
            for k, j in self._fb_output:
                uc[k] = yp[j]
        return xp, up, xc, uc, command

    def rhs(self, t, x, u):
        """Plant and controller state derivatives, stacked."""
        xp, up, xc, uc, _ = self._split(t, x, u)
        dp = np.asarray(self._plant_functions()[0](t, xp, up), dtype=float)
        dc = np.asarray(self.controller.rhs(t, xc, uc), dtype=float).reshape((self.controller.n_states,)
                                                                             + dp.shape[1:])
        return np.concatenate([dp, dc])

    def output(self, t, x, u):
        """Plant outputs, then the commands the controller applies (``<input>_after_<controller>``)."""
        xp, up, _, _, command = self._split(t, x, u)
        return np.concatenate([np.asarray(self._plant_functions()[1](t, xp, up), dtype=float), command])

    def compiled_rhs(self):
        """The loop compiled by numba for ``simulate(..., backend="compiled")`` (see :meth:`vehdyn.Model.compiled_rhs`).

        Compiled when both the plant and the controller have a compiled rhs and the controller a
        compiled output (the SingleTrack and FullVehicle with their compiled tire laws; ABS,
        TractionControl, ESC; the drivers of :mod:`vehdyn.driver`; an inner ClosedLoop of those):
        the same sequence as :meth:`rhs`, with the controllers' laws from the same source
        (:mod:`vehdyn.interconnect._compiled_loop`). None otherwise, so that ``backend="auto"``
        runs numpy; the plant's :class:`~vehdyn.ParameterError` (a configuration without a
        compiled form) passes through.

        Returns
        -------
        vehdyn.simulation.compiled.CompiledModel or None
            The compiled rhs and output, their key and their arguments.
        """
        from vehdyn.interconnect import _compiled_loop

        return _compiled_loop.compiled_loop(self)

    def __repr__(self) -> str:
        return f"<ClosedLoop {type(self.controller).__name__} around {self.plant!r}>"


class Controller(Model):
    r"""Base of the controllers: a ``Model`` whose outputs command a plant's inputs.

    A controller reads demands :math:`d` (loop inputs named like plant inputs) and feedback
    (plant states and outputs, by name) and commands plant inputs, :math:`\dot x_c = f_c(t, x_c,
    u_c)`, :math:`y_c = h_c(t, x_c, u_c)`; :meth:`close` puts it in the loop with a plant
    (:class:`ClosedLoop`, whose docstring gives the equations of the loop). The drivers
    (:mod:`vehdyn.driver`) and the chassis controllers (:mod:`vehdyn.chassis`) derive from it.

    .. math::

        u_p = P u + S h_c(t, x_c, u_c)

    References
    ----------
    .. [1] K. J. Åström and R. M. Murray, *Feedback Systems*, 2nd ed., Princeton University Press,
       2021, sec. 3.3 (controller and process in a feedback loop).
    """

    def close(self, plant: Model) -> ClosedLoop:
        """The closed loop of ``plant`` with this controller.

        Parameters
        ----------
        plant : Model
            The model whose inputs this controller commands (a vehicle model or a ClosedLoop).

        Returns
        -------
        ClosedLoop
            ``ClosedLoop(plant, self)``; a :class:`~vehdyn.ParameterError` names the signals the
            plant lacks.
        """
        return ClosedLoop(plant, self)
