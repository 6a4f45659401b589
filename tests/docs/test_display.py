"""Results and parameters display well in a notebook, and a result draws its module's standard figure.

``Solution._repr_html_`` is checked against the arrays themselves (every field listed with its shape and a
range that bounds it), ``sol.plot()`` by the data of the lines it draws (not the pixels), and the parameter
dataclasses by a one-line repr that is valid input again.
"""

from __future__ import annotations

import html
import math
import re
import subprocess
import sys
from collections import Counter

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

from rigidbody import euler_poinsot as ep
from rigidbody import gyrostat as gy
from rigidbody import lagrange as lg
from rigidbody import viscous as vs
from rigidbody.core._display import status_text
from rigidbody.core.ode import Solution


def _lagrange_averaged() -> Solution:
    return lg.paper_solution(2, n_out=81, tau_end=20.0)


def _lagrange_full() -> Solution:
    return lg.simulate(lg.PAPER_TOP, lg.PAPER_DRAG, 0.05, lg.paper_initial_state(2), (0.0, 10.0),
                       t_eval=np.linspace(0.0, 10.0, 101))


def _lagrange_motion() -> Solution:
    return lg.lagrange_motion(lg.PAPER_TOP, lg.paper_initial_state(2), np.linspace(0.0, 5.0, 60))


BODY = ep.Body(3.2, 2.6, 1.67)
I1 = np.diag([2.322, 1.31, 1.425])


def _ep_averaged() -> Solution:
    return ep.averaged(BODY, I1, 0.0, G0=1.0, k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4, tau_span=(0.0, 2.0),
                       tau_eval=np.linspace(0.0, 2.0, 41))


def _ep_full() -> Solution:
    return ep.simulate(BODY, I1, 0.04, k2_0=0.9, tau_span=(0.0, 0.1), tau_eval=np.linspace(0.0, 0.1, 21))


def _gyrostat() -> Solution:
    sat = gy.Satellite(M=1.0, A1=0.012, A2=0.01, A3=0.008)
    m = gy.stationary_motion(sat, 1.0, 0.5, k2=0.0)
    return gy.simulate(m.satellite, m, (0.0, 10.0), t_eval=np.linspace(0.0, 10.0, 51), dy0=1e-4 * np.ones(13))


def _viscous() -> Solution:
    return vs.simulate(vs.Body(2.0, 1.0), vs.Medium(0.4, 0.1), [1.0, 0.0, 0.0], [0.0, 2.0, 0.0], 6.0, (0.0, 10.0),
                       t_eval=np.linspace(0.0, 10.0, 200))


RESULTS = {
    "lagrange.averaged": _lagrange_averaged,
    "lagrange.simulate": _lagrange_full,
    "lagrange.lagrange_motion": _lagrange_motion,
    "euler_poinsot.averaged": _ep_averaged,
    "euler_poinsot.simulate": _ep_full,
    "gyrostat.simulate": _gyrostat,
    "viscous.simulate": _viscous,
}


def _rows(page: str) -> dict[str, tuple[str, str]]:
    """field -> (shape, range) from the HTML table."""
    rows = re.findall(r"<tr><td><code>(.*?)</code></td><td>(.*?)</td><td>(.*?)</td></tr>", page)
    return {html.unescape(n): (s, r) for n, s, r in rows}


@pytest.mark.parametrize("kind", RESULTS)
def test_html_lists_every_field_with_its_shape_and_a_range_that_bounds_it(kind):
    sol = RESULTS[kind]()
    page = sol._repr_html_()
    rows = _rows(page)
    assert list(rows) == [sol.time_name, *sol.fields]
    for name, (shape, rng) in rows.items():
        value = np.asarray(getattr(sol, name))
        assert shape == str(value.shape), name
        if not np.issubdtype(value.dtype, np.number) and value.dtype != bool:
            assert rng == "—", name
            continue
        nums = [float(x) for x in re.findall(r"[-+]?\d+(?:\.\d*)?(?:e[-+]?\d+)?", rng.split(" (")[0])]
        lo, hi = (nums[0], nums[0]) if len(nums) == 1 else nums
        finite = value[np.isfinite(value)].astype(float)
        # 6 significant digits are printed: the bounds agree with the array's to that precision
        assert lo == pytest.approx(finite.min(), rel=1e-5, abs=1e-300), name
        assert hi == pytest.approx(finite.max(), rel=1e-5, abs=1e-300), name
    assert f"{sol.time_name} ∈ [" in page and f"{sol.time.size} samples" in page
    assert f"status {sol.status}" in page and html.escape(sol.message) in page


