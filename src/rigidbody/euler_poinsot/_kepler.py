r"""An orbit in SI units for :class:`Spacecraft`: the semi-major axis (or altitude) and the gravitational
parameter, or the mean motion; the eccentricity, the true anomaly at the start, and the orbit's orientation in an
inertial frame.

The paper's orbital axes :math:`Ox_i` (the *perifocal* frame: :math:`x_1` to the pericentre, :math:`x_3` along
the orbit normal, :math:`x_2` along the velocity at the pericentre) are the frame of :class:`Orbit` and of the
torques; ``orientation`` maps them to the user's inertial frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ..core.validate import positive, real
from ._model import Orbit

__all__ = ["MU_EARTH", "R_EARTH", "KeplerOrbit"]

#: The Earth's gravitational parameter :math:`GM_\oplus` in m^3/s^2: IERS Conventions (2010), IERS Technical
#: Note 36, Table 1.1 (TT-compatible value; the same number defines WGS 84 with EGM96).
MU_EARTH = 3.986004418e14

#: The Earth's equatorial radius in m: the semi-major axis of the WGS 84 ellipsoid (NIMA TR8350.2).
R_EARTH = 6378137.0


@dataclass(frozen=True, eq=False)
class KeplerOrbit:
    r"""The orbit of a spacecraft's centre of mass, in SI units.

    Give exactly one of ``radius``, ``altitude``, ``mean_motion``. The gravity-gradient torque depends on the
    orbit only through the mean motion :math:`n = \sqrt{\mu/a^3}`, the eccentricity and the true anomaly.

    Parameters
    ----------
    radius : float, optional
        The semi-major axis :math:`a` in m (the radius of a circular orbit).
    altitude : float, optional
        :math:`a - R_\oplus` in m, :math:`R_\oplus` = ``R_EARTH`` (WGS 84 equatorial radius): the altitude of a
        circular orbit above the equator.
    mean_motion : float, optional
        :math:`n` in rad/s (then ``mu`` is not used).
    mu : float
        The gravitational parameter in m^3/s^2; default ``MU_EARTH`` = 3.986004418e14 (IERS Conventions 2010,
        WGS 84).
    e : float
        Eccentricity in [0, 1).
    nu0 : float
        True anomaly at ``t = 0`` (rad), from the pericentre (on a circular orbit: from the axis :math:`x_1`).
    orientation : scipy.spatial.transform.Rotation, optional
        The orbital axes :math:`Ox_i` (:math:`x_1` to the pericentre, :math:`x_3` the orbit normal) -> the
        user's inertial frame, e.g. ``Rotation.from_euler('ZXZ', [raan, inclination, arg_perigee])`` for an
        Earth-centred inertial frame. Default: the inertial frame *is* :math:`Ox_i`.

    Attributes
    ----------
    n : float
        The mean motion in rad/s.
    period : float
        :math:`2\pi/n` in s.

    See Also
    --------
    Orbit : the paper's nondimensional orbit (eccentricity only).
    Spacecraft : the state and orbit a run starts from.

    Examples
    --------
    The International Space Station's orbit, 400 km up, goes round in 92.6 minutes:

    >>> from rigidbody.euler_poinsot import KeplerOrbit
    >>> orbit = KeplerOrbit(altitude=400e3)
    >>> print(f"{orbit.period / 60:.1f} min, n = {orbit.n:.4e} rad/s")
    92.6 min, n = 1.1314e-03 rad/s
    """

    radius: float | None = None
    altitude: float | None = None
    mean_motion: float | None = None
    mu: float = MU_EARTH
    e: float = 0.0
    nu0: float = 0.0
    orientation: Rotation | None = None

    def __post_init__(self) -> None:
        given = [name for name in ("radius", "altitude", "mean_motion") if getattr(self, name) is not None]
        if len(given) != 1:
            raise ValueError("KeplerOrbit needs exactly one of radius (semi-major axis, m), altitude (m above "
                             f"R_EARTH) or mean_motion (rad/s), got {given or 'none'}")
        mu = positive(self.mu, "mu")
        if self.mean_motion is not None:
            n = positive(self.mean_motion, "mean_motion")
        else:
            a = (positive(self.radius, "radius") if self.radius is not None
                 else R_EARTH + positive(self.altitude, "altitude"))
            n = math.sqrt(mu / a**3)
        object.__setattr__(self, "n", n)
        object.__setattr__(self, "mu", mu)
        object.__setattr__(self, "nu0", real(self.nu0, "nu0"))
        object.__setattr__(self, "paper", Orbit(e=self.e))  # validates e
        object.__setattr__(self, "e", self.paper.e)
        R = self.orientation
        if R is not None and not (isinstance(R, Rotation) and R.single):
            raise TypeError(f"orientation must be a single scipy Rotation (orbital axes -> inertial), got {R!r}")

    n: float = field(init=False)
    paper: Orbit = field(init=False, repr=False)  # the paper's Orbit(e)

    @property
    def period(self) -> float:
        r"""The orbital period :math:`2\pi/n` in s.

        Examples
        --------
        Kepler's third law: the geostationary radius, 42164 km, gives one sidereal day (86164 s):

        >>> from rigidbody.euler_poinsot import KeplerOrbit
        >>> print(f"{KeplerOrbit(radius=42164.17e3).period:.0f} s")
        86164 s
        """
        return 2.0 * math.pi / self.n

    def to_inertial(self) -> Rotation:
        """The rotation :math:`Ox_i` -> inertial (the identity without ``orientation``).

        Examples
        --------
        On an orbit of inclination 90 degrees with its ascending node on the inertial x axis the orbit normal
        is :math:`-y`:

        >>> from scipy.spatial.transform import Rotation
        >>> from rigidbody.euler_poinsot import KeplerOrbit
        >>> polar = Rotation.from_euler("ZXZ", [0.0, 90.0, 0.0], degrees=True)
        >>> orbit = KeplerOrbit(altitude=500e3, orientation=polar)
        >>> print([f"{x:+.3f}" for x in orbit.to_inertial().apply([0.0, 0.0, 1.0])])
        ['+0.000', '-1.000', '+0.000']
        """
        return Rotation.identity() if self.orientation is None else self.orientation

    def true_anomaly(self, t: Any) -> np.ndarray:
        r"""The true anomaly (rad, continuous) at times ``t`` (s) after the start, from Kepler's equation
        :math:`E - e\sin E = M_0 + nt` (Newton's method; :math:`\nu = \nu_0 + nt` on a circular orbit).

        Examples
        --------
        From the pericentre, half a period later the body is at the apocentre, one period later back at the
        pericentre, one turn on:

        >>> import math
        >>> from rigidbody.euler_poinsot import KeplerOrbit
        >>> orbit = KeplerOrbit(mean_motion=1e-3, e=0.3)
        >>> print([f"{nu / math.pi:.12f}" for nu in orbit.true_anomaly([0.0, orbit.period / 2, orbit.period])])
        ['0.000000000000', '1.000000000000', '2.000000000000']
        """
        t = np.asarray(t, dtype=float)
        e, nu0 = self.e, self.nu0
        if e == 0.0:
            return nu0 + self.n * t
        b = e / (1.0 + math.sqrt(1.0 - e * e))  # nu = E + 2 atan2(b sin E, 1 - b cos E), continuous in E
        E0 = nu0 - 2.0 * math.atan2(b * math.sin(nu0), 1.0 + b * math.cos(nu0))
        M = E0 - e * math.sin(E0) + self.n * t
        E = M + e * np.sin(M)
        for _ in range(60):
            step = (E - e * np.sin(E) - M) / (1.0 - e * np.cos(E))
            E = E - step
            if np.all(np.abs(step) <= 4e-16 * np.maximum(1.0, np.abs(E))):
                break
        return np.asarray(E + 2.0 * np.arctan2(b * np.sin(E), 1.0 - b * np.cos(E)))

    def field_in_orbit_axes(self, B: Any) -> Any:
        r"""A field given in the inertial frame (3 components, or a function of the true anomaly returning
        ``(..., 3)``) in the orbital axes :math:`Ox_i`, as :class:`MagneticDipole` takes it (unchanged without
        ``orientation``; a function's result of another shape is passed on for :class:`MagneticDipole` to
        refuse).

        Examples
        --------
        A field along the inertial :math:`z` axis on an orbit inclined by 30 degrees: in the orbital axes it has
        :math:`\cos 30^\circ` along the orbit normal:

        >>> from scipy.spatial.transform import Rotation
        >>> from rigidbody.euler_poinsot import KeplerOrbit
        >>> inclined = Rotation.from_euler("ZXZ", [0.0, 30.0, 0.0], degrees=True)
        >>> orbit = KeplerOrbit(altitude=500e3, orientation=inclined)
        >>> print([f"{b:+.6f}" for b in orbit.field_in_orbit_axes([0.0, 0.0, 1.0])])
        ['+0.000000', '+0.500000', '+0.866025']
        """
        if self.orientation is None:
            return B
        back = self.orientation.inv().as_matrix()
        if callable(B):
            def in_orbit_axes(nu: Any) -> Any:
                b = B(nu)
                arr = np.asarray(b)
                return arr @ back.T if arr.dtype.kind in "fiu" and arr.shape[-1:] == (3,) else b

            in_orbit_axes.__qualname__ = f"{getattr(B, '__qualname__', repr(B))} (turned to the orbital axes)"
            return in_orbit_axes
        return back @ np.asarray(B, dtype=float)
