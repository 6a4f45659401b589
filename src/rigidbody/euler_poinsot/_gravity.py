"""The drag-plus-gravity-gradient torque written out once, on floats or on arrays alike.

The paper's perturbation (3), in the module's scaling: :math:`\\mathbf M = 3f(\\nu)\\,\\boldsymbol\\rho\\times
(A\\boldsymbol\\rho) - I\\boldsymbol\\omega` in body axes, with :math:`\\boldsymbol\\rho` the unit radius vector in
body axes, :math:`A` the principal moments, :math:`I` the drag tensor and :math:`f` the orbit factor. The full
equations (one run on floats, a batch on arrays, the body form and the angles form) and the
:class:`~rigidbody.euler_poinsot.GravityGradient` torque object evaluate it here, so the formula has one home.
Only arithmetic is used: each argument may be a float or an array (all of one shape, or broadcasting).
"""

from __future__ import annotations

from typing import Any

__all__ = ["drag_gravity", "radius_in_body"]


def radius_in_body(w: Any, x: Any, y: Any, z: Any, cn: Any, sn: Any) -> tuple[Any, Any, Any]:
    """Body components of the unit radius vector :math:`(\\cos\\nu, \\sin\\nu, 0)` of the orbital axes, for the
    attitude quaternion ``(w, x, y, z)`` (unit, body -> orbital axes: ``C = dcm_from_unit_quat``) and
    ``cn, sn = cos nu, sin nu``: :math:`C^T\\mathbf e_r`."""
    r1 = (1 - 2 * (y * y + z * z)) * cn + 2 * (x * y + w * z) * sn
    r2 = 2 * (x * y - w * z) * cn + (1 - 2 * (x * x + z * z)) * sn
    r3 = 2 * (x * z + w * y) * cn + 2 * (y * z - w * x) * sn
    return r1, r2, r3


def drag_gravity(A: tuple[float, float, float], f3: Any, r: tuple[Any, Any, Any],
                 drag: tuple[tuple[float, ...], ...] | None = None, o: tuple[Any, Any, Any] | None = None
                 ) -> tuple[Any, Any, Any]:
    """Body components of :math:`f_3\\,\\boldsymbol\\rho\\times(A\\boldsymbol\\rho) - I\\boldsymbol\\omega`
    (:math:`f_3 = 3f(\\nu)` times the squared orbital rate in the torque's units; ``drag`` the rows of :math:`I`
    and ``o`` the body angular velocity, both omitted for the gravity gradient alone)."""
    A1, A2, A3 = A
    r1, r2, r3 = r
    L1, L2, L3 = f3 * (A3 - A2) * r2 * r3, f3 * (A1 - A3) * r3 * r1, f3 * (A2 - A1) * r1 * r2
    if drag is None or o is None:
        return L1, L2, L3
    (I11, I12, I13), (I21, I22, I23), (I31, I32, I33) = drag
    o1, o2, o3 = o
    return (L1 - (I11 * o1 + I12 * o2 + I13 * o3), L2 - (I21 * o1 + I22 * o2 + I23 * o3),
            L3 - (I31 * o1 + I32 * o2 + I33 * o3))
