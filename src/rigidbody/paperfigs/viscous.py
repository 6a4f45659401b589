"""Figures 1-5 of Krivtsov (2000) and, beyond the paper, the time histories of k, R, s, ξ, ζ.

Fig. 1 is the model: the ball-and-rod structure of section 2, drawn for ``N = 4`` balls on a circle of
radius ``a = 1``, rod half-length ``b = 1.5``, ball radius 0.3 (our choice; the paper draws it without
numbers). The paper prints no parameters for figs 2-5 either; we choose (stated here and in :doc:`/viscous`):
``θ12 = 2, θ3 = 1``, ``Ω0 = 6`` (``ξ∞ = 30`` rad ≈ 4.8 turns of the tangent);
fig. 2 contracting ``B12 = 0.4, B3 = 0.1``, ``v0 = 2`` (``k0 = 1.5``, ``R0 = 0.55``);
fig. 3 unwinding ``B12 = 0.1, B3 = 0.1``, ``v0 = 0.6`` (``k0 = 5``, ``R0 = 0.2``);
figs 4-5 one turn of each spiral starting at ``t1 = 0``. Paths are drawn from ``t = 0`` to ``t = ∞``
(the reconstruction runs in the compactified time ``u = 1 - e^{-γt}``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rigidbody import viscous as vs
from rigidbody.paperfigs import register_figures

__all__ = [
    "fig1_ball_and_rod",
    "fig2_contracting_spiral",
    "fig3_unwinding_spiral",
    "fig4_turn_contracting",
    "fig5_turn_unwinding",
    "figure_data",
    "histories",
    "spiral_figure",
    "turn_figure",
]

BODY = vs.Body(theta12=2.0, theta3=1.0)
CONTRACTING = vs.Medium(B12=0.4, B3=0.1)
UNWINDING = vs.Medium(B12=0.1, B3=0.1)
OMEGA0 = 6.0
N0 = np.array([1.0, 0.0, 0.0])
MEDIA = {"contracting": CONTRACTING, "unwinding": UNWINDING}
NDOT0 = {"contracting": np.array([0.0, 2.0, 0.0]), "unwinding": np.array([0.0, 0.6, 0.0])}
#: the structure of fig. 1 as drawn: N balls on a circle of radius a, rod half-length b, ball radius
SKETCH_N, SKETCH_A, SKETCH_B, SKETCH_BALL = 4, 1.0, 1.5, 0.3
#: the times of the histories figure
T_HISTORIES = np.linspace(0.0, 80.0, 801)


def figure_data(name: str, t_max: float = 200.0, num: int = 4000) -> dict[str, np.ndarray]:
    """The arrays behind the spiral figures ('contracting' or 'unwinding'): path n(t) from (v, k) and
    the closed-form histories.

    Parameters
    ----------
    name : {'contracting', 'unwinding'}
    t_max : float
        The last time of the histories.
    num : int
        Number of times.

    Returns
    -------
    dict
        ``t``, the path ``n`` (3, num), its end point ``n_inf`` and binormal ``g_inf`` at ``t = inf``, the
        curvature ``k``, the radius ``R`` and the quasi-coordinates ``s, xi, zeta`` at ``t``.

    See Also
    --------
    spiral_figure, histories : the figures drawn from it.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eqs. (3.4), (4.5), (5.1)-(5.2).

    Examples
    --------
    The contracting spiral: ``k0 = (1 · 6)/(2 · 2) = 1.5``, and the tangent turns by ``ξ∞ = θ3² Ω0/(θ12 B3) = 30``
    rad in all:

    >>> from rigidbody.paperfigs import viscous as figs
    >>> d = figs.figure_data("contracting", num=50)
    >>> print(f"{d['k'][0]:.12f} {d['xi'][-1]:.6f}")
    1.500000000000 30.000000
    """
    medium = MEDIA[name]
    ndot0 = NDOT0[name]
    v0 = float(np.linalg.norm(ndot0))
    # time grid dense where the path turns fast: uniform in the compactified time of the reconstruction
    gamma = min(vs.decay_rates(BODY, medium))
    u = np.linspace(0.0, 1.0 - np.exp(-gamma * t_max), num)
    t = -np.log1p(-u) / gamma
    n, _, g = vs.axis_path(BODY, medium, N0, ndot0, OMEGA0, np.append(t, np.inf), frame=True)
    s, xi, zeta = vs.quasi_coordinates(BODY, medium, OMEGA0, v0, t)
    return {
        "t": t, "n": n[:, :-1], "n_inf": n[:, -1], "g_inf": g[:, -1],
        "k": vs.curvature(BODY, medium, OMEGA0, v0, t), "R": vs.spiral_radius(BODY, medium, OMEGA0, v0, t),
        "s": s, "xi": xi, "zeta": zeta,
    }


def fig1_ball_and_rod(N: int = SKETCH_N, a: float = SKETCH_A, b: float = SKETCH_B, ball_radius: float = SKETCH_BALL,
                      beta: float = 0.1, mass: float = 1.0) -> Any:
    """Fig. 1: the ball-and-rod structure whose drag torque is exactly (1.1), with the body and medium
    :func:`rigidbody.viscous.ball_and_rod` gives for it (one ball: mass 1, drag coefficient 0.1).

    The parameters are those of :func:`rigidbody.viscous.ball_and_rod`; the defaults are the structure as
    drawn: 4 balls on a circle of radius 1, a rod of half-length 1.5, balls of radius 0.3.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.plotting.ball_and_rod_sketch : the drawing.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 2, fig. 1.

    Examples
    --------
    Four balls of radius 0.3 on a circle of radius 1, two on the rod at ``±1.5``: ``θ12 = 2 + 4.5 + 6 · 0.4 · 0.09``,
    ``θ3 = 4 + 0.216``, ``B12 = 0.1 (2 + 4.5)``, ``B3 = 0.4``; ``B12/θ12 > B3/θ3``, so the spiral contracts:

    >>> from rigidbody.paperfigs import viscous as figs
    >>> print(figs.fig1_ball_and_rod().get_suptitle())
    Fig. 1: N = 4 balls on a circle of radius a = 1, rod AB of length 2b = 3
    θ12 = 6.716, θ3 = 4.216, B12 = 0.65, B3 = 0.4: contracting spiral
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import viscous as pv

    body, medium = vs.ball_and_rod(N, a, b, beta=beta, mass=mass, ball_radius=ball_radius)
    fig = plt.figure(figsize=(6.0, 6.0))
    ax = fig.add_subplot(111, projection="3d")
    pv.ball_and_rod_sketch(N, a, b, ball_radius, ax)
    fig.suptitle(f"Fig. 1: N = {N} balls on a circle of radius a = {a:g}, rod AB of length "
                 f"2b = {2 * b:g}\nθ12 = {body.theta12:.4g}, θ3 = {body.theta3:.4g}, B12 = {medium.B12:.4g}, "
                 f"B3 = {medium.B3:.4g}: {vs.regime(body, medium)} spiral", fontsize=9)
    return fig


