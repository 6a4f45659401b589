"""The data behind figures 1-6 (not the pixels), the spiral-axis fit, and the registration."""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

from rigidbody import euler_poinsot as ep
from rigidbody.paperfigs import euler_poinsot as figs
from rigidbody.paperfigs import registry
from rigidbody.plotting import euler_poinsot as epp


def test_registered_with_six_paper_figures():
    fs = registry()["euler_poinsot"]
    assert fs.paper_figures == (
        "fig1_hodograph_case1", "fig2_projection_case1", "fig3_spiral_axis_case1",
        "fig4_hodograph_case2", "fig5_projection_case2", "fig6_spiral_axis_case2",
    )


def test_figure_data_case2_limit_spiral():
    s = figs.figure_data(figs.CASES[2], 0.0, num=601)
    assert s.status == 0 and s.tau[-1] == pytest.approx(6.0, rel=1e-12, abs=0)
    turns = (s.lam[0] - s.lam[-1]) / (2 * math.pi)
    assert 6.0 < turns < 7.5  # measured 6.68 turns of the spiral by tau = 6
    h = epp.hodograph(s)
    assert h.shape == (3, 601) and np.linalg.norm(h[:, 0]) == pytest.approx(1.0, rel=1e-12, abs=0)
    # orbit-averaged: delta is constant, so the hodograph lies on a cone about x3 and the fitted axis is x3
    # (to the integrator's tolerance, rtol ~ 1e-10)
    assert epp.spiral_axis(s) == pytest.approx([0, 0, 1], rel=0, abs=1e-8)


def test_spiral_axis_recovers_a_tilted_cone_from_less_than_one_turn():
    # an independent cone: half-angle 0.4 about a tilted axis, 0.7 of a turn, sampled unevenly
    a = np.array([0.3, -0.2, 0.9])
    a /= np.linalg.norm(a)
    e1 = np.cross(a, [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    phi = 1.4 * np.pi * np.linspace(0, 1, 200) ** 2

    class Path:
        n = (np.cos(0.4) * a[:, None] + np.sin(0.4) * (np.outer(e1, np.cos(phi)) + np.outer(e2, np.sin(phi))))

    assert epp.spiral_axis(Path) == pytest.approx(a, rel=0, abs=1e-12)


def test_figure_data_case1_eps_main_ends_with_slow_rotation():
    s = figs.figure_data(figs.CASES[1], 0.005, num=601)
    assert s.status == 1 and s.event == "slow_rotation"
    assert ep.spin_ratio(figs.BODY, 0.005, s.G[-1], s.k2[-1]) == pytest.approx(1.0, rel=0, abs=0.05)


def test_figure_data_large_eps_is_flagged_outside_the_theory():
    assert ep.spin_ratio(figs.BODY, 0.1, 1.0, 0.99) < 1  # so figure_data switches the check off
    s = figs.figure_data(figs.CASES[1], 0.3, num=601)
    assert s.status == 0 and np.abs(s.delta - math.pi / 4).max() > 0.3


def test_spiral_axis_figure_draws_the_cone_as_a_straight_line():
    sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=401)}
    fig = figs.fig3_spiral_axis_case1(sols)
    try:
        side = fig.axes[1]
        (line,) = side.lines
        across, along = line.get_xdata(), line.get_ydata()
        # on the cone delta = pi/4 about x3 the height equals the distance from the axis (cot(pi/4) = 1)
        np.testing.assert_allclose(along, across, rtol=1e-8, atol=0)
        np.testing.assert_allclose(np.hypot(across, along), sols[0.0].G, rtol=1e-12, atol=0)
        # looking down the axis: the projection on Ox1x2 (the axis is x3), zoomed on the inner turns
        x, y = fig.axes[0].lines[0].get_xdata(), fig.axes[0].lines[0].get_ydata()
        h = epp.hodograph(sols[0.0])
        np.testing.assert_allclose(np.hypot(x, y), np.hypot(h[0], h[1]), rtol=1e-12, atol=1e-14)
        assert fig.axes[0].get_xlim()[1] < 0.5 * np.hypot(h[0, 0], h[1, 0])
    finally:
        plt.close(fig)


def test_projection_figure_marks_the_enlarged_square():
    sols = {0.0: figs.figure_data(figs.CASES[2], 0.0, num=401)}
    fig = figs.fig5_projection_case2(sols)
    try:
        full, zoom = fig.axes
        (square,) = full.patches
        half = zoom.get_xlim()[1]
        assert square.get_width() == pytest.approx(2 * half, rel=1e-12, abs=0)
        assert zoom.get_ylim() == pytest.approx((-half, half), rel=1e-12, abs=0)
        np.testing.assert_array_equal(zoom.lines[0].get_xdata(), full.lines[0].get_xdata())
    finally:
        plt.close(fig)


@pytest.mark.slow
def test_builder_writes_the_pngs(tmp_path):
    fs = registry()["euler_poinsot"]
    paths = fs.build(tmp_path)
    assert [p.name for p in paths] == [f"{n}.png" for n in fs.figures]
    assert all(p.exists() and p.stat().st_size > 10_000 for p in paths)
