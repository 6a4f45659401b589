"""The second variation of W1 at the motions (2.3) in closed form, vectorised over grids: its entries, the a_ij
and Sylvester conditions (2.5), the restricted-problem conditions and the verdict codes (sections 2, 4). Used by
the maps and by the single-motion analysis of :mod:`._stability`."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.quadform import inertia
from ._family import (
    FRESH,
    ONE,
    SINGULAR_TOL,
    TWO,
    ZERO,
    Scratch,
    common_shape,
    constants,
    fixed,
    own,
)

__all__ = [
    "CONSTRAINED_COORDS",
    "COORDS",
    "VERDICTS",
    "a_matrix",
    "entry_constants",
    "hessian_entries",
    "hessian_matrix",
    "restricted_conditions",
    "second_variation_side",
    "verdict_codes",
    "verdicts",
]

#: verdict codes used by the vectorised routines; -1 marks "no motion / singular chart"
VERDICTS = {0: "stable", 1: "unstable", 2: "undecided", -1: "invalid"}

#: below this cos^2 theta0 or cos^2(theta0 + kappa0) the chart (beta1, beta3, gamma1, gamma2) is singular
_TOL2 = fixed(SINGULAR_TOL**2)

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
        st, ct, sk, ck = np.sin(th), np.cos(th), np.sin(kap), np.cos(kap)
        sp, cp = np.sin(th + kap), np.cos(th + kap)
        b = {"st": st, "ct": ct, "c2t": np.cos(2 * th), "sk": sk, "ck": ck, "tk": sk / ck, "sp": sp, "cp": cp,
             "om": om, "om2": om * om, "S": S, "st2": st * st, "stct": st * ct, "ct2": ct * ct, "icp": 1.0 / cp,
             "ck2": ck * ck}
        b["n2"] = b["om2"] * b["ck2"]
        e = _entries(b, M, A1, A2, A3, mu, R, form)
        e["b1b1"] = e["b1b1"] + om * k2 / cp
        e["b3b3"] = e["b3b3"] + om * k2 / cp**3
    return e


def entry_constants(M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R: Any) -> dict[str, Any]:
    """The factors of :func:`_entries` and :func:`second_variation_side` that involve only the body, mu and R0
    (once per map, not per point)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        M, A1, A2, A3, mu, R = (np.asarray(v, dtype=float) for v in (M, A1, A2, A3, mu, R))
        n0 = mu / R**3
        MR2 = M * R**2
        return {
            "n0": n0, "M": M, "R": R, "MR2": MR2, "MR2/2": 0.5 * MR2, "2MR2": 2 * MR2, "4MR2": 4 * MR2,
            "MR": M * R, "2MR": 2 * M * R, "-R": -R, "A2-A3": A2 - A3, "A2-A1": A2 - A1,
            "RR:st2": 18 * n0 / R**2 * (A2 - A3), "RR:1": 18 * n0 / R**2 * (2 * A3 - A1 - A2) / 3 - 2 * M * n0,
            "G": 3 * n0 * (A2 - A3), "3n0(A1-A3)": 3 * n0 * (A1 - A3), "3n0(A2-A3)": 3 * n0 * (A2 - A3),
            # second_variation_side: G in another order of operations, and W_Rg2 / sin theta0
            "G'": 3 * mu / R**3 * (A2 - A3), "Rg2:st": 9 * mu * (A2 - A3) / R**4,
        }