def spiral_figure(name: str, n: np.ndarray | None = None, view: np.ndarray | None = None) -> Any:
    """Fig. 2 (``'contracting'``) or 3 (``'unwinding'``): the path of the symmetry axis on the unit sphere.

    The contracting spiral is seen from its limit point, the unwinding one from the pole of the great
    circle it tends to; the far side of the sphere is dashed. ``n`` (shape (3, m)) is the path from
    ``t = 0`` to its end point at ``t = inf`` (:func:`rigidbody.viscous.axis_path`) and ``view`` the
    direction it is seen from (default: its end point); without them both come from :func:`figure_data`.

    Parameters
    ----------
    name : {'contracting', 'unwinding'}
    n : ndarray, optional
        The path of the axis, shape (3, m), ending at its limit point.
    view : ndarray, optional
        The direction the sphere is seen from.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    figure_data : the data.
    rigidbody.plotting.sphere_path : the drawing.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, figs 2-3.

    Examples
    --------
    >>> from rigidbody.paperfigs import viscous as figs
    >>> d = figs.figure_data("unwinding", num=50)
    >>> fig = figs.spiral_figure("unwinding", np.column_stack([d["n"], d["n_inf"]]), d["g_inf"])
    >>> fig.axes[0].get_title()
    'Fig. 3: unwinding spiral (B12=0.1, B3=0.1, θ12=2, θ3=1)'
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import viscous as pv

    fig_no = {"contracting": 2, "unwinding": 3}[name]
    medium = MEDIA[name]
    if n is None:
        d = figure_data(name)
        n = np.column_stack([d["n"], d["n_inf"]])
        view = d["n_inf"] if name == "contracting" else d["g_inf"]
    n = np.asarray(n, dtype=float)
    fig = plt.figure(figsize=(5.5, 5.5))
    ax = fig.add_subplot(111, projection="3d")
    pv.sphere_path(n, ax, view=n[:, -1] if view is None else view, label=f"{name} spiral", lw=1.0)
    ax.set_title(f"Fig. {fig_no}: {name} spiral (B12={medium.B12}, B3={medium.B3}, θ12=2, θ3=1)", fontsize=9)
    return fig


def turn_figure(name: str, tr: vs.Turn | None = None) -> Any:
    """Fig. 4 (``'contracting'``) or 5 (``'unwinding'``): one turn of the spiral from ``t1 = 0`` and the solid
    angle χ it bounds (:func:`rigidbody.viscous.turn`), seen from the turn's centre.

    Parameters
    ----------
    name : {'contracting', 'unwinding'}
    tr : rigidbody.viscous.Turn, optional
        The turn to draw (default: the one from ``t1 = 0`` of the spiral of figure 2 or 3).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.plotting.turn_solid_angle : the drawing.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, section 5, figs 4-5.

    Examples
    --------
    The panel's title gives χ and the paper's cap approximation ``2π(1 - sqrt(1 - R²))`` at mid-turn:

    >>> from rigidbody.paperfigs import viscous as figs
    >>> figs.turn_figure("contracting").axes[0].get_title()[:2]
    'χ '
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import viscous as pv

    fig_no = {"contracting": 4, "unwinding": 5}[name]
    if tr is None:
        tr = vs.turn(BODY, MEDIA[name], N0, NDOT0[name], OMEGA0, 0.0)
    fig = plt.figure(figsize=(5.5, 5.5))
    ax = fig.add_subplot(111, projection="3d")
    pv.turn_solid_angle(tr, ax)
    fig.suptitle(f"Fig. {fig_no}: one turn of the {name} spiral, t in [0, {tr.t2:.3f}]", fontsize=10)
    return fig


