"""The plotting helpers of the studies draw the data they are given (tested on the data, not the pixels), from a
sweep's Dataset or from the same numbers as a StudyMap (the figures command's, without xarray)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr

from rigidbody import studies as S
from rigidbody.plotting import studies as sp

# each helper is run on the Dataset and on the StudyMap of the same numbers
KINDS = pytest.mark.parametrize("kind", [lambda ds: ds, S.as_study_map], ids=["Dataset", "StudyMap"])


def _errors() -> xr.Dataset:
    eps = np.array([0.04, 0.02, 0.01])
    c = np.array([1.0, 4.0])
    err = eps[:, None] ** 2 * c[None, :]
    err[2, 1] = np.nan  # a failed point
    return xr.Dataset({"error": (("eps", "k2_0"), err)}, coords={"eps": eps, "k2_0": [0.3, 0.9]})


@KINDS
def test_averaging_error_plot_draws_each_line_and_the_theory_slope(kind):
    fig, ax = plt.subplots()
    lines = sp.averaging_error_plot(kind(_errors()), 2.0, ax=ax)
    assert len(lines) == 3
    np.testing.assert_array_equal(lines[1].get_ydata(), [0.04**2 * 4, 0.02**2 * 4])  # the failed point left out
    x, y = lines[-1].get_data()
    slope = np.polyfit(np.log(x), np.log(y), 1)[0]
    assert slope == pytest.approx(2.0, rel=1e-12, abs=0)
    assert y[0] / x[0] ** 2 == pytest.approx(1.0, rel=1e-12, abs=0)  # median of error / eps^2 = (1, 1, 1, 4, 4)
    plt.close(fig)


@KINDS
def test_scaled_error_map_is_flat_where_the_order_holds(kind):
    fig, ax = plt.subplots()
    mesh = sp.scaled_error_map(kind(_errors()), 2.0, ax=ax, ylog=True)
    z = np.ma.masked_invalid(mesh.get_array()).reshape(2, 3)
    np.testing.assert_allclose(z[0], 0.0, atol=1e-12)  # log10(1)
    np.testing.assert_allclose(z[1, :2], np.log10(4.0), atol=1e-12)
    assert np.ma.getmaskarray(z)[1, 0] and np.ma.getmaskarray(z).sum() == 1  # sorted eps: 0.01 (failed) first
    assert any(t.get_text() == "failed" for t in ax.texts)
    plt.close(fig)


@KINDS
def test_spin_end_map_draws_the_regimes_and_the_lines_of_8(kind):
    r = np.linspace(0.2, 2.2, 5)
    reg = np.array([[S.spin_end_predicted(a, b) for b in r] for a in r], dtype=float)
    ds = xr.Dataset({"regime": (("r1", "r3"), reg)}, coords={"r1": r, "r3": r})
    fig, ax = plt.subplots()
    out = sp.spin_end_map(kind(ds), ax=ax, cases={"case 1": (1.44, 1.69)})
    np.testing.assert_array_equal(out[0].get_array().reshape(5, 5), reg.T)  # r3 vertical
    x, y = out[1].get_data()
    np.testing.assert_allclose(y, 2 * x - 1, rtol=0, atol=1e-12)  # chi = -3
    x, y = out[2].get_data()
    np.testing.assert_allclose(y, x, rtol=0, atol=0)
    x, y = out[3].get_data()
    assert x.max() < 1.0
    np.testing.assert_allclose(y, S.equilibrium_line(x, 0.5), rtol=0, atol=0)
    plt.close(fig)
