r"""Limits of the averaged rates at the separatrix (:math:`k^2\to1`) and their :math:`1/K(k)` approach.

The mean over a period tends to the value at the saddles (rotation about the intermediate axis), the same from the
four regions; the separatrix loops (:mod:`._separatrix`) enter only through the correction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core.validate import real
from ._model import Body, Orbit
from ._regions import ARCS, REGIONS, Arc, Region, check_region, region_arcs
from ._separatrix import momenta_at, orbit_nodes, psi_average, separatrix_setup

__all__ = ["SeparatrixLimits", "separatrix_limits"]


def _rates_at(body: Body, g: np.ndarray, Lb: np.ndarray, Lo: np.ndarray, n: np.ndarray) -> dict[str, np.ndarray]:
    """dG, dT, dh and dn at body momenta g (3, m) for the psi-averaged torques Lb (body), Lo (orbital)."""
    G = np.linalg.norm(g, axis=0)
    omega = g / body.A[:, None]
    dG = (g * Lb).sum(0) / G
    dT = (omega * Lb).sum(0)
    dh = dT - G * dG / body.A2
    dn = (Lo - np.outer(n, n @ Lo)) / G
    return {"dG": dG, "dT": dT, "dh": dh, "dn": dn}


@dataclass(frozen=True)
class SeparatrixLimits:
    r"""Limits of the averaged rates at the separatrix and how they are approached.

    The mean of a smooth function over a period of the Euler--Poinsot motion tends, as :math:`k\to1`, to
    its value at the saddles :math:`\pm G\mathbf e_2` (averaged over :math:`\psi` and over the two
    saddles): the motion spends all but :math:`O(1)` of its period :math:`4K/\dot u` next to them. The
    separatrix loop enters only as the correction :math:`J/(4K)`, with :math:`J` the integral along the two
    arcs of the region of the difference between the function and its value at the saddle being
    approached or left (in the elliptic argument :math:`u`). So the rates are continuous across the
    separatrix (the same limit from all four regions), with an infinite slope in :math:`k^2` there, and the
    convergence is slow: :math:`1/K \approx 1/\ln(4/k')`.

    Attributes
    ----------
    dG, dT : float
        Limits of the averaged :math:`dG/d\tau`, :math:`dT/d\tau`.
    dn : numpy.ndarray
        Limit of :math:`d\mathbf n/d\tau` (unit vector of :math:`\mathbf G` in the orbital axes).
    dk2 : float
        Limit of :math:`dk^2/d\tau` (0: the averaged drift of the energy vanishes at the separatrix).
    slope : dict
        Region -> dict of :math:`J/4` for ``'dG'``, ``'dT'``, ``'dh'``, ``'dk2'`` (floats) and ``'dn'``
        (array), so that the averaged rate near the separatrix is ``limit + slope / K(k)``.

    See Also
    --------
    separatrix_limits : computes it.
    SeparatrixCrossing : what happens at the separatrix itself.

    Examples
    --------
    At :math:`k^2 = 1 - 10^{-4}` the limit is 8 % off (6) (a :math:`1/K` term), ``near`` less than :math:`10^{-4}`:

    >>> from rigidbody import euler_poinsot as ep
    >>> body, I = ep.Body(3.2, 2.6, 1.67), [2.322, 1.31, 1.425]
    >>> lim, exact = ep.separatrix_limits(body, I, 1.0, 0.7, 0.3, None), ep.drag_rates(body, I, 1.0, 1 - 1e-4)[0]
    >>> print(f"{abs(lim.dG / exact - 1):.2f}", bool(abs(lim.near(("max", 1), 1e-4)["dG"] / exact - 1) < 1e-4))
    0.08 True
    """

    dG: float
    dT: float
    dn: np.ndarray
    dk2: float
    slope: dict[Region, dict[str, Any]] = field(repr=False)

    def near(self, region: Any, mc: float) -> dict[str, Any]:
        r"""The two-term asymptotic rates ``limit + slope/K`` at :math:`1 - k^2 = ` ``mc`` in ``region``.

        Examples
        --------
        At :math:`1 - k^2 = 10^{-6}` the limit alone is still 6 % off the drag's rate (6) (:math:`K \approx 8.3`);
        the two terms agree with (6) to better than :math:`10^{-5}`:

        >>> from rigidbody import euler_poinsot as ep
        >>> body, I = ep.Body(3.2, 2.6, 1.67), [2.322, 1.31, 1.425]
        >>> lim, exact = ep.separatrix_limits(body, I, 1.0, 0.7, 0.3, None), ep.drag_rates(body, I, 1.0, 1 - 1e-6)[1]
        >>> print(f"{abs(lim.dT / exact - 1):.2f}", bool(abs(lim.near(("max", 1), 1e-6)["dT"] / exact - 1) < 1e-5))
        0.06 True
        """
        from ..core.elliptic import K

        reg = check_region(region)
        mcf = real(mc, "mc")
        if not (0.0 < mcf <= 1.0):
            raise ValueError(f"mc (= 1 - k**2) must lie in (0, 1], got {mcf}")
        kk = float(K(mc=mcf))
        s = self.slope[reg]
        base = {"dG": self.dG, "dT": self.dT, "dn": self.dn, "dk2": self.dk2, "dh": 0.0}
        return {q: base[q] + s[q] / kk for q in ("dG", "dT", "dn", "dk2", "dh")}


def separatrix_limits(
    body: Body,
    torque: Any,
    G: float,
    delta: float,
    lam: float,
    nu: float | None,
    *,
    orbit: Orbit | None = None,
    n_x: int = 48,
    n_psi: int = 16,
    n_nu: int = 32,
) -> SeparatrixLimits:
    r"""Limits at :math:`k^2\to1` of the averaged rates of :math:`G`, :math:`T`, :math:`\mathbf n`, :math:`k^2`.

    Parameters
    ----------
    body, torque, G, delta, lam, nu, orbit, n_x, n_psi, n_nu
        As in :func:`separatrix_crossing`.

    Returns
    -------
    SeparatrixLimits
        The common limit from the four regions and, per region, the coefficient of the :math:`1/K(k)`
        correction. For the paper's drag (diagonal :math:`I`): :math:`dG/d\tau\to -I_{22}G/A_2`,
        :math:`dT/d\tau\to -I_{22}G^2/A_2^2` (rotation about the intermediate axis), and
        :math:`K\,dk^2/d\tau\to \mp2(I_{33}/A_3 - I_{11}/A_1)` from the ``"max"``/``"min"`` side, the
        limit of (8).

    See Also
    --------
    SeparatrixLimits : its result.
    separatrix_crossing : what happens at the separatrix itself.
    averaged_rates : the rates at :math:`k^2 < 1` whose limits these are.

    Examples
    --------
    The paper's drag: the limits :math:`-I_{22}G/A_2` and :math:`-I_{22}G^2/A_2^2` above:

    >>> from rigidbody import euler_poinsot as ep
    >>> lim = ep.separatrix_limits(ep.Body(3.2, 2.6, 1.67), [2.322, 1.31, 1.425], 1.0, 0.7, 0.3, None)
    >>> print(f"{lim.dG:.6f} {-1.31 / 2.6:.6f} {lim.dT:.6f} {-1.31 / 2.6**2:.6f}")
    -0.503846 -0.503846 -0.193787 -0.193787
    """
    sep, fn, n, nu_, orb, nodes = separatrix_setup(body, torque, G, delta, lam, nu, orbit, n_x, n_psi, n_nu)
    n_x, n_psi, n_nu = nodes
    nus, wnu = orbit_nodes(nu_, orb, n_nu)
    A1, A2, A3 = body.A1, body.A2, body.A3
    Gf = sep.G
    saddles = np.array([[0.0, 0.0], [Gf, -Gf], [0.0, 0.0]])  # +e2, -e2
    Lb, Lo = psi_average(body, fn, saddles, n, nus, wnu, n_psi)
    at = _rates_at(body, saddles, Lb, Lo, n)
    lim = {q: 0.5 * (v[..., 0] + v[..., 1]) for q, v in at.items()}
    # J along an arc, in u = rate * t: from the start saddle to the middle and from the middle to the end
    x, w = np.polynomial.legendre.leggauss(n_x)
    xh = 0.25 * math.pi * (x - 1.0)  # (-pi/2, 0)
    wh = 0.25 * math.pi * w
    arc_J: dict[Arc, dict[str, Any]] = {}
    for arc in ARCS:
        s1, s3 = arc
        start = 0 if s1 * s3 == 1 else 1  # index of the saddle the arc leaves: +e2 when s1 s3 = 1
        J: dict[str, Any] = {}
        for half, xs, sad in ((0, xh, start), (1, -xh[::-1], 1 - start)):
            g = momenta_at(sep, xs, arc)
            Lb_, Lo_ = psi_average(body, fn, g, n, nus, wnu, n_psi)
            r = _rates_at(body, g, Lb_, Lo_, n)
            wq = wh if half == 0 else wh[::-1]
            for q, v in r.items():
                diff = (v - at[q][..., sad : sad + 1]) / np.cos(xs)  # du = dx / cos x
                J[q] = J.get(q, 0.0) + diff @ wq
        arc_J[arc] = J
    dk2_dD = (A1 - A3) / ((A1 - A2) * (A2 - A3))  # |dk^2/dD| at D = A2, both kinds
    slope: dict[Region, dict[str, Any]] = {}
    for reg in REGIONS:
        a, b = region_arcs(reg)
        s = {q: 0.25 * (arc_J[a][q] + arc_J[b][q]) for q in ("dG", "dT", "dh", "dn")}
        # D = G^2/2T: dD = -(2 A2^2/G^2) dh at the separatrix; k^2 decreases with D for 'max', increases for 'min'
        sign = float(reg.h_sign)
        s["dk2"] = sign * dk2_dD * (-2.0 * A2 * A2 / (Gf * Gf)) * s["dh"]
        slope[reg] = {q: (float(v) if np.ndim(v) == 0 else np.asarray(v)) for q, v in s.items()}
    return SeparatrixLimits(float(lim["dG"]), float(lim["dT"]), np.asarray(lim["dn"]), 0.0, slope)
