"""Figures 1-3 builder and plotting helpers (the data are tested in tests/papers/test_lagrange_paper.py)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

from rigidbody import lagrange as L
from rigidbody.plotting.lagrange import plot_integrals, plot_roots, slow_time_axis


def test_builder_writes_three_figures(tmp_path):
    from rigidbody.paperfigs import registry

    build = registry()["lagrange"].build
    paths = build(tmp_path)
    assert [p.name for p in paths] == ["lagrange_fig1.png", "lagrange_fig2.png", "lagrange_fig3.png"]
    assert all(p.stat().st_size > 10_000 for p in paths)


def test_plot_helpers_draw_the_solution_arrays():
    sol = L.paper_solution(2, n_out=101, tau_end=30.0)
    fig, ax = plt.subplots(1, 2)
    lines = plot_roots(sol, ax[0], x="xi")
    np.testing.assert_array_equal(lines[0].get_xdata(), np.log1p(sol.tau))  # xi = ln(1 + tau)
    np.testing.assert_array_equal(lines[2].get_ydata(), sol.u3)
    lines = plot_integrals(sol, ax[1], mgl=0.5)
    np.testing.assert_array_equal(lines[1].get_ydata(), sol.H)
    plt.close(fig)
    with pytest.raises(ValueError, match="'tau' or 'xi'"):
        slow_time_axis(sol, "t")
