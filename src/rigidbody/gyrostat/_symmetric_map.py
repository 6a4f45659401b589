"""Vectorised verdicts of the motions (3.2) of a dynamically symmetric satellite over parameter grids."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.quadform import inertia, leading_minors
from ._family import SINGULAR_TOL, broadcast_shape, check_omega_sign, float_arrays
from ._model import Satellite
from ._secondvar import VERDICTS, verdict_codes
from ._symmetric import check_symmetric, symmetric_derivatives, symmetric_family_arrays
from ._symmetric_stability import W_thetatheta_stable

__all__ = ["SymmetricStabilityMap", "symmetric_stability_map"]


@dataclass(frozen=True)
class SymmetricStabilityMap:
    """Verdicts of the motions (3.2) over a grid (codes as in :class:`rigidbody.gyrostat.StabilityMap`).

    See Also
    --------
    symmetric_stability_map : the function that returns it.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (3.4).

    Examples
    --------
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
    >>> sm = gyrostat.symmetric_stability_map(sat, 1.0, [0.5, 1.0], A3=[0.006, 0.012])
    >>> sm.code
    array([[0, 1],
           [0, 1]], dtype=int8)
    """

    params: dict[str, np.ndarray]
    kappa0: np.ndarray
    omega0: np.ndarray
    c: np.ndarray
    W_psipsi: np.ndarray
    minors: np.ndarray
    degree: np.ndarray
    code: np.ndarray

    @property
    def verdict(self) -> np.ndarray:
        """Verdict strings ('stable', 'unstable', 'undecided', 'invalid').

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
        >>> gyrostat.symmetric_stability_map(sat, 1.0, [0.5], A3=[0.006, 0.012]).verdict
        array(['stable', 'unstable'], dtype='<U9')
        """
        names = np.array([VERDICTS[0], VERDICTS[1], VERDICTS[2], VERDICTS[-1]])
        return names[np.where(self.code < 0, 3, self.code)]

    @property
    def paper_condition(self) -> np.ndarray:
        """(3.4) > 0.

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
        >>> gyrostat.symmetric_stability_map(sat, 1.0, [0.5], A3=[0.006, 0.012]).paper_condition
        array([ True, False])
        """
        return self.W_psipsi > 0


def symmetric_stability_map(
    sat: Satellite, R0: Any, theta0: Any, *, omega_sign: int = 1, grid: bool = True, rtol: float = 1e-12,
    **overrides: Any,
) -> SymmetricStabilityMap:
    r"""Vectorised verdicts of the motions (3.2) from the full 4x4 second variation.

    Parameters as in :func:`rigidbody.gyrostat.stability_map`; overridable: ``M, A1, A3, mu`` (A2 = A1).
    With ``grid=True`` the 1-D arrays among theta0, R0, M, A1, A3, mu form an outer grid in that order.
    Points with sin theta0 = 0 (Euler chart) or no motion get code -1.

    Returns
    -------
    SymmetricStabilityMap

    See Also
    --------
    stability : one motion, with its Hessian.
    stability_map : the motions (2.3) of a triaxial satellite.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (3.4) and the statements after it.

    Examples
    --------
    At :math:`\theta_0 = \pi/4`: stable for :math:`A_3 < A_1`; unstable (degree 1) for
    :math:`A_1 < A_3 < \frac43A_1`, as the paper says of (3.4) reversed; beyond :math:`3A_3 = 4A_1` the degree is 2
    and the claim fails (:doc:`/gyrostat`):

    >>> import math
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.01, A2=0.01, A3=0.006)
    >>> sm = gyrostat.symmetric_stability_map(sat, 1.0, math.pi / 4, A3=[0.006, 0.012, 0.0145])
    >>> sm.verdict, sm.degree
    (array(['stable', 'unstable', 'undecided'], dtype='<U9'), array([0, 1, 2]))
    """
    check_symmetric(sat)
    omega_sign = check_omega_sign(omega_sign)
    bad = set(overrides) - {"M", "A1", "A3", "mu"}
    if bad:
        raise TypeError(f"unknown parameter(s) {sorted(bad)}; overridable: M, A1, A3, mu")
    vals = {"theta0": theta0, "R0": R0, "M": overrides.get("M", sat.M), "A1": overrides.get("A1", sat.A1),
            "A3": overrides.get("A3", sat.A3), "mu": overrides.get("mu", sat.mu)}
    arrs = float_arrays(vals)
    if grid:
        axes = [n for n in arrs if arrs[n].ndim == 1 and arrs[n].size != 1]
        for n, m in zip(axes, np.meshgrid(*[arrs[n] for n in axes], indexing="ij")):
            arrs[n] = m
    shape = broadcast_shape(arrs)
    P = {n: np.broadcast_to(v, shape) for n, v in arrs.items()}
    f = symmetric_family_arrays(P["M"], P["A1"], P["A3"], P["mu"], P["R0"], P["theta0"], omega_sign)
    physical = (P["A3"] > 0) & (P["A1"] > 0) & (P["A3"] <= 2 * P["A1"] * (1 + 1e-12)) & (P["M"] > 0)
    with np.errstate(all="ignore"):  # the body fits inside its orbit (see check_fits)
        physical &= (P["mu"] > 0) & (P["R0"] > 0) & (P["R0"] ** 2 > (2 * P["A1"] + P["A3"]) / (2 * P["M"]))
    valid = f["exists"] & physical & (np.abs(f["sin_t"]) > SINGULAR_TOL) & (np.abs(f["cos_tk"]) > SINGULAR_TOL)
    with np.errstate(all="ignore"):
        _, H = symmetric_derivatives(P["M"], P["A1"], P["A3"], P["mu"], f["k"], f["c"], P["R0"], f["kappa0"],
                                     f["theta0"], np.pi + 0 * f["kappa0"])
    H = np.array(H)
    with np.errstate(all="ignore"):
        H[..., 2, 2] = W_thetatheta_stable(P["M"], P["A1"], P["A3"], P["mu"], P["R0"], f["theta0"], f["kappa0"],
                                           f["omega0"], f["c"])
    H[..., 3, :3] = 0.0  # the psi row decouples at psi = pi (sin psi = 0 analytically)
    H[..., :3, 3] = 0.0
    valid &= np.all(np.isfinite(H), axis=(-1, -2))
    n_neg = np.full(shape, -1, dtype=np.int64)
    code = np.full(shape, -1, dtype=np.int8)
    minors = np.full((*shape, 4), np.nan)
    if np.any(valid):
        _, nn, nz = inertia(H[valid], rtol=rtol)
        n_neg[valid] = nn
        code[valid] = verdict_codes(nn, nz)
        minors[valid] = leading_minors(H[valid])
    W_pp = np.where(valid, H[..., 3, 3], np.nan)
    return SymmetricStabilityMap(params=P, kappa0=f["kappa0"], omega0=f["omega0"], c=f["c"], W_psipsi=W_pp,
                                 minors=minors, degree=n_neg, code=code)
