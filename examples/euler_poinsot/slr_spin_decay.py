"""
Larets and Stella: an observed spin-down against the averaged eddy-current torque
=================================================================================

Two passive laser-ranged spheres whose spin periods, measured by satellite laser ranging, grow exponentially:
Larets ``T = 0.860499 exp(0.0197066 D)`` s and Stella ``T = 13.5582 exp(0.00431232 D)`` s, ``D`` in days since
launch (Kucharski, Lim, Kirchner, Koidl, *Adv. Space Res.* 53(1), 90-96 (2014), abstract). Mass, diameter and
orbit from the ILRS mission pages: Larets 23.28 kg, 24 cm, 691 km, inclination 98.204 deg, eccentricity 0.0002;
Stella 48 kg, 24 cm, perigee 800 km, 98.6 deg, 0.0007567 (altitudes taken above the equatorial radius
``R_EARTH``). The field is the axial dipole of IGRF-13 (epoch 2020.0, ``DipoleField``).

The model: a sphere (moment ``A = 2 m r^2 / 5``, magnetic tensor ``P = p I``) under the eddy-current torque,
averaged over the spin and the orbit: :func:`rigidbody.studies.predicted_period` runs ``Spacecraft([A, A, A], omega,
orbit=...).averaged(..., eddy=p, field=DipoleField(...), orbit_averaged=True)``. The spin across the orbit's mean
field decays: ``dG/dt = -(p/A)(tr S - S) G`` with ``S`` the mean of ``B B^T``, so the rate depends on the spin axis,
which the sources do not give; nor do they give the conductivity and geometry that make ``p``. So ``p/A`` is
**fitted** (:func:`rigidbody.studies.fitted_eddy_rate`: the rate averaged over directions is the observed one;
Larets ``p/A`` = 299, Stella 72.1 per s per T^2), and the figure shows what the model then says: the spin-down for a
spin axis along each principal direction of ``S`` (fastest: the weakest mean field, near the orbit normal; slowest:
the strongest, in the orbit's plane) against the published fit, drawn over two observed decay times (the span of the
measurements is not in the abstract; the line is the fit, not the data).

The ratio of the predicted to the observed decay time is 0.67 to 1.47 with the axis (1 on average over directions,
by the fit). The fitted ``p/A`` corresponds to a homogeneous sphere of conductivity 3.8e6 S/m (Larets) and
1.9e6 S/m (Stella) (:func:`rigidbody.studies.equivalent_conductivity`), in the range of metals. Left out: the
nodal precession of these Sun-synchronous orbits (the orbital axes turn once a year under a spin axis fixed in
space), the dipole's tilt, the Earth's rotation and the field's secular change, the skin effect at the first
spin rates, and every other torque.
"""

import matplotlib.pyplot as plt
import numpy as np

from rigidbody import studies

fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.2))
directions = ["weakest mean field (fastest)", "intermediate mean field", "strongest mean field (slowest)"]
for ax, case in zip(axes, [studies.LARETS, studies.STELLA]):
    days = np.linspace(0.0, 2.0 / case.rate, 81)
    s, V = studies.field_axes(case)
    ax.semilogy(days, studies.observed_period(case, days), "k-", lw=2.5, label="published fit (SLR)")
    for k, name in enumerate(directions):
        ratio = studies.decay_time_ratio(case, V[:, k])
        ax.semilogy(days, studies.predicted_period(case, days, V[:, k]), "--",
                    label=f"axis along the {name}: ratio {ratio:.2f}")
        print(f"{case.name}: spin axis along the {name}: predicted/observed decay time {ratio:.3f}")
    p_over_A = studies.fitted_eddy_rate(case)
    sigma = studies.equivalent_conductivity(case, p_over_A)
    print(f"{case.name}: fitted p/A = {p_over_A:.4g} /(s T^2), equivalent conductivity {sigma:.3g} S/m")
    ax.set_title(f"{case.name} (launched {case.launch}); fitted p/A = {p_over_A:.3g} /(s T$^2$)")
    ax.set_xlabel("days since launch")
    ax.set_ylabel("spin period (s)")
    ax.legend(fontsize=8)
fig.suptitle("Spin-down under the averaged eddy-current torque in the axial dipole, against laser ranging")
fig.tight_layout()
plt.show()
