"""Transient handling: ISO 7401 step-steer metrics, the yaw mode and steering frequency responses.

Step-steer metrics (ISO 7401:2011, *Road vehicles - Lateral transient response test methods*,
sec. 9.2; Abe, *Vehicle Handling Dynamics*, 2009, sec. 4.2) are computed from the time histories
of any :class:`~vehdyn.SimulationResult` (a linear bicycle, a lateral-yaw-roll model, a nonlinear
single track, a measurement), vectorized over a batch:

* time origin: the instant the steer signal passes 50 % of its change;
* steady-state value: the mean over the last ``steady_window`` seconds;
* response time: from the origin to the first time the response reaches 90 % of its steady-state
  change; rise time: 10 % to 90 %;
* peak response time and peak value: the first maximum (in the direction of the steady state),
  refined by a parabola through the three samples around it;
* overshoot: (peak - steady) / steady.

The yaw mode of the 2-DOF bicycle model (characteristic polynomial s^2 + 2 zeta w_n s + w_n^2;
Abe 2009 eq. 4.9-4.10; Mitschke & Wallentowitz, *Dynamik der Kraftfahrzeuge*, 2014, sec. 25.3)::

    w_n^2        = C_f C_r L^2 / (m I_z u^2) + (C_r b - C_f a) / I_z
    2 zeta w_n   = (C_f + C_r) / (m u) + (C_f a^2 + C_r b^2) / (I_z u)
    r / delta_f  = (C_f a / I_z s + C_f C_r L / (m I_z u)) / (s^2 + 2 zeta w_n s + w_n^2)
    a_y/delta_f  = (C_f / m s^2 + C_f C_r b L / (m I_z u) s + C_f C_r L / (m I_z)) / (same)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vehdyn.handling.bicycle import LinearBicycle, bicycle_parameters, speed_of

__all__ = [
    "YawMode",
    "yaw_mode",
    "yaw_rate_transfer_function",
    "lateral_acceleration_transfer_function",
    "steering_frequency_response",
]


# --------------------------------------------------------------------------- yaw mode
@dataclass(frozen=True)
class YawMode:
    """The coupled sideslip/yaw mode of the 2-DOF bicycle model against speed.

    Attributes
    ----------
    speed : ndarray
        [m/s].
    natural_frequency_squared : ndarray
        w_n^2 [rad^2/s^2] (negative above the critical speed of an oversteering vehicle).
    natural_frequency : ndarray
        w_n [rad/s] (NaN where w_n^2 < 0).
    damping_ratio : ndarray
        zeta [-] (NaN where w_n^2 < 0; > 1 for two real eigenvalues).
    eigenvalues : ndarray of complex, shape (2,) + speed.shape
        Roots of s^2 + 2 zeta w_n s + w_n^2 [1/s]; the one with the larger real part first.
    """

    speed: np.ndarray
    natural_frequency_squared: np.ndarray
    natural_frequency: np.ndarray
    damping_ratio: np.ndarray
    eigenvalues: np.ndarray

    @property
    def natural_frequency_hz(self) -> np.ndarray:
        """w_n / (2 pi) [Hz]."""
        return self.natural_frequency / (2 * np.pi)

    @property
    def stable(self) -> np.ndarray:
        """True where both eigenvalues have negative real parts."""
        return np.all(self.eigenvalues.real < 0, axis=0)

    def to_frame(self):
        """The mode against speed as a table.

        Returns
        -------
        pandas.DataFrame
            Indexed by ``speed``; the natural frequency [rad/s and Hz], the damping ratio and the
            two eigenvalues' real and imaginary parts; units in ``attrs["units"]``.
        """
        import pandas as pd

        df = pd.DataFrame({
            "natural_frequency": np.ravel(self.natural_frequency),
            "natural_frequency_hz": np.ravel(self.natural_frequency_hz),
            "damping_ratio": np.ravel(self.damping_ratio),
            "eigenvalue_1_real": np.ravel(self.eigenvalues[0].real),
            "eigenvalue_1_imag": np.ravel(self.eigenvalues[0].imag),
            "eigenvalue_2_real": np.ravel(self.eigenvalues[1].real),
            "eigenvalue_2_imag": np.ravel(self.eigenvalues[1].imag),
        }, index=pd.Index(np.ravel(self.speed), name="speed"))
        df.attrs["units"] = {"speed": "m/s", "natural_frequency": "rad/s", "natural_frequency_hz": "Hz",
                             "damping_ratio": "-", "eigenvalue_1_real": "1/s", "eigenvalue_1_imag": "rad/s",
                             "eigenvalue_2_real": "1/s", "eigenvalue_2_imag": "rad/s"}
        return df


def _characteristic_polynomial(p, u):
    m, iz, a, b = p.mass, p.yaw_inertia, p.a, p.b
    cf, cr, L = p.front_cornering_stiffness, p.rear_cornering_stiffness, p.wheelbase
    wn2 = cf * cr * L**2 / (m * iz * u**2) + (cr * b - cf * a) / iz
    two_zeta_wn = (cf + cr) / (m * u) + (cf * a**2 + cr * b**2) / (iz * u)
    return wn2, two_zeta_wn


def yaw_mode(vehicle_or_bicycle, speed=None) -> YawMode:
    """Natural frequency, damping and eigenvalues of the yaw mode against speed (closed form).

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
    speed : float or array_like, optional
        [m/s]; defaults to the bicycle's.

    Returns
    -------
    YawMode
        For the 2-DOF model without tire lag (use ``LinearBicycle(..., tire_lag=True).modes()`` for
        the model with lag).
    """
    p = bicycle_parameters(vehicle_or_bicycle)
    u = speed_of(vehicle_or_bicycle, speed)
    wn2, c1 = _characteristic_polynomial(p, u)
    disc = np.sqrt((0.25 * c1**2 - wn2).astype(complex))
    eig = np.stack([-0.5 * c1 + disc, -0.5 * c1 - disc])
    with np.errstate(invalid="ignore"):
        wn = np.where(wn2 > 0, np.sqrt(np.abs(wn2)), np.nan)
        zeta = c1 / (2 * wn)
    return YawMode(speed=u, natural_frequency_squared=wn2, natural_frequency=wn, damping_ratio=zeta,
                   eigenvalues=eig)


def yaw_rate_transfer_function(vehicle_or_bicycle, speed=None):
    r"""Yaw rate per unit front road-wheel steer angle of the 2-DOF bicycle model, as a transfer function.

    .. math::

        \frac{r}{\delta_f}(s) = \frac{\frac{C_f a}{I_z} s + \frac{C_f C_r L}{m I_z u}}
                                      {s^2 + 2 \zeta \omega_n s + \omega_n^2}

    with omega_n and zeta of :func:`yaw_mode` (module docstring; Abe 2009, sec. 4.2). Usable with
    ``control.tf(num, den)`` and ``scipy.signal.freqs``.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (see :func:`~vehdyn.handling.bicycle_parameters`).
    speed : float, optional
        Forward speed u [m/s], > 0; defaults to the bicycle's.

    Returns
    -------
    numerator, denominator : ndarray
        Polynomial coefficients in s, highest power first; the gain at s = 0 is r / delta_f [1/s].
    """
    p = bicycle_parameters(vehicle_or_bicycle)
    u = float(speed_of(vehicle_or_bicycle, speed))
    wn2, c1 = _characteristic_polynomial(p, u)
    cf, cr, L, m, iz = p.front_cornering_stiffness, p.rear_cornering_stiffness, p.wheelbase, p.mass, p.yaw_inertia
    return np.array([cf * p.a / iz, cf * cr * L / (m * iz * u)]), np.array([1.0, c1, wn2])


def lateral_acceleration_transfer_function(vehicle_or_bicycle, speed=None):
    r"""Lateral acceleration per unit front road-wheel steer angle of the 2-DOF bicycle model.

    .. math::

        \frac{a_y}{\delta_f}(s) = \frac{\frac{C_f}{m} s^2 + \frac{C_f C_r b L}{m I_z u} s
                                          + \frac{C_f C_r L}{m I_z}}
                                         {s^2 + 2 \zeta \omega_n s + \omega_n^2}

    (module docstring; Abe 2009, sec. 4.2).

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
        The vehicle (see :func:`~vehdyn.handling.bicycle_parameters`).
    speed : float, optional
        Forward speed u [m/s], > 0; defaults to the bicycle's.

    Returns
    -------
    numerator, denominator : ndarray
        Polynomial coefficients in s, highest power first; the gain at s = 0 is a_y / delta_f
        [(m/s^2)/rad].
    """
    p = bicycle_parameters(vehicle_or_bicycle)
    u = float(speed_of(vehicle_or_bicycle, speed))
    wn2, c1 = _characteristic_polynomial(p, u)
    cf, cr, L, m, iz = p.front_cornering_stiffness, p.rear_cornering_stiffness, p.wheelbase, p.mass, p.yaw_inertia
    return np.array([cf / m, cf * cr * p.b * L / (m * iz * u), cf * cr * L / (m * iz)]), np.array([1.0, c1, wn2])


def steering_frequency_response(vehicle_or_bicycle, omega, speed=None, *,
                                outputs=("yaw_rate", "lateral_acceleration", "sideslip_angle"),
                                tire_lag: bool = False):
    """Frequency response of the bicycle model to the front road-wheel steer angle.

    Parameters
    ----------
    vehicle_or_bicycle : Vehicle, LinearBicycle or BicycleParameters
    omega : array_like
        Angular frequencies [rad/s].
    speed : float, optional
        [m/s]; defaults to the bicycle's.
    outputs : sequence of str
        Outputs of :class:`LinearBicycle`.
    tire_lag : bool
        Include tire lag (ignored for a LinearBicycle, which keeps its own states).

    Returns
    -------
    FrequencyResponse
        ``fr["yaw_rate", "front_steer_angle"]`` etc.
    """
    if isinstance(vehicle_or_bicycle, LinearBicycle) and (speed is None or speed == vehicle_or_bicycle.speed):
        model = vehicle_or_bicycle
    else:
        if isinstance(vehicle_or_bicycle, LinearBicycle):
            model = vehicle_or_bicycle.at_speed(float(speed_of(vehicle_or_bicycle, speed)))
        else:
            model = LinearBicycle(vehicle_or_bicycle, float(speed_of(vehicle_or_bicycle, speed)), tire_lag=tire_lag)
    return model.frequency_response(omega, outputs=list(outputs), inputs=["front_steer_angle"])
