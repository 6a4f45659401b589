"""Figures 1-3 of Akulenko, Leshchenko, Chernousko (1979): the heavy top under linear drag.

Parameters from the paper: ``A = 1.5, C = 1, mgl = 0.5, a = 0.125, b = 0.1``, spun about its axis with
``r0 = sqrt(3)`` and tilted by ``theta0 = 5, 60, 170`` degrees. Spans (the paper gives none): cases 1, 2
``tau in [0, 150]``, shown against ``tau`` and against ``xi = ln(1 + tau)`` (as the paper did);
case 3 ``tau in [0, 60]``. Dotted verticals mark the sign change of ``delta1`` of (2.8).
"""

from __future__ import annotations

from pathlib import Path

from rigidbody import lagrange as lg
from rigidbody.paperfigs import register


@register("lagrange", "Figs 1-3: the heavy top under linear drag, averaged (3.4) (Akulenko et al. 1979)")
def build(outdir: Path) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rigidbody.plotting.lagrange import plot_integrals, plot_roots

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    paths = []
    for case in (1, 2, 3):
        sol = lg.paper_solution(case)
        xs = ("tau", "xi") if case in (1, 2) else ("tau",)
        fig, axes = plt.subplots(len(xs), 2, figsize=(11, 4.0 * len(xs)), squeeze=False)
        for row, x in enumerate(xs):
            plot_roots(sol, axes[row, 0], x=x)
            plot_integrals(sol, axes[row, 1], x=x, mgl=lg.PAPER_TOP.mgl)
        th0 = lg.PAPER_CASES[case]
        fig.suptitle(f"Fig. {case}: theta0 = {th0:g} deg, r0 = sqrt(3), A = 1.5, C = 1, mgl = 0.5, "
                     "a = 0.125, b = 0.1 (averaged system (3.4))")
        fig.tight_layout()
        p = outdir / f"lagrange_fig{case}.png"
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    return paths
