"""The data behind the figure builder (figs 1-6) and its registration."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import euler_poinsot as ep
from rigidbody.paperfigs import euler_poinsot as figs
from rigidbody.paperfigs import registry
from rigidbody.plotting import euler_poinsot as epp


def test_registered():
    assert "euler_poinsot" in registry()


def test_figure_data_case2_limit_spiral():
    s = figs.figure_data(figs.CASES["case 2 (chi>0)"], 0.0, num=601)
    assert s.status == 0 and s.tau[-1] == pytest.approx(6.0)
    turns = (s.lam[0] - s.lam[-1]) / (2 * math.pi)
    assert 6.0 < turns < 7.5  # measured 6.68 turns of the spiral by tau = 6
    h = epp.hodograph(s)
    assert h.shape == (3, 601) and np.linalg.norm(h[:, 0]) == pytest.approx(1.0)
    # orbit-averaged: delta constant, so the spiral axis is x3
    assert epp.spiral_axis(s) == pytest.approx([0, 0, 1], abs=0.05)


def test_figure_data_case1_eps_main_ends_with_slow_rotation():
    s = figs.figure_data(figs.CASES["case 1 (chi<0)"], 0.005, num=601)
    assert s.status == 1 and s.event == "slow_rotation"
    assert ep.spin_ratio(figs.BODY, 0.005, s.G[-1], s.k2[-1]) == pytest.approx(1.0, abs=0.05)


def test_figure_data_large_eps_is_flagged_outside_the_theory():
    assert ep.spin_ratio(figs.BODY, 0.1, 1.0, 0.99) < 1  # so figure_data switches the check off
    s = figs.figure_data(figs.CASES["case 1 (chi<0)"], 0.3, num=601)
    assert s.status == 0 and np.abs(s.delta - math.pi / 4).max() > 0.3


@pytest.mark.slow
def test_builder_writes_the_pngs(tmp_path):
    paths = figs.build(tmp_path)
    assert len(paths) == 5 and all(p.exists() and p.stat().st_size > 10_000 for p in paths)
