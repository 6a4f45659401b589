"""How stability_map evaluates: block by block, sines and cosines from tangents, non-finite input."""

from __future__ import annotations

import math
import warnings

import mpmath
import numpy as np
import pytest

from rigidbody import gyrostat
from rigidbody.gyrostat import _maps
from rigidbody.gyrostat._family import sin_cos

SAT = gyrostat.Satellite(M=1.0, A1=0.03, A2=0.02, A3=0.012)


def test_sin_cos_from_tangents_against_mpmath():
    """sin, cos and cos 2theta from tan(theta), tan(theta/2), tan(2 theta): a couple of ulp relative everywhere,
    including the places where a naive route fails: cos 2theta at theta = pi/4 (ct^2 - st^2 has no correct
    digit there), cos theta at pi/2 (a tiny positive number for the double next to pi/2), signs past pi/2
    and pi, angles outside (-pi, pi], signed zeros and subnormal angles."""
    rng = np.random.default_rng(5)
    special = [0.0, -0.0, 5e-324, 1e-300, -1e-300, math.pi / 4, -math.pi / 4, math.pi / 2, -math.pi / 2,
               math.pi, -math.pi, 3 * math.pi / 4, 1.5 * math.pi, 2 * math.pi, 1e3]
    th = np.concatenate([special, rng.uniform(-10, 10, 400), math.pi / 4 + rng.uniform(-1e-9, 1e-9, 50),
                         math.pi / 2 + rng.uniform(-1e-6, 1e-6, 50), math.pi + rng.uniform(-1e-6, 1e-6, 50)])
    st, ct, c2t = sin_cos(th)
    worst = 0.0
    with mpmath.workdps(40):
        for i, t in enumerate(th):
            x = mpmath.mpf(float(t))
            for got, ref in ((st[i], mpmath.sin(x)), (ct[i], mpmath.cos(x)), (c2t[i], mpmath.cos(2 * x))):
                if ref == 0:
                    assert got == 0
                    continue
                assert math.copysign(1.0, got) == math.copysign(1.0, float(ref))
                worst = max(worst, float(abs((got - ref) / ref)))
    # tan to an ulp, then sqrt(1 + T^2) and a division: a few roundings of relative eps = 1.1e-16 each
    assert worst < 5 * 2.2e-16, worst


@pytest.mark.parametrize("layout", ["theta long", "k2 long", "scattered"])
def test_blocks_do_not_change_the_map(monkeypatch, layout):
    """The evaluation runs in blocks along the longest axis; with blocks of a few dozen points (many blocks,
    the per-theta0 part cut along the axis or shared by all blocks) every verdict, degree and quantity equals
    the single-block evaluation and, at sampled points, the scalar stationary_motion + stability."""
    rng = np.random.default_rng(2)
    if layout == "theta long":
        args, kw = (np.linspace(-1.5, 1.5, 61),), {"k2": np.linspace(-0.2, 0.2, 7)}
    elif layout == "k2 long":
        args, kw = (np.linspace(-1.5, 1.5, 7),), {"k2": np.linspace(-0.2, 0.2, 61)}
    else:
        args, kw = (rng.uniform(-3, 3, 500),), {"k3": rng.uniform(-0.2, 0.2, 500), "grid": False}
    one = gyrostat.stability_map(SAT, 1.0, *args, **kw)
    monkeypatch.setattr(_maps, "_BLOCK", 32)
    many = gyrostat.stability_map(SAT, 1.0, *args, **kw)
    np.testing.assert_array_equal(many.code, one.code)
    np.testing.assert_array_equal(many.degree, one.degree)
    for name in ("s1", "s2", "s3", "k2", "k3", "kappa0", "omega0", "minors", "r2"):
        # the same operations on the same numbers: equal up to the last bit (NaN at the same invalid points)
        np.testing.assert_array_equal(getattr(many, name), getattr(one, name), err_msg=name)
    assert len(np.unique(one.code)) >= 3  # stable, unstable and undecided (and invalid) points all occur
    for idx in zip(*(rng.integers(0, n, 12) for n in one.shape)):
        th, k2 = float(one.theta0[idx]), float(one.k2[idx])
        if one.code[idx] == -1:
            continue
        m = gyrostat.stationary_motion(SAT, 1.0, th, k2=k2)
        st = gyrostat.stability(m.satellite, m)
        assert (st.verdict, st.degree) == (one.verdict[idx], one.degree[idx])


def test_non_finite_and_overflowing_input_is_invalid_without_warnings():
    """inf and nan, and a k2 so large that W_b1b1 = ... + omega0 k2 / cos(theta0 + kappa0) overflows: invalid
    points (code -1, NaN quantities), never an exception or a warning; the finite points of the same map are
    classified, a huge but representable k2 like its limit (the verdict of k2 = +-1e150)."""
    k2 = np.array([0.01, math.inf, -math.inf, math.nan, 1e308, -1e308, 1e150, -1e150])
    th = np.array([0.3, 1.0])  # omega0 / cos(theta0 + kappa0) ~ 1.05 and 1.85: 1e308 overflows at 1.0 only
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mp = gyrostat.stability_map(SAT, 1.0, th, k2=k2)
        assert np.all(mp.code[:, 0] >= 0) and np.all(mp.code[:, 1:4] == -1) and np.all(mp.code[1, 4:6] == -1)
        assert np.all(np.isnan(mp.s2[:, 1:4])) and np.all(mp.degree[:, 1:4] == -1)
        assert np.all(np.isnan(mp.minors[:, 1:4]))
        assert mp.code[0, 4:6].tolist() == mp.code[0, 6:8].tolist() and np.all(mp.code[:, 6:8] >= 0)
        bad_body = gyrostat.stability_map(SAT, 1.0, 0.3, k2=0.01, M=np.array([1.0, math.inf, math.nan]), grid=False)
        assert bad_body.code.tolist()[1:] == [-1, -1] and bad_body.code[0] >= 0