def test_html_names_the_producer():
    t = np.linspace(0.0, 1.0, 3)
    sol = Solution.build(producer="tests.<by hand>", time=t, y=t[None, :], status=0, message="done")
    assert "(from <code>tests.&lt;by hand&gt;</code>)" in sol._repr_html_()
    assert "from <code>" not in Solution("t", t, t[None, :], {}, 0, "", None, {}, {}, None, 0)._repr_html_()


def test_html_escapes_the_message_and_lists_the_events():
    t = np.linspace(0.0, 1.0, 5)
    sol = Solution("t", t, t[None, :], {"x": t}, 1, "stopped: k2 < 0 & <b>", "flip", {"flip": np.array([0.5])},
                   {"flip": np.zeros((1, 1))}, None, 10)
    page = sol._repr_html_()
    assert "k2 &lt; 0 &amp; &lt;b&gt;" in page and "<b>\"" not in page
    assert "stopped by an event" in page and "flip at t = 0.5" in page


def test_html_of_a_batch_summarises_the_members():
    # a real batch (lagrange.averaged with initial states of shape (2, 3, 3)) in the u chart only: the paper's
    # case 1 starts next to a branch point of (2.8) (refused, status -1), case 2 reaches one (event
    # 'branch_point', NaN after it), case 3 the end of the span -- each twice
    ini = np.array([lg.integrals(lg.PAPER_TOP, *lg.paper_initial_state(c)[:5]) for c in (1, 2, 3)])
    sol = lg.averaged(lg.PAPER_TOP, lg.PAPER_DRAG, np.stack([ini, ini]), (0.0, 60.0),
                      tau_eval=np.linspace(0.0, 60.0, 7), chart="u")
    page = sol._repr_html_()
    assert "batch shape (2, 3) (6 members)" in page
    counts = Counter(np.asarray(sol.status).ravel().tolist())
    assert set(counts) == {-1, 0, 1}  # the three outcomes are all there
    for s, c in counts.items():
        assert f"{s} ({status_text(s)}) × {c}" in page
    events = [e for e in np.asarray(sol.event).ravel() if e is not None]
    assert events and f"{events[0]} × {len(events)}" in page
    r = np.asarray(sol.r)
    nan = int(np.isnan(r).sum())
    assert 0 < nan < r.size  # members that ended early have NaN after their end
    shape, rng = _rows(page)["r"]
    assert shape == str(r.shape) and rng.endswith(f"({nan} NaN)")


def _line_data(axes) -> list[np.ndarray]:
    out = []
    for ax in np.asarray(axes, dtype=object).ravel():
        for line in ax.lines:
            out.append(np.asarray(line.get_data_3d() if hasattr(line, "get_data_3d") else line.get_data(), float))
    return out


def _drawn(axes, *arrays) -> bool:
    """Whether one line of ``axes`` has exactly these coordinates."""
    n = np.size(arrays[0])
    want = np.vstack([np.broadcast_to(np.asarray(a, dtype=float), (n,)) for a in arrays])
    return any(d.shape == want.shape and np.array_equal(d, want, equal_nan=True) for d in _line_data(axes))


@pytest.mark.parametrize("kind", RESULTS)
def test_plot_draws_the_result_arrays_and_returns_the_axes(kind):
    sol = RESULTS[kind]()
    try:
        axes = sol.plot()
        flat = np.asarray(axes, dtype=object).ravel()
        assert flat.size >= 1 and all(isinstance(a, matplotlib.axes.Axes) for a in flat)
        t = sol.time
        if kind == "lagrange.averaged":
            assert _drawn(axes, t, sol.u1) and _drawn(axes, t, sol.u3) and _drawn(axes, t, sol.H)
        elif kind.startswith("lagrange."):
            assert _drawn(axes, t, sol.u) and _drawn(axes, t, sol.Gz) and _drawn(axes, t, sol.r)
        elif kind.startswith("euler_poinsot."):
            for f in ("G", "T", "k2", "delta", "lam"):
                assert _drawn(axes, sol.tau, getattr(sol, f)), f
        elif kind == "gyrostat.simulate":
            assert _drawn(axes, t, sol.R) and _drawn(axes, t, sol.kappa) and _drawn(axes, t, sol.gamma[2])
        else:
            # the path on the sphere: lifted off the surface by a constant factor, split into the near side
            # (solid) and the far side (dashed) with NaN gaps; together they are the path
            parts = [d for d in _line_data(axes) if d.shape == sol.n.shape]
            assert len(parts) >= 1
            merged = np.where(np.isnan(parts[0]), parts[-1], parts[0])
            lift = np.linalg.norm(merged, axis=0)
            np.testing.assert_allclose(merged / lift, sol.n, rtol=1e-12, atol=1e-12)
            assert np.ptp(lift) < 1e-12
    finally:
        plt.close("all")


