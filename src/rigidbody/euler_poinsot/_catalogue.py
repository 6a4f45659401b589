r"""More of the torque catalogue: torques the literature averages over the Euler--Poinsot motion.

A torque fixed in the body (:class:`ConstantTorque`), a cavity filled with a viscous fluid
(:class:`ViscousCavity`) and a permanent magnet in a magnetic field (:class:`MagneticDipole`), each with its
closed-form average (derived in :ref:`ep-any-torque`); the protocol and the paper's torques are in
:mod:`._torques`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from scipy import special

from ._geomag import orbital_field
from ._grid import nu_nodes
from ._model import Body, Orbit, check_body, elliptic_ratios
from ._state import Mean, State, amplitudes
from ._torques import ArrayEq, check_same_body, frozen_array

__all__ = ["ConstantTorque", "MagneticDipole", "ViscousCavity"]


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b over the last axis (broadcasting), written out: np.cross is slow for the small arrays of a
    right-hand side."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def _vector(v: Any, name: str) -> np.ndarray:
    try:
        a = np.asarray(v, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be 3 real numbers, got {v!r}") from None
    if a.shape != (3,):
        raise ValueError(f"{name} must have shape (3,), got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite, got {v!r}")
    return frozen_array(a)


def _mean_omega1(st: State) -> float:
    r"""Mean of the labelled component :math:`\omega_1 = \sigma c_{dn}\operatorname{dn}` over the period:
    :math:`\sigma c_{dn}\pi/(2K)` (the other two components have zero mean)."""
    c_dn = amplitudes(st)[0]
    K = float(special.elliprf(0.0, st.mc, 1.0))
    return st.sigma * c_dn * math.pi / (2.0 * K)


@dataclass(frozen=True, eq=False)
class ConstantTorque(ArrayEq):
    r"""A torque constant in the body axes, :math:`\mathbf M = \mathbf M_0` (thrusters, a misaligned motor).

    The torque model (not its averages) of M. Romano, "Exact analytic solution for the rotation of a rigid
    body having spherical ellipsoid of inertia and subjected to a constant torque", Celestial Mechanics and
    Dynamical Astronomy 100, 181-189 (2008), doi:10.1007/s10569-007-9112-7, who solves the motion of a body
    with three equal moments exactly. Averaged over the Euler--Poinsot motion (derived here, see
    :ref:`ep-any-torque`): only the component along the axis of rotation survives,
    :math:`\langle C\mathbf M\rangle = \mathbf n\,a_1\bar\omega_1 M_{0,1}/G`,
    :math:`\langle\boldsymbol\omega\cdot\mathbf M\rangle = \bar\omega_1M_{0,1}` with
    :math:`\bar\omega_1 = \sigma c_{dn}\pi/2K` (labelled axes: 1 is the axis of :math:`A_1` for ``'max'``,
    of :math:`A_3` for ``'min'``). Not odd in :math:`\boldsymbol\omega`: the averages change sign with the
    sense of rotation ``sigma``.

    Parameters
    ----------
    M : array_like
        The three body components (section-3 scaling divided by :math:`\varepsilon^2`).

    See Also
    --------
    MagneticDipole : a torque whose average is of the same form (the magnet's moment fixed in the body).
    averaged_rates : the averaged rates of any torque (from this closed form).
    Torque : the protocol a torque follows (``closed_mean``).

    Examples
    --------
    At :math:`k^2 = 0` the body spins steadily about the axis of :math:`A_1` with :math:`\omega_1 = G/A_1`,
    so a torque :math:`M_{0,1} = 0.1` along it gives exactly :math:`dG/d\tau = 0.1` and
    :math:`dT/d\tau = \omega_1M_{0,1} = 0.1/3.2 = 0.03125`; both change sign with the sense of rotation:

    >>> from rigidbody import euler_poinsot as ep
    >>> body, push = ep.Body(3.2, 2.6, 1.67), ep.ConstantTorque([0.1, 0.0, 0.0])
    >>> for sigma in (1, -1):
    ...     r = ep.averaged_rates(body, push, 1.0, 0.0, 0.7, 0.3, None, sigma=sigma)
    ...     print(f"{r['dG']:.6f} {r['dT']:.6f}")
    0.100000 0.031250
    -0.100000 -0.031250
    """

    _broadcasts: ClassVar[bool] = True

    M: Any = field()

    def __post_init__(self) -> None:
        object.__setattr__(self, "M", _vector(self.M, "M"))

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        return np.zeros(np.shape(omega)) + self.M

    def closed_mean(self, st: State) -> Mean:
        w1 = _mean_omega1(st)
        M1 = float(self.M[st.lab[0]])
        a1, _, a3 = st.a
        dQ = 2.0 * (a1 - a3) * w1 * M1  # d(G^2 - 2 T a3)/dt: only omega_1 has a mean
        return Mean(st.n * (a1 * w1 * M1 / st.G), w1 * M1, -st.k2 * dQ / st.Q)


#: below this k^2 the mean of sn^4 comes from its power series (the recurrence cancels like eps/k^2)
_SN4_SERIES = 0.2


def _sn4_mean(k2: float) -> float:
    r""":math:`\langle\operatorname{sn}^4\rangle` over a period, stable for :math:`0 \le k^2 \le 1`.

    For :math:`k^2 \ge 0.2` the recurrence :math:`3k^2\langle\operatorname{sn}^4\rangle = 2(1+k^2)
    \langle\operatorname{sn}^2\rangle - 1` (differentiate :math:`\operatorname{sn}^3\operatorname{cn}
    \operatorname{dn}` over a period); below, the ratio of the series
    :math:`\int_0^{\pi/2}\sin^4\varphi/\Delta = \tfrac\pi2\sum a_na_{n+2}k^{2n}` and
    :math:`K = \tfrac\pi2\sum a_n^2k^{2n}`, :math:`a_n = (1/2)_n/n!` (converged to 1e-21 in 30 terms).
    """
    if k2 >= _SN4_SERIES:
        _, sn2 = elliptic_ratios(k2)
        return (2.0 * (1.0 + k2) * sn2 - 1.0) / (3.0 * k2)
    a = [1.0]
    for n in range(1, 33):
        a.append(a[-1] * (n - 0.5) / n)
    num = sum(a[n] * a[n + 2] * k2**n for n in range(31))
    den = sum(a[n] * a[n] * k2**n for n in range(31))
    return num / den


@dataclass(frozen=True, eq=False)
class ViscousCavity(ArrayEq):
    r"""The torque of a cavity filled with a highly viscous fluid (small Reynolds number).

    .. math:: \mathbf M = P\ddot{\boldsymbol\omega} + \boldsymbol\omega\times P\dot{\boldsymbol\omega},

    with :math:`\dot{\boldsymbol\omega} = A^{-1}(A\boldsymbol\omega\times\boldsymbol\omega)` and
    :math:`\ddot{\boldsymbol\omega}` its derivative along the rigid motion, :math:`P` a symmetric positive
    semi-definite tensor of the cavity's shape times :math:`\rho/\nu` (density over kinematic viscosity).
    The method is F. L. Chernousko's: "Motion of a solid body with cavities filled with viscous liquid at
    small Reynolds numbers", Zh. Vychisl. Mat. Mat. Fiz. 5(6), 1049-1070 (1965), and the book "Motion of a
    solid body with cavities filled with a viscous fluid" (Computing Centre of the USSR Academy of Sciences,
    Moscow, 1968). Averaging over the Euler--Poinsot motion with it: L. D. Akulenko, Ya. S. Zinkevich,
    D. D. Leshchenko, A. L. Rachinskaya, "Rotations of a satellite with a cavity filled with a viscous fluid
    under the action of gravitational and light torques" (in Russian), Visnyk of Odesa National
    University, Mathematics and Mechanics 13(11), 117-131 (2008) (reference [7] of Rachinskaya's paper), and
    D. D. Leshchenko, L. D. Akulenko, A. L. Rachinskaya, Yu. S. Shchetinina, "Rotational motion of a satellite
    with viscous fluid under the action of the external resistance torque", Mathematics in Engineering,
    Science and Aerospace (2015). We saw only titles and abstracts of these: the form of the torque (from the
    relative angular momentum :math:`-P\dot{\boldsymbol\omega}` of the fluid) and its averages were derived
    here (:ref:`ep-any-torque`) and are checked against the engine (which averages the
    torque itself) and the full equations. The fluid is internal: :math:`G` is conserved on average
    (:math:`C\mathbf M = d(CP\dot{\boldsymbol\omega})/dt`), the energy is dissipated,
    :math:`\langle\dot T\rangle = -\langle\dot{\boldsymbol\omega}\cdot P\dot{\boldsymbol\omega}\rangle`, so a
    spin about the axis of the smallest moment decays towards the separatrix (the energy sink at constant
    :math:`G` behind the flat spin of Explorer 1).

    Parameters
    ----------
    body : Body
        The body (the torque uses its moments; a run with another body is refused).
    P : array_like
        The tensor :math:`\tilde P = \rho P\Omega_0^2/(\nu G_0\varepsilon^2)` in body axes (3x3 symmetric
        positive semi-definite, or its 3 diagonal entries). Only the diagonal enters the averages.

    See Also
    --------
    LinearDrag : a dissipative torque from outside the body, which changes :math:`G` as well.
    average_torque : the engine's average of the torque itself, the check of the closed form.

    References
    ----------
    :ref:`L. D. Akulenko, Ya. S. Zinkevich, D. D. Leshchenko, A. L. Rachinskaya (2008) <ref-azlr-2008>`.

    Examples
    --------
    The fluid is internal: on average :math:`G` keeps its value while the energy falls
    (:math:`\langle\dot T\rangle = -\langle\dot{\boldsymbol\omega}\cdot P\dot{\boldsymbol\omega}\rangle < 0`):

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> r = ep.averaged_rates(body, ep.ViscousCavity(body, [1.0, 1.0, 1.0]), 1.0, 0.5, 0.7, 0.3, None)
    >>> print(abs(r["dG"]) < 1e-12, r["dT"] < 0)
    True True
    """

    _broadcasts: ClassVar[bool] = True

    body: Body
    P: Any = field()

    def __post_init__(self) -> None:
        check_body(self.body)
        try:
            Pm = np.asarray(self.P, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"P must be a 3x3 real matrix or its 3 diagonal entries, got {self.P!r}") from None
        if Pm.shape == (3,):
            Pm = np.diag(Pm)
        if Pm.shape != (3, 3) or not np.all(np.isfinite(Pm)):
            raise ValueError(f"P must be a finite 3x3 matrix (or 3 diagonal entries), got shape {Pm.shape}")
        if np.abs(Pm - Pm.T).max() > 1e-12 * max(np.abs(Pm).max(), 1e-300):
            raise ValueError("P must be symmetric")
        if np.linalg.eigvalsh(Pm).min() < -1e-12 * np.abs(Pm).max():
            raise ValueError(f"P must be positive semi-definite (the fluid dissipates), eigenvalues "
                             f"{np.linalg.eigvalsh(Pm)}")
        object.__setattr__(self, "P", frozen_array(Pm))

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        A = self.body.A
        w = np.asarray(omega, dtype=float)
        g = w * A
        gdot = _cross(g, w)  # dg/dt of the torque-free motion
        wdot = gdot / A
        wddot = (_cross(gdot, w) + _cross(g, wdot)) / A
        return wddot @ self.P + _cross(w, wdot @ self.P)

    def closed_mean(self, st: State) -> Mean:
        a1, a2, a3 = st.a
        k2 = st.k2
        c_dn, c_sn, c_cn = amplitudes(st)
        _, s2 = elliptic_ratios(k2)
        s4 = _sn4_mean(k2)
        sncn, sndn, cndn = s2 - s4, s2 - k2 * s4, 1.0 - (1.0 + k2) * s2 + k2 * s4
        # <(d omega_i/dt)^2> in the labelled axes: d omega_1/dt = (a2 - a3)/a1 omega_2 omega_3, cyclic
        w1 = ((a2 - a3) / a1) ** 2 * k2 * k2 * (c_sn * c_cn) ** 2 * sncn
        w2 = ((a3 - a1) / a2) ** 2 * k2 * (c_cn * c_dn) ** 2 * cndn
        w3 = ((a1 - a2) / a3) ** 2 * k2 * (c_dn * c_sn) ** 2 * sndn
        P = self.P
        l1, l2, l3 = st.lab
        dT = -(P[l1, l1] * w1 + P[l2, l2] * w2 + P[l3, l3] * w3)
        c = (a2 - a3) / (a1 - a2)
        return Mean(np.zeros(3), float(dT), float(2.0 * dT * (c * a1 + k2 * a3) / st.Q))

    def check_setup(self, body: Body, orbit: Orbit) -> None:
        check_same_body("ViscousCavity", self.body, body)


@dataclass(frozen=True, eq=False)
class MagneticDipole(ArrayEq):
    r"""The torque :math:`\mathbf m\times\mathbf B` of a permanent magnet in a magnetic field.

    :math:`\mathbf m` fixed in the body, :math:`\mathbf B` in the orbital axes, constant or a function of the true
    anomaly: the torque model of passive magnetic attitude control (Gerhardt & Palo, SSC10, 2010). Averaged
    (derived in :doc:`/euler_poinsot`, "Any torque"), :math:`\langle C\mathbf m\rangle = \mathbf n\,a_1
    \bar\omega_1m_1/G`: :math:`\mathbf G` precesses about :math:`\mathbf B` at :math:`a_1\bar\omega_1m_1
    |\mathbf B|/G^2` (reversed with ``sigma``), :math:`G, T, k^2` constant on average (:math:`\bar\omega_1` as
    in :class:`ConstantTorque`).

    Parameters
    ----------
    m : array_like
        The magnetic moment in body axes (3 components).
    B : array_like or callable
        The field in the orbital axes: 3 components, or a function ``B(nu) -> (..., 3)`` vectorised over
        ``nu``. :math:`\tilde m\tilde B = mB/(G_0\Omega_0\varepsilon^2)` in the module's scaling.

    See Also
    --------
    ConstantTorque : the same average along the axis of rotation, for a torque fixed in the body.

    Examples
    --------
    At :math:`k^2 = 0` (:math:`\bar\omega_1 = G/A_1`) a magnet :math:`m_1 = 0.2` in a field :math:`0.5` along
    the orbit normal turns :math:`\mathbf G` at :math:`-m_1|\mathbf B|/G = -0.1` (:math:`\dot{\mathbf n}
    \propto \mathbf n\times\mathbf B`), and leaves :math:`G` unchanged:

    >>> from rigidbody import euler_poinsot as ep
    >>> body, magnet = ep.Body(3.2, 2.6, 1.67), ep.MagneticDipole([0.2, 0.0, 0.0], [0.0, 0.0, 0.5])
    >>> r = ep.averaged_rates(body, magnet, 1.0, 0.0, 0.7, 0.3, None)
    >>> print(abs(r["dG"]) < 1e-12, f"{r['dlam']:.6f}")
    True -0.100000
    """

    m: Any = field()
    B: Any = field()

    def __post_init__(self) -> None:
        object.__setattr__(self, "m", _vector(self.m, "m"))
        if not callable(self.B):
            object.__setattr__(self, "B", _vector(self.B, "B"))

    def field_at(self, nu: Any) -> np.ndarray:
        r""":math:`\mathbf B` in the orbital axes at the true anomaly ``nu``, shape ``(..., 3)``.

        Examples
        --------
        A constant field is the same at every :math:`\nu`. The Earth's dipole on an equatorial circular orbit of
        radius :math:`a_E` is :math:`-g_1^0` = 29404.8 nT (IGRF-13) to the north, along the orbit normal, at every
        :math:`\nu`:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> ep.MagneticDipole([0.2, 0.0, 0.0], [0.0, 0.0, 0.5]).field_at(np.array([0.0, 1.0])).tolist()
        [[0.0, 0.0, 0.5], [0.0, 0.0, 0.5]]
        >>> earth = ep.DipoleField(0.0, 0.0, ep.IGRF_RADIUS, scale=1e9)  # in nanotesla
        >>> B = ep.MagneticDipole([0.2, 0.0, 0.0], earth).field_at(np.array([0.0, 2.0]))
        >>> (np.round(B, 6) + 0.0).tolist()
        [[0.0, 0.0, 29404.8], [0.0, 0.0, 29404.8]]
        """
        return orbital_field(self.B, nu)

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        Bb = np.einsum("...ij,...i->...j", np.asarray(C, dtype=float), self.field_at(nu))  # C^T B
        return _cross(np.broadcast_to(self.m, Bb.shape), Bb)

    def closed_mean(self, st: State) -> Mean:
        if st.nu is None:  # the field averaged over the orbit in time (Kepler's law)
            nu, w = nu_nodes(st.orbit.e, 256)
            B = w @ self.field_at(nu)
        else:
            B = self.field_at(st.nu)
        mu = st.a[0] * _mean_omega1(st) * float(self.m[st.lab[0]]) / st.G  # <C m> = mu n
        n = st.n
        L = mu * np.array([n[1] * B[2] - n[2] * B[1], n[2] * B[0] - n[0] * B[2], n[0] * B[1] - n[1] * B[0]])
        return Mean(L, 0.0, 0.0)
