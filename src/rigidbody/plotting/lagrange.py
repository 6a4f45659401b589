"""Plotting helpers for :mod:`rigidbody.lagrange` (take an ``ax``, return artists)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .common import get_ax

__all__ = ["plot_averaged", "plot_integrals", "plot_roots", "plot_top_motion", "slow_time_axis"]


def slow_time_axis(sol: Any, x: str = "tau") -> tuple[np.ndarray, str]:
    r"""The abscissa of a slow-variable plot: ``'tau'`` or ``'xi'`` (``xi = ln(1 + tau)``, as the paper).

    Parameters
    ----------
    sol : Solution
        An averaged run (its ``tau``).
    x : {'tau', 'xi'}

    Returns
    -------
    (numpy.ndarray, str)
        The values and the axis label.

    See Also
    --------
    plot_roots, plot_integrals : the plots that use it.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    figs 1-2 (the abscissa xi).

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody.plotting import slow_time_axis
    >>> from rigidbody import lagrange
    >>> sol = lagrange.paper_solution(3, n_out=50, tau_end=5.0)
    >>> xi, label = slow_time_axis(sol, "xi")
    >>> print(np.allclose(xi, np.log1p(sol.tau), rtol=0, atol=1e-15), label)
    True $\xi = \ln(1 + \tau)$
    """
    if x == "tau":
        return np.asarray(sol.tau), r"$\tau = \varepsilon t$"
    if x == "xi":
        return np.log1p(np.asarray(sol.tau)), r"$\xi = \ln(1 + \tau)$"
    raise ValueError(f"x must be 'tau' or 'xi', got {x!r}")


def plot_roots(sol: Any, ax: Any = None, x: str = "tau") -> list:
    r"""Draw u1, u2, u3 of an averaged solution against tau or xi; mark sign switches of delta1.

    Parameters
    ----------
    sol : Solution
        A run of :func:`rigidbody.lagrange.averaged`.
    ax : matplotlib.axes.Axes, optional
    x : {'tau', 'xi'}
        The abscissa (:func:`slow_time_axis`).

    Returns
    -------
    list
        The artists drawn (the three roots first).

    See Also
    --------
    plot_integrals : the slow variables Gz, H, r.
    plot_averaged : both side by side.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    eqs. (1.5) and (3.4), figs 1-3.

    Examples
    --------
    Case 3 of the paper starts at rest relative to its nutation (``p = q = 0``), so :math:`\cos\theta_0` is a
    turning point, the root :math:`u_2`:

    >>> import math
    >>> from rigidbody.plotting import plot_roots
    >>> from rigidbody import lagrange
    >>> sol = lagrange.paper_solution(3, n_out=50, tau_end=5.0)
    >>> lines = plot_roots(sol)
    >>> [ln.get_label() for ln in lines[:3]]
    ['$u_1$', '$u_2$', '$u_3$']
    >>> print(f"{lines[1].get_ydata()[0]:.12f} {math.cos(math.radians(170)):.12f}")
    -0.984807753012 -0.984807753012
    """
    ax = get_ax(ax)
    xs, label = slow_time_axis(sol, x)
    arts = []
    for i, (name, c) in enumerate(zip(("u_1", "u_2", "u_3"), ("C0", "C1", "C2"))):
        arts += ax.plot(xs, sol.u[i], color=c, lw=1.4, label=f"${name}$")
    for te in np.asarray(sol.t_events.get("delta1_flip", [])):
        xv = te if x == "tau" else np.log1p(te)
        arts.append(ax.axvline(xv, color="0.6", ls=":", lw=1.0))
    ax.axhline(1.0, color="0.8", lw=0.8)
    ax.axhline(-1.0, color="0.8", lw=0.8)
    ax.set_xlabel(label)
    ax.set_ylabel("roots of Q(u)")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    return arts


def plot_integrals(sol: Any, ax: Any = None, x: str = "tau", mgl: float | None = None) -> list:
    """Draw Gz, H, r of an averaged solution against tau or xi (and the limit H = -mgl if given).

    Parameters
    ----------
    sol : Solution
        A run of :func:`rigidbody.lagrange.averaged`.
    ax : matplotlib.axes.Axes, optional
    x : {'tau', 'xi'}
        The abscissa (:func:`slow_time_axis`).
    mgl : float, optional
        Draw the level ``H = -mgl`` (the top hanging at rest).

    Returns
    -------
    list
        The artists drawn.

    See Also
    --------
    plot_roots : the roots u1, u2, u3.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    eqs. (1.2) and (3.4), figs 1-3.

    Examples
    --------
    >>> from rigidbody.plotting import plot_integrals
    >>> from rigidbody import lagrange
    >>> sol = lagrange.paper_solution(3, n_out=50, tau_end=5.0)
    >>> arts = plot_integrals(sol, mgl=lagrange.PAPER_TOP.mgl)
    >>> [a.get_label() for a in arts[:3]], list(arts[3].get_ydata())
    (['$G_z$', '$H$', '$r$'], [-0.5, -0.5])
    """
    ax = get_ax(ax)
    xs, label = slow_time_axis(sol, x)
    arts = []
    arts += ax.plot(xs, sol.Gz, color="C3", lw=1.4, label="$G_z$")
    arts += ax.plot(xs, sol.H, color="C4", lw=1.4, label="$H$")
    arts += ax.plot(xs, sol.r, color="C5", lw=1.4, label="$r$")
    if mgl is not None:
        arts.append(ax.axhline(-mgl, color="C4", ls="--", lw=0.8))
    ax.axhline(0.0, color="0.8", lw=0.8)
    ax.set_xlabel(label)
    ax.set_ylabel("slow variables")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    return arts


def _panels(ax: Any, n: int, figsize: tuple[float, float]) -> np.ndarray:
    if ax is not None:
        axes = np.asarray(ax, dtype=object).ravel()
        if axes.size != n:
            raise ValueError(f"ax must hold {n} Axes, got {axes.size}")
        return axes
    import matplotlib.pyplot as plt

    _, axes = plt.subplots(1, n, figsize=figsize)
    return np.asarray(axes, dtype=object)


def plot_averaged(sol: Any, ax: Any = None, x: str = "tau") -> np.ndarray:
    """The standard figure of :func:`rigidbody.lagrange.averaged`: :func:`plot_roots` and
    :func:`plot_integrals` side by side (two Axes, created when ``ax`` is None); returns the Axes.

    Parameters
    ----------
    sol : Solution
        A run of :func:`rigidbody.lagrange.averaged`.
    ax : sequence of two Axes, optional
    x : {'tau', 'xi'}
        The abscissa (:func:`slow_time_axis`).

    Returns
    -------
    numpy.ndarray of Axes

    See Also
    --------
    rigidbody.plotting.plot_solution : ``sol.plot()``, which calls it.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    figs 1-3.

    Examples
    --------
    >>> from rigidbody.plotting import plot_averaged
    >>> from rigidbody import lagrange
    >>> sol = lagrange.paper_solution(3, n_out=50, tau_end=5.0)
    >>> import matplotlib.pyplot as plt
    >>> [ax.get_ylabel() for ax in plot_averaged(sol, plt.subplots(1, 2)[1])]
    ['roots of Q(u)', 'slow variables']
    """
    axes = _panels(ax, 2, (11.0, 4.0))
    plot_roots(sol, axes[0], x=x)
    plot_integrals(sol, axes[1], x=x)
    if ax is None:
        axes[0].figure.tight_layout()
    return axes


def plot_top_motion(sol: Any, ax: Any = None, **kw: Any) -> np.ndarray:
    """The standard figure of a full motion (:func:`rigidbody.lagrange.simulate`,
    :func:`rigidbody.lagrange.lagrange_motion`): the nutation ``u = cos(theta)`` and the integrals
    ``Gz, H, r`` against the time (two Axes, created when ``ax`` is None); returns the Axes.

    ``u`` moves between the roots ``u1`` and ``u2`` of the unperturbed motion; ``Gz, H, r`` are its
    integrals, constant without a torque and slowly changing under one.

    Parameters
    ----------
    sol : Solution
        A full motion.
    ax : sequence of two Axes, optional
    **kw
        Line style of ``u``.

    Returns
    -------
    numpy.ndarray of Axes

    See Also
    --------
    plot_averaged : the averaged counterpart.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (1.1)-(1.3).

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> import numpy as np
    >>> from rigidbody import lagrange
    >>> from rigidbody.plotting import plot_top_motion
    >>> m = lagrange.lagrange_motion(lagrange.PAPER_TOP, lagrange.paper_initial_state(3), np.linspace(0, 10, 101))
    >>> axes = plot_top_motion(m, plt.subplots(1, 2)[1])  # on given Axes (without them: a new figure)
    >>> u = axes[0].lines[0].get_ydata()
    >>> bool(m.u1 - 1e-9 <= u.min() and u.max() <= m.u2 + 1e-9)
    True
    """
    axes = _panels(ax, 2, (11.0, 4.0))
    t = np.asarray(sol.time)
    axes[0].plot(t, sol.u, lw=0.8, **kw)
    axes[0].set_ylabel(r"$u = \cos\theta$")
    for name, label, c in (("Gz", "$G_z$", "C3"), ("H", "$H$", "C4"), ("r", "$r$", "C5")):
        # lagrange_motion keeps the constant integrals as single values
        axes[1].plot(t, np.broadcast_to(np.asarray(getattr(sol, name), dtype=float), t.shape), color=c, lw=1.0,
                     label=label)
    axes[1].set_ylabel("integrals (1.2)")
    axes[1].legend(loc="best", fontsize=8)
    for a in axes:
        a.set_xlabel(f"${sol.time_name}$")
        a.grid(alpha=0.3)
    if ax is None:
        axes[0].figure.tight_layout()
    return axes
