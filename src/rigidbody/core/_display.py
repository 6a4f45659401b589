"""How a :class:`~rigidbody.core.ode.Solution` shows itself in a notebook and draws itself.

``Solution._repr_html_`` and ``Solution.plot`` are one-line delegations to :func:`solution_html` and
:func:`plot_solution` here, so that the result class stays small and the display logic has one home.

* :func:`solution_html` renders an HTML table of the fields (name, shape, range), the time span, the
  producer, the status and the message; for a batch run (``sol.batch_shape != ()``) the batch shape and a
  summary of the members' statuses, events and messages.
* :func:`plot_solution` draws the module's standard figure with the plotting backend: the module named by
  ``Solution.plot_backend`` (``'rigidbody.plotting'``), imported by name when called, as pandas finds its
  plotting backend. ``rigidbody.core`` imports neither Matplotlib nor the plotting layer.
"""

from __future__ import annotations

import html
import importlib
from collections import Counter
from typing import Any

import numpy as np

__all__ = ["plot_solution", "solution_html", "status_text"]

_STATUS = {-1: "failed", 0: "reached the end of the span", 1: "stopped by an event"}


def status_text(status: int) -> str:
    """What a SciPy status code means: -1 failed, 0 reached the end of the span, 1 stopped by an event."""
    return _STATUS.get(int(status), "unknown status")


def _num(x: float) -> str:
    return f"{x:.6g}"


def _range(value: Any) -> str:
    arr = np.asarray(value)
    if arr.size == 0 or not (np.issubdtype(arr.dtype, np.number) or arr.dtype == bool):
        return "—"
    arr = arr.astype(float)
    finite = arr[np.isfinite(arr)]
    if finite.size == 0:
        return "no finite value"
    lo, hi = float(finite.min()), float(finite.max())
    text = _num(lo) if lo == hi else f"[{_num(lo)}, {_num(hi)}]"
    if finite.size < arr.size:
        text += f" ({arr.size - finite.size} NaN)"
    return text


def _counts(values: Any) -> str:
    items = Counter(str(v) for v in np.asarray(values, dtype=object).ravel()).most_common()
    shown = ", ".join(f"{html.escape(k)} × {n}" for k, n in items[:5])
    return shown + (f", … ({len(items) - 5} more)" if len(items) > 5 else "")


def solution_html(sol: Any) -> str:
    """HTML summary of a result: time span, status, message, events and a table of fields.

    Parameters
    ----------
    sol : Solution
        A single run or a batch run (``sol.batch_shape`` non-empty, see :class:`~rigidbody.core.ode.Solution`).

    Returns
    -------
    str
        An HTML fragment (what Jupyter shows for the object).
    """
    time = np.asarray(sol.time)
    name = html.escape(str(sol.time_name))
    batch_shape = tuple(getattr(sol, "batch_shape", ()))
    span = f"[{_num(time[0])}, {_num(time[-1])}]" if time.size else "empty"
    lines = [f"<b>Solution</b>: {name} ∈ {span}, {time.size} samples"]
    producer = getattr(sol, "producer", None)
    if producer:
        lines[0] += f" (from <code>{html.escape(str(producer))}</code>)"
    if batch_shape:
        n = int(np.prod(batch_shape))
        lines.append(f"batch shape {batch_shape} ({n} members)")
        status = np.asarray(sol.status)
        lines.append("status: " + ", ".join(f"{s} ({status_text(s)}) × {c}" for s, c in
                                            sorted(Counter(status.ravel().tolist()).items())))
        events = np.asarray(getattr(sol, "event", np.full(batch_shape, None)), dtype=object)
        if any(e is not None for e in events.ravel()):
            lines.append("events: " + _counts([e for e in events.ravel() if e is not None]))
        lines.append("messages: " + _counts(getattr(sol, "message", np.full(batch_shape, ""))))
    else:
        lines.append(f"status {int(sol.status)} ({status_text(sol.status)}): {html.escape(str(sol.message))}")
        seen = {k: np.asarray(v) for k, v in (getattr(sol, "t_events", None) or {}).items() if np.size(v)}
        if seen:
            lines.append("events: " + "; ".join(
                f"{html.escape(k)} at {name} = " + ", ".join(_num(t) for t in v.ravel()[:4])
                + (" …" if v.size > 4 else "") for k, v in seen.items()))
    head = "<br>".join(lines)
    rows = [f"<tr><td><code>{name}</code></td><td>{time.shape}</td><td>{_range(time)}</td></tr>"]
    for f in sol.fields:
        value = getattr(sol, f)
        rows.append(f"<tr><td><code>{html.escape(f)}</code></td><td>{np.shape(value)}</td>"
                    f"<td>{_range(value)}</td></tr>")
    table = ("<table><thead><tr><th style='text-align:left'>field</th><th style='text-align:left'>shape</th>"
             "<th style='text-align:left'>range</th></tr></thead><tbody>" + "".join(rows) + "</tbody></table>")
    return f"<div class='rigidbody-solution'><p>{head}</p>{table}</div>"


def plot_solution(sol: Any, ax: Any = None, *, backend: str, **kwargs: Any) -> Any:
    """Draw the standard figure of the module that produced ``sol`` with the plotting backend ``backend``.

    Parameters
    ----------
    sol : Solution
        A single run or a batch run.
    ax : Axes or array of Axes, optional
        Where to draw.
    backend : str
        The name of a module with a function ``plot_solution(sol, ax=None, **kwargs)`` that draws a result and
        returns its Axes (``'rigidbody.plotting'``: :func:`rigidbody.plotting.plot_solution`); imported now.
    **kwargs
        Passed to the drawing function.

    Returns
    -------
    Axes or numpy.ndarray of Axes
        What the backend drew on.

    Raises
    ------
    TypeError
        If ``backend`` is not a module name or the module has no function ``plot_solution``.
    ImportError
        If the module cannot be imported.
    """
    if not isinstance(backend, str) or not backend:
        raise TypeError(f"the plotting backend (Solution.plot_backend, or plot(backend=...)) is the name of a module, "
                        f"got {backend!r}")
    try:
        module = importlib.import_module(backend)
    except ImportError as exc:
        raise ImportError(f"the plotting backend {backend!r} (Solution.plot_backend, or plot(backend=...)) cannot be "
                          f"imported: {exc}") from exc
    draw = getattr(module, "plot_solution", None)
    if not callable(draw):
        raise TypeError(f"the plotting backend {backend!r} has no function plot_solution(sol, ax=None, **kwargs)")
    return draw(sol, ax, **kwargs)
