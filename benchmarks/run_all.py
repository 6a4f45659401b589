"""Run every benchmark and collect their ratio lines (run on demand: ``python benchmarks/run_all.py``).

Each ``benchmarks/bench_*.py`` runs in its own process, one after the other (the ratios are timings: running
two at once would distort both), with its full output shown as it comes. At the end the lines that state a
ratio are repeated together: lines starting with ``RATIO`` (the convention for new benchmarks), and in older
scripts any line mentioning a ratio or printing one as ``<number>x``. A benchmark that fails is reported
and the others still run; the exit status is non-zero if any failed.

Options: names to select some benchmarks (``python benchmarks/run_all.py lagrange core``).
"""

from __future__ import annotations

import re
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
RATIO = re.compile(r"^RATIO\b|\bratio\b|\d\.\d+x\b", re.IGNORECASE)


def main(argv: list[str]) -> int:
    scripts = sorted(HERE.glob("bench_*.py"))
    if argv:
        scripts = [s for s in scripts if any(a in s.stem for a in argv)]
    collected: list[tuple[str, str]] = []
    failed: list[str] = []
    for script in scripts:
        print(f"===== {script.name}", flush=True)
        t0 = time.perf_counter()
        proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True, cwd=HERE.parent)
        assert proc.stdout is not None
        for line in proc.stdout:
            print(line, end="", flush=True)
            if RATIO.search(line):
                collected.append((script.stem, line.strip()))
        if proc.wait() != 0:
            failed.append(script.name)
        print(f"===== {script.name}: {time.perf_counter() - t0:.1f} s, exit {proc.returncode}", flush=True)
    print("\n===== ratios")
    for name, line in collected:
        print(f"[{name}] {line}")
    if failed:
        print(f"\nfailed: {', '.join(failed)}")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
