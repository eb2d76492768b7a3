"""A road profile (elevation along a track, one or two tracks) and discrete road events: bumps,
potholes, speed humps and steps."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.checks import positive_number as _positive

__all__ = ["RoadProfile", "bump", "pothole", "speed_hump", "step"]


@dataclass(frozen=True)
class RoadProfile:
    """A road elevation profile on a uniform distance grid.

    Attributes
    ----------
    distance : ndarray
        Longitudinal position x [m], uniformly spaced.
    elevation : ndarray
        Road elevation z(x) [m] (positive up).
    coefficients : ndarray or None
        For synthesized profiles: the complex Fourier coefficients c_i [m] of
        z(x) = Re sum c_i e^(j 2 pi n_i x), n_i = i / length, so that shifts and slopes are exact
        (spectral).

    Raises
    ------
    ParameterError
        If the arrays are not 1-D of equal length >= 2, the distance is not uniformly spaced and
        increasing, or an elevation is not finite.

    Examples
    --------
    >>> import numpy as np
    >>> from vehdyn.road import RoadProfile, bump
    >>> x = np.arange(0.0, 20.0, 0.01)
    >>> road = RoadProfile(x, bump(x, position=5.0, length=2.0, height=0.05))
    >>> z, slope = road.sample([6.0, 7.5])            # at the crest, and beyond the bump
    >>> z.tolist(), slope.tolist()
    ([0.05, 0.0], [0.0, 0.0])
    """

    distance: np.ndarray
    elevation: np.ndarray
    coefficients: np.ndarray | None = field(default=None, repr=False)

    def __post_init__(self):
        x = np.asarray(self.distance, dtype=float)
        z = np.asarray(self.elevation, dtype=float)
        if x.ndim != 1 or x.size < 2 or z.shape != x.shape:
            raise ParameterError(f"distance and elevation must be 1-D arrays of equal length >= 2, got {x.shape} and "
                                 f"{z.shape}", key="elevation", value=z.shape)
        dx = np.diff(x)
        if np.any(dx <= 0) or not np.allclose(dx, dx[0], rtol=1e-6, atol=0):
            raise ParameterError("distance must be uniformly spaced and increasing", key="distance", value=dx[0])
        if not np.all(np.isfinite(z)):
            raise ParameterError("elevation contains non-finite values", key="elevation", value=z[~np.isfinite(z)][0])
        object.__setattr__(self, "distance", x)
        object.__setattr__(self, "elevation", z)

    @property
    def spacing(self) -> float:
        """Sample spacing [m]."""
        return float(self.distance[1] - self.distance[0])

    @property
    def length(self) -> float:
        """Length [m] (number of samples times spacing: the period of a synthesized profile)."""
        return self.distance.size * self.spacing

    def __add__(self, other: "RoadProfile | np.ndarray") -> "RoadProfile":
        z = other.elevation if isinstance(other, RoadProfile) else np.asarray(other, dtype=float)
        return RoadProfile(self.distance, self.elevation + z)

    def slope(self) -> np.ndarray:
        """The profile's slope on its grid.

        Returns
        -------
        ndarray
            dz/dx [-]: spectral (exact) for synthesized profiles, else central differences.
        """
        if self.coefficients is not None:
            return self._spectral(1j * 2.0 * np.pi * self._frequencies())
        return np.gradient(self.elevation, self.spacing)

    def shifted(self, offset: float) -> "RoadProfile":
        """The profile seen by a wheel behind the reference point.

        Parameters
        ----------
        offset : float
            Distance behind the reference [m].

        Returns
        -------
        RoadProfile
            z(x - offset) on the same grid: exact for synthesized profiles (the sum of cosines is
            evaluated shifted), linear interpolation otherwise, holding the first value before
            the start.
        """
        if self.coefficients is not None:
            c = self.coefficients * np.exp(-2j * np.pi * self._frequencies() * offset)
            return RoadProfile(self.distance, self._spectral(1.0, c), c)
        z = np.interp(self.distance - offset, self.distance, self.elevation)
        return RoadProfile(self.distance, z)

    def sample(self, position):
        """Elevation and slope at any positions.

        Parameters
        ----------
        position : array_like
            Positions x [m].

        Returns
        -------
        elevation : ndarray
            z [m], linearly interpolated between the grid values, held before the start and
            after the end.
        slope : ndarray
            dz/dx [-], interpolated from :meth:`slope` (spectral for synthesized profiles,
            central differences otherwise); zero outside the profile.
        """
        pos = np.asarray(position, dtype=float)
        z = np.interp(pos, self.distance, self.elevation)
        inside = (pos >= self.distance[0]) & (pos <= self.distance[-1])
        return z, np.where(inside, np.interp(pos, self.distance, self.slope()), 0.0)

    def road_inputs(self, speed: float, offsets: dict[str, float] | None = None, time=None):
        """Time grid and ride-model inputs for driving over the profile at ``speed`` [m/s].

        The one implementation of "the road under each wheel" (exact delay in the time domain):
        :func:`vehdyn.ride.road_inputs` calls it with the wheel positions of a ride model.

        Parameters
        ----------
        speed : float
            V [m/s] (constant).
        offsets : dict, optional
            ``{suffix: distance behind the first axle [m]}``, e.g. ``{"_front": 0.0, "_rear": 2.7}``;
            default ``{"": 0.0}`` (inputs ``road_displacement`` and ``road_velocity``).
        time : array_like, optional
            Time grid [s]; default the profile's own grid, t = (x - x_0) / V.

        Returns
        -------
        time : ndarray
            [s]; at t the first axle is at x_0 + V t, a wheel ``offset`` behind it at
            x_0 + V t - offset.
        inputs : dict
            ``road_displacement<suffix>`` [m] and ``road_velocity<suffix>`` = V dz/dx [m/s] for each
            suffix, ready for :func:`vehdyn.simulate`. On the profile's own grid a synthesized
            profile is shifted exactly (:meth:`shifted`); otherwise the profile is sampled by
            :meth:`sample` (linear interpolation, elevation held beyond the ends).
        """
        V = _positive(speed, "speed")
        offsets = {"": 0.0} if offsets is None else offsets
        own_grid = time is None
        t = (self.distance - self.distance[0]) / V if own_grid else np.asarray(time, dtype=float)
        inputs = {}
        for suffix, off in offsets.items():
            if own_grid and (off == 0 or self.coefficients is not None):
                p = self if off == 0 else self.shifted(off)
                z, slope = p.elevation, p.slope()
            else:
                z, slope = self.sample(self.distance[0] + V * t - off)
            inputs[f"road_displacement{suffix}"] = z
            inputs[f"road_velocity{suffix}"] = V * slope
        return t, inputs

    def _frequencies(self) -> np.ndarray:
        return np.arange(self.coefficients.size) / self.length

    def _spectral(self, factor, coefficients=None) -> np.ndarray:
        c = (self.coefficients if coefficients is None else coefficients) * factor
        N = self.distance.size
        X = np.zeros(N // 2 + 1, dtype=complex)
        X[: c.size] = c * N / 2.0
        phase0 = np.exp(2j * np.pi * self._frequencies()[: c.size] * self.distance[0])
        X[: c.size] *= phase0
        return np.fft.irfft(X, N)


def _window(x, position, length):
    x = np.asarray(x, dtype=float)
    L = _positive(length, "length")
    return x, (x - float(position)) / L, L


def bump(x, position: float, length: float, height: float) -> np.ndarray:
    r"""Haversine (1 - cos) bump.

    .. math::

        z(x) = \frac{h}{2} \left(1 - \cos \frac{2 \pi (x - x_0)}{L}\right)
        \quad \text{on } [x_0, x_0 + L], \quad 0 \text{ elsewhere}

    Parameters
    ----------
    x : array_like
        Positions [m].
    position : float
        Start x0 of the bump [m].
    length : float
        Length L [m], > 0.
    height : float
        Height h [m] (negative for a dip).

    Returns
    -------
    ndarray
        Elevation z [m] at ``x``.
    """
    x, u, _ = _window(x, position, length)
    return np.where((u >= 0) & (u <= 1), 0.5 * float(height) * (1.0 - np.cos(2.0 * np.pi * u)), 0.0)


def pothole(x, position: float, length: float, depth: float, *, edge_length: float = 0.0) -> np.ndarray:
    """Pothole: a flat-bottomed depression.

    Parameters
    ----------
    x : array_like
        Positions [m].
    position : float
        Start of the pothole [m].
    length : float
        Length at the road surface [m], > 0.
    depth : float
        Depth [m], > 0.
    edge_length : float
        Length of each edge's half-cosine ramp [m], at most half the length (0: vertical edges,
        a step down and up).

    Returns
    -------
    ndarray
        Elevation z [m] at ``x`` (-depth at the bottom).
    """
    x, u, L = _window(x, position, length)
    d = _positive(depth, "depth")
    e = _positive(edge_length, "edge_length", allow_zero=True)
    if 2 * e > L:
        raise ParameterError(f"edge_length = {e} m is more than half the pothole length {L} m",
                             key="edge_length", value=e)
    s = (x - float(position))
    if e == 0:
        return np.where((s >= 0) & (s < L), -d, 0.0)
    down = 0.5 * (1 - np.cos(np.pi * np.clip(s / e, 0, 1)))
    up = 0.5 * (1 - np.cos(np.pi * np.clip((L - s) / e, 0, 1)))
    return -d * np.minimum(down, up) * ((s >= 0) & (s <= L))


def speed_hump(x, position: float, length: float = 3.7, height: float = 0.1, *, shape: str = "circular") -> np.ndarray:
    """Road hump: a circular arc (default; the 3.7 m x 100 mm round-top hump) or a sinusoid.

    Parameters
    ----------
    x : array_like
        Positions [m].
    position : float
        Start of the hump [m].
    length : float
        Length L [m] (default 3.7).
    height : float
        Height h [m] (default 0.1), > 0.
    shape : {"circular", "sinusoidal"}
        ``"circular"``: the arc of a circle through both ends and the crest, radius
        R = (L^2/4 + h^2) / (2 h). ``"sinusoidal"``: the (1 - cos) :func:`bump` of the same
        length and height.

    Returns
    -------
    ndarray
        Elevation z [m] at ``x``.

    References
    ----------
    .. [1] G. R. Watts, *Road humps for the control of vehicle speeds*, TRRL Laboratory Report
       597, Transport and Road Research Laboratory, 1973 (the 3.7 m round-top hump).
    """
    if shape == "sinusoidal":
        return bump(x, position, length, height)
    if shape != "circular":
        raise ParameterError(f"shape must be 'circular' or 'sinusoidal', got {shape!r}", key="shape", value=shape)
    x, u, L = _window(x, position, length)
    h = _positive(height, "height")
    R = (L**2 / 4.0 + h**2) / (2.0 * h)
    xc = float(position) + L / 2.0
    inside = (u >= 0) & (u <= 1)
    return np.where(inside, np.sqrt(np.maximum(R**2 - (x - xc) ** 2, 0.0)) - (R - h), 0.0)


def step(x, position: float, height: float) -> np.ndarray:
    """Step in the road.

    Parameters
    ----------
    x : array_like
        Positions [m].
    position : float
        Where the step is [m].
    height : float
        Height [m] (negative for a step down).

    Returns
    -------
    ndarray
        Elevation z [m] at ``x``: 0 before ``position``, ``height`` from it on.
    """
    x = np.asarray(x, dtype=float)
    return np.where(x >= float(position), float(height), 0.0)


# --------------------------------------------------------------------------- IRI
