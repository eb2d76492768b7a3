"""Series connection of two linear models by signal names."""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import LinearModel

__all__ = ["connect_in_series"]


def connect_in_series(upstream: LinearModel, downstream: LinearModel, connections=None, *, name=None) -> LinearModel:
    """Feed outputs of ``upstream`` into inputs of ``downstream``.

    Parameters
    ----------
    upstream, downstream : LinearModel
    connections : mapping of str to str, optional
        ``{downstream_input: upstream_output}``; by default every downstream input that shares a
        name with an upstream output is connected.
    name : str, optional
        Name of the result (default ``"<upstream> -> <downstream>"``).

    Returns
    -------
    LinearModel
        States: upstream's then downstream's. Inputs: upstream's, then the downstream inputs left
        unconnected. Outputs: downstream's, then upstream's outputs whose names are not taken.
        This is how a road shaping filter is appended to a ride model.
    """
    if connections is None:
        connections = {i: i for i in downstream.input_names if i in upstream.output_names}
    if not connections:
        raise ParameterError("connect_in_series: no input of downstream matches an output of upstream",
                             key="connections", value=None)
    n1, n2 = upstream.n_states, downstream.n_states
    conn_in = [downstream.index(i, "inputs") for i in connections]
    conn_out = [upstream.index(o, "outputs") for o in connections.values()]
    free_in = [k for k in range(downstream.n_inputs) if k not in conn_in]
    # downstream input vector = S @ y1 + T @ u_free
    S = np.zeros((downstream.n_inputs, upstream.n_outputs))
    S[conn_in, conn_out] = 1.0
    T = np.zeros((downstream.n_inputs, len(free_in)))
    T[free_in, range(len(free_in))] = 1.0
    A1, B1, C1, D1 = upstream.A, upstream.B, upstream.C, upstream.D
    A2, B2, C2, D2 = downstream.A, downstream.B, downstream.C, downstream.D
    A = np.block([[A1, np.zeros((n1, n2))], [B2 @ S @ C1, A2]])
    B = np.block([[B1, np.zeros((n1, len(free_in)))], [B2 @ S @ D1, B2 @ T]])
    keep_up = [k for k, o in enumerate(upstream.output_names) if o not in downstream.output_names]
    C = np.block([[D2 @ S @ C1, C2], [C1[keep_up], np.zeros((len(keep_up), n2))]])
    D = np.block([[D2 @ S @ D1, D2 @ T], [D1[keep_up], np.zeros((len(keep_up), len(free_in)))]])
    return LinearModel(
        A,
        B,
        C,
        D,
        states=upstream.states + downstream.states,
        inputs=upstream.inputs + tuple(downstream.inputs[k] for k in free_in),
        outputs=downstream.outputs + tuple(upstream.outputs[k] for k in keep_up),
        name=name or f"{upstream.name} -> {downstream.name}",
        phenomena=upstream.phenomena | downstream.phenomena,
    )
