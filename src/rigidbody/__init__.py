"""rigidbody — rigid-body attitude dynamics after four classic papers.

Modules
-------
rigidbody.core
    Shared mathematics: Jacobi elliptic functions and integrals in the modulus ``k``
    (:mod:`rigidbody.core.elliptic`), 3-1-3 Euler angles, direction cosines and quaternions
    (:mod:`rigidbody.core.euler`), period averaging (:mod:`rigidbody.core.averaging`) and an ODE
    wrapper returning named trajectories (:mod:`rigidbody.core.ode`).
rigidbody.gyrostat
    Stationary motions of a gyrostat satellite and their stability by Routh's method (Stepanov 1968).
rigidbody.lagrange
    Perturbed motions of a heavy top close to the Lagrange case, averaging in (u1, u2, u3)
    (Akulenko, Leshchenko, Chernousko 1979).
rigidbody.euler_poinsot
    Fast rotation of a satellite under gravity-gradient and drag torques, averaging over the
    Euler--Poinsot motion (Rachinskaya).
rigidbody.viscous
    Axisymmetric body in a linearly viscous medium: quasi-coordinates and curvature spirals (Krivtsov 2000).

Submodules are imported on demand: ``from rigidbody import lagrange``.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("rigidbody")
except PackageNotFoundError:  # pragma: no cover - running from a source tree without installation
    __version__ = "0.0.0+unknown"

__all__ = ["__version__"]
