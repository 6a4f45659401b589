"""The public entry of the full equations: :func:`simulate` (a single run, or a batch when an input is an array)."""

from __future__ import annotations

from math import pi
from typing import Any

from ..core.ode import Solution
from ._batch import simulate_batch
from ._fullrun import run_full
from ._members import is_batch
from ._model import Body, Orbit
from ._options import simulate_options
from ._symbody import SymmetricBody, is_symmetric
from ._symfull import simulate_symmetric

__all__ = ["simulate"]


def simulate(
    body: Body | SymmetricBody,
    torque: Any,
    eps: Any,
    G0: Any = 1.0,
    k2_0: Any = None,
    delta0: Any = pi / 4,
    lam0: Any = pi / 4,
    tau_span: tuple[float, float] = (0.0, 3.0),
    tau_eval: Any = None,
    nu0: Any = 0.0,
    *,
    kind: str | None = None,
    T0: Any = None,
    orbit: Orbit | None = None,
    sigma: int = 1,
    **options: Any,
) -> Solution:
    r"""Integrate the full, unaveraged motion (1), (3), (4) in the slow time :math:`\tau`.

    Same arguments and output fields as :func:`averaged` (the slow variables are the instantaneous,
    osculating ones: :math:`k^2` from (5) with the current :math:`G, T`), plus the body's initial phase.
    The body-frame equations are regular on the separatrix :math:`G^2 = 2TA_2`: the run goes through it,
    the osculating kind of motion (and with it the formula for :math:`k^2`) switches there, and each passage
    is recorded in ``t_events['separatrix']``.

    A :class:`SymmetricBody` (two equal moments, the sphere) runs the same body-frame equations from its regular
    precession at the nutation angle ``theta0``; it has no separatrix, no :math:`k^2` and no kind of motion.

    Parameters
    ----------
    body : Body or SymmetricBody
    torque : array_like, Drag, torque object or callable
        A drag tensor :math:`\tilde I` (3x3, its diagonal, or a :class:`Drag`): Rachinskaya's drag *plus*
        the gravity-gradient torque (3), as in :func:`averaged`. A torque object
        (:class:`LinearDrag`, :class:`GravityGradient`, their sums, ...) or a plain callable
        ``torque(omega, C, nu) -> M`` is the whole perturbation (body components, the section-3 scaling
        divided by :math:`\varepsilon^2`; see :class:`Torque`): :math:`d\mathbf g/d\tau =
        \varepsilon^{-2}\mathbf g\times\boldsymbol\omega + \mathbf M`.
    eps, G0, delta0, lam0, tau_span, tau_eval, nu0, orbit
        As in :func:`averaged` (``eps``, ``G0``, ``delta0``, ``lam0``, ``nu0`` floats or arrays of a batch);
        ``eps`` must be positive (the cost grows like :math:`\varepsilon^{-2}`: :math:`\tau` spans
        :math:`\tau/\varepsilon^2` units of :math:`\tilde t`).
    k2_0, kind : float or array_like, {'max', 'min'}
        Initial modulus squared (in [0, 1); default 0.99) and kind of motion (default ``'max'``, the paper's).
        A :class:`SymmetricBody` refuses them (``ValueError``: give ``theta0``).
    T0 : float or array_like, optional
        The initial kinetic energy instead of ``k2_0`` and ``kind``: any :math:`T_0` in
        :math:`[G_0^2/(2A_1), G_0^2/(2A_3)]` off the separatrix (the kind follows from :func:`kind_of`). For a
        :class:`SymmetricBody` instead of ``theta0``: :math:`\cos\theta_0` of sign ``sigma`` from
        :math:`2T_0 = G_0^2((1 - \cos^2\theta_0)/A + \cos^2\theta_0/C)` (not for the sphere).
    sigma : {+1, -1}
        Sense of rotation of the Euler--Poinsot motion (see :func:`initial_state`); for a :class:`SymmetricBody`
        the sign of :math:`\cos\theta_0` found from ``T0`` (with ``theta0``: 1).
    **options
        The options below, by keyword; an unknown keyword raises ``TypeError`` naming it.
    u0, psi0 : float or array_like
        Initial elliptic phase (default 0; a :class:`SymmetricBody` refuses it: ``phi0``) and precession angle about
        :math:`\mathbf G` (default 0; floats or arrays of a batch; see :func:`initial_state`).
    theta0, phi0 : float or array_like
        A :class:`SymmetricBody`'s start (required for it unless ``T0`` is given; a :class:`Body` refuses them): the
        nutation angle of :math:`\mathbf G` from the symmetry axis :math:`z_3`, in :math:`[0, \pi]`, and the
        azimuth of :math:`\mathbf G` in the body about :math:`z_3` (default 0): :math:`\mathbf g =
        G_0(\sin\theta_0\sin\varphi_0, \sin\theta_0\cos\varphi_0, \cos\theta_0)`, the attitude
        :math:`Y R_3(\psi_0) R_1(\theta_0) R_3(\varphi_0)` with ``psi0`` the precession angle about
        :math:`\mathbf G`.
    solver : Solver, or rtol, atol, method
        The integrator as one value (:class:`Solver`) or field by field, as in :func:`averaged`.
    stops : Stops, or k2_max, min_spin_ratio
        The stops as one value (:class:`Stops`; its ``drift_tol`` and ``resonance_tol``, stops of the averaged
        system, must keep their defaults) or field by field, as below.
    formulation : {'body', 'angles'}
        Euler's equations with a quaternion (default, regular everywhere) or the paper's (1), (3), (4) (a triaxial
        body only).
    k2_max : float or None
        The run ends (event ``'separatrix'``) as soon as the osculating :math:`k^2` of the initial kind reaches
        it (default :math:`1 - 10^{-6}`, as :func:`averaged`). ``None``: no stop; the motion goes on through the
        separatrix (the body-frame equations are regular there) and the crossings are recorded, not terminal. A
        :class:`SymmetricBody` has no separatrix: it refuses any other value than these two.
    min_spin_ratio : float
        The run ends (event ``'slow_rotation'``) when :func:`spin_ratio` of the osculating motion falls to this
        value, as in :func:`averaged`. In a run through the separatrix (``k2_max=None``) the ratio is taken at
        :math:`\min(k^2, 0.99)`: within 0.01 of the separatrix the period grows like :math:`\ln(1/(1-k^2))`
        while the body still turns fast (about the intermediate axis), and the momentary infinite period of a
        passage must not end the run. For a :class:`SymmetricBody` the frequency is the precession rate
        :math:`G/A` (positive at every nutation angle and for the sphere).

    Returns
    -------
    Solution
        ``tau, G, T, k2, delta, lam, nu, n`` as :func:`averaged`, and ``kind`` (``'max'``/``'min'`` at each
        output time: the osculating kind of motion; ``k2`` is that kind's modulus) and ``sigma`` (+1/-1: the
        sign of :math:`g_1` for ``'max'``, of :math:`g_3` for ``'min'``); ``t_events['separatrix']`` holds the
        times of the passages through the separatrix. ``'body'`` adds ``g`` (body components of G, shape
        (3, n)) and ``q``; ``'angles'`` adds ``theta, phi, psi`` and ``T`` is the integrated energy of (4).
        For a batch every field has the leading ``batch_shape`` (and ``tau_eval``, default 101 times, as its
        last axis), NaN after a member's end; ``status``, ``message``, ``event`` are per member. A
        :class:`SymmetricBody`'s run has ``tau, G, T, theta`` (the osculating nutation angle
        :math:`\arccos(g_3/G)`), ``delta, lam, nu, n, g, q`` and ``t_events['slow_rotation']`` only.

    See Also
    --------
    averaged : the averaged system (9) of the same problem.
    initial_state : the attitude a run starts from.

    Notes
    -----
    *Batches.* Arrays for ``eps``, ``G0``, ``k2_0`` (or ``T0``), ``delta0``, ``lam0``, ``nu0``, ``u0``, ``psi0``
    (for a :class:`SymmetricBody` ``theta0`` or ``T0``, ``phi0`` instead of ``k2_0`` and ``u0``) broadcast to one
    batch shape (a batch over initial phases is an ensemble of the same slow state). The
    ``'body'`` formulation integrates the members together (:func:`rigidbody.core.batch.integrate_batch`, the
    torque evaluated on all members at once: a torque object through its vectorised protocol), with
    ``lam`` continuous from the located passages of :math:`\mathbf n` through the branch cut of the azimuth;
    the ``'angles'`` formulation (and a ``method`` other than DOP853) runs member by member. A member whose
    start the single call refuses gets ``status = -1`` and that call's message.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (1), (3), (4) (the full equations) and (5)
    (the modulus :math:`k^2`).

    Examples
    --------
    With no torque the motion is Euler--Poinsot's: :math:`G` and :math:`T`, hence :math:`k^2`, keep their
    initial values (1 and 0.5 here) to the integrator's tolerance:

    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> sol = ep.simulate(body, ep.ConstantTorque([0.0, 0.0, 0.0]), 0.1, k2_0=0.5, tau_span=(0, 0.05),
    ...                   tau_eval=[0, 0.05])
    >>> print(sol.status, f"{sol.G[-1]:.6f} {sol.k2[-1]:.6f}")
    0 1.000000 0.500000

    A prolate symmetric body keeps its regular precession: :math:`G` and the nutation angle stay at 1.2 and 0.6,
    while the body turns about :math:`\mathbf G` at :math:`G/A` (the attitude changes):

    >>> sym = ep.SymmetricBody(A=2.0, C=1.0)
    >>> sol = ep.simulate(sym, ep.ConstantTorque([0.0, 0.0, 0.0]), 0.1, G0=1.2, theta0=0.6, tau_span=(0, 0.05),
    ...                   tau_eval=[0, 0.05])
    >>> print(sol.status, f"{sol.G[-1]:.6f} {sol.theta[-1]:.6f}", bool(abs(sol.q[:, -1] @ sol.q[:, 0]) < 0.99))
    0 1.200000 0.600000 True
    """
    opts = simulate_options(kind=kind, T0=T0, orbit=orbit, sigma=sigma, **options)
    if is_symmetric(body):
        return simulate_symmetric(body, torque, eps, G0, k2_0, delta0, lam0, tau_span, tau_eval, nu0, opts)
    for name in ("theta0", "phi0"):
        if opts.pop(name) is not None:
            raise ValueError(f"{name} starts a SymmetricBody; a triaxial Body starts from k2_0 (or T0) and kind, at "
                             "the phase u0 and psi0")
    if opts["u0"] is None:
        opts["u0"] = 0.0
    if is_batch(eps, G0, k2_0, delta0, lam0, nu0, opts["T0"], opts["u0"], opts["psi0"]):
        return simulate_batch(body, torque, eps, G0, k2_0, delta0, lam0, tau_span, tau_eval, nu0, opts["u0"],
                              opts["psi0"], opts)
    return run_full(body, torque, eps, G0, k2_0, delta0, lam0, tau_span, tau_eval, nu0, **opts)
