"""The drawings of Rachinskaya's figures 1-6 for either drag case, and the dependence on eps
(:mod:`rigidbody.paperfigs.euler_poinsot` re-exports them with the paper's numbered figures).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.core.ode import Solution
from rigidbody.paperfigs._euler_poinsot_data import (
    BODY,
    CASES,
    EPS_SCAN,
    SETUP,
    drag_tensor,
    figure_data,
    hodograph_data,
)

__all__ = ["eps_dependence", "hodograph_figure", "projection_figure", "slow_variables_figure", "spiral_axis_figure"]


def _style(eps: float, sol: Solution) -> dict[str, Any]:
    """Line style and legend label of one run: eps = 0 dashed on top of the eps > 0 run it nearly covers."""
    lab = f"ε = {eps:g}" + (" (orbit-averaged)" if eps == 0 else "")
    if sol.status == 1:
        lab += f", ends at τ = {sol.tau[-1]:.2f}: {sol.event}"
    if eps == 0:
        return dict(color="k", lw=0.8, ls="--", label=lab, zorder=3)
    return dict(color="C1", lw=1.4, label=lab, zorder=2)


def _title(case: int, fig_no: int, what: str) -> str:
    return f"Fig. {fig_no}: {what}, case {case} (χ = {ep.chi(BODY, drag_tensor(case)):.3f})"


def _runs(case: int, sols: dict[float, Solution] | None) -> dict[float, Solution]:
    # draw eps > 0 first so that the dashed eps = 0 line lies on top
    sols = hodograph_data(case) if sols is None else sols
    return dict(sorted(sols.items(), key=lambda kv: -kv[0]))


def hodograph_figure(case: int, sols: dict[float, Solution] | None = None) -> Any:
    """Figure 1 (case 1) or 4 (case 2): the hodograph of the angular momentum in the axes Ox1x2x3.

    The orbit normal :math:`x_3` is drawn grey; the axes have equal scales. ``sols`` defaults to
    :func:`hodograph_data`.

    Parameters
    ----------
    case : {1, 2}
    sols : dict of float to Solution, optional
        ``{eps: run}``.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.plotting.hodograph_3d : draws one run.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, figs 1 and 4; :math:`\\chi` (9) printed -4.477 and 3.853
    (see :doc:`/errata`).

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> figs.hodograph_figure(2, {0.0: figs.figure_data(figs.CASES[2], 0.0, num=61)}).axes[0].get_title()
    'Fig. 4: hodograph of G, case 2 (χ = 3.852)'
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import euler_poinsot as epp

    fig = plt.figure(figsize=(6.5, 6.0))
    ax = fig.add_subplot(111, projection="3d")
    sols = _runs(case, sols)
    top = max(float(np.nanmax(epp.hodograph(s)[2])) for s in sols.values())
    ax.plot([0, 0], [0, 0], [0, top], color="0.6", lw=0.8, label="orbit normal $x_3$")
    for eps, s in sols.items():
        epp.hodograph_3d(s, ax, **_style(eps, s))
    ax.view_init(elev=22, azim=-60)
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title(_title(case, 1 + 3 * (case - 1), "hodograph of G"), fontsize=10)
    return fig


def _zoom_radius(sol: Solution, normal: Any, turns: float = 1.0) -> float:
    """Radius (in the projection normal to ``normal``) of the part of the path after its first ``turns``."""
    from rigidbody.plotting import euler_poinsot as epp

    _, e1, e2 = epp.plane_basis(normal)
    h = epp.hodograph(sol)
    x, y = e1 @ h, e2 @ h
    ang = np.unwrap(np.arctan2(y, x))
    later = np.abs(ang - ang[0]) >= 2 * np.pi * turns
    if not np.any(later):
        later = np.arange(x.size) >= x.size // 2
    return float(np.max(np.hypot(x[later], y[later])))


def _projection(ax: Any, sols: dict[float, Solution], normal: Any, zoom: float | None = None) -> None:
    """Project the runs on ``ax`` (plane normal to ``normal``); ``zoom``: half-width of a centred window."""
    from rigidbody.plotting import euler_poinsot as epp

    for eps, s in sols.items():
        epp.hodograph_projection(s, ax, normal=normal, **_style(eps, s))
    if zoom is not None:
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlim(-zoom, zoom)
        ax.set_ylim(-zoom, zoom)
    ax.grid(alpha=0.3)


