"""Where an averaged run goes at a separatrix crossing: the branch rules ('likely', 'random', forced regions)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._regions import REGIONS, Region, check_region
from ._separatrix import SeparatrixCrossing
from ._stops import stop_message

__all__ = ["BRANCHES", "check_branch", "choose_region"]


BRANCHES = ("likely", "random")


def check_branch(branch: Any) -> Any:
    """'likely', 'random', a region (kind, sigma) or a sequence of regions (one per crossing)."""
    if isinstance(branch, str):
        if branch not in BRANCHES:
            raise ValueError(f"branch must be 'likely', 'random', a region such as ('max', 1) or a list of "
                             f"regions, got {branch!r}")
        return branch
    try:
        return (check_region(branch, "branch"),)
    except ValueError:
        pass
    try:
        seq = tuple(branch)
    except TypeError:
        raise ValueError(f"branch must be 'likely', 'random', a region such as ('max', 1) or a list of regions, "
                         f"got {branch!r}") from None
    return tuple(check_region(r, "branch") for r in seq)


def choose_region(crossing: SeparatrixCrossing, branch: Any, index: int, rng: np.random.Generator | None
            ) -> tuple[Region | None, str]:
    """The region the averaged motion continues in at crossing number ``index`` (or None and why not)."""
    probs = crossing.probabilities
    text = ", ".join(f"{r}: {p:.3g}" for r, p in probs.items() if p > 0)
    if not crossing.crosses or crossing.undetermined > 0.5 or not any(p > 0 for p in probs.values()):
        loops = ", ".join(f"{r}: {v:.3g}" for r, v in crossing.loop_drifts.items())
        return None, ("the separatrix attracts from both sides: no region keeps the motions that reach it "
                      f"(loop drifts {loops}); the averaged theory cannot continue")
    if isinstance(branch, tuple) and index < len(branch):
        want = branch[index]
        if probs[want] <= 0.0:
            return None, stop_message("branch", region=want, probabilities=text)
        return want, ""
    if branch == "random":
        regions = [r for r in REGIONS if probs[r] > 0]
        p = np.array([probs[r] for r in regions])
        gen = rng if rng is not None else np.random.default_rng()
        return regions[int(gen.choice(len(regions), p=p / p.sum()))], ""
    return crossing.most_probable(), ""
