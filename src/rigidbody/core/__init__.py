"""Shared mathematics of the four analyses.

:mod:`rigidbody.core.elliptic`
    Jacobi elliptic functions and elliptic integrals in the papers' modulus ``k``.
:mod:`rigidbody.core.euler`
    3-1-3 Euler angles, direction cosines, quaternions, kinematic equations.
:mod:`rigidbody.core.averaging`
    Spectrally convergent period averages over motions written in Jacobi functions.
:mod:`rigidbody.core.ode`
    ``solve_ivp`` wrapper returning named trajectories with a clear status, or DOP853 on Python floats for
    small systems; the :class:`~.ode.Solution` result, for one run or a batch.
:mod:`rigidbody.core.batch`
    Many independent systems integrated together (vectorised DOP853 with per-member step control,
    events and status).
:mod:`rigidbody.core.piecewise`
    One driver for runs made of pieces (modes, terminal events that continue in another mode): members grouped
    by mode, a group of one on the scalar integrator, a larger group on the vectorised one.
:mod:`rigidbody.core.dop853`
    The numerics both integrators share: the DOP853 coefficients, error norm, step-size controller,
    initial step and event rules.
:mod:`rigidbody.core.kernel`
    One formula for a single run and a batch: ``math``/NumPy namespaces for right-hand sides, elliptic
    means (``<sn^2>``, ``E/K``) by the AGM without cancellation.
:mod:`rigidbody.core.quadform`
    Quadratic forms: inertia-preserving scaling, leading minors, inertia (degree of instability),
    constrained (null-space) forms, finite-difference Hessians, complex-step gradients.
:mod:`rigidbody.core.validate`
    Validation of scalar user input (clear ``TypeError``/``ValueError`` naming the parameter).
"""

from . import averaging, batch, dop853, elliptic, euler, kernel, ode, piecewise, quadform, validate

__all__ = ["averaging", "batch", "dop853", "elliptic", "euler", "kernel", "ode", "piecewise", "quadform", "validate"]
