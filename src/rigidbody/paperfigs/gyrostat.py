"""Stepanov (1968): the paper's figure (the dumbbell), and stability maps and kappa0(theta0) beyond it.

Choices the paper leaves open (stated here and in :doc:`/gyrostat`):

- nondimensional units M = mu = R0 = 1; bodies with principal moments proportional to the six orderings
  of (1.2, 1.0, 0.8), scaled so that l = sqrt(Abar/M) = l/R;
- maps in the plane (theta0, u = k2 / (omega0 Abar)) on a 301 x 301 grid, theta0 in (-1.5, 1.5),
  u in (-6, 6), omega0 > 0;
- kappa0 curves for l/R = 0.05, 0.1, 0.2, 0.3 with the ordering A1 : A2 : A3 = 1.2 : 1.0 : 0.8;
- the symmetric family (3.2): verdicts over theta0 in (-pi, pi) and A3/A1 in (0.05, 2) at l/R = 0.1, with
  the paper's boundary A3 = A1 ((3.4)) and the line 3 A3 = 4 A1 beyond which its instability claim fails;
- the dumbbell: two equal balls at arm a = 0.3 R0 from G (A1 = A2 = M a^2, A3 = 0.01 A1 for the rod),
  theta0 = pi/4, the symmetric family (3.2)-(3.3), drawn to scale.
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np

from rigidbody import gyrostat
from rigidbody.paperfigs import register_figures

__all__ = [
    "body",
    "dumbbell_data",
    "fig1_dumbbell",
    "kappa0",
    "kappa_data",
    "map_data",
    "orderings",
    "stability_maps",
    "stability_maps_lr01",
    "stability_maps_lr02",
    "symmetric_map",
    "symmetric_map_data",
]

BASE = (1.2, 1.0, 0.8)
THETA = np.linspace(-1.5, 1.5, 301)
U = np.linspace(-6.0, 6.0, 301)
L_OVER_R_MAPS = (0.1, 0.2)
L_OVER_R_KAPPA = (0.05, 0.1, 0.2, 0.3)
ARM = 0.3
THETA_DUMBBELL = math.pi / 4


def body(l_over_R: float, ratios: tuple[float, float, float] = BASE) -> gyrostat.Satellite:
    """Nondimensional body with moments proportional to ``ratios`` and sqrt(Abar/M) = l_over_R.

    Parameters
    ----------
    l_over_R : float
        Size of the body over the orbit radius (``M = mu = R0 = 1``).
    ratios : (float, float, float)
        Proportions of ``A1, A2, A3``.

    Returns
    -------
    rigidbody.gyrostat.Satellite

    See Also
    --------
    orderings : the proportions of the maps.
    map_data : a map of such a body.

    Examples
    --------
    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> sat = figs.body(0.1)
    >>> print(f"{sat.l:.12f} {sat.A1 / sat.A3:.12f}")
    0.100000000000 1.500000000000
    """
    s = l_over_R**2 * 3 / sum(ratios)
    return gyrostat.Satellite(M=1.0, A1=ratios[0] * s, A2=ratios[1] * s, A3=ratios[2] * s)


def orderings() -> list[tuple[float, float, float]]:
    """The six orderings of BASE, A1 > A2 > A3 first.

    Returns
    -------
    list of (float, float, float)

    See Also
    --------
    stability_maps : one panel per ordering.

    Examples
    --------
    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> figs.orderings()
    [(1.2, 1.0, 0.8), (1.2, 0.8, 1.0), (1.0, 1.2, 0.8), (1.0, 0.8, 1.2), (0.8, 1.2, 1.0), (0.8, 1.0, 1.2)]
    """
    return sorted({(a, b, c) for a, b, c in itertools.permutations(BASE)}, reverse=True)


def map_data(l_over_R: float, ratios: tuple[float, float, float]) -> dict:
    """Arrays behind one map panel: codes on (THETA x U) and the boundary curves u(theta0).

    Parameters
    ----------
    l_over_R : float
        Size of the body over the orbit radius.
    ratios : (float, float, float)
        Proportions of ``A1, A2, A3``.

    Returns
    -------
    dict
        ``sat`` (the body), ``code`` (the verdicts), ``b`` (the boundaries of
        :func:`rigidbody.gyrostat.normalized_stability_map`), ``map`` (the :class:`~rigidbody.gyrostat.StabilityMap`).

    See Also
    --------
    stability_maps : the figure of the six panels.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5).

    Examples
    --------
    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> d = figs.map_data(0.1, (1.2, 1.0, 0.8))
    >>> d["code"].shape, sorted(d)
    ((301, 301), ['b', 'code', 'map', 'sat'])
    """
    sat = body(l_over_R, ratios)
    mp, b = gyrostat.normalized_stability_map(sat, 1.0, THETA, U)
    return {"sat": sat, "code": mp.code, "b": b, "map": mp}


def kappa_data() -> dict[float, np.ndarray]:
    """kappa0(theta0) on THETA for each l/R (k2 = 0; kappa0 does not depend on k2).

    Returns
    -------
    dict of float to numpy.ndarray

    See Also
    --------
    kappa0 : the figure.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 2 (kappa0 is of order l^2/R^2 and maximal
    at theta0 = pi/4).

    Examples
    --------
    The maximum sits at the grid point next to :math:`\\pi/4` for the smallest body:

    >>> import numpy as np
    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> kd = figs.kappa_data()
    >>> sorted(kd), float(figs.THETA[np.argmax(kd[0.05])])
    ([0.05, 0.1, 0.2, 0.3], 0.79)
    """
    out = {}
    for lR in L_OVER_R_KAPPA:
        sat = body(lR)
        out[lR] = gyrostat.stability_map(sat, 1.0, THETA, k2=0.0).kappa0
    return out


SYM_THETA = np.linspace(-3.1, 3.1, 311)
SYM_RATIO = np.linspace(0.05, 2.0, 196)
SYM_L_OVER_R = 0.1


def symmetric_map_data() -> gyrostat.SymmetricStabilityMap:
    """Verdicts of (3.2) on SYM_THETA x SYM_RATIO (A3/A1), l/R = SYM_L_OVER_R (A1 fixed, A3 varied).

    Returns
    -------
    rigidbody.gyrostat.SymmetricStabilityMap

    See Also
    --------
    symmetric_map : the figure.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (3.4).

    Examples
    --------
    Near :math:`\\theta_0 = \\pi/4`: stable for :math:`A_3/A_1 = 0.5`, unstable for 1.2, undecided beyond 4/3:

    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> sm = figs.symmetric_map_data()
    >>> print(round(float(figs.SYM_THETA[194]), 2), figs.SYM_RATIO[[45, 115, 145]], sm.verdict[194, [45, 115, 145]])
    0.78 [0.5 1.2 1.5] ['stable' 'unstable' 'undecided']
    """
    A1 = SYM_L_OVER_R**2
    sat = gyrostat.Satellite(M=1.0, A1=A1, A2=A1, A3=A1)
    return gyrostat.symmetric_stability_map(sat, 1.0, SYM_THETA, A3=SYM_RATIO * A1)


def dumbbell_data() -> tuple[gyrostat.Satellite, gyrostat.SymmetricMotion]:
    """The dumbbell of the paper's figure: the satellite and its stationary motion (3.2)-(3.3).

    Returns
    -------
    (rigidbody.gyrostat.Satellite, rigidbody.gyrostat.SymmetricMotion)

    See Also
    --------
    fig1_dumbbell : the figure.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 5 and its figure.

    Examples
    --------
    By (3.3) at :math:`\\theta_0 = \\pi/4`: :math:`\\tan\\kappa_0 = \\frac32(A_1 - A_3)/(1 + \\frac34(A_1 - A_3))`
    (``M = mu = R0 = 1``):

    >>> import math
    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> sat, ms = figs.dumbbell_data()
    >>> d = sat.A1 - sat.A3
    >>> print(f"{ms.kappa0:.12f} {math.atan(1.5 * d / (1 + 0.75 * d)):.12f}")
    0.124628982946 0.124628982946
    """
    A1 = 1.0 * ARM**2
    sat = gyrostat.Satellite(M=1.0, A1=A1, A2=A1, A3=0.01 * A1)
    return sat, gyrostat.symmetric_stationary_motion(sat, 1.0, THETA_DUMBBELL)


def _label(r: tuple[float, float, float]) -> str:
    names = sorted(zip(r, ("A1", "A2", "A3")), reverse=True)
    return " > ".join(n for _, n in names)


def stability_maps(l_over_R: float, maps: dict[tuple[float, float, float], Any] | None = None) -> Any:
    """Verdicts of (2.3) in the plane (theta0, k2 / (omega0 Abar)) for the six orderings of the moments.

    Exact boundaries s2 = 0, s3 = 0, s1 = 0 in black, the restricted problem's in blue
    (:func:`rigidbody.plotting.normalized_map_plot`).

    Parameters
    ----------
    l_over_R : float
        Size of the body over the orbit radius, ``sqrt(Abar / M) / R0``.
    maps : dict, optional
        ``{ratios: (StabilityMap, boundaries)}`` for the six :func:`orderings`, each the result of
        :func:`rigidbody.gyrostat.normalized_stability_map` for ``body(l_over_R, ratios)`` with ``R0 = 1`` on
        :data:`THETA` x :data:`U` (default: computed here).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    map_data : one panel's data.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5) and the restricted conditions after it.

    Examples
    --------
    One panel per ordering of the principal moments, each the map of :func:`map_data` (the figure itself takes
    about a second: the gallery and ``python -m rigidbody figures`` draw it):

    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> panels = [figs.map_data(0.1, r)["code"] for r in figs.orderings()]
    >>> len(panels), panels[0].shape
    (6, (301, 301))
    >>> fig = figs.stability_maps(0.1)  # doctest: +SKIP
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import gyrostat as pg

    fig, axes = plt.subplots(2, 3, figsize=(13, 8), sharex=True, sharey=True)
    for ax, r in zip(axes.ravel(), orderings()):
        data = None if maps is None else maps[r]
        pg.normalized_map_plot(body(l_over_R, r), 1.0, THETA, U, ax, legend=(ax is axes[0, 0]), data=data)
        ax.set_title(_label(r), fontsize=10)
    for ax in axes.ravel():
        ax.label_outer()
    fig.suptitle(f"Stability of the motions (2.3), l/R = {l_over_R}: exact (black) vs restricted (blue) boundaries")
    fig.tight_layout()
    return fig


