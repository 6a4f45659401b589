"""The batch convention of lagrange.averaged and lagrange.simulate: per-member components that broadcast.

``initial=(Gz0, H0, r0)`` (and ``state0=(p, q, r, phi, theta, psi)`` with ``eps``) broadcast by NumPy's rules:
the batch shape is their broadcast shape, as for the per-member arguments of ``euler_poinsot.averaged``. An
array is stacked on its last axis (the earlier form). The references: the exact spin of linear drag
r = r0 exp(-b tau / C) (3.3) in the averaged system and in the full equations (C r' = eps M3 = -eps b r), and
the start values each member was given.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidbody import lagrange as L

TOP, DRAG = L.PAPER_TOP, L.PAPER_DRAG
TAU = np.linspace(0.0, 2.0, 5)


def test_components_broadcast_to_the_batch_shape():
    # Slip caught: components read in the wrong order or the broadcast transposed (a member would start from
    # another member's Gz or r, or spin down from the wrong r0). Gz0 over the rows, r0 over the columns.
    th = math.radians(70.0)
    Gz1, H, r1 = L.integrals(TOP, 0.0, 0.0, 1.7, 0.0, th)
    Gz0 = Gz1 * np.array([[0.95], [1.0]])
    r0 = r1 * np.array([0.97, 1.0, 1.01])
    s = L.averaged(TOP, DRAG, (Gz0, H, r0), (0.0, 2.0), tau_eval=TAU, rtol=1e-10)
    assert s.batch_shape == (2, 3) and s.r.shape == (2, 3, TAU.size)
    assert np.all(s.status == 0)
    # start values to rounding of the chart's round trip (the u chart decodes (Gz, H, r) from the roots: a
    # few ulps times the roots' conditioning, 1e-12 relative is ample and far below a member's difference)
    np.testing.assert_allclose(s.Gz[..., 0], np.broadcast_to(Gz0, (2, 3)), rtol=1e-12, atol=0)
    np.testing.assert_allclose(s.H[..., 0], np.full((2, 3), H), rtol=1e-12, atol=0)
    # (3.3) exactly; the integration at rtol 1e-10 keeps r to ~1e-10 relative (factor 10 margin)
    exact = r0[None, :, None] * np.exp(-DRAG.b * TAU / TOP.C)
    np.testing.assert_allclose(s.r, np.broadcast_to(exact, s.r.shape), rtol=1e-9, atol=0)


def test_integrals_of_arrays_are_a_batch_as_they_are():
    # integrals() returns the three components: with arrays of states they go into averaged unchanged, and
    # each member equals its stacked form's member (the same states, so the same integration: rounding only)
    th = np.radians([40.0, 80.0, 120.0])
    comps = L.integrals(TOP, 0.0, 0.0, 1.7, 0.0, th)
    a = L.averaged(TOP, DRAG, comps, (0.0, 2.0), tau_eval=TAU, rtol=1e-10)
    b = L.averaged(TOP, DRAG, np.stack(comps, axis=-1), (0.0, 2.0), tau_eval=TAU, rtol=1e-10)
    assert a.batch_shape == b.batch_shape == (3,)
    for name in ("Gz", "H", "r", "u1", "u2", "u3"):
        np.testing.assert_allclose(a[name], b[name], rtol=1e-12, atol=1e-14)


def test_scalars_are_one_run_in_either_form():
    Gz, H, r = L.integrals(TOP, 0.0, 0.0, 1.7, 0.0, math.radians(60.0))
    for initial in ((Gz, H, r), [Gz, H, r], np.array([Gz, H, r])):
        s = L.averaged(TOP, DRAG, initial, (0.0, 1.0))
        assert s.batch_shape == () and s.status == 0
        assert s.r[-1] == pytest.approx(r * math.exp(-DRAG.b / TOP.C), rel=1e-10, abs=0)  # (3.3), rtol 1e-12 runs


@pytest.mark.parametrize(
    ("initial", "match"),
    [
        ([[0.1, 1.0, 1.7], [0.2, 1.0, 1.7]], r"initial as a tuple or list holds the 3 components \(Gz, H, r\), "
                                             r"got 2 entries"),
        ([[0.1, 1.0, 1.7]] * 3, "initial is ambiguous"),
        ((np.ones(2), 1.0, np.ones(3)), r"must broadcast together, got shapes \[\(2,\), \(\), \(3,\)\]"),
        (np.ones((2, 4)), r"initial must be \(Gz, H, r\) or an array of shape batch_shape \+ \(3,\), got shape "
                          r"\(2, 4\)"),
        (np.ones((0, 3)), "the batch of initial is empty"),
    ],
)
def test_what_has_no_single_reading_is_refused(initial, match):
    with pytest.raises(ValueError, match=match):
        L.averaged(TOP, DRAG, initial, (0.0, 1.0))


def test_a_component_that_is_not_numbers_is_named():
    with pytest.raises(TypeError, match=r"initial\[2\] \(r\) must be real numbers"):
        L.averaged(TOP, DRAG, (0.1, 1.0, "fast"), (0.0, 1.0))


def test_simulate_components_broadcast_with_eps():
    # Slip caught: state0's components or eps broadcast wrongly (a member with another's spin or eps). The full
    # equations keep C r' = -eps b r exactly: r = r0 exp(-eps b t / C) per member (rtol 1e-10 runs: 1e-9 margin)
    th = np.radians([[30.0], [70.0]])
    r0 = np.array([1.5, 1.7, 2.0])
    eps = np.array([0.01, 0.02, 0.03])
    t = np.linspace(0.0, 5.0, 6)
    s = L.simulate(TOP, DRAG, eps, (0.0, 0.0, r0, 0.0, th, 0.0), (0.0, 5.0), t_eval=t)
    assert s.batch_shape == (2, 3) and np.all(s.status == 0)
    exact = r0[:, None] * np.exp(-eps[:, None] * DRAG.b * t / TOP.C)
    np.testing.assert_allclose(s.r, np.broadcast_to(exact, s.r.shape), rtol=1e-9, atol=0)
    # theta starts where each member was tilted (Euler angles from the quaternion: rounding)
    np.testing.assert_allclose(s.theta[..., 0], np.broadcast_to(th, (2, 3)), rtol=0, atol=1e-12)
