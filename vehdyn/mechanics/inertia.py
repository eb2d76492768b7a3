"""Mass properties of rigid bodies: the inertia tensor, primitives, parallel axes and composites.

Sign convention of the products of inertia
------------------------------------------
The moments and products of inertia about a point O, in axes x, y, z through O, are

    Ixx = integral (y^2 + z^2) dm,   Iyy = integral (z^2 + x^2) dm,   Izz = integral (x^2 + y^2) dm,
    Ixy = integral x y dm,           Ixz = integral x z dm,           Iyz = integral y z dm,

and the inertia tensor (the matrix that maps the angular velocity to the angular momentum,
H = I omega) carries the products with a minus sign::

        [  Ixx  -Ixy  -Ixz ]
    I = [ -Ixy   Iyy  -Iyz ]
        [ -Ixz  -Iyz   Izz ]

This is the convention of the flight- and vehicle-dynamics literature whose body axes SAE J670
adopted (B. Etkin, *Dynamics of Atmospheric Flight*, Wiley, 1972, ch. 4, cited from memory: its
moment equations carry -Ixz as here). Some texts (e.g. Goldstein, *Classical
Mechanics*, ch. 5) call the matrix entries themselves "products of inertia"; vehdyn does not:
:class:`InertiaTensor` takes ``ixy``, ``ixz``, ``iyz`` as the integrals above and ``.matrix`` holds
their negatives. The sign of a product is that of its integral: in SAE vehicle axes (x forward,
z down) a body whose mass lies high (z < 0) where it lies forward (x > 0) has Ixz < 0.

All moments are in kg m^2, masses in kg, lengths in m.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Iterable, Sequence

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.base import ParameterSet, parameter
from vehdyn.params.inertia import check_realizable, relative_tolerance

__all__ = [
    "InertiaTensor",
    "MassProperties",
    "inertia_matrix",
    "parallel_axis_shift",
    "composite",
    "solid_box",
    "solid_cylinder",
    "hollow_cylinder",
    "solid_sphere",
    "hollow_sphere",
    "solid_cone",
    "slender_rod",
]

_AXES = ("x", "y", "z")


@dataclasses.dataclass(frozen=True)
class InertiaTensor(ParameterSet):
    r"""Inertia tensor of a rigid body about a point, in a set of body axes.

    Parameters
    ----------
    ixx, iyy, izz : float
        Moments of inertia about the x, y and z axes [kg m^2], Ixx = integral (y^2 + z^2) dm etc.
    ixy, ixz, iyz : float, optional
        Products of inertia [kg m^2] defined as Ixy = integral x y dm, Ixz = integral x z dm,
        Iyz = integral y z dm (default 0). The tensor :attr:`matrix` carries them with a minus sign.

    Raises
    ------
    ParameterError
        If a value is not a finite number, a moment is negative, the moments about the axes violate
        a triangle inequality (Ixx + Iyy >= Izz and the cyclic ones), or the tensor is not positive
        semi-definite (no mass distribution has it). The message names the entry and its value.

    Notes
    -----
    With the moments and products as integrals over the body (position r = (x, y, z) from the
    reference point), the tensor that maps the angular velocity to the angular momentum,
    :math:`\mathbf H = \mathbf I \boldsymbol\omega`, is

    .. math::

        \mathbf I = \int (|\mathbf r|^2 \mathbf E - \mathbf r \mathbf r^T) \, dm
        = \begin{bmatrix} I_{xx} & -I_{xy} & -I_{xz} \\ -I_{xy} & I_{yy} & -I_{yz} \\
          -I_{xz} & -I_{yz} & I_{zz} \end{bmatrix},
        \qquad I_{xx} = \int (y^2 + z^2) \, dm, \quad I_{xz} = \int x z \, dm, \ \dots

    (the sign convention of the flight- and vehicle-dynamics literature and of SAE J670; see the
    module docstring). A tensor is realizable by a mass distribution exactly when its principal
    moments are non-negative and satisfy the triangle inequalities; the checks here test the
    principal moments (which implies the same for the moments about the given axes). A singular
    tensor (a point mass or a slender rod, which has no moment about its own axis) is accepted as
    a part of a composite; the dynamics (:func:`vehdyn.mechanics.newton_euler`,
    :class:`vehdyn.mechanics.RigidBody6DOF`) need a positive-definite one and check it
    (:attr:`is_positive_definite`).

    References
    ----------
    .. [1] H. Goldstein, C. Poole and J. Safko, *Classical Mechanics*, 3rd ed., Addison-Wesley,
       2002, sec. 5.3-5.4 (the inertia tensor, principal axes).
    .. [2] SAE J670, *Vehicle Dynamics Terminology*, 2008 (vehicle axes).

    Examples
    --------
    >>> from vehdyn.mechanics import InertiaTensor
    >>> tensor = InertiaTensor(500.0, 2000.0, 2200.0, ixz=40.0)    # a car's body about its CG [kg m^2]
    >>> float(tensor.matrix[0, 2])                                  # products enter with a minus sign
    -40.0
    >>> [round(float(m), 3) for m in tensor.principal_moments]     # ascending [kg m^2]
    [499.059, 2000.0, 2200.941]
    >>> round(tensor.moment_about([1.0, 0.0, 1.0]), 1)              # about a 45-degree axis [kg m^2]
    1310.0
    """

    ixx: float = parameter("kg*m^2", "moment of inertia about x, integral (y^2 + z^2) dm", ge=0.0)
    iyy: float = parameter("kg*m^2", "moment of inertia about y, integral (z^2 + x^2) dm", ge=0.0)
    izz: float = parameter("kg*m^2", "moment of inertia about z, integral (x^2 + y^2) dm", ge=0.0)
    ixy: float = parameter("kg*m^2", "product of inertia integral x y dm (matrix entry is -ixy)", default=0.0)
    ixz: float = parameter("kg*m^2", "product of inertia integral x z dm (matrix entry is -ixz)", default=0.0)
    iyz: float = parameter("kg*m^2", "product of inertia integral y z dm (matrix entry is -iyz)", default=0.0)

    def check(self) -> None:
        check_realizable(self.matrix)

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_matrix(cls, matrix) -> "InertiaTensor":
        """The tensor whose :attr:`matrix` is ``matrix``.

        Parameters
        ----------
        matrix : array_like, shape (3, 3)
            Symmetric inertia matrix [kg m^2], off-diagonal entries -Ixy, -Ixz, -Iyz.

        Returns
        -------
        InertiaTensor
            With ``ixy = -matrix[0, 1]``, ``ixz = -matrix[0, 2]``, ``iyz = -matrix[1, 2]``.

        Raises
        ------
        ParameterError
            If the shape is not (3, 3), an entry is not finite, the matrix is not symmetric (to
            1e-9 of its largest entry) or not realizable (key ``inertia`` or the entry).
        """
        m = np.asarray(matrix, dtype=float)
        if m.shape != (3, 3):
            raise ParameterError(f"inertia matrix must be 3x3, got shape {m.shape}", key="inertia", value=m.shape)
        if not np.all(np.isfinite(m)):
            raise ParameterError("inertia matrix has non-finite entries", key="inertia", value=m)
        asym = float(np.max(np.abs(m - m.T)))
        if asym > 1e-9 * max(float(np.max(np.abs(m))), np.finfo(float).tiny):
            raise ParameterError(f"inertia matrix is not symmetric (largest |I - I^T| = {asym:g} kg*m^2)",
                                 key="inertia", value=m)
        m = 0.5 * (m + m.T)
        return cls(float(m[0, 0]), float(m[1, 1]), float(m[2, 2]),
                   ixy=float(0.0 - m[0, 1]), ixz=float(0.0 - m[0, 2]), iyz=float(0.0 - m[1, 2]))

    @classmethod
    def from_principal(cls, moments: Sequence[float], axes=None) -> "InertiaTensor":
        """The tensor with given principal moments along given principal directions.

        Parameters
        ----------
        moments : sequence of float
            Principal moments (I1, I2, I3) [kg m^2].
        axes : array_like, shape (3, 3), optional
            Proper rotation matrix [-] whose columns are the principal directions expressed in the
            target axes (identity by default).

        Returns
        -------
        InertiaTensor
            I = axes @ diag(moments) @ axes.T.
        """
        moments = np.asarray(moments, dtype=float)
        if moments.shape != (3,):
            raise ParameterError(f"principal moments must be three numbers, got shape {moments.shape}",
                                 key="moments", value=moments)
        rot = np.eye(3) if axes is None else _rotation(axes, "axes")
        return cls.from_matrix(rot @ np.diag(moments) @ rot.T)

    @classmethod
    def from_radii_of_gyration(cls, mass: float, kx: float, ky: float, kz: float, *, ixy: float = 0.0,
                               ixz: float = 0.0, iyz: float = 0.0) -> "InertiaTensor":
        """The tensor of a body of known mass and radii of gyration.

        Parameters
        ----------
        mass : float
            Mass m [kg], > 0.
        kx, ky, kz : float
            Radii of gyration about the x, y and z axes [m], >= 0.
        ixy, ixz, iyz : float, optional
            Products of inertia [kg m^2] (integrals, as in the class), default 0.

        Returns
        -------
        InertiaTensor
            Moments Ixx = m kx^2, Iyy = m ky^2, Izz = m kz^2 and the given products.
        """
        mass = _positive(mass, "mass", "kg")
        return cls(mass * _nonnegative(kx, "kx", "m") ** 2, mass * _nonnegative(ky, "ky", "m") ** 2,
                   mass * _nonnegative(kz, "kz", "m") ** 2, ixy=ixy, ixz=ixz, iyz=iyz)

    # ------------------------------------------------------------------ views
    @property
    def matrix(self) -> np.ndarray:
        """The 3x3 tensor [kg m^2], off-diagonal entries -Ixy, -Ixz, -Iyz (a fresh array)."""
        xy, xz, yz = 0.0 - self.ixy, 0.0 - self.ixz, 0.0 - self.iyz  # 0.0 - 0.0 is +0.0, not -0.0
        return np.array([[self.ixx, xy, xz], [xy, self.iyy, yz], [xz, yz, self.izz]])

    def __array__(self, dtype=None, copy=None):
        return self.matrix if dtype is None else self.matrix.astype(dtype)

    @property
    def is_positive_definite(self) -> bool:
        """True when every principal moment is positive (the body can be given dynamics)."""
        return bool(np.linalg.eigvalsh(self.matrix)[0] > relative_tolerance(self.ixx + self.iyy + self.izz))

    def principal(self) -> tuple[np.ndarray, np.ndarray]:
        """Principal moments and axes.

        Returns
        -------
        moments : ndarray, shape (3,)
            Principal moments in ascending order [kg m^2].
        axes : ndarray, shape (3, 3)
            A proper rotation matrix (det +1) whose column k is the unit principal direction of
            ``moments[k]`` in the tensor's axes, so ``matrix == axes @ diag(moments) @ axes.T``.
            Each column's sign is chosen so that its largest component is positive (then the last
            column is fixed by det +1).
        """
        moments, axes = np.linalg.eigh(self.matrix)
        for k in range(2):
            col = axes[:, k]
            if col[np.argmax(np.abs(col))] < 0:
                axes[:, k] = -col
        if np.linalg.det(axes) < 0:
            axes[:, 2] = -axes[:, 2]
        return moments, axes

    @property
    def principal_moments(self) -> np.ndarray:
        """Principal moments in ascending order [kg m^2]."""
        return np.linalg.eigvalsh(self.matrix)

    def moment_about(self, direction) -> float:
        """Moment of inertia about an axis through the reference point.

        Parameters
        ----------
        direction : array_like, shape (3,)
            Direction of the axis in the tensor's axes [-]; need not be unit length.

        Returns
        -------
        float
            n^T I n [kg m^2] with n = direction / |direction|.
        """
        n = np.asarray(direction, dtype=float)
        norm = float(np.linalg.norm(n))
        if n.shape != (3,) or not norm > 0 or not np.isfinite(norm):
            raise ParameterError(f"direction must be a non-zero 3-vector, got {direction!r}", key="direction",
                                 value=direction)
        n = n / norm
        return float(n @ self.matrix @ n)

    def radius_of_gyration(self, mass: float) -> np.ndarray:
        """Radii of gyration about the x, y and z axes.

        Parameters
        ----------
        mass : float
            Mass m of the body [kg], > 0.

        Returns
        -------
        ndarray, shape (3,)
            k = sqrt(I / m) about x, y and z [m].
        """
        mass = _positive(mass, "mass", "kg")
        return np.sqrt(np.array([self.ixx, self.iyy, self.izz]) / mass)

    # ------------------------------------------------------------------ transformations
    def rotated(self, rotation) -> "InertiaTensor":
        """The same body's tensor in other axes.

        Parameters
        ----------
        rotation : array_like, shape (3, 3)
            Proper rotation matrix [-] whose columns are this tensor's axes expressed in the new
            axes (so a vector's components transform as v_new = rotation @ v_old).

        Returns
        -------
        InertiaTensor
            I_new = rotation @ I @ rotation.T.
        """
        rot = _rotation(rotation, "rotation")
        return InertiaTensor.from_matrix(rot @ self.matrix @ rot.T)

    def shifted(self, mass: float, offset) -> "InertiaTensor":
        """Parallel-axis shift from the centre of mass to another point (Steiner's theorem).

        Parameters
        ----------
        mass : float
            Mass of the body [kg].
        offset : array_like, shape (3,)
            Position of the centre of mass relative to the new reference point [m], in this tensor's
            axes (the sign does not matter: the shift is quadratic in it).

        Returns
        -------
        InertiaTensor
            I_P = I_G + m (|d|^2 E - d d^T); e.g. Ixx_P = Ixx_G + m (dy^2 + dz^2),
            Ixz_P = Ixz_G + m dx dz (so the matrix entry gains -m dx dz).

        Notes
        -----
        Valid only when this tensor is about the centre of mass; see :meth:`to_centre_of_mass` for
        the reverse shift.
        """
        return InertiaTensor.from_matrix(self.matrix + parallel_axis_shift(mass, offset))

    def to_centre_of_mass(self, mass: float, offset) -> "InertiaTensor":
        """The reverse of :meth:`shifted`: from a point P to the centre of mass G.

        Parameters
        ----------
        mass : float
            Mass of the body [kg].
        offset : array_like, shape (3,)
            Position d of G relative to P [m], in this tensor's axes.

        Returns
        -------
        InertiaTensor
            I_G = I_P - m (|d|^2 E - d d^T).
        """
        return InertiaTensor.from_matrix(self.matrix - parallel_axis_shift(mass, offset))

    def __add__(self, other: "InertiaTensor") -> "InertiaTensor":
        """Sum of two tensors about the same point in the same axes (two parts of one body)."""
        if not isinstance(other, InertiaTensor):
            return NotImplemented
        return InertiaTensor.from_matrix(self.matrix + other.matrix)


def parallel_axis_shift(mass, offset) -> np.ndarray:
    r"""The parallel-axis (Steiner) term of a mass at an offset.

    .. math::

        \Delta \mathbf I = m \, (|\mathbf d|^2 \mathbf E - \mathbf d \mathbf d^T)

    It is the inertia tensor, in the sign convention of this module, of a point mass at d; added
    to a tensor about the centre of mass it gives the tensor about the point -d from it.

    Parameters
    ----------
    mass : float or array_like, shape (n,)
        Mass m [kg], >= 0 (an array for a batch).
    offset : array_like, shape (3,) or (3, n)
        Offset d [m].

    Returns
    -------
    ndarray, shape (3, 3) or (3, 3, n)
        The term [kg m^2].

    References
    ----------
    .. [1] H. Goldstein, C. Poole and J. Safko, *Classical Mechanics*, 3rd ed., 2002, sec. 5.3.
    """
    d = np.asarray(offset, dtype=float)
    if d.shape[:1] != (3,):
        raise ParameterError(f"offset must have 3 components, got shape {d.shape}", key="offset", value=offset)
    if not np.all(np.isfinite(d)):
        raise ParameterError(f"offset must be finite, got {offset!r}", key="offset", value=offset)
    m = np.asarray(mass, dtype=float)
    if not np.all(np.isfinite(m)) or np.any(m < 0):
        raise ParameterError(f"mass must be finite and non-negative [kg], got {mass!r}", key="mass", value=mass)
    eye = np.eye(3).reshape((3, 3) + (1,) * (d.ndim - 1))
    return m * (np.einsum("i...,i...->...", d, d) * eye - np.einsum("i...,j...->ij...", d, d))


def inertia_matrix(inertia) -> np.ndarray:
    """A validated 3x3 (or 3x3xn batch) inertia matrix [kg m^2] from a tensor or an array.

    Parameters
    ----------
    inertia : InertiaTensor or array_like, shape (3, 3) or (3, 3, n)
        An :class:`InertiaTensor` or the tensor's matrix [kg m^2] (off-diagonal entries -Ixy,
        -Ixz, -Iyz), optionally with a trailing batch axis of n variants.

    Returns
    -------
    ndarray, shape (3, 3) or (3, 3, n)
        The matrix [kg m^2] (a fresh array for a tensor; the array as given, as floats, otherwise).

    Raises
    ------
    ParameterError
        If the shape is wrong, an entry is not finite, the matrix is not symmetric, not positive
        definite (a rigid body needs an invertible tensor) or breaks a triangle inequality (no mass
        distribution has it): the same check as :class:`InertiaTensor`'s (:func:`check_realizable`).
    """
    if isinstance(inertia, InertiaTensor):
        mat = inertia.matrix
    else:
        mat = np.asarray(inertia, dtype=float)
        if mat.shape[:2] != (3, 3) or mat.ndim > 3:
            raise ParameterError(f"inertia must be an InertiaTensor or a 3x3 (or 3x3xn) matrix, got shape "
                                 f"{mat.shape}", key="inertia", value=mat.shape)
        if not np.all(np.isfinite(mat)):
            raise ParameterError("inertia matrix has non-finite entries", key="inertia", value=mat)
        scale = np.max(np.abs(mat))
        if np.max(np.abs(mat - np.swapaxes(mat, 0, 1))) > 1e-9 * max(scale, np.finfo(float).tiny):
            raise ParameterError("inertia matrix is not symmetric; its off-diagonal entries must be -Ixy, -Ixz, "
                                 "-Iyz on both sides", key="inertia", value=mat)
    check_realizable(mat, definite=True, key="inertia")
    return mat


# ---------------------------------------------------------------------------- mass properties
@dataclasses.dataclass(frozen=True)
class MassProperties:
    """Mass, centre of mass and inertia tensor (about the centre of mass) of a rigid body or part.

    The building block of :func:`composite`: describe each part (a primitive such as
    :func:`solid_box`, or measured values) in one set of reference axes and combine them. Not the
    vehicle's parameter group, which is :class:`vehdyn.params.MassAndInertia` (``Vehicle.mass``).

    Parameters
    ----------
    mass : float
        Mass [kg], > 0.
    centre_of_mass : array_like, shape (3,)
        Position of the centre of mass in the reference axes [m] (default the origin).
    inertia : InertiaTensor or array_like, shape (3, 3)
        Tensor about the centre of mass, in axes parallel to the reference axes [kg m^2] (a
        matrix is converted by :meth:`InertiaTensor.from_matrix`); default zero (a point mass).

    Raises
    ------
    ParameterError
        If the mass is not a finite number > 0, the centre of mass not three finite numbers, or
        the tensor not realizable.

    Examples
    --------
    >>> from vehdyn.mechanics import MassProperties, composite, solid_sphere
    >>> ball = MassProperties(2.0, (1.0, 0.0, 0.0), solid_sphere(2.0, 0.1))
    >>> body = composite([ball, ball.moved([-2.0, 0.0, 0.0])])      # two balls 2 m apart
    >>> body.mass, body.centre_of_mass
    (4.0, (0.0, 0.0, 0.0))
    >>> round(body.inertia.izz, 4)                                   # 2 (2/5 m r^2 + m d^2) [kg m^2]
    4.016
    """

    mass: float
    centre_of_mass: tuple = (0.0, 0.0, 0.0)
    inertia: InertiaTensor = dataclasses.field(default_factory=lambda: InertiaTensor(0.0, 0.0, 0.0))

    def __post_init__(self):
        object.__setattr__(self, "mass", _positive(self.mass, "mass", "kg"))
        cg = np.asarray(self.centre_of_mass, dtype=float)
        if cg.shape != (3,) or not np.all(np.isfinite(cg)):
            raise ParameterError(f"centre_of_mass must be three finite numbers [m], got {self.centre_of_mass!r}",
                                 key="centre_of_mass", value=self.centre_of_mass)
        object.__setattr__(self, "centre_of_mass", tuple(float(c) for c in cg))
        if not isinstance(self.inertia, InertiaTensor):
            object.__setattr__(self, "inertia", InertiaTensor.from_matrix(self.inertia))

    def inertia_about(self, point=(0.0, 0.0, 0.0)) -> InertiaTensor:
        """The part's tensor about another point, by the parallel-axis shift.

        Parameters
        ----------
        point : array_like, shape (3,)
            The point in the reference axes [m] (default the origin).

        Returns
        -------
        InertiaTensor
            I_P = I_G + m (|d|^2 E - d d^T), d the centre of mass relative to the point [kg m^2].
        """
        return self.inertia.shifted(self.mass, np.subtract(self.centre_of_mass, np.asarray(point, dtype=float)))

    def rotated(self, rotation) -> "MassProperties":
        """The same part expressed in rotated reference axes.

        Parameters
        ----------
        rotation : array_like, shape (3, 3)
            Proper rotation matrix [-] with v_new = rotation @ v_old.

        Returns
        -------
        MassProperties
            Centre of mass rotation @ r_G, tensor rotation @ I @ rotation.T.
        """
        rot = _rotation(rotation, "rotation")
        return MassProperties(self.mass, rot @ np.asarray(self.centre_of_mass), self.inertia.rotated(rot))

    def moved(self, offset) -> "MassProperties":
        """The same part translated.

        Parameters
        ----------
        offset : array_like, shape (3,)
            Translation [m] in the reference axes.

        Returns
        -------
        MassProperties
            Centre of mass moved by ``offset``; mass and tensor (about the centre of mass) unchanged.
        """
        return MassProperties(self.mass, np.add(self.centre_of_mass, offset), self.inertia)


def composite(parts: Iterable[MassProperties]) -> MassProperties:
    r"""Combine parts into one body: total mass, centre of mass and tensor about that centre.

    .. math::

        m = \sum_i m_i, \qquad \mathbf r_G = \frac{1}{m} \sum_i m_i \mathbf r_i, \qquad
        \mathbf I_G = \sum_i \left[\mathbf I_i + m_i (|\mathbf d_i|^2 \mathbf E
        - \mathbf d_i \mathbf d_i^T)\right], \quad \mathbf d_i = \mathbf r_i - \mathbf r_G

    Parameters
    ----------
    parts : iterable of MassProperties
        The parts, each with its centre of mass and its tensor about that centre, all in the same
        reference axes.

    Returns
    -------
    MassProperties
        The body: its mass [kg], centre of mass [m] and tensor about it [kg m^2].

    Raises
    ------
    ParameterError
        If ``parts`` is empty or holds anything but :class:`vehdyn.mechanics.MassProperties`.

    References
    ----------
    .. [1] H. Goldstein, C. Poole and J. Safko, *Classical Mechanics*, 3rd ed., 2002, sec. 5.3.
    """
    parts = list(parts)
    if not parts or not all(isinstance(p, MassProperties) for p in parts):
        raise ParameterError("composite needs one or more vehdyn.mechanics.MassProperties parts", key="parts",
                             value=parts)
    masses = np.array([p.mass for p in parts])
    centres = np.array([p.centre_of_mass for p in parts]).T  # (3, n)
    total = float(masses.sum())
    cg = centres @ masses / total
    offsets = centres - cg[:, None]
    tensor = sum(p.inertia.matrix for p in parts) + parallel_axis_shift(masses, offsets).sum(axis=-1)
    return MassProperties(total, cg, InertiaTensor.from_matrix(tensor))


# ---------------------------------------------------------------------------- primitives
def _axial(mass_axial: float, mass_transverse: float, axis: str) -> InertiaTensor:
    """A tensor with moment ``mass_axial`` about ``axis`` and ``mass_transverse`` about the others."""
    if axis not in _AXES:
        raise ParameterError(f"axis must be one of {_AXES}, got {axis!r}", key="axis", value=axis)
    moments = [mass_transverse] * 3
    moments[_AXES.index(axis)] = mass_axial
    return InertiaTensor(*moments)


def solid_box(mass: float, length_x: float, width_y: float, height_z: float) -> InertiaTensor:
    """Homogeneous cuboid about its centre, edges along the axes.

    Parameters
    ----------
    mass : float
        Mass m [kg], > 0.
    length_x, width_y, height_z : float
        Full edge lengths a, b, c along x, y and z [m], > 0.

    Returns
    -------
    InertiaTensor
        Ixx = m (b^2 + c^2) / 12, Iyy = m (c^2 + a^2) / 12, Izz = m (a^2 + b^2) / 12 [kg m^2];
        no products.

    References
    ----------
    .. [1] J. L. Meriam and L. G. Kraige, *Engineering Mechanics: Dynamics*, Wiley, the appendix
       table of the mass moments of inertia of homogeneous solids.
    """
    mass = _positive(mass, "mass", "kg")
    a, b, c = (_positive(v, n, "m") for v, n in ((length_x, "length_x"), (width_y, "width_y"), (height_z, "height_z")))
    return InertiaTensor(mass * (b * b + c * c) / 12, mass * (c * c + a * a) / 12, mass * (a * a + b * b) / 12)


def solid_cylinder(mass: float, radius: float, length: float, axis: str = "z") -> InertiaTensor:
    """Homogeneous solid cylinder about its centre.

    Parameters
    ----------
    mass : float
        Mass m [kg], > 0.
    radius : float
        Radius r [m], > 0.
    length : float
        Length L along the cylinder's axis [m], >= 0 (0: a thin disc).
    axis : {"x", "y", "z"}
        The body axis along which the cylinder's axis lies.

    Returns
    -------
    InertiaTensor
        m r^2 / 2 about ``axis``, m (3 r^2 + L^2) / 12 about the transverse axes [kg m^2].

    References
    ----------
    .. [1] J. L. Meriam and L. G. Kraige, *Engineering Mechanics: Dynamics*, Wiley, the appendix
       table of the mass moments of inertia of homogeneous solids.
    """
    return hollow_cylinder(mass, radius, 0.0, length, axis)


def hollow_cylinder(mass: float, outer_radius: float, inner_radius: float, length: float,
                    axis: str = "z") -> InertiaTensor:
    """Homogeneous thick-walled tube about its centre.

    Parameters
    ----------
    mass : float
        Mass m [kg], > 0.
    outer_radius : float
        Outer radius r_o [m], > 0.
    inner_radius : float
        Inner radius r_i [m], 0 <= r_i <= r_o (``inner_radius = outer_radius``: a thin-walled
        tube, m r^2 about its axis).
    length : float
        Length L along the tube's axis [m], >= 0.
    axis : {"x", "y", "z"}
        The body axis along which the tube's axis lies.

    Returns
    -------
    InertiaTensor
        m (r_o^2 + r_i^2) / 2 about ``axis``, m (3 (r_o^2 + r_i^2) + L^2) / 12 about the
        transverse axes [kg m^2].

    References
    ----------
    .. [1] J. L. Meriam and L. G. Kraige, *Engineering Mechanics: Dynamics*, Wiley, the appendix
       table of the mass moments of inertia of homogeneous solids.
    """
    mass = _positive(mass, "mass", "kg")
    ro = _positive(outer_radius, "outer_radius", "m")
    ri = _nonnegative(inner_radius, "inner_radius", "m")
    if ri > ro:
        raise ParameterError(f"inner_radius must be <= outer_radius = {ro:g} m, got {ri!r}", key="inner_radius",
                             value=inner_radius)
    length = _nonnegative(length, "length", "m")
    r2 = ro * ro + ri * ri
    return _axial(mass * r2 / 2, mass * (3 * r2 + length * length) / 12, axis)


def solid_sphere(mass: float, radius: float) -> InertiaTensor:
    """Homogeneous solid sphere about its centre.

    Parameters
    ----------
    mass : float
        Mass m [kg], > 0.
    radius : float
        Radius r [m], > 0.

    Returns
    -------
    InertiaTensor
        2 m r^2 / 5 about every axis [kg m^2].
    """
    mass = _positive(mass, "mass", "kg")
    r = _positive(radius, "radius", "m")
    return _axial(0.4 * mass * r * r, 0.4 * mass * r * r, "z")


def hollow_sphere(mass: float, radius: float) -> InertiaTensor:
    """Thin spherical shell about its centre.

    Parameters
    ----------
    mass : float
        Mass m [kg], > 0.
    radius : float
        Radius r [m], > 0.

    Returns
    -------
    InertiaTensor
        2 m r^2 / 3 about every axis [kg m^2].
    """
    mass = _positive(mass, "mass", "kg")
    r = _positive(radius, "radius", "m")
    return _axial(2.0 * mass * r * r / 3, 2.0 * mass * r * r / 3, "z")


def solid_cone(mass: float, radius: float, height: float, axis: str = "z") -> InertiaTensor:
    """Homogeneous right circular cone about its centre of mass (on the axis, h/4 above the base).

    Parameters
    ----------
    mass : float
        Mass m [kg], > 0.
    radius : float
        Base radius r [m], > 0.
    height : float
        Height h [m], > 0.
    axis : {"x", "y", "z"}
        The body axis along which the cone's axis lies.

    Returns
    -------
    InertiaTensor
        3 m r^2 / 10 about ``axis``; 3 m (r^2 / 20 + h^2 / 80) about the transverse axes through
        the centre of mass [kg m^2].

    References
    ----------
    .. [1] J. L. Meriam and L. G. Kraige, *Engineering Mechanics: Dynamics*, Wiley, the appendix
       table of the mass moments of inertia of homogeneous solids.
    """
    mass = _positive(mass, "mass", "kg")
    r = _positive(radius, "radius", "m")
    h = _positive(height, "height", "m")
    return _axial(0.3 * mass * r * r, 3 * mass * (r * r / 20 + h * h / 80), axis)


def slender_rod(mass: float, length: float, axis: str = "x") -> InertiaTensor:
    """Thin rod along ``axis`` about its centre.

    Parameters
    ----------
    mass : float
        Mass m [kg], > 0.
    length : float
        Length L [m], > 0.
    axis : {"x", "y", "z"}
        The body axis along which the rod lies.

    Returns
    -------
    InertiaTensor
        m L^2 / 12 about the transverse axes, 0 about its own [kg m^2]. The tensor is singular
        (a line mass): use it as a part of a :func:`composite`.
    """
    mass = _positive(mass, "mass", "kg")
    length = _positive(length, "length", "m")
    return _axial(0.0, mass * length * length / 12, axis)


# ---------------------------------------------------------------------------- checks
def _positive(value, name: str, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) \
            or not math.isfinite(value) or not value > 0:
        raise ParameterError(f"{name} must be a finite number > 0 [{unit}], got {value!r}", key=name, value=value)
    return float(value)


def _nonnegative(value, name: str, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) \
            or not math.isfinite(value) or value < 0:
        raise ParameterError(f"{name} must be a finite number >= 0 [{unit}], got {value!r}", key=name, value=value)
    return float(value)


def _rotation(matrix, name: str) -> np.ndarray:
    rot = np.asarray(matrix, dtype=float)
    if rot.shape != (3, 3) or not np.all(np.isfinite(rot)):
        raise ParameterError(f"{name} must be a finite 3x3 rotation matrix, got shape {rot.shape}", key=name,
                             value=matrix)
    if np.max(np.abs(rot @ rot.T - np.eye(3))) > 1e-9 or np.linalg.det(rot) < 0:
        raise ParameterError(f"{name} is not a proper rotation matrix (R R^T = E, det R = +1)", key=name,
                             value=matrix)
    return rot