def _histories(name: str, t: np.ndarray) -> dict[str, np.ndarray]:
    medium, v0 = MEDIA[name], float(np.linalg.norm(NDOT0[name]))
    s, xi, zeta = vs.quasi_coordinates(BODY, medium, OMEGA0, v0, t)
    return {"t": t, "k": vs.curvature(BODY, medium, OMEGA0, v0, t),
            "R": vs.spiral_radius(BODY, medium, OMEGA0, v0, t), "s": s, "xi": xi, "zeta": zeta}


def histories(data: dict[str, dict[str, np.ndarray]] | None = None) -> Any:
    """Beyond the paper: curvature (4.5), spiral radius (5.2) and quasi-coordinates (5.1) against t for both
    spirals, to t = 80.

    ``data``: ``{'contracting': d, 'unwinding': d}``, each ``d`` with the arrays ``t, k, R, s, xi, zeta``
    (default: the closed forms on :data:`T_HISTORIES` for the spirals of figures 2 and 3).

    Parameters
    ----------
    data : dict, optional
        ``{'contracting': figure_data(...), 'unwinding': figure_data(...)}`` (computed if not given).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    figure_data : the data.
    rigidbody.plotting.quasi_coordinate_histories : one column.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, eqs. (4.5), (5.1)-(5.2).

    Examples
    --------
    Five panels a spiral, one column each:

    >>> from rigidbody.paperfigs import viscous as figs
    >>> data = {name: figs.figure_data(name, num=50) for name in ("contracting", "unwinding")}
    >>> fig = figs.histories(data)
    >>> [ax.get_title() for ax in fig.axes[:2]], [ax.get_ylabel() for ax in fig.axes[::2]]
    (['contracting', 'unwinding'], ['k', 'R', 's', 'ξ', 'ζ'])
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import viscous as pv

    datas = {name: _histories(name, T_HISTORIES) for name in MEDIA} if data is None else data
    fig, axes = plt.subplots(5, 2, figsize=(9.0, 9.0), sharex=True)
    for j, name in enumerate(("contracting", "unwinding")):
        d = datas[name]
        pv.quasi_coordinate_histories(
            d["t"], {"k": d["k"], "R": d["R"], "s": d["s"], "ξ": d["xi"], "ζ": d["zeta"]}, axes=axes[:, j])
        axes[0, j].set_title(name)
    fig.suptitle("Curvature (4.5), spiral radius (5.2) and quasi-coordinates (5.1)")
    fig.tight_layout()
    return fig


def fig2_contracting_spiral(n: np.ndarray | None = None, view: np.ndarray | None = None) -> Any:
    """Fig. 2: the contracting spiral (:func:`spiral_figure`).

    Parameters
    ----------
    n, view : ndarray, optional
        The path of the axis and the direction it is seen from (:func:`spiral_figure`; computed from
        :func:`figure_data` of ``'contracting'`` if not given).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    spiral_figure : the same for either spiral.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, fig. 2.

    Examples
    --------
    Our parameters (the paper gives none) start the path with the curvature ``k0 = 1.5`` and the radius
    ``R0 = 1/sqrt(1 + k0²)``:

    >>> import math
    >>> from rigidbody.paperfigs import viscous as figs
    >>> data = figs.figure_data("contracting", num=50)
    >>> print(f"{data['k'][0]:.12f} {data['R'][0]:.12f} {1 / math.sqrt(1 + 1.5**2):.12f}")
    1.500000000000 0.554700196225 0.554700196225
    >>> figs.fig2_contracting_spiral().axes[0].get_title()[:26]
    'Fig. 2: contracting spiral'
    """
    return spiral_figure("contracting", n, view)


def fig3_unwinding_spiral(n: np.ndarray | None = None, view: np.ndarray | None = None) -> Any:
    """Fig. 3: the unwinding spiral (:func:`spiral_figure`).

    Parameters
    ----------
    n, view : ndarray, optional
        The path of the axis and the direction it is seen from (:func:`spiral_figure`; computed from
        :func:`figure_data` of ``'unwinding'`` if not given).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    spiral_figure : the same for either spiral.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, fig. 3.

    Examples
    --------
    Our parameters (the paper gives none) start the path with the curvature ``k0 = 5.0`` and the radius
    ``R0 = 1/sqrt(1 + k0²)``:

    >>> import math
    >>> from rigidbody.paperfigs import viscous as figs
    >>> data = figs.figure_data("unwinding", num=50)
    >>> print(f"{data['k'][0]:.12f} {data['R'][0]:.12f} {1 / math.sqrt(1 + 5.0**2):.12f}")
    5.000000000000 0.196116135138 0.196116135138
    >>> figs.fig3_unwinding_spiral().axes[0].get_title()[:24]
    'Fig. 3: unwinding spiral'
    """
    return spiral_figure("unwinding", n, view)


def fig4_turn_contracting(tr: vs.Turn | None = None) -> Any:
    """Fig. 4: one turn of the contracting spiral and its solid angle (:func:`turn_figure`).

    Parameters
    ----------
    tr : rigidbody.viscous.Turn, optional
        The turn to draw (:func:`turn_figure`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    turn_figure : the same for either spiral.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, fig. 4.

    Examples
    --------
    The spiral radius (5.2) shrinks over the turn:

    >>> from rigidbody import viscous
    >>> from rigidbody.paperfigs import viscous as figs
    >>> tr = viscous.turn(figs.BODY, figs.MEDIA["contracting"], figs.N0, figs.NDOT0["contracting"], figs.OMEGA0)
    >>> bool(tr.R2 < tr.R1)
    True
    >>> fig = figs.fig4_turn_contracting()
    >>> fig.get_suptitle() == f"Fig. 4: one turn of the contracting spiral, t in [0, {tr.t2:.3f}]"
    True
    """
    return turn_figure("contracting", tr)


def fig5_turn_unwinding(tr: vs.Turn | None = None) -> Any:
    """Fig. 5: one turn of the unwinding spiral and its solid angle (:func:`turn_figure`).

    Parameters
    ----------
    tr : rigidbody.viscous.Turn, optional
        The turn to draw (:func:`turn_figure`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    turn_figure : the same for either spiral.

    References
    ----------
    :ref:`A. M. Krivtsov, PMM 64 (2000) <ref-krivtsov-2000>`, fig. 5.

    Examples
    --------
    The spiral radius (5.2) grows over the turn:

    >>> from rigidbody import viscous
    >>> from rigidbody.paperfigs import viscous as figs
    >>> tr = viscous.turn(figs.BODY, figs.MEDIA["unwinding"], figs.N0, figs.NDOT0["unwinding"], figs.OMEGA0)
    >>> bool(tr.R2 > tr.R1)
    True
    >>> fig = figs.fig5_turn_unwinding()
    >>> fig.get_suptitle() == f"Fig. 5: one turn of the unwinding spiral, t in [0, {tr.t2:.3f}]"
    True
    """
    return turn_figure("unwinding", tr)


register_figures(
    "viscous",
    "Figs 1-5: the ball-and-rod model, spirals of the symmetry axis, the solid angle of a turn (Krivtsov 2000)",
    {
        "fig1_ball_and_rod": fig1_ball_and_rod,
        "fig2_contracting_spiral": fig2_contracting_spiral,
        "fig3_unwinding_spiral": fig3_unwinding_spiral,
        "fig4_turn_contracting": fig4_turn_contracting,
        "fig5_turn_unwinding": fig5_turn_unwinding,
        "histories": histories,
    },
)
