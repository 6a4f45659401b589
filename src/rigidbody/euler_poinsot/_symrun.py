r"""The averaged system of a body with two equal moments (:class:`SymmetricBody`) as a problem for the piecewise
driver :func:`rigidbody.core.piecewise.run_pieces`: one run and a batch (:func:`averaged` dispatches here).

State of a member: :math:`(\ln G, \mathbf n, \theta)` (:math:`\mathbf n` the unit vector of :math:`\mathbf G` in the
orbital axes, :math:`\theta` the nutation angle: its equation is regular on the axis, where :math:`\cos\theta` would
stall against 1), for the sphere :math:`(\ln G, \mathbf n,
\hat{\mathbf g})` (:math:`\hat{\mathbf g}` the direction of :math:`\mathbf G` in the body), and :math:`\nu` on an
eccentric orbit with :math:`\varepsilon > 0`; rates from :mod:`._symengine`. There is no separatrix: :math:`\theta`
passes :math:`\pi/2` (a spin about a transverse axis) smoothly, and a run is one piece. ``rtol`` is the relative
accuracy of :math:`G` and the absolute one (per step) of :math:`\mathbf n` and :math:`\theta`.

The one stop (``eps > 0``): ``'slow_rotation'``, when the fast motion is no longer fast against the orbital rate
:math:`\varepsilon`: the precession :math:`G/A` and, for a torque whose means depend on the body azimuth
:math:`\varphi` (:func:`._symengine.phase_invariant`), the proper rotation :math:`G|c||1/A - 1/C|` too (it
vanishes at :math:`c = 0`, where such a torque's mean over :math:`\varphi` no longer holds).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.ode import Event, Solution
from ..core.piecewise import Continue, MemberRecords, PieceEnd, PieceSpec, Stop, run_pieces
from ..core.validate import RESULT_ERRORS, positive, real, span
from ._boundary import as_torque
from ._checks import check_averaging, check_sigma, check_tau_eval, check_tol
from ._members import assemble, batch_grid
from ._model import Orbit, as_orbit
from ._options import Stops
from ._output import lam_unwrapped, unit_of_angles
from ._protocol import Misfire
from ._stops import drift_refusal, slow_drift, stop_message
from ._symbody import SymmetricBody, cos_theta_of, energy, kind_fields
from ._symengine import choose_grid, phase_invariant, sym_mean, sym_rates
from ._symfull import symmetric_spin_frequency

__all__ = ["SYM_FIELDS", "SymMembers", "SymSetup", "averaged_symmetric", "run_symmetric"]

#: the defaults of the triaxial-only options (a SymmetricBody refuses other values)
_DEFAULTS = {"k2_max": Stops().k2_max, "resonance_tol": Stops().resonance_tol, "branch": "likely", "seed": None}

PRODUCER = "euler_poinsot.averaged"

#: the output fields of an averaged run of a symmetric body (``gb``: the sphere's direction of G in the body)
SYM_FIELDS = ("G", "T", "theta", "k2", "delta", "lam", "nu", "n", "kind", "sigma")


@dataclass
class SymSetup:
    """What the members of a run share: torque object, body, orbit, tolerances, the stop, the quadrature tolerance."""

    torque: Any
    body: SymmetricBody
    orbit: Orbit
    rtol: float
    method: str
    min_spin_ratio: float
    quad_tol: float
    drift_tol: float | None


@dataclass
class SymMembers:
    """Per-member starts (flat arrays): eps, G0, the direction of G in the body (``gb0``, rows), delta0, lam0, nu0;
    the batch shape and the members refused at the start (index -> message)."""

    batch_shape: tuple[int, ...]
    eps: np.ndarray
    G0: np.ndarray
    gb0: np.ndarray
    delta0: np.ndarray
    lam0: np.ndarray
    nu0: np.ndarray
    refused: dict[int, str]


class _Member:
    """One member's run: its grid, whether its torque needs the proper rotation, and its right-hand side."""

    def __init__(self, run: SymSetup, eps: float, G0: float, gb0: np.ndarray, n0: np.ndarray, nu0: float,
                 t0: float) -> None:
        self.run, self.eps, self.t0 = run, eps, t0
        body = run.body
        self.sphere = body.shape == "sphere"
        self.held = eps > 0.0  # the true anomaly held at its value (else averaged over the orbit)
        self.nu_state = self.held and run.orbit.e > 0.0
        self.nu_start = nu0 + (t0 / eps if self.held and not self.nu_state else 0.0)
        nu = self.nu_start if self.held else None
        self.grid, m0 = choose_grid(run.torque, body, G0, gb0, n0, nu, run.orbit, run.quad_tol)
        self.invariant = self.sphere or phase_invariant(run.torque, body, self.grid, G0, n0, nu, run.orbit)
        self.errors = [m0.error / m0.scale if m0.scale > 0.0 else 0.0]
        self.misfire = Misfire()  # a torque that misbehaves part-way ends the run with a status naming it
        y0 = [math.log(G0), *n0.tolist(), *(gb0.tolist() if self.sphere else [math.atan2(gb0[1], gb0[2])])]
        self.y0 = y0 + ([nu0] if self.nu_state else [])
        self.memo: tuple[float, tuple[float, ...], dict[str, Any]] | None = None  # the last rates (the drift event)
        if self.held and run.min_spin_ratio > 0.0:
            r = self.spin_ratio(self.y0)
            if r < run.min_spin_ratio:
                raise ValueError(f"the start is not a fast rotation: the spin ratio {r:.6g} is below "
                                 f"min_spin_ratio = {run.min_spin_ratio:g} (pass a smaller min_spin_ratio)")
        if self.held and run.drift_tol is not None and (d0 := self.drift(t0, self.y0)) > run.drift_tol:
            raise ValueError(drift_refusal(eps, d0, run.drift_tol))

    def unpack(self, t: float, y: Any) -> tuple[float, np.ndarray, np.ndarray, float | None]:
        G = math.exp(y[0])
        n = np.array(y[1:4], dtype=float)
        n /= np.linalg.norm(n)
        if self.sphere:
            gb = np.array(y[4:7], dtype=float)
            gb /= np.linalg.norm(gb)
        else:
            gb = np.array([0.0, math.sin(y[4]), math.cos(y[4])])
        nu = None if not self.held else (float(y[-1]) if self.nu_state else self.nu_start + (t - self.t0) / self.eps)
        return G, n, gb, nu

    def rates(self, t: float, y: Any) -> dict[str, Any]:
        """The averaged rates at ``(t, y)`` (remembered: the drift event asks at the points of the steps)."""
        key = tuple(float(v) for v in y)
        if self.memo is not None and self.memo[0] == t and self.memo[1] == key:
            return self.memo[2]
        G, n, gb, nu = self.unpack(t, y)
        run = self.run
        r = sym_rates(run.body, sym_mean(run.torque, run.body, self.grid, G, gb, n, nu, run.orbit), G, gb, n)
        self.memo = (t, key, r)
        return r

    def rhs(self, t: float, y: Any) -> list[float]:
        if not all(map(math.isfinite, y)):  # a stage after a misfire (NaN rates): NaN again
            return [math.nan] * len(y)
        try:
            r = self.rates(t, y)
        except RESULT_ERRORS as exc:  # NaN rates: the step fails here, the run ends with misfire's message
            self.misfire.note(t, exc)
            return [math.nan] * len(y)
        G = math.exp(y[0])
        out = [r["dG"] / G, *r["dn"].tolist(), *(r["dgb"].tolist() if self.sphere else [r["dtheta"]])]
        if self.nu_state:
            out.append(self.run.orbit.nu_rate(float(y[-1])) / self.eps)
        return out

    def frequency(self, y: Any) -> float:
        """The slowest fast frequency the averaging needs."""
        body = self.run.body
        G = math.exp(y[0])
        f = symmetric_spin_frequency(body, G)
        if not self.invariant:
            f = min(f, G * abs(math.cos(y[4])) * abs(1.0 / body.transverse - 1.0 / body.axial))
        return f

    def spin_ratio(self, y: Any) -> float:
        """The slowest fast frequency the averaging needs, over the orbital rate."""
        return self.frequency(y) / self.eps

    def drift(self, t: float, y: Any) -> float:
        """The relative change of the slow variables in one period of the slowest fast motion."""
        r = self.rates(t, y)
        G = math.exp(y[0])
        T = float(energy(self.run.body, G, 1.0 if self.sphere else math.cos(y[4])))  # the sphere's T: G^2/2A
        return slow_drift(self.eps, self.frequency(y), G, T, r["dG"], r["dT"], float(np.linalg.norm(r["dn"])))

    def events(self) -> list[Event]:
        if not self.held:
            return []
        run, evs = self.run, []
        if run.min_spin_ratio > 0.0:
            r = run.min_spin_ratio
            evs.append(Event(lambda t, y: self.spin_ratio(y) - r, "slow_rotation", True, -1.0,
                             stop_message("slow_rotation", min_spin_ratio=r)))
        if run.drift_tol is not None:
            tol = run.drift_tol
            evs.append(Event(lambda t, y: self.drift(t, y) - tol, "fast_drift", True, 1.0,
                             stop_message("fast_drift", drift_tol=tol)))
        return evs

    def fields(self, tau: np.ndarray, y: np.ndarray) -> dict[str, Any]:
        body = self.run.body
        G = np.exp(y[0])
        n = y[1:4] / np.linalg.norm(y[1:4], axis=0)
        if self.sphere:
            gb = y[4:7] / np.linalg.norm(y[4:7], axis=0)
            c = gb[2]
        else:
            c = np.cos(y[4])
        nu = (y[-1] if self.nu_state else self.nu_start + (tau - self.t0) / self.eps) if self.held else \
            np.full(tau.size, self.nu_start)
        lam = lam_unwrapped(tau, n, float(math.atan2(n[1, 0], n[0, 0]))) if tau.size else np.empty(0)
        out = {"G": G, "T": energy(body, G, c), "theta": np.arccos(c), "delta": np.arccos(np.clip(n[2], -1.0, 1.0)),
               "lam": lam, "nu": nu, "n": n, **kind_fields(body, c)}
        if self.sphere:
            out["gb"] = gb
        return out

    def error_at(self, y: Any, t: float) -> None:
        G, n, gb, nu = self.unpack(t, y)
        run = self.run
        m = sym_mean(run.torque, run.body, self.grid, G, gb, n, nu, run.orbit, estimate=True)
        self.errors.append(m.error / m.scale if m.scale > 0.0 else 0.0)


