"""Modal analysis: eigenvalues, natural frequencies, damping ratios and labelled mode shapes.

Two views of the same system:

* :func:`state_space_modes` works on any state matrix A. For an eigenvalue
  lambda = sigma + j omega_d the natural frequency is omega_n = |lambda| and the damping ratio
  zeta = -sigma / |lambda| (Meirovitch, *Fundamentals of Vibrations*, 2001, sec. 2.5; Ogata,
  *Modern Control Engineering*, 5th ed., sec. 5-3).
* :func:`modal_analysis` works on M q'' + C q' + K q = 0 in mass-normalized coordinates: the
  generalized eigenproblem K phi = omega^2 M phi with Phi^T M Phi = I and Phi^T K Phi =
  diag(omega^2); the modal damping ratios are zeta_i = (Phi^T C Phi)_ii / (2 omega_i), exact when C
  is proportional (Phi^T C Phi diagonal) and a first-order estimate otherwise (Meirovitch, sec. 7.4
  and 7.12; Inman, *Engineering Vibration*, 4th ed., sec. 4.5).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.signals import Signal

__all__ = ["Modes", "SecondOrderModes", "state_space_modes", "modal_analysis"]


@dataclass(frozen=True)
class Modes:
    """Modes of a state-space model (one row per real eigenvalue or complex pair).

    Attributes
    ----------
    eigenvalues : ndarray of complex
        Eigenvalues [1/s] (for a pair, the member with positive imaginary part).
    natural_frequency : ndarray
        omega_n = |lambda| [rad/s].
    natural_frequency_hz : ndarray
        omega_n / (2 pi) [Hz].
    damped_frequency_hz : ndarray
        |Im lambda| / (2 pi) [Hz].
    damping_ratio : ndarray
        zeta = -Re(lambda) / |lambda| [-] (1 for a stable real eigenvalue, -1 for an unstable one,
        NaN for a zero eigenvalue, which has no frequency scale).
    shapes : ndarray of complex, shape (n_states, n_modes)
        Eigenvectors scaled so the entry of largest magnitude is 1 [each state's unit, relative to
        the largest entry's].
    state_names : tuple of str
        The states the shapes run over.
    """

    eigenvalues: np.ndarray
    natural_frequency: np.ndarray
    natural_frequency_hz: np.ndarray
    damped_frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    shapes: np.ndarray
    state_names: tuple[str, ...]

    def __len__(self) -> int:
        return self.eigenvalues.size

    @property
    def time_constant(self) -> np.ndarray:
        """-1 / Re(lambda) [s] (infinite for Re = 0)."""
        with np.errstate(divide="ignore"):
            return -1.0 / self.eigenvalues.real

    def shape(self, mode: int) -> dict[str, complex]:
        """One mode shape by state name.

        Parameters
        ----------
        mode : int
            The mode's index (modes are sorted by natural frequency).

        Returns
        -------
        dict of str to complex
            ``{state name: complex amplitude}``, the largest of magnitude 1.
        """
        return dict(zip(self.state_names, self.shapes[:, mode]))

    def dominant_state(self, mode: int) -> str:
        """The state with the largest amplitude in a mode.

        Parameters
        ----------
        mode : int
            The mode's index.

        Returns
        -------
        str
            The state's name.
        """
        return self.state_names[int(np.argmax(np.abs(self.shapes[:, mode])))]

    def to_frame(self):
        """The modes as a pandas DataFrame.

        Returns
        -------
        pandas.DataFrame
            One row per mode: eigenvalue (real [1/s], imaginary [rad/s]), natural frequency
            [rad/s] and [Hz], damped frequency [Hz], damping ratio [-] and the dominant state;
            ``attrs["units"]`` maps each column to its unit.
        """
        import pandas as pd

        df = pd.DataFrame(
            {
                "eigenvalue_real": self.eigenvalues.real,
                "eigenvalue_imag": self.eigenvalues.imag,
                "natural_frequency": self.natural_frequency,
                "natural_frequency_hz": self.natural_frequency_hz,
                "damped_frequency_hz": self.damped_frequency_hz,
                "damping_ratio": self.damping_ratio,
                "dominant_state": [self.dominant_state(k) for k in range(len(self))],
            }
        )
        df.index.name = "mode"
        df.attrs["units"] = {
            "eigenvalue_real": "1/s",
            "eigenvalue_imag": "rad/s",
            "natural_frequency": "rad/s",
            "natural_frequency_hz": "Hz",
            "damped_frequency_hz": "Hz",
            "damping_ratio": "-",
            "dominant_state": "",
        }
        return df


def _normalize_columns(vectors: np.ndarray) -> np.ndarray:
    idx = np.argmax(np.abs(vectors), axis=0)
    pivot = vectors[idx, np.arange(vectors.shape[1])]
    pivot = np.where(pivot == 0, 1.0, pivot)
    return vectors / pivot


def state_space_modes(A, states: Sequence[Signal | str]) -> Modes:
    r"""Modes of a state matrix with named states.

    Parameters
    ----------
    A : array_like, shape (n, n)
        State matrix [1/s].
    states : sequence of Signal or str
        The states (their names label the mode shapes).

    Returns
    -------
    Modes
        One entry per real eigenvalue and per complex-conjugate pair (the member with positive
        imaginary part), sorted by natural frequency.

    Notes
    -----
    For an eigenvalue :math:`\lambda = \sigma + j\omega_d` of A,

    .. math::

        \omega_n = |\lambda|, \qquad \zeta = -\frac{\sigma}{|\lambda|}, \qquad
        \omega_d = \omega_n \sqrt{1 - \zeta^2}

    (Ogata, sec. 5-3; Meirovitch, sec. 2.5).

    References
    ----------
    .. [1] K. Ogata, *Modern Control Engineering*, 5th ed., Prentice Hall, 2010, sec. 5-3.
    .. [2] L. Meirovitch, *Fundamentals of Vibrations*, McGraw-Hill, 2001, sec. 2.5.

    Examples
    --------
    >>> from vehdyn.model import state_space_modes
    >>> modes = state_space_modes([[0.0, 1.0], [-4.0, -0.4]], ["roll_angle", "roll_rate"])
    >>> round(float(modes.natural_frequency[0]), 6), round(float(modes.damping_ratio[0]), 6)
    (2.0, 0.1)
    """
    A = np.asarray(A, dtype=float)
    names = tuple(s.name if isinstance(s, Signal) else str(s) for s in states)
    if A.shape != (len(names), len(names)):
        raise ParameterError(f"A has shape {A.shape} but {len(names)} states are named", key="A", value=A.shape)
    lam, vec = np.linalg.eig(A)
    scale = max(1.0, float(np.max(np.abs(lam)))) if lam.size else 1.0
    keep = lam.imag >= -1e-12 * scale  # one member of each conjugate pair
    lam, vec = lam[keep], vec[:, keep]
    lam = np.where(np.abs(lam.imag) <= 1e-12 * scale, lam.real + 0j, lam)
    wn = np.abs(lam)
    order = np.lexsort((lam.real, wn))
    lam, vec, wn = lam[order], vec[:, order], wn[order]
    with np.errstate(invalid="ignore", divide="ignore"):
        zeta = np.where(wn > 0, -lam.real / np.where(wn > 0, wn, 1.0), np.nan)
    return Modes(
        eigenvalues=lam,
        natural_frequency=wn,
        natural_frequency_hz=wn / (2 * np.pi),
        damped_frequency_hz=np.abs(lam.imag) / (2 * np.pi),
        damping_ratio=zeta,
        shapes=_normalize_columns(vec),
        state_names=names,
    )


@dataclass(frozen=True)
class SecondOrderModes:
    """Undamped modes of M q'' + C q' + K q = 0 in mass-normalized coordinates.

    Attributes
    ----------
    natural_frequency : ndarray
        Undamped natural frequencies omega_i [rad/s], ascending.
    natural_frequency_hz : ndarray
        omega_i / (2 pi) [Hz].
    shapes : ndarray, shape (n_dof, n_modes)
        Mass-normalized mode shapes Phi (Phi^T M Phi = I) [1/sqrt(kg) for displacements,
        1/sqrt(kg m^2) for angles].
    damping_ratio : ndarray
        (Phi^T C Phi)_ii / (2 omega_i) [-]; exact for proportional damping.
    modal_damping : ndarray
        Phi^T C Phi [1/s].
    proportional : bool
        True when Phi^T C Phi is diagonal to 1e-9 relative (the modes stay uncoupled).
    dof : tuple of str
        The coordinates the shapes run over.
    """

    natural_frequency: np.ndarray
    natural_frequency_hz: np.ndarray
    shapes: np.ndarray
    damping_ratio: np.ndarray
    modal_damping: np.ndarray
    proportional: bool
    dof: tuple[str, ...]

    def shape(self, mode: int, normalize: str = "mass") -> dict[str, float]:
        """One mode shape by coordinate name.

        Parameters
        ----------
        mode : int
            The mode's index (ascending natural frequency).
        normalize : {"mass", "max"}
            Mass-normalized (Phi^T M Phi = I, as stored) or scaled so that the largest entry is 1.

        Returns
        -------
        dict of str to float
            ``{coordinate name: amplitude}``.
        """
        phi = self.shapes[:, mode]
        if normalize == "max":
            phi = phi / phi[np.argmax(np.abs(phi))]
        return dict(zip(self.dof, phi))

    def to_frame(self):
        """The modes as a pandas DataFrame.

        Returns
        -------
        pandas.DataFrame
            One row per mode: natural frequency [rad/s] and [Hz], damping ratio [-] and one
            ``shape_<dof>`` column per coordinate (mass-normalized); ``attrs["units"]``.
        """
        import pandas as pd

        df = pd.DataFrame(
            {
                "natural_frequency": self.natural_frequency,
                "natural_frequency_hz": self.natural_frequency_hz,
                "damping_ratio": self.damping_ratio,
                **{f"shape_{d}": self.shapes[i] for i, d in enumerate(self.dof)},
            }
        )
        df.index.name = "mode"
        df.attrs["units"] = {"natural_frequency": "rad/s", "natural_frequency_hz": "Hz", "damping_ratio": "-"}
        return df


def modal_analysis(M, K, C=None, dof: Sequence[str] | None = None) -> SecondOrderModes:
    r"""Undamped modal analysis of M q'' + C q' + K q = 0 in mass-normalized coordinates.

    Parameters
    ----------
    M : array_like, shape (n, n)
        Symmetric positive-definite mass matrix [kg, kg*m^2 for angles].
    K : array_like, shape (n, n)
        Symmetric stiffness matrix [N/m, N*m/rad for angles].
    C : array_like, shape (n, n), optional
        Damping matrix [N*s/m, N*m*s/rad for angles] (zeros if omitted).
    dof : sequence of str, optional
        Coordinate names (default ``q0``, ``q1``, ...).

    Returns
    -------
    SecondOrderModes
        Natural frequencies (ascending), mass-normalized shapes and modal damping ratios.

    Notes
    -----
    The generalized eigenproblem and its mass normalization,

    .. math::

        K \varphi_i = \omega_i^2 M \varphi_i, \qquad
        \Phi^T M \Phi = I, \qquad \Phi^T K \Phi = \operatorname{diag}(\omega_i^2),

    give the modal damping ratios

    .. math::

        \zeta_i = \frac{(\Phi^T C \Phi)_{ii}}{2 \omega_i},

    exact when C is proportional (:math:`\Phi^T C \Phi` diagonal) and a first-order estimate
    otherwise (Meirovitch, sec. 7.4 and 7.12; Inman, sec. 4.5).

    References
    ----------
    .. [1] L. Meirovitch, *Fundamentals of Vibrations*, McGraw-Hill, 2001, sec. 7.4 and 7.12.
    .. [2] D. J. Inman, *Engineering Vibration*, 4th ed., Pearson, 2014, sec. 4.5.

    Examples
    --------
    Two equal masses (1 kg) between three equal springs (100 N/m): the in-phase mode at
    sqrt(k/m) = 10 rad/s, the out-of-phase one at sqrt(3k/m) = 17.32 rad/s.

    >>> from vehdyn.model import modal_analysis
    >>> modes = modal_analysis([[1.0, 0.0], [0.0, 1.0]], [[200.0, -100.0], [-100.0, 200.0]], dof=["left", "right"])
    >>> modes.natural_frequency.round(4)
    array([10.    , 17.3205])
    >>> {k: round(float(v), 6) for k, v in modes.shape(1, normalize="max").items()}
    {'left': 1.0, 'right': -1.0}
    """
    M = np.asarray(M, dtype=float)
    K = np.asarray(K, dtype=float)
    n = M.shape[0]
    C = np.zeros((n, n)) if C is None else np.asarray(C, dtype=float)
    if dof is None:
        dof = tuple(f"q{i}" for i in range(n))
    if not np.allclose(K, K.T, rtol=1e-10, atol=1e-12 * np.abs(K).max(initial=1.0)):
        raise ParameterError("modal_analysis: K must be symmetric", key="K", value=K)
    import scipy.linalg

    w2, phi = scipy.linalg.eigh(K, M)  # phi^T M phi = I
    w = np.sqrt(np.clip(w2, 0.0, None))
    # sign convention: largest entry of each shape positive
    sign = np.sign(phi[np.argmax(np.abs(phi), axis=0), np.arange(n)])
    phi = phi * np.where(sign == 0, 1.0, sign)
    Cm = phi.T @ C @ phi
    off = Cm - np.diag(np.diag(Cm))
    proportional = bool(np.abs(off).max(initial=0.0) <= 1e-9 * max(np.abs(Cm).max(initial=0.0), 1e-300))
    with np.errstate(divide="ignore", invalid="ignore"):
        zeta = np.where(w > 0, np.diag(Cm) / (2 * np.where(w > 0, w, 1.0)), np.nan)
    return SecondOrderModes(
        natural_frequency=w,
        natural_frequency_hz=w / (2 * np.pi),
        shapes=phi,
        damping_ratio=zeta,
        modal_damping=Cm,
        proportional=proportional,
        dof=tuple(dof),
    )
