r"""Perturbed motions of a heavy symmetric top close to the Lagrange case.

After L. D. Akulenko, D. D. Leshchenko, F. L. Chernousko, "Perturbed motions of a rigid body close to
the Lagrange case", PMM 43(5), 1979 (equation numbers refer to it). Theory page: :doc:`/lagrange`.

Unperturbed motion (Sec. 1)
    :class:`Top`, :func:`integrals` (1.2), :func:`roots` of Q(u) (1.5), :func:`vieta` (1.6),
    :func:`from_roots` (2.8), :func:`deltas`, :func:`lagrange_motion` (u(t) (1.3)-(1.4); phi, psi by (1.7)),
    :func:`nutation_frequency`.
Torques (Sec. 2-3)
    :class:`Torque` (protocol), :class:`ProportionalTorque` (2.4), :class:`VerticalPlaneTorque` (2.5),
    :class:`StarTorque` (2.2), :class:`LinearDrag` (3.1); :func:`has_closed_form` (a torque's closed-form
    average, its ``closed_means``).
Averaging (Sec. 2-3)
    :func:`averaged_rhs` (2.15)-(2.16), :func:`V_matrix` (2.13), :func:`averaged_slow_rates` (averaged
    (2.7)), :func:`drag_rhs` (closed form (3.4)), :func:`nutation_mean`, :func:`modulus`.
Integration
    :func:`averaged` (slow time tau = eps t, u chart with sign switching), :func:`simulate` (full (1.1),
    quaternion inside); both take batches of initial states (integrated together, per-member status).
Paper cases (Sec. 3, figs 1-3)
    :data:`PAPER_TOP`, :data:`PAPER_DRAG`, :data:`PAPER_TABLE`, :func:`paper_initial_state`,
    :func:`paper_solution`.
"""

from ._averaging import (
    V_matrix,
    averaged_rhs,
    averaged_slow_rates,
    drag_rhs,
    modulus,
    nutation_mean,
)
from ._integrate import averaged, simulate
from ._motion import lagrange_motion, nutation_frequency
from ._paper import (
    PAPER_CASES,
    PAPER_DRAG,
    PAPER_R0,
    PAPER_TABLE,
    PAPER_TAU_END,
    PAPER_TOP,
    paper_initial_state,
    paper_solution,
)
from ._top import Top, cubic_coefficients, deltas, from_roots, integrals, root_radical, roots, vieta
from ._torques import LinearDrag, ProportionalTorque, StarTorque, Torque, VerticalPlaneTorque, has_closed_form

__all__ = [
    "PAPER_CASES",
    "PAPER_DRAG",
    "PAPER_R0",
    "PAPER_TABLE",
    "PAPER_TAU_END",
    "PAPER_TOP",
    "LinearDrag",
    "ProportionalTorque",
    "StarTorque",
    "Top",
    "Torque",
    "V_matrix",
    "VerticalPlaneTorque",
    "averaged",
    "averaged_rhs",
    "averaged_slow_rates",
    "cubic_coefficients",
    "deltas",
    "drag_rhs",
    "from_roots",
    "has_closed_form",
    "integrals",
    "lagrange_motion",
    "modulus",
    "nutation_frequency",
    "nutation_mean",
    "paper_initial_state",
    "paper_solution",
    "root_radical",
    "roots",
    "simulate",
    "vieta",
]
