r"""The full (unaveraged) equations of motion: (1), (3), (4) of Rachinskaya, and a body-frame formulation.

Nondimensional, section-3 scaling, written in the slow time :math:`\tau = \varepsilon^2\tilde t`: the
torque-free parts carry the factor :math:`\varepsilon^{-2}`, the torques

.. math:: \tilde{\mathbf L} = 3f(\nu)\,\mathbf e_r\times J\mathbf e_r - \tilde I\boldsymbol\omega,
          \qquad \nu = \tau/\varepsilon + \nu_0,

(gravity gradient (3) with :math:`J` the inertia tensor and :math:`\mathbf e_r` the unit radius vector,
drag :math:`-\tilde I\boldsymbol\omega` in body axes) do not.

Two independent formulations integrate the same motion:

``formulation='body'`` (default)
    Euler's equations for the body components :math:`\mathbf g` of :math:`\mathbf G` and the attitude
    quaternion (body -> orbital axes :math:`Ox_i`): :math:`\dot{\mathbf g} = \mathbf g\times\boldsymbol\omega
    + \mathbf L`, :math:`\dot q = \tfrac12 q\otimes(0,\boldsymbol\omega)`. No singular states.
``formulation='angles'``
    The paper's equations (1) for :math:`(G, \delta, \lambda, \theta, \varphi, \psi)` with the torque
    projections (3) on :math:`Oy_i` and the energy equation (4) for :math:`T`. Singular at
    :math:`\sin\theta = 0` and :math:`\sin\delta = 0`: the run then ends with a status (events
    ``'sin_theta'``, ``'sin_delta'``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np

from ..core import euler
from ..core.ode import Event, Solution
from ..core.validate import RESULT_ERRORS, real, span
from ._boundary import as_torque, drag_equivalent
from ._checks import check_tau_eval, check_tol
from ._gravity import drag_gravity, radius_in_body
from ._model import Body, Orbit, as_orbit, check_body, frame_y
from ._motion import EulerPoinsot
from ._output import finish_output
from ._protocol import Misfire, evaluate
from ._start import StartRules, check_start, initial_kind
from ._symbody import SymmetricBody
from ._torques import probe

__all__ = ["FullKinds", "FullSingle", "check_full", "full_single", "initial_state"]


def initial_state(
    body: Body, G0: float, k2_0: float, delta0: float, lam0: float, *, kind: str = "max",
    u0: float = 0.0, psi0: float = 0.0, sigma: int = 1,
) -> dict[str, Any]:
    r"""Initial attitude and angular momentum of the full motion with given slow variables.

    The body is put on the Euler--Poinsot motion with :math:`(G_0, k^2_0)` at elliptic phase ``u0`` and
    precession angle ``psi0`` about :math:`\mathbf G`, with :math:`\mathbf G` along
    :math:`(\sin\delta_0\cos\lambda_0, \sin\delta_0\sin\lambda_0, \cos\delta_0)` in :math:`Ox_i`.

    Returns
    -------
    dict
        ``g`` (body components of G), ``R`` (body -> Ox_i), ``q`` (its quaternion), ``psi``, ``theta``,
        ``phi`` (Euler angles relative to Oy_i), ``T``.

    See Also
    --------
    EulerPoinsot : the motion the body is put on.
    simulate : starts from this state.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (1), (5) (the angles and the modulus).

    Examples
    --------
    The body's momentum, turned into the orbital axes, points along :math:`(\delta_0, \lambda_0)`, and the
    energy is that of :func:`T_from`:

    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> st = ep.initial_state(body, 1.0, 0.5, 0.7, 0.3)
    >>> n = [np.sin(0.7) * np.cos(0.3), np.sin(0.7) * np.sin(0.3), np.cos(0.7)]
    >>> bool(np.allclose(st["R"] @ st["g"], n, rtol=0, atol=1e-14))
    True
    >>> print(f"{st['T']:.6f} {ep.T_from(body, 1.0, 0.5):.6f}")
    0.176877 0.176877
    """
    u0, psi0 = real(u0, "u0"), real(psi0, "psi0")
    m = EulerPoinsot(body, G0, k2_0, kind, sigma)
    g = m.g(0.0, u0)
    _, theta, phi = m.angles(0.0, u0)
    Ry = frame_y(delta0, lam0)
    Rb = Ry @ euler.dcm(psi0, theta, phi)
    return {"g": g, "R": Rb, "q": euler.quat_from_dcm(Rb), "psi": psi0, "theta": theta, "phi": phi,
            "T": m.T}


class FullKinds(Protocol):
    """What a full run depends on the body for (implemented by :class:`._fullkinds.TriaxialKinds` and
    :class:`._symfull.SymmetricKinds`; their module :mod:`._fullkinds` describes each part)."""

    event_names: tuple[str, ...]
    field_names: tuple[str, ...]

    def start(self, i: int, G0: float, delta0: float, lam0: float) -> dict[str, Any]: ...

    def scalar_events(self, i: int, eps: float, G_D: Any) -> list[Event]: ...

    def scalar_fields(self, G: Any, T: Any, gb: np.ndarray) -> dict[str, np.ndarray]: ...

    def vector_events(self, idx: np.ndarray, GD: Any) -> tuple[list[Event], tuple[np.ndarray, ...]]: ...

    def vector_fields(self, g: np.ndarray, G: np.ndarray, T: np.ndarray) -> dict[str, np.ndarray]: ...


@dataclass
class _Common:
    """What both formulations of a single run share."""

    body: Body | SymmetricBody
    orbit: Orbit
    torque: Any
    generic: bool
    Im: np.ndarray
    eps: float
    st: dict[str, Any]
    nu0: float
    G0: float
    delta0: float
    lam0: float
    misfire: Misfire
    nu_of: Any



def _body_form(c: _Common) -> tuple[Any, ...]:
    """Euler's equations for g with the attitude quaternion: right-hand side, initial state, the slow variables and
    directions from the state, extra events (none)."""
    body, orb, tq, generic, st, nu0, misfire = c.body, c.orbit, c.torque, c.generic, c.st, c.nu0, c.misfire
    nu_of = c.nu_of
    A1, A2, A3 = A = body.A1, body.A2, body.A3
    ie2, ie, circular = 1.0 / (c.eps * c.eps), 1.0 / c.eps, orb.e == 0.0
    rows = tuple(tuple(float(x) for x in row) for row in c.Im)

    def body_torque_drag(o1: float, o2: float, o3: float, w: float, x: float, yq: float, z: float,
                         nu: float) -> tuple[float, float, float]:
        r = radius_in_body(w, x, yq, z, math.cos(nu), math.sin(nu))
        return drag_gravity(A, 3.0 * orb.factor(nu), r, rows, (o1, o2, o3))

    def body_torque_object(o1: float, o2: float, o3: float, w: float, x: float, yq: float, z: float,
                           nu: float) -> tuple[float, float, float]:
        # the whole perturbation from the torque object: M = torque(omega, C, nu) in body axes
        C = np.array([  # body -> Ox_i, the convention of core.euler.dcm_from_quat
            [1 - 2 * (yq * yq + z * z), 2 * (x * yq - w * z), 2 * (x * z + w * yq)],
            [2 * (x * yq + w * z), 1 - 2 * (x * x + z * z), 2 * (yq * z - w * x)],
            [2 * (x * z - w * yq), 2 * (yq * z + w * x), 1 - 2 * (x * x + yq * yq)],
        ])
        M = evaluate(tq, np.array([o1, o2, o3]), C, nu, (3,))
        return float(M[0]), float(M[1]), float(M[2])

    body_torque = body_torque_object if generic else body_torque_drag

    def rhs(tau: float, y: np.ndarray) -> list[float]:
        g1, g2, g3, w, x, yq, z = y[0], y[1], y[2], y[3], y[4], y[5], y[6]
        nrm = math.sqrt(w * w + x * x + yq * yq + z * z)
        w, x, yq, z = w / nrm, x / nrm, yq / nrm, z / nrm
        o1, o2, o3 = g1 / A1, g2 / A2, g3 / A3
        nu = nu_of(tau, y, 7)
        try:
            L1, L2, L3 = body_torque(o1, o2, o3, w, x, yq, z, nu)
        except RESULT_ERRORS as exc:
            misfire.note(tau, exc)
            L1 = L2 = L3 = math.nan
        dg1 = (g2 * o3 - g3 * o2) * ie2 + L1
        dg2 = (g3 * o1 - g1 * o3) * ie2 + L2
        dg3 = (g1 * o2 - g2 * o1) * ie2 + L3
        h = 0.5 * ie2
        dw = h * (-x * o1 - yq * o2 - z * o3)
        dx = h * (w * o1 + yq * o3 - z * o2)
        dy = h * (w * o2 - x * o3 + z * o1)
        dz = h * (w * o3 + x * o2 - yq * o1)
        out = [dg1, dg2, dg3, dw, dx, dy, dz]
        if not circular:
            out.append(ie * orb.nu_rate(nu))
        return out

    if generic:
        probe(tq, st["g"] / body.A, st["R"], nu0)
    y0 = [*st["g"], *st["q"]]

    def GT(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        g = y[0:3]
        return np.sqrt((g * g).sum(0)), 0.5 * (g[0] ** 2 / A1 + g[1] ** 2 / A2 + g[2] ** 2 / A3)

    def nvec(y: np.ndarray) -> np.ndarray:
        g = y[0:3]
        R = euler.dcm_from_quat(y[3:7].T)
        n = np.einsum("nij,jn->in", R, g)
        return n / np.linalg.norm(n, axis=0)

    def G_D(y: np.ndarray) -> tuple[float, float]:
        G2 = y[0] ** 2 + y[1] ** 2 + y[2] ** 2
        return math.sqrt(G2), G2 / (y[0] ** 2 / A1 + y[1] ** 2 / A2 + y[2] ** 2 / A3)

    def body_dir(y: np.ndarray) -> np.ndarray:
        return y[0:3] / np.sqrt((y[0:3] ** 2).sum(0))

    extra_events: list[Event] = []
    return rhs, y0, GT, nvec, G_D, body_dir, extra_events


def _angle_torques(c: _Common) -> Any:
    """The torque projected on the axes Oy of the angles form, ``torques(y, nu) -> (L1, L2, L3)``: the drag tensor
    plus the gravity gradient written out on floats, or any torque object through its body components."""
    body, orb, tq = c.body, c.orbit, c.torque
    A1, A2, A3 = A = body.A1, body.A2, body.A3
    rows = tuple(tuple(float(x) for x in row) for row in c.Im)

    def torques_drag(y: np.ndarray, nu: float) -> tuple[float, ...]:
        G, de, la, th, ph, ps = y[0], y[1], y[2], y[3], y[4], y[5]
        c1, s1 = math.cos(ps), math.sin(ps)
        c2, s2 = math.cos(th), math.sin(th)
        c3, s3 = math.cos(ph), math.sin(ph)
        # alpha_ij = y_i . z_j = dcm(psi, theta, phi)
        a11, a12, a13 = c1 * c3 - s1 * c2 * s3, -c1 * s3 - s1 * c2 * c3, s1 * s2
        a21, a22, a23 = s1 * c3 + c1 * c2 * s3, -s1 * s3 + c1 * c2 * c3, -c1 * s2
        a31, a32, a33 = s2 * s3, s2 * c3, c2
        o1, o2, o3 = G * a31 / A1, G * a32 / A2, G * a33 / A3
        cnl, snl = math.cos(nu - la), math.sin(nu - la)
        b1, b2, b3 = cnl * math.cos(de), snl, cnl * math.sin(de)
        # the body components of e_r, the torque in body axes, then projected on Oy: L = alpha M
        e = (a11 * b1 + a21 * b2 + a31 * b3, a12 * b1 + a22 * b2 + a32 * b3, a13 * b1 + a23 * b2 + a33 * b3)
        M1, M2, M3 = drag_gravity(A, 3.0 * orb.factor(nu), e, rows, (o1, o2, o3))
        return (a11 * M1 + a12 * M2 + a13 * M3, a21 * M1 + a22 * M2 + a23 * M3, a31 * M1 + a32 * M2 + a33 * M3)

    def torques_generic(y: np.ndarray, nu: float) -> tuple[float, ...]:
        # the torque object in body axes, projected on Oy: L = alpha M, C = Y alpha
        G, de, la = y[0], y[1], y[2]
        if not math.isfinite(y[3] + y[4] + y[5]):  # a stage after a misfire (NaN rates): NaN again
            return math.nan, math.nan, math.nan
        alpha = euler.dcm(y[5], y[3], y[4])  # alpha_ij = y_i . z_j (body -> Oy)
        omega = G * alpha[2] / body.A
        M = evaluate(tq, omega, frame_y(de, la) @ alpha, nu, (3,))
        L = alpha @ M
        return float(L[0]), float(L[1]), float(L[2])

    return torques_generic if c.generic else torques_drag


def _angles_form(c: _Common) -> tuple[Any, ...]:
    """The paper's equations (1), (3), (4) in (G, delta, lambda, theta, phi, psi, T): right-hand side, initial state,
    the slow variables and directions from the state, the events of their singular states."""
    body, orb, tq, generic, st, nu0, misfire = c.body, c.orbit, c.torque, c.generic, c.st, c.nu0, c.misfire
    nu_of = c.nu_of
    A1, A2, A3 = body.A1, body.A2, body.A3
    ie2, ie, circular = 1.0 / (c.eps * c.eps), 1.0 / c.eps, orb.e == 0.0
    G0, delta0, lam0 = c.G0, c.delta0, c.lam0

    torques = _angle_torques(c)

    def rhs(tau: float, y: np.ndarray) -> list[float]:
        G, de, th, ph, ps, T = y[0], y[1], y[3], y[4], y[5], y[6]
        nu = nu_of(tau, y, 7)
        try:
            L1, L2, L3 = torques(y, nu)
        except RESULT_ERRORS as exc:
            misfire.note(tau, exc)
            L1 = L2 = L3 = math.nan
        s2, c2 = math.sin(th), math.cos(th)
        sp, cp = math.sin(ph), math.cos(ph)
        sps, cps = math.sin(ps), math.cos(ps)
        sd = math.sin(de)
        dG = L3
        dde = L1 / G
        dla = L2 / (G * sd)
        P = L2 * cps - L1 * sps
        Q = L1 * cps + L2 * sps
        dth = G * s2 * sp * cp * (1 / A1 - 1 / A2) * ie2 + P / G
        dph = G * c2 * (1 / A3 - sp * sp / A1 - cp * cp / A2) * ie2 + Q / (G * s2)
        dps = G * (sp * sp / A1 + cp * cp / A2) * ie2 - Q / G * c2 / s2 - L2 / G * math.cos(de) / sd
        dT = 2 * T / G * L3 + G * s2 * (
            c2 * (sp * sp / A1 + cp * cp / A2 - 1 / A3) * P + sp * cp * (1 / A1 - 1 / A2) * Q
        )
        out = [dG, dde, dla, dth, dph, dps, dT]
        if not circular:
            out.append(ie * orb.nu_rate(nu))
        return out

    y0 = [G0, delta0, lam0, st["theta"], st["phi"], st["psi"], st["T"]]
    if generic:
        probe(tq, st["g"] / body.A, st["R"], nu0)
    if abs(math.sin(delta0)) <= 1e-6 or abs(math.sin(st["theta"])) <= 1e-6:
        raise ValueError(
            "formulation='angles' is singular at sin(delta) = 0 or sin(theta) = 0 (the initial state is "
            "there): use formulation='body'"
        )

    def GT(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return y[0], y[6]

    def nvec(y: np.ndarray) -> np.ndarray:
        de, la = y[1], y[2]
        return np.array([np.sin(de) * np.cos(la), np.sin(de) * np.sin(la), np.cos(de)])

    def G_D(y: np.ndarray) -> tuple[float, float]:
        return y[0], y[0] ** 2 / (2 * y[6])

    def body_dir(y: np.ndarray) -> np.ndarray:
        st_ = np.sin(y[3])
        return np.array([st_ * np.sin(y[4]), st_ * np.cos(y[4]), np.cos(y[3])])

    extra_events = [
        Event(lambda t, y: abs(math.sin(y[3])) - 1e-6, "sin_theta", True, -1.0,
              "sin(theta) -> 0: the Euler angles of (1) are singular; use formulation='body'"),
        Event(lambda t, y: abs(math.sin(y[1])) - 1e-6, "sin_delta", True, -1.0,
              "sin(delta) -> 0: lambda is undefined and (1) singular; use formulation='body'"),
    ]
    return rhs, y0, GT, nvec, G_D, body_dir, extra_events


@dataclass
class FullSingle:
    """One member's full equations on floats: right-hand side, start, events (with ``cuts``: the passages of the
    azimuth of G through its branch cut, recorded for a member of a batch), and its output fields."""

    rhs: Any
    y0: list[float]
    events: list[Event]
    make_fields: Any
    nvec: Any
    misfire: Misfire
    lam0: float

    def finish(self, res: Solution, tau_eval: Any) -> Solution:
        """The single-run result on ``tau_eval`` (the integrator's steps without it), lambda unwrapped along the
        steps, a torque's failure named in the message."""
        self.misfire.settle(res)
        return finish_output(res, tau_eval, self.make_fields, self.lam0, self.nvec, producer="euler_poinsot.simulate")


def full_single(body: Body | SymmetricBody, tensor: Any, tq: Any, orb: Orbit, eps: float, G0: float, delta0: float,
                lam0: float, nu0: float, st: dict[str, Any], kinds: FullKinds, i: int, *, formulation: str,
                cuts: bool = False) -> FullSingle:
    """The full equations of one member (``i`` of ``kinds``, the body's part of the run: see :mod:`._fullkinds`)
    whose start ``st`` is checked: the torque object ``tq`` written out with the drag tensor ``tensor`` when it is
    one's meaning (drag plus gravity gradient), else evaluated through its protocol (probed at the start: its
    failure raises)."""
    generic = tensor is None
    Im = np.zeros((3, 3)) if generic else np.asarray(tensor, dtype=float)
    ie = 1.0 / eps
    circular = orb.e == 0.0

    def nu_of(tau: float, y: np.ndarray, i: int) -> float:
        return y[i] if not circular else tau * ie + nu0

    misfire = Misfire()  # a torque that misbehaves part-way: NaN rates there, the run ends with a status

    c = _Common(body, orb, tq, generic, Im, eps, st, nu0, G0, delta0, lam0, misfire, nu_of)
    rhs, y0, GT, nvec, G_D, body_dir, extra_events = (_body_form if formulation == "body" else _angles_form)(c)
    inu = 7
    if not circular:
        y0.append(nu0)
    events = [*kinds.scalar_events(i, eps, G_D), *extra_events]
    if cuts:
        events += [Event(_n2, "_cut_up", False, 1.0, ""), Event(_n2, "_cut_down", False, -1.0, "")]

    def make_fields(tau: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
        G, T = GT(y)
        n = nvec(y) if y.shape[1] else np.empty((3, 0))
        nu = y[inu] if not circular else tau * ie + nu0
        out = {"G": G, "T": T, **kinds.scalar_fields(G, T, body_dir(y)), "delta": np.arccos(np.clip(n[2], -1, 1)),
               "n": n, "nu": nu}
        if formulation == "body":
            out["g"] = y[0:3]
            out["q"] = y[3:7] / np.linalg.norm(y[3:7], axis=0)
        else:
            out["theta"], out["phi"], out["psi"] = y[3], y[4], y[5]
        return out

    return FullSingle(rhs, y0, events, make_fields, nvec, misfire, lam0)


def _n2(tau: float, y: Any) -> float:
    """The second orbital component of G (sign only) from the body-frame state (g, q) on floats."""
    g1, g2, g3, w, x, yq, z = y[0], y[1], y[2], y[3], y[4], y[5], y[6]
    return 2 * (x * yq + w * z) * g1 + (w * w - x * x + yq * yq - z * z) * g2 + 2 * (yq * z - w * x) * g3


def check_full(body: Any, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any, tau_span: Any,
               tau_eval: Any, nu0: Any, *, kind: str | None, T0: Any, orbit: Orbit | None, u0: Any, psi0: Any,
               formulation: str, rtol: float, atol: float, k2_max: float | None, min_spin_ratio: float
               ) -> tuple[Any, ...]:
    """The checks of one run of the full equations (the single call of :func:`rigidbody.euler_poinsot.simulate`),
    in its order: the torque resolved, the start values as floats.

    Returns
    -------
    tuple
        ``tensor, torque, orbit, kind, k2_max, min_spin_ratio, (eps, G0, k2_0, delta0, lam0, nu0), u0, psi0``:
        the torque as an object, with the drag tensor whose meaning it has (or None).
    """
    check_body(body)
    k2_0, kind = initial_kind(body, real(G0, "G0"), k2_0, kind, T0)
    span(tau_span, "tau_span")
    check_tau_eval(tau_eval, tau_span)
    check_tol(rtol, atol)
    if formulation not in ("body", "angles"):
        raise ValueError(f"formulation must be 'body' or 'angles', got {formulation!r}")
    orb = as_orbit(orbit)
    tq, _ = as_torque(torque, body, orb)
    tq.check_setup(body, orb)
    k2_max = None if k2_max is None else real(k2_max, "k2_max")
    min_spin_ratio = real(min_spin_ratio, "min_spin_ratio")
    rules = StartRules(body, k2_max, min_spin_ratio, full=True)
    start = check_start(rules, kind, eps, G0, k2_0, delta0, lam0, nu0, u0, psi0)
    return (drag_equivalent(tq, body, orb), tq, orb, kind, k2_max, min_spin_ratio, start, real(u0, "u0"),
            real(psi0, "psi0"))