class SymProblem:
    """The averaged system of a symmetric body for the members of ``mem`` (one mode, one piece each)."""

    continues: tuple[str, ...] = ()

    def __init__(self, run: SymSetup, mem: SymMembers, tau_span: tuple[float, float], te: Any, single: bool,
                 lam0: np.ndarray) -> None:
        self.run, self.mem, self.te, self.single, self.lam0 = run, mem, te, single, lam0
        self.t0 = float(tau_span[0])
        self.members: dict[int, _Member] = {}
        self.sols: dict[int, Solution] = {}

    def piece(self, mode: Any, members: list[int], scalar: bool, tau: np.ndarray) -> PieceSpec:
        i = members[0]
        mem = self.mem
        self.run.torque.check_setup(self.run.body, self.run.orbit)
        n0 = np.array(unit_of_angles(float(mem.delta0[i]), float(mem.lam0[i])))
        m = self.members[i] = _Member(self.run, float(mem.eps[i]), float(mem.G0[i]), mem.gb0[i], n0,
                                      float(mem.nu0[i]), self.t0)
        rtol = self.run.rtol
        return PieceSpec(lambda t, y: m.rhs(t, y), m.y0, rtol, rtol / 10.0, m.events(), (), self.te, True,
                         self.run.method)

    def record(self, mode: Any, members: list[int], sol: Solution, end: PieceEnd) -> None:
        self.sols[members[0]] = self.members[members[0]].misfire.settle(sol)
        end.message[0] = str(sol.message)

    def on_event(self, mode: Any, i: int, j: int, end: PieceEnd) -> Continue | Stop:  # pragma: no cover - none
        raise AssertionError("a symmetric body's averaged run has no continued event")

    def member_result(self, i: int, rec: MemberRecords) -> Solution | str:
        m, sol = self.members.get(i), self.sols.get(i)
        if m is None or sol is None:
            return str(rec.message[i])
        tau, y = np.asarray(sol.time, dtype=float), np.asarray(sol.y, dtype=float)
        if y.shape[-1]:
            m.error_at(y[:, -1], float(tau[-1]))
        fields = m.fields(tau, y)
        lam_user = float(self.lam0[i])
        if tau.size:  # the branch of lambda the user gave
            fields["lam"] = fields["lam"] + 2.0 * math.pi * round((lam_user - fields["lam"][0]) / (2.0 * math.pi))
        return Solution.build(producer=PRODUCER, time_name="tau", time=tau, y=y, status=int(rec.status[i]),
                              message=str(rec.message[i]), event=rec.event[i], fields=fields,
                              t_events=sol.t_events, y_events=sol.y_events, dense=sol.sol, nfev=int(rec.nfev[i]),
                              quad_error=max(m.errors))


