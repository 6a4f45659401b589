r"""The averaged system (6)-(9) of Rachinskaya: :func:`averaged`, the public entry of its integration.

The entry collects the options (:mod:`._options`) and hands a single run to :func:`._run.run_averaged`, a batch
(an array among the per-member inputs) to :func:`._batch.averaged_batch`; the integrator itself is described here.

Nondimensional form (section 3): :math:`\tilde G = G/G_0`, :math:`\tilde A_i = A_i\Omega_0/G_0`,
:math:`\varepsilon^2\tilde I = I/G_0`, the orbital rate is :math:`\varepsilon` in units of :math:`\Omega_0`,
slow time :math:`\tau = \varepsilon^2\tilde t` and true anomaly :math:`\nu = \tau/\varepsilon + \nu_0`.
In :math:`\tau` the system (9) is (6) with :math:`\omega_0 = 1` and :math:`I\to\tilde I`, so one set of
functions serves both forms: pass ``omega0`` and dimensional ``I`` for (6) in :math:`t`.

The closed forms of a drag tensor: coordinates, and what ``rtol`` means
-----------------------------------------------------------------------
With a drag tensor each segment of a run integrates (9) in :math:`(\ln G, \ln k^2, \delta, \lambda)` (plus
:math:`\nu` on an eccentric orbit; :math:`(\ln G, \ln k^2, \lambda)` in the orbit-averaged limit
:math:`\varepsilon = 0`, where :math:`\delta` is constant and :math:`\dot\lambda =
\tfrac34(1-e^2)^{-3/2}N^*\cos\delta_0/G`, :func:`precession_rate`) with the right-hand sides of
:mod:`._kernel`: ``rtol`` is the relative accuracy of :math:`G`, :math:`T`, :math:`k^2` however far they decay,
the angle equations (6) are regular at :math:`\sin\delta = 0` (the poles are fixed points of the
gravity-gradient average) and :math:`\lambda` is continuous by construction. DOP853 runs on Python floats
(``core.ode.integrate(engine='python')``) with the kernel's formulas folded into closures; its dense output is
computed for the steps that are sampled. A batch (array inputs, :mod:`._batch`) integrates the same equations
over members with :func:`rigidbody.core.batch.integrate_batch`.

Any torque
----------
With a torque object (``rigidbody.euler_poinsot.LinearDrag``, ..., or a plain function) the integrator evolves
:math:`(\ln G, \ln(k^2 + c), \mathbf n[, \nu])` (the direction of :math:`\mathbf G` as the angles
:math:`(\delta, \lambda)` or the unit vector :math:`\mathbf n`, see :class:`._segment.KindRun`) with
:math:`d(G\mathbf n)/d\tau = \langle C\mathbf M\rangle` and the :math:`k^2` rate of :mod:`._engine` (DOP853 on
Python floats, as for a drag tensor: ``rtol`` is the relative accuracy of :math:`G` and :math:`k^2`, the direction
is held to ``rtol/10`` per step), the means from the closed forms of the torque's parts where they exist and from the
averaging engine otherwise (its grid chosen once, at the start). ``KindRun`` integrates
one kind of motion from given :math:`(G, k^2, \mathbf n)`: a run that reaches the separatrix can be
restarted in the other kind with :math:`G`, :math:`T`, :math:`\mathbf n` continuous. With
:math:`\varepsilon > 0` the run checks the drift per Euler--Poinsot period (event) and the resonances
between the precession and the Euler--Poinsot frequency (predicted jumps, after the integration).
"""

from __future__ import annotations

from math import pi
from typing import Any

from ..core.ode import Solution
from ._batch import averaged_batch
from ._members import drag_batch, is_batch
from ._model import Body, Orbit
from ._options import averaged_options
from ._run import run_averaged
from ._symbody import SymmetricBody, is_symmetric
from ._symrun import averaged_symmetric

__all__ = ["averaged", "averaged_branches"]


