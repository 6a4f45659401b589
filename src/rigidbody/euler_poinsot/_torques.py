r"""Perturbing torques as objects: the protocol and the catalogue.

The protocol
------------
A perturbing torque is any callable

.. code-block:: python

    torque(omega, C, nu) -> M

vectorised over leading axes, so that the averaging engine evaluates a whole quadrature grid in one call:

``omega``
    body components of the angular velocity, shape ``(..., 3)``;
``C``
    direction cosines from the body axes to the orbital axes :math:`Ox_1x_2x_3` (``x_orbit = C @ x_body``;
    :math:`x_1` to the pericentre, :math:`x_3` along the orbit normal), shape ``(..., 3, 3)``;
``nu``
    the true anomaly, shape ``(...)`` (a float for a single state);
returns
    the body components of the torque, shape ``(..., 3)`` (or a shape that broadcasts to it, such as a constant
    ``(3,)``): finite real numbers. What a torque returns is checked wherever it is evaluated
    (:func:`._protocol.evaluate`): None, complex numbers, a scalar, another shape, NaN or infinities raise a
    ``TypeError``/``ValueError`` naming the torque (at a run's start), or end a run part-way with
    ``status = -1`` and a message naming the torque and the time.

The leading axes of the three arguments broadcast against each other but need not be equal: the averaging
engine passes ``omega`` of shape ``(1, 1, n, 3)``, ``C`` of shape ``(1, m, n, 3, 3)`` and ``nu`` of shape
``(l, 1, 1)`` so that a torque that does not depend on the attitude or on ``nu`` is evaluated once per node
of the phase (it checks on its first grid that the torque gives the same values as with full arrays, and
passes full arrays otherwise). The arrays may be read-only views: a torque must not write into them. The
torque is in the module's section-3 scaling divided by :math:`\varepsilon^2` (the full equations in the slow time
:math:`\tau` read :math:`d\mathbf g/d\tau = \varepsilon^{-2}\,\mathbf g\times\boldsymbol\omega + \mathbf M`):
Rachinskaya's drag is ``-I @ omega`` and the gravity-gradient torque is
:math:`3f(\nu)\,\boldsymbol\rho\times(A\boldsymbol\rho)` with :math:`\boldsymbol\rho = C^T(\cos\nu, \sin\nu, 0)`
the unit radius vector in body axes and :math:`f` the orbit factor of (3).

Torques add (``a + b``); a plain function with the signature above is a torque (``Torque + function``
works, and :func:`~rigidbody.euler_poinsot.simulate` and :func:`~rigidbody.euler_poinsot.averaged` accept
the bare function). The catalogue classes are frozen, validated dataclasses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from typing import Any, ClassVar

import numpy as np
from scipy import special

from ..core.validate import RESULT_ERRORS
from ._algebra import dk2_labelled, drag_rates_labelled, nstar_labelled
from ._engine import nu_nodes
from ._geomag import orbital_field
from ._model import Body, Orbit, as_drag, as_orbit, check_body, elliptic_ratios
from ._protocol import FunctionTorque, Torque, TorqueSum, evaluate
from ._state import Mean, State, amplitudes

__all__ = [
    "ConstantTorque",
    "FunctionTorque",
    "GravityGradient",
    "LinearDrag",
    "MagneticDipole",
    "Torque",
    "TorqueSum",
    "ViscousCavity",
]


@dataclass(frozen=True, eq=False)
class _ArrayEq(Torque):
    """Equality and hashing by value for frozen torque dataclasses that hold arrays."""

    def _key(self) -> tuple[Any, ...]:
        out: list[Any] = []
        for f in fields(self):
            v = getattr(self, f.name)
            out.append(v.tobytes() if isinstance(v, np.ndarray) else v)
        return tuple(out)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _ArrayEq) and type(self) is type(other) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash((type(self).__name__, self._key()))


def _frozen_array(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


# --------------------------------------------------------------------------------------------------
# the catalogue
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class LinearDrag(_ArrayEq):
    r"""Linear drag :math:`\mathbf M = -I\boldsymbol\omega` with a constant tensor :math:`I` in body axes.

    The drag of Rachinskaya's paper, formula (3) (with the sign that dissipates, see :ref:`errata-euler-poinsot`),
    and of L. D. Akulenko, D. D. Leshchenko, A. L. Rachinskaya, "Evolution of the satellite fast rotation
    due to the gravitational torque in a dragging medium", Mechanics of Solids 43(2), 173-184 (2008).
    Closed-form averages: :math:`dG/d\tau`, :math:`dT/d\tau` of (6) and the :math:`k^2` equation (8); the
    averaged drag has no component across :math:`\mathbf G`.

    Parameters
    ----------
    I : array_like
        The nondimensional tensor :math:`\tilde I = I/(G_0\varepsilon^2)` (3x3, any; or its 3 diagonal
        entries); its symmetric part must be positive definite (as for :class:`Drag`).

    See Also
    --------
    Drag, drag_rates, dk2_dtau

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (3), (6), (8).

    Examples
    --------
    The torque is :math:`-I\boldsymbol\omega` at every instant, and its averages are those of (6):

    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> drag = ep.LinearDrag([1.0, 2.0, 3.0])
    >>> drag([1.0, 1.0, 1.0], np.eye(3), 0.0).tolist()
    [-1.0, -2.0, -3.0]
    >>> body, I = ep.Body(3.2, 2.6, 1.67), [2.322, 1.31, 1.425]
    >>> r = ep.averaged_rates(body, ep.LinearDrag(I), 1.0, 0.5, 0.7, 0.3, None)
    >>> dG, dT = ep.drag_rates(body, I, 1.0, 0.5)
    >>> print(f"{r['dG']:.6f} {dG:.6f} {r['dT']:.6f} {dT:.6f}")
    -0.665135 -0.665135 -0.235227 -0.235227
    """

    _broadcasts: ClassVar[bool] = True

    I: Any = field()

    def __post_init__(self) -> None:
        object.__setattr__(self, "I", as_drag(self.I).I)

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        return -(np.asarray(omega, dtype=float) @ self.I.T)

    def closed_mean(self, st: State) -> Mean:
        # (6) and (8): only the diagonal enters; the averaged drag is along G
        Id = tuple(float(self.I[i, i]) for i in st.lab)
        dG, dT = drag_rates_labelled(st.a, Id, st.G, st.k2)  # type: ignore[arg-type]  # a 3-tuple
        return Mean(dG * st.n, dT, dk2_labelled(st.a, Id, st.k2))  # type: ignore[arg-type]  # a 3-tuple


@dataclass(frozen=True, eq=False)
class GravityGradient(_ArrayEq):
    r"""The gravity-gradient torque :math:`3\omega_0^2 f(\nu)\,\boldsymbol\rho\times(A\boldsymbol\rho)` of (3).

    :math:`\boldsymbol\rho = C^T(\cos\nu, \sin\nu, 0)` is the unit radius vector in body axes, :math:`A`
    the inertia tensor and :math:`f = (1+e\cos\nu)^3/(1-e^2)^3` the orbit factor (1 on a circular orbit).
    Source: F. L. Chernousko, "On the motion of a satellite about its centre of mass under the action of
    gravitational moments", Prikl. Mat. Mekh. 27(3), 474-483 (1963) [J. Appl. Math. Mech. 27(3), 708-722]
    (reference [2] of Rachinskaya's paper, which prints the pages as 472-483). Closed-form
    averages: :math:`N^*` of (6) (no change of :math:`G` and :math:`T` on average).

    Parameters
    ----------
    body : Body
        The body the torque acts on (a run with another body is refused).
    orbit : Orbit, optional
        The orbit (default circular); a run on another orbit is refused.
    omega0 : float
        The orbital mean motion in the units of the torque: 1 (default) in the module's scaling (the
        torque divided by :math:`\varepsilon^2`); the dimensional :math:`\omega_0` for dimensional torques.

    See Also
    --------
    Orbit, N_star, precession_rate

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (3), (6).

    Examples
    --------
    With the body axes along the orbital ones (:math:`C = 1`) at :math:`\nu = \pi/4` the radius vector is
    :math:`\boldsymbol\rho = (1, 1, 0)/\sqrt2`, so the torque is :math:`3\cdot\tfrac12(A_2 - A_1)
    = -0.9` about the third axis:

    >>> import math
    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> print(f"{ep.GravityGradient(body)([1.0, 0.0, 0.0], np.eye(3), math.pi / 4)[2]:.6f}")
    -0.900000

    On average it turns :math:`\mathbf G` at the :func:`precession_rate` without changing :math:`G`:

    >>> r = ep.averaged_rates(body, ep.GravityGradient(body), 1.0, 0.5, 0.7, 0.3, None)
    >>> print(abs(r["dG"]) < 1e-12, f"{r['dlam']:.6f} {ep.precession_rate(body, 1.0, 0.5, 0.7):.6f}")
    True -0.727719 -0.727719
    """

    _broadcasts: ClassVar[bool] = True

    body: Body
    orbit: Orbit | None = None
    omega0: float = 1.0

    def __post_init__(self) -> None:
        check_body(self.body)
        object.__setattr__(self, "orbit", as_orbit(self.orbit))
        w = self.omega0
        if isinstance(w, bool) or not isinstance(w, (int, float, np.integer, np.floating)) or not math.isfinite(w):
            raise TypeError(f"omega0 must be a finite real number, got {w!r}")
        if w <= 0:
            raise ValueError(f"omega0 (orbital mean motion) must be positive, got {w}")
        object.__setattr__(self, "omega0", float(w))

    def factor(self, nu: Any) -> Any:
        """:math:`3\\omega_0^2 f(\\nu)`, vectorised."""
        e = self.orbit.e  # type: ignore[union-attr]  # set to an Orbit in __post_init__
        c = 3.0 * self.omega0**2
        if e == 0.0:
            return c
        return c * (1.0 + e * np.cos(nu)) ** 3 / (1.0 - e * e) ** 3

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        C = np.asarray(C, dtype=float)
        nu = np.asarray(nu, dtype=float)
        cn: Any
        sn: Any
        A1, A2, A3 = self.body.A1, self.body.A2, self.body.A3
        held = nu.size == 1 and nu.ndim <= C.ndim - 2  # one true anomaly (the engine with nu held)
        if held:
            x = float(nu.reshape(()))
            cn, sn, f = math.cos(x), math.sin(x), self.factor(x)
        else:
            cn, sn = np.cos(nu), np.sin(nu)
            f = np.asarray(self.factor(nu), dtype=float)
        # the number of points, or more (a choice of code path only): arrays that broadcast against each other
        n_c = C.size // 9
        if (n_c if nu.size in (1, n_c) else n_c * nu.size) < 2048:
            c1, s1 = (cn, sn) if held else (cn[..., None], sn[..., None])
            rho = C[..., 0, :] * c1 + C[..., 1, :] * s1  # C^T e_r, e_r = (cos nu, sin nu, 0)
            r1, r2, r3 = rho[..., 0], rho[..., 1], rho[..., 2]
        else:  # large grids: component by component (NumPy's loops over a trailing axis of 3 are slow)
            r1 = C[..., 0, 0] * cn + C[..., 1, 0] * sn
            r2 = C[..., 0, 1] * cn + C[..., 1, 1] * sn
            r3 = C[..., 0, 2] * cn + C[..., 1, 2] * sn
        out = np.empty((*r1.shape, 3))
        out[..., 0] = f * (A3 - A2) * r2 * r3  # rho x (A rho)
        out[..., 1] = f * (A1 - A3) * r3 * r1
        out[..., 2] = f * (A2 - A1) * r1 * r2
        return out

    def closed_mean(self, st: State) -> Mean:
        # (6): d n/dt = (3 w0^2/2G) f N* (e_r . n)(n x e_r); over the orbit <f e_r e_r^T> = mf diag(1/2, 1/2, 0)
        Ns = nstar_labelled(st.a, st.k2)
        n1, n2, n3 = (float(x) for x in st.n)
        w2 = self.omega0**2
        if st.nu is None:  # n x e3 = (n2, -n1, 0)
            c = -0.75 * w2 * st.orbit.mean_factor * Ns * n3
            return Mean(np.array([c * n2, -c * n1, 0.0]), 0.0, 0.0)
        cn, sn = math.cos(st.nu), math.sin(st.nu)  # n x e_r = (-n3 sin nu, n3 cos nu, n1 sin nu - n2 cos nu)
        c = 1.5 * w2 * st.orbit.factor(st.nu) * Ns * (cn * n1 + sn * n2)
        return Mean(np.array([-c * n3 * sn, c * n3 * cn, c * (n1 * sn - n2 * cn)]), 0.0, 0.0)

    def check_setup(self, body: Body, orbit: Orbit) -> None:
        _check_same_body("GravityGradient", self.body, body)
        if orbit != self.orbit:
            raise ValueError(f"GravityGradient was built for {self.orbit!r}, but the run is on {orbit!r}")


def resolve(torque: Any) -> Any:
    """Split the ``torque`` argument of the public functions into its two meanings.

    Returns ``("drag", Drag)`` for a drag tensor (3x3 matrix, its diagonal, or a :class:`Drag`): Rachinskaya's
    drag *plus* the gravity-gradient torque, handled by the closed forms and the paper's code paths; and
    ``("torque", Torque)`` for a torque object or a plain callable, which is the whole perturbation.
    """
    if isinstance(torque, Torque):
        return "torque", torque
    if callable(torque):
        return "torque", FunctionTorque(torque)
    if isinstance(torque, (str, bytes)) or torque is None:
        raise TypeError(_WHAT + f", got {torque!r}")
    try:
        return "drag", as_drag(torque)
    except TypeError:
        raise TypeError(_WHAT + f", got {type(torque).__name__}") from None


_WHAT = ("torque must be a drag tensor (3x3 matrix, its diagonal or a Drag: drag plus gravity gradient), "
         "a torque object (LinearDrag, GravityGradient, ...) or a callable torque(omega, C, nu) -> M")


def drag_as_torque(drag: Any, body: Body, orbit: Orbit, omega0: float = 1.0) -> Torque:
    """The torque object equivalent to a drag tensor's meaning: linear drag plus gravity gradient."""
    return LinearDrag(drag) + GravityGradient(body, orbit, omega0)