def run_symmetric(run: SymSetup, mem: SymMembers, tau_span: tuple[float, float], te: Any, single: bool) -> Solution:
    """Integrate the averaged system of a symmetric body for the members ``mem`` over ``tau_span`` (``single``: one
    run, whose errors raise; ``te`` its output times, or the integrator's steps when None)."""
    B = mem.eps.size
    pb = SymProblem(run, mem, tau_span, te, single, mem.lam0)
    rec = MemberRecords.start([("member", i) for i in range(B)], float(tau_span[0]), mem.refused)
    run_pieces(pb, rec, float(tau_span[1]), strict=single)
    out = [pb.member_result(i, rec) for i in range(B)]
    if single:
        assert isinstance(out[0], Solution)
        return out[0]
    return assemble(out, mem.batch_shape, te, SYM_FIELDS, PRODUCER)


_TRIAXIAL_ONLY = ("k2_max", "resonance_tol", "branch", "seed")


def _start_direction(body: SymmetricBody, G0: float, theta0: Any, T0: Any, sigma: int) -> np.ndarray:
    """The unit vector of G in the body at the start, from ``theta0`` (or ``T0`` with ``sigma``): the symmetric
    body's azimuth is averaged (any value), the sphere's is taken 0 (G in the plane of z2, z3)."""
    if T0 is not None:
        c = cos_theta_of(body, G0, real(T0, "T0"), sigma)
    else:
        th = real(theta0, "theta0")
        if not (0.0 <= th <= math.pi):
            raise ValueError(f"theta0 (the nutation angle of G from the symmetry axis) must lie in [0, pi], got {th}")
        c = math.cos(th)
    return np.array([0.0, math.sqrt(max(0.0, 1.0 - c * c)), c])