def averaged(
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
    r"""Integrate the nondimensional averaged system (9) in the slow time :math:`\tau = \varepsilon^2\tilde t`.

    Parameters
    ----------
    body : Body or SymmetricBody
        Nondimensional moments :math:`\tilde A_i`. A :class:`SymmetricBody` (two equal moments) is averaged over its
        regular precession (see "Bodies with two equal moments" below): its start is ``theta0``.
    torque : array_like, Drag, torque object or callable
        A nondimensional drag tensor :math:`\tilde I` (3x3, its diagonal or a :class:`Drag`; only the
        diagonal enters (9)): Rachinskaya's drag *plus* the gravity-gradient torque, integrated with the
        closed forms (9); an array of shape ``batch_shape + (3, 3)`` gives each member of a batch its own
        tensor. A torque object (:class:`LinearDrag`, :class:`GravityGradient`, ... and sums) or a
        plain callable ``torque(omega, C, nu) -> M`` is the whole perturbation: the averaged system is then
        :math:`d(G\mathbf n)/d\tau = \langle C\mathbf M\rangle`, :math:`dT/d\tau = \langle\boldsymbol\omega
        \cdot\mathbf M\rangle` with the means from the closed forms of the parts that have them and from the
        averaging engine otherwise (see :func:`average_torque` and :ref:`ep-any-torque`).
    eps : float or array_like
        :math:`\varepsilon`, the orbital rate in units of :math:`\Omega_0`; the true anomaly is
        :math:`\nu = \tau/\varepsilon + \nu_0` (Kepler's law for an eccentric ``orbit``). ``eps = 0`` gives
        the orbit-averaged limit (the gravity terms averaged over :math:`\nu`).
    G0, k2_0, delta0, lam0 : float or array_like
        Initial :math:`\tilde G`, :math:`k^2` (in [0, 1); default 0.99), :math:`\delta`, :math:`\lambda`
        (radians).
    tau_span : (float, float)
    tau_eval : array_like, optional
        Output times (default: the solver's steps; for a batch 101 times over ``tau_span``).
    nu0 : float or array_like
        Initial true anomaly.
    kind : {'max', 'min'}
        Initial kind of Euler--Poinsot motion ('max': about the axis of :math:`A_1`, the paper's case;
        the default).
    T0 : float or array_like, optional
        The initial kinetic energy instead of ``k2_0`` and ``kind``: any :math:`T_0` in
        :math:`[G_0^2/(2A_1), G_0^2/(2A_3)]` off the separatrix (the kind follows from :func:`kind_of`).
    orbit : Orbit, optional
        Default circular.
    sigma : {+1, -1}
        Sense of rotation of the Euler--Poinsot motion (torque objects; the drag tensor's averages do not
        depend on it).
    theta0 : float or array_like, optional
        (By keyword, in ``options``.) A :class:`SymmetricBody`'s start: the nutation angle of :math:`\mathbf G`
        from the symmetry axis :math:`z_3`, in :math:`[0, \pi]` (or give ``T0`` and ``sigma``, the sign of
        :math:`\cos\theta`); ``k2_0`` and ``kind`` do not apply (:math:`k^2 = 0` in every motion of such a body).
    **options
        The options below (Other Parameters), by keyword: each group as one value or field by field; an unknown
        keyword raises ``TypeError`` naming it.

    Returns
    -------
    Solution
        ``sol.tau``, ``sol.G``, ``sol.T``, ``sol.k2``, ``sol.delta`` (in [0, pi]), ``sol.lam`` (continuous,
        unwrapped), ``sol.nu`` (the true anomaly; constant ``nu0`` when ``eps = 0``, where it is averaged
        out), ``sol.n`` (unit vector of G in :math:`Ox_i`, shape (3, n)), ``sol.kind`` and ``sol.sigma``
        (the kind of motion and its sense at every output time; ``k2`` is the modulus of that kind),
        ``sol.status`` (0 end reached, 1 an event ended the run, -1 failure: e.g. a torque that turns non-finite
        part-way, named in the message with the time), ``sol.message`` (for an event: what ended the run and the
        option that relaxes it), ``sol.event``
        (``'separatrix'``, ``'slow_rotation'`` or None; with a torque object also ``'fast_drift'`` and
        ``'resonance'``). ``sol.t_events['separatrix']`` holds the times of the separatrix crossings and
        ``sol.crossings`` one dict per crossing: ``tau``, ``source`` and ``region`` (the regions
        ``(kind, sigma)`` before and after), ``probabilities`` (capture probability of each region) and
        ``drifts`` (see :class:`SeparatrixCrossing`). A run that crossed the separatrix has as raw state
        ``sol.y`` the rows ``G, k2, n1, n2, n3`` (and a piecewise dense output ``sol.sol``).
        With a torque object the result also has ``sol.quad_error`` (the estimated quadrature error of the
        engine's averages on the run's grid: the largest of those of the mean torque
        :math:`\langle C\mathbf M\rangle`, of :math:`dT/d\tau` times :math:`G/T` and of :math:`dk^2/d\tau`
        times :math:`G`, relative to the size of the averaged torque, at the first and the last state of each
        segment; 0 when only closed forms are used),
        ``sol.resonances`` (the resonance crossings with their predicted jumps: dicts with
        ``tau``, ``j``, ``m``, ``rho``, ``jump``, ``jump_G``, ``jump_T``, ``jump_n``, ``bound``: True where the
        jumps are upper bounds, for high orders shown harmless without computing their coefficient), ``sol.kind``
        and ``sol.sigma``.

        For a batch every field has shape ``batch_shape + (len(tau_eval),)`` (``n``: ``batch_shape + (3, n_t)``),
        NaN after a member's end; ``status``, ``message``, ``event`` and ``crossings`` are per member; ``sol[i]``
        is member ``i`` as a single-run result.


    Other Parameters
    ----------------
    solver : Solver, or rtol, atol, method
        The integrator as one value (:class:`Solver`) or field by field.
        With a drag tensor ``rtol`` is the relative accuracy of :math:`G`, :math:`T` and :math:`k^2` however far
        they decay (the closed forms are integrated in :math:`\ln G`, :math:`\ln k^2` with absolute control
        ``rtol``) and the angles are held to ``rtol/10`` radians per step (:math:`\lambda` relatively beyond a
        radian); ``atol`` is then not used. With a torque object the state is :math:`(\ln G, \ln k^2, \mathbf n)`
        with the same meaning of ``rtol`` for :math:`G`, :math:`T`, :math:`k^2`, and the unit vector :math:`\mathbf n`
        of :math:`\mathbf G` held to ``rtol/10`` per step; ``atol`` is not used either.
        ``method``: ``'DOP853'`` (default; run on Python floats) or another
        :func:`scipy.integrate.solve_ivp` method (one run only: a batch uses DOP853).
    stops : Stops, or k2_max, min_spin_ratio, drift_tol, resonance_tol
        The stops of the run as one value (:class:`Stops`) or field by field, as below.
    k2_max : float or None
        The run ends (status 1, event ``'separatrix'``) when :math:`k^2` reaches this value (default
        :math:`1 - 10^{-6}`: at :math:`k^2 = 1` the period of the Euler--Poinsot motion is infinite). ``None``:
        the evolution goes on through the separatrix into the other kind of motion (see ``branch``), with
        :math:`G`, :math:`T` and :math:`\mathbf n` continuous; the averaged rates have finite limits there
        (:func:`separatrix_limits`).
    min_spin_ratio : float
        The run ends (event ``'slow_rotation'``) when the rotation is no longer fast: when
        :func:`spin_ratio` (frequency :math:`2\pi/P` of the Euler--Poinsot motion over the orbital rate
        :math:`\varepsilon`) falls to this value (``eps > 0`` only; a start below it raises ``ValueError``;
        pass 0 to switch the check off, e.g. to show where the theory fails). In a run through the separatrix
        (``k2_max=None``) the ratio is taken at :math:`\min(k^2, 0.99)`: the momentary infinite period of the
        crossing itself does not end it.
    averaging : {'auto', 'numerical'}
        For a torque object (or, with ``'numerical'``, a drag tensor): ``'numerical'`` uses the averaging
        engine for every part, also where a closed form exists (for checks and benchmarks).
    quad_tol : float
        Relative tolerance of the engine's quadrature, to which its grid is chosen at the start.
        ``sol.quad_error`` reports the estimated error of the averages at the first and last states.
    drift_tol : float or None
        Torque objects, ``eps > 0``: the run ends (event ``'fast_drift'``) when the slow variables change
        by more than this fraction in one Euler--Poinsot period,
        :math:`\varepsilon^2P(|\dot G|/G + |\dot T|/T + |\dot{\mathbf n}|)`: then there is no separation of
        time scales and the averaging does not hold. ``None`` switches the check off.
    resonance_tol : float or None
        Torque objects, ``eps > 0``: where the rotation number :math:`\rho = \langle\dot\psi\rangle P/2\pi`
        crosses a resonance :math:`j\rho = -m` (:math:`j = 1, 2`) the averaging over :math:`\psi` and the
        phase does not hold; the passage changes the slow variables by the jump
        :math:`2|c_{jm}|\varepsilon\sqrt{P/|j\dot\rho|}` (:math:`c_{jm}` the resonant harmonic of the
        torque's effect), which is computed and listed in ``sol.resonances``. A jump larger than this
        (relative to :math:`G`, :math:`T`; radians for the direction) ends the run there (event
        ``'resonance'``): the passage is too slow (a capture into resonance is possible). ``None`` switches
        the check off.
    branch : 'likely', 'random', (str, int) or sequence of them
        Where the motion goes at a separatrix crossing: beyond the separatrix there are motions of either
        kind and sense, ``(kind, sigma)``, and which one the body enters depends on the fast phase at the
        crossing; :func:`separatrix_crossing` gives their capture probabilities. ``'likely'`` (default)
        continues in the most probable one (ties: ``sigma = +1``, then ``'max'``), ``'random'`` draws it
        (``seed``), a region ``('max', -1)`` forces it, a list of regions forces one per crossing (then
        ``'likely'``). A forced region of probability 0 (its drift points back to the separatrix) ends the
        run there with status 1, event ``'separatrix'``; so does a separatrix that no region leaves (it
        attracts from all sides). :func:`averaged_branches` runs every branch of the first crossing.
    seed : int or numpy.random.Generator, optional
        Random source for ``branch='random'``.

    See Also
    --------
    simulate : the full (unaveraged) equations of the same problem.
    averaged_rates : the right-hand sides integrated here.
    averaged_branches : every branch of a separatrix crossing.

    Notes
    -----
    *Batches.* Arrays for ``eps``, ``G0``, ``k2_0`` (or ``T0``), ``delta0``, ``lam0``, ``nu0`` (and a batch of
    drag tensors) broadcast to one batch shape; the body, the orbit, ``tau_span``, ``kind``, ``sigma`` and the
    options are shared. With a drag tensor the members are integrated together
    (:func:`rigidbody.core.batch.integrate_batch`, the closed forms vectorised over members, per-member step
    control and events), round by round: a member that reaches the separatrix in a run through it
    (``k2_max=None``) crosses as its single run does and continues in the next round in the other kind of
    motion. A member whose start the single call refuses gets ``status = -1`` and that call's message; the
    others go on. A torque object made of :class:`LinearDrag` parts and the :class:`GravityGradient` of the run
    (the drag tensor's meaning) runs the same vectorised closed forms; any other torque object (or
    ``averaging='numerical'``) runs its members one by one through the single call (the engine's quadrature
    adapts to each state). Every member equals its single call within
    the tolerance; with ``branch='random'`` the members draw from one generator seeded by ``seed``.

    *Bodies with two equal moments.* For a :class:`SymmetricBody` (transverse moment :math:`A`, axial :math:`C`;
    the sphere :math:`A = C`) the slow variables are :math:`G`, the nutation cosine :math:`c = \cos\theta` and the
    direction :math:`\mathbf n` of :math:`\mathbf G`: :math:`d(G\mathbf n)/d\tau = \langle C\mathbf M\rangle`,
    :math:`dc/d\tau = (\langle M_3\rangle - c\,\mathbf n\cdot\langle C\mathbf M\rangle)/G`, the means over the
    precession angle and the body azimuth of :math:`\mathbf G` (and the orbit for ``eps = 0``) by the trapezoid
    rule on a grid chosen at the start to ``quad_tol``. These are the limits of the triaxial rates as two moments
    meet (tested at relative differences 1e-3, 1e-6, 1e-9). There is no separatrix (:math:`c` passes 0
    smoothly). The sphere has no proper rotation: the direction of :math:`\mathbf G` in the body is a slow
    variable. The result has ``theta`` (nutation angle) besides ``G``, ``T``, ``delta``, ``lam``, ``nu``, ``n``,
    ``kind`` (``'max'`` for an oblate body, ``'min'`` for a prolate one), ``sigma`` (the sign of
    :math:`\cos\theta`), ``k2`` (0) and ``quad_error``; the stop ``min_spin_ratio`` compares the precession rate
    :math:`G/A` with :math:`\varepsilon` and, for a torque whose means depend on the body azimuth, the proper
    rotation :math:`G|c||1/A - 1/C|` too, and ``drift_tol`` the change of the slow variables in one period of
    that slowest motion. The options of the separatrix and of the resonance check do not apply (the resonances
    between precession and proper rotation are not checked).

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eqs. (6)-(9) and section 3 (the drag cases).

    Examples
    --------
    A prolate axisymmetric body under an axisymmetric drag :math:`-I\boldsymbol\omega`: the axial component of
    :math:`\mathbf G` decays at :math:`I_3/C = 0.3`, the transverse one at :math:`I_1/A = 0.05`, so
    :math:`\tan\theta = \tan\theta_0\,e^{0.25\tau}` and :math:`\mathbf G` leaves the symmetry axis:

    >>> import math
    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.SymmetricBody(A=2.0, C=1.0)
    >>> drag = ep.LinearDrag([0.1, 0.1, 0.3])
    >>> sol = ep.averaged(body, drag, 0.0, theta0=1.0, tau_span=(0, 3), tau_eval=[0, 3])
    >>> print(sol.status, f"{sol.theta[-1]:.6f} {math.atan(math.tan(1.0) * math.exp(0.75)):.6f}", sol.kind[-1])
    0 1.276312 1.276312 min

    The paper's first drag case, orbit-averaged (``eps = 0``): the drag dissipates, so :math:`G` falls:

    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> sol = ep.averaged(body, np.diag([2.322, 1.31, 1.425]), 0.0, tau_span=(0, 3), tau_eval=[0, 3])
    >>> bool(sol.G[-1] < sol.G[0]), sol.status
    (True, 0)
    """
    opts = averaged_options(kind=kind, T0=T0, orbit=orbit, sigma=sigma, **options)
    theta0 = opts.pop("theta0")
    if is_symmetric(body):
        return averaged_symmetric(body, torque, eps, G0, k2_0, delta0, lam0, tau_span, tau_eval, nu0, theta0, opts)
    if theta0 is not None:
        raise ValueError("theta0 starts a SymmetricBody; a Body's start is k2_0 and kind (or T0)")
    if is_batch(eps, G0, k2_0, delta0, lam0, nu0, opts["T0"]) or drag_batch(torque) is not None:
        return averaged_batch(body, torque, eps, G0, k2_0, delta0, lam0, tau_span, tau_eval, nu0, opts)
    return run_averaged(body, torque, eps, G0, k2_0, delta0, lam0, tau_span, tau_eval, nu0, **opts)


def averaged_branches(*args: Any, **kwargs: Any) -> dict[tuple[str, int], Solution]:
    r"""Every branch of the first separatrix crossing of an averaged run.

    Runs :func:`averaged` with the same arguments (``branch`` excepted) and, at its first separatrix crossing,
    continues once in each region ``(kind, sigma)`` of positive capture probability (later crossings take
    the most probable branch).

    Parameters
    ----------
    *args, **kwargs
        As for :func:`averaged`, without ``branch``.

    Returns
    -------
    dict
        Region -> Solution; each Solution's ``crossings[0]['probabilities'][region]`` is the probability of
        that branch. A run that does not cross the separatrix gives one entry, its initial region.

    See Also
    --------
    averaged : one run, in the most probable (or a chosen) branch.
    separatrix_crossing : the capture probabilities.

    References
    ----------
    :ref:`A. L. Rachinskaya (c. 2014) <ref-rachinskaya>`, eq. (9) (integrated on each side of the separatrix).

    Examples
    --------
    For the drag ``diag(3, 2, 1)`` :math:`k^2` grows to the separatrix (:func:`k2_equilibria`: only the
    unstable :math:`k^2 = 0`), and the motion goes on about the axis of :math:`A_3`; the drag is odd in
    :math:`\boldsymbol\omega`, so the two senses of rotation there are equally likely:

    >>> from rigidbody import euler_poinsot as ep
    >>> runs = ep.averaged_branches(ep.Body(3.2, 2.6, 1.67), [3.0, 2.0, 1.0], 0.0, k2_0=0.9, tau_span=(0, 3),
    ...                             k2_max=None)
    >>> for region, sol in sorted(runs.items()):
    ...     print(region, sol.status, f"{sol.crossings[0]['probabilities'][region]:.6f}")
    ('min', -1) 0 0.500000
    ('min', 1) 0 0.500000
    """
    if "branch" in kwargs:
        raise TypeError("averaged_branches runs every branch: do not pass branch")
    first = averaged(*args, **kwargs)
    if not getattr(first, "crossings", None):
        return {(str(first.kind[0]), int(first.sigma[0])): first} if first.tau.size else {}
    c = first.crossings
    out: dict[tuple[str, int], Solution] = {}
    for region, p in c[0]["probabilities"].items():
        if p > 0.0:
            out[region] = first if region == c[0]["region"] else averaged(*args, branch=[region], **kwargs)
    return out

