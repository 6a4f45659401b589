r"""Fast rotation of a triaxial satellite under gravity-gradient and drag torques (Rachinskaya).

A. L. Rachinskaya, "Rapid rotation of a satellite in a resisting medium in a circular orbit"
(c. 2014). A triaxial body (:math:`A_1 > A_2 > A_3`) spins fast (:math:`\varepsilon = \omega_0/\omega \ll 1`)
on a circular orbit under the gravity-gradient torque and a weak linear drag torque
:math:`-I\boldsymbol\omega` (constant tensor :math:`I` in body axes). The angular-momentum vector
:math:`\mathbf G` evolves slowly; the module averages over the Euler--Poinsot motion.

Model
-----
``Body(A1, A2, A3)``
    principal moments, validated (A1 > A2 > A3, triangle inequality).
``SymmetricBody(A, C)``
    a body with two equal moments (transverse A, axial C; the sphere A = C): ``averaged`` averages over
    its regular precession (slow variables G, the nutation angle theta, delta, lam).
``Drag(I)``
    drag tensor (3x3, any; symmetric part positive definite); torque :math:`-I\boldsymbol\omega`.
``Orbit(e=0.0)``
    circular (paper) or eccentric orbit (factor of (3), Kepler's law).

Euler--Poinsot motion (unperturbed)
-----------------------------------
``EulerPoinsot(body, G, k2, kind='max'|'min', sigma=1)``
    closed form in Jacobi functions: ``.omega(t)``, ``.g(t)``, ``.angles(t)`` (psi, theta, phi),
    ``.period``, ``.T``, ``.nodes(n)``, ``.average(f)``: mean over psi and the period (the averaging of
    sec. 2).
``EulerPoinsot.from_state(inertia, omega, attitude) -> FreeMotion``
    the torque-free motion of any body (two equal moments, the sphere, on the separatrix, at rest) from a
    physical state: ``.omega(t)``, ``.rotation(t)`` (a SciPy ``Rotation``), the paper's variables.
``Spacecraft(inertia, omega, attitude, orbit=KeplerOrbit(...))``
    a spacecraft's state and orbit in SI units: ``.averaged(t_span, ...)`` and ``.simulate(t_span, ...)`` with
    torques in SI units (gravity gradient, drag, magnet, constant), results in SI units
    (:class:`SpacecraftSolution`); ``.paper`` the paper's nondimensional start (:class:`PaperStart`).
``k2_from(body, G, T, kind)``, ``T_from(body, G, k2, kind)``, ``kind_of(body, G, T)``
    formula (5), its counterpart for rotation about the A3 axis, and their inverses.

Averaged system (6)-(9)
-----------------------
``chi(body, I)``, ``N_time(body, I)``
    chi and N of (7).
``dk2_dtau(body, I, k2)``, ``k2_equilibria(body, I)``
    the k^2 equation (8); its roots and their stability.
``drag_rates(body, I, G, k2)``, ``N_star(body, k2)``
    dG/dt, dT/dt and N* of (6).
``averaged_rates(body, torque, G, k2, delta, lam, nu, sigma=1, method='auto')``
    all right-hand sides of (6)/(9); for a torque object, from its parts' closed forms or the engine.
``average_torque(body, torque, G, k2, delta, lam, nu, ...) -> TorqueAverage``
    the averaging engine: the mean of any torque over psi, the elliptic phase (and the orbit for
    ``nu=None``), with its estimated quadrature error.
``precession_rate(body, G, k2, delta)``
    orbit-averaged (eps -> 0) d lambda / d tau.
``spin_ratio(body, eps, G, k2)``
    Euler--Poinsot frequency / orbital rate (validity of the averaging).
``averaged(body, torque, eps, G0=1, k2_0=0.99, delta0=pi/4, lam0=pi/4, tau_span=(0, 3), tau_eval=None, nu0=0)``
    integrate (9) in tau = eps^2 t; eps = 0 is the orbit-averaged limit. The result has ``.tau``,
    ``.G``, ``.T``, ``.k2``, ``.delta``, ``.lam`` (unwrapped), ``.nu``, ``.n``, ``.status``,
    ``.message``; with a torque object also ``.quad_error``, ``.resonances``, ``.kind``, ``.sigma``.
    Arrays for ``eps, G0, k2_0 (or T0), delta0, lam0, nu0`` (or a batch of drag tensors) give a batch of
    evolutions integrated together, with per-member statuses.

Full equations
--------------
``simulate(body, torque, eps, ..., formulation='body'|'angles', u0=0, psi0=0, sigma=1)``
    the unaveraged motion: Euler's equations and a quaternion, or the paper's (1), (3), (4). ``torque`` is
    a drag tensor (drag plus gravity gradient, the paper's case) or a torque object / callable (the whole
    perturbation). Array inputs (also ``u0``, ``psi0``) give a batch.
``initial_state(body, G0, k2_0, delta0, lam0)``
    the attitude that starts a full run on given slow variables.

Separatrix (k^2 = 1) and its crossing
-------------------------------------
``Separatrix(body, G)``
    the separatrix motions in hyperbolic functions, on the four arcs ``ARCS`` between the saddles
    (rotation about the intermediate axis) that bound the four ``REGIONS`` (kind, sigma).
``separatrix_limits(body, torque, G, delta, lam, nu)``
    limits of the averaged rates at k^2 -> 1 (the same from all regions) and their 1/K(k) approach.
``separatrix_crossing(body, torque, G, delta, lam, nu, source)``
    drifts of the energy along the arcs and the probabilities of capture into each region.
``averaged(..., branch=...)``, ``averaged_branches(...)``
    averaged runs go on through the separatrix in the chosen (by default the most probable) region, or in
    each; ``simulate`` goes through it as well.

All quantities are nondimensional in the paper's section-3 scaling (G0 = 1, A~ = A Omega0/G0,
I~ = I/(G0 eps^2), orbital rate eps, tau = eps^2 t~); see :ref:`ep-scaling`.
"""

