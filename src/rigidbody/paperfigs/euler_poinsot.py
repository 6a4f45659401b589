"""Figures 1-6 of Rachinskaya: the hodograph of the angular momentum; G, T, k², δ, λ against τ.

The paper's setup (sec. 3): A = (3.2, 2.6, 1.67), G(0) = 1, k²(0) = 0.99, δ(0) = λ(0) = π/4, drag
I = diag(2.322, 1.31, 1.425) (case 1, χ < 0: figs 1-3) and diag(0.919, 5.228, 1.666) (case 2, χ > 0:
figs 4-6). Fig. 1 (4) is the 3-D hodograph in the orbital axes Ox1x2x3, fig. 2 (5) its projection on the
orbit plane Ox1x2, fig. 3 (6) the view along the spiral axis; figs 2, 3, 5, 6 are "at a larger scale".

The paper states neither ε, ν0 nor the end time. Our choices (also in :doc:`/euler_poinsot`): ν0 = 0,
τ ∈ [0, 6]; the hodographs show the orbit-averaged limit ε = 0 and ε = 0.005 (ν kept; in case 1 that run
ends at τ = 4.77 when the decaying rotation is no longer fast, spin ratio = 1; in case 2 it stays fast to
τ = 6). "Larger scale" is an inset magnifying the inner turns. "Along the spiral axis" is read both ways:
looking down the axis (the projection on the plane normal to it) and the spiral laid along it (distance
from the axis against the height along it, where a straight axis gives a straight line). The axis is
the one of the best-fitting cone (:func:`rigidbody.plotting.spiral_axis`). A separate figure
(:func:`eps_dependence`) shows how the picture depends on ε, including ε = 0.1 and 0.3, integrated with the
validity check switched off (``min_spin_ratio=0``) to show what the equations do outside the theory
(the drift of δ and the bent spiral the paper describes).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.core.ode import Solution
from rigidbody.paperfigs import register_figures

__all__ = [
    "eps_dependence",
    "fig1_hodograph_case1",
    "fig2_projection_case1",
    "fig3_spiral_axis_case1",
    "fig4_hodograph_case2",
    "fig5_projection_case2",
    "fig6_spiral_axis_case2",
    "figure_data",
    "hodograph_data",
    "hodograph_figure",
    "projection_figure",
    "slow_variables_case1",
    "slow_variables_case2",
    "slow_variables_figure",
    "spiral_axis_figure",
]

#: the paper's body (sec. 3)
BODY = ep.Body(3.2, 2.6, 1.67)
#: the drag tensors of the two cases (sec. 3): case 1 has chi < 0, case 2 chi > 0
CASES = {1: np.diag([2.322, 1.31, 1.425]), 2: np.diag([0.919, 5.228, 1.666])}
#: the paper's initial state; nu0 = 0 is our choice
SETUP: dict[str, Any] = dict(G0=1.0, k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4, nu0=0.0)
#: slow-time span (our choice)
TAU = (0.0, 6.0)
#: eps of the hodograph figures: the orbit-averaged limit and a small eps within the theory
EPS_MAIN = (0.0, 0.005)
#: eps of :func:`eps_dependence` (0.1 and 0.3 lie outside the theory)
EPS_SCAN = (0.0, 0.01, 0.1, 0.3)


def figure_data(I: np.ndarray, eps: float, num: int = 3001) -> Solution:
    """The averaged solution (9) behind a figure, on ``num`` points of :data:`TAU`.

    For an ``eps`` above the theory's range at the start (spin ratio <= 1) the validity check is switched
    off (``min_spin_ratio=0``) so that the figure shows what the equations do there.

    Parameters
    ----------
    I : numpy.ndarray
        The drag tensor (:data:`CASES`).
    eps : float
        The small parameter (0: the orbit-averaged limit).
    num : int
        Output points on :data:`TAU`.

    Returns
    -------
    Solution
        A run of :func:`rigidbody.euler_poinsot.averaged`.

    See Also
    --------
    hodograph_data : the runs of the paper's figures.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, section 3 (the initial state and the two drag tensors).

    Examples
    --------
    The paper's initial state, :math:`G = 1`, :math:`k^2 = 0.99`, :math:`\\delta = \\lambda = \\pi/4`; in the
    orbit-averaged limit of case 1 the decaying :math:`\\mathbf G` keeps its angle :math:`\\delta` to the
    orbit normal:

    >>> import math
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sol = figs.figure_data(figs.CASES[1], 0.0, num=61)
    >>> print(sol.G[0], sol.k2[0], sol.delta[0] == sol.lam[0] == math.pi / 4)
    1.0 0.99 True
    >>> print(f"{sol.tau[-1]:.1f} {sol.delta[-1]:.12f} {sol.n[2, -1]:.12f} {math.cos(math.pi / 4):.12f}")
    6.0 0.785398163397 0.707106781187 0.707106781187
    """
    tau_eval = np.linspace(*TAU, num)
    big = eps > 0 and ep.spin_ratio(BODY, eps, SETUP["G0"], SETUP["k2_0"]) <= 1.0
    return ep.averaged(BODY, I, eps, tau_span=TAU, tau_eval=tau_eval, min_spin_ratio=0.0 if big else 1.0, **SETUP)


def hodograph_data(case: int) -> dict[float, Solution]:
    """The runs of figures 1-3 (``case=1``) or 4-6 (``case=2``): ``{eps: Solution}`` for :data:`EPS_MAIN`.

    Parameters
    ----------
    case : {1, 2}
        The paper's drag case.

    Returns
    -------
    dict of float to Solution

    See Also
    --------
    figure_data : one run.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, section 3 and figs 1-6.

    Examples
    --------
    The orbit-averaged limit and a small eps within the theory (our choices: the paper gives no eps):

    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> runs = figs.hodograph_data(2)
    >>> sorted(runs), runs[0.005].status  # case 2 stays fast to tau = 6
    ([0.0, 0.005], 0)
    """
    return {eps: figure_data(_drag(case), eps) for eps in EPS_MAIN}


def _drag(case: int) -> np.ndarray:
    if case not in CASES:
        raise ValueError(f"case must be 1 or 2, got {case!r}")
    return CASES[case]


def _style(eps: float, sol: Solution) -> dict[str, Any]:
    """Line style and legend label of one run: eps = 0 dashed on top of the eps > 0 run it nearly covers."""
    lab = f"ε = {eps:g}" + (" (orbit-averaged)" if eps == 0 else "")
    if sol.status == 1:
        lab += f", ends at τ = {sol.tau[-1]:.2f}: {sol.event}"
    if eps == 0:
        return dict(color="k", lw=0.8, ls="--", label=lab, zorder=3)
    return dict(color="C1", lw=1.4, label=lab, zorder=2)


def _title(case: int, fig_no: int, what: str) -> str:
    return f"Fig. {fig_no}: {what}, case {case} (χ = {ep.chi(BODY, _drag(case)):.3f})"


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
    I = _drag(case)
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
        sols = {case: {eps: figure_data(_drag(case), eps) for eps in EPS_SCAN} for case in CASES}
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


def fig1_hodograph_case1(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 1: the hodograph of G, case 1 (:func:`hodograph_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 1).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    hodograph_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 1.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig1_hodograph_case1(sols)
    >>> fig.axes[0].get_title()  # chi: printed -4.477, see the errata page
    'Fig. 1: hodograph of G, case 1 (χ = -4.474)'
    """
    return hodograph_figure(1, sols)


