"""Progress bar modes; the optional dependencies stay optional."""

from __future__ import annotations

import fcntl
import os
import pty
import struct
import subprocess
import sys
import termios
from pathlib import Path

import pytest
import sweep_testlib as lib

from rigidbody.sweep import sweep
from rigidbody.sweep._api import require

GRID = {"a": [0.0, 1.0, 3.0], "b": [0.5, 1.5]}
SRC = Path(__file__).resolve().parents[2] / "src"
OPTIONAL = ("xarray", "dask", "distributed", "zarr", "tqdm", "cloudpickle", "pandas")


def test_progress_false_and_none_off_a_terminal_print_nothing(capfd):
    sweep(lib.poly, GRID, executor="serial", progress=False)
    assert capfd.readouterr().err == ""
    sweep(lib.poly, GRID, executor="serial")  # None: stderr is captured here, not a terminal
    assert capfd.readouterr().err == ""


def test_progress_true_draws_a_bar_counting_points(capfd):
    sweep(lib.poly, GRID, executor="serial", progress=True, chunk_size=2)
    err = capfd.readouterr().err
    assert "6/6" in err and "sweep poly" in err


def test_the_bar_of_a_partial_is_labelled_by_its_function(capfd):
    # the label was the tail of the partial's repr after its last dot ("sweep 5)):" for a bound 0.5)
    from functools import partial

    sweep(partial(lib.poly, b=0.5), {"a": [0.0, 1.0]}, executor="serial", progress=True)
    err = capfd.readouterr().err
    assert "sweep poly (partial)" in err and "5)" not in err


def test_progress_none_on_a_terminal_draws_the_bar():
    code = ("import sys; from rigidbody.sweep import sweep\n"
            "def f(a):\n    return {'x': a}\n"
            "sweep(f, {'a': [1.0, 2.0, 3.0, 4.0, 5.0]}, executor='serial')\n"
            "print('isatty', sys.stderr.isatty(), file=sys.stderr)\n")
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # a terminal of 100 columns
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.Popen([sys.executable, "-c", code], stderr=slave, stdout=subprocess.DEVNULL, env=env)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 4096)
        except OSError:  # the terminal closed
            break
        if not data:
            break
        chunks.append(data)
    os.close(master)
    assert proc.wait(timeout=60) == 0
    text = b"".join(chunks).decode(errors="replace")
    assert "isatty True" in text and "5/5" in text


def test_import_rigidbody_needs_none_of_the_optional_dependencies():
    code = ("import sys, rigidbody, rigidbody.sweep, rigidbody.core.ode\n"
            f"print(sorted({{m.split('.')[0] for m in sys.modules}} & set({OPTIONAL!r})))\n")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")]))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    assert out.stdout.strip() == "[]"


def test_a_missing_optional_dependency_says_how_to_install_it():
    with pytest.raises(ImportError, match=r'pip install "rigidbody\[sweep\]"'):
        require("rigidbody_no_such_module")
