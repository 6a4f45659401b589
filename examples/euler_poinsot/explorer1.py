"""
The flat spin of Explorer 1, from its own numbers
=================================================

Explorer 1 (1958) was spun at about 750 rpm about its long axis, the axis of its least moment, and was found
turning end over end after about one orbit: "from observations of its antenna pattern it was deduced that after
about one orbit the spin rate decreased to about 2 cycles per second and that its spin axis had rotated about
90 degrees" (W. Bollay, "Spin stability of the Explorer satellite", Stanford Engineering Case Library ECL 1006,
1967). Its four flexible whip antennas dissipated kinetic energy at constant angular momentum G.

The case, :func:`rigidbody.studies.explorer1.explorer1_case`, with every input's source in
:mod:`rigidbody.studies.explorer1`:

- mass 13.97 kg, length 2.03 m, diameter 0.152 m, orbital period 114.8 min (perigee 358 km, apogee 2550 km):
  NASA's NSSDC catalogue, 1958-001A; spin 750 rpm about the long axis (Bollay: "about 10 revolutions per
  second");
- the moments are NOT published: those of a homogeneous cylinder of that mass and envelope, ``A/C = 119``
  (the antennas, of unpublished mass, left out), a :class:`~rigidbody.euler_poinsot.SymmetricBody`;
- ``eps = n / Omega0 = 1 / (750 x 114.8) = 1.16e-5``, Explorer's own: 86 100 spin revolutions in one orbit;
- the antennas' damping is NOT published: the energy sink
  :class:`~rigidbody.studies.explorer1.AntennaDamping`, ``M = -kappa (omega - (omega.g) g / G^2)``, with
  ``kappa`` FITTED to "flat spin after about one orbit", read as the nutation angle theta of G from the long
  axis going from 1 degree (our choice: the initial nutation is not published) to 80 degrees in one orbital
  period.

A body with two equal moments has no separatrix: the flat spin, theta = 90 degrees, is a circle of
equilibria, which the energy loss at constant G approaches (tan theta grows exponentially) without crossing
anything; the passage through a separatrix is a triaxial body's (``separatrix_passage``). No external torque is
included: the gravity gradient has no component along the axis of a body with two equal moments, and on the
eccentric orbit (e = 0.14 from perigee and apogee) it leaves theta unchanged on average and turns G by a fraction
of a degree in one orbit (checked with ``GravityGradient`` added to the averaged run).

The averaged evolution (:func:`rigidbody.euler_poinsot.averaged`, over the regular precession) covers 130
minutes; the full equations (:func:`rigidbody.euler_poinsot.simulate`) cover 2 minutes around theta = 45
degrees, started from the averaged state at 80 minutes: 1500 spin revolutions, a few seconds (the whole orbit
is 86 100 revolutions, too long for the gallery). For this torque the averaged law of theta is exact (the
torque's component along the axis depends on theta alone), so the two agree to the integrators' tolerance.

(a) theta against time, the full window in orange and the criterion of the fit; (b) the spin about the long axis
``G cos(theta) / C`` and the end-over-end rate ``G sin(theta) / A`` at constant G, with Bollay's two rates
(squares): 2 after 10 revolutions per second is what the spin about the axis does at theta = 78 degrees, if the
antenna pattern's cycles are the body's turns about its axis (our reading; the model gives 130 rpm after one
orbit, and the end-over-end rate levels off at G/A = 6.2 rpm, which depends on the unpublished moments); (c) the
full window.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import euler_poinsot as ep
from rigidbody.studies import explorer1 as ex

case = ex.explorer1_case()  # the published inputs; kappa fitted: theta from 1 to 80 degrees in one orbit
body, eps, torque, per_min = case.body, case.eps, case.torque, case.tau_per_minute
print(f"A/C = {case.moments[0] / case.moments[1]:.1f}, eps = {eps:.4e} ({1 / eps:.0f} spin revolutions per orbit), "
      f"fitted kappa = {case.kappa:.5g} (scaled)")

minutes = np.linspace(0.0, 130.0, 521)
avg = ep.averaged(body, torque, eps, theta0=case.theta0, tau_span=(0.0, minutes[-1] * per_min),
                  tau_eval=minutes * per_min)

W0, W1 = 80.0, 82.0  # the full motion's window (min), from the averaged state at W0
i0 = int(np.searchsorted(minutes, W0))
window = np.linspace(W0, W1, 241)
full = ep.simulate(body, torque, eps, theta0=avg.theta[i0], delta0=avg.delta[i0], lam0=avg.lam[i0],
                   nu0=avg.nu[i0], tau_span=(W0 * per_min, W1 * per_min), tau_eval=window * per_min)
common = slice(i0, i0 + 9)  # the averaged run's times in the window (every 30th of the full run's)

orbit = ex.ORBIT_PERIOD_MIN
theta_orbit = np.degrees(np.interp(orbit, minutes, avg.theta))
print(f"theta after one orbit ({orbit} min): {theta_orbit:.3f} deg (fitted to 80)")
print(f"full against averaged over {W0:g}-{W1:g} min: max |d theta| = "
      f"{np.degrees(np.abs(full.theta[::30] - avg.theta[common]).max()):.1e} deg")

rpm = case.omega0_rpm  # the unit of the scaled rates
spin = avg.G * np.cos(avg.theta) / body.axial * rpm
tumble = avg.G * np.sin(avg.theta) / body.transverse * rpm
print(f"after one orbit: spin about the axis {np.interp(orbit, minutes, spin):.0f} rpm, "
      f"end over end {np.interp(orbit, minutes, tumble):.2f} rpm")

fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.2), gridspec_kw={"width_ratios": [1.3, 1.2, 1.0]})
ax = axes[0]
ax.plot(minutes, np.degrees(avg.theta), color="C0", label="averaged")
ax.plot(window, np.degrees(full.theta), color="C1", lw=3, label=f"full motion, {W0:g}-{W1:g} min")
ax.axhline(90.0, color="0.6", ls="--", lw=0.8)
ax.axvline(orbit, color="0.6", ls=":", lw=0.8)
ax.plot([orbit], [np.degrees(ex.THETA_FLAT)], "kx", ms=8, label="fitted: 80° after one orbit")
ax.set(xlabel="time (min)", ylabel="nutation angle θ of G from the long axis (deg)",
       title="(a) the spin axis leaves G")
ax.legend(loc="lower right", fontsize=8)
ax = axes[1]
ax.semilogy(minutes, spin, color="C0", label="about the long axis, G cos θ / C")
ax.semilogy(minutes, tumble, color="C2", label="end over end, G sin θ / A")
ax.plot([0.0, orbit], [600.0, 120.0], "ks", mfc="none", ms=8, label="Bollay: about 10, then 2 per second")
ax.set(xlabel="time (min)", ylabel="rate (rpm)", title="(b) the rates at constant G")
ax.legend(fontsize=8)
ax = axes[2]
ax.plot(window, np.degrees(full.theta), color="C1", lw=2.5, label="full (osculating θ)")
ax.plot(minutes[common], np.degrees(avg.theta[common]), "o", color="C0", ms=5, label="averaged")
ax.set(xlabel="time (min)", ylabel="θ (deg)", title=f"(c) {(W1 - W0) * ex.SPIN_RPM:.0f} spin revolutions")
ax.legend(fontsize=8)
fig.suptitle("Explorer 1 from its own numbers: the flat spin after one orbit (damping fitted)")
fig.tight_layout()
plt.show()