def test_closed_form_a_ij_equal_the_elimination_of_the_printed_entries():
    """second_variation_side writes a22, a23, a33 of (2.5) in closed form (W_g2g2 and W_b3g2 combined
    through the third relation (2.4)); a_matrix builds them from the entries one by one, as printed.  Equal
    to rounding, over random bodies, tilts in all four quadrants and both signs of omega0."""
    from rigidbody.gyrostat._family import family_side
    from rigidbody.gyrostat._secondvar import a_matrix, hessian_entries, second_variation_side

    rng = np.random.default_rng(8)
    n = 400
    a = rng.uniform(0.3, 1.0, (n, 3))
    A = a / a.mean(axis=1, keepdims=True) * rng.uniform(0.01, 0.3, n)[:, None] ** 2
    ok = (A[:, 0] <= A[:, 1] + A[:, 2]) & (A[:, 1] <= A[:, 0] + A[:, 2]) & (A[:, 2] <= A[:, 0] + A[:, 1])
    A = A[ok]
    th = rng.uniform(-3.1, 3.1, A.shape[0])
    sgn = rng.choice([-1.0, 1.0], A.shape[0])
    f = family_side(1.0, A[:, 0], A[:, 1], A[:, 2], 1.0, 1.0, th, sgn)
    d = second_variation_side(f, 1.0, A[:, 0], A[:, 1], A[:, 2], 1.0, 1.0)
    e = hessian_entries(1.0, A[:, 0], A[:, 1], A[:, 2], 1.0, 1.0, th, f["kappa0"], f["omega0"], 0.0, f["S0"])
    ref = a_matrix(e, th, f["kappa0"])
    use = d["valid"]
    got = {"a11": d["a11"], "a22": d["a22"], "a12": d["a12"], "a13": d["a13"], "a23": d["a23"], "a33": d["a33_0"]}
    where = {"a11": (0, 0), "a22": (1, 1), "a12": (0, 1), "a13": (0, 2), "a23": (1, 2), "a33": (2, 2)}
    # entries of size O(1) built from terms of size O(1) (nondimensional, l/R <= 0.3) and 1/cos^3 up to
    # ~1e3 near the singular chart: 1e-12 of the row scale
    scale = np.max(np.abs(ref[use]), axis=(1, 2))
    for name, (i, j) in where.items():
        err = np.abs(got[name][use] - ref[use][:, i, j]) / scale
        assert np.max(err) < 1e-12, (name, np.max(err))


@pytest.mark.parametrize("layout", ["scattered bodies", "A1 along the blocks"])
def test_blocks_with_a_varying_body_do_not_change_the_map(monkeypatch, layout):
    """The factors that involve only the body, mu and R0 are computed once per map and cut into blocks with
    the points; with a body that varies along the blocked axis (per point, or one grid axis) and blocks of a
    few dozen points, every quantity equals the single-block evaluation and, at sampled points, the scalar
    stationary_motion + stability of that body."""
    rng = np.random.default_rng(4)
    if layout == "scattered bodies":
        n = 400
        a = rng.uniform(0.3, 1.0, (n, 3))
        A = a / a.mean(axis=1, keepdims=True) * rng.uniform(0.05, 0.3, n)[:, None] ** 2
        args = (rng.uniform(1.0, 1.5, n), rng.uniform(-3, 3, n))
        kw = {"k2": rng.uniform(-0.2, 0.2, n), "A1": A[:, 0], "A2": A[:, 1], "A3": A[:, 2], "grid": False,
              "omega_sign": -1}
    else:
        args = (1.0, np.linspace(-1.5, 1.5, 9))
        kw = {"k2": np.linspace(-0.2, 0.2, 5), "A1": np.linspace(0.01, 0.032, 70)}
    one = gyrostat.stability_map(SAT, *args, **kw)
    monkeypatch.setattr(_maps, "_BLOCK", 32)
    many = gyrostat.stability_map(SAT, *args, **kw)
    for name in ("code", "degree", "s1", "s2", "s3", "k2", "k3", "kappa0", "omega0", "minors"):
        # the same operations on the same numbers: equal up to the last bit (NaN at the same invalid points)
        np.testing.assert_array_equal(getattr(many, name), getattr(one, name), err_msg=name)
    assert len(np.unique(one.code)) >= 3
    P = one.params
    for idx in zip(*(rng.integers(0, n, 40) for n in one.shape)):
        if one.code[idx] == -1:
            continue
        sat = gyrostat.Satellite(M=1.0, A1=float(P["A1"][idx]), A2=float(P["A2"][idx]), A3=float(P["A3"][idx]))
        m = gyrostat.stationary_motion(sat, float(P["R0"][idx]), float(P["theta0"][idx]), k2=float(P["k2"][idx]),
                                       omega_sign=kw.get("omega_sign", 1))
        st = gyrostat.stability(m.satellite, m)
        assert (st.verdict, st.degree) == (one.verdict[idx], one.degree[idx])
        # the same float64 formulas, evaluated vectorised (SIMD loops may round tan, sqrt differently in the last bit)
        assert one.s3[idx] == pytest.approx(st.s3, rel=1e-12, abs=0)
        assert one.kappa0[idx] == pytest.approx(m.kappa0, rel=1e-13, abs=0)
