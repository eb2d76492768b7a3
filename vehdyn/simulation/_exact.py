"""``method="exact"``: the exact discretization of a :class:`~vehdyn.LinearModel` through the matrix
exponential, and the recurrence it defines evaluated as a parallel prefix scan.

For inputs held constant (zero-order hold) or linear (first-order hold) between samples, the
state of dx/dt = A x + B u at the next sample is an exact linear function of the state and the
inputs: one matrix exponential per distinct step size gives it (:func:`exact_discretization`;
Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed., sec. 4.3 and 6.3.2).
The recurrence x[k+1] = Ad x[k] + g[k] is then evaluated in log2(N) array passes of
``c[d:] += Ad^d c[:-d]`` instead of N Python iterations.
"""

from __future__ import annotations

import math

import numpy as np

from vehdyn.errors import ParameterError


def exact_discretization(A: np.ndarray, B: np.ndarray, dt: float, hold: str = "zoh"):
    r"""Exact discretization of dx/dt = A x + B u over one step ``dt``.

    Parameters
    ----------
    A : array_like
        State matrix (n, n) [1/s].
    B : array_like
        Input matrix (n, m) [state unit / (input unit s)].
    dt : float
        Step [s].
    hold : {"zoh", "foh"}
        How the input varies over the step: held at its first sample (zero-order hold) or linear
        between its two samples (first-order hold).

    Returns
    -------
    Ad : ndarray
        State transition matrix e^(A dt) (n, n) [-].
    B0, B1 : ndarray
        Input matrices (n, m) [state unit / input unit] of the samples at the start and the end of
        the step; ``B1`` is zero for a zero-order hold.

    Notes
    -----
    The state at the end of the step is

    .. math::

        x_{k+1} = A_d\, x_k + B_0\, u_k + B_1\, u_{k+1}, \qquad A_d = e^{A\,\Delta t}.

    One matrix exponential of a block matrix gives every term (Van Loan 1978, Theorem 1):

    .. math::

        \exp\begin{bmatrix} A\,\Delta t & B\,\Delta t & 0 \\ 0 & 0 & I \\ 0 & 0 & 0 \end{bmatrix}
        = \begin{bmatrix} A_d & \Gamma_1 & \Gamma_2 \\ 0 & I & I \\ 0 & 0 & I \end{bmatrix},
        \qquad
        \Gamma_1 = \int_0^{\Delta t} e^{A s}\, ds\, B, \quad
        \Gamma_2 = \int_0^{\Delta t} e^{A s}\, \frac{\Delta t - s}{\Delta t}\, ds\, B,

    so that :math:`B_0 = \Gamma_1,\ B_1 = 0` for the zero-order hold and
    :math:`B_0 = \Gamma_1 - \Gamma_2,\ B_1 = \Gamma_2` for the first-order hold (Franklin, Powell
    & Workman, sec. 4.3.1 and 6.3.2). The exponential is scipy's scaling and squaring with Padé
    approximants (Al-Mohy & Higham 2009), the method Moler & Van Loan recommend.

    References
    ----------
    .. [1] C. F. Van Loan, "Computing integrals involving the matrix exponential", *IEEE
       Transactions on Automatic Control* 23(3), 395-404, 1978.
    .. [2] C. Moler and C. F. Van Loan, "Nineteen dubious ways to compute the exponential of a
       matrix, twenty-five years later", *SIAM Review* 45(1), 3-49, 2003.
    .. [3] G. F. Franklin, J. D. Powell and M. L. Workman, *Digital Control of Dynamic Systems*,
       3rd ed., Addison-Wesley, 1998, sec. 4.3 and 6.3.2.
    .. [4] A. H. Al-Mohy and N. J. Higham, "A new scaling and squaring algorithm for the matrix
       exponential", *SIAM Journal on Matrix Analysis and Applications* 31(3), 970-989, 2009.

    Examples
    --------
    A first-order lag dx/dt = -2 x + 2 u sampled at 10 Hz: Ad = e^(-0.2), and under a zero-order
    hold B0 = 1 - e^(-0.2).

    >>> import numpy as np
    >>> from vehdyn.simulation import exact_discretization
    >>> Ad, B0, B1 = exact_discretization(np.array([[-2.0]]), np.array([[2.0]]), 0.1)
    >>> round(float(Ad[0, 0]), 12), round(float(B0[0, 0]), 12), float(B1[0, 0])
    (0.818730753078, 0.181269246922, 0.0)
    """
    from scipy.linalg import expm

    A, B = np.asarray(A, dtype=float), np.asarray(B, dtype=float)
    if A.ndim != 2 or B.ndim != 2 or A.shape != (B.shape[0], B.shape[0]):
        raise ParameterError(f"A must be (n, n) and B (n, m), got shapes {A.shape} and {B.shape}", key="A",
                             value=A.shape)
    number = isinstance(dt, (int, float, np.floating, np.integer)) and not isinstance(dt, bool)
    if not (number and math.isfinite(dt) and dt > 0):
        raise ParameterError(f"dt must be a positive, finite number [s], got {dt!r}", key="dt", value=dt)
    if hold not in ("zoh", "foh"):
        raise ParameterError(f"hold must be 'zoh' or 'foh', got {hold!r}", key="hold", value=hold)
    n, m = B.shape
    if hold == "zoh":
        blk = np.zeros((n + m, n + m))
        blk[:n, :n] = A * dt
        blk[:n, n:] = B * dt
        E = expm(blk)
        return E[:n, :n], E[:n, n:], np.zeros((n, m))
    blk = np.zeros((n + 2 * m, n + 2 * m))
    blk[:n, :n] = A * dt
    blk[:n, n:n + m] = B * dt
    blk[n:n + m, n + m:] = np.eye(m)
    E = expm(blk)
    Ad, G1, G2 = E[:n, :n], E[:n, n:n + m], E[:n, n + m:]
    return Ad, G1 - G2, G2