def stability_maps_lr01(maps: dict[tuple[float, float, float], Any] | None = None) -> Any:
    """Beyond the paper: :func:`stability_maps` for l/R = 0.1.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    stability_maps : the same for any l/R.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5).

    Examples
    --------
    Its panels are the maps of :func:`map_data` for a body of size ``l/R = 0.1`` (the figure itself,
    ``stability_maps_lr01()``, is drawn by the gallery and ``python -m rigidbody figures``):

    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> figs.L_OVER_R_MAPS[0], figs.map_data(0.1, figs.orderings()[0])["sat"].l
    (0.1, 0.1)
    >>> fig = figs.stability_maps_lr01()  # doctest: +SKIP
    """
    return stability_maps(L_OVER_R_MAPS[0], maps)


def stability_maps_lr02(maps: dict[tuple[float, float, float], Any] | None = None) -> Any:
    """Beyond the paper: :func:`stability_maps` for l/R = 0.2.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    stability_maps : the same for any l/R.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5).

    Examples
    --------
    Its panels are the maps of :func:`map_data` for a body of size ``l/R = 0.2`` (the figure itself,
    ``stability_maps_lr02()``, is drawn by the gallery and ``python -m rigidbody figures``):

    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> figs.L_OVER_R_MAPS[1], figs.map_data(0.2, figs.orderings()[0])["sat"].l
    (0.2, 0.2)
    >>> fig = figs.stability_maps_lr02()  # doctest: +SKIP
    """
    return stability_maps(L_OVER_R_MAPS[1], maps)


