r"""The Euler--Poinsot motion of a triaxial body in closed form (the unperturbed motion of Rachinskaya, sec. 2).

With :math:`\mathbf G` fixed along :math:`Oy_3`, the body components of the angular momentum are
:math:`G\alpha_{3j} = G(\sin\theta\sin\varphi, \sin\theta\cos\varphi, \cos\theta)` and, for the kind
``'max'`` (:math:`2TA_1\ge G^2>2TA_2`, the paper's case; Landau & Lifshitz, Mechanics, sec. 37),

.. math::
    \omega_1 = \sigma a_1\operatorname{dn}u,\quad \omega_2 = -\sigma a_2\operatorname{sn}u,\quad
    \omega_3 = a_3\operatorname{cn}u,\qquad u = \dot u\,t + u_0,

.. math::
    a_1 = G\sqrt{\frac{A_2-A_3}{A_1R}},\ a_2 = Gk\sqrt{\frac{A_1-A_3}{A_2R}},\
    a_3 = Gk\sqrt{\frac{A_1-A_2}{A_3R}},\ \dot u = G\sqrt{\frac{(A_1-A_2)(A_1-A_3)(A_2-A_3)}{A_1A_2A_3R}},

with :math:`R = A_1(A_2-A_3)+A_3(A_1-A_2)k^2` and :math:`k^2` of (5); :math:`\sigma=\pm1` is the sense of
rotation about :math:`z_1`. These amplitudes are Landau's written through :math:`(G, k^2)` with
:math:`G^2-2TA_3 = G^2(A_1-A_3)(A_2-A_3)/R`, :math:`2TA_1-G^2 = G^2k^2(A_1-A_2)(A_1-A_3)/R` (no
cancellation as :math:`k\to0`). The kind ``'min'`` is the same with the labels 1 and 3 exchanged
(:math:`\omega_3 = \sigma b_3\operatorname{dn}u`, :math:`\omega_2 = -\sigma b_2\operatorname{sn}u`,
:math:`\omega_1 = b_1\operatorname{cn}u`; signs checked against Euler's equations in the tests).
The body-frame period of the motion is :math:`4K/\dot u`; the separatrix
:math:`k^2 = 1` (infinite period) is a boundary both kinds exclude.

The precession angle follows from (1) with :math:`L = 0`,
:math:`\dot\psi = G(\sin^2\varphi/A_1+\cos^2\varphi/A_2)`, a :math:`2K`-periodic function of :math:`u`,
integrated in closed form with the incomplete elliptic integral of the third kind (:mod:`._precession`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core import averaging as avg
from ..core import elliptic as ell
from ..core import euler
from ..core.validate import real
from ._algebra import T_from, k2_from
from ._model import Body, check_kind
from ._physical import FreeMotion
from ._precession import elliptic_pi

__all__ = ["EulerPoinsot"]


@dataclass(frozen=True)
class EulerPoinsot:
    r"""Closed-form Euler--Poinsot motion with given :math:`G` and :math:`k^2`.

    Parameters
    ----------
    body : Body
    G : float
        Magnitude of the angular momentum (> 0).
    k2 : float
        Modulus squared, :math:`0 \le k^2 < 1` (formula (5) or its counterpart for ``kind='min'``).
    kind : {'max', 'min'}
        Rotation about the axis of the largest (``'max'``, the paper's case) or smallest moment.
    sigma : {+1, -1}
        Sense of rotation about the axis of rotation (sign of :math:`g_1` for 'max', :math:`g_3` for 'min').
    mc : float, optional
        :math:`1-k^2` when known more accurately than ``1 - k2`` (near the separatrix).

    See Also
    --------
    Separatrix : the limit :math:`k^2 \to 1`.
    k2_from, T_from : formula (5) and its inverse.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, section 2 and eq. (5).

    Examples
    --------
    :math:`|\mathbf g| = G` at every instant (the motion conserves the angular momentum):

    >>> from rigidbody.euler_poinsot import Body, EulerPoinsot
    >>> m = EulerPoinsot(Body(3.2, 2.6, 1.67), G=1.0, k2=0.5)
    >>> g = m.g(0.3)
    >>> bool(abs((g**2).sum() - 1.0) < 1e-14)
    True
    """

    body: Body
    G: float
    k2: float
    kind: str = "max"
    sigma: int = 1
    mc: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.body, Body):
            raise TypeError(f"body must be a Body, got {type(self.body).__name__}")
        check_kind(self.kind)
        G = real(self.G, "G")
        if G <= 0:
            raise ValueError(f"G must be positive, got {G}")
        k2 = real(self.k2, "k2")
        mc = 1.0 - k2 if self.mc is None else real(self.mc, "mc")
        if not (0.0 <= k2 <= 1.0):
            raise ValueError(f"k2 must lie in [0, 1), got {k2}")
        if mc <= 0.0:
            raise ValueError("k2 = 1 is the separatrix: the motion is not periodic (asymptotic motion)")
        if self.mc is not None and abs(k2 + mc - 1.0) > 1e-12:
            raise ValueError("k2 and mc are inconsistent: k2 + mc must equal 1")
        if self.sigma not in (1, -1):
            raise ValueError(f"sigma must be +1 or -1, got {self.sigma!r}")
        object.__setattr__(self, "G", G)
        object.__setattr__(self, "k2", k2)
        object.__setattr__(self, "mc", mc)

    # ------------------------------------------------------------------ constructors / properties
    @classmethod
    def from_GT(cls, body: Body, G: float, T: float, sigma: int = 1) -> EulerPoinsot:
        """The motion with given :math:`G` and :math:`T` (the kind is decided by :math:`G^2` vs :math:`2TA_2`).

        Examples
        --------
        The energy of a motion gives the motion back:

        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), G=1.0, k2=0.5)
        >>> back = ep.EulerPoinsot.from_GT(m.body, 1.0, m.T)
        >>> print(back.kind, f"{back.k2:.9f}")
        max 0.500000000
        """
        D = G * G / (2.0 * T)
        kind = "max" if D > body.A2 else "min"
        return cls(body, G, k2_from(body, G, T, kind), kind, sigma)

    @classmethod
    def from_state(cls, inertia: Any, omega: Any, attitude: Any = None) -> FreeMotion:
        r"""The torque-free motion of any rigid body from a physical state.

        Parameters
        ----------
        inertia : array_like
            The inertia tensor, 3x3 symmetric positive definite, in any body axes (its principal axes and their
            order are found, the rotation kept), or three principal moments in any order (the body axes are then
            principal). Refused (``ValueError``): asymmetry beyond rounding, a moment <= 0, moments that violate the
            triangle inequality.
        omega : array_like, shape (3,)
            The body angular velocity, in the same body axes, in any unit of 1/time: the motion's times are in
            that unit.
        attitude : scipy.spatial.transform.Rotation or array_like, optional
            Body -> inertial: a ``Rotation``, a quaternion (x, y, z, w: scalar last, as SciPy) or a direction
            cosine matrix (columns: body axes in inertial axes). Default the identity.

        Returns
        -------
        FreeMotion
            ``.omega(t)`` (user's body axes, shape ``t.shape + (3,)``), ``.rotation(t)`` (a ``Rotation``, body ->
            inertial), the paper's variables ``G, k2, kind, sigma, phase, frame`` and, for a triaxial body in
            ``'max'`` or ``'min'``, the paper's motion ``.paper``. Two equal moments, the sphere, a state on the
            separatrix or at rest have a motion too (``paper`` is then ``None``: :class:`Body` needs
            :math:`A_1 > A_2 > A_3`).

        Notes
        -----
        The paper's variables give the state back: with ``ep = m.paper``, ``A = m.axes``,
        ``omega = A @ ep.omega(t, m.phase)`` and ``attitude = m.frame @ euler.dcm(*ep.angles(t, m.phase)) @ A.T``
        (``rigidbody.core.euler.dcm``), the attitude exact to rounding: :math:`\psi` in closed form (the incomplete
        elliptic integral of the third kind), as in Principia's ``EulerSolver``.

        Examples
        --------
        A spin about the intermediate axis with a small wobble flips (the tennis-racket effect) while the
        angular momentum stays fixed in space:

        >>> import numpy as np
        >>> from rigidbody.euler_poinsot import EulerPoinsot
        >>> m = EulerPoinsot.from_state([3.0, 5.0, 7.0], [0.0, 0.4, 0.001])
        >>> m.kind, m.paper is not None
        ('max', True)
        >>> R = m.rotation(np.linspace(0.0, 40.0, 5))
        >>> L = R.apply(m.omega(np.linspace(0.0, 40.0, 5)) * [3.0, 5.0, 7.0])
        >>> bool(np.abs(L - m.momentum).max() < 1e-13)
        True
        """
        return FreeMotion(inertia, omega, attitude, paper=cls)

    @property
    def T(self) -> float:
        r"""Kinetic energy, the inverse of (5).

        Examples
        --------
        :math:`2T = \boldsymbol\omega\cdot\mathbf g` at any instant of the motion:

        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), G=1.0, k2=0.5)
        >>> print(f"{2 * m.T:.9f} {m.omega(0.7) @ m.g(0.7):.9f}")
        0.353753236 0.353753236
        """
        return float(T_from(self.body, self.G, self.k2, self.kind))

    def _amps(self) -> tuple[tuple[float, float, float], float]:
        """Amplitudes of (dn-, sn-, cn-components) of omega divided by (1, k, k), and du/dt."""
        b = self.body
        if self.kind == "max":
            A1, A2, A3 = b.A1, b.A2, b.A3
        else:
            A1, A2, A3 = b.A3, b.A2, b.A1
        k2 = self.k2
        R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
        G = self.G
        c_dn = G * math.sqrt((A2 - A3) / (A1 * R))
        c_sn = G * math.sqrt((A1 - A3) / (A2 * R))
        c_cn = G * math.sqrt((A1 - A2) / (A3 * R))
        rate = G * math.sqrt((A1 - A2) * (A1 - A3) * (A2 - A3) / (A1 * A2 * A3 * R))
        return (c_dn, c_sn, c_cn), rate

    @property
    def k(self) -> float:
        """The modulus :math:`k`.

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), G=1.0, k2=0.5)
        >>> print(f"{m.k:.6f}")
        0.707107
        """
        return math.sqrt(self.k2)

    @property
    def rate(self) -> float:
        r""":math:`\dot u`, the rate of the elliptic argument.

        Examples
        --------
        :math:`\omega_2` is proportional to :math:`\operatorname{sn}(\dot u\,t, k)` (largest at :math:`\dot u t = K`):

        >>> from rigidbody.core import elliptic as ell
        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), G=1.0, k2=0.5)
        >>> w2_max = m.omega(m.K / m.rate)[1]
        >>> print(f"{m.omega(0.4)[1] / w2_max:.9f} {ell.sn(m.rate * 0.4, m.k):.9f}")
        0.053136593 0.053136593
        """
        return self._amps()[1]

    @property
    def K(self) -> float:
        """Complete elliptic integral :math:`K(k)`.

        Examples
        --------
        SciPy's ``ellipk`` takes the parameter :math:`m = k^2`:

        >>> from scipy.special import ellipk
        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), G=1.0, k2=0.5)
        >>> print(f"{m.K:.9f} {ellipk(0.5):.9f}")
        1.854074677 1.854074677
        """
        return float(ell.K(mc=self.mc))

    @property
    def period(self) -> float:
        r"""Period of the body components of :math:`\boldsymbol\omega`: :math:`4K/\dot u`.

        Examples
        --------
        After half a period :math:`\omega_2` and :math:`\omega_3` (:math:`\operatorname{sn}`,
        :math:`\operatorname{cn}`) have changed sign and :math:`\omega_1` (:math:`\operatorname{dn}`) has not:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), G=1.0, k2=0.5)
        >>> print(np.round(m.omega(0.3 + m.period / 2) / m.omega(0.3), 12))
        [ 1. -1. -1.]
        """
        return 4.0 * self.K / self.rate

    # ------------------------------------------------------------------ the motion
    def _components(self, t: Any, u0: float, k_free: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Body components of omega; with ``k_free`` the sn- and cn-components without their factor k."""
        (c_dn, c_sn, c_cn), rate = self._amps()
        u = rate * np.asarray(t, dtype=float) + u0
        sn, cn, dn, _ = ell.jacobi(u, mc=self.mc)
        k = 1.0 if k_free else self.k
        s = self.sigma
        w_dn = s * c_dn * np.asarray(dn)
        w_sn = s * k * c_sn * np.asarray(sn)
        w_cn = k * c_cn * np.asarray(cn)
        if self.kind == "max":
            return w_dn, -w_sn, w_cn
        return w_cn, -w_sn, w_dn

    def _theta_phi(self, t: Any, u0: float) -> tuple[np.ndarray, np.ndarray]:
        r""":math:`\theta, \varphi` of :math:`\alpha_{3j} = g_j/G`; for ``'min'`` :math:`\tan\varphi = g_1/g_2`
        with the factor :math:`k` common to :math:`g_1, g_2` divided out (so defined at :math:`k = 0`)."""
        k_free = self.kind == "min"
        w1, w2, w3 = self._components(t, u0, k_free)
        A1, A2, A3 = self.body.A
        g12 = np.hypot(A1 * w1, A2 * w2)
        theta = np.arctan2(self.k * g12 if k_free else g12, A3 * w3)
        return theta, np.arctan2(A1 * w1, A2 * w2)

    def omega(self, t: Any, u0: float = 0.0) -> np.ndarray:
        r"""Body components of the angular velocity, shape ``(3, *t.shape)``.

        Parameters
        ----------
        t : array_like
            Time.
        u0 : float
            Initial elliptic argument (phase of the motion).

        Examples
        --------
        The motion repeats after ``period`` :math:`= 4K(k)/\dot u` (:math:`K` from SciPy), and
        :math:`\boldsymbol\omega\cdot\mathbf g = 2T` at every instant:

        >>> import numpy as np
        >>> from scipy.special import ellipk
        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), 1.0, 0.5)
        >>> print(f"{m.period:.6f} {4 * ellipk(0.5) / m.rate:.6f}")
        55.788752 55.788752
        >>> bool(np.allclose(m.omega(0.3 + m.period), m.omega(0.3), rtol=0, atol=1e-14))
        True
        >>> print(f"{m.omega(0.3) @ m.g(0.3):.6f} {2 * m.T:.6f}")
        0.353753 0.353753
        """
        w1, w2, w3 = self._components(t, u0)
        return np.stack([np.asarray(w1, float), np.asarray(w2, float), np.asarray(w3, float)])

    def g(self, t: Any, u0: float = 0.0) -> np.ndarray:
        r"""Body components of the angular momentum :math:`G\alpha_{3j}`, shape ``(3, *t.shape)``.

        Examples
        --------
        Its length is :math:`G` at every instant:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), G=1.0, k2=0.5)
        >>> g = m.g(np.linspace(0.0, m.period, 5))
        >>> g.shape, np.round(np.linalg.norm(g, axis=0), 12)
        ((3, 5), array([1., 1., 1., 1., 1.]))
        """
        return self.body.A.reshape((3,) + (1,) * np.ndim(t)) * self.omega(t, u0)

    def angles(self, t: Any, u0: float = 0.0, psi0: float = 0.0) -> tuple[Any, Any, Any]:
        r"""Euler angles :math:`(\psi, \theta, \varphi)` of the body relative to the frame :math:`Oy_i`.

        :math:`\cos\theta = g_3/G`, :math:`\tan\varphi = g_1/g_2` (rule of ``rigidbody.core.euler``:
        :math:`\alpha_{3j} = (\sin\theta\sin\varphi, \sin\theta\cos\varphi, \cos\theta)`), and
        :math:`\psi = \psi_0 + \int_0^t G(\sin^2\varphi/A_1 + \cos^2\varphi/A_2)\,dt` (closed form, exact to
        rounding). ``phi`` is
        in :math:`(-\pi, \pi]`.

        For ``kind='min'`` at :math:`k = 0` (pure spin about :math:`z_3`, :math:`\theta = 0` or :math:`\pi`,
        where only :math:`\psi\pm\varphi` is defined) :math:`\varphi` is the limit :math:`k\to0` of the
        angle of the nearby motions (:math:`g_1/g_2` with the common factor :math:`k` divided out): it keeps
        turning, :math:`\psi+\varphi` advances at :math:`G/A_3`, and the attitude is continuous in
        :math:`k^2`. (The degenerate-angle rule of ``rigidbody.core.euler.angles``, :math:`\varphi = 0`, is
        for reading angles off a matrix; here it would leave :math:`\psi` the only moving angle, at the
        wrong rate.)

        Examples
        --------
        :math:`\cos\theta = g_3/G`:

        >>> import math
        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), 1.0, 0.5)
        >>> psi, theta, phi = m.angles(0.3)
        >>> print(f"{math.cos(theta):.6f} {m.g(0.3)[2]:.6f}")
        0.379290 0.379290
        """
        theta, phi = self._theta_phi(t, u0)
        psi = psi0 + self._psi_integral(np.asarray(t, dtype=float), u0)
        f = (lambda x: float(x)) if np.ndim(t) == 0 else (lambda x: x)
        return f(psi), f(theta), f(phi)

    def _psi_rate_nodes(self, n: int) -> np.ndarray:
        """dpsi/dt on n uniform nodes of u over [0, 2K) (ratios formed with the k-free amplitudes)."""
        b = self.body
        (c_dn, c_sn, c_cn), _ = self._amps()
        s, sn, cn, dn = avg.phase_grid(n=n, mc=self.mc, period="2K")
        k2 = self.k2
        if self.kind == "max":
            x1 = (b.A1 * c_dn * dn) ** 2
            x2 = k2 * (b.A2 * c_sn * sn) ** 2
        else:  # g1, g2 both carry the factor k: divide it out
            x1 = (b.A1 * c_cn * cn) ** 2
            x2 = (b.A2 * c_sn * sn) ** 2
        return self.G * (x1 / b.A1 + x2 / b.A2) / (x1 + x2)

    def psi_rate_mean(self) -> float:
        r"""Mean precession rate :math:`\langle\dot\psi\rangle` over a period.

        Examples
        --------
        For :math:`k^2 = 0` the body spins about the axis of :math:`A_1` and precesses at :math:`G/A_1`; for
        :math:`k^2 > 0` the rate lies between :math:`G/A_1` and :math:`G/A_2`:

        >>> from rigidbody import euler_poinsot as ep
        >>> body = ep.Body(3.2, 2.6, 1.67)
        >>> print(f"{ep.EulerPoinsot(body, 1.0, 0.0).psi_rate_mean():.9f} {1 / 3.2:.9f}")
        0.312500000 0.312500000
        >>> bool(1 / 3.2 < ep.EulerPoinsot(body, 1.0, 0.5).psi_rate_mean() < 1 / 2.6)
        True
        """
        n = 2 * avg.n_nodes(mc=self.mc, period="2K")
        return float(np.mean(self._psi_rate_nodes(n)))

    def _psi_integral(self, t: np.ndarray, u0: float) -> np.ndarray:
        """psi(t) - psi(0) in closed form (:mod:`._precession`): with :math:`z_3` as the polar axis both kinds have
        :math:`\\dot\\psi = G/A_3 - c/(1 - n\\operatorname{sn}^2u)`, :math:`c = G(A_1 - A_3)/(A_1A_3)`,
        :math:`n = -A_3(A_1 - A_2)/(A_1(A_2 - A_3))` times :math:`k^2` for ``'max'``."""
        A1, A2, A3 = self.body.A1, self.body.A2, self.body.A3
        n = -A3 * (A1 - A2) / (A1 * (A2 - A3)) * (self.k2 if self.kind == "max" else 1.0)
        rate = self.rate
        u = rate * t + u0
        mc = float(self.mc)  # type: ignore[arg-type]  # set by __post_init__
        span = elliptic_pi(u, n, mc, *ell.jacobi(u, mc=mc)[:3]) - elliptic_pi(u0, n, mc, *ell.jacobi(u0, mc=mc)[:3])
        return self.G / A3 * t - self.G * (A1 - A3) / (A1 * A3 * rate) * span

    def nodes(self, n: int | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Times and body angular momenta on ``n`` uniform nodes of one period (for period averages).

        Returns
        -------
        t : numpy.ndarray, shape (n,)
        g : numpy.ndarray, shape (3, n)

        Examples
        --------
        Over a period :math:`g_2` and :math:`g_3` (:math:`\\operatorname{sn}`, :math:`\\operatorname{cn}`) average
        to zero:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> m = ep.EulerPoinsot(ep.Body(3.2, 2.6, 1.67), G=1.0, k2=0.5)
        >>> t, g = m.nodes(32)
        >>> t.shape, g.shape, np.round(g.mean(axis=1)[1:], 12) + 0.0
        ((32,), (3, 32), array([0., 0.]))
        """
        if n is None:
            n = avg.n_nodes(mc=self.mc, period="4K")
        t = np.arange(n) * (self.period / n)
        return t, self.g(t)

    def average(self, f: Any, n: int | None = None, n_psi: int = 16) -> Any:
        r"""Mean of ``f`` over the precession angle and one period of the motion (the averaging of sec. 2).

        Rachinskaya averages first over :math:`\psi` (uniformly: no resonance between the precession and
        the Euler--Poinsot period is assumed), then over time along :math:`\theta(t), \varphi(t)`. Both
        means use the trapezoid rule on uniform grids (spectrally accurate for periodic integrands).

        Parameters
        ----------
        f : callable
            ``f(alpha, omega)`` with ``alpha`` of shape ``(n_psi, n, 3, 3)`` (direction cosines
            :math:`\alpha_{ij} = y_i\cdot z_j`, body -> :math:`Oy_i`) and ``omega`` of shape ``(n, 3)``
            (body angular velocity); returns an array of shape ``(n_psi, n, ...)``.
        n : int, optional
            Time nodes per period (default from ``rigidbody.core.averaging.n_nodes``).
        n_psi : int
            Nodes in :math:`\psi`; exact for trigonometric polynomials of degree < ``n_psi``.

        Returns
        -------
        float or numpy.ndarray
            The mean over the two leading axes.

        Examples
        --------
        The mean moment of inertia about :math:`\mathbf G`, :math:`\langle J_{GG}\rangle =
        \langle\sum_j\alpha_{3j}^2A_j\rangle`, gives :math:`N^* = A_1 + A_2 + A_3 - 3\langle J_{GG}\rangle`,
        the closed form of (6) (:func:`N_star`):

        >>> from rigidbody import euler_poinsot as ep
        >>> body = ep.Body(3.2, 2.6, 1.67)
        >>> J = ep.EulerPoinsot(body, 1.0, 0.5).average(lambda a, w: (a[..., 2, :] ** 2 * body.A).sum(-1))
        >>> print(f"{body.A.sum() - 3 * J:.6f} {ep.N_star(body, 0.5):.6f}")
        -1.268617 -1.268617
        """
        t, g = self.nodes(n)
        omega = (g / self.body.A[:, None]).T
        theta, phi = self._theta_phi(t, 0.0)
        psi = np.arange(n_psi) * (2.0 * math.pi / n_psi)
        alpha = euler.dcm(psi[:, None], theta[None, :], phi[None, :])
        vals = np.asarray(f(alpha, omega), dtype=float)
        res = vals.mean(axis=(0, 1))
        return float(res) if np.ndim(res) == 0 else res

