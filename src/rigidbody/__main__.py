"""Command line: ``python -m rigidbody figures --out DIR`` regenerates the paper figures.

Each figure is written to ``DIR/<set>/<name>.png``; the paper's figures are named ``fig<N>_<slug>``
(``euler_poinsot/fig4_hodograph_case2.png``), the figures beyond the papers have no ``fig<N>`` prefix.
``python -m rigidbody figures --list`` lists the registered figure sets and their figures; ``--only NAME``
(repeatable) builds one set (``--only gyrostat``) or one figure (``--only gyrostat/fig1_dumbbell``). One
progress line is printed per figure set, with its time.
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
            for fname in fs.figures:
                print(f"    {fs.name}/{fname}")
        return 0
    # NAME selects a whole set, NAME/FIGURE one figure of it
    wanted: dict[str, list[str] | None] = {}
    for item in args.only or list(reg):
        set_name, _, fig_name = item.partition("/")
        if set_name not in reg:
            print(f"unknown figure set(s): {set_name}; available: {', '.join(reg)}", file=sys.stderr)
            return 2
        if fig_name and fig_name not in reg[set_name].figures:
            print(f"unknown figure {item}; figures of {set_name}: {', '.join(reg[set_name].figures) or 'none named'}",
                  file=sys.stderr)
            return 2
        if not fig_name:
            wanted[set_name] = None
        elif set_name not in wanted or wanted[set_name] is not None:
            wanted.setdefault(set_name, [])
            sel = wanted[set_name]
            if sel is not None and fig_name not in sel:
                sel.append(fig_name)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    failed = []
    total = time.perf_counter()
    for name, only in wanted.items():
        fs = reg[name]
        t0 = time.perf_counter()
        sub = out / name
        sub.mkdir(parents=True, exist_ok=True)
        try:
            paths = fs.build(sub) if only is None else fs.build(sub, only=only)
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
    pf.add_argument("--only", action="append", metavar="NAME",
                    help="build only this figure set, or SET/FIGURE one figure (repeatable)")
    pf.add_argument("--list", action="store_true", help="list the registered figure sets and their figures, and exit")
    args = parser.parse_args(argv)
    if args.command == "figures":
        return _figures(args)
    return 2  # pragma: no cover


if __name__ == "__main__":
    sys.exit(main())
