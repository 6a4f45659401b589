r"""Perturbing torques as objects: the protocol and the paper's torques (drag and gravity gradient).

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
the bare function). The catalogue classes are frozen, validated dataclasses; the torques beyond the paper's
(constant, viscous cavity, magnetic dipole) are in :mod:`._catalogue`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from typing import Any, ClassVar

import numpy as np

from ..core.validate import RESULT_ERRORS
from ._algebra import dk2_labelled, drag_rates_labelled, nstar_labelled
from ._gravity import drag_gravity
from ._model import Body, Orbit, as_drag, as_orbit
from ._protocol import FunctionTorque, Torque, TorqueSum, evaluate
from ._state import Mean, State
from ._symbody import SymmetricBody, check_any_body

__all__ = [
    "ArrayEq",
    "FunctionTorque",
    "GravityGradient",
    "LinearDrag",
    "Torque",
    "TorqueSum",
    "check_same_body",
    "drag_as_torque",
    "frozen_array",
    "probe",
    "resolve",
]


@dataclass(frozen=True, eq=False)
class ArrayEq(Torque):
    """Equality and hashing by value for frozen torque dataclasses that hold arrays."""

    def _key(self) -> tuple[Any, ...]:
        out: list[Any] = []
        for f in fields(self):
            v = getattr(self, f.name)
            out.append(v.tobytes() if isinstance(v, np.ndarray) else v)
        return tuple(out)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ArrayEq) and type(self) is type(other) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash((type(self).__name__, self._key()))


def frozen_array(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


# --------------------------------------------------------------------------------------------------
# the catalogue
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class LinearDrag(ArrayEq):
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
class GravityGradient(ArrayEq):
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

    body: Body | SymmetricBody
    orbit: Orbit | None = None
    omega0: float = 1.0

    def __post_init__(self) -> None:
        check_any_body(self.body)
        object.__setattr__(self, "orbit", as_orbit(self.orbit))
        w = self.omega0
        if isinstance(w, bool) or not isinstance(w, (int, float, np.integer, np.floating)) or not math.isfinite(w):
            raise TypeError(f"omega0 must be a finite real number, got {w!r}")
        if w <= 0:
            raise ValueError(f"omega0 (orbital mean motion) must be positive, got {w}")
        object.__setattr__(self, "omega0", float(w))

    def factor(self, nu: Any) -> Any:
        r""":math:`3\omega_0^2 f(\nu)`, vectorised.

        Examples
        --------
        :math:`f = (a/r)^3` with :math:`r` the distance from the centre: at the pericentre :math:`r = a(1 - e)`, at
        the apocentre :math:`a(1 + e)`, so for :math:`e = 1/2` the factor is :math:`3\cdot2^3 = 24` and
        :math:`3/1.5^3 = 0.888889`; on a circular orbit it is :math:`3\omega_0^2` at every :math:`\nu`:

        >>> import math
        >>> from rigidbody import euler_poinsot as ep
        >>> body = ep.Body(3.2, 2.6, 1.67)
        >>> gg = ep.GravityGradient(body, ep.Orbit(0.5))
        >>> print(f"{gg.factor(0.0):.6f} {gg.factor(math.pi):.6f}", ep.GravityGradient(body, omega0=2.0).factor(1.0))
        24.000000 0.888889 12.0
        """
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
        out[..., 0], out[..., 1], out[..., 2] = drag_gravity((A1, A2, A3), f, (r1, r2, r3))  # f rho x (A rho)
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
        check_same_body("GravityGradient", self.body, body)
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


def drag_as_torque(drag: Any, body: Body | SymmetricBody, orbit: Orbit, omega0: float = 1.0) -> Torque:
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


def check_same_body(name: str, own: Body | SymmetricBody, body: Body | SymmetricBody) -> None:
    if body != own:
        raise ValueError(f"{name} was built for {own!r}, but the run is for {body!r}")
