"""Figures 1-6 of Rachinskaya: the hodograph of the angular momentum; G, T, k², δ, λ against τ.

The paper's setup (sec. 3): A = (3.2, 2.6, 1.67), G(0) = 1, k²(0) = 0.99, δ(0) = λ(0) = π/4, drag
I = diag(2.322, 1.31, 1.425) (case 1, χ < 0: figs 1-3) and diag(0.919, 5.228, 1.666) (case 2, χ > 0:
figs 4-6). Fig. 1 (4) is the 3-D hodograph in the orbital axes Ox1x2x3, fig. 2 (5) its projection on the
orbit plane Ox1x2, fig. 3 (6) the view along the spiral axis; figs 2, 3, 5, 6 are "at a larger scale".

The paper states neither ε, ν0 nor the end time. Our choices (also in :doc:`/euler_poinsot`): ν0 = 0,
τ ∈ [0, 6]; the hodographs show the orbit-averaged limit ε = 0 and ε = 0.005 (ν kept; in case 1 that run
ends at τ = 4.77 when the decaying rotation is no longer fast, spin ratio = 1; in case 2 it stays fast to
τ = 6). "Larger scale" is an inset magnifying the inner turns. "Along the spiral axis" is read both ways:
looking down the axis (the projection on the plane normal to it) and the spiral laid along it (distance
from the axis against the height along it, where a straight axis gives a straight line). The axis is
the one of the best-fitting cone (:func:`rigidbody.plotting.spiral_axis`). A separate figure
(:func:`eps_dependence`) shows how the picture depends on ε, including ε = 0.1 and 0.3, integrated with the
validity check switched off (``min_spin_ratio=0``) to show what the equations do outside the theory
(the drift of δ and the bent spiral the paper describes).
"""

from __future__ import annotations

from typing import Any

from rigidbody.core.ode import Solution
from rigidbody.paperfigs import register_figures
from rigidbody.paperfigs._euler_poinsot_data import BODY as BODY
from rigidbody.paperfigs._euler_poinsot_data import CASES as CASES
from rigidbody.paperfigs._euler_poinsot_data import EPS_MAIN as EPS_MAIN
from rigidbody.paperfigs._euler_poinsot_data import EPS_SCAN as EPS_SCAN
from rigidbody.paperfigs._euler_poinsot_data import SETUP as SETUP
from rigidbody.paperfigs._euler_poinsot_data import TAU as TAU
from rigidbody.paperfigs._euler_poinsot_data import drag_tensor as drag_tensor
from rigidbody.paperfigs._euler_poinsot_data import figure_data, hodograph_data
from rigidbody.paperfigs._euler_poinsot_draw import (
    eps_dependence,
    hodograph_figure,
    projection_figure,
    slow_variables_figure,
    spiral_axis_figure,
)

__all__ = [
    "eps_dependence",
    "fig1_hodograph_case1",
    "fig2_projection_case1",
    "fig3_spiral_axis_case1",
    "fig4_hodograph_case2",
    "fig5_projection_case2",
    "fig6_spiral_axis_case2",
    "figure_data",
    "hodograph_data",
    "hodograph_figure",
    "projection_figure",
    "slow_variables_case1",
    "slow_variables_case2",
    "slow_variables_figure",
    "spiral_axis_figure",
]


def fig1_hodograph_case1(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 1: the hodograph of G, case 1 (:func:`hodograph_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 1).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    hodograph_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 1.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig1_hodograph_case1(sols)
    >>> fig.axes[0].get_title()  # chi: printed -4.477, see the errata page
    'Fig. 1: hodograph of G, case 1 (χ = -4.474)'
    """
    return hodograph_figure(1, sols)


def fig2_projection_case1(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 2: its projection on the orbit plane Ox1x2 (:func:`projection_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 1).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    projection_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 2.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig2_projection_case1(sols)
    >>> fig.get_suptitle()
    'Fig. 2: projection on the orbit plane $Ox_1x_2$, case 1 (χ = -4.474)'
    """
    return projection_figure(1, sols)


def fig3_spiral_axis_case1(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 3: the view along the spiral axis, case 1 (:func:`spiral_axis_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 1).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    spiral_axis_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 3.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig3_spiral_axis_case1(sols)
    >>> fig.get_suptitle()[:43]
    'Fig. 3: view along the spiral axis (0.0000,'
    """
    return spiral_axis_figure(1, sols)


def fig4_hodograph_case2(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 4: the hodograph of G, case 2 (:func:`hodograph_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 2).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    hodograph_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 4.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[2], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig4_hodograph_case2(sols)
    >>> fig.axes[0].get_title()  # chi: printed 3.853
    'Fig. 4: hodograph of G, case 2 (χ = 3.852)'
    """
    return hodograph_figure(2, sols)


def fig5_projection_case2(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 5: its projection on the orbit plane Ox1x2 (:func:`projection_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 2).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    projection_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 5.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[2], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig5_projection_case2(sols)
    >>> fig.get_suptitle()
    'Fig. 5: projection on the orbit plane $Ox_1x_2$, case 2 (χ = 3.852)'
    """
    return projection_figure(2, sols)


def fig6_spiral_axis_case2(sols: dict[float, Solution] | None = None) -> Any:
    """Fig. 6: the view along the spiral axis, case 2 (:func:`spiral_axis_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 2).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    spiral_axis_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 6.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[2], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.fig6_spiral_axis_case2(sols)
    >>> fig.get_suptitle()[:43]
    'Fig. 6: view along the spiral axis (0.0000,'
    """
    return spiral_axis_figure(2, sols)


def slow_variables_case1(sols: dict[float, Solution] | None = None) -> Any:
    """Beyond the paper: G, T, k², δ, λ against τ, case 1 (:func:`slow_variables_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 1).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    slow_variables_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 1-3.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[1], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.slow_variables_case1(sols)
    >>> len(fig.axes)
    5
    """
    return slow_variables_figure(1, sols)


def slow_variables_case2(sols: dict[float, Solution] | None = None) -> Any:
    """Beyond the paper: G, T, k², δ, λ against τ, case 2 (:func:`slow_variables_figure`).

    Parameters
    ----------
    sols : dict of float to Solution, optional
        ``{eps: run}`` (default :func:`hodograph_data` of case 2).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    slow_variables_figure : the same for either case.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, fig. 4-6.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sols = {0.0: figs.figure_data(figs.CASES[2], 0.0, num=61)}  # the orbit-averaged run only, 61 points
    >>> fig = figs.slow_variables_case2(sols)
    >>> len(fig.axes)
    5
    """
    return slow_variables_figure(2, sols)


register_figures(
    "euler_poinsot",
    "Figs 1-6: hodograph of G under gravity-gradient and drag torques (Rachinskaya)",
    {
        "fig1_hodograph_case1": fig1_hodograph_case1,
        "fig2_projection_case1": fig2_projection_case1,
        "fig3_spiral_axis_case1": fig3_spiral_axis_case1,
        "fig4_hodograph_case2": fig4_hodograph_case2,
        "fig5_projection_case2": fig5_projection_case2,
        "fig6_spiral_axis_case2": fig6_spiral_axis_case2,
        "slow_variables_case1": slow_variables_case1,
        "slow_variables_case2": slow_variables_case2,
        "eps_dependence": eps_dependence,
    },
)
