"""The data behind figs 2-5 (not the pixels) and a smoke run of the registered builder."""

import numpy as np
import pytest

from rigidbody import viscous as vs
from rigidbody.paperfigs import viscous as figs


@pytest.mark.parametrize("name", ["contracting", "unwinding"])
def test_spiral_figure_data(name):
    d = figs.figure_data(name, t_max=60.0, num=400)
    medium = figs.MEDIA[name]
    assert vs.regime(figs.BODY, medium) == name
    # the plotted path is the simulated axis (1e-10: both at rtol 1e-12, see test_viscous_path.py)
    idx = [0, 100, 250, 399]
    sim = vs.simulate(figs.BODY, medium, figs.N0, figs.NDOT0[name], figs.OMEGA0, (0.0, d["t"][-1]), t_eval=d["t"][idx])
    assert np.max(np.linalg.norm(d["n"][:, idx] - sim.n, axis=0)) < 1e-10
    assert np.allclose(np.linalg.norm(d["n"], axis=0), 1.0, atol=1e-12)  # frame stays orthonormal to ~rtol
    if name == "contracting":
        assert np.all(np.diff(d["k"]) > 0) and np.all(np.diff(d["R"]) < 0)
        # the end point x is the limit of the spiral: within the remaining length s_inf - s(t_max)
        s_inf = vs.limits(figs.BODY, medium, figs.OMEGA0, 2.0)[0]
        assert np.linalg.norm(d["n"][:, -1] - d["n_inf"]) <= s_inf - d["s"][-1] + 1e-12
    else:
        assert np.all(np.diff(d["k"]) < 0) and np.all(np.diff(d["R"]) > 0)
        # tends to a great circle: R -> 1 (k(60) = 5 e^{-3} = 0.25 -> R = 0.97)
        assert d["R"][-1] == pytest.approx(1 / np.hypot(1, 5 * np.exp(-0.05 * d["t"][-1])), rel=1e-12, abs=0)
        assert d["R"][-1] > 0.95


def test_builder_writes_the_figures(tmp_path):
    import matplotlib.pyplot as plt

    from rigidbody.paperfigs import registry

    fs = registry()["viscous"]
    assert fs.paper_figures == ("fig1_ball_and_rod", "fig2_contracting_spiral", "fig3_unwinding_spiral",
                                "fig4_turn_contracting", "fig5_turn_unwinding")
    paths = fs.build(tmp_path)
    assert [p.name for p in paths] == [f"{n}.png" for n in fs.figures]
    assert all(p.exists() and p.stat().st_size > 10_000 for p in paths)
    plt.close("all")


def test_ball_and_rod_sketch_places_the_balls_of_the_model():
    import matplotlib.pyplot as plt

    from rigidbody.plotting import viscous as pv

    N, a, b, r = 5, 1.0, 1.2, 0.2
    ax = pv.ball_and_rod_sketch(N, a, b, r)
    try:
        assert len(ax.collections) == N + 2  # one surface per ball: N on the circle, A and B on the rod
        ends = []
        for ln in ax.lines:
            x, y, z = (np.asarray(c, dtype=float) for c in ln.get_data_3d())
            if x.size == 2 and x[0] == y[0] == z[0] == 0 and z[1] == 0:  # a spoke from C in the plane z = 0
                ends.append((x[1], y[1]))
        # the spokes end where ball_and_rod puts the masses: radius a, equal angles
        ang = np.sort(np.mod(np.arctan2([e[1] for e in ends], [e[0] for e in ends]), 2 * np.pi))
        np.testing.assert_allclose(np.hypot(*np.array(ends).T), a, rtol=1e-12, atol=0)
        np.testing.assert_allclose(ang, 2 * np.pi * np.arange(N) / N, rtol=0, atol=1e-12)
        rod = [ln for ln in ax.lines if np.allclose(ln.get_data_3d()[0], 0) and np.allclose(ln.get_data_3d()[1], 0)]
        assert any(np.allclose(sorted(ln.get_data_3d()[2]), [-b, b]) for ln in rod)  # the rod AB
    finally:
        plt.close("all")
    with pytest.raises(ValueError, match="N must be >= 3"):
        pv.ball_and_rod_sketch(2, a, b, r)
