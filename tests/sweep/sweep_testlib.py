"""Functions swept by the tests (module level, so every executor can run them)."""

from __future__ import annotations

import math
import os
import signal
import sys
import time
import uuid
from pathlib import Path

import numpy as np

from rigidbody.sweep import batched

#: the point of :func:`poly` that raises
BAD = (2.0, -1.0)


def poly(a: float, b: float) -> dict:
    """Outputs with an independent closed form (see ``expected``); raises at ``BAD``."""
    if (a, b) == BAD:
        raise ValueError(f"no value at a={a}, b={b}")
    return {"s": a + 2.0 * b, "p": a * b, "v": np.array([a, b, math.hypot(a, b)])}


def expected(a: np.ndarray, b: np.ndarray) -> dict[str, np.ndarray]:
    A, B = np.meshgrid(a, b, indexing="ij")
    bad = (A == BAD[0]) & (B == BAD[1])
    out = {"s": A + 2.0 * B, "p": A * B, "v": np.stack([A, B, np.hypot(A, B)], axis=-1)}
    for v in out.values():
        v[bad] = np.nan
    return out


def record_call(calls_dir: str, **point: float) -> None:
    """One file per call (calls happen in other processes): the name carries the point."""
    tag = "_".join(f"{k}={v!r}" for k, v in sorted(point.items()))
    (Path(calls_dir) / f"{tag}__{uuid.uuid4().hex}").touch()


def calls(calls_dir: str) -> list[str]:
    return sorted(p.name.split("__")[0] for p in Path(calls_dir).iterdir())


def _first(calls_dir: str, what: str, times: int = 1) -> bool:
    """True for the first ``times`` visits (marker files made atomically, visible to every process)."""
    for i in range(times):
        try:
            fd = os.open(Path(calls_dir).parent / f"{what}.{i}", os.O_CREAT | os.O_EXCL | os.O_WRONLY)
        except FileExistsError:
            continue
        os.close(fd)
        return True
    return False


#: seconds a call of :func:`counted` takes while the file ``<calls_dir>.hold`` exists
HOLD_S = 0.2


def hold(calls_dir: object, on: bool = True) -> None:
    """Make every call of :func:`counted` on ``calls_dir`` take at least :data:`HOLD_S` seconds (or stop that)."""
    path = Path(f"{calls_dir}.hold")
    if on:
        path.touch()
    else:
        path.unlink(missing_ok=True)


def counted(a: float, b: float, *, calls_dir: str, interrupt_at: float | None = None,
            kill_at: float | None = None, kill_times: int = 1, delay: float = 0.0,
            stop_at: tuple[float, float] | None = None, stop: str = "self", stop_signal: int = signal.SIGKILL) -> dict:
    """:func:`poly` that records its calls once it has computed them (so a call recorded has finished).

    The first visit of ``(interrupt_at, 0)`` raises KeyboardInterrupt (like Ctrl-C), the first ``kill_times``
    visits of ``(kill_at, 0)`` end its own process (a killed worker); later visits (a resumed run with the
    same function) compute normally. The first visit of ``stop_at`` sends ``stop_signal`` to its own process
    (``stop='self'``) or to its parent (``'parent'``: the sweeping process of a local worker) and waits to be
    ended. "First" is told by marker files."""
    if interrupt_at is not None and a == interrupt_at and b == 0.0 and _first(calls_dir, "interrupted"):
        raise KeyboardInterrupt
    if kill_at is not None and a == kill_at and b == 0.0 and _first(calls_dir, "killed", kill_times):
        os._exit(3)
    if stop_at is not None and (a, b) == tuple(stop_at) and _first(calls_dir, "stopped"):
        os.kill(os.getpid() if stop == "self" else os.getppid(), stop_signal)
        time.sleep(60)  # a KeyboardInterrupt in the sweeping process ends this; a worker is ended
    if Path(f"{calls_dir}.hold").exists():  # a test holds each call back (same function, so a store accepts it)
        delay = max(delay, HOLD_S)
    if delay:
        time.sleep(delay)
    record_call(calls_dir, a=a, b=b)
    return poly(a, b)


