r"""How fast the body turns: the frequency of the Euler--Poinsot motion and the spin-ratio check of the averaging.

The period :math:`P = 4K/\dot u` of the motion (5) grows without bound at the separatrix; the averaged and the full
integrations compare :math:`2\pi/P` with the orbital rate (``min_spin_ratio``).
"""

from __future__ import annotations

import math

from scipy import special

from ..core.validate import real
from ._model import Body, check_body, check_kind, labelled

__all__ = ["K2_SPIN_CAP", "nutation_frequency", "spin_ratio"]


#: The rotation-speed check (``min_spin_ratio``) takes the period at ``min(k2, K2_SPIN_CAP)``: next to the
#: separatrix the period grows without bound (like ln(1/(1 - k^2))) while the body still turns fast (about the
#: intermediate axis, at rate G/A2); the momentary infinite period of a passage must not end a run. At
#: k^2 = 0.99 the period is about 2.4 times that at k = 0.
K2_SPIN_CAP = 0.99


def nutation_frequency(A: tuple[float, float, float], G: float, k2: float) -> float:
    r"""Angular frequency :math:`2\pi/P = \pi\dot u/(2K)` of the Euler--Poinsot motion (labelled moments)."""
    A1, A2, A3 = A
    mc = 1.0 - k2
    if mc <= 0.0:
        return 0.0
    R = A1 * (A2 - A3) + A3 * (A1 - A2) * k2
    rate = G * math.sqrt((A1 - A2) * (A1 - A3) * (A2 - A3) / (A1 * A2 * A3 * R))
    return math.pi * rate / (2.0 * float(special.elliprf(0.0, mc, 1.0)))


def spin_ratio(body: Body, eps: float, G: float, k2: float, kind: str = "max") -> float:
    r"""How fast the rotation is compared with the orbit: :math:`(2\pi/P)/\omega_0`.

    :math:`P = 4K/\dot u` is the period of the Euler--Poinsot motion (the slowest fast oscillation; it
    grows without bound at the separatrix) and :math:`\omega_0 = \varepsilon` in the section-3 scaling
    (dimensional use: pass :math:`\omega_0` as ``eps``). The averaging needs this ratio to be large; the
    integrators stop when it falls to ``min_spin_ratio``.

    The period follows from the closed-form Euler--Poinsot motion of section 2 with the modulus (5),
    :math:`\dot u = G\sqrt{(A_1-A_2)(A_1-A_3)(A_2-A_3)/(A_1A_2A_3R)}` (labels 1 and 3 exchanged for
    ``kind='min'``).

    Parameters
    ----------
    body : Body
    eps : float
        Orbital rate in the section-3 scaling, :math:`\tilde\omega_0 = \varepsilon` (> 0); or the
        dimensional mean motion :math:`\omega_0` with dimensional ``G`` and moments.
    G : float
        Magnitude of the angular momentum (> 0; :math:`\tilde G` in the section-3 scaling).
    k2 : float
        Modulus squared of the Euler--Poinsot motion (5), in :math:`[0, 1]`.
    kind : {'max', 'min'}
        Kind of Euler--Poinsot motion ('max' is the paper's).

    Returns
    -------
    float
        The dimensionless ratio :math:`(2\pi/P)/\omega_0` (0 at the separatrix :math:`k^2 = 1`).

    Raises
    ------
    TypeError
        If ``body`` is not a :class:`Body` or ``eps``, ``G``, ``k2`` is not a real number.
    ValueError
        If ``kind`` is unknown, ``eps <= 0``, ``G <= 0`` or ``k2`` is outside :math:`[0, 1]`.

    See Also
    --------
    EulerPoinsot : the motion whose period :math:`P` it takes.
    Stops : ``min_spin_ratio``, where an integration stops.

    Examples
    --------
    The ratio is :math:`2\pi/(P\varepsilon)` with the period of :class:`EulerPoinsot`:

    >>> import math
    >>> from rigidbody import euler_poinsot as ep
    >>> body = ep.Body(3.2, 2.6, 1.67)
    >>> P = ep.EulerPoinsot(body, 1.0, 0.5).period
    >>> print(f"{ep.spin_ratio(body, 0.1, 1.0, 0.5):.6f} {2 * math.pi / (P * 0.1):.6f}")
    1.126246 1.126246
    """
    check_body(body)
    check_kind(kind)
    eps = real(eps, "eps")
    if eps <= 0:
        raise ValueError("eps must be positive")
    G, k2 = real(G, "G"), real(k2, "k2")
    if G <= 0:
        raise ValueError(f"G must be positive, got {G}")
    if not (0.0 <= k2 <= 1.0):
        raise ValueError(f"k2 must lie in [0, 1], got {k2}")
    return nutation_frequency(labelled(body, kind), G, k2) / eps
