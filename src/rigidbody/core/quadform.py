"""Quadratic forms: inertia, leading minors, constrained second variations, numerical Hessians.

Stability by Routh's (or Lagrange's) method asks for the sign pattern of a second variation.  In SI
units the entries of such a Hessian easily span twenty orders of magnitude (an orbit radius of 7e6 m
next to an attitude angle), so a raw ``numpy.linalg.eigvalsh`` mixes round-off of the large entries
into the small eigenvalues.  The helpers here first *equilibrate* the matrix by a congruence with a
positive diagonal matrix, ``H -> D H D`` (Sylvester's law of inertia: the numbers of positive,
negative and zero eigenvalues are unchanged, and so are the signs of all leading minors), and only
then count signs.

Everything is vectorised over leading axes: ``H`` has shape ``(..., n, n)``.

Functions
---------
equilibrate(H)            -> (Hs, d)   Hs = diag(d) H diag(d), rows of Hs of max-norm ~1 (Ruiz scaling)
leading_minors(H)         -> (..., n)  all leading principal minors, computed on the equilibrated matrix
inertia(H, rtol=1e-12)    -> (n_pos, n_neg, n_zero)
null_space_form(H, G)     -> Z^T H Z with Z an orthonormal basis of ker G (constrained second variation)
hessian_fd(f, x, h)       -> 8th-order central-difference Hessian of a scalar function (float64)
gradient_cs(f, x, h)      -> complex-step gradient (no subtractive cancellation)
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "equilibrate",
    "gradient_cs",
    "hessian_fd",
    "inertia",
    "leading_minors",
    "null_space_form",
]


def _as_square_stack(H: ArrayLike, name: str = "H") -> NDArray[np.float64]:
    A = np.asarray(H, dtype=float)
    if A.ndim < 2 or A.shape[-1] != A.shape[-2]:
        raise ValueError(f"{name} must have shape (..., n, n); got {A.shape}")
    return A


def equilibrate(H: ArrayLike, *, iterations: int = 12) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    r"""Symmetric Ruiz equilibration ``Hs = diag(d) H diag(d)`` with ``d > 0``.

    Each pass divides row and column ``i`` by ``sqrt(max_j abs(H_ij))``; after a few passes every row of
    ``Hs`` has max-norm close to one.  The congruence preserves the inertia and the signs of all
    leading principal minors (``det Hs_k = det H_k * prod(d[:k])**2``).  Zero rows are left alone.

    Parameters
    ----------
    H : array_like, shape (..., n, n)
        Symmetric matrices.
    iterations : int
        Number of scaling passes.  Each pass roughly halves the logarithmic imbalance of the rows, so 12
        passes bring a spread of 40 decades to within a few per cent.

    Returns
    -------
    Hs : ndarray, shape (..., n, n)
    d : ndarray, shape (..., n)
        The positive scale factors.

    See Also
    --------
    inertia : the inertia of a form, equilibrated where its signs are not certain.
    leading_minors : the minors of the scaled matrix, scaled back.

    References
    ----------
    D. Ruiz, "A scaling algorithm to equilibrate both rows and columns norms in matrices", Rutherford Appleton
    Laboratory report RAL-TR-2001-034 (2001).

    Examples
    --------
    Entries over thirty decades become numbers near one; the determinant changes by the positive factor
    :math:`\prod d_i^2` (Sylvester's law of inertia):

    >>> import numpy as np
    >>> from rigidbody.core.quadform import equilibrate
    >>> H = np.array([[4e20, 2e10], [2e10, -1.0]])
    >>> Hs, d = equilibrate(H)
    >>> print(np.round(np.abs(Hs).max(axis=1), 2))
    [1.   0.99]
    >>> print(f"{np.linalg.det(Hs):.9f} {np.linalg.det(H) * np.prod(d)**2:.9f}")
    -1.976970532 -1.976970532
    """
    A = _as_square_stack(H).copy()
    d = np.ones(A.shape[:-1])
    for _ in range(iterations):
        r = np.sqrt(np.max(np.abs(A), axis=-1))
        r = np.where(r > 0, r, 1.0)
        A /= r[..., :, None]
        A /= r[..., None, :]
        d /= r
    return A, d


def _det_small(A: NDArray[np.float64]) -> NDArray[np.float64]:
    n = A.shape[-1]
    if n == 1:
        return A[..., 0, 0].copy()
    if n == 2:
        return A[..., 0, 0] * A[..., 1, 1] - A[..., 0, 1] * A[..., 1, 0]
    if n == 3:
        return (
            A[..., 0, 0] * (A[..., 1, 1] * A[..., 2, 2] - A[..., 1, 2] * A[..., 2, 1])
            - A[..., 0, 1] * (A[..., 1, 0] * A[..., 2, 2] - A[..., 1, 2] * A[..., 2, 0])
            + A[..., 0, 2] * (A[..., 1, 0] * A[..., 2, 1] - A[..., 1, 1] * A[..., 2, 0])
        )
    return np.linalg.det(A)


def _scaled_minors(Hs: NDArray[np.float64]) -> NDArray[np.float64]:
    n = Hs.shape[-1]
    return np.stack([_det_small(Hs[..., : k + 1, : k + 1]) for k in range(n)], axis=-1)


def leading_minors(H: ArrayLike) -> NDArray[np.float64]:
    """All leading principal minors ``det H[:k, :k]``, k = 1..n (Sylvester's criterion).

    Computed on the diagonally scaled matrix (Ruiz-equilibrated if a diagonal entry vanishes) and scaled
    back, so their signs are reliable even when the entries of ``H`` span many orders of magnitude.

    Returns
    -------
    ndarray, shape (..., n)

    See Also
    --------
    inertia : the numbers of positive, negative and zero eigenvalues.

    References
    ----------
    F. R. Gantmacher, The Theory of Matrices, vol. 1 (Chelsea, 1959): Sylvester's criterion.

    Examples
    --------
    >>> from rigidbody.core.quadform import leading_minors
    >>> print(leading_minors([[2.0, 1.0], [1.0, 2.0]]).round(12))  # 2 and 2*2 - 1*1
    [2. 3.]
    >>> print(*(f"{m:.6e}" for m in leading_minors([[4e20, 2e10], [2e10, -1.0]])))  # 4e20, -4e20 - 4e20
    4.000000e+20 -8.000000e+20
    """
    A = _as_square_stack(H)
    diag = np.abs(np.diagonal(A, axis1=-2, axis2=-1))
    if np.all(diag > 0):  # one diagonal scaling (a congruence) is enough to balance the products
        d = 1.0 / np.sqrt(diag)
        Hs = A * d[..., :, None] * d[..., None, :]
    else:
        Hs, d = equilibrate(A)
    D = _scaled_minors(Hs)
    scale = np.cumprod(d, axis=-1) ** 2
    return D / scale


def _lead_dets_first(S: NDArray[np.float64]) -> list[NDArray[np.float64]]:
    """Leading minors of matrices stored with the matrix axes FIRST, ``S`` of shape (n, n, ...)."""
    n = S.shape[0]
    out = [S[0, 0]]
    if n >= 2:
        out.append(S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0])
    if n >= 3:
        out.append(
            S[0, 0] * (S[1, 1] * S[2, 2] - S[1, 2] * S[2, 1])
            - S[0, 1] * (S[1, 0] * S[2, 2] - S[1, 2] * S[2, 0])
            + S[0, 2] * (S[1, 0] * S[2, 1] - S[1, 1] * S[2, 0])
        )
    for k in range(4, n + 1):
        out.append(np.linalg.det(np.moveaxis(S[:k, :k], (0, 1), (-2, -1))))
    return out


def inertia(
    H: ArrayLike, *, rtol: float = 1e-12
) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """Inertia (numbers of positive, negative and zero eigenvalues) of symmetric matrices.

    Fast path: scale by the diagonal (``H_ij / sqrt(abs(H_ii H_jj))``, an inertia-preserving congruence)
    and apply Jacobi's rule (the number of negative eigenvalues equals the number of sign changes in
    ``1, D1, ..., Dn``) wherever every leading minor exceeds ``sqrt(rtol)`` times its Hadamard bound
    (so its computed sign is certain).  Elsewhere the matrix is Ruiz-equilibrated and its eigenvalues
    computed; those below ``rtol`` relative to the largest count as zero.

    Parameters
    ----------
    H : array_like, shape (..., n, n)
    rtol : float
        Relative threshold for a zero eigenvalue of the equilibrated matrix.

    Returns
    -------
    n_pos, n_neg, n_zero : integer ndarrays of shape ``H.shape[:-2]`` (0-d arrays for one matrix).

    See Also
    --------
    leading_minors : the minors behind Jacobi's rule.
    null_space_form : the form on the tangent space of constraints, whose inertia decides a constrained
        minimum.

    References
    ----------
    F. R. Gantmacher, The Theory of Matrices, vol. 1 (Chelsea, 1959): Sylvester's law of inertia and
    Jacobi's rule for the signs of the leading minors.

    Examples
    --------
    :math:`[[1, 2], [2, 1]]` has the eigenvalues 3 and -1; :math:`[[1, 1], [1, 1]]` has 2 and 0:

    >>> import numpy as np
    >>> from rigidbody.core.quadform import inertia
    >>> [tuple(int(n) for n in inertia(H)) for H in ([[1.0, 2.0], [2.0, 1.0]], [[1.0, 1.0], [1.0, 1.0]])]
    [(1, 1, 0), (1, 0, 1)]

    Entries sixteen decades apart (an orbit radius next to an angle in SI units) keep their signs:

    >>> tuple(int(n) for n in inertia(np.diag([7e6, -3e-9, 2.0])))
    (2, 1, 0)
    """
    A = _as_square_stack(H)
    if not np.all(np.isfinite(A)):
        raise ValueError("H contains non-finite entries")
    At = np.swapaxes(A, -1, -2)
    dg = np.abs(np.diagonal(A, axis1=-2, axis2=-1))
    # relative to each entry and to the geometric mean of its diagonal (entries may span 20 decades)
    scale = np.abs(A) + np.abs(At) + np.sqrt(dg[..., :, None] * dg[..., None, :])
    if np.any(np.abs(A - At) > 1e-8 * scale):
        raise ValueError("H must be symmetric (the inertia of a quadratic form is that of its symmetric matrix)")
    n = A.shape[-1]
    S = np.ascontiguousarray(np.moveaxis(A, (-2, -1), (0, 1)))
    diag = np.abs(np.stack([S[i, i] for i in range(n)]))
    d = np.where(diag > 0, 1.0 / np.sqrt(np.where(diag > 0, diag, 1.0)), 1.0)
    S = S * d[:, None] * d[None, :]
    D = _lead_dets_first(S)
    row2 = S * S
    n_neg = np.zeros(A.shape[:-2], dtype=np.int64)
    reliable = np.ones(A.shape[:-2], dtype=bool)
    prev = np.ones(A.shape[:-2])
    tol = np.sqrt(rtol)
    for k in range(n):
        bound = np.prod(np.sqrt(np.sum(row2[: k + 1, : k + 1], axis=1)), axis=0)
        reliable &= np.abs(D[k]) > tol * bound
        n_neg += (D[k] * prev < 0).astype(np.int64)
        prev = D[k]
    n_zero = np.zeros_like(n_neg)
    bad = ~reliable
    if np.any(bad):
        Hs, _ = equilibrate(A[bad])
        ev = np.linalg.eigvalsh(Hs)
        big = np.max(np.abs(ev), axis=-1, keepdims=True)
        big = np.where(big > 0, big, 1.0)
        zero = np.abs(ev) <= rtol * big
        n_neg[bad] = np.sum((ev < 0) & ~zero, axis=-1)
        n_zero[bad] = np.sum(zero, axis=-1)
    n_pos = n - n_neg - n_zero
    return n_pos, n_neg, n_zero


def null_space_form(H: ArrayLike, G: ArrayLike) -> NDArray[np.float64]:
    """Second variation restricted to the tangent space of linear constraints: ``Z^T H Z``.

    Parameters
    ----------
    H : array_like, shape (n, n)
        Hessian of the Lagrange function ``W + lambda . chi``.
    G : array_like, shape (m, n) or (n,)
        Gradients of the constraints (rows), assumed of full rank ``m``.

    Returns
    -------
    ndarray, shape (n - m, n - m)
        The form in an orthonormal basis ``Z`` of ``ker G`` (its inertia, not its entries, is
        basis-independent).

    See Also
    --------
    inertia : the signs of the restricted form.
    rigidbody.gyrostat.constrained_second_variation : the constrained second variation of the gyrostat.

    References
    ----------
    F. R. Gantmacher, The Theory of Matrices, vol. 1 (Chelsea, 1959) (quadratic forms on a subspace);
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5).

    Examples
    --------
    The form :math:`x^2 + y^2 - z^2` is indefinite, but positive definite on the plane :math:`z = 0`:

    >>> import numpy as np
    >>> from rigidbody.core.quadform import inertia, null_space_form
    >>> Hz = null_space_form(np.diag([1.0, 1.0, -1.0]), [0.0, 0.0, 1.0])
    >>> Hz.shape, tuple(int(n) for n in inertia(Hz))
    ((2, 2), (2, 0, 0))
    """
    from scipy.linalg import null_space

    Hm = _as_square_stack(H)
    Gm = np.atleast_2d(np.asarray(G, dtype=float))
    if Gm.shape[-1] != Hm.shape[-1]:
        raise ValueError(f"G must have {Hm.shape[-1]} columns; got shape {Gm.shape}")
    Z = null_space(Gm)
    return Z.T @ Hm @ Z


# central-difference weights for the first derivative, O(h^8)
_FD8 = ((1, 4.0 / 5.0), (2, -1.0 / 5.0), (3, 4.0 / 105.0), (4, -1.0 / 280.0))


def hessian_fd(
    f: Callable[[NDArray[np.float64]], float], x: ArrayLike, h: ArrayLike | float = 1e-3
) -> NDArray[np.float64]:
    """Hessian of a scalar function by nested 8th-order central differences (float64).

    Truncation error O(h^8), round-off ~ eps abs(f) / h^2: useful when the function's value is not many
    orders of magnitude larger than its second variation (nondimensional problems).  For SI-scale
    problems evaluate ``f`` in extended precision instead (e.g. mpmath in tests).

    Parameters
    ----------
    f : callable
        ``f(x) -> float`` for a 1-D array ``x``.
    x : array_like, shape (n,)
    h : float or array_like, shape (n,)
        Step per coordinate.

    Returns
    -------
    numpy.ndarray, shape (n, n)
        The symmetric matrix of second derivatives.

    See Also
    --------
    gradient_cs : first derivatives by the complex step.

    References
    ----------
    B. Fornberg, "Generation of finite difference formulas on arbitrarily spaced grids", Mathematics of
    Computation 51(184), 699-706 (1988) (the central-difference weights).

    Examples
    --------
    A cubic is differentiated exactly (to rounding) by the 8th-order formula:
    :math:`f = x_0^2x_1 + x_1^3` has the Hessian :math:`[[2x_1, 2x_0], [2x_0, 6x_1]]`:

    >>> from rigidbody.core.quadform import hessian_fd
    >>> print(hessian_fd(lambda x: x[0]**2 * x[1] + x[1]**3, [1.0, 2.0]).round(8))
    [[ 4.  2.]
     [ 2. 12.]]
    """
    x0 = np.asarray(x, dtype=float)
    n = x0.size
    hv = np.broadcast_to(np.asarray(h, dtype=float), (n,))

    def d1(g: Callable[[NDArray[np.float64]], float], y: NDArray[np.float64], i: int) -> float:
        acc = 0.0
        for m, w in _FD8:
            e = np.zeros(n)
            e[i] = m * hv[i]
            acc += w * (g(y + e) - g(y - e))
        return acc / hv[i]

    H = np.empty((n, n))
    for i in range(n):
        for j in range(i, n):
            def dfj(y: np.ndarray, j: int = j) -> float:
                return d1(f, y, j)

            H[i, j] = H[j, i] = d1(dfj, x0, i)
    return H


def gradient_cs(
    f: Callable[[NDArray[np.complex128]], complex], x: ArrayLike, h: float = 1e-30
) -> NDArray[np.float64]:
    """Complex-step gradient ``df/dx_i = Im f(x + i h e_i) / h`` (exact to round-off, no cancellation).

    ``f`` must be analytic and written with functions that accept complex arguments (``numpy``/
    ``cmath``, not ``math``), with real branches chosen explicitly (no ``abs``).

    Parameters
    ----------
    f : callable
        Scalar function of a complex vector of the shape of ``x``.
    x : array_like
        Point (real), flattened.
    h : float
        Imaginary step; any tiny value works since no difference is taken.

    Returns
    -------
    numpy.ndarray
        The gradient, shape ``(x.size,)``.

    See Also
    --------
    hessian_fd : second derivatives by finite differences.

    References
    ----------
    W. Squire, G. Trapp, "Using complex variables to estimate derivatives of real functions", SIAM Review
    40(1), 110-112 (1998).

    Examples
    --------
    :math:`f = x_0^2 e^{x_1}` has the gradient :math:`(2x_0e^{x_1}, x_0^2e^{x_1}) = (3, 2.25)` at
    :math:`(1.5, 0)`:

    >>> import numpy as np
    >>> from rigidbody.core.quadform import gradient_cs
    >>> print(gradient_cs(lambda z: z[0]**2 * np.exp(z[1]), [1.5, 0.0]).round(14))
    [3.   2.25]
    """
    x0 = np.asarray(x, dtype=float)
    g = np.empty(x0.size)
    for i in range(x0.size):
        z = x0.astype(complex)
        z[i] += 1j * h
        g[i] = np.imag(f(z)) / h
    return g
