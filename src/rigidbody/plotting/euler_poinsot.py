"""Plots for :mod:`rigidbody.euler_poinsot`: the hodograph of the angular momentum in the orbital axes
(3-D, projections, view along the spiral axis) and the slow variables against tau (Rachinskaya, figs 1-6)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .common import get_ax

__all__ = [
    "equal_3d",
    "hodograph",
    "hodograph_3d",
    "hodograph_projection",
    "hodograph_side_view",
    "plane_basis",
    "separatrix_passage",
    "slow_variables",
    "spiral_axis",
]


def hodograph(sol: Any) -> np.ndarray:
    """The points of the hodograph, :math:`\\mathbf G = G\\mathbf n` in the orbital axes, shape (3, n).

    Parameters
    ----------
    sol : Solution
        A run with the fields ``G`` (magnitude) and ``n`` (unit direction, shape (3, n)).

    Returns
    -------
    numpy.ndarray

    See Also
    --------
    hodograph_3d, hodograph_projection, hodograph_side_view : draw it.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, figs 1-6.

    Examples
    --------
    A third of a turn on the cone of half-angle 0.3 about ``a = (0, 0.6, 0.8)``, with a decaying ``G`` (any object
    with the fields ``G`` and ``n`` will do, such as a result of :func:`rigidbody.euler_poinsot.averaged`):

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> a, e1 = np.array([0.0, 0.6, 0.8]), np.array([1.0, 0.0, 0.0])
    >>> e2 = np.cross(a, e1)
    >>> t, delta = np.linspace(0.0, 2.0, 40), 0.3
    >>> n = np.cos(delta) * a[:, None] + np.sin(delta) * (np.cos(t) * e1[:, None] + np.sin(t) * e2[:, None])
    >>> sol = SimpleNamespace(G=np.exp(-0.1 * t), n=n)
    >>> from rigidbody.plotting import hodograph
    >>> h = hodograph(sol)
    >>> h.shape, np.allclose(np.linalg.norm(h, axis=0), sol.G, rtol=1e-15, atol=0)
    ((3, 40), True)
    """
    return np.asarray(sol.G) * np.asarray(sol.n)


def spiral_axis(sol: Any) -> np.ndarray:
    r"""Direction of the spiral's axis: the axis of the cone that best fits the directions :math:`\mathbf n`.

    The hodograph :math:`G\mathbf n` lies on a cone of half-angle :math:`\delta` about its axis when
    :math:`\mathbf a\cdot\mathbf n` is constant. The axis :math:`\mathbf a` is taken as the eigenvector of the
    smallest eigenvalue of the covariance of :math:`\mathbf n`, the samples weighted by the arc length
    they cover (so a dense output grid does not pull the fit towards a slow part of the path). It is exact
    for a circular cone however few of its turns are sampled: in the orbit-averaged limit
    (:math:`\delta` constant) it is :math:`x_3`; with :math:`\nu` kept it wobbles by :math:`O(\varepsilon)`.
    Oriented so that the mean of :math:`\mathbf a\cdot\mathbf n` is positive; :math:`x_3` if the path is
    too short to define a cone.

    Parameters
    ----------
    sol : Solution
        A run with the field ``n`` (shape (3, n)).

    Returns
    -------
    numpy.ndarray, shape (3,)

    See Also
    --------
    hodograph_projection, hodograph_side_view : views along and beside the axis.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, figs 3 and 6.

    Examples
    --------
    Only a third of a turn on the cone of half-angle 0.3 about ``a = (0, 0.6, 0.8)``, with a decaying ``G`` (any object
    with the fields ``G`` and ``n`` will do, such as a result of :func:`rigidbody.euler_poinsot.averaged`):

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> a, e1 = np.array([0.0, 0.6, 0.8]), np.array([1.0, 0.0, 0.0])
    >>> e2 = np.cross(a, e1)
    >>> t, delta = np.linspace(0.0, 2.0, 40), 0.3
    >>> n = np.cos(delta) * a[:, None] + np.sin(delta) * (np.cos(t) * e1[:, None] + np.sin(t) * e2[:, None])
    >>> sol = SimpleNamespace(G=np.exp(-0.1 * t), n=n)
    >>> from rigidbody.plotting import spiral_axis
    >>> print(np.round(spiral_axis(sol), 9) + 0.0)  # + 0.0: no -0.0
    [0.  0.6 0.8]
    """
    n = np.asarray(sol.n, dtype=float)
    if n.ndim != 2 or n.shape[1] < 3:
        return np.array([0.0, 0.0, 1.0])
    seg = np.linalg.norm(np.diff(n, axis=1), axis=0)
    w = np.zeros(n.shape[1])
    w[:-1] += seg / 2
    w[1:] += seg / 2
    if w.sum() <= 0:
        return np.array([0.0, 0.0, 1.0])
    mean = (n * w).sum(axis=1) / w.sum()
    d = n - mean[:, None]
    cov = (d * w) @ d.T / w.sum()
    vals, vecs = np.linalg.eigh(cov)
    if vals[1] <= 1e-12 * max(vals[2], 1e-300):  # the samples (nearly) lie on one line: no plane, no axis
        return np.array([0.0, 0.0, 1.0])
    a = vecs[:, 0]
    return a if a @ mean >= 0 else -a


def hodograph_3d(sol: Any, ax: Any = None, **kw: Any) -> Any:
    """Draw the hodograph in the axes :math:`Ox_1x_2x_3` (paper's figs 1 and 4); returns the line.

    The start is marked by a dot; the axes get equal scales (:func:`equal_3d`) so that the cone on which the
    hodograph lies is not distorted.

    Parameters
    ----------
    sol : Solution
        A run with the fields ``G`` and ``n``.
    ax : Axes3D, optional
    **kw
        Line style.

    Returns
    -------
    matplotlib.lines.Line2D

    See Also
    --------
    hodograph : the points drawn.
    hodograph_projection, hodograph_side_view : the 2-D views.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, figs 1 and 4.

    Examples
    --------
    A third of a turn on the cone of half-angle 0.3 about ``a = (0, 0.6, 0.8)``, with a decaying ``G`` (any object
    with the fields ``G`` and ``n`` will do, such as a result of :func:`rigidbody.euler_poinsot.averaged`):

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> a, e1 = np.array([0.0, 0.6, 0.8]), np.array([1.0, 0.0, 0.0])
    >>> e2 = np.cross(a, e1)
    >>> t, delta = np.linspace(0.0, 2.0, 40), 0.3
    >>> n = np.cos(delta) * a[:, None] + np.sin(delta) * (np.cos(t) * e1[:, None] + np.sin(t) * e2[:, None])
    >>> sol = SimpleNamespace(G=np.exp(-0.1 * t), n=n)
    >>> from rigidbody.plotting import hodograph, hodograph_3d
    >>> line = hodograph_3d(sol)
    >>> np.allclose(line.get_data_3d()[2], hodograph(sol)[2], rtol=0, atol=0)
    True
    """
    ax = get_ax(ax, projection="3d")
    h = hodograph(sol)
    (line,) = ax.plot(h[0], h[1], h[2], **kw)
    ax.scatter([h[0, 0]], [h[1, 0]], [h[2, 0]], color=line.get_color(), s=12)
    ax.set_xlabel("$x_1$")
    ax.set_ylabel("$x_2$")
    ax.set_zlabel("$x_3$")
    equal_3d(ax)
    return line


def equal_3d(ax: Any) -> Any:
    """Give a 3-D axes equal scales on its three axes (a box around everything drawn so far).

    Parameters
    ----------
    ax : Axes3D

    Returns
    -------
    Axes3D

    See Also
    --------
    hodograph_3d : calls it.

    Examples
    --------
    A segment from the origin to ``(2, 1, 1)``: a box of proportions 2 : 1 : 1:

    >>> import numpy as np
    >>> from rigidbody.plotting import equal_3d, get_ax
    >>> ax = get_ax(projection="3d")
    >>> lines = ax.plot([0.0, 2.0], [0.0, 1.0], [0.0, 1.0])
    >>> aspect = np.asarray(equal_3d(ax).get_box_aspect())
    >>> print(np.round(aspect / aspect[0], 12))
    [1.  0.5 0.5]
    """
    pts = [np.asarray(line.get_data_3d(), dtype=float) for line in ax.lines]
    if not pts:
        return ax
    p = np.concatenate(pts, axis=1)
    lo, hi = np.nanmin(p, axis=1), np.nanmax(p, axis=1)
    span = np.maximum(hi - lo, 1e-12)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(tuple(span / span.max()))
    return ax


def plane_basis(normal: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Unit ``normal`` and an in-plane basis ``(e1, e2)``: ``e1`` is :math:`x_1` projected on the plane (or
    :math:`x_2` when the normal is close to :math:`x_1`), ``e2 = normal x e1``.

    Parameters
    ----------
    normal : array_like, shape (3,)
        Any finite nonzero vector.

    Returns
    -------
    (d, e1, e2) : numpy.ndarray
        A right-handed orthonormal triple, ``d`` along ``normal``.

    See Also
    --------
    hodograph_projection : projects on the plane.

    Examples
    --------
    >>> from rigidbody.plotting import plane_basis
    >>> plane_basis([0.0, 0.0, 2.0])
    (array([0., 0., 1.]), array([1., 0., 0.]), array([0., 1., 0.]))
    """
    d = np.asarray(normal, dtype=float)
    if d.shape != (3,) or not np.all(np.isfinite(d)) or np.linalg.norm(d) == 0:
        raise ValueError(f"normal must be a finite nonzero 3-vector, got {normal!r}")
    d = d / np.linalg.norm(d)
    ref = np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = ref - d * (ref @ d)
    e1 /= np.linalg.norm(e1)
    return d, e1, np.cross(d, e1)


def hodograph_projection(sol: Any, ax: Any = None, normal: Any = (0.0, 0.0, 1.0), **kw: Any) -> Any:
    """Project the hodograph on the plane orthogonal to ``normal`` (``(0, 0, 1)``: the plane :math:`Ox_1x_2`,
    fig. 2; :func:`spiral_axis`: the view along the spiral, fig. 3). Returns the line.

    The in-plane coordinates are those of :func:`plane_basis`; the start is marked by a dot.

    Parameters
    ----------
    sol : Solution
        A run with the fields ``G`` and ``n``.
    ax : matplotlib.axes.Axes, optional
    normal : array_like, shape (3,)
        The normal of the plane of projection.
    **kw
        Line style.

    Returns
    -------
    matplotlib.lines.Line2D

    See Also
    --------
    hodograph_3d : the 3-D view.
    spiral_axis : the normal of the view along the spiral.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, figs 2-3 and 5-6.

    Examples
    --------
    A third of a turn on the cone of half-angle 0.3 about ``a = (0, 0.6, 0.8)``, with a decaying ``G`` (any object
    with the fields ``G`` and ``n`` will do, such as a result of :func:`rigidbody.euler_poinsot.averaged`):

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> a, e1 = np.array([0.0, 0.6, 0.8]), np.array([1.0, 0.0, 0.0])
    >>> e2 = np.cross(a, e1)
    >>> t, delta = np.linspace(0.0, 2.0, 40), 0.3
    >>> n = np.cos(delta) * a[:, None] + np.sin(delta) * (np.cos(t) * e1[:, None] + np.sin(t) * e2[:, None])
    >>> sol = SimpleNamespace(G=np.exp(-0.1 * t), n=n)
    >>> from rigidbody.plotting import hodograph, hodograph_projection
    >>> line = hodograph_projection(sol)  # on the plane Ox1x2: the coordinates G n1, G n2
    >>> np.allclose(line.get_xdata(), hodograph(sol)[0], rtol=0, atol=0), line.axes.get_xlabel()
    (True, '$x_1$')
    """
    ax = get_ax(ax)
    d, e1, e2 = plane_basis(normal)
    h = hodograph(sol)
    (line,) = ax.plot(e1 @ h, e2 @ h, **kw)
    ax.plot([e1 @ h[:, 0]], [e2 @ h[:, 0]], "o", color=line.get_color(), ms=3)
    ax.set_aspect("equal", adjustable="datalim")
    if np.allclose(d, [0, 0, 1]):
        ax.set_xlabel("$x_1$")
        ax.set_ylabel("$x_2$")
    else:
        ax.set_xlabel("along $x_1$ projected")
        ax.set_ylabel("normal $\\times$ that")
    return line


def hodograph_side_view(sol: Any, ax: Any = None, axis: Any = (0.0, 0.0, 1.0), **kw: Any) -> Any:
    """The hodograph seen from the side of ``axis``: distance from the axis against the height along it.

    A hodograph on a cone about ``axis`` (constant angle :math:`\\delta` to it) is a straight line through
    the origin here, so a bent spiral axis shows as a curved line. Returns the line.

    Parameters
    ----------
    sol : Solution
        A run with the fields ``G`` and ``n``.
    ax : matplotlib.axes.Axes, optional
    axis : array_like, shape (3,)
        The axis (e.g. :func:`spiral_axis`).
    **kw
        Line style.

    Returns
    -------
    matplotlib.lines.Line2D

    See Also
    --------
    hodograph_projection : the view along the axis.
    spiral_axis : the axis of the best-fitting cone.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, figs 3 and 6.

    Examples
    --------
    On the cone about its axis the slope distance/height is :math:`\\tan\\delta` everywhere:

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> a, e1 = np.array([0.0, 0.6, 0.8]), np.array([1.0, 0.0, 0.0])
    >>> e2 = np.cross(a, e1)
    >>> t, delta = np.linspace(0.0, 2.0, 40), 0.3
    >>> n = np.cos(delta) * a[:, None] + np.sin(delta) * (np.cos(t) * e1[:, None] + np.sin(t) * e2[:, None])
    >>> sol = SimpleNamespace(G=np.exp(-0.1 * t), n=n)
    >>> from rigidbody.plotting import hodograph_side_view
    >>> line = hodograph_side_view(sol, axis=a)
    >>> np.allclose(line.get_xdata() / line.get_ydata(), np.tan(delta), rtol=1e-12, atol=0)
    True
    """
    ax = get_ax(ax)
    d, _, _ = plane_basis(axis)
    h = hodograph(sol)
    along = d @ h
    across = np.linalg.norm(h - np.outer(d, along), axis=0)
    (line,) = ax.plot(across, along, **kw)
    ax.set_xlabel("distance from the axis")
    ax.set_ylabel("height along the axis")
    return line


def slow_variables(sol: Any, axes: Any = None, label: str | None = None, **kw: Any) -> Any:
    """Plot G, T, k², δ, λ against τ on five axes (created when ``axes`` is None); returns the axes. A run of a
    :class:`~rigidbody.euler_poinsot.SymmetricBody` (``k2`` is 0 there) shows its nutation angle θ instead of k².

    Parameters
    ----------
    sol : Solution
        A run of :func:`rigidbody.euler_poinsot.averaged` (or of its ``simulate``).
    axes : sequence of five Axes, optional
    label : str, optional
        Legend label of the run.
    **kw
        Line style.

    Returns
    -------
    sequence of Axes

    See Also
    --------
    rigidbody.plotting.plot_solution : ``sol.plot()``, which calls it.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (8)-(9).

    Examples
    --------
    Case 2 of the paper, orbit-averaged (:math:`\\varepsilon = 0`):

    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> body, I = ep.Body(3.2, 2.6, 1.67), np.diag([0.919, 5.228, 1.666])
    >>> sol = ep.averaged(body, I, 0.0, G0=1.0, k2_0=0.99, tau_span=(0.0, 6.0), tau_eval=np.linspace(0.0, 6.0, 61))
    >>> import matplotlib.pyplot as plt
    >>> from rigidbody.plotting import slow_variables
    >>> axes = slow_variables(sol, plt.subplots(5, 1, sharex=True)[1])  # on given Axes (else a new figure)
    >>> print(*(ax.get_ylabel() for ax in axes))
    $G$ $T$ $k^2$ $\\delta$ $\\lambda$
    >>> np.array_equal(axes[0].lines[0].get_ydata(), sol.G)
    True
    """
    new = axes is None
    if new:
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(5, 1, figsize=(6.0, 9.0), sharex=True)
    third = ("theta", "$\\theta$") if "theta" in getattr(sol, "fields", ()) else ("k2", "$k^2$")
    names = [("G", "$G$"), ("T", "$T$"), third, ("delta", "$\\delta$"), ("lam", "$\\lambda$")]
    for ax, (f, lab) in zip(axes, names):
        ax.plot(sol.tau, getattr(sol, f), label=label, **kw)
        ax.set_ylabel(lab)
    axes[-1].set_xlabel("$\\tau$")
    if label is not None:
        axes[0].legend(fontsize=8)
    if new:
        axes[0].figure.tight_layout()
    return axes


def _body_direction(sol: Any) -> np.ndarray:
    """Unit vector of G in body axes, shape (3, n), from a full run (either formulation)."""
    if "g" in sol.fields:
        g = np.asarray(sol.g)
        return g / np.linalg.norm(g, axis=0)
    th, ph = np.asarray(sol.theta), np.asarray(sol.phi)
    return np.array([np.sin(th) * np.sin(ph), np.sin(th) * np.cos(ph), np.cos(th)])


def _envelope(body: Any, sol: Any, n: int = 64) -> tuple[np.ndarray, np.ndarray]:
    """Range (min, max) of g1/G and g3/G over the Euler--Poinsot motion at each output of an averaged run."""
    from ..euler_poinsot import EulerPoinsot

    lo = np.full((2, np.size(sol.tau)), np.nan)
    hi = np.full_like(lo, np.nan)
    kinds = np.broadcast_to(np.asarray(sol.kind), np.shape(sol.tau)) if "kind" in sol.fields else ["max"] * lo.shape[1]
    sigmas = np.broadcast_to(np.asarray(sol.sigma), np.shape(sol.tau)) if "sigma" in sol.fields else [1] * lo.shape[1]
    for i, (G, k2, kind, sig) in enumerate(zip(sol.G, sol.k2, kinds, sigmas)):
        if not (0.0 <= k2 < 1.0):
            continue
        m = EulerPoinsot(body, float(G), float(k2), str(kind), int(sig))
        g = m.g(np.arange(n) * (m.period / n))[[0, 2]] / G
        lo[:, i], hi[:, i] = g.min(axis=1), g.max(axis=1)
    return lo, hi


def separatrix_passage(body: Any, full: Any, averaged: Any = None, axes: Any = None) -> Any:
    r"""Draw a passage through the separatrix: energy, body components of :math:`\mathbf G`, and the polhode.

    Three panels: (a) :math:`2TA_2/G^2` against :math:`\tau` (1 on the separatrix, :math:`A_2/A_3` for a pure
    spin about the minor axis, :math:`A_2/A_1` about the major axis); (b) :math:`g_1/G` and :math:`g_3/G` of
    the full motion, with the range they sweep over the Euler--Poinsot motion of the averaged run;
    (c) the path of :math:`\mathbf g/G` seen along the intermediate axis :math:`z_2`, with the separatrix (the
    planes :math:`g_3 = \pm g_1\sqrt{A_3(A_1-A_2)/(A_1(A_2-A_3))}`).

    Parameters
    ----------
    body : Body
    full : Solution
        A run of :func:`~rigidbody.euler_poinsot.simulate` (either formulation).
    averaged : Solution, optional
        A run of :func:`~rigidbody.euler_poinsot.averaged` over the same span.
    axes : sequence of three Axes, optional
        Created (one figure, three panels) when None.

    Returns
    -------
    numpy.ndarray
        The three axes.

    See Also
    --------
    rigidbody.euler_poinsot.separatrix_crossing : the crossing of the averaged motion.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, section 1 (the Euler--Poinsot motion and its separatrix).

    Examples
    --------
    A minor-axis spin losing energy at constant :math:`G` (the gallery's ``separatrix_passage``, shortened); panel
    (a) starts at :math:`2T_0A_2/G_0^2` and carries the levels :math:`A_2/A_3`, 1 and :math:`A_2/A_1`:

    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> from rigidbody.plotting import separatrix_passage
    >>> body = ep.Body(A1=3.2, A2=2.6, A3=1.67)
    >>> def dissipation(omega, C, nu):
    ...     g = omega * body.A
    ...     return -3.0 * (omega - (omega * g).sum(-1, keepdims=True) * g / (g * g).sum(-1, keepdims=True))
    >>> full = ep.simulate(body, dissipation, 0.05, kind="min", k2_0=0.05, delta0=1.0, lam0=0.3, tau_span=(0.0, 0.5),
    ...                    tau_eval=np.linspace(0.0, 0.5, 201), k2_max=None)
    >>> axes = separatrix_passage(body, full)
    >>> levels = [line.get_ydata()[0] for line in axes[0].lines]
    >>> print(*(f"{x:.9f}" for x in levels))
    1.460636079 1.556886228 1.000000000 0.812500000
    >>> print(f"{2 * full.T[0] * body.A2 / full.G[0]**2:.9f} {body.A2 / body.A3:.9f} {body.A2 / body.A1:.9f}")
    1.460636079 1.556886228 0.812500000
    """
    if axes is None:
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(1, 3, figsize=(13.0, 4.0), gridspec_kw={"width_ratios": [1.2, 1.2, 1.0]})
    ax_e, ax_g, ax_p = axes
    A1, A2, A3 = body.A1, body.A2, body.A3
    e_full = 2.0 * np.asarray(full.T) * A2 / np.asarray(full.G) ** 2
    ax_e.plot(full.tau, e_full, lw=0.6, color="C0", label="full")
    if averaged is not None:
        ax_e.plot(averaged.tau, 2.0 * np.asarray(averaged.T) * A2 / np.asarray(averaged.G) ** 2, "--", lw=2,
                  color="C3", label="averaged")
    for level, text in ((A2 / A3, "spin about $z_3$ (minor axis)"), (1.0, "separatrix"),
                        (A2 / A1, "spin about $z_1$ (major axis)")):
        ax_e.axhline(level, color="0.5", lw=0.8, ls=":")
        ax_e.annotate(text, (ax_e.get_xlim()[0], level), xytext=(3, 2), textcoords="offset points", fontsize=7,
                      color="0.35")
    ax_e.set_xlabel("$\\tau$")
    ax_e.set_ylabel("$2TA_2/G^2$")
    ax_e.legend(fontsize=8, loc="upper right")
    u = _body_direction(full)
    ax_g.plot(full.tau, u[2], lw=0.5, color="C0", label="$g_3/G$ (full)")
    ax_g.plot(full.tau, u[0], lw=0.5, color="C2", label="$g_1/G$ (full)")
    if averaged is not None:
        lo, hi = _envelope(body, averaged)
        for j, c in ((1, "C0"), (0, "C2")):
            ax_g.fill_between(averaged.tau, lo[j], hi[j], color=c, alpha=0.15, lw=0)
            ax_g.plot(averaged.tau, lo[j], color=c, lw=1.2, ls="--")
            ax_g.plot(averaged.tau, hi[j], color=c, lw=1.2, ls="--")
    ax_g.set_xlabel("$\\tau$")
    ax_g.set_ylabel("body components of $\\mathbf{G}/G$")
    ax_g.set_ylim(-1.05, 1.05)
    ax_g.legend(fontsize=8, loc="lower left")
    th = np.linspace(0.0, 2.0 * np.pi, 361)
    ax_p.plot(np.cos(th), np.sin(th), color="0.6", lw=0.8)
    c = np.sqrt(A3 * (A1 - A2) / (A1 * (A2 - A3)))
    x = 1.0 / np.sqrt(1.0 + c * c)
    for sgn in (1.0, -1.0):
        ax_p.plot([-x, x], [-sgn * c * x, sgn * c * x], color="k", lw=1.0, ls="--")
    ax_p.plot(u[0], u[2], lw=0.4, color="C0")
    ax_p.plot([u[0, 0]], [u[2, 0]], "o", color="C1", ms=5, label="start")
    ax_p.plot([u[0, -1]], [u[2, -1]], "s", color="C3", ms=5, label="end")
    ax_p.set_aspect("equal")
    ax_p.set_xlabel("$g_1/G$ (major axis)")
    ax_p.set_ylabel("$g_3/G$ (minor axis)")
    ax_p.legend(fontsize=8, loc="lower right")
    return axes

