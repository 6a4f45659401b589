r"""The three computed cases of Akulenko, Leshchenko, Chernousko (1979), Sec. 3 (figs 1-3).

A top with ``A = 1.5, C = 1, mgl = 0.5`` under linear drag ``a = 0.125, b = 0.1``, spun about its
symmetry axis with ``r0 = sqrt(3)`` and tilted by ``theta0 = 5, 60, 170`` degrees. The paper does not
state the integration spans; we use ``tau in [0, 150]`` for cases 1, 2 (``xi = ln(1 + tau)`` up to
about 5, where the approach to the lower equilibrium is visible) and ``tau in [0, 60]`` for case 3.
"""

from __future__ import annotations

import math

import numpy as np

from ..core.ode import Solution
from ._integrate import averaged
from ._top import Top, integrals
from ._torques import LinearDrag

__all__ = [
    "PAPER_CASES",
    "PAPER_DRAG",
    "PAPER_R0",
    "PAPER_TABLE",
    "PAPER_TAU_END",
    "PAPER_TOP",
    "paper_initial_state",
    "paper_solution",
]

PAPER_TOP = Top(A=1.5, C=1.0, mgl=0.5)
PAPER_DRAG = LinearDrag(a=0.125, b=0.1)
PAPER_R0 = math.sqrt(3.0)
#: case -> theta0 in degrees
PAPER_CASES = {1: 5.0, 2: 60.0, 3: 170.0}
#: the printed table of initial roots (u1, u2, u3), 3 decimals
PAPER_TABLE = {1: (0.913, 0.996, 1.087), 2: (0.0, 0.5, 2.0), 3: (-0.992, -0.985, 2.992)}
#: our choice of slow-time spans (not stated in the paper)
PAPER_TAU_END = {1: 150.0, 2: 150.0, 3: 60.0}


def paper_initial_state(case: int) -> tuple[float, float, float, float, float, float]:
    """Initial ``(p, q, r, phi, theta, psi)`` of the paper's case 1, 2 or 3.

    Section 3 (figs 1-3): the top is spun about its symmetry axis, ``p = q = 0``, ``r = r0 = sqrt(3)``,
    tilted by ``theta0`` = 5, 60 or 170 degrees (:data:`PAPER_CASES`); its roots of (1.5) are those of
    :data:`PAPER_TABLE`.

    Parameters
    ----------
    case : {1, 2, 3}
        Case number of the paper.

    Returns
    -------
    tuple of 6 floats
        ``(p, q, r, phi, theta, psi)``: body angular velocity in the paper's units of :data:`PAPER_TOP`
        (``A = 1.5, C = 1, mgl = 0.5``) and 3-1-3 Euler angles in radians, ready for
        :func:`~rigidbody.lagrange.integrals` and :func:`~rigidbody.lagrange.simulate`.

    Raises
    ------
    ValueError
        If ``case`` is not 1, 2 or 3.

    See Also
    --------
    paper_solution : the averaged solution from this state.
    integrals : its first integrals (1.2).

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, section 3.

    Examples
    --------
    Case 2 is spun at ``r0 = sqrt(3)`` and tilted by 60 degrees; its roots are the paper's ``(0, 0.5, 2)``:

    >>> import math
    >>> from rigidbody import lagrange
    >>> p, q, r, phi, theta, psi = lagrange.paper_initial_state(2)
    >>> print(f"{r:.6f} {math.degrees(theta):.6f}")
    1.732051 60.000000
    >>> lagrange.PAPER_TABLE[2]
    (0.0, 0.5, 2.0)
    """
    if case not in PAPER_CASES:
        raise ValueError(f"case must be 1, 2 or 3, got {case!r}")
    return (0.0, 0.0, PAPER_R0, 0.0, math.radians(PAPER_CASES[case]), 0.0)


def paper_solution(case: int, n_out: int = 1501, tau_end: float | None = None) -> Solution:
    """Averaged solution (3.4) of case 1, 2 or 3 on a uniform grid of ``n_out`` slow times.

    The first-approximation system (2.15) for linear drag (3.1), :data:`PAPER_DRAG`, in its closed form
    (3.4), integrated by :func:`~rigidbody.lagrange.averaged` from the integrals (1.2) of
    :func:`paper_initial_state`; the data of the paper's figs 1-3.

    Parameters
    ----------
    case : {1, 2, 3}
        Case number of the paper.
    n_out : int
        Number of output points, uniform in ``tau`` on ``[0, tau_end]``.
    tau_end : float, optional
        End of the slow time ``tau = eps t`` (default :data:`PAPER_TAU_END`: 150 for cases 1, 2 and 60
        for case 3; the paper does not state its spans).

    Returns
    -------
    rigidbody.core.ode.Solution
        As returned by :func:`~rigidbody.lagrange.averaged` (roots ``u1, u2, u3``, integrals ``Gz, H, r``,
        signs ``delta1, delta2`` and ``chart`` against ``tau``). A terminal event may end it before
        ``tau_end``.

    Raises
    ------
    ValueError
        If ``case`` is not 1, 2 or 3.

    See Also
    --------
    averaged : the integrator it calls.
    paper_initial_state : the initial states.

    References
    ----------
    :ref:`L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, PMM 43 (1979) <ref-alc-1979>`, eqs. (3.3)-(3.4), figs 1-3.

    Examples
    --------
    The spin follows ``r = r0 exp(-b tau / C)`` (3.3) exactly: at ``tau = 10``, ``sqrt(3)/e``; the
    roots start at the paper's table ``(0, 0.5, 2)``:

    >>> import math
    >>> from rigidbody import lagrange
    >>> sol = lagrange.paper_solution(2, n_out=11, tau_end=10.0)
    >>> print(f"{sol.r[-1]:.6f} {math.sqrt(3) / math.e:.6f}")
    0.637186 0.637186
    >>> print(f"{sol.u2[0]:.6f} {sol.u3[0]:.6f}")
    0.500000 2.000000
    """
    state = paper_initial_state(case)
    T = PAPER_TAU_END[case] if tau_end is None else float(tau_end)
    ini = integrals(PAPER_TOP, *state[:5])
    return averaged(PAPER_TOP, PAPER_DRAG, ini, (0.0, T), tau_eval=np.linspace(0.0, T, n_out))