@batched
def poly_batched(a: np.ndarray, b: np.ndarray, *, calls_dir: str | None = None) -> dict:
    """:func:`poly` for a whole chunk; the bad point gets a per-point status instead of raising."""
    if calls_dir is not None:
        (Path(calls_dir) / f"n={a.size}__{uuid.uuid4().hex}").touch()
    bad = (a == BAD[0]) & (b == BAD[1])
    return {"s": a + 2.0 * b, "p": a * b, "v": np.stack([a, b, np.hypot(a, b)], axis=-1),
            "status": np.where(bad, 7, 0), "message": np.where(bad, "bad point", "")}


@batched
def poly_batched_raising(a: np.ndarray, b: np.ndarray) -> dict:
    """Raises for any chunk holding the bad point: the sweep retries that chunk point by point."""
    if np.any((a == BAD[0]) & (b == BAD[1])):
        raise ValueError("bad point in this batch")
    return {"s": a + 2.0 * b, "p": a * b, "v": np.stack([a, b, np.hypot(a, b)], axis=-1)}


def other_outputs(a: float, b: float) -> dict:
    return {"s": a + 2.0 * b}


def changing(a: float, b: float, *, calls_dir: str) -> dict:
    """A function whose code "changes" between runs: a second output once the file ``new_outputs`` exists.
    The first visit of ``(3, 0)`` raises KeyboardInterrupt (an interrupted first run)."""
    if a == 3.0 and b == 0.0 and _first(calls_dir, "interrupted"):
        raise KeyboardInterrupt
    out = {"s": a + 2.0 * b}
    if (Path(calls_dir).parent / "new_outputs").exists():
        out["q"] = np.array([a, b])
    return out


class Abort(BaseException):
    """A BaseException that is not an Exception (some libraries raise such to unwind)."""


def exiting(a: float, b: float, *, interrupt: bool = False) -> dict:
    """:func:`poly`, except that ``(2, 0)`` calls sys.exit(3), ``(3, 0.5)`` raises :class:`Abort`, and with
    ``interrupt`` ``(1, 0.5)`` raises KeyboardInterrupt (in the sweeping process that is the user's Ctrl-C)."""
    if (a, b) == (2.0, 0.0):
        sys.exit(3)
    if (a, b) == (3.0, 0.5):
        raise Abort("abandoned")
    if interrupt and (a, b) == (1.0, 0.5):
        raise KeyboardInterrupt
    return poly(a, b)


def killing(a: float, b: float, *, calls_dir: str, kill_at: tuple[float, float], how: str = "sigkill") -> dict:
    """:func:`counted` whose point ``kill_at`` ends its own process at every visit (each visit leaves a file
    ``visit-*`` beside ``calls_dir``): by SIGKILL (a killed worker, a segfault) or ``os._exit``."""
    if (a, b) == tuple(kill_at):
        (Path(calls_dir).parent / f"visit-{uuid.uuid4().hex}").touch()
        if how == "sigkill":
            os.kill(os.getpid(), signal.SIGKILL)
        os._exit(5)
    return counted(a, b, calls_dir=calls_dir)


def visits(calls_dir: str) -> int:
    return len(list(Path(calls_dir).parent.glob("visit-*")))


def shifting(a: float, b: float, *, slow: float = 0.0) -> dict:
    """Other outputs from ``a = 2`` on (a function whose outputs are not the same everywhere); the first point
    takes ``slow`` seconds (so that on workers later chunks finish first)."""
    if (a, b) == (0.0, 0.0):
        time.sleep(slow)
    if a < 2.0:
        return {"x": a + b}
    return {"y": np.array([a, b])}


def nested(a: float, *, store: str) -> dict:
    """Starts a second sweep on ``store`` (which the sweep calling it writes)."""
    from rigidbody.sweep import sweep

    sweep(poly, {"a": [a], "b": [0.0]}, executor="serial", store=store, progress=False)
    return {"x": a}