def _linear_recurrence(Ad: np.ndarray, g: np.ndarray) -> np.ndarray:
    """All partial sums c[k] = sum_{j<=k} Ad^(k-j) g[j] by a Hillis-Steele prefix scan.

    g has shape (N, n, ...); the scan does ceil(log2 N) passes of c[d:] += Ad^d c[:-d].
    """
    c = g.copy()
    N = c.shape[0]
    P = Ad.copy()
    d = 1
    while d < N:
        # the product is formed before the in-place add, so the overlap of c[d:] and c[:-d] is safe
        c[d:] += (c[:-d] @ P.T) if c.ndim == 2 else (P @ c[:-d])
        d *= 2
        if d < N:
            P = P @ P
    return c


def _simulate_exact(model, t, u, x0, hold):
    """States (n, n_t[, n_batch]) of a LinearModel on the grid ``t`` and the number of matrix
    exponentials it took: one on a uniform grid (then the prefix scan), else one per distinct step."""
    A, B = model.A, model.B
    n = A.shape[0]
    dts = np.diff(t)
    N = t.size
    batch_shape = x0.shape[1:]
    if u.ndim == 3 and not batch_shape:
        batch_shape = u.shape[2:]
    x = np.empty((N, n) + tuple(batch_shape))
    x0b = np.broadcast_to(x0.reshape((n,) + x0.shape[1:] + (1,) * (len(batch_shape) - len(x0.shape[1:]))),
                          (n,) + tuple(batch_shape))
    uT = np.moveaxis(u, 1, 0)  # (N, m, ...)
    if uT.ndim - 2 < len(batch_shape):
        uT = np.broadcast_to(uT[..., None], uT.shape + tuple(batch_shape))
    x[0] = x0b
    uniform = np.allclose(dts, dts[0], rtol=1e-9, atol=0.0)
    if uniform:
        Ad, B0, B1 = exact_discretization(A, B, float(np.mean(dts)), hold)
        if uT.ndim == 2:
            g = uT[:-1] @ B0.T
            if hold == "foh":
                g += uT[1:] @ B1.T
        else:
            g = B0 @ uT[:-1]
            if hold == "foh":
                g += B1 @ uT[1:]
        g[0] += Ad @ x0b
        x[1:] = _linear_recurrence(Ad, g)
        n_expm = 1
    else:
        # one discretization per distinct step size; the recurrence then runs step by step
        cache: dict[float, tuple] = {}
        for k, dt in enumerate(dts):
            key = float(np.round(dt, 15))
            if key not in cache:
                cache[key] = exact_discretization(A, B, dt, hold)
            Ad, B0, B1 = cache[key]
            x[k + 1] = Ad @ x[k] + B0 @ uT[k] + (B1 @ uT[k + 1] if hold == "foh" else 0.0)
        n_expm = len(cache)
    return np.moveaxis(x, 0, 1), n_expm
