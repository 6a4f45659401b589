r"""The geomagnetic field along an orbit: the axial (aligned) dipole of the IGRF, in the orbital axes.

The first term of the International Geomagnetic Reference Field, :math:`V = a\,(a/r)^2g_1^0\cos\theta`, is the
field of a dipole along the Earth's axis :math:`\hat{\mathbf z}`:

.. math:: \mathbf B = g_1^0\Bigl(\frac{a}{r}\Bigr)^3\bigl(3(\hat{\mathbf z}\cdot\hat{\mathbf r})\hat{\mathbf r}
   - \hat{\mathbf z}\bigr)

(:math:`a` = 6371.2 km the IGRF reference radius; :math:`g_1^0 < 0`: the field points north at the equator). On
an orbit of inclination :math:`i` and argument of pericentre :math:`\omega`, in the orbital axes (:math:`x_1` to
the pericentre, :math:`x_3` along the normal) :math:`\hat{\mathbf r} = (\cos\nu, \sin\nu, 0)`,
:math:`\hat{\mathbf z} = (\sin\omega\sin i, \cos\omega\sin i, \cos i)` and :math:`r = p/(1 + e\cos\nu)`: a
function of the true anomaly alone, independent of the node. A *tilted* dipole (the :math:`g_1^1, h_1^1` terms,
about 9.4 degrees in 2020) turns with the Earth once a sidereal day, so its field depends on time and on the
node, not on :math:`\nu` alone; the torque protocol's field ``B(nu)`` cannot carry it, and it is left out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.validate import positive, real, returned
from ._model import Orbit, as_orbit

__all__ = ["IGRF13_G10", "IGRF_RADIUS", "DipoleField", "orbital_field"]

#: The IGRF-13 Gauss coefficient :math:`g_1^0` for the epoch 2020.0, in tesla (-29404.8 nT): P. Alken et al.,
#: "International Geomagnetic Reference Field: the thirteenth generation", Earth, Planets and Space 73, 49
#: (2021), doi:10.1186/s40623-020-01288-x.
IGRF13_G10 = -29404.8e-9

#: The IGRF reference radius (the Earth's mean radius of the model), in metres.
IGRF_RADIUS = 6371.2e3


def orbital_field(B: Any, nu: Any) -> np.ndarray:
    """The field ``B`` of a torque (3 components, or a function ``B(nu) -> (..., 3)`` whose output is checked and
    named in the messages) at the true anomaly ``nu``: shape ``(..., 3)`` in the orbital axes."""
    if callable(B):
        shape = (*np.shape(nu), 3)
        out = returned(B(nu), B, shape, role="the field B")
        return out if out.shape == shape else np.broadcast_to(out, shape)
    return np.zeros((*np.shape(nu), 3)) + B


@dataclass(frozen=True)
class DipoleField:
    r"""The axial dipole of the geomagnetic field along an orbit, in the orbital axes: a field ``B(nu)``.

    .. math:: \mathbf B(\nu) = s\,g_1^0\Bigl(\frac{a_E}{r}\Bigr)^3\bigl(3\sin i\sin(\omega+\nu)\,
       \hat{\mathbf r} - \hat{\mathbf z}\bigr),\qquad r = \frac{a(1-e^2)}{1+e\cos\nu},

    with :math:`\hat{\mathbf r} = (\cos\nu, \sin\nu, 0)`, :math:`\hat{\mathbf z} = (\sin\omega\sin i,
    \cos\omega\sin i, \cos i)` the Earth's axis in the orbital axes (:math:`x_1` to the pericentre,
    :math:`x_3` along the orbit normal) and :math:`s` = ``scale``. The dipole's tilt is left out (it turns with
    the Earth, so its field is not a function of :math:`\nu` alone: :doc:`/euler_poinsot`, "Eddy currents").

    Parameters
    ----------
    inclination : float
        The orbit's inclination :math:`i` to the equator, radians.
    argp : float
        The argument of pericentre :math:`\omega`, radians (on a circular orbit: where :math:`\nu` is counted
        from, measured from the ascending node).
    a : float
        The semi-major axis, metres.
    orbit : Orbit, optional
        The orbit (its eccentricity; default circular).
    g10 : float
        The Gauss coefficient :math:`g_1^0` in tesla (default :data:`IGRF13_G10`, IGRF-13 for 2020.0).
    radius : float
        The model's reference radius :math:`a_E` in metres (default :data:`IGRF_RADIUS`).
    scale : float
        A factor applied to the field in tesla: 1 for tesla, ``1e9`` for nanotesla, ``1/B_ref`` for a field in
        units of :math:`B_{ref}` (the units :class:`EddyCurrent`'s tensor is given in).

    See Also
    --------
    EddyCurrent : the torque it is a field for.
    MagneticDipole : a permanent magnet in a field.

    References
    ----------
    :ref:`P. Alken et al. (2021) <ref-igrf13>` (IGRF-13).

    Examples
    --------
    On a polar circular orbit at the reference radius the field over the north pole (:math:`\nu = \pi/2` with
    :math:`\omega = 0`, where :math:`\hat{\mathbf r} = \hat{\mathbf z} = \mathbf x_2`) is
    :math:`2g_1^0\hat{\mathbf r}`, pointing down into the Earth, and at the equator :math:`-g_1^0\hat{\mathbf z}`,
    pointing north:

    >>> import math
    >>> from rigidbody import euler_poinsot as ep
    >>> f = ep.DipoleField(math.pi / 2, 0.0, ep.IGRF_RADIUS, scale=1e9)
    >>> print([round(float(x), 1) + 0.0 for x in f(math.pi / 2)], [round(float(x), 1) + 0.0 for x in f(0.0)])
    [0.0, -58809.6, 0.0] [0.0, 29404.8, 0.0]
    """

    inclination: float
    argp: float
    a: float
    orbit: Orbit | None = None
    g10: float = IGRF13_G10
    radius: float = IGRF_RADIUS
    scale: float = 1.0

    def __post_init__(self) -> None:
        i = real(self.inclination, "inclination")
        if not 0.0 <= i <= math.pi:
            raise ValueError(f"inclination must lie in [0, pi] (radians), got {i!r}")
        object.__setattr__(self, "inclination", i)
        object.__setattr__(self, "argp", real(self.argp, "argp"))
        object.__setattr__(self, "orbit", as_orbit(self.orbit))
        object.__setattr__(self, "g10", real(self.g10, "g10"))
        for name in ("a", "radius", "scale"):
            object.__setattr__(self, name, positive(getattr(self, name), name))
        e = self.orbit.e  # type: ignore[union-attr]  # an Orbit after as_orbit
        if self.a * (1.0 - e) < self.radius:
            raise ValueError(f"the orbit's pericentre a (1 - e) = {self.a * (1 - e):.6g} m lies inside the reference "
                             f"radius {self.radius:.6g} m (a is in metres)")

    @property
    def axis(self) -> np.ndarray:
        """The Earth's axis :math:`\\hat{\\mathbf z}` in the orbital axes.

        Examples
        --------
        On an equatorial orbit the axis is the orbit normal; on a polar orbit with the pericentre at the node
        it lies in the orbit's plane, a quarter turn from the pericentre:

        >>> import math
        >>> from rigidbody import euler_poinsot as ep
        >>> [round(float(x), 12) + 0.0 for x in ep.DipoleField(0.0, 0.0, 7e6).axis]
        [0.0, 0.0, 1.0]
        >>> [round(float(x), 12) + 0.0 for x in ep.DipoleField(math.pi / 2, 0.0, 7e6).axis]
        [0.0, 1.0, 0.0]
        """
        si = math.sin(self.inclination)
        return np.array([math.sin(self.argp) * si, math.cos(self.argp) * si, math.cos(self.inclination)])

    def __call__(self, nu: Any) -> np.ndarray:
        nu = np.asarray(nu, dtype=float)
        e = self.orbit.e  # type: ignore[union-attr]  # an Orbit after as_orbit
        ratio = self.radius * (1.0 + e * np.cos(nu)) / (self.a * (1.0 - e * e))  # a_E / r
        z = self.axis
        r = np.stack([np.cos(nu), np.sin(nu), np.zeros_like(nu)], axis=-1)
        zr = (r @ z)[..., None]
        return (self.scale * self.g10 * ratio**3)[..., None] * (3.0 * zr * r - z)
