r"""A batch of full (unaveraged) motions integrated together: the body-frame formulation over members.

Each member is the ``formulation='body'`` run of :func:`rigidbody.euler_poinsot.simulate`: Euler's equations
for the body components :math:`\mathbf g` of :math:`\mathbf G` and the attitude quaternion (body -> orbital
axes), in the slow time :math:`\tau`, with :math:`d\mathbf g/d\tau = \varepsilon^{-2}\mathbf g\times
\boldsymbol\omega + \mathbf M`. The members share the body, the torque, the orbit, ``tau_span`` and the
options; their initial slow variables, the phase ``u0``, ``psi0`` of the Euler--Poinsot motion, ``nu0`` and
``eps`` are per member. The torque is evaluated on all active members at once: the drag tensor (drag plus
gravity gradient) by its formula, a torque object through its vectorised protocol ``torque(omega, C, nu)``
(arrays of shape ``(m, 3)``, ``(m, 3, 3)``, ``(m,)``).

The direction of :math:`\mathbf G` in the orbital axes is output as ``delta`` and a continuous ``lam``: the
azimuth ``atan2(n2, n1)`` plus :math:`2\pi` for every passage through its branch cut (``n2 = 0`` with
``n1 < 0``), located as events of the integration, so the output grid may be as coarse as one likes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.batch import integrate_batch, member_records
from ..core.euler import dcm_from_unit_quat
from ..core.ode import Event, Solution
from ..core.validate import result_message
from . import _kernel as _k
from ._full import initial_state
from ._members import Members
from ._model import Body, Orbit
from ._protocol import ROLE, evaluate
from ._stops import stop_message

__all__ = ["FullRun", "full_batch"]


@dataclass
class FullRun:
    """What the members share: body, torque (``what`` 'drag' with the tensor, or 'torque' with the object),
    orbit, the initial kind of each member (an array) and the sense of motion, tolerances and the terminal
    checks."""

    body: Body
    what: str
    torque: Any
    orbit: Orbit
    kind: np.ndarray
    sigma: int
    rtol: float
    atol: float
    k2_max: float | None
    min_spin_ratio: float
    spin_cap: float = 1.0


def _osculating(A: tuple[float, float, float], D: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Labelled moments (arrays) of the kind D = G^2/2T belongs to and its osculating k2 in [0, 1]."""
    A1, A2, A3 = A
    mx = D >= A2
    a1 = np.where(mx, A1, A3)
    a3 = np.where(mx, A3, A1)
    den = (a1 - A2) * (D - a3)
    with np.errstate(divide="ignore", invalid="ignore"):
        k2 = np.where(den > 0.0, (A2 - a3) * (a1 - D) / np.where(den > 0.0, den, 1.0), np.inf)
    return a1, a3, np.clip(k2, 0.0, 1.0)


def _k2_initial_kind(A1: Any, A2: float, A3: Any, D: np.ndarray) -> np.ndarray:
    """The osculating k2 by the formula of the initial kind (labelled moments, per member), unclipped (inf beyond
    the separatrix)."""
    den = (A1 - A2) * (D - A3)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0.0, (A2 - A3) * (A1 - D) / np.where(den > 0.0, den, 1.0), np.inf)


