"""Figure functions and the registry behind ``python -m rigidbody figures``.

One function draws one figure. Each module ``rigidbody/paperfigs/<set>.py`` defines, for every figure of
its paper and for the figures that go beyond it, a public function that computes the data with the public
API, draws it with :mod:`rigidbody.plotting` and returns the Matplotlib figure; it then registers them::

    from rigidbody.paperfigs import register_figures

    def fig1_case1_theta5(sol=None):          # the paper's figure 1: fig<N>_<slug>
        ...
        return fig

    def averaged_vs_full(...):                # a figure beyond the paper: no fig<N> prefix
        ...

    register_figures("lagrange", "Figs 1-3: the heavy top under linear drag (Akulenko et al. 1979)",
                     {"fig1_case1_theta5": fig1_case1_theta5, "averaged_vs_full": averaged_vs_full})

The command saves each as ``<set>/<name>.png``; the gallery script ``examples/<set>/<name>.py`` calls the
same function, so a figure is drawn by one piece of code. A figure function takes its data as arguments
(computed by the function when they are left out): the gallery script computes them in view, with the public
calls of the analysis, and passes them in. The names of the paper's figures start with
``fig<N>_``. Older builders that write their own files register with the :func:`register` decorator.

The functions live in the package (not in ``examples/``) so that the command works after a plain
``pip install .`` from any directory. Submodules are discovered automatically.
"""

from __future__ import annotations

import importlib
import pkgutil
import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

__all__ = ["PAPER_FIGURE", "FigureSet", "discover", "register", "register_figures", "registry"]

#: the name of a paper's figure: ``fig<N>_<slug>`` (``fig4_hodograph_case2``)
PAPER_FIGURE = re.compile(r"^fig(?P<number>[1-9][0-9]*)_(?P<slug>[a-z0-9]+(?:_[a-z0-9]+)*)$")
_NAME = re.compile(r"^[a-z][a-z0-9]*(?:_[a-z0-9]+)*$")

#: resolution of the written PNGs
_DPI = 110


@dataclass(frozen=True)
class FigureSet:
    """A registered figure set.

    Attributes
    ----------
    name : str
        The set's name, the output sub-folder (``lagrange``, ``euler_poinsot``, ...).
    description : str
        One line for ``--list``.
    build : callable
        ``build(outdir, only=None) -> list of written paths``.
    figures : dict
        Figure name -> drawing function (returns a Matplotlib figure); empty for a builder registered
        with :func:`register`, which writes its files itself.

    See Also
    --------
    registry : all the registered sets.
    register_figures : registers a set.

    Examples
    --------
    >>> from rigidbody.paperfigs import registry
    >>> fs = registry()["viscous"]
    >>> fs.name, fs.figures["histories"].__name__
    ('viscous', 'histories')
    """

    name: str
    description: str
    build: Callable[..., list[Path]]
    figures: Mapping[str, Callable[[], Any]] = field(default_factory=dict)

    @property
    def paper_figures(self) -> tuple[str, ...]:
        """Names of the paper's figures (``fig<N>_<slug>``), in the order of registration.

        Examples
        --------
        Krivtsov's paper has five figures:

        >>> from rigidbody.paperfigs import registry
        >>> registry()["viscous"].paper_figures
        ('fig1_ball_and_rod', 'fig2_contracting_spiral', 'fig3_unwinding_spiral', 'fig4_turn_contracting',
         'fig5_turn_unwinding')
        """
        return tuple(n for n in self.figures if PAPER_FIGURE.match(n))

    @property
    def extra_figures(self) -> tuple[str, ...]:
        """Names of the figures beyond the paper.

        Examples
        --------
        >>> from rigidbody.paperfigs import registry
        >>> registry()["viscous"].extra_figures
        ('histories',)
        """
        return tuple(n for n in self.figures if not PAPER_FIGURE.match(n))


_REGISTRY: dict[str, FigureSet] = {}


def register(name: str, description: str) -> Callable[[Callable[[Path], list[Path]]], Callable[[Path], list[Path]]]:
    """Decorator registering ``build(outdir) -> list of written paths`` under ``name``.

    For a builder that writes its own files; :func:`register_figures` is the form for one function per
    figure.

    Parameters
    ----------
    name : str
        The set's name, also the output sub-folder.
    description : str
        One line for ``python -m rigidbody figures --list``.

    Returns
    -------
    callable
        The decorator: it registers ``build`` and returns it unchanged.

    See Also
    --------
    register_figures : the form for one function per figure.

    Examples
    --------
    Calling ``register`` registers nothing yet; its result does, applied to the builder::

        @register("my_set", "Figures written by their own builder")
        def build(outdir):
            ...                 # write the files into outdir
            return paths        # the paths written

    >>> from rigidbody.paperfigs import register, registry
    >>> deco = register("my_set", "Figures written by their own builder")
    >>> callable(deco), "my_set" in registry()
    (True, False)
    """

    def deco(func: Callable[[Path], list[Path]]) -> Callable[[Path], list[Path]]:
        def build(outdir: Path, only: Iterable[str] | None = None) -> list[Path]:
            if only is not None:
                raise ValueError(f"figure set {name!r} has no individually named figures")
            return func(Path(outdir))

        _REGISTRY[name] = FigureSet(name, description, build)
        return func

    return deco