def probe(torque: Torque, omega: np.ndarray, C: np.ndarray, nu: Any) -> np.ndarray:
    """Evaluate ``torque`` once at a run's start (through :func:`evaluate`: its output checked, the torque named);
    an error the torque itself raises is reported with the shapes it was called with."""
    try:
        return evaluate(torque, omega, C, nu, omega.shape)
    except RESULT_ERRORS:
        raise
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"the torque failed on omega of shape {omega.shape}, C of shape {C.shape}: {exc}") from exc


# --------------------------------------------------------------------------------------------------
# more of the catalogue: torques the literature averages over the Euler-Poinsot motion
# --------------------------------------------------------------------------------------------------
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
    return _frozen_array(a)


def _mean_omega1(st: State) -> float:
    r"""Mean of the labelled component :math:`\omega_1 = \sigma c_{dn}\operatorname{dn}` over the period:
    :math:`\sigma c_{dn}\pi/(2K)` (the other two components have zero mean)."""
    c_dn = amplitudes(st)[0]
    K = float(special.elliprf(0.0, st.mc, 1.0))
    return st.sigma * c_dn * math.pi / (2.0 * K)


def _check_same_body(name: str, own: Body, body: Body) -> None:
    if body != own:
        raise ValueError(f"{name} was built for {own!r}, but the run is for {body!r}")


@dataclass(frozen=True, eq=False)
class ConstantTorque(_ArrayEq):
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
class ViscousCavity(_ArrayEq):
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
        object.__setattr__(self, "P", _frozen_array(Pm))

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
        _check_same_body("ViscousCavity", self.body, body)


@dataclass(frozen=True, eq=False)
class MagneticDipole(_ArrayEq):
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
        """:math:`\\mathbf B` in the orbital axes at the true anomaly ``nu``, shape ``(..., 3)``."""
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