def kappa0(data: dict[float, np.ndarray] | None = None) -> Any:
    """Beyond the paper: the latitude kappa0(theta0) of the orbit (2.4) for several l/R, and scaled by
    (l/R)^2 (the curves collapse, extremal near theta0 = +-pi/4).

    ``data``: ``{l/R: kappa0 on THETA}`` (default :func:`kappa_data`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    kappa_data : the curves.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.4) and section 2.

    Examples
    --------
    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> fig = figs.kappa0()
    >>> [len(ax.get_legend().get_texts()) for ax in fig.axes]  # one curve per l/R
    [4, 4]
    """
    import matplotlib.pyplot as plt

    kd = kappa_data() if data is None else data
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for lR, kap in kd.items():
        ax1.plot(THETA, np.degrees(kap), label=f"l/R = {lR}")
        ax2.plot(THETA, kap / lR**2, label=f"l/R = {lR}")
        i = int(np.argmax(kap))
        ax2.plot(THETA[i], kap[i] / lR**2, "k.", ms=5)
    for ax in (ax1, ax2):
        ax.axvline(math.pi / 4, color="0.5", ls=":", lw=0.8)
        ax.axvline(-math.pi / 4, color="0.5", ls=":", lw=0.8)
        ax.set_xlabel("θ0 (rad)")
        ax.legend(fontsize=8)
    ax1.set_ylabel("κ0 (deg)")
    ax2.set_ylabel("κ0 / (l/R)²")
    ax2.set_title("κ0 = O(l²/R²), extremal near θ0 = ±π/4 (dots: maxima)", fontsize=10)
    ax1.set_title(f"latitude of the orbit, A1:A2:A3 = {BASE[0]}:{BASE[1]}:{BASE[2]}", fontsize=10)
    fig.tight_layout()
    return fig


