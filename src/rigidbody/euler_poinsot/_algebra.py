r"""The algebra of the averaged system (Rachinskaya, eqs. (5)-(9)): plain functions of the body's moments of
inertia, the drag tensor and the slow variables :math:`(G, k^2)` (the notation of :mod:`._model`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.validate import real
from ._model import Body, as_drag, check_body, check_kind, elliptic_ratios, float_array, labelled

__all__ = ["N_star", "N_time", "T_from", "chi", "dk2_dtau", "dk2_labelled", "drag_rates", "drag_rates_labelled",
           "k2_equilibria", "k2_from", "kind_of", "nstar_labelled"]


def _S_over_R(A: tuple[float, float, float], k2: float) -> float:
    A1, A2, A3 = A
    return (A2 - A3 + (A1 - A2) * k2) / (A1 * (A2 - A3) + A3 * (A1 - A2) * k2)


# --------------------------------------------------------------------------------------------------
# public algebra
# --------------------------------------------------------------------------------------------------
def k2_from(body: Body, G: Any, T: Any, kind: str = "max") -> Any:
    r"""Modulus :math:`k^2` of the Euler--Poinsot motion from :math:`G` and :math:`T`, formula (5).

    .. math:: k^2 = \frac{(A_2-A_3)(2TA_1-G^2)}{(A_1-A_2)(G^2-2TA_3)}\quad(\text{kind 'max'}),\qquad
              k^2 = \frac{(A_1-A_2)(G^2-2TA_3)}{(A_2-A_3)(2TA_1-G^2)}\quad(\text{kind 'min'}).

    Parameters
    ----------
    body : Body
    G, T : array_like
        Angular-momentum magnitude (> 0) and kinetic energy (> 0); broadcast together.
    kind : {'max', 'min'}

    Returns
    -------
    float or numpy.ndarray
        :math:`k^2 \in [0, 1]`.

    Raises
    ------
    ValueError
        If :math:`G^2/2T` lies outside :math:`[A_3, A_1]` (no rigid-body state) or on the other side of the
        separatrix :math:`G^2 = 2TA_2` than ``kind`` says (use :func:`kind_of`).

    See Also
    --------
    T_from, kind_of

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (5).

    Examples
    --------
    :math:`k^2 = 0` for rotation about the axis of :math:`A_1` (:math:`2TA_1 = G^2`); (5) inverts :func:`T_from`:

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> print(f"{ep.k2_from(body, 1.0, 1 / 6.4):.6f} {ep.k2_from(body, 1.0, ep.T_from(body, 1.0, 0.3)):.6f}")
    0.000000 0.300000
    """
    check_body(body)
    check_kind(kind)
    G_ = float_array(G, "G")
    T_ = float_array(T, "T")
    if np.any(~np.isfinite(G_)) or np.any(G_ <= 0):
        raise ValueError("G must be positive and finite")
    if np.any(~np.isfinite(T_)) or np.any(T_ <= 0):
        raise ValueError("T must be positive and finite")
    A1, A2, A3 = body.A1, body.A2, body.A3
    D = G_**2 / (2.0 * T_)
    tol = 1e-12 * A1
    if np.any(D > A1 + tol) or np.any(D < A3 - tol):
        raise ValueError(f"G**2/(2T) must lie in [A3, A1] = [{A3}, {A1}] for a rigid body")
    if kind == "max":
        if np.any(D < A2 - tol):
            raise ValueError("G**2 < 2T A2: the state circulates about the axis of A3, use kind='min'")
        num = (A2 - A3) * (A1 - D)
        den = (A1 - A2) * (D - A3)
    else:
        if np.any(D > A2 + tol):
            raise ValueError("G**2 > 2T A2: the state circulates about the axis of A1, use kind='max'")
        num = (A1 - A2) * (D - A3)
        den = (A2 - A3) * (A1 - D)
    k2 = np.clip(num / den, 0.0, 1.0)
    return float(k2) if np.ndim(k2) == 0 else k2


def T_from(body: Body, G: Any, k2: Any, kind: str = "max") -> Any:
    r"""Kinetic energy from :math:`G` and :math:`k^2`: the inverse of (5).

    .. math:: 2T = G^2\,\frac{S}{R} = G^2\,\frac{A_2-A_3+(A_1-A_2)k^2}{A_1(A_2-A_3)+A_3(A_1-A_2)k^2}
              \quad(\text{kind 'max'; labels 1}\leftrightarrow 3\text{ for 'min'}).

    Parameters
    ----------
    body : Body
    G : array_like
        Angular-momentum magnitude (> 0).
    k2 : array_like
        Modulus squared in [0, 1].
    kind : {'max', 'min'}

    Returns
    -------
    float or numpy.ndarray

    See Also
    --------
    k2_from : its inverse, formula (5).
    kind_of : the kind of motion of a state :math:`(G, T)`.
    EulerPoinsot : the motion at :math:`(G, k^2)`.

    Examples
    --------
    :math:`T` runs from :math:`G^2/2A_1 = 1/6.4` (:math:`k^2 = 0`) to :math:`G^2/2A_2 = 1/5.2` (:math:`k^2 = 1`):

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> print(f"{ep.T_from(body, 1.0, 0.0):.6f} {1 / 6.4:.6f} {ep.T_from(body, 1.0, 1.0):.6f} {1 / 5.2:.6f}")
    0.156250 0.156250 0.192308 0.192308
    """
    check_body(body)
    check_kind(kind)
    G_ = float_array(G, "G")
    k2_ = float_array(k2, "k2")
    if np.any(~np.isfinite(G_)) or np.any(G_ <= 0):
        raise ValueError("G must be positive and finite")
    if np.any(~np.isfinite(k2_)) or np.any(k2_ < 0) or np.any(k2_ > 1):
        raise ValueError("k2 must lie in [0, 1]")
    A1, A2, A3 = labelled(body, kind)
    T = 0.5 * G_**2 * (A2 - A3 + (A1 - A2) * k2_) / (A1 * (A2 - A3) + A3 * (A1 - A2) * k2_)
    return float(T) if np.ndim(T) == 0 else T


def kind_of(body: Body, G: float, T: float) -> str:
    """'max', 'min' or 'separatrix' for a state (G, T) (compares :math:`G^2` with :math:`2TA_2`).

    The two kinds of Euler--Poinsot motion of section 2: ``'max'`` (:math:`2TA_1 \\ge G^2 > 2TA_2`, the
    domain of formula (5)) and ``'min'`` (:math:`2TA_2 > G^2 \\ge 2TA_3`).

    Parameters
    ----------
    body : Body
    G : float
        Magnitude of the angular momentum (> 0).
    T : float
        Kinetic energy (> 0), in units consistent with ``G`` and the moments (dimensional, or the
        nondimensional :math:`\\tilde G, \\tilde T` of section 3).

    Returns
    -------
    {'max', 'min', 'separatrix'}
        ``'separatrix'`` only when :math:`G^2 = 2TA_2` exactly.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``G``, ``T`` is not a real number.
    ValueError
        If ``G`` or ``T`` is not positive, or :math:`G^2/2T` lies outside :math:`[A_3, A_1]` (no rigid-body
        state has it).

    See Also
    --------
    k2_from : :math:`k^2` of a state, formula (5).
    T_from : the energy from :math:`G` and :math:`k^2`.
    Separatrix : the motions of kind ``'separatrix'``.

    Examples
    --------
    With :math:`G = 1` the separatrix energy is :math:`1/2A_2 = 1/5.2`; less energy is the ``'max'`` kind:

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> ep.kind_of(body, 1.0, 0.17), ep.kind_of(body, 1.0, 0.25), ep.kind_of(body, 1.0, 1 / 5.2)
    ('max', 'min', 'separatrix')
    """
    check_body(body)
    G, T = real(G, "G"), real(T, "T")
    if G <= 0 or T <= 0:
        raise ValueError(f"G and T must be positive, got G={G}, T={T}")
    D = G**2 / (2.0 * T)
    tol = 1e-12 * body.A1
    if D > body.A1 + tol or D < body.A3 - tol:
        raise ValueError(f"G**2/(2T) = {D:g} must lie in [A3, A1] = [{body.A3}, {body.A1}] for a rigid body")
    if D > body.A2:
        return "max"
    if D < body.A2:
        return "min"
    return "separatrix"


def chi(body: Body, I: Any) -> float:
    r"""The parameter :math:`\chi` of the :math:`k^2` equation (7).

    .. math:: \chi = \frac{2I_{22}A_1A_3 - I_{11}A_2A_3 - I_{33}A_1A_2}{(I_{33}A_1 - I_{11}A_3)A_2}.

    Only the diagonal of ``I`` enters. For the paper's two drag cases this gives -4.4743 and 3.8523
    (printed: -4.477 and 3.853; see :ref:`errata-euler-poinsot`).

    Parameters
    ----------
    body : Body
    I : array_like or Drag
        Drag tensor in body axes (3x3, or its 3 diagonal entries); only its diagonal enters.

    Returns
    -------
    float
        :math:`\chi` (dimensionless: a ratio of drag-times-moment products, the same for the dimensional
        :math:`I, A_i` and the nondimensional :math:`\tilde I, \tilde A_i` of section 3). The slope of (8)
        at :math:`k^2 = 0` is :math:`(-3-\chi)/(2N)`: for :math:`N > 0` (:func:`N_time`) that equilibrium
        is stable iff :math:`\chi > -3`.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``I`` is not a real matrix.
    ValueError
        If ``I`` has the wrong shape, is not finite or its symmetric part is not positive definite (see
        :class:`Drag`); or if :math:`I_{33}A_1 = I_{11}A_3` (then :math:`N = \infty` and :math:`\chi` is
        undefined; the :math:`k^2` equation itself stays finite: use :func:`dk2_dtau`).

    See Also
    --------
    N_time : the time scale of (7).
    dk2_dtau : the :math:`k^2` equation (8).
    k2_equilibria : its roots, whose stability :math:`\chi` decides.

    Examples
    --------
    The paper's two drag cases, printed as -4.477 and 3.853 (the first is sensitive to the rounding of
    the printed data, :doc:`/errata`):

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> print(f"{ep.chi(body, [2.322, 1.31, 1.425]):.4f} {ep.chi(body, [0.919, 5.228, 1.666]):.4f}")
    -4.4743 3.8523
    """
    check_body(body)
    I11, I22, I33 = as_drag(I).diag
    A1, A2, A3 = body.A1, body.A2, body.A3
    den = (I33 * A1 - I11 * A3) * A2
    if den == 0.0:
        raise ValueError("chi is undefined for I33*A1 == I11*A3 (N infinite); use dk2_dtau")
    return (2 * I22 * A1 * A3 - I11 * A2 * A3 - I33 * A1 * A2) / den


def N_time(body: Body, I: Any) -> float:
    r"""The time scale :math:`N = A_1A_3/(I_{33}A_1 - I_{11}A_3)` of (7) (:math:`\xi = (t-t_*)/N`).

    Parameters
    ----------
    body : Body
    I : array_like or Drag
        Drag tensor in body axes (3x3, or its 3 diagonal entries); only :math:`I_{11}, I_{33}` enter.

    Returns
    -------
    float
        :math:`N` in units of time: dimensional :math:`t` for the dimensional :math:`I`, or :math:`\tau`
        for the nondimensional :math:`\tilde I = I/(G_0\varepsilon^2)` of section 3. Negative when
        :math:`I_{33}A_1 < I_{11}A_3`.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``I`` is not a real matrix.
    ValueError
        If ``I`` is not a valid drag tensor (see :class:`Drag`), or :math:`I_{33}A_1 = I_{11}A_3` (then
        :math:`N` is infinite).

    See Also
    --------
    chi : the other parameter of (7).
    dk2_dtau : the :math:`k^2` equation (8).
    k2_equilibria : its roots and their stability.

    Examples
    --------
    The paper's first drag case, :math:`N = 3.2\cdot1.67/(1.425\cdot3.2 - 2.322\cdot1.67)`:

    >>> from rigidbody import euler_poinsot as ep
    >>> N = ep.N_time(ep.Body(3.2, 2.6, 1.67), [2.322, 1.31, 1.425])
    >>> print(f"{N:.6f} {3.2 * 1.67 / (1.425 * 3.2 - 2.322 * 1.67):.6f}")
    7.832791 7.832791
    """
    check_body(body)
    I11, _, I33 = as_drag(I).diag
    den = I33 * body.A1 - I11 * body.A3
    if den == 0.0:
        raise ValueError("N is infinite for I33*A1 == I11*A3")
    return body.A1 * body.A3 / den


def dk2_labelled(A: tuple[float, float, float], I: tuple[float, float, float], k2: float) -> float:
    A1, A2, A3 = A
    I11, I22, I33 = I
    ek, sn2 = elliptic_ratios(k2)
    W = k2 * sn2
    # (8) rewritten: c(1-chi) = 2(I33/A3 - I22/A2), c(1+chi) = 2(I22/A2 - I11/A1), c = 1/N
    return -2.0 * (I33 / A3 - I22 / A2) * (k2 - W) - 2.0 * (I22 / A2 - I11 / A1) * k2 * ek


def dk2_dtau(body: Body, I: Any, k2: float, kind: str = "max") -> float:
    r"""Right-hand side of the :math:`k^2` equation (8) (dimensional :math:`t`, or :math:`\tau` with :math:`\tilde I`).

    Implemented in the equivalent form

    .. math:: \frac{dk^2}{dt} = -2\Big(\frac{I_{33}}{A_3}-\frac{I_{22}}{A_2}\Big)(k^2-W)
              - 2\Big(\frac{I_{22}}{A_2}-\frac{I_{11}}{A_1}\Big)k^2\frac{E}{K},

    which equals :math:`N^{-1}\{(1-\chi)(1-k^2)-[(1-\chi)+(1+\chi)k^2]E/K\}` (since
    :math:`(1-\chi)/N = 2(I_{33}/A_3 - I_{22}/A_2)`, :math:`(1+\chi)/N = 2(I_{22}/A_2 - I_{11}/A_1)`) but
    stays finite when :math:`I_{33}A_1 = I_{11}A_3` and has no 0/0 at :math:`k \to 0` (both terms are
    :math:`O(k^2)`). For ``kind='min'`` the labels 1 and 3 are exchanged.

    Parameters
    ----------
    body : Body
    I : array_like or Drag
        Drag tensor in body axes (3x3, or its 3 diagonal entries); only its diagonal enters (8).
        Dimensional :math:`I` gives :math:`dk^2/dt`; the nondimensional :math:`\tilde I = I/(G_0\varepsilon^2)`
        (with :math:`\tilde A_i = A_i\Omega_0/G_0`) gives :math:`dk^2/d\tau` of (9).
    k2 : float
        Modulus squared of the Euler--Poinsot motion (5), in :math:`[0, 1]`.
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max' is the paper's).

    Returns
    -------
    float
        :math:`dk^2/dt` (or :math:`dk^2/d\tau`); independent of :math:`G`.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body`, ``k2`` is not a real number or ``I`` is not a real matrix.
    ValueError
        If ``kind`` is unknown, ``k2`` is outside :math:`[0, 1]` or ``I`` is not a valid drag tensor (see
        :class:`Drag`).

    See Also
    --------
    chi, N_time, k2_equilibria

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (7), (8).

    Examples
    --------
    The paper's form of (7)-(8), with SciPy's complete elliptic integrals, gives the same number:

    >>> from scipy.special import ellipe, ellipk
    >>> from rigidbody import euler_poinsot as ep
    >>> body, I, k2 = ep.Body(3.2, 2.6, 1.67), [2.322, 1.31, 1.425], 0.9
    >>> c, N = ep.chi(body, I), ep.N_time(body, I)
    >>> paper = ((1 - c) * (1 - k2) - ((1 - c) + (1 + c) * k2) * ellipe(k2) / ellipk(k2)) / N
    >>> print(f"{ep.dk2_dtau(body, I, k2):.6f} {paper:.6f}")
    -0.058536 -0.058536
    """
    check_body(body)
    check_kind(kind)
    k2f = real(k2, "k2")
    if not (0.0 <= k2f <= 1.0):
        raise ValueError(f"k2 must lie in [0, 1], got {k2f}")
    A, Id = labelled(body, kind, as_drag(I).diag)
    return dk2_labelled(A, Id, k2f)


def drag_rates_labelled(
    A: tuple[float, float, float], I: tuple[float, float, float], G: float, k2: float
) -> tuple[float, float]:
    """(dG/dt, dT/dt) of (6) in 'max' labelling."""
    A1, A2, A3 = A
    I11, I22, I33 = I
    ek, sn2 = elliptic_ratios(k2)
    W = k2 * sn2
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    # <g_i^2>/G^2 over the Euler-Poinsot motion: (A2-A3)(1-W)/R, (A1-A3)W/R, (A1-A2)(k2-W)/R
    m1 = (A2 - A3) * ek / R
    m2 = (A1 - A3) * W / R
    m3 = (A1 - A2) * (k2 - W) / R
    dG = -G * (I11 * m1 + I22 * m2 + I33 * m3)
    dT = -G * G * (I11 * m1 / A1 + I22 * m2 / A2 + I33 * m3 / A3)
    return dG, dT


def drag_rates(body: Body, I: Any, G: float, k2: float, kind: str = "max") -> tuple[float, float]:
    r"""The averaged drag terms :math:`(dG/dt, dT/dt)` of (6).

    .. math:: \frac{dG}{dt} = -\frac{G}{R}\{I_{22}(A_1-A_3)W + I_{11}(A_2-A_3)(1-W) + I_{33}(A_1-A_2)(k^2-W)\},

    and :math:`dT/dt` as printed in (6), evaluated in the equivalent form
    :math:`dT/dt = -(G^2/R)\{I_{11}(A_2-A_3)(1-W)/A_1 + I_{22}(A_1-A_3)W/A_2 + I_{33}(A_1-A_2)(k^2-W)/A_3\}`
    (the same expression after :math:`2T = G^2S/R`; the tests compare both with numerical averages of
    :math:`-\boldsymbol\omega\cdot I\boldsymbol\omega`). The gravity-gradient torque does not change
    :math:`G` and :math:`T` on average. Only the diagonal of ``I`` enters.

    Returns
    -------
    dG, dT : float
        Per unit dimensional time :math:`t` (or per :math:`\tau` with the nondimensional :math:`\tilde I`).

    See Also
    --------
    dk2_dtau : the drag's rate of :math:`k^2`, (8).
    N_star : the gravity-gradient term of (6).
    LinearDrag : the torque object with these averages.
    averaged_rates : all right-hand sides of (6) and (9).

    Examples
    --------
    An isotropic drag :math:`-c\boldsymbol\omega` gives :math:`dG/dt = -c\,\mathbf g\cdot\boldsymbol\omega/G =
    -2cT/G` at every instant:

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> print(f"{ep.drag_rates(body, [0.5, 0.5, 0.5], 1.0, 0.4)[0]:.6f} {-ep.T_from(body, 1.0, 0.4):.6f}")
    -0.173241 -0.173241
    """
    check_body(body)
    check_kind(kind)
    A, Id = labelled(body, kind, as_drag(I).diag)
    G, k2 = real(G, "G"), real(k2, "k2")
    if G <= 0 or not (0.0 <= k2 <= 1.0):
        raise ValueError(f"need G > 0 and k2 in [0, 1], got G={G}, k2={k2}")
    return drag_rates_labelled(A, Id, G, k2)


def nstar_labelled(A: tuple[float, float, float], k2: float) -> float:
    A1, A2, A3 = A
    _, sn2 = elliptic_ratios(k2)
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    fac = k2 * (A1 - A2) * (A1 - A3) / R  # = 2 A1 T / G^2 - 1, without cancellation
    return A2 + A3 - 2.0 * A1 + 3.0 * fac * (A3 + (A2 - A3) * sn2)


def N_star(body: Body, k2: Any, kind: str = "max") -> Any:
    r""":math:`N^*` of (6): :math:`N^* = A_2+A_3-2A_1+3(2A_1T/G^2-1)[A_3+(A_2-A_3)(K-E)/(Kk^2)]`.

    A function of :math:`k^2` only (:math:`2A_1T/G^2 - 1 = k^2(A_1-A_2)(A_1-A_3)/R`). Physically
    :math:`N^* = A_1+A_2+A_3-3\langle J_{GG}\rangle`, where :math:`J_{GG}` is the moment of inertia
    about the direction of :math:`\mathbf G` averaged over the Euler--Poinsot motion. It drives the
    gravity-gradient equations for :math:`\delta, \lambda` in (6) and (9) (:func:`precession_rate`).

    Parameters
    ----------
    body : Body
    k2 : float or array_like
        Modulus squared of the Euler--Poinsot motion (5), in :math:`[0, 1]`.
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max' is the paper's; labels 1 and 3 exchanged for 'min').

    Returns
    -------
    float or numpy.ndarray
        :math:`N^*`, in the units of the moments :math:`A_i` (dimensional, or :math:`\tilde A_i` of
        section 3); a float for scalar ``k2``.

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``k2`` is not real.
    ValueError
        If ``kind`` is unknown or ``k2`` is not finite and in :math:`[0, 1]`.

    See Also
    --------
    GravityGradient : the torque whose average :math:`N^*` sets.
    precession_rate : the orbit-averaged precession of :math:`\mathbf G` it drives.
    drag_rates : the drag's right-hand sides of (6).

    Examples
    --------
    At :math:`k^2 = 0` the body turns about the axis of :math:`A_1`: :math:`J_{GG} = A_1`,
    :math:`N^* = A_2 + A_3 - 2A_1`:

    >>> from rigidbody import euler_poinsot as ep
    >>> print(f"{ep.N_star(ep.Body(3.2, 2.6, 1.67), 0.0):.6f} {2.6 + 1.67 - 2 * 3.2:.6f}")
    -2.130000 -2.130000
    """
    check_body(body)
    check_kind(kind)
    A = labelled(body, kind)
    k2a = float_array(k2, "k2")
    if np.any(~np.isfinite(k2a)) or np.any(k2a < 0) or np.any(k2a > 1):
        raise ValueError("k2 must lie in [0, 1]")
    out = np.vectorize(lambda x: nstar_labelled(A, float(x)))(k2a)
    return float(out) if np.ndim(out) == 0 else out


def k2_equilibria(body: Body, I: Any, kind: str = "max", n_grid: int = 2001) -> list[tuple[float, str]]:
    r"""Equilibria of the :math:`k^2` equation (8) in :math:`[0, 1)` and their stability.

    :math:`k^2 = 0` is always an equilibrium; its linearisation is
    :math:`dk^2/dt \approx -(I_{33}/A_3 + I_{22}/A_2 - 2I_{11}/A_1)\,k^2 = N^{-1}\tfrac{-3-\chi}{2}k^2`.
    Interior roots are bracketed on a grid and refined with Brent's method. Near :math:`k^2=1` the right-hand
    side has the sign of :math:`-(I_{33}/A_3 - I_{11}/A_1)`: when that is positive, :math:`k^2` reaches the
    separatrix in finite time.

    Parameters
    ----------
    body : Body
    I : array_like or Drag
        Drag tensor (only its diagonal enters (8)).
    kind : {'max', 'min'}
    n_grid : int
        Points of the uniform grid in :math:`[0, 1]` on which sign changes are bracketed (>= 4); two
        roots closer than its spacing can be missed.

    Returns
    -------
    list of (k2, 'stable' | 'unstable' | 'neutral')

    See Also
    --------
    dk2_dtau : the equation whose roots they are.
    chi : the parameter of (7) that, with :math:`N`, decides the stability of :math:`k^2 = 0`.
    N_time : the time scale of (7).

    Examples
    --------
    The paper's first drag case: :math:`\chi < -3` and :math:`N > 0` make :math:`k^2 = 0` unstable; the
    interior root is a zero of :func:`dk2_dtau`:

    >>> from rigidbody import euler_poinsot as ep
    >>> body, I = ep.Body(3.2, 2.6, 1.67), [2.322, 1.31, 1.425]
    >>> (k0, s0), (k1, s1) = ep.k2_equilibria(body, I)
    >>> print(f"{k0:.6f} {s0} {k1:.5f} {s1}", abs(ep.dk2_dtau(body, I, k1)) < 1e-12)
    0.000000 unstable 0.52064 stable True
    """
    from scipy.optimize import brentq

    check_body(body)
    check_kind(kind)
    if isinstance(n_grid, (bool, np.bool_)) or not isinstance(n_grid, (int, np.integer)) or n_grid < 4:
        raise ValueError(f"n_grid must be an integer >= 4 (grid on which roots are bracketed), got {n_grid!r}")
    A, Id = labelled(body, kind, as_drag(I).diag)
    out: list[tuple[float, str]] = []
    slope0 = -(Id[2] / A[2] + Id[1] / A[1] - 2.0 * Id[0] / A[0])
    out.append((0.0, "stable" if slope0 < 0 else ("unstable" if slope0 > 0 else "neutral")))
    xs = np.linspace(0.0, 1.0, n_grid)[1:-1]
    fs = np.array([dk2_labelled(A, Id, float(x)) for x in xs])
    for i in range(len(xs) - 1):
        if fs[i] == 0.0 or fs[i] * fs[i + 1] < 0:
            r = brentq(lambda x: dk2_labelled(A, Id, x), xs[i], xs[i + 1], xtol=1e-15, rtol=1e-14)
            stab = "stable" if fs[i] > 0 or fs[i + 1] < 0 else "unstable"
            out.append((float(r), stab))
    return out
