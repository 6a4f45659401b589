"""Run every benchmark and collect their ratio lines, or compare the current tree with an earlier commit.

Each ``benchmarks/bench_*.py`` runs in its own process, one after the other (the ratios are timings: running
two at once would distort both), with its full output shown as it comes. At the end the lines that state a
ratio are repeated together: lines starting with ``RATIO`` (the convention for new benchmarks), and in older
scripts any line mentioning a ratio or printing one as ``<number>x``. A benchmark that fails is reported
and the others still run; the exit status is non-zero if any failed.

Options: names to select some benchmarks (``python benchmarks/run_all.py lagrange core``).

Before and after (``python benchmarks/run_all.py --against [REV]``): the cases of ``before_after.py`` (single
runs on the scalar integrator, batches, the averaging engine, sweeps) timed on the package of commit ``REV``
(default :data:`BEFORE`, the last commit before the restructuring of the package into one driver per system)
and on the current tree, side by side in one table: the CPU seconds of each side, their ratio (after /
before; above 1.10 is marked ``slower``), the accuracy of each side against the case's reference, and how far
the two sides' results differ. ``REV``'s ``src`` is exported with ``git archive`` into a temporary directory and
imported from there by a subprocess (``PYTHONPATH``); the current tree likewise from its ``src``. The sides
alternate (before, after, after, before, ...) over ``--rounds`` rounds (default 2) and each case keeps its
best time, so a busy machine slows both alike. The whole run takes about a minute.
"""

from __future__ import annotations

import argparse
import io
import json
import os
import re
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
RATIO = re.compile(r"^RATIO\b|\bratio\b|\d\.\d+x\b", re.IGNORECASE)
#: the reference of ``--against`` without a commit: the last commit before the package's restructuring (one
#: driver per system, one batch convention, results built by keywords) began
BEFORE = "96e1f3b"
#: a ratio after / before above this is marked (timings on a shared machine vary by a few per cent)
SLOWER = 1.10


def run_benchmarks(names: list[str]) -> int:
    """Run the ``bench_*.py`` scripts (those whose names contain one of ``names``, all by default)."""
    scripts = sorted(HERE.glob("bench_*.py"))
    if names:
        scripts = [s for s in scripts if any(a in s.stem for a in names)]
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


def export_tree(rev: str, into: Path) -> str:
    """Write commit ``rev``'s ``src`` into the directory ``into`` (``git archive``); returns its description."""
    root = str(HERE.parent)
    described = subprocess.run(["git", "-C", root, "log", "-1", "--format=%h %s", rev], capture_output=True,
                               text=True, check=True).stdout.strip()
    blob = subprocess.run(["git", "-C", root, "archive", "--format=tar", rev, "src"], capture_output=True,
                          check=True).stdout
    with tarfile.open(fileobj=io.BytesIO(blob)) as tar:
        if hasattr(tarfile, "data_filter"):
            tar.extractall(into, filter="data")
        else:  # Python without extraction filters: the archive is git's own output of the repository
            tar.extractall(into)
    return described


def time_side(src: Path, repeat: int) -> dict[str, dict]:
    """The cases of ``before_after.py`` run in a subprocess that imports the package from ``src``."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    proc = subprocess.run([sys.executable, str(HERE / "before_after.py"), str(repeat)], env=env, cwd=HERE,
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"the cases failed on {src}:\n{proc.stdout}{proc.stderr}")
    rows = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    tree = rows[0]["tree"]
    if not Path(tree).resolve().is_relative_to(src.resolve()):
        raise RuntimeError(f"the subprocess imported rigidbody from {tree}, not from {src}")
    return {r["case"]: r for r in rows[1:]}


def _differ(a: list[float], b: list[float]) -> float:
    """Largest relative difference of two sides' result values (NaN where they have other lengths)."""
    if len(a) != len(b):
        return float("nan")
    return max((abs(x - y) / max(abs(x), abs(y), 1e-300) for x, y in zip(a, b)), default=0.0)


def compare(rev: str, rounds: int, repeat: int) -> int:
    """Time the cases on commit ``rev`` and on the current tree, alternately, and print one table."""
    with tempfile.TemporaryDirectory(prefix="rigidbody-before-") as tmp:
        described = export_tree(rev, Path(tmp))
        trees = {"before": Path(tmp) / "src", "after": HERE.parent / "src"}
        best: dict[str, dict[str, dict]] = {"before": {}, "after": {}}
        t0 = time.perf_counter()
        for k in range(rounds):
            for side in ("before", "after") if k % 2 == 0 else ("after", "before"):
                for name, row in time_side(trees[side], repeat).items():
                    if name not in best[side] or row["seconds"] < best[side][name]["seconds"]:
                        best[side][name] = row
    print(f"before: {described}\nafter:  the current tree ({HERE.parent / 'src'})")
    print(f"best CPU seconds per call of {rounds} rounds x {repeat} repeats ({time.perf_counter() - t0:.0f} s)\n")
    head = f"{'case':<16} {'before s':>10} {'after s':>10} {'ratio':>6}  {'err before':>10} {'err after':>10} " \
           f"{'sides differ':>12}"
    print(head + "\n" + "-" * len(head))
    slower = []
    for name in best["after"]:
        b, a = best["before"][name], best["after"][name]
        ratio = a["seconds"] / b["seconds"]
        mark = "  slower" if ratio > SLOWER else ""
        if mark:
            slower.append(name)
        print(f"{name:<16} {b['seconds']:>10.4g} {a['seconds']:>10.4g} {ratio:>6.2f}  {b['error']:>10.1e} "
              f"{a['error']:>10.1e} {_differ(b['value'], a['value']):>12.1e}{mark}")
    print("\n" + "\n".join(f"{name:<16} {row['what']}" for name, row in best["after"].items()))
    print(f"\nRATIO after/before above {SLOWER}: {', '.join(slower) if slower else 'none'}")
    return 0


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="run the bench_*.py scripts whose names contain one of these")
    parser.add_argument("--against", nargs="?", const=BEFORE, metavar="REV",
                        help=f"compare the current tree with commit REV (default {BEFORE}) instead")
    parser.add_argument("--rounds", type=int, default=2, help="rounds of the before/after comparison")
    parser.add_argument("--repeat", type=int, default=5, help="repeats of each case within a round")
    args = parser.parse_args(argv)
    if args.against:
        return compare(args.against, args.rounds, args.repeat)
    return run_benchmarks(args.names)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
