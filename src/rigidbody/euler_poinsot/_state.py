"""The slow state of the averaged system at one time (body, kind and sense of motion, G, k^2, n, true anomaly) and
the averaged effect of a torque there, as values; the frame attached to G and the amplitudes of the motion."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._model import AXES, Body, Orbit, labelled

__all__ = ["Mean", "State", "amplitudes", "frame"]


@dataclass
class State:
    r"""One slow state: the body, the kind of motion and its sense, G, k^2, n and the true anomaly.

    What a torque's :meth:`Torque.closed_mean` receives.

    Parameters
    ----------
    body : Body
        The body.
    kind : {'max', 'min'}
        Rotation about the axis of the largest (``'max'``) or the smallest moment (``'min'``).
    sigma : {1, -1}
        The sense of the motion.
    G : float
        The magnitude of the angular momentum.
    k2 : float
        The squared modulus of the Jacobi functions of the motion, in [0, 1).
    n : numpy.ndarray
        The unit vector of :math:`\mathbf G` in the orbital axes, shape (3,).
    nu : float or None
        The true anomaly, held during the average; None in the orbit-averaged limit (the average is also over
        the orbit).
    orbit : Orbit
        The orbit.
    mc : float, optional
        :math:`1 - k^2` (given where it is known more precisely than ``1 - k2``, next to the separatrix).

    Attributes
    ----------
    a : tuple of float
        The moments in the order of the ``'max'``-kind formulas: ``(A1, A2, A3)``, ``(A3, A2, A1)`` for ``'min'``.
    lab : tuple of int
        The body axes in that order.
    Q, T : float
        :math:`G^2 - 2Ta_3` and the kinetic energy :math:`T` of the motion.

    See Also
    --------
    Mean : what a torque's ``closed_mean`` returns at a State.
    Torque : the protocol whose ``closed_mean`` takes a State.
    EulerPoinsot : the torque-free motion a State stands for.
    """

    body: Body
    kind: str
    sigma: int
    G: float
    k2: float
    n: np.ndarray
    nu: float | None
    orbit: Orbit
    mc: float = field(default=-1.0)

    def __post_init__(self) -> None:
        if self.mc < 0.0:
            self.mc = 1.0 - self.k2
        self.lab = AXES[self.kind]
        self.a: tuple[float, float, float] = labelled(self.body, self.kind)

    @property
    def Q(self) -> float:
        r""":math:`G^2 - 2Ta_3` (:math:`a_3` the moment of the axis of the least moment for ``'max'``).

        Examples
        --------
        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> st = ep.State(ep.Body(3.2, 2.6, 1.67), "max", 1, 1.0, 0.5, np.array([0.0, 0.0, 1.0]), None, ep.Orbit())
        >>> print(f"{st.Q:.9f} {st.G**2 - 2 * st.T * 1.67:.9f}")
        0.409232097 0.409232097
        """
        a1, a2, a3 = self.a
        R = a1 * (a2 - a3) + a3 * (a1 - a2) * self.k2
        return self.G**2 * (a1 - a3) * (a2 - a3) / R

    @property
    def T(self) -> float:
        """The kinetic energy of the motion, the inverse of (5).

        Examples
        --------
        The energy of the Euler--Poinsot motion with the same ``G`` and ``k2``:

        >>> import numpy as np
        >>> from rigidbody import euler_poinsot as ep
        >>> st = ep.State(ep.Body(3.2, 2.6, 1.67), "max", 1, 1.0, 0.5, np.array([0.0, 0.0, 1.0]), None, ep.Orbit())
        >>> print(f"{st.T:.9f} {ep.EulerPoinsot(st.body, 1.0, 0.5).T:.9f}")
        0.176876618 0.176876618
        """
        a1, a2, a3 = self.a
        return 0.5 * self.G**2 * (a2 - a3 + (a1 - a2) * self.k2) / (a1 * (a2 - a3) + a3 * (a1 - a2) * self.k2)


@dataclass
class Mean:
    r"""Averaged effect of a torque: L = <C M> (orbital axes), dT, dk2; linear in the torque (``a + b`` adds).

    What a torque's :meth:`Torque.closed_mean` returns.

    Parameters
    ----------
    L : numpy.ndarray
        The mean torque :math:`\langle C\mathbf M\rangle` in the orbital axes, shape (3,):
        :math:`d(G\mathbf n)/d\tau`.
    dT : float
        :math:`\langle\boldsymbol\omega\cdot\mathbf M\rangle = dT/d\tau`.
    dk2 : float
        :math:`dk^2/d\tau`.

    See Also
    --------
    State : the slow state at which a mean is taken.
    Torque : the protocol whose ``closed_mean`` returns a Mean.
    TorqueAverage : the engine's average, with its quadrature error.
    """

    L: np.ndarray
    dT: float
    dk2: float

    def __add__(self, other: Mean) -> Mean:
        return Mean(self.L + other.L, self.dT + other.dT, self.dk2 + other.dk2)


def frame(n: np.ndarray) -> np.ndarray:
    """An orthonormal frame (columns y1, y2, y3 = n); y2 in the orbit plane (the paper's Oy) off the poles."""
    n1, n2, n3 = (float(x) for x in n)
    r = math.sqrt(n1 * n1 + n2 * n2 + n3 * n3)
    n1, n2, n3 = n1 / r, n2 / r, n3 / r
    h = math.hypot(n1, n2)
    c, s = (n1 / h, n2 / h) if h > 1e-300 else (1.0, 0.0)
    # y2 = (-sin lam, cos lam, 0), y1 = y2 x n = (cos delta cos lam, cos delta sin lam, -sin delta)
    return np.array([[n3 * c, -s, n1], [n3 * s, c, n2], [-h, 0.0, n3]])


def amplitudes(st: State) -> tuple[float, float, float]:
    r"""The amplitudes of the Euler--Poinsot motion in the labelled axes (sec. 2):
    :math:`\omega = (\sigma c_{dn}\operatorname{dn}, -\sigma k c_{sn}\operatorname{sn}, k c_{cn}\operatorname{cn})`."""
    a1, a2, a3 = st.a
    R = a1 * (a2 - a3) + a3 * (a1 - a2) * st.k2
    G = st.G
    return (G * math.sqrt((a2 - a3) / (a1 * R)), G * math.sqrt((a1 - a3) / (a2 * R)),
            G * math.sqrt((a1 - a2) / (a3 * R)))
