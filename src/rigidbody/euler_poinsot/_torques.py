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
    the body components of the torque, shape ``(..., 3)``.

The arrays passed in may be read-only broadcast views: a torque must not write into them. The torque is in
the module's section-3 scaling divided by :math:`\varepsilon^2` (the full equations in the slow time
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
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from ._engine import _Mean, _State
from ._model import Body, Orbit, _as_orbit, _check_body, _dk2, _drag_rates, _nstar, as_drag

__all__ = ["FunctionTorque", "GravityGradient", "LinearDrag", "Torque", "TorqueSum"]


class Torque:
    """Base class of the torque objects (see the module docstring for the protocol).

    Subclasses implement ``__call__(omega, C, nu)``. Adding two torques (or a torque and a plain function)
    gives a :class:`TorqueSum`.
    """

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        raise NotImplementedError

    def __add__(self, other: Any) -> TorqueSum:
        return TorqueSum((*_parts(self), *_parts(as_torque(other, "other"))))

    def __radd__(self, other: Any) -> TorqueSum:
        return TorqueSum((*_parts(as_torque(other, "other")), *_parts(self)))

    def parts(self) -> tuple[Torque, ...]:
        """The torques this one is the sum of (itself for a single torque)."""
        return (self,)

    def _check_setup(self, body: Body, orbit: Orbit) -> None:
        """Refuse a run whose body or orbit differs from the one this torque was built for."""

    def _closed(self, st: _State) -> _Mean | None:
        """The closed-form average at a slow state, or None when the torque has none (the engine is used)."""
        return None


def _parts(t: Torque) -> tuple[Torque, ...]:
    return t.parts()


def as_torque(value: Any, name: str = "torque") -> Torque:
    """``value`` as a :class:`Torque`: a torque object is returned as is, a plain callable is wrapped."""
    if isinstance(value, Torque):
        return value
    if callable(value):
        return FunctionTorque(value)
    raise TypeError(
        f"{name} must be a torque object or a callable torque(omega, C, nu) -> M, got {type(value).__name__}"
    )


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


@dataclass(frozen=True)
class FunctionTorque(Torque):
    """A plain function ``fun(omega, C, nu) -> M`` used as a torque object (what ``as_torque`` wraps)."""

    fun: Callable[..., Any]

    def __post_init__(self) -> None:
        if not callable(self.fun):
            raise TypeError(f"fun must be callable (omega, C, nu) -> M, got {type(self.fun).__name__}")

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        return np.asarray(self.fun(omega, C, nu), dtype=float)


@dataclass(frozen=True)
class TorqueSum(Torque):
    """The sum of torques (what ``a + b`` returns); nested sums are flattened."""

    terms: tuple[Torque, ...]

    def __post_init__(self) -> None:
        flat: list[Torque] = []
        for t in self.terms:
            flat.extend(as_torque(t, "terms").parts())
        if not flat:
            raise ValueError("terms: a TorqueSum needs at least one torque")
        object.__setattr__(self, "terms", tuple(flat))

    def parts(self) -> tuple[Torque, ...]:
        return self.terms

    def __iter__(self) -> Iterator[Torque]:
        return iter(self.terms)

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        out = np.asarray(self.terms[0](omega, C, nu), dtype=float)
        for t in self.terms[1:]:
            out = out + np.asarray(t(omega, C, nu), dtype=float)
        return out

    def _check_setup(self, body: Body, orbit: Orbit) -> None:
        for t in self.terms:
            t._check_setup(body, orbit)


# --------------------------------------------------------------------------------------------------
# the catalogue
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class LinearDrag(_ArrayEq):
    r"""Linear drag :math:`\mathbf M = -I\boldsymbol\omega` with a constant tensor :math:`I` in body axes.

    The drag of Rachinskaya's paper, formula (3) (with the sign that dissipates, see ``docs/errata.md``),
    and of L. D. Akulenko, D. D. Leshchenko, A. L. Rachinskaya, "Evolution of the satellite fast rotation
    due to the gravitational torque in a dragging medium", Mechanics of Solids 43(2), 173-184 (2008).
    Closed-form averages: :math:`dG/d\tau`, :math:`dT/d\tau` of (6) and the :math:`k^2` equation (8); the
    averaged drag has no component across :math:`\mathbf G`.

    Parameters
    ----------
    I : array_like
        The nondimensional tensor :math:`\tilde I = I/(G_0\varepsilon^2)` (3x3, any; or its 3 diagonal
        entries); its symmetric part must be positive definite (as for :class:`Drag`).
    """

    I: Any = field()

    def __post_init__(self) -> None:
        object.__setattr__(self, "I", as_drag(self.I).I)

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        return -(np.asarray(omega, dtype=float) @ self.I.T)

    def _closed(self, st: _State) -> _Mean:
        # (6) and (8): only the diagonal enters; the averaged drag is along G
        Id = tuple(float(self.I[i, i]) for i in st.lab)
        dG, dT = _drag_rates(st.a, Id, st.G, st.k2)  # type: ignore[arg-type]  # a 3-tuple
        return _Mean(dG * st.n, dT, _dk2(st.a, Id, st.k2))  # type: ignore[arg-type]  # a 3-tuple


