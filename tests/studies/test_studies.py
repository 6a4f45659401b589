"""The two studies: the measured error of averaging scales with the theory's order; the regimes of k2 over
the drag plane agree with an independent analysis of (8) and with the equilibria of the library."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from rigidbody import euler_poinsot as ep
from rigidbody import studies as S
from rigidbody.paperfigs.studies import paper_cases
from rigidbody.sweep import sweep


# ---------------------------------------------------------------------------------- where averaging holds
def test_euler_poinsot_error_scales_like_eps_squared():
    # away from the separatrix (1 - k2_0 >= 0.3); eps = 0.04 ... 0.01 (the quick grid's range)
    ds = sweep(S.averaging_error_euler_poinsot, {"eps": [0.04, 0.02, 0.01], "k2_0": [0.3, 0.7]}, progress=False,
               chunk_size=1)
    assert (ds.status == 0).all()
    p_G = S.fitted_order(ds, "G").values
    p_err = S.fitted_order(ds, "error").values
    # theory: O(eps^2) (averaging over the Euler-Poinsot motion with nu kept). Measured over this eps range
    # (factor 4) with 201 samples: 1.98-2.23 for G, T, k2 at k2_0 = 0.1 ... 0.95 (with 11 samples the max
    # of the oscillating difference scatters the exponent by 0.3); +-0.15 around that
    assert np.all((p_G > 1.85) & (p_G < 2.35)), p_G
    assert np.all((p_err > 1.85) & (p_err < 2.35)), p_err
    # halving eps divides the error by about 4, not 2 (first order); 0.35: halfway in log between 1/4 and 1/2
    assert np.all(ds["error"].sel(eps=0.01) < 0.35 * ds["error"].sel(eps=0.02))


def test_lagrange_error_scales_like_eps():
    ds = sweep(S.averaging_error_lagrange, {"eps": [0.04, 0.02, 0.01], "theta0": np.radians([30.0, 90.0])},
               progress=False, chunk_size=1)
    assert (ds.status == 0).all()
    p = S.fitted_order(ds, "error").values
    # theory: O(eps) (first approximation); measured 1.00 for theta0 = 30 ... 170 deg (1.1-1.2 at 5 deg,
    # next to the sleeping top) over eps = 0.04 ... 0.005 with 201 samples; +-0.1 around that
    assert np.all((p > 0.9) & (p < 1.1)), p
    # r obeys (3.3), r = r0 exp(-b tau / C), in both: its difference is the integrators' error only
    assert float(ds["r"].max()) < 1e-8
    assert np.all(ds["error"].sel(eps=0.01) > 0.35 * ds["error"].sel(eps=0.02))  # not second order


def test_fitted_order_recovers_a_known_power():
    eps = np.array([0.1, 0.05, 0.02])
    c = np.array([1.0, 3.0])
    ds = xr.Dataset({"error": (("eps", "k"), eps[:, None] ** 1.5 * c[None, :])}, coords={"eps": eps, "k": [0, 1]})
    np.testing.assert_allclose(S.fitted_order(ds).values, [1.5, 1.5], rtol=1e-12, atol=0)
    ds["error"][0, 1] = np.nan  # a failed point is left out of its fit
    np.testing.assert_allclose(S.fitted_order(ds).values, [1.5, 1.5], rtol=1e-12, atol=0)
    ds["error"][1, 1] = np.nan
    assert math.isnan(float(S.fitted_order(ds).values[1]))


def test_points_outside_the_theory_raise_and_a_sweep_records_them():
    with pytest.raises(ValueError, match="eps must be > 0"):
        S.averaging_error_euler_poinsot(0.0, 0.5)
    with pytest.raises(ValueError, match=r"k2_0 must lie in \(0, 1\)"):
        S.averaging_error_euler_poinsot(0.01, 1.0)
    with pytest.raises(ValueError, match=r"theta0 must lie in \(0, pi\)"):
        S.averaging_error_lagrange(0.01, 0.0)
    with pytest.raises(ValueError, match="n_out must be an integer >= 2"):
        S.averaging_error_lagrange(0.01, 1.0, n_out=1)
    # next to the separatrix at a large eps the rotation is not fast: the full run refuses to start or stops
    ds = sweep(S.averaging_error_euler_poinsot, {"eps": [0.04], "k2_0": [0.99]}, executor="serial",
               progress=False)
    assert ds.status.item() == 1 and "rotation is no longer fast" in ds.message.item()


# ------------------------------------------------------------------------------------- where the spin ends
def _F(r1: float, r3: float, k2: float) -> float:
    """dk2/dtau of (8) with a2 = 1, from SciPy's integrals in the parameter m = k2 (not the library's core)."""
    e_over_k = ellipe(k2) / ellipk(k2)
    return -2.0 * ((r3 - 1.0) * (k2 - 1.0 + e_over_k) + (1.0 - r1) * k2 * e_over_k)


def _expected(r1: float, r3: float, k2_0: float) -> tuple[int, float]:
    """The regime from the signs of (8) near 0, near 1 and at k2_0, and the root where it settles."""
    ks = np.linspace(1e-4, 1.0 - 1e-9, 400)
    f = np.array([_F(r1, r3, k) for k in ks])
    roots = [brentq(lambda k: _F(r1, r3, k), ks[i], ks[i + 1], xtol=1e-14)
             for i in range(ks.size - 1) if f[i] * f[i + 1] < 0]
    if _F(r1, r3, k2_0) > 0:
        above = [k for k in roots if k > k2_0]
        return (1, min(above)) if above else (2, 1.0)
    below = [k for k in roots if k < k2_0]
    return (1, max(below)) if below else (0, 0.0)


def _far_from_the_lines(r1: float, r3: float, k2_0: float) -> bool:
    # a finite run (tau_end = 100, k2 < 1e-3 counts as 0) decides within ln(k2_0 / 1e-3) / 100 = 0.06 of the
    # chi = -3 line only slowly; near r3 = r1 the separatrix is approached slowly; near the line where k2_0
    # is an equilibrium k2 hardly moves
    return (abs(r3 - (2 * r1 - 1)) > 0.15 and abs(r3 - r1) > 0.1
            and abs(r3 - float(S.equilibrium_line(r1, k2_0))) > 0.1)


def test_spin_end_agrees_with_the_analysis_of_8_and_with_k2_equilibria():
    r = np.linspace(0.15, 2.4, 7)
    ds = sweep(S.spin_end, {"r1": r, "r3": r}, progress=False)
    assert (ds.status == 0).all()
    checked = set()
    for i, r1 in enumerate(r):
        for j, r3 in enumerate(r):
            if not _far_from_the_lines(r1, r3, 0.5):
                continue
            regime, k_star = _expected(r1, r3, 0.5)
            assert int(ds.regime[i, j]) == regime, (r1, r3)
            assert S.spin_end_predicted(r1, r3) == regime, (r1, r3)
            if regime == 1:  # settled at the root of (8): the approach is exponential, tau_end = 100
                assert float(ds.k2_end[i, j]) == pytest.approx(k_star, abs=1e-4)
            checked.add(regime)
    assert checked == {0, 1, 2}


@pytest.mark.parametrize("r1", [0.3, 0.8, 1.6, 2.2])
def test_the_lines_of_the_plane(r1):
    body = S.PAPER_BODY
    # chi = -3 on r3 = 2 r1 - 1 ((7) evaluated by the library); k2 = 0 is stable above, unstable below
    r3 = float(S.chi_minus_3_line(r1))
    if r3 > 0 and abs(r3 - r1) > 1e-9:
        assert ep.chi(body, S.drag_from_ratios(r1, r3)) == pytest.approx(-3.0, rel=1e-12, abs=0)
    above, below = r3 + 0.05, r3 - 0.05
    if above > 0:
        assert ep.k2_equilibria(body, S.drag_from_ratios(r1, above))[0] == (0.0, "stable")
    if below > 0:
        assert ep.k2_equilibria(body, S.drag_from_ratios(r1, below))[0] == (0.0, "unstable")
    # r3 = r1: the flow near k2 = 1 points up below the line, down above it ((8) by the library)
    assert ep.dk2_dtau(body, S.drag_from_ratios(r1, r1 * 0.95), 1.0 - 1e-9) > 0
    assert ep.dk2_dtau(body, S.drag_from_ratios(r1, r1 * 1.05), 1.0 - 1e-9) < 0
    # on the equilibrium line, k2_0 is an equilibrium of (8); its slope rho was derived, (8) checks it
    for k2_0 in (0.2, 0.5, 0.9):
        r3e = float(S.equilibrium_line(r1, k2_0))
        if r3e > 0:
            rate = ep.dk2_dtau(body, S.drag_from_ratios(r1, r3e), k2_0)
            scale = abs(ep.dk2_dtau(body, S.drag_from_ratios(r1, r3e + 0.1), k2_0))
            assert abs(rate) < 1e-12 * max(1.0, scale)


def test_rho_falls_from_2_to_1():
    # an interior equilibrium exists exactly between the chi = -3 line (rho = 2) and r3 = r1 (rho = 1)
    k2 = np.linspace(1e-6, 1 - 1e-9, 500)
    rho = np.array([1.0 - float(S.equilibrium_line(0.0, k)) for k in k2])  # the line at r1 = 0: 1 - rho
    e_over_k = ellipe(k2) / ellipk(k2)  # SciPy's integrals in m = k2
    np.testing.assert_allclose(rho, k2 * e_over_k / (k2 - 1.0 + e_over_k), rtol=1e-9, atol=0)
    assert np.all(np.diff(rho) < 0)
    assert rho[0] == pytest.approx(2.0, abs=1e-5) and rho[-1] == pytest.approx(1.0, abs=1e-3)


def test_the_paper_cases_in_the_plane():
    # (r1, r3) of the paper's drag tensors give back chi of (7) through chi = (2 - r1 - r3)/(r3 - r1)
    cases = paper_cases()
    for (r1, r3), diag in zip(cases.values(), (S.PAPER_DRAG_CASE1, (0.919, 5.228, 1.666))):
        assert (2 - r1 - r3) / (r3 - r1) == pytest.approx(ep.chi(S.PAPER_BODY, np.diag(diag)), rel=1e-12, abs=0)
    # case 1: an interior equilibrium k*2 = 0.52064 (docs/euler_poinsot.md); case 2: k2 -> 0
    out1 = S.spin_end(*cases["case 1"])
    assert out1["regime"] == 1 and out1["k2_end"] == pytest.approx(0.52064, abs=1e-5)
    assert S.spin_end(*cases["case 2"])["regime"] == 0
    with pytest.raises(ValueError, match=r"r1 must be > 0 \(a drag dissipates\)"):
        S.spin_end(0.0, 1.0)


def test_spin_end_on_arrays_is_one_batch_equal_to_the_point_calls():
    # marked batched: a sweep sends chunks of points, integrated as one batch with a drag tensor per point; each
    # point equals its own call (the event ending a run is located to the integration's accuracy, rtol 1e-6)
    r1 = np.array([0.3, 1.44, 2.2, 1.0, 0.5])
    r3 = np.array([0.5, 1.69, 0.4, 1.0, 2.0])
    out = S.spin_end(r1, r3)
    assert out["status"].tolist() == [0] * 5 and list(out["message"]) == [""] * 5
    for i in range(r1.size):
        one = S.spin_end(float(r1[i]), float(r3[i]))
        assert out["regime"][i] == one["regime"]
        assert out["k2_end"][i] == pytest.approx(one["k2_end"], rel=1e-5, abs=1e-9)
        assert out["tau_end"][i] == pytest.approx(one["tau_end"], rel=1e-5, abs=0)
        assert out["chi"][i] == pytest.approx(one["chi"], rel=1e-12, abs=0) or (math.isnan(out["chi"][i])
                                                                               and math.isnan(one["chi"]))
    assert set(out["regime"].tolist()) == {0.0, 1.0, 2.0}
