r"""A spacecraft's physical state in SI units, mapped onto Rachinskaya's nondimensional problem: :class:`Spacecraft`
(its ``averaged`` and ``simulate``), the paper's start :class:`PaperStart` and the results in SI units
:class:`SpacecraftSolution`.

The scaling (section 3 of the paper, as the module uses it; :doc:`/euler_poinsot`, "Scaling"): the unit of
rate is :math:`\Omega_0 = |\boldsymbol\omega(0)|` (the paper's definition), the unit of angular momentum
:math:`G_0 = |\mathbf G(0)|`, so :math:`\tilde G_0 = 1`, :math:`\tilde A_i = A_i\Omega_0/G_0`,
:math:`\tilde{\boldsymbol\omega} = \boldsymbol\omega/\Omega_0`, :math:`\tilde T = T/(G_0\Omega_0)`; the orbital
mean motion :math:`n` is :math:`\varepsilon` in that unit, :math:`\varepsilon = n/\Omega_0`, and the slow time
is :math:`\tau = \varepsilon^2\Omega_0 t`. A torque :math:`\mathbf M` (N m) enters the module's equations
:math:`d\tilde{\mathbf g}/d\tau = \varepsilon^{-2}\tilde{\mathbf g}\times\tilde{\boldsymbol\omega} + \tilde{\mathbf M}`
as :math:`\tilde{\mathbf M} = \mathbf M/(G_0\varepsilon^2\Omega_0)` (from :math:`d\mathbf G/dt = \mathbf M`): a
drag tensor :math:`I` (N m s) as :math:`\tilde I = I/(G_0\varepsilon^2)`, a magnet :math:`\mathbf m` (A m^2) in
a field :math:`\mathbf B` (T) as :math:`\tilde{\mathbf m} = \mathbf m/(G_0\varepsilon^2\Omega_0)`, :math:`\mathbf B`
unchanged, and the gravity gradient :math:`3n^2f(\nu)\boldsymbol\rho\times J\boldsymbol\rho` as
:math:`3f(\nu)\boldsymbol\rho\times\tilde A\boldsymbol\rho` (:class:`GravityGradient` of :math:`\tilde A`).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ..core.ode import Solution
from ..core.validate import finite_array, span
from ._averaged import averaged
from ._catalogue import ConstantTorque, MagneticDipole
from ._checks import check_tau_eval
from ._eddy import EddyCurrent
from ._geomag import DipoleField
from ._kepler import KeplerOrbit
from ._motion import EulerPoinsot
from ._physical import as_attitude
from ._scstart import PaperStart, angles_of, paper_start, symmetry_axes
from ._simulate import simulate
from ._symbody import SymmetricBody
from ._torques import GravityGradient, LinearDrag

__all__ = ["Spacecraft", "SpacecraftSolution"]


@dataclass(frozen=True, eq=False)
class SpacecraftSolution:
    r"""A run of :meth:`Spacecraft.averaged` or :meth:`Spacecraft.simulate` in SI units, with the paper's slow
    variables alongside.

    Attributes
    ----------
    t : numpy.ndarray
        Times (s).
    G, T, spin_rate : numpy.ndarray
        :math:`|\mathbf G|` (N m s), the kinetic energy (J) and the spin rate about :math:`\mathbf G`,
        :math:`\boldsymbol\omega\cdot\mathbf G/G = 2T/G` (rad/s; constant on the torque-free motion).
    momentum : numpy.ndarray
        :math:`\mathbf G` in the inertial frame, shape ``(len(t), 3)`` (N m s).
    k2, kind, sigma, delta, lam, nu : numpy.ndarray
        The paper's slow variables: modulus squared, kind of motion, sense, the direction of :math:`\mathbf G` in
        the orbital axes :math:`Ox_i` (rad; ``lam`` continuous) and the true anomaly (constant ``nu0`` with
        ``orbit_averaged=True``, where it is averaged out).
    omega : numpy.ndarray or None
        ``simulate``: the angular velocity in the user's body axes, ``(len(t), 3)`` (rad/s).
    attitude : scipy.spatial.transform.Rotation or None
        ``simulate``: the attitude (body -> inertial) at each time.
    status, message, event
        As the paper's run (0: the end reached; 1: a stop, named in ``event`` and explained in ``message``, whose
        times are the slow time :math:`\tau = t\,d\tau/dt`; -1: a failure).
    paper : Solution or None
        The nondimensional run (``None`` where the closed form was used: a torque-free body that the paper's
        :class:`Body` does not describe).
    start : PaperStart or None
        The scaling (``None`` as ``paper``).

    See Also
    --------
    Spacecraft.averaged, Spacecraft.simulate : the runs that return it.
    rigidbody.core.ode.Solution : the nondimensional result inside it.

    Examples
    --------
    The gravity gradient alone keeps :math:`G` and :math:`T` on average; it turns :math:`\mathbf G`:

    >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
    >>> sc = Spacecraft([12.0, 10.0, 7.0], [0.08, 0.01, 0.06], orbit=KeplerOrbit(altitude=500e3))
    >>> sol = sc.averaged((0.0, 86400.0), [0.0, 86400.0])
    >>> print(sol.status, f"{sol.G[-1] / sol.G[0]:.12f} {sol.T[-1] / sol.T[0]:.12f}", sol.momentum.shape)
    0 1.000000000000 1.000000000000 (2, 3)
    """

    t: np.ndarray
    G: np.ndarray
    T: np.ndarray
    spin_rate: np.ndarray
    momentum: np.ndarray
    k2: np.ndarray
    kind: np.ndarray
    sigma: np.ndarray
    delta: np.ndarray
    lam: np.ndarray
    nu: np.ndarray
    status: int
    message: str
    event: str | None
    omega: np.ndarray | None = None
    attitude: Rotation | None = None
    paper: Solution | None = None
    start: PaperStart | None = None

    def __repr__(self) -> str:
        span_ = f"t=[{self.t[0]:.6g}, {self.t[-1]:.6g}] s" if len(self.t) else "no samples"
        return f"<SpacecraftSolution {span_} ({len(self.t)} samples) status={self.status} message={self.message!r}>"


class Spacecraft:
    r"""A spacecraft's physical state in SI units on an orbit, and its slow evolution under torques.

    Parameters
    ----------
    inertia : array_like
        The inertia tensor in kg m^2: 3x3 symmetric positive definite in any body axes, or three principal
        moments in any order (as :meth:`EulerPoinsot.from_state`).
    omega : array_like, shape (3,)
        The body angular velocity in rad/s, in the same body axes.
    attitude : scipy.spatial.transform.Rotation or array_like, optional
        Body -> the inertial frame of ``orbit`` (a ``Rotation``, a quaternion scalar last, or a direction cosine
        matrix); default the identity.
    orbit : KeplerOrbit
        The orbit, with the true anomaly at ``t = 0`` and its orientation in the inertial frame.

    Attributes
    ----------
    motion : FreeMotion
        The torque-free motion (times in s; ``rotation(t)`` body -> the inertial frame).
    inertia : numpy.ndarray
        The tensor in the user's body axes (3x3).
    orbit : KeplerOrbit

    See Also
    --------
    EulerPoinsot.from_state : the torque-free motion alone.
    averaged, simulate : the nondimensional runs it calls.

    Notes
    -----
    Frames: the torques act in the orbital axes :math:`Ox_i` of the paper (:math:`x_1` to the pericentre,
    :math:`x_3` along the orbit normal); the user's inertial frame is :math:`Ox_i` turned by
    ``orbit.orientation``. Units and scaling: :doc:`/euler_poinsot`, "From a spacecraft's state", and the how-to
    :doc:`/howto/spacecraft`.

    Examples
    --------
    A satellite spinning at 0.1 rad/s in a 500 km orbit: the paper's :math:`\varepsilon` is the ratio of the
    orbital rate to the spin, and the start comes back from the paper's variables to rounding:

    >>> import numpy as np
    >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
    >>> sc = Spacecraft([12.0, 10.0, 7.0], [0.08, 0.01, 0.06], orbit=KeplerOrbit(altitude=500e3))
    >>> p = sc.paper
    >>> print(f"eps = {p.eps:.5f}, k2 = {p.k2_0:.4f}, kind {p.kind!r}")
    eps = 0.01101, k2 = 0.4961, kind 'max'
    >>> omega, attitude = p.state()
    >>> bool(np.allclose(omega, [0.08, 0.01, 0.06], rtol=0, atol=1e-15))
    True
    """

    def __init__(self, inertia: Any, omega: Any, attitude: Any = None, *, orbit: KeplerOrbit) -> None:
        if not isinstance(orbit, KeplerOrbit):
            raise TypeError(f"orbit must be a KeplerOrbit (SI units), got {orbit!r}")
        self.orbit = orbit
        R = as_attitude(attitude)
        self.motion = EulerPoinsot.from_state(inertia, omega, R)
        # the same motion relative to the orbital axes, which the paper's start is read from
        self._in_orbit_axes = EulerPoinsot.from_state(inertia, omega, orbit.to_inertial().inv() * R)
        J = finite_array(inertia, "inertia")
        self.inertia = np.diag(J) if J.shape == (3,) else J

    def __repr__(self) -> str:
        m = self.motion
        return (f"<Spacecraft moments=({', '.join(f'{a:.6g}' for a in m.moments)}) kg m^2, |omega|="
                f"{np.linalg.norm(m.omega0):.6g} rad/s, kind={m.kind!r}, orbit n={self.orbit.n:.6g} rad/s>")

    @functools.cached_property
    def paper(self) -> PaperStart:
        """The paper's nondimensional start (a :class:`SymmetricBody` for two equal moments; a ``ValueError`` for a
        state it does not describe: at rest, exactly on a triaxial body's separatrix)."""
        return paper_start(self._in_orbit_axes, self.orbit)

    def torque(self, *, gravity_gradient: bool = True, drag: Any = None, dipole: Any = None, field: Any = None,
               torque: Any = None, eddy: Any = None) -> Any:
        r"""The torques in the paper's scaling, a torque object (``None``: no torque).

        Parameters
        ----------
        gravity_gradient : bool
            The gravity-gradient torque of the orbit, :math:`3n^2f(\nu)\,\boldsymbol\rho\times J\boldsymbol\rho`.
        drag : array_like, optional
            A linear drag :math:`-I\boldsymbol\omega`: the tensor :math:`I` in N m s in the user's body axes
            (3x3, or its diagonal); its symmetric part positive definite.
        dipole, field : array_like, optional
            A magnet: its moment in A m^2 (user's body axes) and the field in T in the inertial frame (3
            components, or a function ``field(nu) -> (..., 3)`` of the true anomaly; a :class:`DipoleField` is
            already in the orbital axes and is taken as it is); both or neither (``field`` also for ``eddy``).
        torque : array_like, optional
            A torque constant in the body, N m (user's body axes).
        eddy : float or array_like, optional
            Eddy currents (:class:`EddyCurrent`): the magnetic tensor :math:`P` in S m^4 (the torque
            :math:`(P(\boldsymbol\omega\times\mathbf B))\times\mathbf B` in N m for rad/s and T; a number, 3 diagonal
            entries or 3x3 in the user's body axes), in ``field``.

        Returns
        -------
        Torque or None
            :class:`GravityGradient`, :class:`LinearDrag`, :class:`MagneticDipole`, :class:`ConstantTorque`,
            :class:`EddyCurrent` of the paper's start (:attr:`paper`), summed.

        Examples
        --------
        A drag tensor of :math:`G_0\varepsilon^2` N m s is the paper's :math:`\tilde I = 1`:

        >>> import numpy as np
        >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
        >>> sc = Spacecraft([12.0, 10.0, 7.0], [0.0, 0.0, 0.1], orbit=KeplerOrbit(mean_motion=1e-3))
        >>> p = sc.paper
        >>> drag = sc.torque(gravity_gradient=False, drag=np.array([1.0, 2.0, 3.0]) * p.G_unit * p.eps**2)
        >>> print([f"{x:.6f}" for x in drag.I.diagonal()])
        ['1.000000', '2.000000', '3.000000']
        """
        if not isinstance(gravity_gradient, bool):
            raise TypeError(f"gravity_gradient must be True or False, got {gravity_gradient!r}")
        if (dipole is None and eddy is None) != (field is None):
            raise ValueError("field (T, inertial frame) goes with dipole (A m^2, body axes) or eddy (S m^4): give "
                             "the field with them, and only with them")
        if not gravity_gradient and drag is None and dipole is None and torque is None and eddy is None:
            return None
        p = self.paper
        P, c = p.axes, 1.0 / p.torque_unit
        parts: list[Any] = []
        if gravity_gradient:
            parts.append(GravityGradient(p.body, p.orbit))
        if drag is not None:
            I = finite_array(drag, "drag")
            if I.shape not in ((3,), (3, 3)):
                raise ValueError(f"drag must be a 3x3 tensor in N m s (or its diagonal), got shape {I.shape}")
            parts.append(LinearDrag(P.T @ (np.diag(I) if I.shape == (3,) else I) @ P * (c * p.Omega0)))
        B = None if field is None else field if isinstance(field, DipoleField) else self.orbit.field_in_orbit_axes(
            field if callable(field) else _vector(field, "field"))
        if dipole is not None:
            parts.append(MagneticDipole(P.T @ _vector(dipole, "dipole") * c, B))
        if eddy is not None:
            Pm = finite_array(eddy, "eddy")
            if Pm.shape not in ((), (3,), (3, 3)):
                raise ValueError(f"eddy must be a number, 3 diagonal entries or a 3x3 tensor in S m^4, got shape "
                                 f"{Pm.shape}")
            Pm = Pm * np.eye(3) if Pm.shape == () else np.diag(Pm) if Pm.shape == (3,) else Pm
            parts.append(EddyCurrent(P.T @ Pm @ P * (c * p.Omega0), B))
        if torque is not None:
            parts.append(ConstantTorque(P.T @ _vector(torque, "torque") * c))
        return sum(parts[1:], parts[0]) if parts else None

    def averaged(self, t_span: Any, t_eval: Any = None, *, gravity_gradient: bool = True, drag: Any = None,
                 dipole: Any = None, field: Any = None, torque: Any = None, eddy: Any = None,
                 orbit_averaged: bool = False, **options: Any) -> SpacecraftSolution:
        r"""The slow evolution (the averaged system (9) of any torque) in SI units.

        Parameters
        ----------
        t_span : (float, float)
            Start and end time in s: the spacecraft's state (and ``orbit.nu0``) is the one at ``t_span[0]``.
        t_eval : array_like, optional
            Output times in s (default the integrator's steps).
        gravity_gradient, drag, dipole, field, torque, eddy
            The torques in SI units, as in :meth:`torque`.
        orbit_averaged : bool
            Average the torques over the orbit too (the paper's :math:`\varepsilon = 0`); default: the true
            anomaly runs with time.
        **options
            Passed to :func:`averaged` (``rtol``, ``k2_max``, ``min_spin_ratio``, ...).

        Returns
        -------
        SpacecraftSolution
            Without ``omega`` and ``attitude`` (the averaged system has none).

        Examples
        --------
        Drag spins the satellite down; its rotation stays about the axis of the largest moment:

        >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
        >>> sc = Spacecraft([12.0, 10.0, 7.0], [0.08, 0.01, 0.06], orbit=KeplerOrbit(altitude=500e3))
        >>> day = 86400.0
        >>> sol = sc.averaged((0.0, day), [0.0, day], drag=[2e-5, 2e-5, 2e-5])
        >>> print(sol.status, f"G {sol.G[0]:.4f} -> {sol.G[-1]:.4f} N m s", sol.kind[-1])
        0 G 1.0526 -> 0.8971 N m s max
        """
        torques = {"gravity_gradient": gravity_gradient, "drag": drag, "dipole": dipole, "field": field,
                   "torque": torque, "eddy": eddy}
        _check_options(options, "averaged")
        if not isinstance(orbit_averaged, bool):
            raise TypeError(f"orbit_averaged must be True or False, got {orbit_averaged!r}")
        return self._run(averaged, t_span, t_eval, torques, False, orbit_averaged=orbit_averaged, **options)

    def simulate(self, t_span: Any, t_eval: Any = None, *, gravity_gradient: bool = True, drag: Any = None,
                 dipole: Any = None, field: Any = None, torque: Any = None, eddy: Any = None,
                 **options: Any) -> SpacecraftSolution:
        r"""The full motion (Euler's equations with a quaternion, :func:`simulate`) in SI units.

        Parameters
        ----------
        t_span, t_eval, gravity_gradient, drag, dipole, field, torque, eddy
            As in :meth:`averaged`.
        **options
            Passed to :func:`simulate` (``rtol``, ``atol``, ``k2_max``, ``min_spin_ratio``, ...; the formulation
            is the body-frame one).

        Returns
        -------
        SpacecraftSolution
            With ``omega`` (rad/s, user's body axes) and ``attitude`` (body -> inertial).

        Examples
        --------
        With no torque the run follows the closed-form motion:

        >>> import numpy as np
        >>> from rigidbody.euler_poinsot import KeplerOrbit, Spacecraft
        >>> sc = Spacecraft([12.0, 10.0, 7.0], [0.08, 0.01, 0.06], orbit=KeplerOrbit(altitude=500e3))
        >>> sol = sc.simulate((0.0, 60.0), [60.0], gravity_gradient=False, rtol=1e-12)
        >>> bool(np.allclose(sol.omega[-1], sc.motion.omega(60.0), rtol=0, atol=1e-10))
        True
        """
        _check_options(options, "simulate")
        torques = {"gravity_gradient": gravity_gradient, "drag": drag, "dipole": dipole, "field": field,
                   "torque": torque, "eddy": eddy}
        if self.motion.kind != "rest" and symmetry_axes(self.motion.moments) is not None:  # a SymmetricBody
            options = {"phi0": self.paper.u0, "psi0": self.paper.psi0, **options}
        elif self.motion.paper is not None:
            options = {"u0": self.paper.u0, "psi0": self.paper.psi0, **options}
        return self._run(simulate, t_span, t_eval, torques, True, **options)

    def _run(self, run: Any, t_span: Any, t_eval: Any, torques: dict[str, Any], with_attitude: bool, *,
             orbit_averaged: bool = False, **kwargs: Any) -> SpacecraftSolution:
        """One run: the paper's problem through ``run`` (:func:`averaged` or :func:`simulate`), or the closed form
        of a torque-free body that :class:`Body` does not describe; the state is that at ``t_span[0]``."""
        t0, t1 = span(t_span, "t_span")
        try:  # the rule of the runs' output times, in seconds
            check_tau_eval(t_eval, (t0, t1))
        except (TypeError, ValueError) as exc:
            raise type(exc)(str(exc).replace("tau_", "t_")) from None
        if t_eval is not None:
            t_eval = np.asarray(t_eval, dtype=float).reshape(-1)
        M = self.torque(**torques)
        if M is None and self.motion.paper is None:
            t = np.linspace(t0, t1, 101) if t_eval is None else t_eval
            return self._closed_form(t, t0, with_attitude)
        p = self.paper
        s = p.tau_per_second
        M = M if M is not None else ConstantTorque([0.0, 0.0, 0.0])
        tau_eval = None if t_eval is None else (t_eval - t0) * s
        start = ({"theta0": p.theta0} if isinstance(p.body, SymmetricBody) else
                 {"k2_0": p.k2_0, "kind": p.kind, "sigma": p.sigma})
        sol = run(p.body, M, 0.0 if orbit_averaged else p.eps, p.G0, delta0=p.delta0, lam0=p.lam0,
                  tau_span=(0.0, (t1 - t0) * s), tau_eval=tau_eval, nu0=p.nu0, orbit=p.orbit, **start, **kwargs)
        return self._result(sol, p, t0, with_attitude)

    def _result(self, sol: Solution, p: PaperStart, t0: float, with_attitude: bool) -> SpacecraftSolution:
        """The paper's run in SI units."""
        s = p.tau_per_second
        G = p.G_unit * np.asarray(sol.G)
        T = p.G_unit * p.Omega0 * np.asarray(sol.T)
        n = np.asarray(sol.n, dtype=float).T.reshape(-1, 3)
        omega = attitude = None
        if with_attitude:
            q = np.asarray(sol.q, dtype=float)
            omega, attitude = p.physical(np.asarray(sol.g, dtype=float).T,
                                         Rotation.from_quat(q[[1, 2, 3, 0]].T))
        return SpacecraftSolution(
            t0 + np.asarray(sol.tau) / s, G, T, _spin(T, G), G[:, None] * p.to_inertial.apply(n),
            np.asarray(sol.k2), np.asarray(sol.kind), np.asarray(sol.sigma), np.asarray(sol.delta),
            np.asarray(sol.lam), np.asarray(sol.nu), int(sol.status), str(sol.message), sol.event, omega, attitude,
            sol, p)

    def _closed_form(self, t: np.ndarray, t0: float, with_attitude: bool) -> SpacecraftSolution:
        """The torque-free motion of a body the paper's problem does not describe, in closed form."""
        m = self.motion
        ones = np.ones(len(t))
        delta, lam = angles_of(self._in_orbit_axes.momentum / m.G) if m.G > 0.0 else (0.0, 0.0)
        G, T = m.G * ones, m.T * ones
        return SpacecraftSolution(
            t, G, T, _spin(T, G), np.outer(ones, m.momentum), m.k2 * ones,
            np.full(len(t), m.kind), np.full(len(t), m.sigma), delta * ones, lam * ones,
            self.orbit.true_anomaly(t - t0), 0, "the torque-free motion in closed form (FreeMotion)", None,
            m.omega(t - t0) if with_attitude else None,
            m.rotation(t - t0) if with_attitude else None)


#: What the spacecraft's state, orbit and the body-frame equations set (not options of its runs).
_FROM_STATE = ("eps", "G0", "k2_0", "delta0", "lam0", "tau_span", "tau_eval", "nu0", "kind", "T0", "orbit", "sigma",
               "u0", "psi0", "formulation", "theta0", "phi0")


def _check_options(options: dict[str, Any], method: str) -> None:
    taken = [name for name in _FROM_STATE if name in options]
    if taken:
        raise TypeError(f"Spacecraft.{method}: {', '.join(taken)} follow from the spacecraft's state and orbit (the "
                        "body-frame equations for simulate) and are not options")


def _spin(T: np.ndarray, G: np.ndarray) -> np.ndarray:
    """The spin rate about G, 2T/G (0 at rest)."""
    return np.divide(2.0 * T, G, out=np.zeros_like(T), where=G > 0.0)


def _vector(value: Any, name: str) -> np.ndarray:
    v = finite_array(value, name)
    if v.shape != (3,):
        raise ValueError(f"{name} must have 3 components, got shape {v.shape}")
    return v