def register_figures(name: str, description: str, figures: Mapping[str, Callable[[], Any]]) -> None:
    """Register a figure set given as ``{figure name: drawing function}``.

    Parameters
    ----------
    name : str
        The set's name (lower case, underscores), also the output sub-folder.
    description : str
        One line for ``python -m rigidbody figures --list``.
    figures : mapping
        Figure name -> function called without arguments that returns a Matplotlib figure. A name
        ``fig<N>_<slug>`` is figure N of the paper (:data:`PAPER_FIGURE`); other names are figures beyond it.

    Raises
    ------
    ValueError
        If a name is not lower case with underscores, or a paper figure number is used twice.

    See Also
    --------
    registry : the registered sets.
    PAPER_FIGURE : the pattern of a paper's figure name.

    Examples
    --------
    A figure module ends with its table (see the module's docstring). The names are checked before
    anything is registered:

    >>> from rigidbody.paperfigs import register_figures, registry
    >>> def draw():
    ...     import matplotlib.pyplot as plt
    ...     return plt.figure()
    >>> register_figures("my_set", "One figure", {"Fig1_bad": draw})
    Traceback (most recent call last):
        ...
    ValueError: figure name must be lower case with underscores, got 'Fig1_bad'
    >>> register_figures("my_set", "Two figures 2", {"fig2_a": draw, "fig2_b": draw})
    Traceback (most recent call last):
        ...
    ValueError: figure 2 of 'my_set' is registered twice: 'fig2_a' and 'fig2_b'
    >>> "my_set" in registry()
    False
    """
    numbers: dict[str, str] = {}
    for fname in figures:
        if not _NAME.match(fname):
            raise ValueError(f"figure name must be lower case with underscores, got {fname!r}")
        m = PAPER_FIGURE.match(fname)
        if m:
            if m["number"] in numbers:
                raise ValueError(f"figure {m['number']} of {name!r} is registered twice: "
                                 f"{numbers[m['number']]!r} and {fname!r}")
            numbers[m["number"]] = fname
    table = dict(figures)

    def build(outdir: Path, only: Iterable[str] | None = None) -> list[Path]:
        import matplotlib.pyplot as plt

        selected = list(table) if only is None else list(only)
        unknown = [n for n in selected if n not in table]
        if unknown:
            raise ValueError(f"figure set {name!r} has no figure(s) {unknown}; it has {list(table)}")
        outdir = Path(outdir)
        outdir.mkdir(parents=True, exist_ok=True)
        paths = []
        for fname in selected:
            fig = table[fname]()
            path = outdir / f"{fname}.png"
            fig.savefig(path, dpi=_DPI, bbox_inches="tight")
            plt.close(fig)
            paths.append(path)
        return paths

    _REGISTRY[name] = FigureSet(name, description, build, table)


def discover() -> None:
    """Import every builder module in this package (each registers itself).

    See Also
    --------
    registry : calls it, then lists the sets.

    Examples
    --------
    >>> import sys
    >>> from rigidbody.paperfigs import discover
    >>> discover()
    >>> "rigidbody.paperfigs.gyrostat" in sys.modules
    True
    """
    for info in pkgutil.iter_modules(__path__):
        importlib.import_module(f"{__name__}.{info.name}")


def registry() -> dict[str, FigureSet]:
    """All registered figure sets, sorted by name (after :func:`discover`).

    Returns
    -------
    dict of str to FigureSet

    See Also
    --------
    FigureSet : one set.

    Examples
    --------
    The four papers' figures: Stepanov's one, Akulenko et al.'s three, Rachinskaya's six and Krivtsov's five;
    the studies' figures go beyond the papers:

    >>> from rigidbody.paperfigs import registry
    >>> {name: len(fs.paper_figures) for name, fs in registry().items()}
    {'euler_poinsot': 6, 'gyrostat': 1, 'lagrange': 3, 'studies': 0, 'viscous': 5}
    """
    discover()
    return dict(sorted(_REGISTRY.items()))
