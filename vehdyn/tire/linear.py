"""The linear tire: forces proportional to slip, optionally to load.

::

    F_x = C_kappa kappa f_z sign(vx),   F_y = (-C_alpha alpha + C_gamma gamma) f_z,   M_z = -t F_y sign(vx)

with ``f_z = F_z / F_z0`` when a nominal load ``F_z0`` is given (constant cornering and slip
*coefficients* ``C / F_z``, Pacejka 2012, ch. 1), else ``f_z = 1`` for a loaded tire; ``f_z = 0`` when ``F_z <= 0`` (lift-off).
ISO-W signs (:mod:`vehdyn.conventions`): a positive slip angle makes a negative side force; in
reverse ``kappa`` keeps MFeval's meaning (``-V_sx / V_x``, see :mod:`vehdyn.tire.slip`) and
``sign(vx)`` (+1 at standstill) flips ``F_x`` and ``M_z``.

The linear tire has no friction limit: it is valid for small slips only, roughly where the
lateral acceleration stays below about half the friction limit (Pacejka 2012, ch. 1).

References
----------
H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, ch. 1 (cornering stiffness, slip
stiffness, pneumatic trail). R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., 2012, ch. 2
(linear lateral tire model).
"""

from __future__ import annotations

import dataclasses

from vehdyn.params.base import ParameterSet, parameter
from vehdyn.tire._common import VectorizedTire, planar_forces
from vehdyn.tire._mf_ops import NumpyOps, ScalarOps
from vehdyn.tire.base import TireForces

__all__ = ["LinearTire", "linear_tire_law"]


def linear_tire_law(xp, coefficients, fz, kappa, alpha, gamma, vx):
    """``(F_x, F_y, M_z)`` [N, N, N m] of the linear law (module docstring), ISO-W.

    Written against the array namespace ``xp`` (:mod:`vehdyn.tire.kernels`), so that numpy arrays,
    Python floats and numba-compiled callers (:mod:`vehdyn.tire.compiled`) run this one source.

    Parameters
    ----------
    xp : namespace
        ``NumpyOps``, ``ScalarOps`` or a compiled equivalent.
    coefficients : tuple of float
        ``(C_alpha [N/rad], C_kappa [N], C_gamma [N/rad], t [m], F_z0 [N] or 0 for no load scaling)``
        (:attr:`LinearTire.coefficients`).
    fz, kappa, alpha, gamma, vx
        Normal load [N] (negative counts as 0), slip ratio [-], slip angle [rad], inclination [rad],
        forward speed [m/s].

    Returns
    -------
    tuple
        (F_x [N], F_y [N], M_z [N*m]), ISO-W.
    """
    cornering, slip, camber, trail, nominal = coefficients
    fz = xp.maximum(fz, 0.0)
    if nominal > 0.0:
        scale = fz / nominal
    else:
        scale = xp.where(fz > 0.0, 1.0, 0.0)
    direction = xp.where(vx < 0.0, -1.0, 1.0)  # +1 at standstill: the side the patch is entered from
    fy = (camber * gamma - cornering * alpha) * scale
    fx = slip * kappa * scale * direction
    return fx, fy, -trail * fy * direction


