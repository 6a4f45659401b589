r"""The closed-form averaged system (9) of a drag tensor, in coordinates whose error the integrator controls.

Under drag the slow variables decay: :math:`G` and :math:`T` by many orders over long spans, and :math:`k^2`
tends to 0 where :math:`k^2 = 0` is stable (the paper's case 2). An integrator that controls
``atol + rtol |y|`` of :math:`(G, k^2)` controls only an absolute error of these small numbers. The closed
forms are therefore integrated in

* :math:`\ln G` and :math:`s = \ln k^2` with absolute error control ``rtol``: a relative error ``rtol`` of
  :math:`G` and of :math:`k^2` however far they decay (:math:`T = G^2S/2R` inherits it). Both rates are
  finite functions of :math:`k^2` alone, :math:`d\ln G/d\tau = -(I_{11}m_1 + I_{22}m_2 + I_{33}m_3)` and,
  from (8),

  .. math:: \frac{d\ln k^2}{d\tau} = -2\Big(\frac{I_{33}}{A_3}-\frac{I_{22}}{A_2}\Big)(1-\langle\operatorname{sn}^2
            \rangle) - 2\Big(\frac{I_{22}}{A_2}-\frac{I_{11}}{A_1}\Big)\frac EK

  (:math:`k^2 - W = k^2(1 - \langle\operatorname{sn}^2\rangle)`, no 0/0 at :math:`k \to 0`). A start at
  :math:`k^2 = 0` exactly stays there (an equilibrium of (8)): such a member carries the factor ``z = 0``;
* the angles :math:`(\delta, \lambda)` of :math:`\mathbf G` in :math:`Ox_i`, whose equations (6) for the drag
  tensor are regular everywhere: with :math:`x = \nu - \lambda`,

  .. math:: \dot\delta = -h\sin x\sin\delta,\qquad \dot\lambda = h\cos x\cos\delta,\qquad
            h = \tfrac32 f(\nu)N^*\cos x/G

  (:math:`\beta_2\beta_3 = \sin x\cos x\sin\delta`, :math:`\beta_1\beta_3/\sin\delta = \cos^2x\cos\delta`; the
  poles :math:`\sin\delta = 0` are fixed points of the gravity-gradient average), so :math:`\lambda` is
  continuous by construction. In the orbit-averaged limit :math:`\varepsilon = 0`, :math:`\delta = \delta_0`
  and :math:`\dot\lambda = \tfrac34(1-e^2)^{-3/2}N^*\cos\delta_0/G` (:func:`precession_rate`).

The angles are controlled to ``rtol/10`` radians per step (:math:`\lambda`, which accumulates turns as
:math:`G` decays, relatively to ``rtol`` beyond a radian): with :math:`\varepsilon > 0` their local errors add
up over the orbits the run resolves. The elliptic means come from :func:`rigidbody.core.kernel.elliptic_ratios`.

Every function takes the namespace ``xp`` first (:data:`rigidbody.core.kernel.SCALAR` for one run on Python
floats, :data:`~rigidbody.core.kernel.ARRAY` for a batch, elementwise over members), so a single run and a
batch integrate the same equations; the drag coefficients may be floats or per-member arrays.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy import special

from ..core.kernel import SCALAR as _SCALAR
from ..core.kernel import elliptic_ratios

#: the smallest relative tolerance the integrators use (SciPy's floor): the log coordinates are controlled
#: through their absolute tolerance
RTOL_FLOOR = 100.0 * float(np.finfo(float).eps)


class DragCoefficients:
    """The constants of the closed forms (6), (8) for labelled moments ``A`` and labelled drag ``Id``.

    ``g1, g2, g3`` weigh the means :math:`\\langle g_i^2\\rangle` in :math:`d\\ln G/d\\tau`; ``c3, c1`` are
    :math:`2(I_{33}/A_3 - I_{22}/A_2)` and :math:`2(I_{22}/A_2 - I_{11}/A_1)` of (8). Floats or arrays (one
    entry per member).
    """

    __slots__ = ("A", "c1", "c3", "g1", "g2", "g3")

    def __init__(self, A: tuple[float, float, float], Id: tuple[Any, Any, Any]) -> None:
        A1, A2, A3 = A
        I1, I2, I3 = Id
        self.A = A
        self.g1 = I1 * (A2 - A3)
        self.g2 = I2 * (A1 - A3)
        self.g3 = I3 * (A1 - A2)
        self.c3 = 2.0 * (I3 / A3 - I2 / A2)
        self.c1 = 2.0 * (I2 / A2 - I1 / A1)

    def args(self) -> tuple[Any, ...]:
        """The per-member coefficients in the order :func:`slow_rates` takes them."""
        return self.g1, self.g2, self.g3, self.c3, self.c1


def slow_rates(xp: Any, A: tuple[float, float, float], g1: Any, g2: Any, g3: Any, c3: Any, c1: Any,
               k2: Any) -> tuple[Any, Any, Any]:
    r"""``(d ln G/dtau, d ln k^2/dtau, N*)`` of (6), (8) at :math:`k^2` (in [0, 1]; labelled moments)."""
    A1, A2, A3 = A
    ek, sn2 = elliptic_ratios(xp, k2)
    iR = 1.0 / (A1 * (A2 - A3) + A3 * (A1 - A2) * k2)
    csn = 1.0 - sn2
    dlnG = -(g1 * ek + (g2 * sn2 + g3 * csn) * k2) * iR
    dlnk2 = -c3 * csn - c1 * ek
    Ns = A2 + A3 - 2.0 * A1 + 3.0 * (A1 - A2) * (A1 - A3) * k2 * iR * (A3 + (A2 - A3) * sn2)
    return dlnG, dlnk2, Ns


def s_over_r(A: tuple[float, float, float], k2: Any) -> Any:
    """:math:`S/R = 2T/G^2` of the kind with labelled moments ``A`` (floats or arrays)."""
    A1, A2, A3 = A
    return (A2 - A3 + (A1 - A2) * k2) / (A1 * (A2 - A3) + A3 * (A1 - A2) * k2)


def nut_freq(xp: Any, A: tuple[float, float, float], G: Any, k2: Any) -> Any:
    r"""Angular frequency :math:`2\pi/P = \pi\dot u/(2K)` of the Euler--Poinsot motion (0 at the separatrix)."""
    A1, A2, A3 = A
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    rate = G * xp.sqrt((A1 - A2) * (A1 - A3) * (A2 - A3) / (A1 * A2 * A3 * R))
    if not xp.array:
        return 0.0 if k2 >= 1.0 else math.pi * rate / (2.0 * float(special.ellipk(k2)))
    with np.errstate(divide="ignore"):
        return np.where(k2 >= 1.0, 0.0, math.pi * rate / (2.0 * special.ellipk(np.minimum(k2, 1.0))))


def orbit_factor(xp: Any, e: float, nu: Any) -> Any:
    """The gravity-gradient factor :math:`(1+e\\cos\\nu)^3/(1-e^2)^3` of (3)."""
    return (1.0 + e * xp.cos(nu)) ** 3 / (1.0 - e * e) ** 3


def nu_rate(xp: Any, e: float, nu: Any) -> Any:
    """:math:`\\dot\\nu/\\omega_0 = (1+e\\cos\\nu)^2/(1-e^2)^{3/2}` (Kepler's law)."""
    return (1.0 + e * xp.cos(nu)) ** 2 / (1.0 - e * e) ** 1.5


def k2_of(xp: Any, s: Any, z: Any) -> Any:
    """:math:`k^2 = z e^s` clipped to 1 (``z = 0`` for a member that started at :math:`k^2 = 0`)."""
    return xp.minimum(z * xp.exp(s), 1.0)


def rhs_limit(xp: Any, A: tuple[float, float, float], tau: Any, y: Any, g1: Any, g2: Any, g3: Any, c3: Any,
              c1: Any, z: Any, hl: Any) -> list[Any]:
    r"""The orbit-averaged system (:math:`\varepsilon = 0`) in :math:`(\ln G, \ln k^2, \lambda)`;
    ``hl`` is :math:`\tfrac34(1-e^2)^{-3/2}\cos\delta_0`."""
    lnG = y[0]
    dlnG, dlnk2, Ns = slow_rates(xp, A, g1, g2, g3, c3, c1, xp.minimum(z * xp.exp(y[1]), 1.0))
    return [dlnG, dlnk2, hl * Ns * xp.exp(-lnG)]


def rhs_orbit(xp: Any, A: tuple[float, float, float], e: float, tau: Any, y: Any, g1: Any, g2: Any, g3: Any,
              c3: Any, c1: Any, z: Any, ie: Any, nu0: Any) -> list[Any]:
    r"""The averaged system (9) with the true anomaly explicit in :math:`(\ln G, \ln k^2, \delta, \lambda)`, plus
    :math:`\nu` on an eccentric orbit (``e > 0``; ``nu0`` is then unused). ``ie`` is :math:`1/\varepsilon`."""
    lnG, de, la = y[0], y[2], y[3]
    dlnG, dlnk2, Ns = slow_rates(xp, A, g1, g2, g3, c3, c1, xp.minimum(z * xp.exp(y[1]), 1.0))
    if e == 0.0:
        nu = tau * ie + nu0
        f = 1.5
    else:
        nu = y[4]
        f = 1.5 * orbit_factor(xp, e, nu)
    x = nu - la
    c, sx = xp.cos(x), xp.sin(x)
    h = f * Ns * xp.exp(-lnG) * c
    out = [dlnG, dlnk2, -h * sx * xp.sin(de), h * c * xp.cos(de)]
    if e != 0.0:
        out.append(ie * nu_rate(xp, e, nu))
    return out


# --------------------------------------------------------------------------------------------------
# one run on Python floats: the same right-hand sides with the constants folded in
# --------------------------------------------------------------------------------------------------
def scalar_rhs(A: tuple[float, float, float], coefficients: tuple[float, ...], z: float, e: float, limit: bool,
               hl: float = 0.0, ie: float = 0.0, nu0: float = 0.0) -> Any:
    """:func:`rhs_limit` (``limit``) or :func:`rhs_orbit` for one run, as a closure on floats with every constant
    folded in and the calls of :func:`slow_rates` written out: the same arithmetic (tested equal to rounding),
    at half the cost of the generic functions, whose layers of Python calls cost more than the formulas."""
    A1, A2, A3 = A
    g1, g2, g3, c3, c1 = coefficients
    R0, R1 = A1 * (A2 - A3), A3 * (A1 - A2)
    N0, N1, N2 = A2 + A3 - 2.0 * A1, 3.0 * (A1 - A2) * (A1 - A3), A2 - A3
    exp, cos, sin = math.exp, math.cos, math.sin
    ratios = elliptic_ratios
    sc = _SCALAR

    def slow(s: float) -> tuple[float, float, float]:
        k2 = z * exp(s)
        if k2 > 1.0:
            k2 = 1.0
        ek, sn2 = ratios(sc, k2)
        iR = 1.0 / (R0 + R1 * k2)
        csn = 1.0 - sn2
        return (-(g1 * ek + (g2 * sn2 + g3 * csn) * k2) * iR, -c3 * csn - c1 * ek,
                N0 + N1 * k2 * iR * (A3 + N2 * sn2))

    if limit:
        def f_limit(tau: float, y: Any) -> list[float]:
            dlnG, dlnk2, Ns = slow(y[1])
            return [dlnG, dlnk2, hl * Ns * exp(-y[0])]
        return f_limit
    if e != 0.0:
        def f_ecc(tau: float, y: Any) -> list[float]:
            return rhs_orbit(sc, A, e, tau, y, g1, g2, g3, c3, c1, z, ie, nu0)
        return f_ecc

    def f_orbit(tau: float, y: Any) -> list[float]:
        dlnG, dlnk2, Ns = slow(y[1])
        x = tau * ie + nu0 - y[3]
        c, sx = cos(x), sin(x)
        h = 1.5 * Ns * exp(-y[0]) * c
        de = y[2]
        return [dlnG, dlnk2, -h * sx * sin(de), h * c * cos(de)]
    return f_orbit


# --------------------------------------------------------------------------------------------------
# initial state and output fields, shared by one run and a batch
# --------------------------------------------------------------------------------------------------
def initial_state(eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, nu0: Any, e: float) -> tuple[Any, Any]:
    """The state vector(s) and the factor ``z`` (0 where ``k2_0 = 0``); arrays of members, or floats (then a list
    and a float)."""
    if isinstance(k2_0, float) and isinstance(eps, float):  # one member: on floats
        zf = 1.0 if k2_0 > 0.0 else 0.0
        head = [math.log(G0), math.log(k2_0) if zf else 0.0]
        return head + ([lam0] if eps == 0.0 else [delta0, lam0] + ([nu0] if e != 0.0 else [])), zf
    z = np.where(np.asarray(k2_0) > 0.0, 1.0, 0.0)
    with np.errstate(divide="ignore"):
        s0 = np.where(z > 0.0, np.log(np.where(z > 0.0, k2_0, 1.0)), 0.0)
    lnG = np.log(G0)
    if np.ndim(eps) == 0 and float(eps) == 0.0:
        y = [lnG, s0, lam0]
    else:
        y = [lnG, s0, delta0, lam0] + ([nu0] if e != 0.0 else [])
    return np.stack(np.broadcast_arrays(*y), axis=-1), z


def fields(A: tuple[float, float, float], e: float, tau: np.ndarray, y: np.ndarray, z: Any, limit: bool, delta0: Any,
           nu0: Any, ie: Any) -> dict[str, np.ndarray]:
    """Output fields from raw states ``y`` of shape ``(..., n_state, n_t)`` (members on the leading axes)."""
    lnG, s = y[..., 0, :], y[..., 1, :]
    G = np.exp(lnG)
    k2 = np.exp(s)
    k2 *= np.asarray(z, dtype=float)[..., None]
    np.minimum(k2, 1.0, out=k2)
    A1, A2, A3 = A
    T = A1 * (A2 - A3) + A3 * (A1 - A2) * k2  # G^2 S/(2R), in place
    np.divide(A2 - A3 + (A1 - A2) * k2, T, out=T)
    T *= 0.5 * G * G
    if limit:
        nan = np.isnan(lnG)
        delta = np.where(nan, np.nan, np.asarray(delta0, dtype=float)[..., None])
        lam = y[..., 2, :]
        nu = np.where(nan, np.nan, np.asarray(nu0, dtype=float)[..., None])
    else:
        delta, lam = y[..., 2, :], y[..., 3, :]
        if e != 0.0:
            nu = y[..., 4, :]
        else:  # NaN where the state is (0 * NaN)
            nu = tau * np.asarray(ie, dtype=float)[..., None] + np.asarray(nu0, dtype=float)[..., None] + 0.0 * lnG
    n = np.empty((*lam.shape[:-1], 3, lam.shape[-1]))
    sd = np.sin(delta)
    np.cos(lam, out=n[..., 0, :])
    n[..., 0, :] *= sd
    np.sin(lam, out=n[..., 1, :])
    n[..., 1, :] *= sd
    np.cos(delta, out=n[..., 2, :])
    return {"G": G, "T": T, "k2": k2, "delta": delta, "lam": lam, "nu": nu, "n": n}


#: the angles' absolute tolerance as a fraction of rtol: their local errors add up over the orbits a run with
#: eps > 0 resolves (~100 per tau unit at eps = 0.005), so each step is held to a tenth (the global error of
#: delta and lambda then stays near rtol over the paper's spans; see the theory page, :ref:`ep-rtol`)
ANGLE_FACTOR = 0.1


def tolerances(rtol: float, n_state: int) -> tuple[np.ndarray, np.ndarray]:
    """Per-component ``(rtol, atol)`` of the state: ``ln G``, ``ln k^2`` absolutely to ``rtol``, ``delta``
    absolutely to ``ANGLE_FACTOR * rtol``, ``lambda`` likewise and relatively to ``rtol`` beyond a radian, ``nu``
    (eccentric orbits) like ``lambda``."""
    rt = np.full(n_state, RTOL_FLOOR)
    at = np.full(n_state, float(rtol))
    at[2:] *= ANGLE_FACTOR
    rt[3 if n_state >= 4 else 2] = rtol  # lambda
    if n_state == 5:
        rt[4] = rtol
    return rt, at