def _zoom(sols: dict[float, Solution], normal: Any) -> float:
    return 1.1 * max(_zoom_radius(s, normal) for s in sols.values())


def projection_figure(case: int, sols: dict[float, Solution] | None = None) -> Any:
    """Figure 2 (case 1) or 5 (case 2): the hodograph projected on the orbit plane Ox1x2; right, the
    turns after the first one at a larger scale (the square on the left).

    Parameters
    ----------
    case : {1, 2}
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.plotting.hodograph_projection : draws one run.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, figs 2 and 5.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.projection_figure(1, sols)
    >>> [ax.get_title() for ax in fig.axes]
    ['the whole path', 'the square, enlarged']
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11.5, 5.4))
    sols = _runs(case, sols)
    normal = (0.0, 0.0, 1.0)
    r = _zoom(sols, normal)
    _projection(ax1, sols, normal)
    ax1.add_patch(Rectangle((-r, -r), 2 * r, 2 * r, fill=False, ec="0.4", lw=0.8))
    ax1.legend(fontsize=7, loc="upper left")
    ax1.set_title("the whole path", fontsize=9)
    _projection(ax2, sols, normal, zoom=r)
    ax2.set_title("the square, enlarged", fontsize=9)
    fig.suptitle(_title(case, 2 + 3 * (case - 1), "projection on the orbit plane $Ox_1x_2$"), fontsize=10)
    fig.tight_layout()
    return fig


def spiral_axis_figure(case: int, sols: dict[float, Solution] | None = None) -> Any:
    """Figure 3 (case 1) or 6 (case 2): the hodograph along the spiral axis.

    Left: looking down the axis (the projection on the plane normal to it), the turns after the first
    one at a larger scale. Right: the spiral laid along its axis, distance from the axis against the
    height along it; a spiral on a cone about a straight axis is a straight line through the origin. The
    axis is that of the ``eps > 0`` run (:func:`rigidbody.plotting.spiral_axis`), printed in the title.

    Parameters
    ----------
    case : {1, 2}
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.plotting.hodograph_side_view : the right panel.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, figs 3 and 6.

    Examples
    --------
    In the orbit-averaged limit :math:`\\delta` is constant, the hodograph lies on a circular cone about the
    orbit normal :math:`x_3`, and that is the axis found:

    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> figs.spiral_axis_figure(1, sols).get_suptitle()
    'Fig. 3: view along the spiral axis (0.0000, 0.0000, 1.0000), case 1 (χ = -4.474)'
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import euler_poinsot as epp

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11.5, 5.4))
    sols = _runs(case, sols)
    axis = epp.spiral_axis(sols[max(sols)])
    _projection(ax1, sols, axis, zoom=_zoom(sols, axis))
    ax1.set_xlabel("in-plane coordinate 1 ($x_1$ projected)")
    ax1.set_ylabel("in-plane coordinate 2")
    ax1.legend(fontsize=7, loc="upper left")
    ax1.set_title("looking down the spiral axis (inner turns)", fontsize=9)
    for eps, s in sols.items():
        epp.hodograph_side_view(s, ax2, axis=axis, **_style(eps, s))
    ax2.set_xlim(left=0)
    ax2.set_ylim(bottom=0)
    ax2.set_aspect("equal", adjustable="box")
    ax2.set_title("the spiral laid along its axis (straight axis: a straight line)", fontsize=9)
    ax2.grid(alpha=0.3)
    a = ", ".join(f"{round(float(c), 4) + 0.0:.4f}" for c in axis)  # + 0.0: no "-0.0000"
    fig.suptitle(_title(case, 3 + 3 * (case - 1), f"view along the spiral axis ({a})"), fontsize=10)
    fig.tight_layout()
    return fig