from ._algebra import N_star, N_time, T_from, chi, dk2_dtau, drag_rates, k2_equilibria, k2_from, kind_of
from ._averaged import averaged, averaged_branches
from ._catalogue import ConstantTorque, MagneticDipole, ViscousCavity
from ._eddy import EddyCurrent
from ._engine import TorqueAverage
from ._full import initial_state
from ._geomag import IGRF13_G10, IGRF_RADIUS, DipoleField
from ._kepler import MU_EARTH, R_EARTH, KeplerOrbit
from ._model import KINDS, Body, Drag, Orbit
from ._motion import EulerPoinsot
from ._options import Solver, Stops
from ._physical import FreeMotion
from ._rates import average_torque, averaged_rates, precession_rate
from ._scstart import PaperStart
from ._separatrix import ARCS, REGIONS, Separatrix, SeparatrixCrossing, separatrix_crossing
from ._seplimits import SeparatrixLimits, separatrix_limits
from ._simulate import simulate
from ._spacecraft import Spacecraft, SpacecraftSolution
from ._spin import spin_ratio
from ._state import Mean, State
from ._symbody import SymmetricBody
from ._symrates import symmetric_rates
from ._torques import FunctionTorque, GravityGradient, LinearDrag, Torque, TorqueSum

__all__ = [
    "ARCS",
    "IGRF13_G10",
    "IGRF_RADIUS",
    "KINDS",
    "MU_EARTH",
    "REGIONS",
    "R_EARTH",
    "Body",
    "ConstantTorque",
    "DipoleField",
    "Drag",
    "EddyCurrent",
    "EulerPoinsot",
    "FreeMotion",
    "FunctionTorque",
    "GravityGradient",
    "KeplerOrbit",
    "LinearDrag",
    "MagneticDipole",
    "Mean",
    "N_star",
    "N_time",
    "Orbit",
    "PaperStart",
    "Separatrix",
    "SeparatrixCrossing",
    "SeparatrixLimits",
    "Solver",
    "Spacecraft",
    "SpacecraftSolution",
    "State",
    "Stops",
    "SymmetricBody",
    "T_from",
    "Torque",
    "TorqueAverage",
    "TorqueSum",
    "ViscousCavity",
    "average_torque",
    "averaged",
    "averaged_branches",
    "averaged_rates",
    "chi",
    "dk2_dtau",
    "drag_rates",
    "initial_state",
    "k2_equilibria",
    "k2_from",
    "kind_of",
    "precession_rate",
    "separatrix_crossing",
    "separatrix_limits",
    "simulate",
    "spin_ratio",
    "symmetric_rates",
]
