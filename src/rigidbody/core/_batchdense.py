"""The vectorised DOP853's dense output and event location, per member (used by :mod:`rigidbody.core.batch`).

:class:`BatchDense` is Hairer's 7th-order interpolant of one accepted step for a set of members, evaluated as
SciPy's ``Dop853DenseOutput`` does; :func:`locate` finds each member's root of an event in its step on it;
:func:`comb` forms the linear combinations of stages that the step and its interpolant are made of.
"""

from __future__ import annotations

import numpy as np

from . import dop853 as rk
from .ode import Event

__all__ = ["BatchDense", "comb", "locate"]


def comb(c: np.ndarray, K: np.ndarray) -> np.ndarray:
    """The linear combination ``c @ K`` of stage rows by einsum's own loop: a BLAS call would spread these
    memory-bound products over threads, which on a loaded machine costs more than it saves."""
    return np.einsum("...j,jk->...k", c, K)


class BatchDense:
    """The DOP853 dense output of one accepted step for a set of members (``F`` of shape (7, m, n)).

    Parameters
    ----------
    t_old, h : numpy.ndarray
        The members' step starts and sizes, shape ``(m,)``.
    y_old : numpy.ndarray
        Their states at the step starts, shape ``(m, n)``.
    F : numpy.ndarray
        The interpolant's coefficient rows, shape ``(7, m, n)``.
    """

    __slots__ = ("F", "h", "t_old", "y_old")

    def __init__(self, t_old: np.ndarray, h: np.ndarray, y_old: np.ndarray, F: np.ndarray) -> None:
        self.t_old, self.h, self.y_old, self.F = t_old, h, y_old, F

    def __call__(self, t: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """States at times ``t`` (shape (p,)) of the members ``rows`` (indices into this step's members)."""
        x = ((t - self.t_old[rows]) / self.h[rows])[:, None]
        F = self.F[:, rows, :]
        y = np.zeros_like(F[0])
        for i, f in enumerate(F[::-1]):
            y += f
            if i % 2 == 0:
                y *= x
            else:
                y *= 1.0 - x
        return y + self.y_old[rows]

    def on_grid(self, te: np.ndarray, rows: np.ndarray, lo: np.ndarray, cnt: np.ndarray) -> tuple[np.ndarray, ...]:
        """States on the grid points ``te[lo_i], ..., te[lo_i + cnt_i - 1]`` of each member ``rows_i`` (``cnt_i
        >= 1``): the interpolant evaluated per member on a block of its samples (the member's coefficients
        gathered once, not once per sample), members grouped by their number of samples (up to 2, 4, 8, ...) so
        that a block is never more than half empty. Returns the members' positions (into ``rows``), the grid
        indices and the states, one row per sample."""
        out_w, out_j, out_y = [], [], []
        bucket = np.ceil(np.log2(np.maximum(cnt, 1))).astype(int)
        for b in np.unique(bucket):
            sel = np.nonzero(bucket == b)[0]
            r, c = rows[sel], cnt[sel]
            S = int(c.max())
            k = np.arange(S)
            J = lo[sel, None] + k
            valid = k < c[:, None]
            t = te[np.minimum(J, te.size - 1)]
            x = ((t - self.t_old[r][:, None]) / self.h[r][:, None])[:, :, None]
            x1 = 1.0 - x
            F = self.F[:, r, :][:, :, None, :]
            y = F[6] * x
            for q in range(5, -1, -1):  # the alternating factors of scipy's Dop853DenseOutput, innermost first
                y += F[q]
                y *= x1 if q % 2 else x
            y += self.y_old[r][:, None, :]
            out_w.append(np.repeat(sel, c))
            out_j.append(J[valid])
            out_y.append(y[valid])
        if len(out_w) == 1:
            return out_w[0], out_j[0], out_y[0]
        return np.concatenate(out_w), np.concatenate(out_j), np.concatenate(out_y)


def locate(
    ev: Event, dense: BatchDense, rows: np.ndarray, ta: np.ndarray, tb: np.ndarray, ga: np.ndarray,
    args_rows: tuple[np.ndarray, ...],
) -> np.ndarray:
    """Zero of ``ev.fun`` on each member's step ``[ta, tb]`` (a bracket with ``ga`` at ``ta``).

    A vectorised Illinois (modified regula falsi) iteration with a bisection fallback, each member until its
    estimate moves by less than ``dop853.ROOT_TOL`` (4 ulp) of ``t`` or 1e-12 of the step: every iteration
    evaluates the event once on the unconverged members.

    Parameters
    ----------
    ev : Event
        The event (``ev.fun`` vectorised over members).
    dense : BatchDense
        The dense output of the step.
    rows : numpy.ndarray
        The members' positions in ``dense``.
    ta, tb, ga : numpy.ndarray
        Each member's step and its event value at ``ta``.
    args_rows : tuple of numpy.ndarray
        The members' extra arguments of ``ev.fun``.

    Returns
    -------
    numpy.ndarray
        The roots, within each member's step.
    """
    a, b = ta.copy(), tb.copy()
    fa = ga.copy()
    fb = np.asarray(ev.fun(b, dense(b, rows), *args_rows), dtype=float).reshape(-1)
    ta_val, tb_val = fa.copy(), fb.copy()  # the event's values at a and b (fa, fb are Illinois-weighted)
    side = np.zeros(a.size)
    root = np.where(fb == 0.0, b, np.where(fa == 0.0, a, 0.5 * (a + b)))
    todo = (fa != 0.0) & (fb != 0.0)
    # converged when an estimate moves by less than 4 ulp of t or 1e-12 of the step: far below the integration
    # error of the state at the event (the event function's own rounding would stall a tighter criterion)
    tol_all = np.maximum(rk.ROOT_TOL * np.maximum(np.abs(ta), np.abs(tb)), 1e-12 * (tb - ta))
    small_all = 1e-10 * np.maximum(np.abs(fa), np.abs(fb))
    for _ in range(100):
        idx = np.nonzero(todo)[0]
        if not idx.size:
            break
        ai, bi, fai, fbi = a[idx], b[idx], fa[idx], fb[idx]
        with np.errstate(all="ignore"):
            c = bi - fbi * (bi - ai) / (fbi - fai)
        # a secant estimate on (or, by rounding, beyond) an end whose event value is already negligible: that end
        # is the root; on an end otherwise (the Illinois weights at work), or not finite: bisect
        small = small_all[idx]
        hit_a = (c <= ai) & (np.abs(ta_val[idx]) <= small)
        hit_b = (c >= bi) & (np.abs(tb_val[idx]) <= small)
        done_end = hit_a | hit_b
        if done_end.any():
            root[idx[done_end]] = np.where(hit_a, ai, bi)[done_end]
            todo[idx[done_end]] = False
            keep = ~done_end
            idx, ai, bi, fai, fbi, c = idx[keep], ai[keep], bi[keep], fai[keep], fbi[keep], c[keep]
            if not idx.size:
                break
        c = np.where(np.isfinite(c) & (c > ai) & (c < bi), c, 0.5 * (ai + bi))
        sub_args = tuple(x[idx] for x in args_rows)
        fc = np.asarray(ev.fun(c, dense(c, rows[idx]), *sub_args), dtype=float).reshape(-1)
        tol = tol_all[idx]
        conv = (fc == 0.0) | (np.abs(c - root[idx]) <= tol) | (bi - ai <= 2.0 * tol)
        root[idx] = c
        keep_a = np.sign(fc) == np.sign(fai)  # c replaces a (the root lies in [c, b])
        si = side[idx]
        # Illinois: halve the value at the end kept twice in a row
        fb[idx] = np.where(keep_a & (si == -1), 0.5 * fbi, fbi)
        fa[idx] = np.where(~keep_a & (si == 1), 0.5 * fai, fai)
        a[idx] = np.where(keep_a, c, ai)
        fa[idx] = np.where(keep_a, fc, fa[idx])
        ta_val[idx] = np.where(keep_a, fc, ta_val[idx])
        b[idx] = np.where(keep_a, bi, c)
        fb[idx] = np.where(keep_a, fb[idx], fc)
        tb_val[idx] = np.where(keep_a, tb_val[idx], fc)
        side[idx] = np.where(keep_a, -1, 1)
        todo[idx] = ~conv
    # never report a root outside the step
    return np.clip(root, ta, tb)
