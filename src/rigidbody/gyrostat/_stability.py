"""Stability of one stationary motion (2.3): the Hessian of W1 (closed form and by differences), the constrained
second variation and Routh's verdict with the Sylvester quantities (2.5) (sections 2, 4)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._family import SINGULAR_TOL, family_side
from ._model import Satellite
from ._secondvar import (
    VERDICTS,
    a_matrix,
    hessian_entries,
    hessian_matrix,
    restricted_conditions,
    second_variation_side,
    verdicts,
)
from ._stationary import StationaryMotion

__all__ = [
    "Stability",
    "constrained_second_variation",
    "constraint_gradient",
    "hessian_W1",
    "hessian_W1_numerical",
    "stability_triaxial",
]


def hessian_W1(sat: Satellite, m: StationaryMotion, *, form: str = "stable") -> np.ndarray:
    """The 6x6 Hessian of W1 at the motion ``m`` from the closed forms (order :data:`COORDS`).

    ``form``: "stable" (default) or "printed", see :func:`hessian_entries`. The twelve nonzero entries are
    those printed in section 2 after (2.4), evaluated at the motion (2.3); they feed the second variation
    (2.5) (:func:`constrained_second_variation`).

    Parameters
    ----------
    sat : Satellite
        Must have the mass properties (``M, A1, A2, A3, mu``) the motion was computed for.
    m : StationaryMotion
        A member of the family (2.3)-(2.4), from :func:`~rigidbody.gyrostat.stationary_motion`.
    form : {"stable", "printed"}
        ``"printed"``: the paper's expressions literally; ``"stable"``: without the O(l^2/R^2)
        cancellation of ``W_g2g2`` (third relation (2.4)); equal values in exact arithmetic.

    Returns
    -------
    ndarray, shape (6, 6)
        Symmetric matrix of ``d^2 W1 / dx_i dx_j`` in the order :data:`COORDS`
        ``(R, kappa, beta1, beta3, gamma1, gamma2)``, in the units of ``sat``: W1 is an energy, so ``W_RR``
        is energy/length^2, the other entries of the R row energy/length, all the rest energy.

    Raises
    ------
    TypeError
        If ``sat`` is not a :class:`Satellite` or ``m`` not a :class:`StationaryMotion`.
    ValueError
        If ``form`` is unknown or ``sat`` differs from ``m.satellite`` in ``M, A1, A2, A3, mu``.

    See Also
    --------
    hessian_W1_numerical : the same by finite differences of W1.
    constrained_second_variation : the second variation on the constraint (2.1).

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 2 (the second derivatives printed after (2.4)).

    Examples
    --------
    The closed forms agree with the finite differences of W1, and the printed and the stable forms agree:

    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> H = gyrostat.hessian_W1(m.satellite, m)
    >>> np.allclose(H, gyrostat.hessian_W1_numerical(m.satellite, m), rtol=0, atol=1e-8)
    True
    >>> np.allclose(H, gyrostat.hessian_W1(m.satellite, m, form="printed"), rtol=0, atol=1e-14)
    True
    """
    _check_same_body(sat, m)
    e = hessian_entries(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, m.R0, m.theta0, m.kappa0, m.omega0, m.k2, m.S0,
                        form=form)
    return hessian_matrix(e)


def hessian_W1_numerical(sat: Satellite, m: StationaryMotion, *, h: float | None = None) -> np.ndarray:
    """The 6x6 Hessian of W1 at ``m`` by 8th-order central differences of :func:`amended_potential`.

    An independent float64 route for nondimensional problems (M = mu = R0 = 1 and l/R not too small):
    its round-off is ~ eps abs(W1) / h^2, so in SI units (abs(W1) ~ 1e11 next to entries ~ 1e-3) it is useless
    -- evaluate W1 with ``lib=mpmath`` there (as the tests do).  ``h`` defaults to 1e-3 times the
    natural scale of each coordinate (R0 for R, 1 for the angles and direction cosines).

    The finite-difference counterpart of :func:`hessian_W1` (the second derivatives printed after (2.4),
    at the motion (2.3)).

    Parameters
    ----------
    sat : Satellite
        Must have the mass properties the motion was computed for (W1 itself is evaluated with
        ``m.satellite``, which carries the motion's ``k2, k3``).
    m : StationaryMotion
        A member of the family (2.3)-(2.4).
    h : float, optional
        Relative step: the step of each coordinate is ``h`` times its natural scale (default 1e-3).

    Returns
    -------
    ndarray, shape (6, 6)
        Hessian of W1 in the order :data:`COORDS` ``(R, kappa, beta1, beta3, gamma1, gamma2)``, in the
        units of ``sat``.

    Raises
    ------
    TypeError
        If ``sat`` is not a :class:`Satellite` or ``m`` not a :class:`StationaryMotion`.
    ValueError
        If ``sat`` differs from ``m.satellite`` in ``M, A1, A2, A3, mu``.

    See Also
    --------
    hessian_W1 : the closed forms.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, section 2 (the second derivatives printed after (2.4)).

    Examples
    --------
    Round-off ~ eps abs(W1) / h^2 and truncation O(h^8): with ``h = 1e-3`` about 1e-10 next to entries of
    order 1:

    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> H = gyrostat.hessian_W1_numerical(m.satellite, m)
    >>> bool(np.abs(H - gyrostat.hessian_W1(m.satellite, m)).max() < 1e-8)
    True
    """
    from ..core.quadform import hessian_fd
    from ._potential import amended_potential

    _check_same_body(sat, m)

    steps = np.array([m.R0, 1, 1, 1, 1, 1]) * (1e-3 if h is None else h)
    return hessian_fd(lambda x: float(amended_potential(m.satellite, x, k=m.k, lam=m.lambda0, branch=m.branch)),
                      np.array(m.point), steps)


def constraint_gradient(m: StationaryMotion) -> np.ndarray:
    """Gradient of chi (2.1) at (2.3) w.r.t. :data:`COORDS`: cos kappa0 (0, -1, 0, 1/cos(theta0+kappa0), 0,
    1/cos theta0).

    Its null space is the tangent space of the constraint used in the second variation (2.5):
    ``delta gamma2 = cos theta0 delta kappa - cos theta0 / cos(theta0 + kappa0) delta beta3``.

    Parameters
    ----------
    m : StationaryMotion
        A member of the family (2.3)-(2.4) (only ``theta0`` and ``kappa0`` enter).

    Returns
    -------
    ndarray, shape (6,)
        ``d chi / dx`` in the order ``(R, kappa, beta1, beta3, gamma1, gamma2)``; the R entry is 0, the
        others are dimensionless (per radian for kappa). The beta3 and gamma2 entries are unbounded as
        ``cos(theta0 + kappa0)`` or ``cos theta0`` tends to 0 (the chart is singular there).

    See Also
    --------
    chi : the constraint itself.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eqs. (2.1) and (2.5).

    Examples
    --------
    The closed form is the complex-step gradient of :func:`chi` at the motion:

    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> from rigidbody.core.quadform import gradient_cs
    >>> G = gyrostat.constraint_gradient(m)
    >>> np.allclose(G, gradient_cs(lambda z: gyrostat.chi(z, branch=m.branch), m.point), rtol=0, atol=1e-14)
    True
    """
    ck = np.cos(m.kappa0)
    return ck * np.array([0.0, -1.0, 0.0, 1.0 / np.cos(m.theta0 + m.kappa0), 0.0, 1.0 / np.cos(m.theta0)])


def constrained_second_variation(sat: Satellite, m: StationaryMotion) -> np.ndarray:
    """delta^2 W1 after substituting delta gamma2 from (2.1), 5x5 in the order :data:`CONSTRAINED_COORDS`.

    Block diagonal: ``[[W_g1g1, W_b1g1], [W_b1g1, W_b1b1]]`` and the a_ij of (2.5).
    The Sylvester quantities of (2.5) are ``s1 = Hc[0, 0]``, ``s2 = det Hc[:2, :2]`` and
    ``s3 = det Hc[2:, 2:]``. Entries from the stable form of :func:`hessian_W1`.

    Parameters
    ----------
    sat : Satellite
        Must have the mass properties the motion was computed for.
    m : StationaryMotion
        A member of the family (2.3)-(2.4).

    Returns
    -------
    ndarray, shape (5, 5)
        The constrained second variation ``Hc`` in the order :data:`CONSTRAINED_COORDS`
        ``(gamma1, beta1, R, kappa, beta3)``, in the units of ``sat``. Not checked for the singular chart
        ``cos theta0 = 0`` or ``cos(theta0 + kappa0) = 0``, where entries blow up (:func:`stability`
        refuses such motions).

    See Also
    --------
    stability : its signs, the verdict.
    rigidbody.core.quadform.null_space_form : the same form in an orthonormal basis of the tangent space.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5).

    Examples
    --------
    The Sylvester quantities of :func:`stability` are its minors, and its inertia is that of the
    Hessian restricted to the tangent space of (2.1) in any other basis:

    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> Hc = gyrostat.constrained_second_variation(m.satellite, m)
    >>> st = gyrostat.stability(m.satellite, m)
    >>> print(f"{Hc[0, 0]:.9f} {st.s1:.9f} | {np.linalg.det(Hc[2:, 2:]):.9f} {st.s3:.9f}")
    0.011473161 0.011473161 | 0.029975940 0.029975940
    >>> from rigidbody.core.quadform import inertia, null_space_form
    >>> Hz = null_space_form(gyrostat.hessian_W1(m.satellite, m), gyrostat.constraint_gradient(m))
    >>> [int(n) for n in inertia(Hc)], [int(n) for n in inertia(Hz)]
    ([5, 0, 0], [5, 0, 0])

    Raises
    ------
    TypeError
        If ``sat`` is not a :class:`Satellite` or ``m`` not a :class:`StationaryMotion`.
    ValueError
        If ``sat`` differs from ``m.satellite`` in ``M, A1, A2, A3, mu``.
    """
    _check_same_body(sat, m)
    e = hessian_entries(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, m.R0, m.theta0, m.kappa0, m.omega0, m.k2, m.S0)
    a = a_matrix(e, m.theta0, m.kappa0)
    Hc = np.zeros((5, 5))
    Hc[0, 0], Hc[0, 1], Hc[1, 0], Hc[1, 1] = e["g1g1"], e["b1g1"], e["b1g1"], e["b1b1"]
    Hc[2:, 2:] = a
    return Hc


@dataclass(frozen=True)
class Stability:
    r"""Stability of a stationary motion (2.3) by Routh's method.

    Attributes
    ----------
    s1, s2, s3 : float
        The Sylvester quantities of (2.5): ``s1 = W_g1g1``, ``s2 = W_g1g1 W_b1b1 - W_b1g1^2``,
        ``s3 = det a``.
    a : ndarray (3, 3)
        The a_ij of (2.5).
    minors : ndarray (5,)
        All leading principal minors of the constrained second variation in the order
        (gamma1, beta1, R, kappa, beta3): ``s1, s2, s2 a11, s2 (a11 a22 - a12^2), s2 s3``.  The paper
        lists only s1, s2, s3; a11 > 0 and a11 a22 > a12^2 hold for l << R but are checked here.
    degree : int
        Degree of instability: number of negative eigenvalues of the constrained second variation.
    nullity : int
        Number of (numerically) zero eigenvalues.
    verdict : {'stable', 'unstable', 'undecided'}
        'stable': positive definite (Routh; sufficient, conditional on the unperturbed area constant);
        'unstable': odd degree and nondegenerate (Kelvin--Chetaev: gyroscopic forces cannot
        stabilise); 'undecided': even positive degree or a degenerate form.
    jacobian : float
        Jacobian of the system (2.1), (2.2) in (R, kappa, beta1, beta3, gamma1, gamma2, lambda),
        i.e. the bordered Hessian ``-(cos^2 kappa0 / cos^2 theta0) s2 s3`` (section 4; the paper
        prints it without the minus sign).
    unconditionally_stable : bool
        Stable and jacobian != 0: Lyapunov's addendum to Routh's theorem applies, so the motion is
        stable also under perturbations of the area constant k (section 4).
    restricted : tuple (r1, r2, r3)
        The restricted-problem quantities (see :func:`restricted_conditions`).

    See Also
    --------
    stability : the function that returns it.
    StabilityMap : the same quantities over a grid.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5) and section 4.

    Examples
    --------
    The Jacobian of section 4 is :math:`-(\cos^2\kappa_0/\cos^2\theta_0)s_2s_3`:

    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> st = gyrostat.stability(m.satellite, m)
    >>> c = np.cos(m.kappa0)**2 / np.cos(m.theta0)**2
    >>> print(st.verdict, st.degree, f"{st.jacobian:.6e} {-c * st.s2 * st.s3:.6e}")
    stable 0 -7.268827e-06 -7.268827e-06
    """

    s1: float
    s2: float
    s3: float
    a: np.ndarray
    minors: np.ndarray
    degree: int
    nullity: int
    verdict: str
    jacobian: float
    unconditionally_stable: bool
    restricted: tuple[float, float, float]

    @property
    def restricted_verdict(self) -> bool:
        r"""True when all three restricted-problem inequalities hold.

        Examples
        --------
        For a body with :math:`l \ll R_0` it agrees with the verdict of (2.5) away from the boundaries:

        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> for k2 in (0.0, 0.02):
        ...     m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=k2)
        ...     st = gyrostat.stability(m.satellite, m)
        ...     print(k2, st.verdict, st.restricted_verdict)
        0.0 unstable False
        0.02 stable True
        """
        return all(r > 0 for r in self.restricted)


def _check_same_body(sat: Satellite, m: StationaryMotion) -> None:
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    if not isinstance(m, StationaryMotion):
        raise TypeError(f"m must be a StationaryMotion (from stationary_motion); got {type(m).__name__}")
    for name in ("M", "A1", "A2", "A3", "mu"):
        if getattr(sat, name) != getattr(m.satellite, name):
            raise ValueError(f"sat.{name} differs from the satellite the motion was computed for")


def stability_triaxial(sat: Satellite, m: StationaryMotion, *, rtol: float = 1e-12) -> Stability:
    _check_same_body(sat, m)
    if abs(np.cos(m.theta0)) < SINGULAR_TOL or abs(np.cos(m.theta0 + m.kappa0)) < SINGULAR_TOL:
        raise ValueError(
            "the chart (beta1, beta3, gamma1, gamma2) is singular at cos(theta0) = 0 or "
            "cos(theta0 + kappa0) = 0 (|cos| < 1e-6 here): the second variation (2.5) is not defined"
        )
    # the motion's own closed forms, evaluated exactly as stability_map does (same verdict at the same point)
    f = family_side(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, m.R0, m.theta0, 1.0 if m.omega0 >= 0 else -1.0)
    d = second_variation_side(f, sat.M, sat.A1, sat.A2, sat.A3, sat.mu, m.R0, rtol=rtol)
    v = verdicts(d, np.asarray(m.k2), d["valid"], rtol=rtol)
    code = int(v["code"])
    s1, s2, s3, a11, C = float(d["g1g1"]), float(v["s2"]), float(v["s3"]), float(d["a11"]), float(d["C"])
    a = np.array([[d["a11"], d["a12"], d["a13"]], [d["a12"], d["a22"], d["a23"]], [d["a13"], d["a23"], v["a33"]]],
                 dtype=float)
    minors = np.array([s1, s2, s2 * a11, s2 * C, s2 * s3])
    jac = -(float(f["cos_k"]) ** 2 / float(f["cos_t"]) ** 2) * s2 * s3
    r1, r2, r3 = restricted_conditions(sat.A1, sat.A2, sat.A3, m.theta0, m.k2, f["omega0"])
    r = (float(r1), float(r2), float(r3))
    if code == -1:
        s1 = s2 = s3 = jac = math.nan
        minors[:] = math.nan
    return Stability(
        s1=s1, s2=s2, s3=s3, a=a, minors=minors,
        degree=int(v["n_neg"]) if code != -1 else -1, nullity=int(v["n_zero"]) if code != -1 else -1,
        verdict=VERDICTS[code], jacobian=jac, unconditionally_stable=(code == 0 and jac != 0.0), restricted=r,
    )
