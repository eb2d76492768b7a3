"""Ride analysis: labelled modes, pitch and bounce centres, Olley's flat-ride criteria, road responses.

* :func:`ride_modes` — natural frequencies (undamped, and of the damped model), damping ratios
  and mode shapes of any ride model, each mode labelled ``body bounce``, ``pitch``, ``roll`` or
  ``wheel hop`` (``wheel tramp`` for the left-right antiphase hop of an axle) by where its
  kinetic energy lies (Gillespie, *Fundamentals of Vehicle Dynamics*, 1992, ch. 5; Meirovitch,
  *Fundamentals of Vibrations*, 2001, sec. 7.4).
* :func:`bounce_pitch_centres` — the node (centre of rotation) of each body mode in the pitch
  plane, x = -z / theta ahead of the CG; the mode whose node lies farther from the CG (outside the
  wheelbase, normally) is the bounce mode, the other the pitch mode (Gillespie 1992, ch. 5,
  "Pitch/bounce"; Milliken & Milliken, *Race Car Vehicle Dynamics*, 1995, ch. 16). Also the
  spring (elastic) centre and the dynamic index I_y / (m a b).
* :func:`olley_criteria` — Olley's flat-ride guidelines as listed by Gillespie (1992, ch. 5):
  (1) the front ride rate about 30 % lower than the rear, or the spring centre at least 6.5 % of
  the wheelbase behind the CG; (2) pitch and bounce frequencies close, the bounce frequency below
  1.2 times the pitch frequency; (3) neither above 1.3 Hz; (4) the roll frequency about equal to
  the pitch and bounce frequencies.
* :func:`transmissibility`, :func:`suspension_travel_response`, :func:`dynamic_tire_load_response`
  — per unit road elevation, with the exact wheelbase delay when a speed is given (see
  :func:`vehdyn.ride.road_frequency_response`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vehdyn.model.modal import state_space_modes
from vehdyn.errors import ParameterError
from vehdyn.results import FrequencyResponse
from vehdyn.ride.wheelbase import road_frequency_response

__all__ = [
    "RideModes",
    "ride_modes",
    "BouncePitchCentres",
    "bounce_pitch_centres",
    "OlleyCheck",
    "olley_criteria",
    "axle_ride_rates",
    "transmissibility",
    "suspension_travel_response",
    "dynamic_tire_load_response",
]


def _require_ride_model(model):
    from vehdyn.ride._ride_model import RideModel

    if not isinstance(model, RideModel):
        raise ParameterError(f"expected a vehdyn.ride model (QuarterCar, BouncePitch, FullCar), got "
                             f"{type(model).__name__}", key="model", value=model)


@dataclass(frozen=True)
class RideModes:
    """Labelled modes of a ride model, one row per degree of freedom, ascending undamped frequency.

    Attributes
    ----------
    labels : tuple of str
        ``"body bounce"``, ``"pitch"``, ``"roll"``, ``"wheel hop"`` (``"wheel hop front"``,
        ``"wheel tramp rear"``, ... where the model has several wheels).
    undamped_frequency_hz : ndarray
        Natural frequencies of the undamped system M q'' + K q = 0 [Hz].
    natural_frequency_hz : ndarray
        |lambda| / (2 pi) of the damped model's matching eigenvalue [Hz].
    damped_frequency_hz : ndarray
        Im(lambda) / (2 pi) [Hz] (0 for an overdamped mode).
    damping_ratio : ndarray
        -Re(lambda) / |lambda| [-].
    shapes : ndarray, shape (n_dof, n_modes)
        Undamped mode shapes scaled so that the largest entry is 1 [m or rad].
    energy_fraction : ndarray, shape (n_dof, n_modes)
        Share of each coordinate in the mode's kinetic energy, phi_i (M phi)_i / phi' M phi [-].
    dof : tuple of str
        The coordinates (``sprung_displacement``, ``pitch_angle``, ..., ``unsprung_displacement*``).
    """

    labels: tuple[str, ...]
    undamped_frequency_hz: np.ndarray
    natural_frequency_hz: np.ndarray
    damped_frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    shapes: np.ndarray
    energy_fraction: np.ndarray
    dof: tuple[str, ...]

    def __len__(self) -> int:
        return len(self.labels)

    def index(self, label: str) -> int:
        """Position of the (first) mode whose label starts with ``label``.

        Parameters
        ----------
        label : str
            E.g. ``"pitch"``, ``"wheel hop"``, ``"wheel hop front"``.

        Returns
        -------
        int
            Its index in the arrays (ascending undamped frequency).

        Raises
        ------
        KeyError
            When no mode has that label.
        """
        for k, lab in enumerate(self.labels):
            if lab.startswith(label):
                return k
        raise KeyError(f"no mode labelled {label!r}; modes are {list(self.labels)}")

    def shape(self, label: str) -> dict[str, float]:
        """Mode shape of a labelled mode by coordinate name.

        Parameters
        ----------
        label : str
            As for :meth:`index`.

        Returns
        -------
        dict
            ``{coordinate: amplitude}`` [m or rad], the largest entry 1.
        """
        return dict(zip(self.dof, self.shapes[:, self.index(label)]))

    def to_frame(self):
        """The modes as a table.

        Returns
        -------
        pandas.DataFrame
            One row per mode (index ``mode``, the label): frequencies [Hz], damping ratio [-] and
            the shape by coordinate; units in ``attrs["units"]``.
        """
        import pandas as pd

        df = pd.DataFrame({
            "mode": list(self.labels),
            "undamped_frequency_hz": self.undamped_frequency_hz,
            "natural_frequency_hz": self.natural_frequency_hz,
            "damped_frequency_hz": self.damped_frequency_hz,
            "damping_ratio": self.damping_ratio,
            **{f"shape_{d}": self.shapes[i] for i, d in enumerate(self.dof)},
        }).set_index("mode")
        df.attrs["units"] = {"undamped_frequency_hz": "Hz", "natural_frequency_hz": "Hz", "damped_frequency_hz": "Hz",
                             "damping_ratio": "-", **{f"shape_{d}": ("rad" if d.endswith("angle") else "m")
                                                      for d in self.dof}}
        return df


def _label(model, energy: np.ndarray, phi: np.ndarray) -> str:
    dof = model.second_order[4]
    groups = {"body bounce": ["sprung_displacement"], "pitch": ["pitch_angle"], "roll": ["roll_angle"],
              "wheel": [d for d in dof if d.startswith("unsprung_displacement")]}
    share = {g: sum(energy[dof.index(d)] for d in names if d in dof) for g, names in groups.items()}
    kind = max(share, key=share.get)
    if kind != "wheel":
        return kind
    wheels = groups["wheel"]
    if len(wheels) == 1:
        return "wheel hop"
    axle_energy = {}
    for axle in ("front", "rear"):
        axle_energy[axle] = sum(energy[dof.index(d)] for d in wheels if f"_{axle}" in d)
    axle = max(axle_energy, key=axle_energy.get)
    left = [dof.index(d) for d in wheels if d.endswith(f"{axle}_left")]
    right = [dof.index(d) for d in wheels if d.endswith(f"{axle}_right")]
    if left and right:
        in_phase = phi[left[0]] * phi[right[0]] >= 0
        return f"wheel {'hop' if in_phase else 'tramp'} {axle}"
    return f"wheel hop {axle}"


def ride_modes(model) -> RideModes:
    """Labelled natural frequencies, damping ratios and mode shapes of a ride model.

    The undamped modes come from the symmetric eigenproblem K phi = omega^2 M phi; each is matched to
    an eigenvalue of the damped state matrix by the mass-weighted modal assurance criterion of
    the eigenvector's displacement part, which gives its damping ratio and damped frequency
    exactly, however non-proportional the damping. Each mode is labelled by where its kinetic
    energy lies (body bounce, pitch, roll, wheel hop or tramp).

    Parameters
    ----------
    model : QuarterCar, BouncePitch or FullCar
        A ride model of :mod:`vehdyn.ride`.

    Returns
    -------
    RideModes
        One entry per degree of freedom, ascending undamped frequency.

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5.
    .. [2] R. J. Allemang, "The modal assurance criterion -- twenty years of use and abuse",
       *Sound and Vibration*, 2003.
    .. [3] L. Meirovitch, *Fundamentals of Vibrations*, McGraw-Hill, 2001, sec. 7.4.
    """
    _require_ride_model(model)
    from scipy.optimize import linear_sum_assignment

    M, _, _, _, dof = model.second_order
    undamped = model.modal_analysis()
    phi = undamped.shapes
    n = len(dof)
    modes = state_space_modes(model.A, model.states)
    psi = modes.shapes[:n]  # displacement part of each state-space eigenvector
    num = np.abs(phi.T @ M @ psi) ** 2
    den = np.outer(np.einsum("im,ij,jm->m", phi, M, phi), np.real(np.einsum("im,ij,jm->m", psi.conj(), M, psi)))
    mac = num / np.where(den > 0, den, 1.0)
    rows, cols = linear_sum_assignment(-mac)
    match = np.empty(n, dtype=int)
    match[rows] = cols
    energy = phi * (M @ phi) / np.einsum("im,ij,jm->m", phi, M, phi)
    scaled = phi / phi[np.argmax(np.abs(phi), axis=0), np.arange(n)]
    return RideModes(
        labels=tuple(_label(model, energy[:, k], phi[:, k]) for k in range(n)),
        undamped_frequency_hz=undamped.natural_frequency_hz,
        natural_frequency_hz=modes.natural_frequency_hz[match],
        damped_frequency_hz=modes.damped_frequency_hz[match],
        damping_ratio=modes.damping_ratio[match],
        shapes=scaled,
        energy_fraction=energy,
        dof=tuple(dof),
    )


def axle_ride_rates(model) -> tuple[float, float]:
    """Front and rear axle ride rates: per corner k_s k_t / (k_s + k_t), summed over the axle.

    The suspension and tire springs in series (Gillespie 1992, eq. 5-6); with a rigid tire (no
    unsprung mass) the corner's rate k_s is the ride rate.

    Parameters
    ----------
    model : QuarterCar, BouncePitch or FullCar
        A ride model of :mod:`vehdyn.ride`.

    Returns
    -------
    front, rear : float
        Axle ride rates [N/m].
    """
    _require_ride_model(model)
    rates = {"front": 0.0, "rear": 0.0}
    for c in model.corners:
        axle = "front" if c.suffix.startswith("_front") else "rear"
        k = c.spring_rate
        if c.has_unsprung_mass:
            k = k * c.tire_stiffness / (k + c.tire_stiffness)
        rates[axle] += k
    return rates["front"], rates["rear"]


@dataclass(frozen=True)
class BouncePitchCentres:
    """Bounce and pitch modes of the body in the pitch plane, and their centres.

    Distances are measured ahead of the sprung CG [m] (negative = behind).

    Attributes
    ----------
    bounce_frequency_hz, pitch_frequency_hz : float
        Undamped frequencies of the bounce and pitch modes [Hz].
    bounce_centre, pitch_centre : float
        Node of each mode, x = -z / theta [m] (``inf`` for pure bounce).
    spring_centre : float
        Point where a vertical force causes pure bounce, (K_f a - K_r b) / (K_f + K_r) [m], with
        the axle ride rates.
    dynamic_index : float
        DI = k_y^2 / (a b) = I_y / (m a b) [-]; DI = 1 uncouples the axles.
    front_frequency_hz, rear_frequency_hz : float
        Uncoupled frequencies of each end, sqrt(K / (m x static share)) / (2 pi) [Hz].
    wheelbase : float
        [m]
    """

    bounce_frequency_hz: float
    pitch_frequency_hz: float
    bounce_centre: float
    pitch_centre: float
    spring_centre: float
    dynamic_index: float
    front_frequency_hz: float
    rear_frequency_hz: float
    wheelbase: float

    def to_frame(self):
        """The results as a table.

        Returns
        -------
        pandas.DataFrame
            One row per attribute (columns ``value`` and ``unit``); units also in
            ``attrs["units"]``.
        """
        import pandas as pd

        names = ["bounce_frequency_hz", "pitch_frequency_hz", "bounce_centre", "pitch_centre", "spring_centre",
                 "dynamic_index", "front_frequency_hz", "rear_frequency_hz", "wheelbase"]
        units = ["Hz", "Hz", "m", "m", "m", "-", "Hz", "Hz", "m"]
        df = pd.DataFrame({"value": [getattr(self, n) for n in names], "unit": units}, index=names)
        df.attrs["units"] = dict(zip(names, units))
        return df


def bounce_pitch_centres(model) -> BouncePitchCentres:
    r"""Bounce and pitch frequencies and their centres of rotation in the pitch plane.

    The node of each of the two body modes (the undamped modes with the most body energy) lies
    x = -z / theta ahead of the sprung CG; the mode whose node lies farther from the CG is the
    bounce mode. With the axle ride rates K_f, K_r:

    .. math::

        x_{node} = -\frac{z}{\theta}, \qquad
        x_{spring} = \frac{K_f a - K_r b}{K_f + K_r}, \qquad
        DI = \frac{I_y}{m a b}

    Parameters
    ----------
    model : BouncePitch or FullCar
        A ride model with a pitch coordinate.

    Returns
    -------
    BouncePitchCentres
        Frequencies [Hz], centres [m ahead of the CG], dynamic index [-].

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5, "Pitch/bounce
       frequencies".
    .. [2] W. F. Milliken and D. L. Milliken, *Race Car Vehicle Dynamics*, SAE, 1995, ch. 16.
    """
    _require_ride_model(model)
    if "pitch" not in model.body_dof:
        raise ParameterError(f"{type(model).__name__} has no pitch coordinate", key="model", value=model.name)
    p = model.parameters
    modes = ride_modes(model)
    dof = modes.dof
    iz, ith = dof.index("sprung_displacement"), dof.index("pitch_angle")
    body = modes.energy_fraction[iz] + modes.energy_fraction[ith]
    pair = np.sort(np.argsort(body)[-2:])
    undamped = model.modal_analysis()
    z, th = undamped.shapes[iz, pair], undamped.shapes[ith, pair]
    with np.errstate(divide="ignore"):
        nodes = np.where(th != 0, -z / np.where(th != 0, th, 1.0), np.inf)
    kb = int(np.argmax(np.abs(nodes)))
    kp = 1 - kb
    kf, kr = axle_ride_rates(model)
    L = p.a + p.b
    return BouncePitchCentres(
        bounce_frequency_hz=float(undamped.natural_frequency_hz[pair[kb]]),
        pitch_frequency_hz=float(undamped.natural_frequency_hz[pair[kp]]),
        bounce_centre=float(nodes[kb]),
        pitch_centre=float(nodes[kp]),
        spring_centre=(kf * p.a - kr * p.b) / (kf + kr),
        dynamic_index=p.pitch_inertia / (p.mass * p.a * p.b),
        front_frequency_hz=float(np.sqrt(kf / (p.mass * p.b / L)) / (2 * np.pi)),
        rear_frequency_hz=float(np.sqrt(kr / (p.mass * p.a / L)) / (2 * np.pi)),
        wheelbase=L,
    )


@dataclass(frozen=True)
class OlleyCheck:
    """Olley's flat-ride criteria for one vehicle (Gillespie 1992, ch. 5).

    Attributes
    ----------
    centres : BouncePitchCentres
    front_rate_lower_by : float
        (K_r - K_f) / K_r of the axle ride rates [%].
    spring_centre_behind_cg : float
        Spring centre behind the CG as a share of the wheelbase [%].
    frequency_ratio : float
        Front / rear uncoupled frequency [-].
    bounce_to_pitch_ratio : float
        Bounce frequency / pitch frequency [-].
    roll_frequency_hz : float or None
        Roll-mode frequency [Hz] (full car, or given).
    front_softer, frequencies_close, below_limit, roll_matched : bool or None
        Criteria (1) to (4); ``roll_matched`` is None without a roll frequency.
    """

    centres: BouncePitchCentres
    front_rate_lower_by: float
    spring_centre_behind_cg: float
    frequency_ratio: float
    bounce_to_pitch_ratio: float
    roll_frequency_hz: float | None
    front_softer: bool
    frequencies_close: bool
    below_limit: bool
    roll_matched: bool | None

    @property
    def passed(self) -> bool:
        """True when every criterion that can be checked holds."""
        checks = [self.front_softer, self.frequencies_close, self.below_limit]
        if self.roll_matched is not None:
            checks.append(self.roll_matched)
        return all(checks)

    def to_frame(self):
        """The criteria as a table.

        Returns
        -------
        pandas.DataFrame
            One row per criterion: ``value`` and ``criterion_met`` (None where it cannot be
            checked).
        """
        import pandas as pd

        rows = {
            "front ride rate lower than rear [%] (>= 30)": (self.front_rate_lower_by, self.front_softer),
            "spring centre behind CG [% of L] (>= 6.5)": (self.spring_centre_behind_cg, self.front_softer),
            "front/rear uncoupled frequency ratio": (self.frequency_ratio, None),
            "bounce/pitch frequency ratio (< 1.2)": (self.bounce_to_pitch_ratio, self.frequencies_close),
            "highest body frequency [Hz] (<= 1.3)": (max(self.centres.bounce_frequency_hz,
                                                         self.centres.pitch_frequency_hz), self.below_limit),
            "roll frequency [Hz] (~ bounce, pitch)": (self.roll_frequency_hz, self.roll_matched),
        }
        df = pd.DataFrame({"value": [v for v, _ in rows.values()], "criterion_met": [ok for _, ok in rows.values()]},
                          index=list(rows))
        return df


def olley_criteria(model, roll_frequency_hz: float | None = None, *, roll_tolerance: float = 0.2) -> OlleyCheck:
    """Check Olley's flat-ride criteria.

    Parameters
    ----------
    model : BouncePitch or FullCar
    roll_frequency_hz : float, optional
        Roll frequency [Hz]; a :class:`~vehdyn.ride.FullCar`'s own roll mode is used by default.
    roll_tolerance : float
        Criterion (4) holds when the roll frequency is within this fraction [-] of the mean of the
        bounce and pitch frequencies (Olley's "approximately equal"; default 0.2).

    Returns
    -------
    OlleyCheck
        The four criteria and the numbers behind them.

    References
    ----------
    .. [1] T. D. Gillespie, *Fundamentals of Vehicle Dynamics*, SAE, 1992, ch. 5 (Olley's flat-ride
       criteria).
    """
    c = bounce_pitch_centres(model)
    if roll_frequency_hz is None and "roll" in model.body_dof:
        modes = ride_modes(model)
        roll_frequency_hz = float(modes.undamped_frequency_hz[modes.index("roll")])
    kf, kr = axle_ride_rates(model)
    lower_by = 100.0 * (kr - kf) / kr
    behind = -100.0 * c.spring_centre / c.wheelbase
    f_max = max(c.bounce_frequency_hz, c.pitch_frequency_hz)
    mean = 0.5 * (c.bounce_frequency_hz + c.pitch_frequency_hz)
    return OlleyCheck(
        centres=c,
        front_rate_lower_by=lower_by,
        spring_centre_behind_cg=behind,
        frequency_ratio=c.front_frequency_hz / c.rear_frequency_hz,
        bounce_to_pitch_ratio=c.bounce_frequency_hz / c.pitch_frequency_hz,
        roll_frequency_hz=roll_frequency_hz,
        front_softer=bool(lower_by >= 30.0 or behind >= 6.5),
        frequencies_close=bool(c.bounce_frequency_hz < 1.2 * c.pitch_frequency_hz),
        below_limit=bool(f_max <= 1.3),
        roll_matched=None if roll_frequency_hz is None else bool(abs(roll_frequency_hz / mean - 1) <= roll_tolerance),
    )


def _outputs_starting(model, prefix: str) -> list[str]:
    return [n for n in model.output_names if n == prefix or n.startswith(prefix + "_")]


def transmissibility(model, omega, speed: float | None = None) -> FrequencyResponse:
    """Body heave (and pitch, roll) per unit road elevation.

    Parameters
    ----------
    model : QuarterCar, BouncePitch or FullCar
        A ride model of :mod:`vehdyn.ride`.
    omega : array_like
        Angular frequency [rad/s].
    speed : float, optional
        Forward speed [m/s]. With a speed, one profile per track with the exact wheelbase delay
        (see :func:`vehdyn.ride.road_frequency_response`); without, one input per wheel.

    Returns
    -------
    FrequencyResponse
        Outputs ``sprung_displacement`` [m/m] (and ``pitch_angle``, ``roll_angle`` [rad/m]) per
        road input.

    Examples
    --------
    The quarter car's body transmissibility peaks near its body frequency (1.21 Hz):

    >>> import numpy as np
    >>> from vehdyn.ride import QuarterCar, transmissibility
    >>> qc = QuarterCar.from_parameters(sprung_mass=250.0, unsprung_mass=35.0, spring_rate=16e3,
    ...                                 damping=1000.0, tire_stiffness=160e3)
    >>> fr = transmissibility(qc, 2 * np.pi * np.array([0.5, 1.213, 5.0]))
    >>> fr.magnitude[0, 0].round(3).tolist()
    [1.198, 2.594, 0.17]
    """
    _require_ride_model(model)
    outs = [n for n in ("sprung_displacement", "pitch_angle", "roll_angle") if n in model.output_names]
    return road_frequency_response(model, omega, speed=speed, outputs=outs)


def suspension_travel_response(model, omega, speed: float | None = None) -> FrequencyResponse:
    """Suspension travel (rebound +) per unit road elevation at every wheel.

    Parameters
    ----------
    model : QuarterCar, BouncePitch or FullCar
        A ride model of :mod:`vehdyn.ride`.
    omega : array_like
        Angular frequency [rad/s].
    speed : float, optional
        Forward speed [m/s] (the exact wheelbase delay, as :func:`transmissibility`).

    Returns
    -------
    FrequencyResponse
        Outputs ``suspension_travel*`` [m/m] per road input.
    """
    _require_ride_model(model)
    return road_frequency_response(model, omega, speed=speed, outputs=_outputs_starting(model, "suspension_travel"))


def dynamic_tire_load_response(model, omega, speed: float | None = None) -> FrequencyResponse:
    """Dynamic tire load (more load +) per unit road elevation at every wheel.

    Parameters
    ----------
    model : QuarterCar, BouncePitch or FullCar
        A ride model of :mod:`vehdyn.ride`.
    omega : array_like
        Angular frequency [rad/s].
    speed : float, optional
        Forward speed [m/s] (the exact wheelbase delay, as :func:`transmissibility`).

    Returns
    -------
    FrequencyResponse
        Outputs ``dynamic_tire_load*`` [N/m] per road input.
    """
    _require_ride_model(model)
    return road_frequency_response(model, omega, speed=speed, outputs=_outputs_starting(model, "dynamic_tire_load"))