def symmetric_map(sm: gyrostat.SymmetricStabilityMap | None = None) -> Any:
    """Beyond the paper: verdicts of the symmetric family (3.2) by the full second variation over
    (theta0, A3/A1), with the paper's boundary A3 = A1 of (3.4) and the line 3 A3 = 4 A1.

    ``sm``: the map over SYM_THETA x SYM_RATIO (default :func:`symmetric_map_data`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    symmetric_map_data : the verdicts.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (3.4).

    Examples
    --------
    Its verdicts are those of :func:`symmetric_map_data` (drawn by the gallery and
    ``python -m rigidbody figures``):

    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> figs.symmetric_map_data().code.shape == (figs.SYM_THETA.size, figs.SYM_RATIO.size)
    True
    >>> fig = figs.symmetric_map()  # doctest: +SKIP
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import gyrostat as pg

    sm = symmetric_map_data() if sm is None else sm
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    pg.stability_map_plot(SYM_THETA, SYM_RATIO, sm.code, ax,
                          boundaries={"A3 = A1 ((3.4) changes sign)": (SYM_THETA, np.ones_like(SYM_THETA)),
                                      "3 A3 = 4 A1": (SYM_THETA, np.full_like(SYM_THETA, 4 / 3))})
    ax.set_xlabel("θ0 (rad)")
    ax.set_ylabel("A3 / A1")
    ax.set_title(f"Symmetric gyrostat (3.2), l/R ≈ {SYM_L_OVER_R}: full second variation", fontsize=10)
    fig.tight_layout()
    return fig


def fig1_dumbbell(sat: gyrostat.Satellite | None = None, motion: gyrostat.SymmetricMotion | None = None) -> Any:
    """The paper's figure: the spinning dumbbell whose circular orbit plane misses the attracting centre,
    drawn to scale (:func:`rigidbody.plotting.dumbbell_side_view`), with kappa0 and the stability verdict.

    ``sat`` and ``motion``: a dumbbell (two equal balls on a light rod, ``A1 = A2 = M arm^2``) and its
    stationary motion (3.2)-(3.3), both or neither (default :func:`dumbbell_data`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    dumbbell_data : the dumbbell and its motion.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 5 and its figure.

    Examples
    --------
    :math:`\\kappa_0 = 0.12463` rad (see :func:`dumbbell_data`) and, the dumbbell being prolate
    (:math:`A_1 > A_3`), stable by (3.4):

    >>> from rigidbody.paperfigs import gyrostat as figs
    >>> figs.fig1_dumbbell().axes[0].get_title()
    'Spinning dumbbell, arm = 0.3 R0, θ0 = 45°: κ0 = 7.14°, verdict: stable'
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting import gyrostat as pg

    if (sat is None) != (motion is None):
        raise ValueError("give both sat and motion (the dumbbell and its stationary motion), or neither")
    sat, ms = dumbbell_data() if sat is None or motion is None else (sat, motion)
    st = gyrostat.stability(sat, ms)
    arm = math.sqrt(sat.A1 / sat.M)  # two equal balls at +-arm from G: A1 = M arm^2
    fig, ax = plt.subplots(figsize=(8, 5.5))
    pg.dumbbell_side_view(ms.R0, ms.kappa0, ms.theta0, arm, ax, elevation_deg=8.0)
    ax.set_title(f"Spinning dumbbell, arm = {arm / ms.R0:.3g} R0, θ0 = {math.degrees(ms.theta0):.4g}°: "
                 f"κ0 = {math.degrees(ms.kappa0):.2f}°, verdict: {st.verdict}", fontsize=10)
    fig.tight_layout()
    return fig


register_figures(
    "gyrostat",
    "The displaced-orbit dumbbell; stability maps and kappa0(theta0) (Stepanov 1968)",
    {
        "fig1_dumbbell": fig1_dumbbell,
        "stability_maps_lr01": stability_maps_lr01,
        "stability_maps_lr02": stability_maps_lr02,
        "kappa0": kappa0,
        "symmetric_map": symmetric_map,
    },
)