@dataclasses.dataclass(frozen=True, kw_only=True)
class LinearTire(ParameterSet, VectorizedTire):
    r"""Linear tire: forces proportional to slip, optionally to load.

    .. math::

        F_x = C_\kappa \kappa f_z \operatorname{sgn} V_x, \qquad
        F_y = (-C_\alpha \alpha + C_\gamma \gamma) f_z, \qquad
        M_z = -t F_y \operatorname{sgn} V_x

    with :math:`f_z = F_z / F_{z0}` when a nominal load is given (constant cornering and slip
    *coefficients*), else 1 for a loaded tire; :math:`f_z = 0` for :math:`F_z \le 0` (lift-off);
    sgn V_x = +1 at standstill. ISO-W axes and inputs (``forces(fz, kappa, alpha, gamma, vx)``,
    :meth:`vehdyn.tire.TireModel.forces`): a positive slip angle makes a negative side force.
    No friction limit: valid for small slips, roughly while the lateral acceleration stays below
    about half the friction limit.

    Parameters
    ----------
    cornering_stiffness : float
        ``C_alpha = -dF_y/dalpha`` [N/rad] (a positive magnitude), at ``nominal_load`` if given.
    slip_stiffness : float, optional
        ``C_kappa = dF_x/dkappa`` [N]; ``None`` uses ``cornering_stiffness`` (the isotropic brush value).
    camber_stiffness : float
        ``C_gamma = dF_y/dgamma`` [N/rad], ISO-W, signed; default 0.
    pneumatic_trail : float
        ``t`` [m]: ``M_z = -t F_y`` when rolling forwards; default 0.
    nominal_load : float, optional
        ``F_z0`` [N]: when given the stiffnesses scale with ``F_z / F_z0``.

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012,
       ch. 1 (cornering stiffness, longitudinal slip stiffness, pneumatic trail).
    .. [2] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, ch. 2 (the linear
       lateral tire model).

    Examples
    --------
    >>> from vehdyn.tire import LinearTire
    >>> tire = LinearTire(cornering_stiffness=60000.0, pneumatic_trail=0.03, nominal_load=4000.0)
    >>> out = tire.forces(fz=4000.0, kappa=0.0, alpha=0.02)        # [N], [-], [rad]
    >>> out.fy, out.mz                                             # -C_alpha alpha [N], -t F_y [N m]
    (-1200.0, 36.0)
    >>> tire.forces(fz=2000.0, kappa=0.05, alpha=0.0).fx            # C_kappa kappa F_z / F_z0 [N]
    1500.0
    """

    cornering_stiffness: float = parameter("N/rad", "C_alpha: cornering stiffness", gt=0)
    slip_stiffness: float | None = parameter("N", "C_kappa: longitudinal slip stiffness (None: cornering_stiffness)",
                                             default=None, gt=0)
    camber_stiffness: float = parameter("N/rad", "C_gamma: camber stiffness dFy/dgamma (ISO-W)", default=0.0)
    pneumatic_trail: float = parameter("m", "pneumatic trail t", default=0.0, ge=0)
    nominal_load: float | None = parameter("N", "F_z0: load at which the stiffnesses are given (None: no scaling)",
                                           default=None, gt=0)

    name = "linear"

    @property
    def longitudinal_stiffness(self) -> float:
        """``C_kappa`` [N]: ``slip_stiffness`` or, when not given, ``cornering_stiffness``."""
        return self.cornering_stiffness if self.slip_stiffness is None else self.slip_stiffness

    @classmethod
    def from_vehicle(cls, vehicle, axle: str = "front") -> "LinearTire":
        """A linear tire for one wheel of a vehicle's axle (see :func:`vehdyn.tire.tire_for_vehicle`).

        Parameters
        ----------
        vehicle : vehdyn.Vehicle
            The vehicle.
        axle : {"front", "rear"}
            The axle.

        Returns
        -------
        LinearTire
            Half the axle's cornering stiffness, scaled with load about the static wheel load
            (``nominal_load``); slip stiffness equal to it, no camber stiffness, no trail.
        """
        from vehdyn.tire.registry import vehicle_tire_data

        data = vehicle_tire_data(vehicle, axle)
        return cls(cornering_stiffness=data.cornering_stiffness, nominal_load=data.static_load)

    @property
    def coefficients(self) -> tuple:
        """``(C_alpha, C_kappa, C_gamma, t, F_z0 or 0)``: the numbers :func:`linear_tire_law` reads."""
        return (float(self.cornering_stiffness), float(self.longitudinal_stiffness), float(self.camber_stiffness),
                float(self.pneumatic_trail), 0.0 if self.nominal_load is None else float(self.nominal_load))

    def _kernel(self, fz, kappa, alpha, gamma, vx):
        """``(F_x, F_y, M_z)`` for float arrays of one shape."""
        return linear_tire_law(NumpyOps, self.coefficients, fz, kappa, alpha, gamma, vx)

    def _forces_scalar(self, fz: float, kappa: float, alpha: float, gamma: float, vx: float) -> TireForces:
        """The same equations for one point (no numpy overhead)."""
        fx, fy, mz = linear_tire_law(ScalarOps, self.coefficients, fz, kappa, alpha, gamma, vx)
        return planar_forces(fx, fy, max(fz, 0.0), mz)
