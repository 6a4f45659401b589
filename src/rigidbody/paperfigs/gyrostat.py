"""Stepanov (1968): the paper's figure (the dumbbell), and stability maps and kappa0(theta0) beyond it.

Choices the paper leaves open (stated here and in docs/gyrostat.md):

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
    """Nondimensional body with moments proportional to ``ratios`` and sqrt(Abar/M) = l_over_R."""
    s = l_over_R**2 * 3 / sum(ratios)
    return gyrostat.Satellite(M=1.0, A1=ratios[0] * s, A2=ratios[1] * s, A3=ratios[2] * s)


def orderings() -> list[tuple[float, float, float]]:
    """The six orderings of BASE, A1 > A2 > A3 first."""
    return sorted({(a, b, c) for a, b, c in itertools.permutations(BASE)}, reverse=True)


def map_data(l_over_R: float, ratios: tuple[float, float, float]) -> dict:
    """Arrays behind one map panel: codes on (THETA x U) and the boundary curves u(theta0)."""
    sat = body(l_over_R, ratios)
    mp, b = gyrostat.normalized_stability_map(sat, 1.0, THETA, U)
    return {"sat": sat, "code": mp.code, "b": b, "map": mp}


def kappa_data() -> dict[float, np.ndarray]:
    """kappa0(theta0) on THETA for each l/R (k2 = 0; kappa0 does not depend on k2)."""
    out = {}
    for lR in L_OVER_R_KAPPA:
        sat = body(lR)
        out[lR] = gyrostat.stability_map(sat, 1.0, THETA, k2=0.0).kappa0
    return out


SYM_THETA = np.linspace(-3.1, 3.1, 311)
SYM_RATIO = np.linspace(0.05, 2.0, 196)
SYM_L_OVER_R = 0.1


def symmetric_map_data() -> gyrostat.SymmetricStabilityMap:
    """Verdicts of (3.2) on SYM_THETA x SYM_RATIO (A3/A1), l/R = SYM_L_OVER_R (A1 fixed, A3 varied)."""
    A1 = SYM_L_OVER_R**2
    sat = gyrostat.Satellite(M=1.0, A1=A1, A2=A1, A3=A1)
    return gyrostat.symmetric_stability_map(sat, 1.0, SYM_THETA, A3=SYM_RATIO * A1)


def dumbbell_data() -> tuple[gyrostat.Satellite, gyrostat.SymmetricMotion]:
    """The dumbbell of the paper's figure: the satellite and its stationary motion (3.2)-(3.3)."""
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
        ``sqrt(Abar / M) / R0``.
    maps : dict, optional
        ``{ratios: (StabilityMap, boundaries)}`` for the six :func:`orderings`, each the result of
        :func:`rigidbody.gyrostat.normalized_stability_map` for ``body(l_over_R, ratios)`` with ``R0 = 1`` on
        :data:`THETA` x :data:`U` (default: computed here).
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
    """Beyond the paper: :func:`stability_maps` for l/R = 0.1."""
    return stability_maps(L_OVER_R_MAPS[0], maps)


def stability_maps_lr02(maps: dict[tuple[float, float, float], Any] | None = None) -> Any:
    """Beyond the paper: :func:`stability_maps` for l/R = 0.2."""
    return stability_maps(L_OVER_R_MAPS[1], maps)


def kappa0(data: dict[float, np.ndarray] | None = None) -> Any:
    """Beyond the paper: the latitude kappa0(theta0) of the orbit (2.4) for several l/R, and scaled by
    (l/R)^2 (the curves collapse, extremal near theta0 = +-pi/4).

    ``data``: ``{l/R: kappa0 on THETA}`` (default :func:`kappa_data`).
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
