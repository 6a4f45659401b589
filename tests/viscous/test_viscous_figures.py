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

    paths = figs.build(tmp_path)
    assert len(paths) == 5
    assert all(p.exists() and p.stat().st_size > 10_000 for p in paths)
    plt.close("all")


def test_plot_helpers_validate_and_return_axes():
    from rigidbody.plotting import viscous as pv

    with pytest.raises(ValueError, match="shape"):
        pv.sphere_path(np.zeros((2, 5)))
    n = vs.axis_path(figs.BODY, figs.CONTRACTING, figs.N0, figs.NDOT0["contracting"], figs.OMEGA0,
                     np.linspace(0, 10, 50))
    ax = pv.sphere_path(n)
    assert len(ax.lines) >= 1
    import matplotlib.pyplot as plt

    plt.close("all")
