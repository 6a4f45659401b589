"""The data behind the gyrostat figures, and the builder end to end."""

from __future__ import annotations

import math

import numpy as np

from rigidbody import gyrostat
from rigidbody.paperfigs import gyrostat as fg


def test_kappa_curves_collapse_and_peak_near_pi_over_4():
    kd = fg.kappa_data()
    curves = np.array([kd[lR] / lR**2 for lR in fg.L_OVER_R_KAPPA])
    # collapse: the scaled curves differ by O(l^2/R^2) (relative), at most 0.3^2 ~ 9 % here
    ref = curves[0]
    assert np.all(np.abs(curves - ref) <= 0.1 * np.max(np.abs(ref)))
    # odd in theta0, peak at the grid point nearest pi/4 for the smallest l/R (grid step 0.01)
    assert np.allclose(curves[:, ::-1], -curves, atol=1e-15)
    i = int(np.argmax(curves[0]))
    assert abs(fg.THETA[i] - math.pi / 4) <= 0.011


def test_map_panels_match_the_pointwise_api_and_boundaries():
    d = fg.map_data(0.2, (1.0, 1.2, 0.8))  # A2 > A1 > A3: the Lagrange-like ordering
    code = d["code"]
    assert code.shape == (fg.THETA.size, fg.U.size)
    assert set(np.unique(code)) <= {0, 1, 2}
    # a spot check against the scalar API
    i, j = 150, 200
    sat = d["sat"]
    om = d["map"].omega0[i, j]
    m = gyrostat.stationary_motion(sat, 1.0, float(fg.THETA[i]), k2=float(fg.U[j] * om * sat.Abar))
    assert gyrostat.stability(m.satellite, m).verdict == d["map"].verdict[i, j]
    # the stable region is bounded below by s2 = 0 / s3 = 0: just above max(u_s2, u_s3) at theta0 = 0 it is
    # stable, just below it is not
    b = d["b"]
    u_top = max(b["u_s2"][i], b["u_s3"][i])
    sat_k2 = lambda u: float(u * om * sat.Abar)  # noqa: E731
    up = gyrostat.stationary_motion(sat, 1.0, float(fg.THETA[i]), k2=sat_k2(u_top + 1e-6))
    dn = gyrostat.stationary_motion(sat, 1.0, float(fg.THETA[i]), k2=sat_k2(u_top - 1e-6))
    assert gyrostat.stability(up.satellite, up).verdict == "stable"
    assert gyrostat.stability(dn.satellite, dn).verdict != "stable"


def test_dumbbell_figure_data():
    sat, ms = fg.dumbbell_data()
    # the orbit plane is displaced towards the side the dumbbell axis leans to (sin 2 theta0 > 0, A1 > A3)
    assert ms.kappa0 > 0 and ms.displacement > 0
    # to scale: kappa0 of order (arm/R0)^2 (leading order 3/2 (A1 - A3)/(M R0^2) for theta0 = pi/4)
    lead = 1.5 * (sat.A1 - sat.A3)
    assert 0.5 * lead < math.tan(ms.kappa0) < 1.5 * lead
    assert gyrostat.stability(sat, ms).verdict == "stable"  # (3.4) with A1 > A3


def test_builder_writes_the_paper_figure_and_the_extras(tmp_path):
    from rigidbody.paperfigs import registry

    fs = registry()["gyrostat"]
    assert fs.paper_figures == ("fig1_dumbbell",)
    paths = fs.build(tmp_path)
    assert [p.name for p in paths] == [f"{n}.png" for n in fs.figures]
    assert len(paths) == 5
    assert all(p.exists() and p.stat().st_size > 10_000 for p in paths)


def test_symmetric_map_figure_data():
    sm = fg.symmetric_map_data()
    assert sm.code.shape == (fg.SYM_THETA.size, fg.SYM_RATIO.size)
    # away from cos theta0 = 0 (O(l^2/R^2) terms decide there) and the chart's singular line sin theta0 = 0
    ok_th = (np.abs(np.cos(fg.SYM_THETA)) > 0.3) & (np.abs(np.sin(fg.SYM_THETA)) > 1e-6)
    assert np.all(sm.code[np.abs(np.sin(fg.SYM_THETA)) < 1e-6] == -1)
    below = fg.SYM_RATIO < 0.9
    mid = (fg.SYM_RATIO > 1.1) & (fg.SYM_RATIO < 1.23)
    above = fg.SYM_RATIO > 1.45
    v = sm.verdict[ok_th]
    assert np.all(v[:, below] == "stable")
    assert np.all(v[:, mid] == "unstable")
    assert np.all(v[:, above] == "undecided")
