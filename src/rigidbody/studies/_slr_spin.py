r"""Observed spin-down of passive laser-ranged satellites against the averaged eddy-current torque.

A conducting sphere spinning fast in the geomagnetic field loses the spin across the field: with the magnetic
tensor :math:`P = pI` and the moment of inertia :math:`A`, the orbit- and spin-averaged evolution of the angular
momentum is linear (:class:`rigidbody.euler_poinsot.EddyCurrent`, :doc:`/euler_poinsot`, "Eddy currents"),

.. math:: \frac{d\mathbf G}{dt} = -\frac pA\bigl(\operatorname{tr}\bar S - \bar S\bigr)\mathbf G,\qquad
   \bar S = \langle\mathbf B\mathbf B^{\mathsf T}\rangle_{\rm orbit},

so the spin period grows as an exponential whose rate depends on the direction of :math:`\mathbf G`: between
:math:`(p/A)(\operatorname{tr}\bar S - s_{\max})` and :math:`(p/A)(\operatorname{tr}\bar S - s_{\min})` for the
eigenvalues :math:`s` of :math:`\bar S`, and :math:`\tfrac23(p/A)\operatorname{tr}\bar S` averaged over directions.

The cases are the two satellites whose laser-ranging spin periods were published as exponential fits with their
orbits and masses (:data:`LARETS`, :data:`STELLA`). Their conducting structure (the conductivity and geometry
that give :math:`p`) and their spin axes are not in those sources, so :math:`p/A` is *fitted*
(:func:`fitted_eddy_rate`: the direction-averaged rate equals the observed one) and the prediction is the spread
over the spin axis and the conductivity the fitted value implies (:func:`equivalent_conductivity`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import euler_poinsot as ep
from ..core.validate import finite_array, positive, real

__all__ = ["LARETS", "SECONDS_PER_DAY", "STELLA", "SpinDecayCase", "decay_time_ratio", "equivalent_conductivity",
           "field_axes", "fitted_eddy_rate", "observed_period", "predicted_period"]

#: seconds in a day (the published fits count days since launch)
SECONDS_PER_DAY = 86400.0


@dataclass(frozen=True)
class SpinDecayCase:
    r"""A passive spherical satellite: its published mass, size, orbit and exponential fit of the spin period.

    The fit is :math:`T(D) = T_0\exp(kD)` with :math:`D` in days since launch.

    Parameters
    ----------
    name : str
        The satellite.
    launch : str
        The launch date (ISO 8601): :math:`D = 0` of the fit.
    mass : float
        kg.
    radius : float
        The sphere's radius, m.
    a : float
        The orbit's semi-major axis, m.
    e : float
        The orbit's eccentricity.
    inclination : float
        The orbit's inclination to the equator, rad.
    period0 : float
        :math:`T_0`, the fit's spin period at launch, s.
    rate : float
        :math:`k`, the fit's exponent, 1/day.
    sources : str
        Where each number comes from.

    Raises
    ------
    TypeError, ValueError
        A number that is not real, positive (``mass``, ``radius``, ``a``, ``period0``, ``rate``), or an
        eccentricity outside [0, 1) or an inclination outside [0, pi].

    See Also
    --------
    LARETS, STELLA : the published cases.
    predicted_period, observed_period : the model's and the fit's period histories.

    Examples
    --------
    The period of Larets grows by :math:`e` in :math:`1/k` = 50.7 days:

    >>> from rigidbody.studies import LARETS
    >>> print(f"{LARETS.decay_time / 86400:.2f} days")
    50.74 days
    """

    name: str
    launch: str
    mass: float
    radius: float
    a: float
    e: float
    inclination: float
    period0: float
    rate: float
    sources: str

    def __post_init__(self) -> None:
        for name in ("mass", "radius", "a", "period0", "rate"):
            object.__setattr__(self, name, positive(getattr(self, name), name))
        e, i = real(self.e, "e"), real(self.inclination, "inclination")
        if not 0.0 <= e < 1.0:
            raise ValueError(f"e must lie in [0, 1), got {e!r}")
        if not 0.0 <= i <= math.pi:
            raise ValueError(f"inclination must lie in [0, pi] (radians), got {i!r}")
        object.__setattr__(self, "e", e)
        object.__setattr__(self, "inclination", i)

    @property
    def decay_time(self) -> float:
        """The observed e-folding time of the spin period, :math:`1/k`, in s.

        Examples
        --------
        >>> from rigidbody.studies import STELLA
        >>> print(f"{STELLA.decay_time:.6g} s")
        2.00356e+07 s
        """
        return SECONDS_PER_DAY / self.rate

    @property
    def orbit(self) -> ep.KeplerOrbit:
        """The orbit (SI units; the inertial frame is the orbital axes).

        Examples
        --------
        >>> from rigidbody.studies import LARETS
        >>> print(f"{LARETS.orbit.period / 60:.1f} min")
        98.6 min
        """
        return ep.KeplerOrbit(radius=self.a, e=self.e)

    @property
    def field(self) -> ep.DipoleField:
        """The axial dipole (IGRF-13) along the orbit, in tesla; the pericentre at the ascending node (the orbits
        are nearly circular: the argument of pericentre only turns :math:`\\bar S` about the orbit normal).

        Examples
        --------
        The field over the ascending node, pointing north (along the Earth's axis), tens of microtesla:

        >>> from rigidbody.studies import LARETS
        >>> B = LARETS.field(0.0)
        >>> print(f"{B @ LARETS.field.axis * 1e6:.2f} uT")
        21.54 uT
        """
        return ep.DipoleField(self.inclination, 0.0, self.a, orbit=ep.Orbit(self.e))


#: Larets (2003-042F). Mass 23.28 kg, diameter 24 cm, inclination 98.204 deg, eccentricity 0.0002, altitude
#: 691 km (taken above the equatorial radius :data:`rigidbody.euler_poinsot.R_EARTH`), launch 2003-09-27: ILRS
#: mission page "Larets". Spin fit T = 0.860499 exp(0.0197066 D) s: D. Kucharski, H.-C. Lim, G. Kirchner,
#: F. Koidl, "Spin parameters of Low Earth Orbiting satellites Larets and Stella determined from Satellite Laser
#: Ranging data", Adv. Space Res. 53(1), 90-96 (2014), doi:10.1016/j.asr.2013.10.020 (abstract).
LARETS = SpinDecayCase(
    "Larets", "2003-09-27", 23.28, 0.12, ep.R_EARTH + 691e3, 0.0002, math.radians(98.204), 0.860499, 0.0197066,
    "ILRS mission page (mass, diameter, orbit); Kucharski et al., Adv. Space Res. 53, 90 (2014) (spin fit)")

#: Stella (1993-061B). Mass 48 kg, diameter 24 cm, inclination 98.6 deg, eccentricity 0.0007567, perigee 800 km
#: (above :data:`rigidbody.euler_poinsot.R_EARTH`), launch 1993-09-26: ILRS mission page "Starlette and Stella".
#: Spin fit T = 13.5582 exp(0.00431232 D) s: Kucharski et al. (2014), as for :data:`LARETS`.
STELLA = SpinDecayCase(
    "Stella", "1993-09-26", 48.0, 0.12, (ep.R_EARTH + 800e3) / (1.0 - 0.0007567), 0.0007567, math.radians(98.6),
    13.5582, 0.00431232,
    "ILRS mission page (mass, diameter, orbit); Kucharski et al., Adv. Space Res. 53, 90 (2014) (spin fit)")


def observed_period(case: SpinDecayCase, days: Any) -> np.ndarray:
    r"""The published fit of the spin period, :math:`T_0\exp(kD)`, in s at ``days`` since launch.

    See Also
    --------
    predicted_period : the model's.

    Examples
    --------
    >>> from rigidbody.studies import STELLA, observed_period
    >>> print(observed_period(STELLA, [0.0, 1.0 / STELLA.rate]).round(4).tolist())
    [13.5582, 36.855]
    """
    return case.period0 * np.exp(case.rate * finite_array(days, "days"))


def field_axes(case: SpinDecayCase) -> tuple[np.ndarray, np.ndarray]:
    r"""The eigenvalues (ascending, T^2) and eigenvectors (columns, orbital axes) of :math:`\bar S`, the mean of
    :math:`\mathbf B\mathbf B^{\mathsf T}` over the orbit in time.

    A spin along the eigenvector of :math:`s_k` decays at :math:`(p/A)(\operatorname{tr}\bar S - s_k)`, a pure
    exponential: the first column (the weakest mean field, near the orbit normal for a polar orbit) is the fastest.

    See Also
    --------
    rigidbody.euler_poinsot.EddyCurrent.field_square : the mean it diagonalises.

    Examples
    --------
    On a near-polar orbit the dipole's field lies nearly in the orbit's plane:

    >>> from rigidbody.studies import LARETS, field_axes
    >>> s, V = field_axes(LARETS)
    >>> print(f"{s[0] / s.sum():.4f}", f"{abs(V[2, 0]):.4f}")
    0.0067 0.9986
    """
    S = ep.EddyCurrent(1.0, case.field).field_square(None, case.e)
    s, V = np.linalg.eigh(S)
    return s, V


def fitted_eddy_rate(case: SpinDecayCase) -> float:
    r"""The *fitted* :math:`p/A` (1/(s T^2)): the direction-averaged decay rate
    :math:`\tfrac23(p/A)\operatorname{tr}\bar S` equals the observed :math:`k`.

    The magnetic tensor :math:`p` is not in the published sources of :data:`LARETS` and :data:`STELLA` (nor are
    the conductivity and geometry it is computed from), and neither is the spin axis: this is the one constant
    fitted to the observation.

    See Also
    --------
    equivalent_conductivity : what it means as a material property.

    Examples
    --------
    >>> from rigidbody.studies import LARETS, STELLA, fitted_eddy_rate
    >>> print(f"{fitted_eddy_rate(LARETS):.0f} {fitted_eddy_rate(STELLA):.1f}")
    299 72.1
    """
    s, _ = field_axes(case)
    return 1.5 * case.rate / SECONDS_PER_DAY / float(s.sum())


def equivalent_conductivity(case: SpinDecayCase, p_over_A: float) -> float:
    r"""The conductivity (S/m) of a homogeneous solid sphere of the satellite's mass and radius with this
    :math:`p/A`.

    A solid sphere has :math:`p = 2\pi\sigma r^5/15` (Gómez & Walker 2015;
    :class:`~rigidbody.euler_poinsot.EddyCurrent`) and :math:`A = \tfrac25 mr^2`, so
    :math:`\sigma = 3m\,(p/A)/(\pi r^3)`: what the fitted rate means as a material property, for a satellite that
    is *not* homogeneous (a dense core in a lighter shell).

    See Also
    --------
    fitted_eddy_rate : the fitted :math:`p/A`.

    Examples
    --------
    >>> from rigidbody.studies import STELLA, equivalent_conductivity, fitted_eddy_rate
    >>> print(f"{equivalent_conductivity(STELLA, fitted_eddy_rate(STELLA)):.2e} S/m")
    1.91e+06 S/m
    """
    return 3.0 * case.mass * positive(p_over_A, "p_over_A") / (math.pi * case.radius**3)


def _axis(axis: Any) -> np.ndarray:
    v = finite_array(axis, "axis")
    norm = float(np.linalg.norm(v)) if v.shape == (3,) else 0.0
    if norm == 0.0:
        raise ValueError(f"axis must be a non-zero 3-vector (the initial spin axis in the orbital axes), got {axis!r}")
    return v / norm


def predicted_period(case: SpinDecayCase, days: Any, axis: Any, p_over_A: float | None = None) -> np.ndarray:
    r"""The spin period (s) at ``days`` since launch under the orbit- and spin-averaged eddy-current torque of the
    sphere in the axial dipole, from :attr:`SpinDecayCase.period0` about ``axis``.

    A run of :meth:`rigidbody.euler_poinsot.Spacecraft.averaged` of the sphere (moment :math:`A = \tfrac25 mr^2`)
    with ``eddy`` :math:`= p` (S m^4) in ``field=case.field`` and ``orbit_averaged=True``, no gravity gradient;
    the period of a sphere is :math:`2\pi A/G`.

    Parameters
    ----------
    case : SpinDecayCase
    days : array_like
        Increasing days since launch, from 0.
    axis : array_like, shape (3,)
        The initial spin axis in the orbital axes (:math:`x_1` to the pericentre, :math:`x_3` the orbit normal).
    p_over_A : float, optional
        :math:`p/A` in 1/(s T^2); default :func:`fitted_eddy_rate`.

    Returns
    -------
    numpy.ndarray

    Raises
    ------
    ValueError
        ``days`` not two or more values increasing from 0, a zero ``axis``, a ``p_over_A`` that is not positive.
    RuntimeError
        If the averaged run ends early (its message says why).

    See Also
    --------
    rigidbody.euler_poinsot.Spacecraft.averaged : the run.
    decay_time_ratio : its e-folding time against the observed one.

    Examples
    --------
    A spin along the weakest mean field decays fastest:

    >>> from rigidbody.studies import LARETS, field_axes, predicted_period
    >>> s, V = field_axes(LARETS)
    >>> print(predicted_period(LARETS, [0.0, 50.0], V[:, 0]).round(3).tolist())
    [0.86, 3.735]
    """
    t = finite_array(days, "days").reshape(-1) * SECONDS_PER_DAY
    if t.size < 2 or t[0] != 0.0 or np.any(np.diff(t) <= 0.0):
        raise ValueError(f"days must be two or more days since launch increasing from 0, got {days!r}")
    rate = fitted_eddy_rate(case) if p_over_A is None else positive(p_over_A, "p_over_A")
    A = 0.4 * case.mass * case.radius**2
    sc = ep.Spacecraft([A, A, A], 2.0 * math.pi / case.period0 * _axis(axis), orbit=case.orbit)
    sol = sc.averaged((0.0, t[-1]), t, gravity_gradient=False, eddy=rate * A, field=case.field, orbit_averaged=True)
    if sol.status < 0:
        raise RuntimeError(f"predicted_period({case.name}): the averaged run ended early: {sol.message}")
    return 2.0 * math.pi * A / np.asarray(sol.G, dtype=float)


def decay_time_ratio(case: SpinDecayCase, axis: Any, p_over_A: float | None = None) -> float:
    r"""Predicted over observed decay time: the mean e-folding time of :func:`predicted_period` over one
    observed decay time :math:`1/k`, divided by :math:`1/k`.

    See Also
    --------
    predicted_period : the history it is read from.

    Examples
    --------
    With the fitted :math:`p/A`, a spin along the orbit normal decays faster than observed, one in the orbit's
    plane along the strongest mean field slower:

    >>> from rigidbody.studies import STELLA, decay_time_ratio, field_axes
    >>> s, V = field_axes(STELLA)
    >>> print(f"{decay_time_ratio(STELLA, V[:, 0]):.3f} {decay_time_ratio(STELLA, V[:, 2]):.3f}")
    0.672 1.471
    """
    T = predicted_period(case, [0.0, 1.0 / case.rate], axis, p_over_A)
    return 1.0 / math.log(T[1] / T[0])