def _entries(b: dict[str, np.ndarray], M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R: Any,
             form: str = "stable", gamma2: bool = True, *, const: dict[str, Any] | None = None,
             work: Scratch | None = None) -> dict[str, np.ndarray]:
    """The entries of :func:`hessian_entries` WITHOUT the gyrostatic terms ``omega0 k2 / cos(theta0 + kappa0)``
    of W_b1b1 and ``omega0 k2 / cos^3(theta0 + kappa0)`` of W_b3b3 (the only places k2 enters).

    ``b`` holds ``st, ct, sk, ck, sp, cp``: sines and cosines of theta0, kappa0, theta0 + kappa0; ``c2t =
    cos 2 theta0`` (evaluated directly: ``ct^2 - st^2`` has no correct digit at theta0 = pi/4); ``tk = tan
    kappa0``, ``om = omega0``, ``om2 = omega0^2``, ``n2 = omega0^2 cos^2 kappa0``, ``S = S0``, ``st2 = st^2``,
    ``stct = st ct``, ``ct2 = ct^2``, ``ck2 = ck^2``, ``icp = 1 / cp``.  The printed expressions, with the
    factors that are the same at every point of a map (the body, mu, R0; :func:`entry_constants`, given as
    ``const`` or computed here) grouped first, so that array operations are spent only on what varies, and
    shared subexpressions computed once.  Also returns ``Q`` (the bracket of W_b3b3, W_Rb3, W_kb3), ``L``
    (lambda0) and ``om2iS = omega0^2 / S0``.  ``gamma2=False`` leaves out W_g2g2, W_b3g2, W_b3b3 and W_Rg2
    (:func:`second_variation_side` uses the a_ij they combine into, in closed form).  ``work``: see
    :class:`~rigidbody.gyrostat._family.Scratch`.
    """
    c = constants(entry_constants, M, A1, A2, A3, mu, R) if const is None else const
    w = FRESH if work is None else work
    st, ct, sk, ck, sp = b["st"], b["ct"], b["sk"], b["ck"], b["sp"]
    om2, S, ck2, icp, stct = b["om2"], b["S"], b["ck2"], b["icp"], b["stct"]
    s = common_shape(st, sk, sp, om2, S, icp, b["n2"], *c.values())
    wf, xp = w.at(s), w.ops(s)
    mul = xp.multiply
    t = wf["_t0"]  # (a work array or None, never rebound: see Scratch)
    iS = xp.divide(ONE, S, out=wf["_t1"])
    s2k = mul(TWO, sk, out=wf["_t2"])
    s2k *= ck
    Q = mul(s2k, icp, out=wf["Q"])  # M R0^2 sin 2 kappa0 / (2 cos(theta0 + kappa0)) - (A2 - A3) sin(..)
    Q *= c["MR2/2"]
    Q -= mul(c["A2-A3"], sp, out=t)
    om2iS = mul(om2, iS, out=wf["om2iS"])
    # M omega0^2 cos^2 kappa0 = M n2 (second relation (2.4))
    RR = mul(c["4MR2"], ck2, out=wf["RR"])
    RR -= S
    RR *= iS
    RR *= mul(c["M"], b["n2"], out=t)
    RR += mul(c["RR:st2"], b["st2"], out=t)
    RR += c["RR:1"]
    kk = mul(S, ck2, out=wf["kk"])
    x = mul(s2k, s2k, out=t)
    x *= c["MR2"]
    kk += x
    kk *= mul(c["MR2"], om2iS, out=t)
    e = {"Q": Q, "om2iS": om2iS, "RR": RR, "kk": kk}
    if form == "stable":
        G = c["G"]
        L = mul(G, stct, out=wf["L"])  # = lambda0 = M R0^2 omega0^2 sin kappa0 by the third relation (2.4)
        L /= ck
        g1g1 = mul(st, sp, out=wf["g1g1"])
        g1g1 *= G
        g1g1 /= ck
        e["g1g1"] = xp.subtract(c["3n0(A1-A3)"], g1g1, out=own(g1g1))
        if gamma2:
            e["g2g2"] = G * (b["c2t"] - stct * b["tk"]) / b["ct2"]
    else:
        L = (c["MR2"] * om2) * sk
        e["g1g1"] = -L * sp / ct + c["3n0(A1-A3)"]
        if gamma2:
            e["g2g2"] = -L * sp / (b["ct2"] * ct) + c["3n0(A2-A3)"]
    e["L"] = L
    Lsticp = mul(L, st, out=wf["Lsticp"])
    Lsticp *= icp
    b1b1 = mul(c["A2-A1"], om2, out=wf["b1b1"])
    b1b1 += Lsticp
    e["Lsticp"], e["b1b1"] = Lsticp, b1b1
    if gamma2:
        e["b3b3"] = Lsticp * (icp * icp) + c["A2-A3"] * om2 + om2iS * (Q * Q)
        e["b3g2"] = (L * sk) * icp / -ct
    e["b1g1"] = L
    MRom2s2k = mul(om2, s2k, out=wf["_t3"])
    MRom2s2k *= c["MR"]
    Rk = mul(c["2MR2"], ck2, out=wf["Rk"])
    Rk = xp.subtract(S, Rk, out=own(Rk))
    Rk *= iS
    Rk *= MRom2s2k
    Rb3 = mul(om2iS, ck2, out=wf["Rb3"])
    Rb3 *= c["2MR"]
    Rb3 *= Q
    kb3 = mul(c["-R"], iS, out=wf["kb3"])
    kb3 *= MRom2s2k
    kb3 *= Q
    e["Rk"], e["Rb3"], e["kb3"] = Rk, Rb3, kb3
    if gamma2:
        e["Rg2"] = c["Rg2:st"] * st
    return e


