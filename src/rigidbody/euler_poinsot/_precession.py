r"""The precession angle of the Euler--Poinsot motion in closed form (the incomplete elliptic integral of the
third kind).

With the angular momentum along :math:`y_3` and the 3-1-3 angles of a body axis :math:`z_3` that the angular
momentum never reaches, :math:`\dot\psi = G(g_1^2/A_1 + g_2^2/A_2)/(g_1^2 + g_2^2)` ((1) with
:math:`\mathbf L = 0`). Along the motion :math:`g_3^2` is an affine function of :math:`\operatorname{sn}^2 u`,
so that

.. math::
    \dot\psi = \frac{G}{A_3} - \frac{c}{1 - n\operatorname{sn}^2 u},\qquad
    \psi(t) - \psi(0) = \frac{G}{A_3}\,t - \frac{c}{\dot u}\bigl[\Pi(n; \operatorname{am}u \mid m)
    - \Pi(n; \operatorname{am}u_0 \mid m)\bigr],

with :math:`n \le 0` (no pole) and :math:`c, n` given by the caller for its labelling of the axes (Landau &
Lifshitz, Mechanics, sec. 37, problem 1; Celledoni, Fassò, Säfström & Zanna, SIAM J. Sci. Comput. 30 (2008),
whose closed form Principia's ``EulerSolver`` implements). :math:`\Pi` is written in Carlson's symmetric integrals
(NIST DLMF 19.25.14 and 19.25.1),

.. math::
    \Pi(n; \varphi \mid m) = s R_F(c^2, \Delta^2, 1) + \tfrac{n}{3} s^3 R_J(c^2, \Delta^2, 1, 1 - n s^2),\qquad
    s = \sin\varphi,\ c = \cos\varphi,\ \Delta^2 = 1 - m s^2,

for :math:`|\varphi| \le \pi/2`, and extended by :math:`\Pi(n; \varphi + j\pi) = \Pi(n; \varphi) + 2j\Pi(n)`;
:math:`s, c^2, \Delta^2` are :math:`\operatorname{sn}, \operatorname{cn}^2, \operatorname{dn}^2` of the argument,
so no amplitude is formed and the result is exact to the rounding of :math:`u`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.special import elliprf, elliprj

from ..core import elliptic as ell

__all__ = ["elliptic_f", "elliptic_pi", "pi_complete"]


def pi_complete(n: float, mc: float) -> float:
    r"""Complete integral of the third kind :math:`\Pi(n \mid m)` for :math:`n \le 0`, :math:`m = 1 - m_c`
    (:math:`m_c > 0`; DLMF 19.25.2)."""
    return float(elliprf(0.0, mc, 1.0) + n / 3.0 * elliprj(0.0, mc, 1.0, 1.0 - n))


def elliptic_pi(u: Any, n: float, mc: float, sn: Any, cn: Any, dn: Any) -> np.ndarray:
    r""":math:`\Pi(n; \operatorname{am}u \mid 1 - m_c)` for any real ``u`` (``sn, cn, dn`` of ``u``; ``mc = 0``:
    the separatrix, :math:`\operatorname{am}u = \operatorname{gd}u`)."""
    u = np.asarray(u, dtype=float)
    s = np.asarray(sn, dtype=float)
    c2 = np.asarray(cn, dtype=float) ** 2
    d2 = np.asarray(dn, dtype=float) ** 2
    if mc > 0.0:
        j = np.rint(u / (2.0 * float(ell.K(mc=mc))))
        s = np.where(j % 2 == 0, s, -s)  # sin of the amplitude reduced to [-pi/2, pi/2]
        shift = 2.0 * j * pi_complete(n, mc)
    else:
        shift = np.zeros_like(u)
    s2 = s * s
    val = s * elliprf(c2, d2, 1.0) + (n / 3.0) * s * s2 * elliprj(c2, d2, 1.0, 1.0 - n * s2)
    return np.asarray(shift + val, dtype=float)


def elliptic_f(sn: float, cn: float, mc: float) -> float:
    r"""The argument :math:`u \in (-2K, 2K]` with :math:`\operatorname{sn}u, \operatorname{cn}u` proportional to
    ``sn, cn`` (not both zero; any common positive factor): :math:`F(\varphi \mid m)` of the amplitude
    :math:`\varphi = \operatorname{atan2}(sn, cn)` (DLMF 19.25.5); ``mc = 0`` (the separatrix) needs ``cn > 0``."""
    phi = math.atan2(sn, cn)
    if mc == 0.0:
        return math.asinh(math.tan(phi))
    half = 0.0
    if phi > 0.5 * math.pi:  # am(2K - v) = pi - am(v)
        phi, half = math.pi - phi, 1.0
    elif phi < -0.5 * math.pi:  # am(v - 2K) = am(v) - pi
        phi, half = -math.pi - phi, -1.0
    s, c = math.sin(phi), math.cos(phi)
    f = s * float(elliprf(c * c, c * c + mc * s * s, 1.0))
    return f if half == 0.0 else half * 2.0 * float(ell.K(mc=mc)) - f
