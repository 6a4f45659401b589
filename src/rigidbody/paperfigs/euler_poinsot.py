"""Figures 1-6 of Rachinskaya: the hodograph of the angular momentum, and G, T, k², δ, λ against τ.

The paper's setup (sec. 3): A = (3.2, 2.6, 1.67), G(0) = 1, k²(0) = 0.99, δ(0) = λ(0) = π/4, drag
I = diag(2.322, 1.31, 1.425) (case 1, χ < 0) and diag(0.919, 5.228, 1.666) (case 2, χ > 0).
The paper states neither ε, ν0 nor the end time. Our choices (also in docs/euler_poinsot.md):
ν0 = 0, τ ∈ [0, 6]; the hodographs show the orbit-averaged limit ε = 0 and ε = 0.005 (ν kept; in case 1
the run ends at τ = 4.77 when the decaying rotation is no longer fast, spin ratio = 1; in case 2 it stays
fast to τ = 6). A separate figure shows how the picture depends on ε,
including ε = 0.1 and 0.3, integrated with the validity check switched off (``min_spin_ratio=0``) to show
what the equations do outside the theory (the drift of δ and the bent spiral the paper describes).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.core.ode import Solution
from rigidbody.paperfigs import register

BODY = ep.Body(3.2, 2.6, 1.67)
CASES = {"case 1 (chi<0)": np.diag([2.322, 1.31, 1.425]), "case 2 (chi>0)": np.diag([0.919, 5.228, 1.666])}
SETUP: dict[str, Any] = dict(G0=1.0, k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4, nu0=0.0)
TAU = (0.0, 6.0)
EPS_MAIN = (0.0, 0.005)
EPS_SCAN = (0.0, 0.01, 0.1, 0.3)


def figure_data(I: np.ndarray, eps: float, num: int = 3001) -> Solution:
    """The averaged solution behind a figure (validity check off for eps above the theory's range)."""
    tau_eval = np.linspace(*TAU, num)
    big = eps > 0 and ep.spin_ratio(BODY, eps, SETUP["G0"], SETUP["k2_0"]) <= 1.0
    return ep.averaged(BODY, I, eps, tau_span=TAU, tau_eval=tau_eval, min_spin_ratio=0.0 if big else 1.0, **SETUP)


@register("euler_poinsot", "Figs 1-6: hodograph of G under gravity-gradient and drag torques (Rachinskaya)")
def build(outdir: Path) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rigidbody.plotting import euler_poinsot as epp

    out: list[Path] = []
    outdir = Path(outdir)
    for i, (name, I) in enumerate(CASES.items()):
        sols = {eps: figure_data(I, eps) for eps in EPS_MAIN}
        fig = plt.figure(figsize=(15, 5))
        ax3 = fig.add_subplot(1, 3, 1, projection="3d")
        ax12 = fig.add_subplot(1, 3, 2)
        axa = fig.add_subplot(1, 3, 3)
        axis = epp.spiral_axis(sols[0.0])
        for eps, s in sols.items():
            lab = f"eps = {eps:g}" + (" (orbit-averaged)" if eps == 0 else "")
            if s.status == 1:
                lab += f", stopped at tau = {s.tau[-1]:.2f}: {s.event}"
            kw = dict(lw=0.8, label=lab)
            epp.hodograph_3d(s, ax3, **kw)
            epp.hodograph_projection(s, ax12, **kw)
            epp.hodograph_projection(s, axa, normal=axis, **kw)
        ax3.set_title(f"{name}: hodograph of G (fig. {1 + 3 * i})")
        ax12.set_title(f"projection on Ox1x2 (fig. {2 + 3 * i})")
        axa.set_title(f"view along the spiral axis (fig. {3 + 3 * i})")
        ax12.legend(fontsize=8)
        fig.tight_layout()
        p = outdir / f"euler_poinsot_hodograph_case{i + 1}.png"
        fig.savefig(p, dpi=110)
        plt.close(fig)
        out.append(p)

        fig, axes = plt.subplots(5, 1, figsize=(7, 10), sharex=True)
        for eps, s in sols.items():
            epp.slow_variables(s, axes, label=f"eps = {eps:g}", lw=1.0)
        axes[2].axhline(ep.k2_equilibria(BODY, I)[-1][0], color="0.6", ls=":", lw=0.8)
        axes[0].set_title(f"{name}: slow variables, chi = {ep.chi(BODY, I):.4f}")
        fig.tight_layout()
        p = outdir / f"euler_poinsot_slow_case{i + 1}.png"
        fig.savefig(p, dpi=110)
        plt.close(fig)
        out.append(p)

    # dependence on eps
    fig, axs = plt.subplots(2, 3, figsize=(15, 8))
    for row, (name, I) in enumerate(CASES.items()):
        for eps in EPS_SCAN:
            s = figure_data(I, eps)
            valid = eps == 0 or ep.spin_ratio(BODY, eps, SETUP["G0"], SETUP["k2_0"]) > 1
            lab = f"eps = {eps:g}" + ("" if valid else " (outside the theory)")
            if s.status == 1:
                lab += f", ends at tau = {s.tau[-1]:.2f} ({s.event})"
            axs[row, 0].plot(s.tau, s.delta, lw=0.9, label=lab)
            epp.hodograph_projection(s, axs[row, 1], lw=0.7, label=lab)
            h = epp.hodograph(s)
            axs[row, 2].plot(np.hypot(h[0], h[1]), h[2], lw=0.7, label=lab)
        axs[row, 0].set_ylabel("$\\delta$")
        axs[row, 0].set_xlabel("$\\tau$")
        axs[row, 0].set_title(f"{name}: delta(tau) for several eps")
        axs[row, 1].set_title("projection on Ox1x2")
        axs[row, 2].set_xlabel("distance from $x_3$ axis")
        axs[row, 2].set_ylabel("$x_3$")
        axs[row, 2].set_title("meridian view (delta = const: a straight line)")
        axs[row, 0].legend(fontsize=8)
    fig.tight_layout()
    p = outdir / "euler_poinsot_eps_dependence.png"
    fig.savefig(p, dpi=110)
    plt.close(fig)
    out.append(p)
    return out
