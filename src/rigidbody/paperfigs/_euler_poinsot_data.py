"""The data of Rachinskaya's figures 1-6: the paper's body, drag cases and initial state, and the runs behind
the figures (:mod:`rigidbody.paperfigs.euler_poinsot` draws them and re-exports every name here).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.core.ode import Solution

__all__ = ["drag_tensor", "figure_data", "hodograph_data"]

#: the paper's body (sec. 3)
BODY = ep.Body(3.2, 2.6, 1.67)
#: the drag tensors of the two cases (sec. 3): case 1 has chi < 0, case 2 chi > 0
CASES = {1: np.diag([2.322, 1.31, 1.425]), 2: np.diag([0.919, 5.228, 1.666])}
#: the paper's initial state; nu0 = 0 is our choice
SETUP: dict[str, Any] = dict(G0=1.0, k2_0=0.99, delta0=math.pi / 4, lam0=math.pi / 4, nu0=0.0)
#: slow-time span (our choice)
TAU = (0.0, 6.0)
#: eps of the hodograph figures: the orbit-averaged limit and a small eps within the theory
EPS_MAIN = (0.0, 0.005)
#: eps of :func:`eps_dependence` (0.1 and 0.3 lie outside the theory)
EPS_SCAN = (0.0, 0.01, 0.1, 0.3)


def figure_data(I: np.ndarray, eps: float, num: int = 3001) -> Solution:
    """The averaged solution (9) behind a figure, on ``num`` points of :data:`TAU`.

    For an ``eps`` above the theory's range at the start (spin ratio <= 1) the validity check is switched
    off (``min_spin_ratio=0``) so that the figure shows what the equations do there.

    Parameters
    ----------
    I : numpy.ndarray
        The drag tensor (:data:`CASES`).
    eps : float
        The small parameter (0: the orbit-averaged limit).
    num : int
        Output points on :data:`TAU`.

    Returns
    -------
    Solution
        A run of :func:`rigidbody.euler_poinsot.averaged`.

    See Also
    --------
    hodograph_data : the runs of the paper's figures.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, section 3 (the initial state and the two drag tensors).

    Examples
    --------
    The paper's initial state, :math:`G = 1`, :math:`k^2 = 0.99`, :math:`\\delta = \\lambda = \\pi/4`; in the
    orbit-averaged limit of case 1 the decaying :math:`\\mathbf G` keeps its angle :math:`\\delta` to the
    orbit normal:

    >>> import math
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> sol = figs.figure_data(figs.CASES[1], 0.0, num=61)
    >>> print(sol.G[0], sol.k2[0], sol.delta[0] == sol.lam[0] == math.pi / 4)
    1.0 0.99 True
    >>> print(f"{sol.tau[-1]:.1f} {sol.delta[-1]:.12f} {sol.n[2, -1]:.12f} {math.cos(math.pi / 4):.12f}")
    6.0 0.785398163397 0.707106781187 0.707106781187
    """
    tau_eval = np.linspace(*TAU, num)
    big = eps > 0 and ep.spin_ratio(BODY, eps, SETUP["G0"], SETUP["k2_0"]) <= 1.0
    return ep.averaged(BODY, I, eps, tau_span=TAU, tau_eval=tau_eval, min_spin_ratio=0.0 if big else 1.0, **SETUP)


def hodograph_data(case: int) -> dict[float, Solution]:
    """The runs of figures 1-3 (``case=1``) or 4-6 (``case=2``): ``{eps: Solution}`` for :data:`EPS_MAIN`.

    Parameters
    ----------
    case : {1, 2}
        The paper's drag case.

    Returns
    -------
    dict of float to Solution

    See Also
    --------
    figure_data : one run.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, section 3 and figs 1-6.

    Examples
    --------
    The orbit-averaged limit and a small eps within the theory (our choices: the paper gives no eps):

    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> runs = figs.hodograph_data(2)
    >>> sorted(runs), runs[0.005].status  # case 2 stays fast to tau = 6
    ([0.0, 0.005], 0)
    """
    return {eps: figure_data(drag_tensor(case), eps) for eps in EPS_MAIN}


def drag_tensor(case: int) -> np.ndarray:
    """The drag tensor of the paper's case 1 or 2 (:data:`CASES`), checked.

    Parameters
    ----------
    case : {1, 2}
        The paper's drag case.

    Returns
    -------
    numpy.ndarray
        The 3x3 drag tensor I.

    Raises
    ------
    ValueError
        If ``case`` is not 1 or 2.

    Examples
    --------
    >>> from rigidbody.paperfigs import euler_poinsot as figs
    >>> figs.drag_tensor(2).diagonal().tolist()
    [0.919, 5.228, 1.666]
    >>> figs.drag_tensor(3)
    Traceback (most recent call last):
    ...
    ValueError: case must be 1 or 2, got 3
    """
    if case not in CASES:
        raise ValueError(f"case must be 1 or 2, got {case!r}")
    return CASES[case]
