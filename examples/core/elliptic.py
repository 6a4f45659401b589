"""
Jacobi functions in the papers' modulus k
=========================================

:mod:`rigidbody.core.elliptic` takes the modulus ``k`` of the papers (SciPy's functions take the parameter
``m = k^2``). Prints three tables: ``sn, cn, dn`` over one period ``4K``; ``K`` and ``sn`` next to the
separatrix given the complementary parameter ``1 - k^2`` down to ``1e-12`` (where SciPy's ``ellipj``, given
``m = 1 - (1 - k^2)``, fails for ``u > K``), with the limit ``K ~ ln(4 / sqrt(1 - k^2))``; and the mean of
``sn^2`` over a period by :func:`rigidbody.core.averaging.sn2_average` against its closed form
``(1 - E/K) / k^2``. Prints only.
"""

import numpy as np
import scipy.special

from rigidbody.core import averaging, elliptic

# sn, cn, dn over one period 4K in the modulus k
k = 0.8
KK = elliptic.K(k)
u = np.linspace(0.0, 4 * KK, 9)
sn, cn, dn, am = elliptic.jacobi(u, k)
print(f"k = {k}: K = {KK:.12f}")
print(" u / K        sn             cn             dn")
for row in zip(u / KK, sn, cn, dn):
    print("{:5.1f}  {:+.10f}  {:+.10f}  {:+.10f}".format(*row))

# next to the separatrix, given the complementary parameter mc = 1 - k^2: K against its limit ln(4 / sqrt(mc)),
# and sn(2.5 K) = -1 / sqrt(1 + sqrt(mc)); SciPy's ellipj, given m = 1 - mc, fails there (sn of the wrong sign)
print("\n  1 - k^2   K(k)                ln(4/sqrt(mc))      sn(2.5 K)            SciPy ellipj(2.5 K)")
for mc in (1e-2, 1e-4, 1e-8, 1e-12):
    Kc = elliptic.K(mc=mc)
    scipy_sn = scipy.special.ellipj(2.5 * Kc, 1.0 - mc)[0]
    print(f"{mc:8.0e}  {Kc:.15f}  {np.log(4 / np.sqrt(mc)):.15f}  {elliptic.sn(2.5 * Kc, mc=mc):+.15f}  "
          f"{scipy_sn:+.15f}")

# the mean of sn^2 over a period by quadrature against its closed form (1 - E/K) / k^2
print("\n  k     <sn^2> (quadrature)   (1 - E/K) / k^2")
for k in (0.1, 0.5, 0.8, 0.99):
    mean = averaging.sn2_average(lambda x: x, 0.0, 1.0, k)
    print(f"{k:4}  {mean:.15f}     {(1 - elliptic.E(k) / elliptic.K(k)) / k**2:.15f}")
