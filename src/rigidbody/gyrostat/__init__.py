"""Stationary motions of a gyrostat satellite and their stability by Routh's method.

After S. Ya. Stepanov, "On stationary motions of a gyrostat satellite", PMM 32 (1968).  The problem
is the unrestricted one: the orbit radius R and the latitude kappa of the centre of mass are
coordinates, so the plane of the circular orbit of a stationary motion may be displaced from the
attracting centre (kappa0 != 0, of order l^2/R^2).

Public API
----------
``Satellite``
    frozen dataclass (M, A1, A2, A3, mu, k1, k2, k3), validated.
``stationary_motion(sat, R0, theta0, k2=.. | k3=.., omega_sign=+1)``
    the family (2.3)-(2.4).
``symmetric_stationary_motion(sat, R0, theta0)``
    section 3, (3.2)-(3.3).
``symmetric_stability_map(sat, R0, theta0, A3=...)``
    section 3 verdicts over grids.
``stability(sat, motion)``
    Sylvester quantities s1, s2, s3 of (2.5), degree of instability and a verdict 'stable' /
    'unstable' / 'undecided'; section-4 Jacobian.
``stability_map(sat, R0, theta0, k2=.. | k3=..)``
    vectorised verdicts over parameter grids.
``exact_boundaries(sat, R0, theta0)``
    s2 = 0, s3 = 0 and the restricted boundaries as k2(theta0).
``normalized_stability_map(sat, R0, theta0, u)``
    the same in the plane (theta0, u = k2 / (omega0 Abar)).
``amended_potential``, ``amended_potential_W``, ``chi``, ``gradient_W1``
    W, (2.1), W1 = W + lambda chi, (2.2).
``hessian_W1``, ``hessian_W1_numerical``
    the second variation of W1 in closed form and by finite differences.
``constrained_second_variation``, ``restricted_conditions``
    the second variation on the constraint, and the conditions of the restricted problem.
``symmetric_potential``, ``gradient_W_sym``, ``hessian_W_sym``, ``W_psipsi_34``, ``W_thetatheta_stable``
    the axisymmetric case of section 3.
``simulate(sat, motion, t_span)``, ``initial_state``
    full Newton-Euler equations (validation route).
"""

from __future__ import annotations

from ._dynamics import initial_state, simulate
from ._maps import StabilityMap, exact_boundaries, normalized_stability_map, stability_map
from ._model import GyrostatWarning, Satellite
from ._potential import amended_potential, amended_potential_W, chi, gradient_W1
from ._secondvar import CONSTRAINED_COORDS, COORDS, restricted_conditions
from ._stability import (
    Stability,
    constrained_second_variation,
    constraint_gradient,
    hessian_W1,
    hessian_W1_numerical,
    stability_triaxial,
)
from ._stationary import StationaryMotion, stationary_motion
from ._symmetric import (
    SYM_COORDS,
    SymmetricMotion,
    gradient_W_sym,
    hessian_W_sym,
    symmetric_potential,
    symmetric_stationary_motion,
)
from ._symmetric_map import SymmetricStabilityMap, symmetric_stability_map
from ._symmetric_stability import SymmetricStability, W_psipsi_34, W_thetatheta_stable, stability_symmetric


def stability(
    sat: Satellite, motion: StationaryMotion | SymmetricMotion, *, rtol: float = 1e-12
) -> Stability | SymmetricStability:
    """Stability of a stationary motion by Routh's method (sections 2-4).

    Parameters
    ----------
    sat : Satellite
        The satellite (its mass properties must be those the motion was computed for).
    motion : StationaryMotion or SymmetricMotion
    rtol : float
        Zero-eigenvalue threshold of the equilibrated second variation.

    Returns
    -------
    Stability (for (2.3)) or SymmetricStability (for (3.2)); both carry ``degree``, ``nullity``,
    ``verdict``, ``minors``, ``jacobian`` and ``unconditionally_stable``.

    See Also
    --------
    stationary_motion, symmetric_stationary_motion : the motions.
    stability_map, symmetric_stability_map : verdicts over grids.
    constrained_second_variation : the form whose signs decide.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5) and sections 3-4.

    Examples
    --------
    Stable where the restricted problem's inequalities (after (2.5)) hold, for a body with
    :math:`l = 0.1R_0`; and, by section 4, also under perturbations of the area constant:

    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> st = gyrostat.stability(m.satellite, m)
    >>> st.verdict, st.degree, st.restricted_verdict, st.unconditionally_stable
    ('stable', 0, True, True)

    With :math:`k_2 = 0` the third restricted inequality fails and the degree of instability is odd:

    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.0)
    >>> st = gyrostat.stability(m.satellite, m)
    >>> st.verdict, st.degree, st.restricted_verdict
    ('unstable', 1, False)
    """
    if isinstance(motion, StationaryMotion):
        return stability_triaxial(sat, motion, rtol=rtol)
    if isinstance(motion, SymmetricMotion):
        return stability_symmetric(sat, motion, rtol=rtol)
    raise TypeError(f"motion must be a StationaryMotion or SymmetricMotion; got {type(motion).__name__}")


__all__ = [
    "CONSTRAINED_COORDS",
    "COORDS",
    "SYM_COORDS",
    "GyrostatWarning",
    "Satellite",
    "Stability",
    "StabilityMap",
    "StationaryMotion",
    "SymmetricMotion",
    "SymmetricStability",
    "SymmetricStabilityMap",
    "W_psipsi_34",
    "W_thetatheta_stable",
    "amended_potential",
    "amended_potential_W",
    "chi",
    "constrained_second_variation",
    "constraint_gradient",
    "exact_boundaries",
    "gradient_W1",
    "gradient_W_sym",
    "hessian_W1",
    "hessian_W1_numerical",
    "hessian_W_sym",
    "initial_state",
    "normalized_stability_map",
    "restricted_conditions",
    "simulate",
    "stability",
    "stability_map",
    "stationary_motion",
    "symmetric_potential",
    "symmetric_stability_map",
    "symmetric_stationary_motion",
]
