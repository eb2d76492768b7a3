"""The realizability of an inertia tensor: the one check of every inertia tensor in the package.

A symmetric tensor is the inertia tensor of some mass distribution exactly when its principal
moments are non-negative and satisfy the triangle inequalities (each at most the sum of the
other two).

References
----------
.. [1] H. Goldstein, C. Poole and J. Safko, *Classical Mechanics*, 3rd ed., 2002, sec. 5.4
   (the inertia tensor and its principal moments).
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["check_realizable", "relative_tolerance"]


def relative_tolerance(scale):
    """Slack for equalities that hold exactly only in exact arithmetic (thin plate: Izz = Ixx + Iyy).

    Parameters
    ----------
    scale : float or ndarray
        Size of the quantities compared, e.g. the trace of the tensor [kg m^2].

    Returns
    -------
    float or ndarray
        1e-12 times ``scale`` (at least the smallest normal float) [kg m^2].
    """
    return 1e-12 * np.maximum(scale, np.finfo(float).tiny)


_MOMENTS = ("ixx", "iyy", "izz")
_PRODUCTS = "ixy, ixz, iyz"


def check_realizable(matrix, *, definite: bool = False, key: str | None = None) -> None:
    """Raise :class:`ParameterError` unless ``matrix`` is the inertia tensor of some mass distribution.

    The one check of every inertia tensor in the package: the vehicle's mass group
    (:class:`vehdyn.params.MassAndInertia`, the ``[mass]`` table of a vehicle file) and
    :mod:`vehdyn.mechanics` (its :class:`~vehdyn.mechanics.InertiaTensor`,
    :class:`~vehdyn.mechanics.MassProperties`, :func:`~vehdyn.mechanics.inertia_matrix`,
    :class:`~vehdyn.mechanics.RigidBody6DOF` and :func:`~vehdyn.mechanics.newton_euler`). A symmetric
    tensor is realizable exactly when its principal moments are non-negative and satisfy the
    triangle inequalities (each <= the sum of the other two); then so do the moments about any
    axes. Checked in order: the moments about the given axes (the clearest message), positive
    (semi-)definiteness, the principal moments. Equalities (a thin plate, Izz = Ixx + Iyy) pass
    within 1e-12 of the trace.

    Parameters
    ----------
    matrix : ndarray, shape (3, 3) or (3, 3, n)
        Symmetric, finite tensor (off-diagonal entries -Ixy, -Ixz, -Iyz) [kg m^2], with an optional
        batch axis.
    definite : bool
        Require a positive-definite tensor (a rigid body's dynamics invert it; a point mass or a
        slender rod, accepted as parts of a composite, is singular).
    key : str, optional
        The parameter the error names (default: the offending entry, ``ixx``/``iyy``/``izz`` or
        ``"ixy, ixz, iyz"``).
    """
    mat = np.asarray(matrix, dtype=float)
    stacked = mat.reshape(3, 3, -1)
    moments = np.einsum("iik->ik", stacked)  # (3, n)
    slack = relative_tolerance(np.abs(moments.sum(axis=0)))

    def fail(bad, message, entry, value):
        k = int(np.argmax(bad))
        where = f" (batch member {k})" if mat.ndim == 3 else ""
        products = (0.0 - stacked[0, 1, k], 0.0 - stacked[0, 2, k], 0.0 - stacked[1, 2, k])
        raise ParameterError(f"inertia tensor{where} " + message(k, products), key=key or entry,
                             value=value(k, products))

    for i, j, l in ((2, 0, 1), (0, 1, 2), (1, 2, 0)):
        bad = moments[i] > moments[j] + moments[l] + slack
        if np.any(bad):
            fail(bad, lambda k, _: (f"violates the triangle inequality {_MOMENTS[j]} + {_MOMENTS[l]} >= {_MOMENTS[i]}: "
                                    f"{moments[j, k]:g} + {moments[l, k]:g} < {moments[i, k]:g} [kg*m^2]; no mass "
                                    "distribution has these moments"),
                 _MOMENTS[i], lambda k, _: float(moments[i, k]))
    principal = np.linalg.eigvalsh(np.moveaxis(stacked, -1, 0))  # (n, 3), ascending
    if definite:
        bad = principal[:, 0] <= slack
        kind = ("positive definite", "the products of inertia are too large for the moments"
                if np.any(principal[:, 0] < -slack) else
                "a rigid body needs moments about every axis (a point mass or slender rod alone has none about "
                "some axis)")
    else:
        bad = principal[:, 0] < -slack
        kind = ("positive semi-definite", "the products of inertia are too large for the moments")
    if np.any(bad):
        fail(bad, lambda k, p: (f"is not {kind[0]} (principal moments {principal[k].tolist()} kg*m^2; products "
                                f"ixy={p[0]:g}, ixz={p[1]:g}, iyz={p[2]:g}): {kind[1]}"),
             _PRODUCTS, lambda k, p: p if key is None else float(principal[k, 0]))
    bad = principal[:, 2] > principal[:, 0] + principal[:, 1] + slack
    if np.any(bad):
        fail(bad, lambda k, p: (f"has principal moments {principal[k].tolist()} kg*m^2 that violate the triangle "
                                f"inequality (largest <= sum of the other two; products ixy={p[0]:g}, ixz={p[1]:g}, "
                                f"iyz={p[2]:g}); no mass distribution has them"),
             _PRODUCTS, lambda k, p: p if key is None else principal[k].tolist())
