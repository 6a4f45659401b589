r"""Explorer 1 (1958) from its own numbers: the published inputs, a mass model, the antennas' energy sink and
the one fitted constant.

Explorer 1, the first satellite of the United States, was spun about its long axis (the axis of its smallest
moment) and was found, after about one orbit, turning end over end about a transverse axis (the flat spin):
its four flexible whip antennas dissipated kinetic energy at constant angular momentum. Its body is
dynamically symmetric (two equal transverse moments), so the torque-free motion is a regular precession at
the nutation angle :math:`\theta` of :math:`\mathbf G` from the long axis, and the energy loss drives
:math:`\theta` from near 0 to :math:`90^\circ`.

The published inputs (:data:`MASS`, :data:`LENGTH`, :data:`DIAMETER`, :data:`SPIN_RPM`,
:data:`ORBIT_PERIOD_MIN`, :data:`PERIGEE_KM`, :data:`APOGEE_KM`):

- mass 13.97 kg (30.8 lb), length 203 cm (80 in), diameter 15.2 cm (6.0 in), perigee 358 km, apogee 2550 km,
  period 114.8 min: NASA's NSSDC master catalogue entry 1958-001A (and the National Air and Space Museum's
  data sheet "Explorer-I and Jupiter-C", reproduced by the NASA History Office);
- spin "about 750 rpm" about the long axis (the issue's figure, the usual one for the Jupiter-C upper stages;
  W. Bollay, "Spin stability of the Explorer satellite", Stanford Engineering Case Library ECL 1006 (1967),
  writes "about 10 revolutions per second");
- the observation: "from observations of its antenna pattern it was deduced that after about one orbit the spin
  rate decreased to about 2 cycles per second and that its spin axis had rotated about 90 degrees, so that it
  was now spinning about its axis of maximum moment of inertia" (Bollay, ECL 1006, part I).

Not published (that we found): the moments of inertia and the mass distribution, the antennas' mass and
damping, the initial nutation angle. So:

- the moments are those of a homogeneous solid cylinder of the published mass and envelope
  (:func:`cylinder_moments`): :math:`A/C = 1/2 + (2/3)(L/D)^2 \approx 119`. The antennas (mass unpublished)
  would add :math:`4m_w(r^2 + rl + l^2/3)` to :math:`C` and half of that to :math:`A` for four radial whips of
  mass :math:`m_w` and length :math:`l` from the radius :math:`r` (and :math:`4m_wz^2` to :math:`A` at a distance
  :math:`z` along the axis from the centre of mass); left out. The ratio sets the rate of the final flat spin,
  :math:`G/A`, about 6 rpm, and it does not change the spin-axis history below (only the product of the damping
  constant and :math:`1/C - 1/A` enters it, and that product is fitted).
- the damping is the energy-sink torque :class:`AntennaDamping`, :math:`\mathbf M = -\kappa(\boldsymbol\omega -
  (\boldsymbol\omega\cdot\mathbf g)\mathbf g/G^2)`, with :math:`\kappa` FITTED (:func:`fitted_kappa`) to the
  criterion "flat spin after about one orbit", taken as :math:`\theta` reaching :data:`THETA_FLAT` = 80 degrees
  at one orbital period from :data:`THETA0` = 1 degree (our choice of the unknown initial nutation; the fitted
  :math:`\kappa` grows as :math:`\ln(\tan 80^\circ/\tan\theta_0)`). Bollay's two rates are consistent with that
  reading: at constant :math:`G` the spin about the long axis, :math:`\omega_3 = G\cos\theta/C`, falls as
  :math:`\cos\theta`, and the turnstile's pattern turns with the body about that axis: "about 2" after "about
  10" (or 12.5, for 750 rpm) revolutions per second is :math:`\cos\theta` = 0.2 (0.16), :math:`\theta` = 78
  (81) degrees (if the pattern's cycles are the body's turns about its axis: our reading).

The module's scaling is that of :mod:`rigidbody.euler_poinsot` (:ref:`ep-scaling`): the unit of rate is the
initial :math:`|\boldsymbol\omega|` (750 rpm), the unit of angular momentum the initial :math:`|\mathbf G|`,
:math:`\varepsilon = n/\Omega_0` (:math:`1.16\cdot 10^{-5}` for Explorer: :math:`1/\varepsilon` = 86 100 spin
revolutions per orbit) and the slow time :math:`\tau = \varepsilon^2\Omega_0 t` (:func:`explorer1_case`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.validate import positive, real
from ..euler_poinsot import Body, SymmetricBody, Torque

__all__ = [
    "APOGEE_KM",
    "DIAMETER",
    "LENGTH",
    "MASS",
    "ORBIT_PERIOD_MIN",
    "PERIGEE_KM",
    "SPIN_RPM",
    "THETA0",
    "THETA_FLAT",
    "AntennaDamping",
    "Explorer1Case",
    "cylinder_moments",
    "explorer1_case",
    "fitted_kappa",
    "nutation_angle",
]

#: mass (kg): 13.97 kg (30.8 lb), NSSDC 1958-001A
MASS = 13.97
#: length (m): 203 cm (80 in), NSSDC 1958-001A (205.1 cm, 80.75 in, in other listings)
LENGTH = 2.03
#: diameter (m): 15.2 cm (6.0 in), NSSDC 1958-001A
DIAMETER = 0.152
#: initial spin about the long axis (rpm): "about 750 rpm" (Bollay, ECL 1006: "about 10 revolutions per second")
SPIN_RPM = 750.0
#: orbital period (min), NSSDC 1958-001A
ORBIT_PERIOD_MIN = 114.8
#: perigee altitude (km), NSSDC 1958-001A
PERIGEE_KM = 358.0
#: apogee altitude (km), NSSDC 1958-001A
APOGEE_KM = 2550.0
#: initial nutation angle of G from the long axis (rad): 1 degree, OUR choice (not published)
THETA0 = math.radians(1.0)
#: the criterion of the fit (rad): "flat spin after about one orbit" read as theta = 80 degrees at one period
THETA_FLAT = math.radians(80.0)


def cylinder_moments(mass: float, length: float, diameter: float) -> tuple[float, float]:
    r"""The principal moments of a homogeneous solid circular cylinder about its centre of mass.

    .. math:: A = m\Bigl(\frac{D^2}{16} + \frac{L^2}{12}\Bigr),\qquad C = \frac{mD^2}{8}

    (:math:`A` about a transverse axis, :math:`C` about the cylinder's axis).

    Parameters
    ----------
    mass, length, diameter : float
        In any consistent units (kg and m for kg m^2); each positive and finite.

    Returns
    -------
    tuple of float
        ``(A, C)``.

    Raises
    ------
    TypeError, ValueError
        If an argument is not a positive finite real number (the message names it).

    See Also
    --------
    explorer1_case : Explorer 1's scaled start from these moments.

    Examples
    --------
    Explorer 1's published mass and envelope: the transverse moment is about 119 times the axial one.

    >>> from rigidbody.studies import explorer1 as ex
    >>> A, C = ex.cylinder_moments(ex.MASS, ex.LENGTH, ex.DIAMETER)
    >>> print(f"A = {A:.4f} kg m^2, C = {C:.5f} kg m^2, A/C = {A / C:.1f}")
    A = 4.8176 kg m^2, C = 0.04035 kg m^2, A/C = 119.4
    """
    m, L, D = (positive(v, name) for v, name in ((mass, "mass"), (length, "length"), (diameter, "diameter")))
    return m * (D * D / 16.0 + L * L / 12.0), m * D * D / 8.0


def _wobble(body: Any) -> float:
    """:math:`1/C - 1/A` of a prolate :class:`SymmetricBody` (the rate of the nutation law per unit of kappa)."""
    if not isinstance(body, SymmetricBody):
        raise TypeError(f"body must be a SymmetricBody, got {type(body).__name__}")
    if body.shape != "prolate":
        raise ValueError(f"body must be prolate (C < A: the spin axis of the least moment), got {body!r}")
    return 1.0 / body.axial - 1.0 / body.transverse


@dataclass(frozen=True, eq=False)
class AntennaDamping(Torque):
    r"""An energy sink at constant angular momentum: the whip antennas' damping, averaged over their flexing.

    .. math:: \mathbf M = -\kappa\Bigl(\boldsymbol\omega - \frac{(\boldsymbol\omega\cdot\mathbf g)\,\mathbf g}
              {G^2}\Bigr)

    (body components; :math:`\mathbf g = A\boldsymbol\omega`). :math:`\mathbf M\perp\mathbf G`, so :math:`G` is
    kept, and :math:`\dot T = \boldsymbol\omega\cdot\mathbf M = -\kappa|\boldsymbol\omega_\perp|^2 \le 0`, with
    :math:`\boldsymbol\omega_\perp` the part of :math:`\boldsymbol\omega` across :math:`\mathbf G`. In a regular
    precession of a body with two equal moments :math:`|\boldsymbol\omega_\perp| = G|\sin\theta\cos\theta|\,
    |1/C - 1/A|`: the same :math:`\sin^2\theta\cos^2\theta` as the power a damper on the body dissipates when it
    is driven by the wobble (the body-frame nutation, at the rate :math:`G\cos\theta\,(1/C - 1/A)` and with an
    amplitude :math:`\propto\sin\theta`), the energy-sink model of the flat spin. It gives
    :math:`\dot\theta = \kappa(1/C - 1/A)\sin\theta\cos\theta`, solved by :func:`nutation_angle`, and the same
    equation holds along the full motion (:math:`\dot g_3 = M_3` depends on :math:`\theta` alone), so the
    averaged evolution of :math:`\theta` is exact for this torque.

    Parameters
    ----------
    body : SymmetricBody or Body
        The body whose moments turn :math:`\boldsymbol\omega` into :math:`\mathbf g` (the one of the run).
    kappa : float
        The damping constant (non-negative), in the units of the torques of :mod:`rigidbody.euler_poinsot`
        (torque per unit of angular velocity, slow time :math:`\tau`); for Explorer 1 fitted by
        :func:`fitted_kappa`.

    Raises
    ------
    TypeError
        If ``body`` is not a body or ``kappa`` not a real number.
    ValueError
        If ``kappa`` is negative or not finite.

    See Also
    --------
    nutation_angle : the nutation angle it gives, in closed form.
    fitted_kappa : its constant fitted to the flat spin.

    Examples
    --------
    The torque is across G, and it takes energy away:

    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> from rigidbody.studies.explorer1 import AntennaDamping
    >>> body = ep.SymmetricBody(A=120.0, C=1.0)
    >>> omega = np.array([0.001, 0.0, 1.0])
    >>> M = AntennaDamping(body, 2.0)(omega, np.eye(3), 0.0)
    >>> print(abs(M @ (omega * body.A)) < 1e-12, M @ omega < 0)
    True True
    """

    body: Any
    kappa: float

    def __post_init__(self) -> None:
        if not isinstance(self.body, (Body, SymmetricBody)):
            raise TypeError(f"body must be a Body or a SymmetricBody, got {type(self.body).__name__}")
        k = real(self.kappa, "kappa")
        if not (0.0 <= k < math.inf):
            raise ValueError(f"kappa must be non-negative and finite, got {self.kappa!r}")
        object.__setattr__(self, "kappa", k)

    def __call__(self, omega: Any, C: Any, nu: Any) -> np.ndarray:
        w = np.asarray(omega, dtype=float)
        g = w * self.body.A
        across = w - (w * g).sum(-1, keepdims=True) * g / (g * g).sum(-1, keepdims=True)
        return -self.kappa * across

    def check_setup(self, body: Any, orbit: Any) -> None:
        """Refuse a run whose body has other moments than the torque's (its ``g = A omega`` would be wrong).

        Examples
        --------
        >>> from rigidbody import euler_poinsot as ep
        >>> from rigidbody.studies.explorer1 import AntennaDamping
        >>> damping = AntennaDamping(ep.SymmetricBody(2.0, 1.0), 1.0)
        >>> damping.check_setup(ep.SymmetricBody(2.0, 1.0), ep.Orbit())  # the same body: accepted
        >>> try:
        ...     damping.check_setup(ep.SymmetricBody(3.0, 1.0), ep.Orbit())
        ... except ValueError:
        ...     print("refused")
        refused
        """
        if not np.array_equal(np.asarray(body.A, dtype=float), np.asarray(self.body.A, dtype=float)):
            raise ValueError(f"AntennaDamping was built for {self.body!r}, the run's body is {body!r}")


def nutation_angle(body: SymmetricBody, kappa: float, theta0: float, tau: Any) -> Any:
    r"""The nutation angle under :class:`AntennaDamping` in closed form.

    From :math:`\dot\theta = \kappa(1/C - 1/A)\sin\theta\cos\theta`:
    :math:`\tan\theta = \tan\theta_0\,e^{\lambda\tau}`, :math:`\lambda = \kappa(1/C - 1/A)`, written as
    :math:`\theta = \operatorname{atan2}(\sin\theta_0\,e^{\lambda\tau}, \cos\theta_0)` (any :math:`\theta_0`
    in :math:`[0, \pi]`).

    Parameters
    ----------
    body : SymmetricBody
        A prolate body (:math:`C < A`).
    kappa : float
        The damping constant of :class:`AntennaDamping`.
    theta0 : float
        The initial nutation angle (rad).
    tau : float or array_like
        Times (the unit of ``kappa``'s time: slow time :math:`\tau` in the module's scaling).

    Returns
    -------
    float or numpy.ndarray
        :math:`\theta(\tau)` (rad).

    See Also
    --------
    fitted_kappa : its inverse.
    AntennaDamping : the torque.

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import euler_poinsot as ep
    >>> from rigidbody.studies.explorer1 import nutation_angle
    >>> body = ep.SymmetricBody(A=2.0, C=1.0)
    >>> print(f"{np.degrees(nutation_angle(body, 2.0, np.radians(45.0), np.log(3.0))):.4f}")
    71.5651
    """
    rate = real(kappa, "kappa") * _wobble(body)
    t0 = real(theta0, "theta0")
    return np.arctan2(math.sin(t0) * np.exp(rate * np.asarray(tau, dtype=float)), math.cos(t0))


def fitted_kappa(body: SymmetricBody, theta0: float, theta_flat: float, tau_flat: float) -> float:
    r"""The damping constant of :class:`AntennaDamping` that turns :math:`\theta_0` into :math:`\theta_{flat}` in
    the time :math:`\tau_{flat}`: :math:`\kappa = \ln(\tan\theta_{flat}/\tan\theta_0) / ((1/C - 1/A)\tau_{flat})`
    (the inverse of :func:`nutation_angle`).

    Parameters
    ----------
    body : SymmetricBody
        A prolate body.
    theta0, theta_flat : float
        The initial and the final nutation angle (rad), :math:`0 < \theta_0 < \theta_{flat} < \pi/2`.
    tau_flat : float
        The time to reach ``theta_flat`` (positive).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If the angles or the time are outside their ranges, or the body is not prolate.

    See Also
    --------
    nutation_angle : the law it inverts.

    Examples
    --------
    From 45 to 60 degrees in a unit of time, with :math:`1/C - 1/A = 1/2`:
    :math:`\kappa = 2\ln\sqrt 3 = \ln 3`.

    >>> import math
    >>> from rigidbody import euler_poinsot as ep
    >>> from rigidbody.studies.explorer1 import fitted_kappa
    >>> kappa = fitted_kappa(ep.SymmetricBody(A=2.0, C=1.0), math.radians(45.0), math.radians(60.0), 1.0)
    >>> print(f"{kappa:.6f} {math.log(3.0):.6f}")
    1.098612 1.098612
    """
    wobble = _wobble(body)
    t0, t1, tf = real(theta0, "theta0"), real(theta_flat, "theta_flat"), positive(tau_flat, "tau_flat")
    if not (0.0 < t0 < t1 < 0.5 * math.pi):
        raise ValueError(f"need 0 < theta0 < theta_flat < pi/2 (rad), got theta0={theta0!r}, "
                         f"theta_flat={theta_flat!r}")
    return math.log(math.tan(t1) / math.tan(t0)) / (wobble * tf)


@dataclass(frozen=True)
class Explorer1Case:
    r"""Explorer 1 in the scaling of :mod:`rigidbody.euler_poinsot` (built by :func:`explorer1_case`).

    Attributes
    ----------
    body : SymmetricBody
        The moments :math:`\tilde A = A\Omega_0/G_0`, :math:`\tilde C = C\Omega_0/G_0` (:math:`\Omega_0` the initial
        :math:`|\boldsymbol\omega|`, :math:`G_0` the initial :math:`|\mathbf G|`).
    eps : float
        :math:`n/\Omega_0` (the orbital mean motion over the initial rate).
    theta0 : float
        The initial nutation angle (rad).
    kappa : float
        The FITTED damping constant of :class:`AntennaDamping` (scaled).
    tau_orbit : float
        One orbital period in the slow time: :math:`2\pi\varepsilon`.
    omega0_rpm : float
        :math:`\Omega_0` in rpm (the unit of the scaled rates).
    moments : tuple of float
        The physical ``(A, C)`` (kg m^2).

    See Also
    --------
    explorer1_case : builds it.

    Examples
    --------
    >>> from rigidbody.studies.explorer1 import explorer1_case
    >>> case = explorer1_case()
    >>> print(f"{case.omega0_rpm:.0f} rpm, kappa = {case.kappa:.0f} (fitted)")
    750 rpm, kappa = 79910 (fitted)
    """

    body: SymmetricBody
    eps: float
    theta0: float
    kappa: float
    tau_orbit: float
    omega0_rpm: float
    moments: tuple[float, float]

    @property
    def tau_per_minute(self) -> float:
        r""":math:`d\tau/dt` per minute: :math:`60\,\varepsilon^2\Omega_0`.

        Examples
        --------
        >>> from rigidbody.studies.explorer1 import explorer1_case
        >>> case = explorer1_case()
        >>> print(f"{case.tau_orbit / case.tau_per_minute:.1f} min")
        114.8 min
        """
        return self.eps**2 * self.omega0_rpm * 2.0 * math.pi  # eps^2 Omega0 (rad/s) times 60 s

    @property
    def torque(self) -> AntennaDamping:
        """The fitted :class:`AntennaDamping` of the case's body.

        Examples
        --------
        >>> from rigidbody.studies.explorer1 import explorer1_case
        >>> case = explorer1_case()
        >>> case.torque.kappa == case.kappa and case.torque.body == case.body
        True
        """
        return AntennaDamping(self.body, self.kappa)


def explorer1_case(theta0: float = THETA0, theta_flat: float = THETA_FLAT, *, mass: float = MASS,
                   length: float = LENGTH, diameter: float = DIAMETER, spin_rpm: float = SPIN_RPM,
                   period_min: float = ORBIT_PERIOD_MIN) -> Explorer1Case:
    r"""Explorer 1 from its published numbers, with the antennas' damping fitted to the flat spin.

    The moments from :func:`cylinder_moments`; :math:`\Omega_0` = ``spin_rpm`` is the initial
    :math:`|\boldsymbol\omega|` (with :math:`\mathbf G` at ``theta0`` from the long axis), so
    :math:`\tilde A = A\sqrt{\sin^2\theta_0/A^2 + \cos^2\theta_0/C^2}` and the same factor for :math:`\tilde C`;
    :math:`\varepsilon = n/\Omega_0` with :math:`n = 2\pi/`\ ``period_min``; :math:`\kappa` from
    :func:`fitted_kappa` with :math:`\tau_{flat}` one orbital period, :math:`2\pi\varepsilon`.

    Parameters
    ----------
    theta0 : float, optional
        The initial nutation angle (rad; default :data:`THETA0`, 1 degree, our choice).
    theta_flat : float, optional
        The nutation angle reached after one orbit (rad; default :data:`THETA_FLAT`, 80 degrees).
    mass, length, diameter, spin_rpm, period_min : float, optional
        The published inputs (defaults the module's constants).

    Returns
    -------
    Explorer1Case

    See Also
    --------
    Explorer1Case : what it returns.
    rigidbody.euler_poinsot.Spacecraft : the same start from the physical state in SI units.

    Examples
    --------
    86 100 spin revolutions per orbit; the run's unit of rate is 750 rpm:

    >>> from rigidbody.studies.explorer1 import explorer1_case
    >>> case = explorer1_case()
    >>> print(f"eps = {case.eps:.4e}, 1/eps = {1 / case.eps:.0f}, A/C = {case.body.transverse / case.body.axial:.1f}")
    eps = 1.1614e-05, 1/eps = 86100, A/C = 119.4
    """
    A, C = cylinder_moments(mass, length, diameter)
    t0 = real(theta0, "theta0")
    spin = positive(spin_rpm, "spin_rpm") * 2.0 * math.pi / 60.0
    n = 2.0 * math.pi / (60.0 * positive(period_min, "period_min"))
    scale = math.hypot(math.sin(t0) / A, math.cos(t0) / C)  # |omega| / G
    body = SymmetricBody(A * scale, C * scale)
    eps = n / spin
    tau_orbit = 2.0 * math.pi * eps
    kappa = fitted_kappa(body, t0, theta_flat, tau_orbit)
    return Explorer1Case(body, eps, t0, kappa, tau_orbit, spin * 60.0 / (2.0 * math.pi), (A, C))