def fig2_projection_case1(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 2: its projection on the orbit plane Ox1x2 (:func:`projection_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 1).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    projection_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 2.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig2_projection_case1(sols)
    >>> fig.get_suptitle()
    'Fig. 2: projection on the orbit plane $Ox_1x_2$, case 1 (χ = -4.474)'
    """
    return projection_figure(1, sols)


def fig3_spiral_axis_case1(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 3: the view along the spiral axis, case 1 (:func:`spiral_axis_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 1).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    spiral_axis_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 3.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig3_spiral_axis_case1(sols)
    >>> fig.get_suptitle()[:43]
    'Fig. 3: view along the spiral axis (0.0000,'
    """
    return spiral_axis_figure(1, sols)


def fig4_hodograph_case2(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 4: the hodograph of G, case 2 (:func:`hodograph_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 2).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    hodograph_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 4.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[2], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig4_hodograph_case2(sols)
    >>> fig.axes[0].get_title()  # chi: printed 3.853
    'Fig. 4: hodograph of G, case 2 (χ = 3.852)'
    """
    return hodograph_figure(2, sols)


def fig5_projection_case2(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 5: its projection on the orbit plane Ox1x2 (:func:`projection_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 2).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    projection_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 5.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[2], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig5_projection_case2(sols)
    >>> fig.get_suptitle()
    'Fig. 5: projection on the orbit plane $Ox_1x_2$, case 2 (χ = 3.852)'
    """
    return projection_figure(2, sols)


def fig6_spiral_axis_case2(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 6: the view along the spiral axis, case 2 (:func:`spiral_axis_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 2).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    spiral_axis_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 6.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[2], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig6_spiral_axis_case2(sols)
    >>> fig.get_suptitle()[:43]
    'Fig. 6: view along the spiral axis (0.0000,'
    """
    return spiral_axis_figure(2, sols)


def slow_variables_case1(sols: dict[float, Solution] | None = None) -> Any:
    """Beyond the paper: G, T, k², δ, λ against τ, case 1 (:func:`slow_variables_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 1).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    slow_variables_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 1-3.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.slow_variables_case1(sols)
    >>> len(fig.axes)
    5
    """
    return slow_variables_figure(1, sols)


def slow_variables_case2(sols: dict[float, Solution] | None = None) -> Any:
    """Beyond the paper: G, T, k², δ, λ against τ, case 2 (:func:`slow_variables_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 2).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    slow_variables_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 4-6.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[2], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.slow_variables_case2(sols)
    >>> len(fig.axes)
    5
    """
    return slow_variables_figure(2, sols)


register_figures(
    "euler_poinsot",
    "Figs 1-6: hodograph of G under gravity-gradient and drag torques (Rachinskaya)",
    {
        "fig1_hodograph_case1": fig1_hodograph_case1,
        "fig2_projection_case1": fig2_projection_case1,
        "fig3_spiral_axis_case1": fig3_spiral_axis_case1,
        "fig4_hodograph_case2": fig4_hodograph_case2,
        "fig5_projection_case2": fig5_projection_case2,
        "fig6_spiral_axis_case2": fig6_spiral_axis_case2,
        "slow_variables_case1": slow_variables_case1,
        "slow_variables_case2": slow_variables_case2,
        "eps_dependence": eps_dependence,
    },
)
