"""
Jacobi functions in the papers' modulus k
=========================================

:mod:`rigidbody.core.elliptic` takes the modulus ``k`` of the papers (SciPy's functions take the parameter
``m = k^2``). Prints ``sn`` over one period ``4K``, ``K`` and ``sn`` next to the separatrix given the
complementary parameter ``1 - k^2 = 1e-12`` (where SciPy's ``ellipj`` fails for ``u > K``), and the mean of
``sn^2`` over a period by :func:`rigidbody.core.averaging.sn2_average` against its closed form
``(1 - E/K) / k^2``. Prints only.
"""

import numpy as np

from rigidbody.core import averaging, elliptic

k = 0.8
u = np.linspace(0.0, 4 * elliptic.K(k), 5)
sn, cn, dn, am = elliptic.jacobi(u, k)
print("sn over one period:", np.round(sn, 12))

# near the separatrix pass mc = 1 - k^2 (SciPy's raw ellipj fails here for u > K)
mc = 1e-12
KK = elliptic.K(mc=mc)
print(f"K(1 - k^2 = 1e-12) = {KK:.15f};  sn(2.5 K) = {elliptic.sn(2.5 * KK, mc=mc):.15f}")

# mean of sn^2 over a period equals (1 - E/K)/k^2
mean = averaging.sn2_average(lambda x: x, 0.0, 1.0, k)
print(f"<sn^2> = {mean:.15f}   (1 - E/K)/k^2 = {(1 - elliptic.E(k) / elliptic.K(k)) / k**2:.15f}")
