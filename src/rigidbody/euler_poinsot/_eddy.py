r"""The eddy-current torque of a conducting body spinning in a magnetic field, and its averages in closed form.

.. math:: \mathbf M = \bigl(P(\boldsymbol\omega\times\mathbf b)\bigr)\times\mathbf b,
   \qquad \mathbf b = C^T\mathbf B(\nu),

with :math:`P` the body's magnetic tensor (symmetric, positive semi-definite; :math:`P = pI` for a sphere or a
thin spherical shell) and :math:`\mathbf B` the field in the orbital axes. The torque is linear in
:math:`\boldsymbol\omega` and quadratic in :math:`\mathbf b`, so its average over the precession angle
:math:`\psi` about :math:`\mathbf G` needs only :math:`S = \mathbf B\mathbf B^T` (held :math:`\nu`) or its
mean over the orbit in time (``nu=None``), and its average over the elliptic phase only the moments of the
angular velocity of degree 2 and 4 (:func:`omega_moments`). The derivation is in :ref:`ep-eddy` (the
theory page).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core.kernel import SCALAR, sn2_excess
from ._geomag import DipoleField, orbital_field
from ._grid import nu_nodes
from ._model import Orbit
from ._protocol import Torque
from ._state import Mean, State, amplitudes

__all__ = ["EddyCurrent", "omega_moments", "sn4_mean"]

#: the Levi-Civita symbol
_EPS = np.zeros((3, 3, 3))
_EPS[0, 1, 2] = _EPS[1, 2, 0] = _EPS[2, 0, 1] = 1.0
_EPS[0, 2, 1] = _EPS[2, 1, 0] = _EPS[1, 0, 2] = -1.0

#: below this k^2 the excess <sn^2> - 1/2 over k^2 is its series 1/16 + k^2/32 (next term ~ k^4: below 1e-16)
_SMALL_K2 = 1e-8


def sn4_mean(k2: float, mc: float) -> float:
    r""":math:`\langle\operatorname{sn}^4\rangle` over a period, without cancellation for :math:`0 \le k^2 < 1`.

    From the recurrence :math:`3k^2\langle\operatorname{sn}^4\rangle = 2(1+k^2)\langle\operatorname{sn}^2\rangle
    - 1` (differentiate :math:`\operatorname{sn}^3\operatorname{cn}\operatorname{dn}` over a period) with
    :math:`\langle\operatorname{sn}^2\rangle = 1/2 + x`: :math:`\langle\operatorname{sn}^4\rangle = 1/3 +
    2(1+k^2)(x/k^2)/3`, where :math:`x/k^2` comes from the AGM sum of
    :func:`rigidbody.core.kernel.sn2_excess` (every term positive) and tends to 1/16 (limit 3/8 at
    :math:`k = 0`).
    """
    x = 1.0 / 16.0 + k2 / 32.0 if k2 < _SMALL_K2 else sn2_excess(SCALAR, k2, mc) / k2
    return 1.0 / 3.0 + 2.0 * (1.0 + k2) * x / 3.0


def omega_moments(st: State) -> tuple[np.ndarray, np.ndarray]:
    r"""The means of :math:`\omega_i\omega_j` and :math:`\omega_i\omega_j\omega_k\omega_l` over a period of the
    Euler--Poinsot motion, in body axes.

    With :math:`\boldsymbol\omega = (\sigma c_{dn}\operatorname{dn}, -\sigma kc_{sn}\operatorname{sn},
    kc_{cn}\operatorname{cn})` in the labelled axes, a monomial :math:`\omega_1^a\omega_2^b\omega_3^c` has a
    non-zero mean only for even :math:`b` and :math:`c` (the motion is symmetric under :math:`u\to-u` and
    :math:`u\to u+2K`), so for even :math:`a` too at even degree; these means follow from
    :math:`\langle\operatorname{sn}^2\rangle` and :func:`sn4_mean` (:math:`\operatorname{cn}^2 = 1 -
    \operatorname{sn}^2`, :math:`\operatorname{dn}^2 = 1 - k^2\operatorname{sn}^2`).

    Returns
    -------
    m2, m4 : numpy.ndarray
        Shapes (3, 3) and (3, 3, 3, 3), symmetric in their indices.
    """
    k2, mc = st.k2, st.mc
    s2 = 0.5 + sn2_excess(SCALAR, k2, mc)
    s4 = sn4_mean(k2, mc)
    c_dn, c_sn, c_cn = amplitudes(st)
    w1, w2, w3 = c_dn * c_dn, k2 * c_sn * c_sn, k2 * c_cn * c_cn  # the squared amplitudes
    i, j, k = st.lab
    m2 = np.zeros((3, 3))
    m2[i, i], m2[j, j], m2[k, k] = w1 * (1.0 - k2 * s2), w2 * s2, w3 * (1.0 - s2)
    m4 = np.zeros((3, 3, 3, 3))
    m4[i, i, i, i] = w1 * w1 * (1.0 - 2.0 * k2 * s2 + k2 * k2 * s4)
    m4[j, j, j, j] = w2 * w2 * s4
    m4[k, k, k, k] = w3 * w3 * (1.0 - 2.0 * s2 + s4)
    for a, b, v in ((i, j, w1 * w2 * (s2 - k2 * s4)), (i, k, w1 * w3 * (1.0 - (1.0 + k2) * s2 + k2 * s4)),
                    (j, k, w2 * w3 * (s2 - s4))):
        for p in ((a, a, b, b), (a, b, a, b), (a, b, b, a), (b, b, a, a), (b, a, b, a), (b, a, a, b)):
            m4[p] = v
    return m2, m4


def _magnetic_tensor(P: Any) -> np.ndarray:
    """``P`` (a scalar, 3 diagonal entries or a 3x3 matrix) as a read-only symmetric positive semi-definite
    3x3 array; a ``TypeError``/``ValueError`` naming ``P`` otherwise."""
    try:
        Pm = np.array(P, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"P must be a real number, 3 diagonal entries or a 3x3 real matrix, got {P!r}") from None
    if Pm.ndim == 0:
        Pm = Pm * np.eye(3)
    elif Pm.shape == (3,):
        Pm = np.diag(Pm)
    if Pm.shape != (3, 3) or not np.all(np.isfinite(Pm)):
        raise ValueError(f"P must be a finite number, 3 diagonal entries or a 3x3 matrix, got shape {Pm.shape} "
                         f"({P!r})")
    size = max(float(np.abs(Pm).max()), 1e-300)
    if np.abs(Pm - Pm.T).max() > 1e-12 * size:
        raise ValueError(f"P (the magnetic tensor) must be symmetric, got {Pm.tolist()}")
    eig = np.linalg.eigvalsh(Pm)
    if eig.min() < -1e-12 * size:
        raise ValueError("P (the magnetic tensor) must be positive semi-definite: with M = (P (omega x B)) x B the "
                         f"power omega . M = -(omega x B) . P (omega x B) must not be positive; eigenvalues {eig}")
    Pm = 0.5 * (Pm + Pm.T)
    Pm.setflags(write=False)
    return Pm


@dataclass(frozen=True, eq=False)
class EddyCurrent(Torque):
    r"""The eddy-current torque :math:`\mathbf M = (P(\boldsymbol\omega\times\mathbf b))\times\mathbf b` of a
    conducting body in a magnetic field, :math:`\mathbf b = C^T\mathbf B(\nu)` the field in body axes.

    The currents a rotating conductor carries in a field oppose the rotation across the field (Lenz): the
    power is :math:`\boldsymbol\omega\cdot\mathbf M = -(\boldsymbol\omega\times\mathbf b)\cdot P
    (\boldsymbol\omega\times\mathbf b) \le 0` for the positive semi-definite magnetic tensor :math:`P` (the sign
    that makes the torque dissipative; a tensor with a negative eigenvalue is refused). For a sphere,
    :math:`P = pI` with :math:`p = 2\pi\sigma_c r^4 h/3` for a thin shell (radius :math:`r`, thickness
    :math:`h`, conductivity :math:`\sigma_c`) or :math:`2\pi\sigma_c r^5/15` for a solid sphere, in the
    low-frequency limit; then :math:`\mathbf M = -p\,\mathbf b\times(\boldsymbol\omega\times\mathbf b)`, the
    spin component across the field decays at the rate :math:`pB^2/A`. The model of Praly et al. (2012),
    Gómez & Walker (2015), Efimov, Pritykin & Sidorenko (2018).

    Averaged over the Euler--Poinsot motion (derived in :doc:`/euler_poinsot`, "Eddy currents"; checked
    against the averaging engine and a quadrature): :math:`\langle C\mathbf M\rangle = -\bar c\,
    (\operatorname{tr}S - S)\,\mathbf n` with :math:`S = \mathbf B\mathbf B^T` (its mean over the orbit in
    time for ``nu=None``), :math:`\bar c = \langle\operatorname{tr}P\,\boldsymbol\gamma\cdot
    \boldsymbol\omega - \boldsymbol\gamma\cdot P\boldsymbol\omega\rangle/2`, :math:`\boldsymbol\gamma =
    A\boldsymbol\omega/G`: :math:`\mathbf G` shrinks across the field and keeps its component along a constant
    one; :math:`dT/d\tau` and :math:`dk^2/d\tau` from the means of quadratic and quartic forms of
    :math:`\boldsymbol\omega` (:func:`omega_moments`). All in closed form (the engine is not needed).

    Parameters
    ----------
    P : float or array_like
        The magnetic tensor in body axes: a number :math:`p` (:math:`P = pI`), 3 diagonal entries or a
        symmetric positive semi-definite 3x3 matrix, in the units that make :math:`P B^2\omega` a torque of
        the module's scaling (divided by :math:`\varepsilon^2`) for the units of ``B``.
    B : array_like or callable
        The field in the orbital axes: 3 components, or a function ``B(nu) -> (..., 3)`` vectorised over
        ``nu`` (e.g. :class:`DipoleField`).

    See Also
    --------
    DipoleField : the geomagnetic field along an orbit.
    MagneticDipole : the torque of a permanent magnet in the same field.

    References
    ----------
    :ref:`N. Praly et al. (2012) <ref-praly-2012>`, :ref:`N. O. Gómez, S. J. I. Walker (2015)
    <ref-gomez-walker-2015>` (the magnetic tensor), :ref:`S. Efimov, D. Pritykin, V. Sidorenko (2018)
    <ref-efimov-2018>`.

    Examples
    --------
    A sphere-like body spinning about the orbit normal in a field along the first orbital axis: the whole
    spin is across the field, so on average :math:`dG/d\tau = -pB^2G/A_1` at :math:`k^2 = 0` (the steady
    spin about the axis of the largest moment: :math:`-0.2\cdot1/3.2 = -0.0625` for :math:`G = 1`), and the
    energy :math:`T = G^2/2A_1 = 1/6.4` falls at twice that relative rate:

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> r = ep.averaged_rates(body, ep.EddyCurrent(0.2, [1.0, 0.0, 0.0]), 1.0, 0.0, 0.0, 0.0, 0.3)
    >>> print(f"{r['dG']:.6f} {r['dT'] * 6.4:.6f}")
    -0.062500 -0.125000
    """

    P: Any = field()
    B: Any = field()
    _orbit_means: dict[float, np.ndarray] = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "P", _magnetic_tensor(self.P))
        if not callable(self.B):
            try:
                b = np.array(self.B, dtype=float)
            except (TypeError, ValueError):
                raise TypeError(f"B must be 3 real numbers or a callable B(nu) -> (..., 3), got {self.B!r}") from None
            if b.shape != (3,) or not np.all(np.isfinite(b)):
                raise ValueError(f"B must be 3 finite numbers (the field in the orbital axes), got {self.B!r}")
            b.setflags(write=False)
            object.__setattr__(self, "B", b)

    def _key(self) -> tuple[Any, ...]:
        B = self.B.tobytes() if isinstance(self.B, np.ndarray) else self.B
        return self.P.tobytes(), B

    def __eq__(self, other: object) -> bool:
        return isinstance(other, EddyCurrent) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(("EddyCurrent", self._key()))

    def field_at(self, nu: Any) -> np.ndarray:
        """:math:`\\mathbf B` in the orbital axes at the true anomaly ``nu``, shape ``(..., 3)``.

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> ep.EddyCurrent(0.5, [0.0, 0.0, 2.0]).field_at([0.0, 1.0]).tolist()
        [[0.0, 0.0, 2.0], [0.0, 0.0, 2.0]]
        """
        return orbital_field(self.B, nu)

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        b = np.einsum("...ij,...i->...j", np.asarray(C, dtype=float), self.field_at(nu))  # C^T B
        w = np.asarray(omega, dtype=float)
        wb = np.cross(w, b)
        return np.cross(wb @ self.P, b)  # P symmetric: (P x) = x P

    def field_square(self, nu: float | None, e: float) -> np.ndarray:
        r""":math:`S = \mathbf B\mathbf B^T` at ``nu``, or its mean over the orbit of eccentricity ``e`` in time
        for ``nu=None`` (the trapezoid rule in the true anomaly with the time weights, nodes doubled until it
        settles; cached per eccentricity).

        Examples
        --------
        A constant field has :math:`S = \\mathbf B\\mathbf B^T` at every point and as the orbit's mean:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> eddy = ep.EddyCurrent(0.5, [1.0, 0.0, 2.0])
        >>> S = eddy.field_square(None, 0.3)
        >>> bool(np.allclose(S, [[1, 0, 2], [0, 0, 0], [2, 0, 4]], rtol=0, atol=1e-14))
        True
        """
        if nu is not None:
            B = self.field_at(nu)
            return np.outer(B, B)
        cache = self._orbit_means
        if e not in cache:
            cache[e] = _orbit_mean(self.field_at, e)
        return cache[e]

    def check_setup(self, body: Any, orbit: Orbit) -> None:
        """Refuse a run on another orbit than the one a :class:`DipoleField` ``B`` was built for.

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> eddy = ep.EddyCurrent(0.5, ep.DipoleField(1.0, 0.0, 7e6))  # built for the circular orbit
        >>> eddy.check_setup(ep.Body(3.2, 2.6, 1.67), ep.Orbit(0.1))
        Traceback (most recent call last):
        ...
        ValueError: EddyCurrent's field B was built for Orbit(e=0.0), but the run is on Orbit(e=0.1)
        """
        if isinstance(self.B, DipoleField) and self.B.orbit != orbit:
            raise ValueError(f"EddyCurrent's field B was built for {self.B.orbit!r}, but the run is on {orbit!r}")

    def closed_mean(self, st: State) -> Mean:
        return eddy_mean(self.P, self.field_square(st.nu, st.orbit.e), st)


def _orbit_mean(field_at: Any, e: float) -> np.ndarray:
    """The mean of B B^T over one orbit in time: the trapezoid rule (geometric convergence for a smooth
    periodic field), nodes doubled from 64 until two counts agree to 4e-15 (a few roundings of the sums), at
    most 2^14 nodes."""
    n, prev = 64, None
    while True:
        nu, w = nu_nodes(e, n)
        B = field_at(nu)
        S = (B.T * w) @ B
        S = 0.5 * (S + S.T)
        if (prev is not None and np.abs(S - prev).max() <= 4e-15 * np.abs(S).max()) or n >= 2**14:
            return S
        prev, n = S, 2 * n


def _quadratic_mean(P: np.ndarray, S: np.ndarray, D: np.ndarray, m2: np.ndarray, Aw4: np.ndarray, st: State) -> float:
    r"""The mean of :math:`\mathbf b^T[D\boldsymbol\omega]_\times P[\boldsymbol\omega]_\times\mathbf b`
    (:math:`\sum_i D_i\omega_iM_i` for a diagonal weight ``D``) over the precession angle and the phase."""
    n = st.n
    trS, Snn = float(np.trace(S)), float(n @ S @ n)
    tr = float(np.einsum("ij,j,ij->", P, D, m2) - np.trace(P) * np.einsum("i,ii->", D, m2))
    # gamma^T K gamma = (A w x D w) . P (w x A w) / G^2 with the fourth moments
    gkg = float(np.einsum("ijk,k,il,lmn,jkmn->", _EPS, D, P, _EPS, Aw4)) / st.G**2
    return 0.5 * (trS - Snn) * (tr - gkg) + Snn * gkg


def eddy_mean(P: np.ndarray, S: np.ndarray, st: State) -> Mean:
    r"""The averaged effect of the eddy-current torque of tensor ``P`` in a field of square ``S = <B B^T>``.

    :math:`\langle C\mathbf M\rangle = -\bar c\,(\operatorname{tr}S - S)\mathbf n` with :math:`\bar c =
    \langle\operatorname{tr}P\,\boldsymbol\gamma\cdot\boldsymbol\omega - \boldsymbol\gamma\cdot
    P\boldsymbol\omega\rangle/2`, :math:`\boldsymbol\gamma = A\boldsymbol\omega/G` (the term
    :math:`\tfrac32\langle\boldsymbol\gamma\cdot P(\boldsymbol\omega\times\boldsymbol\gamma)\rangle\,
    \mathbf n\times S\mathbf n` of the average over :math:`\psi` vanishes: :math:`\boldsymbol\gamma\cdot
    P(\boldsymbol\omega\times\boldsymbol\gamma) = -\tfrac12 d(\boldsymbol\gamma\cdot P\boldsymbol\gamma)/dt`
    has no mean over a period); the rates of :math:`T` and :math:`k^2` from :func:`_quadratic_mean`."""
    m2, m4 = omega_moments(st)
    A = st.body.A
    n, G = st.n, st.G
    Aw4 = np.einsum("j,n,jkmn->jkmn", A, A, m4)  # A_j A_n <w_j w_k w_m w_n>
    c = 0.5 * (np.trace(P) * float(A @ np.diag(m2)) - float(np.einsum("i,ij,ij->", A, P, m2))) / G
    L = -c * (np.trace(S) * n - S @ n)
    a1, a2, a3 = st.a
    wP, wQ = np.zeros(3), np.zeros(3)
    for ax, ai in zip(st.lab, st.a):
        wP[ax], wQ[ax] = a1 - ai, ai - a3
    dT = _quadratic_mean(P, S, np.ones(3), m2, Aw4, st)
    dP = 2.0 * _quadratic_mean(P, S, wP, m2, Aw4, st)
    dQ = 2.0 * _quadratic_mean(P, S, wQ, m2, Aw4, st)
    cc = (a2 - a3) / (a1 - a2)
    return Mean(L, dT, (cc * dP - st.k2 * dQ) / st.Q)
