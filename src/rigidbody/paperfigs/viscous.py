"""Figures 2-5 of Krivtsov (2000) and time histories of k, R, s, ξ, ζ.

The paper prints no parameters for its figures; we choose (stated here and in docs/viscous.md):
``θ12 = 2, θ3 = 1``, ``Ω0 = 6`` (``ξ∞ = 30`` rad ≈ 4.8 turns of the tangent);
fig. 2 contracting ``B12 = 0.4, B3 = 0.1``, ``v0 = 2`` (``k0 = 1.5``, ``R0 = 0.55``);
fig. 3 unwinding ``B12 = 0.1, B3 = 0.1``, ``v0 = 0.6`` (``k0 = 5``, ``R0 = 0.2``);
figs 4-5 one turn of each spiral starting at ``t1 = 0``. Paths are drawn from ``t = 0`` to ``t = ∞``
(the reconstruction runs in the compactified time ``u = 1 - e^{-γt}``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rigidbody import viscous as vs
from rigidbody.paperfigs import register

BODY = vs.Body(theta12=2.0, theta3=1.0)
CONTRACTING = vs.Medium(B12=0.4, B3=0.1)
UNWINDING = vs.Medium(B12=0.1, B3=0.1)
OMEGA0 = 6.0
N0 = np.array([1.0, 0.0, 0.0])
MEDIA = {"contracting": CONTRACTING, "unwinding": UNWINDING}
NDOT0 = {"contracting": np.array([0.0, 2.0, 0.0]), "unwinding": np.array([0.0, 0.6, 0.0])}


def figure_data(name: str, t_max: float = 200.0, num: int = 4000) -> dict[str, np.ndarray]:
    """The arrays behind the spiral figures ('contracting' or 'unwinding'): path n(t) from (v, k) and
    the closed-form histories."""
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


@register("viscous", "Figs 2-5: spirals of the symmetry axis and the solid angle of a turn (Krivtsov 2000)")
def build(outdir: Path) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rigidbody.plotting import viscous as pv

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    paths: list[Path] = []
    datas = {}
    for fig_no, (name, medium) in ((2, ("contracting", CONTRACTING)), (3, ("unwinding", UNWINDING))):
        d = figure_data(name)
        datas[name] = d
        fig = plt.figure(figsize=(5.5, 5.5))
        ax = fig.add_subplot(111, projection="3d")
        # contracting: look at the limit point; unwinding: from the pole of the limiting great circle
        view = d["n_inf"] if name == "contracting" else d["g_inf"]
        pv.sphere_path(d["n"], ax, view=view, label=f"{name} spiral", lw=1.0)
        ax.set_title(f"Fig. {fig_no}: {name} spiral (B12={medium.B12}, B3={medium.B3}, θ12=2, θ3=1)", fontsize=9)
        p = outdir / f"viscous_fig{fig_no}_{name}.png"
        fig.savefig(p, dpi=110, bbox_inches="tight")
        plt.close(fig)
        paths.append(p)
    for fig_no, (name, medium) in ((4, ("contracting", CONTRACTING)), (5, ("unwinding", UNWINDING))):
        tr = vs.turn(BODY, medium, N0, NDOT0[name], OMEGA0, 0.0)
        fig = plt.figure(figsize=(5.5, 5.5))
        ax = fig.add_subplot(111, projection="3d")
        pv.turn_solid_angle(tr, ax)
        fig.suptitle(f"Fig. {fig_no}: one turn of the {name} spiral, t in [0, {tr.t2:.3f}]", fontsize=10)
        p = outdir / f"viscous_fig{fig_no}_turn_{name}.png"
        fig.savefig(p, dpi=110, bbox_inches="tight")
        plt.close(fig)
        paths.append(p)
    fig, axes = plt.subplots(5, 2, figsize=(9.0, 9.0), sharex=True)
    for j, name in enumerate(("contracting", "unwinding")):
        d = datas[name]
        mask = d["t"] <= 80.0
        pv.quasi_coordinate_histories(
            d["t"][mask], {"k": d["k"][mask], "R": d["R"][mask], "s": d["s"][mask], "ξ": d["xi"][mask],
                           "ζ": d["zeta"][mask]}, axes=axes[:, j])
        axes[0, j].set_title(name)
    fig.suptitle("Curvature (4.5), spiral radius (5.2) and quasi-coordinates (5.1)")
    fig.tight_layout()
    p = outdir / "viscous_histories.png"
    fig.savefig(p, dpi=110)
    plt.close(fig)
    paths.append(p)
    return paths