def hessian_matrix(e: dict[str, np.ndarray]) -> np.ndarray:
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

    Parameters
    ----------
    A1, A2, A3 : array_like
        Principal moments of inertia.
    theta0, k2, omega0 : array_like
        Tilt (radians), gyrostatic component and angular velocity of the motion (2.3); all broadcast.

    Returns
    -------
    r1 : A1 - A2 sin^2 theta0 - A3 cos^2 theta0                (limit of s1 > 0)
    r2 : A2 - A3 + k2 / (4 omega0 cos^3 theta0)                (limit of s3 > 0, i.e. a33 > 0)
    r3 : r1 (A2 - A1 + k2 / (omega0 cos theta0)) + 3 (A1 - A2)(A2 - A3) sin^2 theta0   (limit of s2 > 0)

    See Also
    --------
    stability : the exact conditions (2.5), which these approximate to O(l^2/R^2).

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, after eq. (2.5).

    Examples
    --------
    At :math:`\theta_0 = 0`, :math:`k_2 = 0`: :math:`r_1 = A_1 - A_3`, :math:`r_2 = A_2 - A_3`,
    :math:`r_3 = r_1(A_2 - A_1)`, negative for :math:`A_1 > A_2`:

    >>> from rigidbody import gyrostat
    >>> print(*(f"{r:.2e}" for r in gyrostat.restricted_conditions(0.012, 0.010, 0.008, 0.0, 0.0, 1.0)))
    4.00e-03 2.00e-03 -8.00e-06
    """
    A1, A2, A3, th, k2, om = (np.asarray(v, dtype=float) for v in (A1, A2, A3, theta0, k2, omega0))
    st2, ct = np.sin(th) ** 2, np.cos(th)
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = A1 - A2 * st2 - A3 * ct**2
        r2 = A2 - A3 + k2 / (4 * om * ct**3)
        r3 = r1 * (A2 - A1 + k2 / (om * ct)) + 3 * (A1 - A2) * (A2 - A3) * st2
    return r1, r2, r3


def verdict_codes(n_neg: np.ndarray, n_zero: np.ndarray) -> np.ndarray:
    code = np.full(n_neg.shape, 2, dtype=np.int8)
    code[(n_neg == 0) & (n_zero == 0)] = 0
    code[(n_neg % 2 == 1) & (n_zero == 0)] = 1
    return code


def second_variation_side(f: dict[str, np.ndarray], M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R0: Any,
                          rtol: float = 1e-12, *, const: dict[str, Any] | None = None,
                          work: Scratch | None = None) -> dict[str, np.ndarray]:
    """The parts of the second variation (2.5) that do not depend on k2, for :func:`family_side` output ``f``.

    k2 enters the second variation only through W_b1b1 (as ``omega0 k2 / cos(theta0 + kappa0)``) and
    W_b3b3 (``omega0 k2 / cos^3``), i.e. through ``b1b1 = b1b1_0 + w1 k2`` and ``a33 = a33_0 + w3 k2``:
    s2 and s3 = det a = a33 C + D0 are linear in k2 (C = a11 a22 - a12^2).  Over a map in which theta0
    and the body vary on fewer points than k2 (a grid), everything here is computed once per theta0.

    Also returns the k2-free parts of the certainty test of :func:`verdicts` and ``valid``: the motion
    exists and the chart (beta1, beta3, gamma1, gamma2) is regular (abs(cos theta0) and abs(cos(theta0 +
    kappa0)) > 1e-6).  ``const``: :func:`entry_constants` of the body; ``work``: see
    :class:`~rigidbody.gyrostat._family.Scratch`.
    """
    c = constants(entry_constants, M, A1, A2, A3, mu, R0) if const is None else const
    w = FRESH if work is None else work
    icp = f["icp"]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        e = _entries(f, M, A1, A2, A3, mu, R0, gamma2=False, const=c, work=w)
        s = e["RR"].shape
        wf, wb, xp = w.at(s), w.at(s, bool), w.ops(s)
        mul, sub = xp.multiply, xp.subtract
        t, u = wf["_t3"], wf["_t4"]
        bt = wb["sv_b"]
        # (2.5) in closed form with the stable entries: with h = cos^2 theta0 W_g2g2 = G (cos 2 theta0 - sin
        # theta0 cos theta0 tan kappa0) and lambda0 sin kappa0 = G sin theta0 cos theta0 tan kappa0 (G =
        # 3 mu R0^-3 (A2 - A3)), the three a_ij that hold W_g2g2 and W_b3g2 reduce to
        #   a22 = W_kk + h,  a23 = W_kb3 - G cos 2 theta0 / cos(theta0 + kappa0),
        #   a33 = W_b3b3 + (h + 2 lambda0 sin kappa0) / cos^2(theta0 + kappa0)   (W_b3b3 written out below)
        # (checked against a_matrix(hessian_entries(...)) in tests/gyrostat/test_gyrostat_map_evaluation.py)
        G = c["G'"]
        Gstct_tk = mul(f["stct"], f["tk"], out=wf["_t0"])
        Gstct_tk *= G
        Gc2t = mul(G, f["c2t"], out=wf["_t1"])
        icp2 = mul(icp, icp, out=wf["icp2"])
        w1 = mul(f["om"], icp, out=wf["w1"])
        a11 = e["RR"]
        a22 = sub(Gc2t, Gstct_tk, out=wf["a22"])
        a22 += e["kk"]
        Rg2ct = mul(c["Rg2:st"], f["stct"], out=wf["_t2"])  # cos theta0 W_Rg2
        a12 = xp.add(e["Rk"], Rg2ct, out=wf["a12"])
        a13 = sub(e["Rb3"], mul(Rg2ct, icp, out=t), out=wf["a13"])
        a23 = sub(e["kb3"], mul(Gc2t, icp, out=t), out=wf["a23"])
        # a33_0 = icp2 (Lsticp + Gc2t + Gstct_tk) + (A2 - A3) omega0^2 + om2iS Q^2
        a33_0 = xp.add(Gc2t, Gstct_tk, out=wf["a33_0"])
        a33_0 += e["Lsticp"]
        a33_0 *= icp2
        a33_0 += mul(c["A2-A3"], f["om2"], out=t)
        x = mul(e["Q"], e["Q"], out=t)
        x *= e["om2iS"]
        a33_0 += x
        a12sq = mul(a12, a12, out=wf["_t2"])
        a11a22 = mul(a11, a22, out=wf["_t0"])
        C = sub(a11a22, a12sq, out=wf["C"])
        a12a23a13 = mul(TWO, a12, out=wf["_t1"])
        a12a23a13 *= a23
        a12a23a13 *= a13
        a11a23sq = mul(a23, a23, out=wf["_t5"])
        a11a23sq *= a11
        a22a13sq = mul(a13, a13, out=wf["_t6"])
        a22a13sq *= a22
        # certainty of the signs (see verdicts): the rounding error of a determinant expansion is below a
        # small multiple of eps times the permanent of abs(a); F and E0 are its parts without a33
        F = xp.abs(a11a22, out=wf["F"])
        F += a12sq
        g1g1 = e["g1g1"]
        tol = fixed(xp.sqrt(rtol))
        s1neg = xp.less(g1g1, ZERO, out=wb["s1neg"])
        a11neg = xp.less(a11, ZERO, out=wb["a11neg"])
        Cneg = xp.less(C, ZERO, out=wb["Cneg"])
        D0 = sub(a12a23a13, a11a23sq, out=wf["D0"])
        D0 -= a22a13sq
        E0 = xp.abs(a12a23a13, out=wf["E0"])
        E0 += xp.abs(a11a23sq, out=t)
        E0 += xp.abs(a22a13sq, out=t)
        # (a product that underflows: not sure)
        sure_T = xp.not_equal(mul(g1g1, a11, out=t), ZERO, out=wb["sure_T"])
        sure_T &= xp.greater(xp.abs(C, out=t), mul(tol, F, out=u), out=bt)
        # degree of the leading part: sign changes in (1, s1) and in (1, a11, a11 a22 - a12^2)
        neg_T = xp.add(s1neg, a11neg, out=w.at(s, np.int8)["neg_T"], dtype=np.int8)
        neg_T += xp.logical_xor(a11neg, Cneg, out=bt)
        d = {
            "g1g1": g1g1, "b1g1": e["b1g1"], "b1b1_0": e["b1b1"], "w1": w1, "a11": a11, "a22": a22, "a12": a12,
            "a13": a13, "a23": a23, "a33_0": a33_0, "w3": mul(w1, icp2, out=wf["w3"]), "C": C, "D0": D0,
            "b1g1_sq": mul(e["b1g1"], e["b1g1"], out=wf["b1g1_sq"]), "F": F, "E0": E0, "sure_T": sure_T,
            "neg_T": neg_T, "s1neg": s1neg, "Cneg": Cneg,
        }
        valid = xp.greater(f["cp2"], _TOL2, out=wb["valid"])
        valid &= f["exists"]
        valid &= xp.greater(f["ct2"], _TOL2, out=w.at(f["ct2"].shape, bool)["sv_b_t"])
        d["valid"] = valid
    return d


#: verdict code of a nondegenerate form by its degree of instability (number of negative eigenvalues, 0..5)
_CODE_OF_DEGREE = np.array([0, 1, 2, 1, 2, 1], dtype=np.int8)


def _take(x: np.ndarray, mask: np.ndarray) -> np.ndarray:
    return np.broadcast_to(x, mask.shape)[mask]


def verdicts(d: dict[str, np.ndarray], k2: np.ndarray, valid: np.ndarray, rtol: float = 1e-12, *,
             out: dict[str, np.ndarray] | None = None, work: Scratch | None = None) -> dict[str, np.ndarray]:
    """Sylvester quantities (2.5), degree of instability and verdict codes at gyrostatic momenta ``k2``.

    ``d`` from :func:`second_variation_side` (broadcast against ``k2``), ``valid`` the points to classify.
    The constrained second variation is block diagonal: the (gamma1, beta1) block with leading minors s1,
    s2 and the a_ij block with a11, a11 a22 - a12^2, s3.  Where every leading minor exceeds sqrt(rtol) times
    the permanent of the absolute values of its block (the scale of the rounding error of its expansion)
    its sign is certain, and the degree is the number of sign changes in the sequences of minors (Jacobi's
    rule).  Elsewhere -- near a boundary, where a minor is within rounding of zero, or where a quantity is
    not finite -- the inertia of the blocks is computed by :func:`rigidbody.core.quadform.inertia`
    (equilibration and eigenvalues; ``rtol`` is its zero threshold); non-finite points are invalid.
    Codes: 0 stable (positive definite), 1 unstable (odd degree, nondegenerate), 2 undecided (even positive
    degree, or a zero eigenvalue), -1 invalid.

    ``out``: arrays of the result's shape that receive ``s2``, ``s3``, ``n_neg`` (int8 or a wider integer
    type) and ``code`` (int8), e.g. views into a map's outputs; ``work``: see
    :class:`~rigidbody.gyrostat._family.Scratch`.
    """
    w = FRESH if work is None else work
    o = {} if out is None else out
    shape = common_shape(np.asarray(k2), d["C"])
    wf, wb, xp = w.at(shape), w.at(shape, bool), w.ops(shape)
    mul = xp.multiply

    def res(name: str, dtype: Any = float) -> np.ndarray:
        return o[name] if name in o else w.at(shape, dtype)[name]

    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        b1b1 = mul(d["w1"], k2, out=wf["_t0"])
        b1b1 += d["b1b1_0"]
        a33 = mul(d["w3"], k2, out=wf["_t1"])
        a33 += d["a33_0"]
        gb = mul(d["g1g1"], b1b1, out=wf["_t2"])
        s2 = xp.subtract(gb, d["b1g1_sq"], out=res("s2"))
        s3 = mul(d["C"], a33, out=res("s3"))
        s3 += d["D0"]
        tol = fixed(xp.sqrt(rtol))
        t, u = wf["_t3"], wf["_t4"]
        bt = wb["vd_b"]
        x = xp.abs(gb, out=t)  # tol (abs(gb) + b1g1^2)
        x += d["b1g1_sq"]
        x *= tol
        sure = xp.greater(xp.abs(s2, out=u), x, out=wb["sure"])
        y = xp.abs(a33, out=t)  # tol (abs(a33) F + E0)
        y *= d["F"]
        y += d["E0"]
        y *= tol
        sure &= xp.greater(xp.abs(s3, out=u), y, out=bt)
        sure &= d["sure_T"]
        n_neg = xp.add(d["neg_T"], xp.logical_xor(xp.less(s2, ZERO, out=bt), d["s1neg"], out=bt),
                       out=res("n_neg", np.int8))
        n_neg += xp.logical_xor(xp.less(s3, ZERO, out=bt), d["Cneg"], out=bt)
    code = _CODE_OF_DEGREE.take(n_neg, out=res("code", np.int8), mode="clip")  # n_neg in 0..5
    if not isinstance(code, np.ndarray):  # one point without a scratch: a numpy scalar
        code = np.array(code)
    valid = np.broadcast_to(valid, shape)
    n_zero: np.ndarray | None = None
    slow = np.logical_not(sure, out=own(sure))
    slow &= valid
    if slow.any():
        B = np.stack([_take(d["g1g1"], slow), _take(d["b1g1"], slow), _take(d["b1g1"], slow), _take(b1b1, slow)],
                     axis=-1).reshape(-1, 2, 2)
        a = np.stack([_take(d[n], slow) if n != "a33" else _take(a33, slow)
                      for n in ("a11", "a12", "a13", "a12", "a22", "a23", "a13", "a23", "a33")],
                     axis=-1).reshape(-1, 3, 3)
        fin = np.all(np.isfinite(B), axis=(1, 2)) & np.all(np.isfinite(a), axis=(1, 2))
        nn = np.full(B.shape[0], -1, dtype=np.int8)
        nz = np.zeros(B.shape[0], dtype=np.int8)
        if np.any(fin):
            _, nb, zb = inertia(B[fin], rtol=rtol)
            _, na, za = inertia(a[fin], rtol=rtol)
            nn[fin], nz[fin] = nb + na, zb + za
        cc = verdict_codes(nn, nz)
        cc[~fin] = -1
        n_zero = np.zeros(shape, dtype=np.int8)
        if not isinstance(n_neg, np.ndarray):
            n_neg = np.array(n_neg)
        n_neg[slow], n_zero[slow], code[slow] = nn, nz, cc
        valid = valid & ~(slow & (code == -1))
    if not valid.all():
        code[~valid] = -1
    return {"b1b1": b1b1, "a33": a33, "s2": s2, "s3": s3, "n_neg": n_neg,
            "n_zero": np.zeros(shape, dtype=np.int8) if n_zero is None else n_zero, "code": code, "valid": valid}