def averaged_symmetric(body: SymmetricBody, torque: Any, eps: Any, G0: Any, k2_0: Any, delta0: Any, lam0: Any,
                       tau_span: Any, tau_eval: Any, nu0: Any, theta0: Any, opts: dict[str, Any]) -> Solution:
    """:func:`averaged` for a :class:`SymmetricBody` (the options ``opts`` of :func:`averaged`): inputs checked
    (a member refused in a batch gets status -1 and the single call's message), then :func:`run_symmetric`."""
    if k2_0 is not None or opts["kind"] is not None:
        raise ValueError("a SymmetricBody has k2 = 0 in every motion (regular precession): give its start by theta0 "
                         "(the nutation angle of G from the symmetry axis), or by T0 and sigma, not k2_0 or kind")
    if (theta0 is None) == (opts["T0"] is None):
        raise ValueError("give the start of a SymmetricBody by theta0 (the nutation angle of G from the symmetry "
                         "axis, radians) or by T0 and sigma (one of them)")
    given = [k for k in _TRIAXIAL_ONLY if opts[k] != _DEFAULTS[k]]
    if given:
        raise ValueError(f"{', '.join(given)}: options of a triaxial Body's run (a SymmetricBody has no separatrix, "
                         "and its run does not check resonances)")
    t0, t1 = span(tau_span, "tau_span")
    check_tau_eval(tau_eval, (t0, t1))
    check_tol(opts["rtol"], opts["atol"])
    orb = as_orbit(opts["orbit"])
    check_averaging(opts["averaging"], "averaging")
    sigma = check_sigma(opts["sigma"])
    tq, _ = as_torque(torque, body, orb)
    drift_tol = None if opts["drift_tol"] is None else positive(opts["drift_tol"], "drift_tol")
    run = SymSetup(tq, body, orb, float(opts["rtol"]), opts["method"], real(opts["min_spin_ratio"], "min_spin_ratio"),
                   positive(opts["quad_tol"], "quad_tol"), drift_tol)
    named = {"eps": eps, "G0": G0, "delta0": delta0, "lam0": lam0, "nu0": nu0,
             "theta0": theta0 if opts["T0"] is None else opts["T0"]}
    single = not any(np.ndim(v) for v in named.values())
    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in named.values()))
    flat = {k: a.reshape(-1) for k, a in zip(named, arrays)}
    B = flat["eps"].size
    gb0, refused = np.zeros((B, 3)), {}
    for i in range(B):
        try:
            e, g = real(flat["eps"][i], "eps"), real(flat["G0"][i], "G0")
            if e < 0.0 or g <= 0.0:
                raise ValueError(f"eps must be >= 0 and G0 positive, got eps = {e}, G0 = {g}")
            d = real(flat["delta0"][i], "delta0")
            if not (0.0 <= d <= math.pi):
                raise ValueError(f"delta0 (polar angle of G from x3) must lie in [0, pi], got {d}")
            real(flat["lam0"][i], "lam0"), real(flat["nu0"][i], "nu0")
            x = flat["theta0"][i]
            gb0[i] = _start_direction(body, g, None if opts["T0"] is not None else x,
                                      x if opts["T0"] is not None else None, sigma)
        except ValueError as exc:
            if single:
                raise
            refused[i] = str(exc)
    mem = SymMembers(arrays[0].shape, flat["eps"], flat["G0"], gb0, flat["delta0"], flat["lam0"], flat["nu0"],
                     refused)
    te = tau_eval if single else batch_grid(tau_eval, (t0, t1))
    if te is not None:
        te = np.atleast_1d(np.asarray(te, dtype=float))
    return run_symmetric(run, mem, (t0, t1), te, single)
