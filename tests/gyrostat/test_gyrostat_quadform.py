"""rigidbody.core.quadform (added for the gyrostat module): inertia, minors, constrained forms, derivatives."""

from __future__ import annotations

import numpy as np
import pytest

from rigidbody.core import quadform as qf


def _random_sym(rng, n, lam=None):
    Q, _ = np.linalg.qr(rng.normal(size=(n, n)))
    lam = rng.normal(size=n) if lam is None else np.asarray(lam, float)
    return Q @ np.diag(lam) @ Q.T, lam


def test_equilibrate_is_a_congruence_with_unit_rows():
    rng = np.random.default_rng(1)
    A, _ = _random_sym(rng, 5)
    D = np.diag(10.0 ** rng.uniform(-9, 9, 5))
    H = D @ A @ D
    Hs, d = qf.equilibrate(H)
    assert np.allclose(Hs, np.diag(d) @ H @ np.diag(d), rtol=1e-12, atol=0)
    # Ruiz scaling: each pass halves the log-imbalance; 12 passes on 36 decades: within ~1 %, 5 % allowed
    assert np.allclose(np.max(np.abs(Hs), axis=1), 1.0, atol=0.05)


def test_leading_minors_badly_scaled():
    rng = np.random.default_rng(2)
    A, _ = _random_sym(rng, 4)
    dd = 10.0 ** rng.uniform(-8, 8, 4)
    H = np.diag(dd) @ A @ np.diag(dd)
    m = qf.leading_minors(H)
    ref = np.array([np.linalg.det(A[:k, :k]) * np.prod(dd[:k]) ** 2 for k in range(1, 5)])
    # the minors of A are O(1): relative accuracy ~1e-14 per factor, 1e-10 is a generous bound
    assert np.allclose(m, ref, rtol=1e-10)


def test_inertia_counts_and_zero_detection():
    rng = np.random.default_rng(3)
    stack = []
    expect = []
    for lam in ([1, 2, 3], [-1, 2, 3], [-1, -2, 3], [-1, -2, -3], [0, 1, -1], [0, 0, 1]):
        A, _ = _random_sym(rng, 3, lam)
        stack.append(A)
        lam = np.array(lam)
        expect.append((np.sum(lam > 0), np.sum(lam < 0), np.sum(lam == 0)))
    n_pos, n_neg, n_zero = qf.inertia(np.array(stack))
    assert n_pos.shape == (6,)
    assert [tuple(map(int, x)) for x in zip(n_pos, n_neg, n_zero)] == expect
    with pytest.raises(ValueError, match="non-finite"):
        qf.inertia(np.array([[np.nan, 0], [0, 1.0]]))
    with pytest.raises(ValueError, match="shape"):
        qf.inertia(np.ones((2, 3)))


def test_null_space_form():
    H = np.diag([1.0, -1.0, 2.0])
    G = np.array([0.0, 1.0, 0.0])
    N = qf.null_space_form(H, G)
    assert N.shape == (2, 2)
    assert np.allclose(np.sort(np.linalg.eigvalsh(N)), [1.0, 2.0])
    with pytest.raises(ValueError, match="columns"):
        qf.null_space_form(H, [1.0, 0.0])


def test_fd_hessian_and_complex_step_gradient():
    def f(x):
        return x[0] ** 3 * x[1] + np.sin(x[2]) * x[0] + np.exp(x[1] * x[2])

    x = np.array([0.7, -0.3, 1.1])
    e = np.exp(x[1] * x[2])
    H_ref = np.array([
        [6 * x[0] * x[1], 3 * x[0] ** 2, np.cos(x[2])],
        [3 * x[0] ** 2, x[2] ** 2 * e, e + x[1] * x[2] * e],
        [np.cos(x[2]), e + x[1] * x[2] * e, -np.sin(x[2]) * x[0] + x[1] ** 2 * e],
    ])
    # 8th-order differences, h = 1e-2: truncation ~h^8 ~ 1e-16, round-off ~ eps/h^2 ~ 1e-12
    assert np.allclose(qf.hessian_fd(f, x, 1e-2), H_ref, atol=1e-9)
    g_ref = np.array([3 * x[0] ** 2 * x[1] + np.sin(x[2]), x[0] ** 3 + x[2] * e, np.cos(x[2]) * x[0] + x[1] * e])
    assert np.allclose(qf.gradient_cs(f, x), g_ref, rtol=1e-15, atol=1e-15)


@pytest.mark.parametrize("lam", [[1e-6, 1, 2, -3, 5], [-1e-6, 1, 2, 3, 4], [1e-6, -1e-6, 1, 1, 1],
                                 [1e-4, -2, 1, 1, -1]])
def test_inertia_survives_twenty_decades_of_scaling(lam):
    """H = D A D with D spanning 1e-10..1e10 (the SI situation) has the inertia of A (Sylvester's law),
    including an eigenvalue of A of 1e-6 relative.  A raw eigvalsh of H cannot resolve it (its absolute
    error eps * |H| ~ 1e4 dwarfs the small eigenvalues: it reports 0 negative ones for the second case)."""
    rng = np.random.default_rng(4)
    A, lam = _random_sym(rng, 5, lam)
    d = 10.0 ** rng.permutation(np.linspace(-10, 10, 5))
    H = A * d[:, None] * d[None, :]
    expect = (int(np.sum(lam > 0)), int(np.sum(lam < 0)), 0)
    assert tuple(int(x) for x in qf.inertia(H)) == expect
    # the same through the vectorised path (a stack with a well-scaled matrix of other inertia)
    n_pos, n_neg, n_zero = qf.inertia(np.stack([H, np.eye(5)]))
    assert (int(n_pos[0]), int(n_neg[0]), int(n_zero[0])) == expect and int(n_neg[1]) == 0
