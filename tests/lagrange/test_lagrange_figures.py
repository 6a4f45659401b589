"""Figures 1-3 and the plotting helpers (the data are tested in tests/papers/test_lagrange_paper.py)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

from rigidbody import lagrange as L
from rigidbody.paperfigs import lagrange as figs
from rigidbody.paperfigs import registry
from rigidbody.plotting.lagrange import plot_integrals, plot_roots, slow_time_axis


def test_builder_writes_one_png_per_paper_figure(tmp_path):
    fs = registry()["lagrange"]
    assert fs.paper_figures == ("fig1_case1_theta5", "fig2_case2_theta60", "fig3_case3_theta170")
    paths = fs.build(tmp_path)
    assert [p.name for p in paths] == [f"{n}.png" for n in fs.figures]
    assert all(p.stat().st_size > 10_000 for p in paths)


def test_case_figure_draws_the_given_solution_against_tau_and_xi():
    sol = L.paper_solution(2, n_out=101, tau_end=30.0)
    fig = figs.fig2_case2_theta60(sol)
    try:
        axes = fig.axes
        assert len(axes) == 4  # roots and integrals, against tau (row 1) and xi (row 2)
        np.testing.assert_array_equal(axes[0].lines[0].get_xdata(), sol.tau)
        np.testing.assert_array_equal(axes[2].lines[0].get_xdata(), np.log1p(sol.tau))
        np.testing.assert_array_equal(axes[3].lines[1].get_ydata(), sol.H)
    finally:
        plt.close(fig)
    fig = figs.fig3_case3_theta170(L.paper_solution(3, n_out=51, tau_end=10.0))
    assert len(fig.axes) == 2  # case 3 only against tau, as in the paper
    plt.close(fig)
    with pytest.raises(ValueError, match="case must be 1, 2 or 3"):
        figs.case_figure(4)


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
