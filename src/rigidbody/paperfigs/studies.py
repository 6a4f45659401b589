"""The two parameter studies of rigidbody.studies as figures, on their quick grids (seconds on 2 cores).

*Where averaging holds*: the error of the averaged against the full evolution over (eps, k2_0) for the
Euler--Poinsot module (order eps^2) and over (eps, theta0) for the Lagrange top (order eps).
*Where the spin ends*: the final regime of k2 over the plane of drag-rate ratios, with the chi = -3 line.
The full grids (``rigidbody.studies.GRIDS[...]['full']``) are for a sweep on a cluster (docs/sweeps.md).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from rigidbody.paperfigs import register

#: the spin-end map starts every drag tensor from this k2
K2_0 = 0.5


def study_data(name: str, size: str = "quick", **sweep_kw: Any) -> Any:
    """The Dataset behind a study figure: ``name`` in ``rigidbody.studies.GRIDS``, swept on local processes."""
    from rigidbody import studies
    from rigidbody.sweep import sweep

    func: dict[str, Callable[..., dict[str, float]]] = {
        "averaging_euler_poinsot": studies.averaging_error_euler_poinsot,
        "averaging_lagrange": studies.averaging_error_lagrange,
        "spin_end": studies.spin_end,
    }
    sweep_kw.setdefault("progress", False)
    return sweep(func[name], studies.GRIDS[name][size], **sweep_kw)


def paper_cases() -> dict[str, tuple[float, float]]:
    """Rachinskaya's drag cases 1 and 2 in the plane (r1, r3) of decay-rate ratios a_i = I_ii / A_i."""
    from rigidbody import studies

    A = np.array([studies.PAPER_BODY.A1, studies.PAPER_BODY.A2, studies.PAPER_BODY.A3])
    out = {}
    for label, diag in (("case 1", studies.PAPER_DRAG_CASE1), ("case 2", (0.919, 5.228, 1.666))):
        a = np.asarray(diag) / A
        out[label] = (float(a[0] / a[1]), float(a[2] / a[1]))
    return out


@register("studies", "Parameter studies: where averaging holds, where the spin ends (rigidbody.sweep)")
def build(outdir: Path) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rigidbody.plotting import studies as sp

    outdir = Path(outdir)
    out: list[Path] = []
    for name, order, across in (("averaging_euler_poinsot", 2.0, "k2_0"), ("averaging_lagrange", 1.0, "theta0")):
        ds = study_data(name)
        if across == "theta0":
            ds = ds.assign_coords(theta0=np.degrees(ds.theta0)).rename(theta0="theta0_deg")
        else:  # the distance to the separatrix, on a log axis
            ds = ds.assign_coords(k2_0=1.0 - ds.k2_0).rename(k2_0="one_minus_k2_0")
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.8))
        sp.averaging_error_plot(ds, order, ax=a1, label="1 - k2_0" if across == "k2_0" else "theta0 (deg)")
        sp.scaled_error_map(ds, order, ax=a2, ylog=across == "k2_0")
        title = {"averaging_euler_poinsot": "Euler-Poinsot: averaged (9) with nu kept vs full, tau in [0, 0.5]",
                 "averaging_lagrange": "Lagrange top: first approximation (3.4) vs full (1.1), tau in [0, 2]"}[name]
        fig.suptitle(title)
        out.append(_save(fig, outdir / f"study_{name}.png"))
    ds = study_data("spin_end")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 5.2))
    sp.spin_end_map(ds, k2_0=K2_0, ax=a1, cases=paper_cases())
    a1.set_title(f"final regime of k2 from k2_0 = {K2_0:g} (averaged (8)/(9), eps = 0)")
    k2 = ds["k2_end"].where(ds["regime"] == 1).transpose("r3", "r1")
    mesh = a2.pcolormesh(ds["r1"].values, ds["r3"].values, k2.values, shading="nearest", cmap="viridis",
                         vmin=0.0, vmax=1.0)
    fig.colorbar(mesh, ax=a2, label="interior equilibrium k*2 reached")
    xs = np.linspace(float(ds.r1.min()), float(ds.r1.max()), 100)
    from rigidbody.studies import chi_minus_3_line

    a2.plot(xs, chi_minus_3_line(xs), "k-", lw=2)
    a2.plot(xs, xs, "k--", lw=1.5)
    a2.set_xlim(xs[0], xs[-1])
    a2.set_ylim(float(ds.r3.min()), float(ds.r3.max()))
    a2.set_xlabel(r"$r_1 = a_1/a_2$")
    a2.set_ylabel(r"$r_3 = a_3/a_2$")
    a2.set_title("where k2 settles inside (0, 1): k*2 -> 0 at chi = -3, -> 1 at r3 = r1")
    out.append(_save(fig, outdir / "study_spin_end.png"))
    return out


def _save(fig: Any, path: Path) -> Path:
    import matplotlib.pyplot as plt

    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