def test_plot_draws_on_given_axes_and_refuses_the_wrong_number():
    sol = _lagrange_averaged()
    fig, axes = plt.subplots(1, 2)
    try:
        assert list(sol.plot(axes)) == list(axes)
        with pytest.raises(ValueError, match="2 Axes"):
            sol.plot(axes[:1])
    finally:
        plt.close(fig)


def test_a_result_without_a_standard_plot_says_so():
    t = np.linspace(0.0, 1.0, 3)
    sol = Solution("t", t, t[None, :], {"x": t}, 0, "", None, {}, {}, None, 0)
    with pytest.raises(ValueError, match="no standard plot"):
        sol.plot()


BACKEND = """
def plot_solution(sol, ax=None, **kwargs):
    return ("drawn by {name}", sol.fields, ax, kwargs)
"""


def test_plot_finds_its_drawing_code_by_name_when_called(tmp_path, monkeypatch):
    # a plotting backend is any module with plot_solution(sol, ax=None, **kwargs), named when plot() is called: per
    # call (backend=...), per result or for every result (Solution.plot_backend); the default draws with
    # rigidbody.plotting (the tests above)
    for name in ("rb_backend_a", "rb_backend_b"):
        (tmp_path / f"{name}.py").write_text(BACKEND.format(name=name))
    (tmp_path / "rb_not_a_backend.py").write_text("x = 1\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    t = np.linspace(0.0, 1.0, 3)
    sol = Solution.build(producer="tests", time=t, y=t[None, :], status=0, message="", fields={"x": t})
    assert Solution.plot_backend == "rigidbody.plotting"
    assert sol.plot("axes", backend="rb_backend_a", lw=2) == ("drawn by rb_backend_a", ("x",), "axes", {"lw": 2})
    monkeypatch.setattr(Solution, "plot_backend", "rb_backend_b")  # set for every result, restored after the test
    assert sol.plot()[0] == "drawn by rb_backend_b"
    sol.plot_backend = "rb_backend_a"  # for this result only
    assert sol.plot()[0] == "drawn by rb_backend_a"
    with pytest.raises(ImportError, match=r"'rb_no_such_module'.*cannot be imported"):
        sol.plot(backend="rb_no_such_module")
    with pytest.raises(TypeError, match="'rb_not_a_backend' has no function plot_solution"):
        sol.plot(backend="rb_not_a_backend")
    with pytest.raises(TypeError, match="name of a module"):
        sol.plot(backend=3)


def test_display_needs_no_matplotlib_until_plot_is_called():
    code = (
        "import sys; from rigidbody import lagrange as lg; s = lg.paper_solution(1, n_out=5, tau_end=1.0); "
        "s._repr_html_(); repr(s); assert 'matplotlib' not in sys.modules, 'imported matplotlib'; "
        "assert 'rigidbody.plotting' not in sys.modules"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr


PARAMETERS = [
    lg.PAPER_TOP, lg.PAPER_DRAG, ep.Body(3.2, 2.6, 1.67), ep.Drag(np.diag([2.322, 1.31, 1.425])),
    ep.Drag([[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 2.0]]), ep.Orbit(0.1),
    gy.Satellite(M=1000.0, A1=1200.0, A2=1000.0, A3=800.0, mu=3.986e14), vs.Body(2.0, 1.0), vs.Medium(0.4, 0.1),
]


@pytest.mark.parametrize("obj", PARAMETERS, ids=lambda o: type(o).__module__.split(".")[1] + "." + type(o).__name__)
def test_parameter_repr_is_one_short_line_that_rebuilds_the_object(obj):
    text = repr(obj)
    assert "\n" not in text and len(text) <= 120, text
    namespace = {type(obj).__name__: type(obj)}
    assert eval(text, namespace) == obj
