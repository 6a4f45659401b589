"""Command line: ``python -m rigidbody figures --out DIR`` regenerates the paper figures.

``python -m rigidbody figures --list`` lists the registered figure sets; ``--only NAME`` (repeatable)
builds a subset. One progress line is printed per figure set, with its time.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path


def _figures(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    from rigidbody.paperfigs import registry

    reg = registry()
    if args.list or (not reg and not args.only):
        if not reg:
            print("no figure sets are registered yet")
        for fs in reg.values():
            print(f"{fs.name:16s} {fs.description}")
        return 0
    names = args.only or list(reg)
    unknown = [n for n in names if n not in reg]
    if unknown:
        print(f"unknown figure set(s): {', '.join(unknown)}; available: {', '.join(reg)}", file=sys.stderr)
        return 2
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    failed = []
    total = time.perf_counter()
    for name in names:
        fs = reg[name]
        t0 = time.perf_counter()
        sub = out / name
        sub.mkdir(parents=True, exist_ok=True)
        try:
            paths = fs.build(sub)
        except Exception as exc:  # report and go on with the other sets
            failed.append(name)
            print(f"[{name}] FAILED after {time.perf_counter() - t0:.1f} s: {type(exc).__name__}: {exc}", flush=True)
            continue
        print(f"[{name}] {len(paths)} figure(s) in {time.perf_counter() - t0:.1f} s -> {sub}", flush=True)
    print(f"done in {time.perf_counter() - total:.1f} s; figures in {out.resolve()}")
    return 1 if failed else 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``python -m rigidbody``."""
    parser = argparse.ArgumentParser(prog="python -m rigidbody", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    pf = sub.add_parser("figures", help="regenerate the paper figures")
    pf.add_argument("--out", default="figures", help="output folder (default: ./figures)")
    pf.add_argument("--only", action="append", metavar="NAME", help="build only this figure set (repeatable)")
    pf.add_argument("--list", action="store_true", help="list the registered figure sets and exit")
    args = parser.parse_args(argv)
    if args.command == "figures":
        return _figures(args)
    return 2  # pragma: no cover


if __name__ == "__main__":
    sys.exit(main())