@dataclass(frozen=True, eq=False)
class GravityGradient(_ArrayEq):
    r"""The gravity-gradient torque :math:`3\omega_0^2 f(\nu)\,\boldsymbol\rho\times(A\boldsymbol\rho)` of (3).

    :math:`\boldsymbol\rho = C^T(\cos\nu, \sin\nu, 0)` is the unit radius vector in body axes, :math:`A`
    the inertia tensor and :math:`f = (1+e\cos\nu)^3/(1-e^2)^3` the orbit factor (1 on a circular orbit).
    Source: F. L. Chernousko, "On the motion of a satellite about its centre of mass under the action of
    gravitational moments", PMM 27(3), 472-483 (1963) (reference [2] of Rachinskaya's paper). Closed-form
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
    """

    body: Body
    orbit: Orbit | None = None
    omega0: float = 1.0

    def __post_init__(self) -> None:
        _check_body(self.body)
        object.__setattr__(self, "orbit", _as_orbit(self.orbit))
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
        cn, sn = np.cos(nu)[..., None], np.sin(nu)[..., None]
        rho = C[..., 0, :] * cn + C[..., 1, :] * sn  # C^T e_r, e_r = (cos nu, sin nu, 0)
        f = np.asarray(self.factor(nu), dtype=float)
        A1, A2, A3 = self.body.A1, self.body.A2, self.body.A3
        r1, r2, r3 = rho[..., 0], rho[..., 1], rho[..., 2]
        out = np.empty(rho.shape)
        out[..., 0] = f * (A3 - A2) * r2 * r3  # rho x (A rho)
        out[..., 1] = f * (A1 - A3) * r3 * r1
        out[..., 2] = f * (A2 - A1) * r1 * r2
        return out

    def _closed(self, st: _State) -> _Mean:
        # (6): d n/dt = (3 w0^2/2G) f N* (e_r . n)(n x e_r); over the orbit <f e_r e_r^T> = mf diag(1/2, 1/2, 0)
        Ns = _nstar(st.a, st.k2)
        n1, n2, n3 = (float(x) for x in st.n)
        w2 = self.omega0**2
        if st.nu is None:  # n x e3 = (n2, -n1, 0)
            c = -0.75 * w2 * st.orbit.mean_factor * Ns * n3
            return _Mean(np.array([c * n2, -c * n1, 0.0]), 0.0, 0.0)
        cn, sn = math.cos(st.nu), math.sin(st.nu)  # n x e_r = (-n3 sin nu, n3 cos nu, n1 sin nu - n2 cos nu)
        c = 1.5 * w2 * st.orbit.factor(st.nu) * Ns * (cn * n1 + sn * n2)
        return _Mean(np.array([-c * n3 * sn, c * n3 * cn, c * (n1 * sn - n2 * cn)]), 0.0, 0.0)

    def _check_setup(self, body: Body, orbit: Orbit) -> None:
        if body != self.body:
            raise ValueError(f"GravityGradient was built for {self.body!r}, but the run is for {body!r}")
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
    """Evaluate ``torque`` once and check its output (shape like ``omega``, finite) with a clear message."""
    try:
        M = np.asarray(torque(omega, C, nu), dtype=float)
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"the torque failed on omega of shape {omega.shape}, C of shape {C.shape}: {exc}") from exc
    if M.shape != omega.shape:
        raise ValueError(
            f"the torque must return body components of shape {omega.shape} (like omega), got {M.shape}"
        )
    if not np.all(np.isfinite(M)):
        raise ValueError("the torque returned non-finite values at the initial state")
    return M