def slow_variables_figure(case: int, sols: dict[float, Solution] | None = None) -> Any:
    """G, T, k², δ, λ against τ for the runs of figures 1-3 (case 1) or 4-6 (case 2); the dotted line is
    the stable equilibrium of k² of (8).

    Parameters
    ----------
    case : {1, 2}
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.plotting.slow_variables : the five panels.
    rigidbody.euler_poinsot.k2_equilibria : the dotted line.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (8)-(9).

    Examples
    --------
    Case 1 (:math:`\\chi < -3`) has a stable equilibrium :math:`k_*^2` of (8) inside (0, 1), the dotted line: a
    zero of the right-hand side of (8), :math:`(1 - \\chi)(1 - k^2) - [(1 - \\chi) + (1 + \\chi)k^2]E/K`:

    >>> from scipy.special import ellipe, ellipk
    >>> from rigidbody import euler_poinsot as ep
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.slow_variables_figure(1, sols)
    >>> len(fig.axes), len(fig.axes[2].lines)
    (5, 2)
    >>> k2, chi = fig.axes[2].lines[1].get_ydata()[0], ep.chi(figs.BODY, figs.CASES[1])
    >>> rhs = (1 - chi) * (1 - k2) - ((1 - chi) + (1 + chi) * k2) * ellipe(k2) / ellipk(k2)
    >>> print(f"{k2:.6f}", bool(abs(rhs) < 1e-12))
    0.520638 True
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import euler_poinsot as epp

    fig, axes = plt.subplots(5, 1, figsize=(7, 10), sharex=True)
    for eps, s in _runs(case, sols).items():
        st = _style(eps, s)
        label = st.pop("label")
        epp.slow_variables(s, axes, label=label, **st)
    I = drag_tensor(case)
    stable = [k for k, kind in ep.k2_equilibria(BODY, I) if kind == "stable"]
    for k in stable:
        axes[2].axhline(k, color="0.6", ls=":", lw=0.8)
    axes[0].set_title(f"Case {case}: slow variables of (9), χ = {ep.chi(BODY, I):.4f}")
    fig.tight_layout()
    return fig


def eps_dependence(sols: dict[int, dict[float, Solution]] | None = None) -> Any:
    """δ(τ), the projection on Ox1x2 and the side view along x3 for ε = 0, 0.01, 0.1, 0.3, both cases.

    ε = 0.1 and 0.3 are above the theory's range at the start (spin ratio < 1) and are integrated with
    the check switched off: only there δ drifts and the spiral bends as the paper describes.

    ``sols``: ``{case: {eps: Solution}}`` for the cases 1, 2 (default: :func:`figure_data` for each eps of
    :data:`EPS_SCAN`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    figure_data : the runs.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, figs 1-6 and the text after them.

    Examples
    --------
    Its runs start outside the theory for :math:`\\varepsilon = 0.1` and 0.3 (spin ratio below 1):

    >>> from rigidbody import euler_poinsot as ep
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> [bool(ep.spin_ratio(figs.BODY, eps, 1.0, 0.99) > 1) for eps in figs.EPS_SCAN[1:]]
    [True, False, False]
    >>> fig = figs.eps_dependence()  # doctest: +SKIP
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import euler_poinsot as epp

    if sols is None:
        sols = {case: {eps: figure_data(drag_tensor(case), eps) for eps in EPS_SCAN} for case in CASES}
    fig, axs = plt.subplots(2, 3, figsize=(15, 8))
    for row, case in enumerate(CASES):
        for eps, s in sols[case].items():
            valid = eps == 0 or ep.spin_ratio(BODY, eps, SETUP["G0"], SETUP["k2_0"]) > 1
            lab = f"ε = {eps:g}" + ("" if valid else " (outside the theory)")
            if s.status == 1:
                lab += f", ends at τ = {s.tau[-1]:.2f} ({s.event})"
            axs[row, 0].plot(s.tau, s.delta, lw=0.9, label=lab)
            epp.hodograph_projection(s, axs[row, 1], lw=0.7, label=lab)
            epp.hodograph_side_view(s, axs[row, 2], lw=0.7, label=lab)
        axs[row, 0].set_ylabel("$\\delta$")
        axs[row, 0].set_xlabel("$\\tau$")
        axs[row, 0].set_title(f"case {case}: δ(τ) for several ε")
        axs[row, 1].set_title("projection on $Ox_1x_2$")
        axs[row, 2].set_xlabel("distance from the $x_3$ axis")
        axs[row, 2].set_ylabel("$x_3$")
        axs[row, 2].set_title("side view (δ = const: a straight line)")
        axs[row, 0].legend(fontsize=8)
    fig.tight_layout()
    return fig