def full_batch(run: FullRun, mem: Members, u0: np.ndarray, psi0: np.ndarray, tau_span: tuple[float, float],
               te: np.ndarray) -> Solution:
    """The batch branch of :func:`rigidbody.euler_poinsot.simulate` (flat per-member arrays in ``mem``)."""
    body, orb = run.body, run.orbit
    A = (body.A1, body.A2, body.A3)
    A1, A2, A3 = A
    e = orb.e
    B = mem.eps.size
    nt = te.size
    t0, t1 = float(tau_span[0]), float(tau_span[1])
    ns = 7 if e == 0.0 else 8
    status, message, event, nfev, t_final = member_records(B, t0)
    Y = np.full((B, ns, nt), np.nan)
    for i, msg in mem.refused.items():
        message[i] = msg
    idx = np.array([i for i in range(B) if i not in mem.refused], dtype=int)
    none = np.empty(0)
    none.setflags(write=False)
    t_ev = {name: np.empty(B, dtype=object) for name in ("separatrix", "slow_rotation")}
    for arr in t_ev.values():
        arr.fill(none)
    lam_shift = np.zeros((B, nt))
    if idx.size:
        y0 = _initial_states(run, mem, idx, u0, psi0, ns)
        ie = 1.0 / mem.eps[idx]
        mx = run.kind[idx] == "max"  # the labelled moments A1, A3 of each member's initial kind (the k2_max stop)
        # the last arg: each member's index, to note where its torque turned non-finite (t_bad; see below)
        args = (ie, ie * ie, mem.nu0[idx], np.where(mx, A1, A3), np.where(mx, A3, A1), idx.astype(float))
        t_bad = np.full(B, np.nan)
        Ab = np.array(A)
        rhs = _rhs(run, t_bad)

        def GD(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            g2 = y[:, 0:3] ** 2
            G2 = g2.sum(axis=1)
            return np.sqrt(G2), G2 / (g2 / Ab).sum(axis=1)

        def n_of(y: np.ndarray) -> np.ndarray:
            q = y[:, 3:7] / np.linalg.norm(y[:, 3:7], axis=1, keepdims=True)
            g = np.einsum("mij,mj->mi", dcm_from_unit_quat(*q.T), y[:, 0:3])
            return g / np.sqrt((y[:, 0:3] ** 2).sum(axis=1))[:, None]

        # the two cut events are evaluated in turn on the same arrays: one evaluation serves both (the cache holds
        # the arrays themselves, so their ids cannot be reused while cached)
        ncache: list[Any] = [None, None]

        def n2(t: np.ndarray, y: np.ndarray, *a: np.ndarray) -> np.ndarray:
            if ncache[0] is not y:
                ncache[:] = [y, n_of(y)[:, 1]]
            return ncache[1]

        r = run.min_spin_ratio
        cap = run.spin_cap

        def ev_spin(t: np.ndarray, y: np.ndarray, ie: np.ndarray, *a: np.ndarray) -> np.ndarray:
            G, D = GD(y)
            a1, a3, k2 = _osculating(A, D)
            out = np.empty(G.shape)
            for lab in (True, False):  # the two labellings
                sel = (a1 == A1) if lab else (a1 != A1)
                if np.any(sel):
                    Al = (A1, A2, A3) if lab else (A3, A2, A1)
                    out[sel] = _k.nut_freq(np, Al, G[sel], np.minimum(k2[sel], cap)) * ie[sel] - r
            return out

        if run.k2_max is None:
            ev_sep = Event(lambda t, y, *a: GD(y)[1] - A2, "separatrix", False, 0.0, "")
        else:
            stop = run.k2_max
            ev_sep = Event(lambda t, y, *a: _k2_initial_kind(a[3], A2, a[4], GD(y)[1]) - stop, "separatrix", True, 1.0,
                           stop_message("separatrix_full", k2_max=stop))
        # passages of the azimuth through its branch cut (n2 = 0 with n1 < 0), both ways
        events = [ev_sep, Event(ev_spin, "slow_rotation", True, -1.0, stop_message("slow_rotation", min_spin_ratio=r)),
                  Event(n2, "_cut_up", False, 1.0, ""), Event(n2, "_cut_down", False, -1.0, "")]
        sol = integrate_batch(rhs, (t0, t1), y0, t_eval=te, rtol=run.rtol, atol=run.atol, events=events, args=args,
                              time_name="tau")
        Y[idx] = sol.y
        status[idx] = sol.status
        message[idx] = sol.message
        event[idx] = sol.event
        nfev[idx] = sol.nfev
        t_final[idx] = sol.t_final
        for name in t_ev:
            t_ev[name][idx] = sol.t_events[name]
        # a member whose torque turned non-finite where it failed: the message names the torque and the time
        why = result_message(getattr(run.torque, "fun", run.torque), (3,), "non-finite values (NaN or inf)", ROLE)
        for i in idx[(status[idx] == -1) & (t_bad[idx] >= t_final[idx])].tolist():
            message[i] = stop_message("torque", tau=t_bad[i], why=why)
        _cut_shifts(sol, idx, n_of, te, lam_shift)
    data = _fields(A, Y, lam_shift, mem, te, e)
    shape = mem.batch_shape
    data = {k: v.reshape(shape + v.shape[1:]) for k, v in data.items()}
    t_events = {k: v.reshape(shape) for k, v in t_ev.items()}
    return Solution("tau", te, Y.reshape(shape + Y.shape[1:]), data, status.reshape(shape), message.reshape(shape),
                    event.reshape(shape), t_events, {}, None, nfev.reshape(shape), batch_shape=shape,
                    t_final=t_final.reshape(shape))


def _initial_states(run: FullRun, mem: Members, idx: np.ndarray, u0: np.ndarray, psi0: np.ndarray,
                    ns: int) -> np.ndarray:
    """The body-frame start (g, q[, nu]) of each member in ``idx``."""
    y0 = np.empty((idx.size, ns))
    for j, i in enumerate(idx):
        st = initial_state(run.body, float(mem.G0[i]), float(mem.k2_0[i]), float(mem.delta0[i]), float(mem.lam0[i]),
                           kind=str(run.kind[i]), u0=float(u0[i]), psi0=float(psi0[i]), sigma=run.sigma)
        y0[j, :3], y0[j, 3:7] = st["g"], st["q"]
        if ns == 8:
            y0[j, 7] = mem.nu0[i]
    return y0


def _cut_shifts(sol: Solution, idx: np.ndarray, n_of: Any, te: np.ndarray, lam_shift: np.ndarray) -> None:
    """Add 2 pi to lambda of each member at every passage of its azimuth through the branch cut (n2 = 0, n1 < 0)."""
    for j, i in enumerate(idx):
        for name, sign in (("_cut_up", -1.0), ("_cut_down", 1.0)):
            tc, yc = sol.t_events[name][j], sol.y_events[name][j]
            if tc.size:
                tc = tc[n_of(yc)[:, 0] < 0.0]
                lam_shift[i] += sign * 2.0 * math.pi * (tc[:, None] <= te[None, :]).sum(axis=0)


def _rhs(run: FullRun, t_bad: np.ndarray) -> Any:
    """The vectorised body-frame equations of the members (drag tensor plus gravity gradient written out, or the
    torque object through its vectorised protocol; where it turns non-finite, the time is noted in ``t_bad``)."""
    A1, A2, A3 = run.body.A1, run.body.A2, run.body.A3
    e = run.orbit.e
    drag = run.what == "drag"
    if drag:
        (I11, I12, I13), (I21, I22, I23), (I31, I32, I33) = np.asarray(run.torque.I, dtype=float).tolist()

    def rhs(t: np.ndarray, y: np.ndarray, ie: np.ndarray, ie2: np.ndarray, nu0: np.ndarray, *lab: np.ndarray
            ) -> np.ndarray:
        g1, g2, g3, w, x, yq, z = y[:, 0], y[:, 1], y[:, 2], y[:, 3], y[:, 4], y[:, 5], y[:, 6]
        nrm = np.sqrt(w * w + x * x + yq * yq + z * z)
        w, x, yq, z = w / nrm, x / nrm, yq / nrm, z / nrm
        o1, o2, o3 = g1 / A1, g2 / A2, g3 / A3
        nu = t * ie + nu0 if e == 0.0 else y[:, 7]
        if drag:  # drag plus gravity gradient, written out as in the single run
            cn, sn = np.cos(nu), np.sin(nu)
            r1 = (1 - 2 * (yq * yq + z * z)) * cn + 2 * (x * yq + w * z) * sn  # e_r in body axes
            r2 = 2 * (x * yq - w * z) * cn + (1 - 2 * (x * x + z * z)) * sn
            r3 = 2 * (x * z + w * yq) * cn + 2 * (yq * z - w * x) * sn
            f3 = 3.0 * _k.orbit_factor(np, e, nu) if e != 0.0 else 3.0
            L1 = f3 * (A3 - A2) * r2 * r3 - (I11 * o1 + I12 * o2 + I13 * o3)
            L2 = f3 * (A1 - A3) * r3 * r1 - (I21 * o1 + I22 * o2 + I23 * o3)
            L3 = f3 * (A2 - A1) * r1 * r2 - (I31 * o1 + I32 * o2 + I33 * o3)
        else:  # the torque's type and shape checked, its finiteness per member (a NaN ends that member only)
            C = dcm_from_unit_quat(w, x, yq, z)
            M = np.broadcast_to(evaluate(run.torque, np.stack([o1, o2, o3], axis=1), C, nu, (t.size, 3),
                                         finite=False), (t.size, 3))
            bad = ~np.isfinite(M).all(axis=1)
            if bad.any():
                t_bad[lab[2][bad].astype(int)] = t[bad]
            L1, L2, L3 = M[:, 0], M[:, 1], M[:, 2]
        out = np.empty_like(y)
        out[:, 0] = (g2 * o3 - g3 * o2) * ie2 + L1
        out[:, 1] = (g3 * o1 - g1 * o3) * ie2 + L2
        out[:, 2] = (g1 * o2 - g2 * o1) * ie2 + L3
        h = 0.5 * ie2
        out[:, 3] = h * (-x * o1 - yq * o2 - z * o3)
        out[:, 4] = h * (w * o1 + yq * o3 - z * o2)
        out[:, 5] = h * (w * o2 - x * o3 + z * o1)
        out[:, 6] = h * (w * o3 + x * o2 - yq * o1)
        if e != 0.0:
            out[:, 7] = ie * _k.nu_rate(np, e, y[:, 7])
        return out

    return rhs


def _fields(A: tuple[float, float, float], Y: np.ndarray, lam_shift: np.ndarray, mem: Members, te: np.ndarray,
            e: float) -> dict[str, np.ndarray]:
    """The output fields of the batch from its raw rows ``Y`` (g, q[, nu]; NaN after a member's end), lambda
    continuous from the counted passages through the branch cut (``lam_shift``)."""
    A1, A2, A3 = A
    g = Y[:, 0:3]
    qn = Y[:, 3:7] / np.linalg.norm(Y[:, 3:7], axis=1, keepdims=True)
    R = dcm_from_unit_quat(*np.moveaxis(qn, 1, 0))  # (B, nt, 3, 3)
    n = np.einsum("bkij,bjk->bik", R, g)
    G = np.sqrt((g * g).sum(axis=1))
    n = n / G[:, None, :]
    T = 0.5 * (g[:, 0] ** 2 / A1 + g[:, 1] ** 2 / A2 + g[:, 2] ** 2 / A3)
    with np.errstate(invalid="ignore", divide="ignore"):
        D = G * G / (2.0 * T)
        _, _, k2 = _osculating(A, D)
        mx = D >= A2
        sig = np.where(np.where(mx, g[:, 0], g[:, 2]) >= 0.0, 1.0, -1.0)
    nan = np.isnan(G)
    k2 = np.where(nan, np.nan, k2)
    sig = np.where(nan, np.nan, sig)
    kinds = np.where(nan, "", np.where(mx, "max", "min"))
    az = np.arctan2(n[:, 1], n[:, 0])
    lam = az + lam_shift
    # the branch of the initial value given by the user
    lam = lam + 2.0 * math.pi * np.round((mem.lam0[:, None] - lam[:, :1]) / (2.0 * math.pi))
    if e == 0.0:
        with np.errstate(divide="ignore", invalid="ignore"):  # refused members (eps = 0) are NaN anyway
            nu = np.where(nan, np.nan, te[None, :] / mem.eps[:, None] + mem.nu0[:, None])
    else:
        nu = Y[:, 7]
    return {"G": G, "T": T, "k2": k2, "delta": np.arccos(np.clip(n[:, 2], -1.0, 1.0)), "n": n, "nu": nu,
            "kind": kinds, "sigma": sig, "lam": lam, "g": g, "q": qn}
