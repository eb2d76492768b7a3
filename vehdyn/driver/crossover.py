"""McRuer's crossover-model driver: a gain on the previewed path error, a delay, a neuromuscular lag."""

from __future__ import annotations
from vehdyn.model import Model
from vehdyn.driver.base import _PathDriver
from vehdyn.driver.loop_analysis import driver_loop_response
import numpy as np
from vehdyn.driver.base import preview_offsets

__all__ = ["CrossoverDriver"]


class CrossoverDriver(_PathDriver):
    """McRuer's crossover-model driver: a gain on the previewed path error, a delay, a neuromuscular lag.

    The driver reads the lateral offset e of the path from the point d = max(u T_p, d_min) ahead
    (:func:`preview_offsets`) and steers the front wheels through a pure delay tau and a
    first-order neuromuscular lag T_N::

        delta(s) = K_p e^(-tau s) / (T_N s + 1) e(s)

    The preview is the driver's lead equalization: to the lateral position y of a car (about a
    double integrator of the steer at low frequency, Y_c ~ K / s^2) the preview point adds
    d psi, a lead of time constant about d / u = T_p, so that near the crossover frequency omega_c
    the open loop takes McRuer's form Y_p Y_c ~ omega_c e^(-tau_e s) / s, tau_e ~ tau + T_N: phase
    margin pi/2 - omega_c tau_e, stable for omega_c tau_e < pi/2 (McRuer & Jex, "A review of
    quasi-linear pilot models", IEEE Trans. HFE 8(3), 1967; McRuer et al., "New results in driver
    steering control models", Human Factors 19(4), 1977). :meth:`tuned` sets K_p for a
    crossover frequency on a given car, as the human adapts (McRuer's adjustment rule).

    Parameters
    ----------
    path_x, path_y : array_like
        Desired CG path in earth axes [m] (SAE, y right), x strictly increasing.
    gain : float
        K_p [rad/m] > 0 (road-wheel steer per metre of previewed error).
    preview_time : float
        T_p [s] > 0 (default 1.0).
    delay : float
        tau [s] >= 0 (default 0.15; McRuer's effective delays are 0.1-0.3 s), through a
        Pade approximant of order ``pade_order`` (default 3) in time-domain runs.
    neuromuscular_lag : float
        T_N [s] > 0 (default 0.1).
    minimum_preview_distance : float
        d_min [m] (default 3).
    max_steer_angle : float
        Limit of the command [rad] (default 0.6).

    Signals
    -------
    Inputs (feedback, read from the plant's states by ClosedLoop): ``x``, ``y``, ``yaw_angle``,
    ``longitudinal_velocity``. States: ``driver_delay_1..n``, ``driver_steer_angle``. Output:
    ``front_steer_angle``.
    """

    _gain_names = ("gain",)

    def __init__(self, path_x, path_y, *, gain: float, preview_time: float = 1.0, delay: float = 0.15,
                 neuromuscular_lag: float = 0.1, minimum_preview_distance: float = 3.0,
                 max_steer_angle: float = 0.6, pade_order: int = 3):
        self._setup(path_x, path_y, delay=delay, neuromuscular_lag=neuromuscular_lag, preview_time=preview_time,
                    minimum_preview_distance=minimum_preview_distance, max_steer_angle=max_steer_angle,
                    pade_order=pade_order, gain=gain)

    def command(self, t, s, steer):
        distance = self.preview_distance(s["longitudinal_velocity"])
        return self.gain * preview_offsets(self.path_x, self.path_y, s["x"], s["y"], s["yaw_angle"], distance)

    def perception(self, speed) -> dict:
        return {"y": self.gain, "yaw_angle": self.gain * float(self.preview_distance(speed))}

    @classmethod
    def tuned(cls, plant: Model, speed: float, path_x, path_y, *, crossover_frequency: float = 2.5, **options):
        """The driver whose open loop with ``plant`` at ``speed`` [m/s] crosses over at ``crossover_frequency`` [rad/s].

        K_p = 1 / |L_1(j omega_c)| with L_1 the loop at unit gain (McRuer's adjustment of the
        gain to the controlled element; the default 2.5 rad/s is within the 2-4 rad/s that
        McRuer et al. 1977 report for lane keeping). ``options`` are the other parameters.
        """
        from vehdyn.params.checks import check_gains

        wc = check_gains(cls.__name__, positive=("crossover_frequency",),
                         crossover_frequency=crossover_frequency)["crossover_frequency"]
        unit = cls(path_x, path_y, gain=1.0, **options)
        loop = driver_loop_response(plant, unit, speed, np.array([wc]))
        return cls(path_x, path_y, gain=1.0 / abs(loop[0]), **options)
