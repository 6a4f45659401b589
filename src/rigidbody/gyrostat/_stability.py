"""Second variation of W1 at the motions (2.3), Sylvester conditions (2.5), verdicts (sections 2, 4)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.quadform import inertia
from ._model import Satellite
from ._stationary import SINGULAR_TOL, StationaryMotion

__all__ = [
    "VERDICTS",
    "Stability",
    "constrained_second_variation",
    "hessian_W1",
    "hessian_W1_numerical",
    "restricted_conditions",
    "stability_arrays",
]

#: verdict codes used by the vectorised routines; -1 marks "no motion / singular chart"
VERDICTS = {0: "stable", 1: "unstable", 2: "undecided", -1: "invalid"}

#: order of the coordinates of the 6x6 Hessian
COORDS = ("R", "kappa", "beta1", "beta3", "gamma1", "gamma2")
#: order of the independent coordinates of the constrained 5x5 second variation
CONSTRAINED_COORDS = ("gamma1", "beta1", "R", "kappa", "beta3")


def hessian_entries(
    M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R0: Any, theta0: Any, kappa0: Any, omega0: Any, k2: Any,
    S0: Any, form: str = "stable",
) -> dict[str, np.ndarray]:
    """The second derivatives of W1 at (2.3) (printed in section 2 after (2.4)); vectorised.

    Keys: ``RR, kk, b1b1, b3b3, g1g1, g2g2, Rk, Rb3, kb3, Rg2, b1g1, b3g2`` (k = kappa, b = beta,
    g = gamma); all other second derivatives vanish.  Every printed entry was verified against
    extended-precision numerical derivatives of W1 (tests/gyrostat/test_gyrostat_hessian.py); none is
    misprinted.

    Parameters
    ----------
    form : {"stable", "printed"}
        ``"printed"``: the paper's expressions literally, with ``lambda0 = M R0^2 omega0^2 sin kappa0``.
        ``"stable"`` (default): the same values with ``M R0^2 omega0^2 sin kappa0`` replaced through the
        third relation (2.4) by ``G sin theta0 cos theta0 / cos kappa0``, ``G = 3 mu R0^-3 (A2 - A3)``.
        This matters in SI units: the printed ``W_g2g2 = -lambda0 sin(theta0+kappa0)/cos^3 theta0 +
        G`` is a difference of two terms equal to O(l^2/R^2) (at theta0 = pi/4 the leading terms
        cancel exactly), whereas the stable form ``G [cos 2theta0 - sin 2theta0 tan kappa0 / 2] /
        cos^2 theta0`` has no cancellation.
    """
    if form not in ("stable", "printed"):
        raise ValueError(f"form must be 'stable' or 'printed'; got {form!r}")
    M, A1, A2, A3, mu, R, th, kap, om, k2, S = (
        np.asarray(v, dtype=float) for v in (M, A1, A2, A3, mu, R0, theta0, kappa0, omega0, k2, S0)
    )
    with np.errstate(divide="ignore", invalid="ignore"):
        n0 = mu / R**3
        ck, sk = np.cos(kap), np.sin(kap)
        s2k = np.sin(2 * kap)
        st, ct = np.sin(th), np.cos(th)
        sp, cp = np.sin(th + kap), np.cos(th + kap)
        MR2 = M * R**2
        L = MR2 * om**2 * sk  # = lambda0
        Q = MR2 * s2k / (2 * cp) - (A2 - A3) * sp
        e = {}
        e["RR"] = (
            (4 * MR2 * ck**2 - S) / S * M * om**2 * ck**2
            - 2 * M * n0
            + 18 * n0 / R**2 * ((A2 - A3) * st**2 + (2 * A3 - A1 - A2) / 3)
        )
        e["kk"] = MR2 / S * om**2 * (S * ck**2 + MR2 * s2k**2)
        e["b1b1"] = L * st / cp + (A2 - A1) * om**2 + om * k2 / cp
        e["b3b3"] = L * st / cp**3 + (A2 - A3) * om**2 + om * k2 / cp**3 + om**2 / S * Q**2
        e["g1g1"] = -L * sp / ct + 3 * n0 * (A1 - A3)
        e["g2g2"] = -L * sp / ct**3 + 3 * n0 * (A2 - A3)
        e["b3g2"] = -MR2 * om**2 * sk**2 / (ct * cp)
        e["b1g1"] = L + 0 * om
        if form == "stable":
            G = 3 * n0 * (A2 - A3)
            Ls = G * st * ct / ck  # = lambda0 by the third relation (2.4)
            e["b1b1"] = Ls * st / cp + (A2 - A1) * om**2 + om * k2 / cp
            e["b3b3"] = Ls * st / cp**3 + (A2 - A3) * om**2 + om * k2 / cp**3 + om**2 / S * Q**2
            e["g1g1"] = 3 * n0 * (A1 - A3) - G * st * sp / ck
            e["g2g2"] = G * (np.cos(2 * th) - 0.5 * np.sin(2 * th) * np.tan(kap)) / ct**2
            e["b3g2"] = -Ls * sk / (ct * cp)
            e["b1g1"] = Ls + 0 * om
        e["Rk"] = -(2 * MR2 * ck**2 - S) / S * M * R * om**2 * s2k
        e["Rb3"] = 2 * M * R * om**2 * ck**2 / S * Q
        e["kb3"] = -MR2 * om**2 * s2k / S * Q
        e["Rg2"] = 9 * mu * (A2 - A3) * st / R**4
    return e


def _hessian_matrix(e: dict[str, np.ndarray]) -> np.ndarray:
    shape = np.broadcast(*e.values()).shape
    H = np.zeros((*shape, 6, 6))
    idx = {"R": 0, "k": 1, "b1": 2, "b3": 3, "g1": 4, "g2": 5}
    pairs = {
        "RR": ("R", "R"), "kk": ("k", "k"), "b1b1": ("b1", "b1"), "b3b3": ("b3", "b3"),
        "g1g1": ("g1", "g1"), "g2g2": ("g2", "g2"), "Rk": ("R", "k"), "Rb3": ("R", "b3"),
        "kb3": ("k", "b3"), "Rg2": ("R", "g2"), "b1g1": ("b1", "g1"), "b3g2": ("b3", "g2"),
    }
    for key, (p, q) in pairs.items():
        H[..., idx[p], idx[q]] = e[key]
        H[..., idx[q], idx[p]] = e[key]
    return H


def a_matrix(e: dict[str, np.ndarray], theta0: Any, kappa0: Any) -> np.ndarray:
    """The symmetric matrix a_ij of (2.5): the (R, kappa, beta3) block after eliminating delta gamma2."""
    th, kap = np.asarray(theta0, dtype=float), np.asarray(kappa0, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        ct, cp = np.cos(th), np.cos(th + kap)
        q = ct / cp
        a11 = e["RR"]
        a22 = e["kk"] + ct**2 * e["g2g2"]
        a33 = e["b3b3"] + q**2 * e["g2g2"] - 2 * q * e["b3g2"]
        a12 = e["Rk"] + ct * e["Rg2"]
        a13 = e["Rb3"] - q * e["Rg2"]
        a23 = e["kb3"] - ct * q * e["g2g2"] + ct * e["b3g2"]
    rows = np.broadcast_arrays(a11, a12, a13, a12, a22, a23, a13, a23, a33)
    return np.stack(rows, axis=-1).reshape(*rows[0].shape, 3, 3)


def restricted_conditions(A1: Any, A2: Any, A3: Any, theta0: Any, k2: Any, omega0: Any) -> tuple:
    """The restricted-problem inequalities printed after (2.5) (Rumyantsev [1]), as quantities > 0.

    Returns
    -------
    r1 : A1 - A2 sin^2 theta0 - A3 cos^2 theta0                (limit of s1 > 0)
    r2 : A2 - A3 + k2 / (4 omega0 cos^3 theta0)                (limit of s3 > 0, i.e. a33 > 0)
    r3 : r1 (A2 - A1 + k2 / (omega0 cos theta0)) + 3 (A1 - A2)(A2 - A3) sin^2 theta0   (limit of s2 > 0)
    """
    A1, A2, A3, th, k2, om = (np.asarray(v, dtype=float) for v in (A1, A2, A3, theta0, k2, omega0))
    st2, ct = np.sin(th) ** 2, np.cos(th)
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = A1 - A2 * st2 - A3 * ct**2
        r2 = A2 - A3 + k2 / (4 * om * ct**3)
        r3 = r1 * (A2 - A1 + k2 / (om * ct)) + 3 * (A1 - A2) * (A2 - A3) * st2
    return r1, r2, r3


def _verdict_codes(n_neg: np.ndarray, n_zero: np.ndarray) -> np.ndarray:
    code = np.full(n_neg.shape, 2, dtype=np.int8)
    code[(n_neg == 0) & (n_zero == 0)] = 0
    code[(n_neg % 2 == 1) & (n_zero == 0)] = 1
    return code


def stability_arrays(f: dict[str, np.ndarray], M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R0: Any,
                     rtol: float = 1e-12) -> dict[str, np.ndarray]:
    """Vectorised stability data for stationary motions given by :func:`family_arrays` output ``f``.

    Invalid points (no motion, or the chart singular: abs(cos theta0) or abs(cos(theta0 + kappa0)) <= 1e-6)
    get code -1 and NaN quantities.
    """
    e = hessian_entries(M, A1, A2, A3, mu, R0, f["theta0"], f["kappa0"], f["omega0"], f["k2"], f["S0"])
    a = a_matrix(e, f["theta0"], f["kappa0"])
    # the chart (beta1, beta3, gamma1, gamma2) is singular at cos theta0 = 0 or cos(theta0 + kappa0) = 0
    valid = f["exists"] & (np.abs(f["cos_t"]) > SINGULAR_TOL) & (np.abs(f["cos_tk"]) > SINGULAR_TOL)
    for v in e.values():
        valid = valid & np.isfinite(v)
    valid = valid & np.all(np.isfinite(a), axis=(-1, -2))
    shape = np.broadcast_shapes(valid.shape, a.shape[:-2], *(np.shape(v) for v in e.values()))
    valid = np.broadcast_to(valid, shape)
    a = np.broadcast_to(a, (*shape, 3, 3))
    s1 = np.broadcast_to(e["g1g1"], shape)
    s2 = np.broadcast_to(e["g1g1"] * e["b1b1"] - e["b1g1"] ** 2, shape)
    B = np.stack([np.broadcast_to(v, shape) for v in (e["g1g1"], e["b1g1"], e["b1g1"], e["b1b1"])], axis=-1)
    B = B.reshape(*shape, 2, 2)
    n_neg = np.zeros(shape, dtype=np.int64)
    n_zero = np.zeros(shape, dtype=np.int64)
    if np.any(valid):
        _, nb, zb = inertia(B[valid], rtol=rtol)
        _, na, za = inertia(a[valid], rtol=rtol)
        n_neg[valid] = nb + na
        n_zero[valid] = zb + za
    code = _verdict_codes(n_neg, n_zero)
    code[~valid] = -1
    with np.errstate(invalid="ignore", over="ignore"):
        s3 = (a[..., 0, 0] * (a[..., 1, 1] * a[..., 2, 2] - a[..., 1, 2] ** 2)
              - a[..., 0, 1] * (a[..., 0, 1] * a[..., 2, 2] - a[..., 1, 2] * a[..., 0, 2])
              + a[..., 0, 2] * (a[..., 0, 1] * a[..., 1, 2] - a[..., 1, 1] * a[..., 0, 2]))
        a2 = a[..., 0, 0] * a[..., 1, 1] - a[..., 0, 1] ** 2
        minors = np.stack([s1, s2, s2 * a[..., 0, 0], s2 * a2, s2 * s3], axis=-1)
        jac = -(np.cos(f["kappa0"]) ** 2 / f["cos_t"] ** 2) * s2 * s3
    nan = np.where(valid, 1.0, np.nan)
    return {
        "e": e, "a": a, "s1": s1 * nan, "s2": s2 * nan, "s3": s3 * nan, "minors": minors * nan[..., None],
        "n_neg": np.where(valid, n_neg, -1), "n_zero": np.where(valid, n_zero, -1), "code": code,
        "jacobian": jac * nan, "valid": valid,
    }


def hessian_W1(sat: Satellite, m: StationaryMotion, *, form: str = "stable") -> np.ndarray:
    """The 6x6 Hessian of W1 at the motion ``m`` from the closed forms (order :data:`COORDS`).

    ``form``: "stable" (default) or "printed", see :func:`hessian_entries`. The twelve nonzero entries are
    those printed in section 2 after (2.4), evaluated at the motion (2.3); they feed the second variation
    (2.5) (:func:`constrained_second_variation`).

    Parameters
    ----------
    sat : Satellite
        Must have the mass properties (``M, A1, A2, A3, mu``) the motion was computed for.
    m : StationaryMotion
        A member of the family (2.3)-(2.4), from :func:`~rigidbody.gyrostat.stationary_motion`.
    form : {"stable", "printed"}
        ``"printed"``: the paper's expressions literally; ``"stable"``: without the O(l^2/R^2)
        cancellation of ``W_g2g2`` (third relation (2.4)); equal values in exact arithmetic.

    Returns
    -------
    ndarray, shape (6, 6)
        Symmetric matrix of ``d^2 W1 / dx_i dx_j`` in the order :data:`COORDS`
        ``(R, kappa, beta1, beta3, gamma1, gamma2)``, in the units of ``sat``: W1 is an energy, so ``W_RR``
        is energy/length^2, the other entries of the R row energy/length, all the rest energy.

    Raises
    ------
    TypeError
        If ``sat`` is not a :class:`Satellite` or ``m`` not a :class:`StationaryMotion`.
    ValueError
        If ``form`` is unknown or ``sat`` differs from ``m.satellite`` in ``M, A1, A2, A3, mu``.
    """
    _check_same_body(sat, m)
    e = hessian_entries(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, m.R0, m.theta0, m.kappa0, m.omega0, m.k2, m.S0,
                        form=form)
    return _hessian_matrix(e)


def hessian_W1_numerical(sat: Satellite, m: StationaryMotion, *, h: float | None = None) -> np.ndarray:
    """The 6x6 Hessian of W1 at ``m`` by 8th-order central differences of :func:`amended_potential`.

    An independent float64 route for nondimensional problems (M = mu = R0 = 1 and l/R not too small):
    its round-off is ~ eps abs(W1) / h^2, so in SI units (abs(W1) ~ 1e11 next to entries ~ 1e-3) it is useless
    -- evaluate W1 with ``lib=mpmath`` there (as the tests do).  ``h`` defaults to 1e-3 times the
    natural scale of each coordinate (R0 for R, 1 for the angles and direction cosines).

    The finite-difference counterpart of :func:`hessian_W1` (the second derivatives printed after (2.4),
    at the motion (2.3)).

    Parameters
    ----------
    sat : Satellite
        Must have the mass properties the motion was computed for (W1 itself is evaluated with
        ``m.satellite``, which carries the motion's ``k2, k3``).
    m : StationaryMotion
        A member of the family (2.3)-(2.4).
    h : float, optional
        Relative step: the step of each coordinate is ``h`` times its natural scale (default 1e-3).

    Returns
    -------
    ndarray, shape (6, 6)
        Hessian of W1 in the order :data:`COORDS` ``(R, kappa, beta1, beta3, gamma1, gamma2)``, in the
        units of ``sat``.

    Raises
    ------
    TypeError
        If ``sat`` is not a :class:`Satellite` or ``m`` not a :class:`StationaryMotion`.
    ValueError
        If ``sat`` differs from ``m.satellite`` in ``M, A1, A2, A3, mu``.
    """
    from ..core.quadform import hessian_fd
    from ._potential import amended_potential

    _check_same_body(sat, m)

    steps = np.array([m.R0, 1, 1, 1, 1, 1]) * (1e-3 if h is None else h)
    return hessian_fd(lambda x: float(amended_potential(m.satellite, x, k=m.k, lam=m.lambda0, branch=m.branch)),
                      np.array(m.point), steps)


def constraint_gradient(m: StationaryMotion) -> np.ndarray:
    """Gradient of chi (2.1) at (2.3) w.r.t. :data:`COORDS`: cos kappa0 (0, -1, 0, 1/cos(theta0+kappa0), 0,
    1/cos theta0).

    Its null space is the tangent space of the constraint used in the second variation (2.5):
    ``delta gamma2 = cos theta0 delta kappa - cos theta0 / cos(theta0 + kappa0) delta beta3``.

    Parameters
    ----------
    m : StationaryMotion
        A member of the family (2.3)-(2.4) (only ``theta0`` and ``kappa0`` enter).

    Returns
    -------
    ndarray, shape (6,)
        ``d chi / dx`` in the order ``(R, kappa, beta1, beta3, gamma1, gamma2)``; the R entry is 0, the
        others are dimensionless (per radian for kappa). The beta3 and gamma2 entries are unbounded as
        ``cos(theta0 + kappa0)`` or ``cos theta0`` tends to 0 (the chart is singular there).
    """
    ck = np.cos(m.kappa0)
    return ck * np.array([0.0, -1.0, 0.0, 1.0 / np.cos(m.theta0 + m.kappa0), 0.0, 1.0 / np.cos(m.theta0)])


def constrained_second_variation(sat: Satellite, m: StationaryMotion) -> np.ndarray:
    """delta^2 W1 after substituting delta gamma2 from (2.1), 5x5 in the order :data:`CONSTRAINED_COORDS`.

    Block diagonal: ``[[W_g1g1, W_b1g1], [W_b1g1, W_b1b1]]`` and the a_ij of (2.5).
    The Sylvester quantities of (2.5) are ``s1 = Hc[0, 0]``, ``s2 = det Hc[:2, :2]`` and
    ``s3 = det Hc[2:, 2:]``. Entries from the stable form of :func:`hessian_W1`.

    Parameters
    ----------
    sat : Satellite
        Must have the mass properties the motion was computed for.
    m : StationaryMotion
        A member of the family (2.3)-(2.4).

    Returns
    -------
    ndarray, shape (5, 5)
        The constrained second variation ``Hc`` in the order :data:`CONSTRAINED_COORDS`
        ``(gamma1, beta1, R, kappa, beta3)``, in the units of ``sat``. Not checked for the singular chart
        ``cos theta0 = 0`` or ``cos(theta0 + kappa0) = 0``, where entries blow up (:func:`stability`
        refuses such motions).

    Raises
    ------
    TypeError
        If ``sat`` is not a :class:`Satellite` or ``m`` not a :class:`StationaryMotion`.
    ValueError
        If ``sat`` differs from ``m.satellite`` in ``M, A1, A2, A3, mu``.
    """
    _check_same_body(sat, m)
    e = hessian_entries(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, m.R0, m.theta0, m.kappa0, m.omega0, m.k2, m.S0)
    a = a_matrix(e, m.theta0, m.kappa0)
    Hc = np.zeros((5, 5))
    Hc[0, 0], Hc[0, 1], Hc[1, 0], Hc[1, 1] = e["g1g1"], e["b1g1"], e["b1g1"], e["b1b1"]
    Hc[2:, 2:] = a
    return Hc


@dataclass(frozen=True)
class Stability:
    """Stability of a stationary motion (2.3) by Routh's method.

    Attributes
    ----------
    s1, s2, s3 : float
        The Sylvester quantities of (2.5): ``s1 = W_g1g1``, ``s2 = W_g1g1 W_b1b1 - W_b1g1^2``,
        ``s3 = det a``.
    a : ndarray (3, 3)
        The a_ij of (2.5).
    minors : ndarray (5,)
        All leading principal minors of the constrained second variation in the order
        (gamma1, beta1, R, kappa, beta3): ``s1, s2, s2 a11, s2 (a11 a22 - a12^2), s2 s3``.  The paper
        lists only s1, s2, s3; a11 > 0 and a11 a22 > a12^2 hold for l << R but are checked here.
    degree : int
        Degree of instability: number of negative eigenvalues of the constrained second variation.
    nullity : int
        Number of (numerically) zero eigenvalues.
    verdict : {'stable', 'unstable', 'undecided'}
        'stable': positive definite (Routh; sufficient, conditional on the unperturbed area constant);
        'unstable': odd degree and nondegenerate (Kelvin--Chetaev: gyroscopic forces cannot
        stabilise); 'undecided': even positive degree or a degenerate form.
    jacobian : float
        Jacobian of the system (2.1), (2.2) in (R, kappa, beta1, beta3, gamma1, gamma2, lambda),
        i.e. the bordered Hessian ``-(cos^2 kappa0 / cos^2 theta0) s2 s3`` (section 4; the paper
        prints it without the minus sign).
    unconditionally_stable : bool
        Stable and jacobian != 0: Lyapunov's addendum to Routh's theorem applies, so the motion is
        stable also under perturbations of the area constant k (section 4).
    restricted : tuple (r1, r2, r3)
        The restricted-problem quantities (see :func:`restricted_conditions`).
    """

    s1: float
    s2: float
    s3: float
    a: np.ndarray
    minors: np.ndarray
    degree: int
    nullity: int
    verdict: str
    jacobian: float
    unconditionally_stable: bool
    restricted: tuple[float, float, float]

    @property
    def restricted_verdict(self) -> bool:
        """True when all three restricted-problem inequalities hold."""
        return all(r > 0 for r in self.restricted)


def _check_same_body(sat: Satellite, m: StationaryMotion) -> None:
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    if not isinstance(m, StationaryMotion):
        raise TypeError(f"m must be a StationaryMotion (from stationary_motion); got {type(m).__name__}")
    for name in ("M", "A1", "A2", "A3", "mu"):
        if getattr(sat, name) != getattr(m.satellite, name):
            raise ValueError(f"sat.{name} differs from the satellite the motion was computed for")


def stability_triaxial(sat: Satellite, m: StationaryMotion, *, rtol: float = 1e-12) -> Stability:
    _check_same_body(sat, m)
    if abs(np.cos(m.theta0)) < SINGULAR_TOL or abs(np.cos(m.theta0 + m.kappa0)) < SINGULAR_TOL:
        raise ValueError(
            "the chart (beta1, beta3, gamma1, gamma2) is singular at cos(theta0) = 0 or "
            "cos(theta0 + kappa0) = 0 (|cos| < 1e-6 here): the second variation (2.5) is not defined"
        )
    f = {
        "theta0": np.asarray(m.theta0), "kappa0": np.asarray(m.kappa0), "omega0": np.asarray(m.omega0),
        "k2": np.asarray(m.k2), "S0": np.asarray(m.S0), "exists": np.asarray(True),
        "cos_t": np.cos(np.asarray(m.theta0)), "cos_tk": np.cos(np.asarray(m.theta0 + m.kappa0)),
    }
    d = stability_arrays(f, sat.M, sat.A1, sat.A2, sat.A3, sat.mu, m.R0, rtol=rtol)
    code = int(d["code"])
    r = restricted_conditions(sat.A1, sat.A2, sat.A3, m.theta0, m.k2, m.omega0)
    jac = float(d["jacobian"])
    return Stability(
        s1=float(d["s1"]), s2=float(d["s2"]), s3=float(d["s3"]), a=d["a"].copy(), minors=d["minors"].copy(),
        degree=int(d["n_neg"]), nullity=int(d["n_zero"]), verdict=VERDICTS[code], jacobian=jac,
        unconditionally_stable=(code == 0 and jac != 0.0), restricted=(float(r[0]), float(r[1]), float(r[2])),
    )
