"""Figures 1-3 of Akulenko, Leshchenko, Chernousko (1979): the heavy top under linear drag.

Parameters from the paper: ``A = 1.5, C = 1, mgl = 0.5, a = 0.125, b = 0.1``, spun about its axis with
``r0 = sqrt(3)`` and tilted by ``theta0 = 5, 60, 170`` degrees (cases 1-3, one figure each). Spans (the
paper gives none): cases 1, 2 ``tau in [0, 150]``, case 3 ``tau in [0, 60]``
(:data:`rigidbody.lagrange.PAPER_TAU_END`). Cases 1 and 2 evolve slowly, so the paper also used
``xi = ln(1 + tau)``; their figures show both abscissas. Dotted verticals mark the sign change of
``delta1`` of (2.8).
"""

from __future__ import annotations

from typing import Any

from rigidbody import lagrange as lg
from rigidbody.core.ode import Solution
from rigidbody.paperfigs import register_figures

__all__ = ["case_figure", "fig1_case1_theta5", "fig2_case2_theta60", "fig3_case3_theta170"]


def case_figure(case: int, sol: Solution | None = None) -> Any:
    """Figure ``case`` of the paper: the roots ``u1, u2, u3`` and the integrals ``Gz, H, r`` against ``tau``
    (and against ``xi = ln(1 + tau)`` for cases 1, 2).

    Parameters
    ----------
    case : {1, 2, 3}
        The paper's case (its figure number).
    sol : Solution, optional
        The averaged solution to draw (default :func:`rigidbody.lagrange.paper_solution` of ``case``).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    rigidbody.lagrange.paper_solution : the data.
    rigidbody.plotting.plot_roots, rigidbody.plotting.plot_integrals : the panels.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, figs 1-3 and eq. (3.4).

    Examples
    --------
    Case 3 of the paper (:math:`\\theta_0 = 170` degrees) on a shorter run than the paper's: one row (case 3 has
    no ``xi`` panels), its title the paper's parameters:

    >>> from rigidbody import lagrange
    >>> from rigidbody.paperfigs.lagrange import case_figure
    >>> fig = case_figure(3, lagrange.paper_solution(3, n_out=100, tau_end=5.0))
    >>> len(fig.axes), fig.get_suptitle()
    (2, 'Fig. 3: theta0 = 170 deg, r0 = sqrt(3), A = 1.5, C = 1, mgl = 0.5, a = 0.125, b = 0.1 (averaged system (3.4))')
    """
    import matplotlib.pyplot as plt

    from rigidbody.plotting.lagrange import plot_integrals, plot_roots

    if case not in lg.PAPER_CASES:
        raise ValueError(f"case must be 1, 2 or 3, got {case!r}")
    sol = lg.paper_solution(case) if sol is None else sol
    xs = ("tau", "xi") if case in (1, 2) else ("tau",)
    fig, axes = plt.subplots(len(xs), 2, figsize=(11, 4.0 * len(xs)), squeeze=False)
    for row, x in enumerate(xs):
        plot_roots(sol, axes[row, 0], x=x)
        plot_integrals(sol, axes[row, 1], x=x, mgl=lg.PAPER_TOP.mgl)
    th0 = lg.PAPER_CASES[case]
    fig.suptitle(f"Fig. {case}: theta0 = {th0:g} deg, r0 = sqrt(3), A = 1.5, C = 1, mgl = 0.5, "
                 "a = 0.125, b = 0.1 (averaged system (3.4))")
    fig.tight_layout()
    return fig


def fig1_case1_theta5(sol: Solution | None = None) -> Any:
    """Fig. 1: case 1, the top tilted by 5 degrees (see :func:`case_figure`).

    Parameters
    ----------
    sol : Solution, optional
        The averaged run (default: the paper's, :func:`rigidbody.lagrange.paper_solution`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    case_figure : the same for any case.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    fig. 1.

    Examples
    --------
    The paper's case 1, :math:`\\theta_0 = 5` degrees; a shorter run than the paper's (``sol`` is optional):

    >>> from rigidbody import lagrange
    >>> from rigidbody.paperfigs.lagrange import fig1_case1_theta5
    >>> fig = fig1_case1_theta5(lagrange.paper_solution(1, n_out=100, tau_end=5.0))
    >>> lagrange.PAPER_CASES[1], len(fig.axes)  # theta0 in degrees; 2 rows of two panels
    (5.0, 4)
    """
    return case_figure(1, sol)


def fig2_case2_theta60(sol: Solution | None = None) -> Any:
    """Fig. 2: case 2, the top tilted by 60 degrees (see :func:`case_figure`).

    Parameters
    ----------
    sol : Solution, optional
        The averaged run (default: the paper's, :func:`rigidbody.lagrange.paper_solution`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    case_figure : the same for any case.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    fig. 2.

    Examples
    --------
    The paper's case 2, :math:`\\theta_0 = 60` degrees; a shorter run than the paper's (``sol`` is optional):

    >>> from rigidbody import lagrange
    >>> from rigidbody.paperfigs.lagrange import fig2_case2_theta60
    >>> fig = fig2_case2_theta60(lagrange.paper_solution(2, n_out=100, tau_end=5.0))
    >>> lagrange.PAPER_CASES[2], len(fig.axes)  # theta0 in degrees; 2 rows of two panels
    (60.0, 4)
    """
    return case_figure(2, sol)


def fig3_case3_theta170(sol: Solution | None = None) -> Any:
    """Fig. 3: case 3, the top tilted by 170 degrees, nearly hanging (see :func:`case_figure`).

    Parameters
    ----------
    sol : Solution, optional
        The averaged run (default: the paper's, :func:`rigidbody.lagrange.paper_solution`).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    case_figure : the same for any case.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`,
    fig. 3.

    Examples
    --------
    The paper's case 3, :math:`\\theta_0 = 170` degrees; a shorter run than the paper's (``sol`` is optional):

    >>> from rigidbody import lagrange
    >>> from rigidbody.paperfigs.lagrange import fig3_case3_theta170
    >>> fig = fig3_case3_theta170(lagrange.paper_solution(3, n_out=100, tau_end=5.0))
    >>> lagrange.PAPER_CASES[3], len(fig.axes)  # theta0 in degrees; 1 rows of two panels
    (170.0, 2)
    """
    return case_figure(3, sol)


register_figures(
    "lagrange",
    "Figs 1-3: the heavy top under linear drag, averaged (3.4) (Akulenko et al. 1979)",
    {"fig1_case1_theta5": fig1_case1_theta5, "fig2_case2_theta60": fig2_case2_theta60,
     "fig3_case3_theta170": fig3_case3_theta170},
)
