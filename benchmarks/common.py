"""What the benchmark scripts share: CPU timing, and the time a baseline takes at the project's accuracy.

Not a benchmark itself (``run_all.py`` runs the ``bench_*.py`` scripts); the scripts import it from their own
folder.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

#: the baseline's tolerances, from loose to tight; the fourth (1e-10) is the project's default
BASELINE_RTOLS = (1e-8, 1e-9, 3e-10, 1e-10, 3e-11, 1e-11, 3e-12, 1e-12)


def cpu_time(f: Callable[[], object], repeat: int = 5, number: int = 1) -> float:
    """The best of ``repeat`` CPU times (of this process) of ``number`` calls of ``f``, per call."""
    best = math.inf
    for _ in range(repeat):
        t0 = time.process_time()
        for _ in range(number):
            f()
        best = min(best, (time.process_time() - t0) / number)
    return best


def time_at_accuracy(target: float, runs: list[tuple[float, float]]) -> tuple[float, str]:
    """The baseline's time at the error ``target``, log-log interpolated in its ``(error, time)`` runs, and a
    note: where even its most accurate run is less accurate than ``target``, that run's time (a lower bound)."""
    errs = np.array([e for e, _ in runs])
    times = np.array([t for _, t in runs])
    order = np.argsort(errs)
    if target <= errs.min():
        return float(times[order][0]), " (the baseline's best is still less accurate: a lower bound)"
    return float(np.exp(np.interp(np.log(target), np.log(errs[order]), np.log(times[order])))), ""
