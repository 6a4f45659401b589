r"""The full equations of a :class:`SymmetricBody`: its start from the nutation angle, its part of a full run, and
the symmetric branch of :func:`rigidbody.euler_poinsot.simulate`.

Euler's equations and the attitude quaternion do not care about the order of the moments, so a symmetric body
runs through the same driver and equations as a triaxial one (:mod:`._fullrun`, :mod:`._full`); what differs is
gathered in :class:`SymmetricKinds` (see :mod:`._fullkinds`): the start on the regular precession at the nutation
angle :math:`\theta_0` (:func:`symmetric_start`), no separatrix (the only event is the slow-rotation stop, at the
precession rate :math:`G/A`, :func:`symmetric_spin_frequency`) and the osculating nutation angle
:math:`\theta = \arccos(g_3/G)` as an output field besides ``k2`` (0), ``kind`` and ``sigma`` (the sign of
:math:`g_3`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core import euler
from ..core.ode import Event, Solution
from ..core.validate import real, span
from ._boundary import as_torque, drag_equivalent
from ._checks import check_sigma, check_tau_eval, check_tol
from ._fullrun import FullRun, probe_members, run_full_members
from ._members import Members, grid_checks, is_batch, member_inputs
from ._model import as_orbit, frame_y
from ._options import Stops
from ._start import check_direction, check_eps_G0, check_full_eps, check_spin
from ._stops import stop_message
from ._symbody import SymmetricBody, cos_theta_of, energy, kind_fields, momentum_body

__all__ = ["SymmetricKinds", "check_symmetric_start", "simulate_symmetric", "symmetric_spin_frequency",
           "symmetric_start"]


def symmetric_start(body: SymmetricBody, G0: float, theta0: float, delta0: float, lam0: float, phi0: float = 0.0,
                    psi0: float = 0.0) -> dict[str, Any]:
    r"""The state of a symmetric body on its regular precession with given slow variables (values already checked).

    :math:`\mathbf G` of magnitude ``G0`` points along :math:`(\sin\delta_0\cos\lambda_0, \sin\delta_0\sin\lambda_0,
    \cos\delta_0)` in the orbital axes :math:`Ox_i`, at the nutation angle ``theta0`` from the symmetry axis
    :math:`z_3`, at the azimuth ``phi0`` in the body (about :math:`z_3`) and the precession angle ``psi0`` about
    itself: :math:`\mathbf g = G_0(\sin\theta_0\sin\varphi_0, \sin\theta_0\cos\varphi_0, \cos\theta_0)` and the
    attitude :math:`C = Y R_3(\psi_0) R_1(\theta_0) R_3(\varphi_0)` (body -> :math:`Ox_i`), :math:`Y` of
    :func:`._model.frame_y` (the angles of :func:`initial_state` for a triaxial body).

    Parameters
    ----------
    body : SymmetricBody
    G0 : float
        The magnitude of the angular momentum (> 0).
    theta0 : float
        The nutation angle of :math:`\mathbf G` from the symmetry axis, in :math:`[0, \pi]`.
    delta0, lam0 : float
        The direction of :math:`\mathbf G` in :math:`Ox_i`.
    phi0, psi0 : float
        The azimuth of :math:`\mathbf G` in the body and the precession angle about :math:`\mathbf G`.

    Returns
    -------
    dict
        ``g`` (body components of G), ``R`` (body -> Ox_i), ``q`` (its quaternion), ``theta``, ``phi``, ``psi``
        and the kinetic energy ``T``.

    Examples
    --------
    The momentum, turned into the orbital axes, points along :math:`(\delta_0, \lambda_0)`, and makes the angle
    :math:`\theta_0` with the symmetry axis :math:`C\mathbf e_3`:

    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> from rigidbody.euler_poinsot._symfull import symmetric_start
    >>> st = symmetric_start(ep.SymmetricBody(2.0, 1.0), 1.5, 0.4, 0.7, 0.3, phi0=1.0, psi0=2.0)
    >>> n = [np.sin(0.7) * np.cos(0.3), np.sin(0.7) * np.sin(0.3), np.cos(0.7)]
    >>> bool(np.allclose(st["R"] @ st["g"], 1.5 * np.array(n), rtol=0, atol=1e-14))
    True
    >>> print(f"{np.arccos(n @ st['R'][:, 2]):.12f}")
    0.400000000000
    """
    g = momentum_body(G0, theta0, phi0)
    R = frame_y(delta0, lam0) @ euler.dcm(psi0, theta0, phi0)
    return {"g": g, "R": R, "q": euler.quat_from_dcm(R), "theta": theta0, "phi": phi0, "psi": psi0,
            "T": energy(body, G0, math.cos(theta0))}


def symmetric_spin_frequency(body: SymmetricBody, G: Any) -> Any:
    r"""The rate :math:`G/A` at which a symmetric body turns about :math:`\mathbf G` (its regular precession): the
    frequency the slow-rotation check (``min_spin_ratio``) compares with the orbital rate. It stays positive for
    every nutation angle and for the sphere, where the proper rotation :math:`G\cos\theta(1/A - 1/C)` vanishes."""
    return G / body.transverse


def check_symmetric_start(body: SymmetricBody, min_spin_ratio: float, eps: Any, G0: Any, theta0: Any, T0: Any,
                          sigma: int, delta0: Any, lam0: Any, nu0: Any, phi0: Any, psi0: Any) -> tuple[float, ...]:
    """The start of one member of a symmetric body's full run, checked in the single call's order (a single run
    raises, a batch refuses the member with the message): ``eps, G0``, the nutation angle (``theta0`` in
    [0, pi], or from ``T0`` with the sign ``sigma`` of its cosine), the direction of G, ``nu0``, the rotation fast
    enough, ``phi0, psi0``.

    Returns
    -------
    tuple of float
        ``eps, G0, theta0, delta0, lam0, nu0, phi0, psi0``.
    """
    eps, G0 = check_eps_G0(eps, G0)
    if T0 is not None:
        theta0 = math.acos(cos_theta_of(body, G0, real(T0, "T0"), sigma))
    else:
        theta0 = real(theta0, "theta0")
        if not 0.0 <= theta0 <= math.pi:
            raise ValueError(f"theta0 (the nutation angle of G from the symmetry axis) must lie in [0, pi], got "
                             f"{theta0}")
    delta0, lam0, nu0 = check_direction(delta0, lam0, nu0)
    check_full_eps(eps)
    if min_spin_ratio > 0:
        check_spin(eps, symmetric_spin_frequency(body, G0) / eps, min_spin_ratio, "the precession rate G/A")
    return eps, G0, theta0, delta0, lam0, nu0, real(phi0, "phi0"), real(psi0, "psi0")


class SymmetricKinds:
    """The symmetric body's part of a full run (see :mod:`._fullkinds`): each member's start on its regular
    precession (``theta0``, ``phi0``, ``psi0``: flat arrays of the members), the slow-rotation stop and the
    osculating nutation angle ``theta``; no separatrix."""

    event_names: tuple[str, ...] = ("slow_rotation",)
    field_names: tuple[str, ...] = ("G", "T", "theta", "k2", "delta", "lam", "nu", "n", "kind", "sigma", "g", "q")

    def __init__(self, body: SymmetricBody, theta0: np.ndarray, phi0: np.ndarray, psi0: np.ndarray,
                 min_spin_ratio: float) -> None:
        self.body, self.theta0, self.phi0, self.psi0, self.min_spin_ratio = body, theta0, phi0, psi0, min_spin_ratio

    def start(self, i: int, G0: float, delta0: float, lam0: float) -> dict[str, Any]:
        return symmetric_start(self.body, G0, float(self.theta0[i]), delta0, lam0, float(self.phi0[i]),
                               float(self.psi0[i]))

    def _spin_event(self, fun: Any) -> Event:
        r = self.min_spin_ratio
        return Event(fun, "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=r))

    def scalar_events(self, i: int, eps: float, G_D: Any) -> list[Event]:
        r, body = self.min_spin_ratio, self.body
        return [self._spin_event(lambda t, y: symmetric_spin_frequency(body, G_D(y)[0]) / eps - r)]

    def scalar_fields(self, G: Any, T: Any, gb: np.ndarray) -> dict[str, np.ndarray]:
        # arccos(g3/G), accurate near 0 and pi too
        return {"theta": np.arctan2(np.hypot(gb[0], gb[1]), gb[2]), **kind_fields(self.body, gb[2])}

    def vector_events(self, idx: np.ndarray, GD: Any) -> tuple[list[Event], tuple[np.ndarray, ...]]:
        r, body = self.min_spin_ratio, self.body
        return [self._spin_event(lambda t, y, ie, *a: symmetric_spin_frequency(body, GD(y)[0]) * ie - r)], ()

    def vector_fields(self, g: np.ndarray, G: np.ndarray, T: np.ndarray) -> dict[str, np.ndarray]:
        return {"theta": np.arctan2(np.hypot(g[:, 0], g[:, 1]), g[:, 2]), **kind_fields(self.body, g[:, 2])}


def _check_options(k2_0: Any, opts: dict[str, Any]) -> None:
    """The options of :func:`simulate` that a symmetric body refuses, each with the way to go on."""
    start = "a SymmetricBody starts from theta0, the nutation angle of G from its symmetry axis in [0, pi]"
    for name, value in (("k2_0", k2_0), ("kind", opts["kind"]), ("u0", opts["u0"])):
        if value is not None:
            raise ValueError(f"{name} describes the Euler-Poinsot motion of a triaxial Body; {start} (and phi0, "
                             f"psi0), or from T0 with sigma: pass theta0 instead of {name}")
    if opts["theta0"] is None and opts["T0"] is None:
        raise ValueError(f"theta0 is missing: {start} (or from T0 with sigma)")
    if opts["theta0"] is not None and opts["T0"] is not None:
        raise ValueError("give the initial nutation angle either by theta0 or by T0 (with sigma), not both")
    if check_sigma(opts["sigma"]) != 1 and opts["T0"] is None:
        raise ValueError("sigma chooses the sign of cos(theta0) found from T0; with theta0 give the angle in [0, pi] "
                         "itself (sigma=1)")
    if opts["formulation"] != "body":
        raise ValueError(f"formulation must be 'body' for a SymmetricBody (the paper's angles (1) are written for a "
                         f"triaxial body), got {opts['formulation']!r}")
    if opts["k2_max"] is not None and opts["k2_max"] != Stops().k2_max:
        raise ValueError(f"k2_max (the separatrix stop) does not apply to a SymmetricBody, which has no separatrix: "
                         f"leave it at its default, got {opts['k2_max']!r}")


def _floats(v: Any, name: str, shape: tuple[int, ...]) -> np.ndarray:
    """A per-member input broadcast to the batch shape, flat (a ``TypeError`` naming it if it is not real)."""
    if isinstance(v, (bool, np.bool_, str, bytes)):
        raise TypeError(f"{name} must be a real number or an array of them, got {v!r}")
    try:
        return np.broadcast_to(np.asarray(v, dtype=float), shape).reshape(-1).copy()
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a real number or an array of them broadcasting to {shape}, got {v!r}"
                        ) from None


def _members(body: SymmetricBody, min_spin: float, sigma: int, eps: Any, G0: Any, theta0: Any, T0: Any, delta0: Any,
             lam0: Any, nu0: Any, phi0: Any, psi0: Any, single: bool) -> tuple[Members, tuple[np.ndarray, ...]]:
    """The members (a batch of one for a single run, whose start errors raise) and their flat ``theta0, phi0,
    psi0``; a batch member whose start the single call refuses is refused with its message. The members' ``k2_0``
    and ``kind`` are unused (a symmetric body has neither)."""
    if single:
        v = np.array(check_symmetric_start(body, min_spin, eps, G0, theta0, T0, sigma, delta0, lam0, nu0, phi0, psi0))
        e, G, th1, d, la, nu, ph1, ps1 = v[:, None]
        return Members((), e, G, np.zeros(1), d, la, nu, np.array(["max"], dtype=object)), (th1, ph1, ps1)
    angle, angle_name = (theta0, "theta0") if T0 is None else (T0, "T0")
    named = f"{angle_name}, phi0 and psi0"
    try:
        phases = np.broadcast_shapes(np.shape(angle), np.shape(phi0), np.shape(psi0))
    except ValueError:
        raise ValueError(f"{named} must broadcast to one batch shape, got {np.shape(angle)}, {np.shape(phi0)}, "
                         f"{np.shape(psi0)}") from None
    mem = member_inputs(body, eps, G0, None, delta0, lam0, nu0, None, None, phases, named)  # type: ignore[arg-type]  # SymmetricBody: no T0 read
    shape = mem.batch_shape
    ang, ph, ps = _floats(angle, angle_name, shape), _floats(phi0, "phi0", shape), _floats(psi0, "psi0", shape)
    th = np.full(ang.shape, np.nan)
    for i in range(mem.eps.size):
        if i in mem.refused:
            continue
        a = float(ang[i])
        try:
            th[i] = check_symmetric_start(body, min_spin, mem.eps[i], mem.G0[i], None if T0 is not None else a,
                                          a if T0 is not None else None, sigma, mem.delta0[i], mem.lam0[i],
                                          mem.nu0[i], ph[i], ps[i])[2]
        except ValueError as exc:
            mem.refused[i] = str(exc)
    return mem, (th, ph, ps)


def simulate_symmetric(body: SymmetricBody, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any,
                       tau_span: Any, tau_eval: Any, nu0: Any, opts: dict[str, Any]) -> Solution:
    """The full equations of a :class:`SymmetricBody` (the branch of :func:`rigidbody.euler_poinsot.simulate`;
    ``opts`` its keyword options): a single run, or a batch when a per-member input is an array, through the
    driver of the triaxial body's runs."""
    _check_options(k2_0, opts)
    sigma = check_sigma(opts["sigma"])
    theta0, T0, psi0 = opts["theta0"], opts["T0"], opts["psi0"]
    phi0 = 0.0 if opts["phi0"] is None else opts["phi0"]
    single = not is_batch(eps, G0, delta0, lam0, nu0, theta0, T0, phi0, psi0)
    if single:
        t0, t1 = span(tau_span, "tau_span")
        check_tau_eval(tau_eval, tau_span)
        check_tol(opts["rtol"], opts["atol"])
        te = tau_eval
    else:  # member by member with another method, as the triaxial batch
        t0, t1, te = grid_checks(tau_span, tau_eval, {**opts, "method": "DOP853"})
    orb = as_orbit(opts["orbit"])
    tq, _ = as_torque(torque, body, orb)
    tq.check_setup(body, orb)
    min_spin = real(opts["min_spin_ratio"], "min_spin_ratio")
    mem, (th, ph, ps) = _members(body, min_spin, sigma, eps, G0, theta0, T0, delta0, lam0, nu0, phi0, psi0, single)
    kinds = SymmetricKinds(body, th, ph, ps, min_spin)
    run = FullRun(body, drag_equivalent(tq, body, orb), tq, orb, kinds, float(opts["rtol"]),
                  float(opts["atol"]), "body", opts["method"])
    if not single:
        probe_members(run, mem)
    return run_full_members(run, mem, (t0, t1), te, single)
