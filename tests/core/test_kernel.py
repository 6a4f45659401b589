"""rigidbody.core.kernel: the elliptic means of the averaged right-hand sides against mpmath, floats = arrays."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from rigidbody.core import kernel as K

K2S = [0.0, 1e-300, 1e-12, 1e-6, 0.01, 0.3, 0.5, 0.9, 0.99, 1 - 1e-6, 1 - 1e-12, 1.0]


def _reference(k2: float) -> tuple[float, float]:
    """E/K and (K - E)/(k^2 K) at 60 digits (the subtraction costs at most ~25 of them at k^2 = 1e-12)."""
    if k2 == 1.0:
        return 0.0, 1.0
    if k2 < 1e-30:  # the series' first terms: <sn^2> = 1/2 + k^2/16 + ..., E/K = 1 - k^2/2 - ...
        return 1.0 - k2 / 2, 0.5 + k2 / 16
    with mpmath.workdps(60):
        m = mpmath.mpf(k2)
        ek = mpmath.ellipe(m) / mpmath.ellipk(m)
        return float(ek), float((1 - ek) / m)


@pytest.mark.parametrize("k2", K2S)
def test_elliptic_ratios_against_mpmath(k2):
    ek_ref, s_ref = _reference(k2)
    ek, s = K.elliptic_ratios(K.SCALAR, k2)
    # <sn^2> is a sum of positive AGM terms: a few ulp; E/K = 1 - k^2 <sn^2> loses relative accuracy only as
    # E/K -> 0 at the separatrix (like 1/ln(4/k'), so at most a factor 30 at 1 - k^2 = 1e-12)
    assert s == pytest.approx(s_ref, rel=1e-14, abs=0)
    assert ek == pytest.approx(ek_ref, rel=3e-14, abs=0)
    ek_a, s_a = K.elliptic_ratios(K.ARRAY, np.array([k2, 0.5, 0.01]))
    # the array path is the AGM throughout (floats take SciPy's K, E from k^2 = 0.1 on): both within the bounds
    # above of the reference, so within their sum of each other
    assert s_a[0] == pytest.approx(s, rel=2e-14, abs=0)
    assert ek_a[0] == pytest.approx(ek, rel=6e-14, abs=1e-17)
    assert s_a[0] == pytest.approx(s_ref, rel=1e-14, abs=0)
    assert ek_a[0] == pytest.approx(ek_ref, rel=3e-14, abs=0)


def test_elliptic_ratios_outside_the_range_give_the_limits():
    # trial stages of an integrator may step past k^2 = 1 or below 0: the limits, never NaN
    assert K.elliptic_ratios(K.SCALAR, 1.5) == (0.0, 1.0)
    assert K.elliptic_ratios(K.SCALAR, -0.1) == (1.0, 0.5)
    ek, s = K.elliptic_ratios(K.ARRAY, np.array([1.5, -0.1, 0.5]))
    assert ek[:2].tolist() == [0.0, 1.0] and s[:2].tolist() == [1.0, 0.5]
    assert np.all(np.isfinite(ek)) and np.all(np.isfinite(s))


def test_namespaces_agree():
    x = 0.37
    for name in ("sqrt", "exp", "log", "sin", "cos", "tanh", "expm1"):
        assert getattr(K.SCALAR, name)(x) == pytest.approx(float(getattr(K.ARRAY, name)(np.array([x]))[0]),
                                                           rel=1e-15, abs=0)
