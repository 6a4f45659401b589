r"""Parameter studies: maps over parameters and initial states, and what theory predicts.

Each study function computes one point of a map from floats and returns a mapping of output names to
floats; given arrays of points it integrates them as batches and returns arrays, with a ``status`` and a
``message`` per point. Two ways to run one over a grid give the same numbers:

:func:`evaluate`
    in this process, one call with all the points (batch integrations), into a :class:`StudyMap` of NumPy
    arrays: the base install suffices (the figures command uses it);
:func:`rigidbody.sweep.sweep`
    ``sweep(func, grid)`` on local processes or a Dask cluster, resumable, into an ``xarray.Dataset`` (the
    ``sweep`` extra).

A point outside the domain of the study raises; a sweep records it (``status`` 1) and goes on, an array call
gives that point ``status`` 1 and the exception as its ``message``. :func:`grid_values` reads a variable of
either kind of map as an array (so do :func:`fitted_order` and the plotting helpers).

*Where averaging holds* — the largest difference between the averaged and the full evolution of the slow
variables over a slow-time span, against the order the theory gives:

:func:`averaging_error_euler_poinsot` over :math:`(\varepsilon, k^2_0)`
    Rachinskaya's averaged system (9) with the true anomaly kept (:func:`rigidbody.euler_poinsot.averaged`)
    against the full equations (:func:`rigidbody.euler_poinsot.simulate`); order :math:`\varepsilon^2`
    (:ref:`ep-numbers`).
:func:`averaging_error_lagrange` over :math:`(\varepsilon, \theta_0)`
    the first approximation (2.15)/(3.4) of Akulenko, Leshchenko and Chernousko
    (:func:`rigidbody.lagrange.averaged`) against the full equations (1.1)
    (:func:`rigidbody.lagrange.simulate`); order :math:`\varepsilon`.
:func:`fitted_order`
    the exponent :math:`p` of ``error ~ C eps**p`` fitted along the ``eps`` axis.

*Where the spin ends* — :func:`spin_end`: the final regime of :math:`k^2` under the averaged equation (8)
over a plane of diagonal drag tensors. Only the decay rates :math:`a_i = I_{ii}/A_i` enter (8), and only
their ratios matter (the scale sets the unit of slow time), so the plane is ``r1 = a1/a2``,
``r3 = a3/a2``. With :math:`a_2 = 1`, (8) reads

.. math:: \frac{dk^2}{d\tau} = -2\left[(r_3 - 1)(k^2 - W) + (1 - r_1)\,k^2 E/K\right],\qquad W = 1 - E/K,

and three lines through ``(1, 1)`` organise the plane (derived here from (7)-(8); see :ref:`sweeps-spin-end`):

- :func:`chi_minus_3_line`, ``r3 = 2 r1 - 1``: there :math:`\chi = -3` in (7); the slope of (8) at
  :math:`k^2 = 0`, :math:`-(r_3 + 1 - 2r_1)`, vanishes: :math:`k^2 = 0` is stable above the line,
  unstable below;
- ``r3 = r1``: near :math:`k^2 = 1`, :math:`dk^2/d\tau \approx -2(r_3 - r_1)E/K`:
  below the line :math:`k^2` reaches the separatrix in finite time, above it is pushed back;
- :func:`equilibrium_line`, ``r3 = 1 + rho(k2_0) (r1 - 1)``: where ``k2_0`` itself is an equilibrium of
  (8) (:math:`\rho = k^2(E/K)/(k^2 - W)` falls from 2 at :math:`k^2 = 0` to 1 at :math:`k^2 = 1`, so an
  interior equilibrium exists exactly between the first two lines). Between the first two lines with
  ``r1 < 1`` it is unstable and this line splits the starts that end at 0 from those that reach the
  separatrix.

:func:`spin_end_predicted` gives the regime from the equilibria of (8) alone
(:func:`rigidbody.euler_poinsot.k2_equilibria`), the analytic counterpart of the integrated map.

*Observed spin-down* — the exponential spin-down of the passive laser-ranged spheres Larets and Stella
(:data:`LARETS`, :data:`STELLA`: published mass, size, orbit and fit of the spin period) against the averaged
eddy-current torque in the geomagnetic dipole: :func:`predicted_period` and :func:`decay_time_ratio` (the
library's averaged run), :func:`observed_period` (the published fit), :func:`fitted_eddy_rate` (the one fitted
constant, :math:`p/A`), :func:`equivalent_conductivity`, :func:`field_axes`. See :ref:`ep-spin-history`.

The maps of the figures (``python -m rigidbody figures --only studies``) use the quick grids of
:data:`GRIDS`; the full grids are for a cluster (:ref:`sweeps-averaging` says how).
"""

from ._averaging import averaging_error_euler_poinsot, averaging_error_lagrange
from ._common import GRIDS, PAPER_BODY, PAPER_DRAG_CASE1
from ._maps import Field, StudyMap, as_study_map, evaluate, fitted_order, grid_values
from ._slr_spin import (
    LARETS,
    SECONDS_PER_DAY,
    STELLA,
    SpinDecayCase,
    decay_time_ratio,
    equivalent_conductivity,
    field_axes,
    fitted_eddy_rate,
    observed_period,
    predicted_period,
)
from ._spin import REGIMES, chi_minus_3_line, drag_from_ratios, equilibrium_line, spin_end, spin_end_predicted

__all__ = [
    "GRIDS",
    "LARETS",
    "PAPER_BODY",
    "PAPER_DRAG_CASE1",
    "REGIMES",
    "SECONDS_PER_DAY",
    "STELLA",
    "Field",
    "SpinDecayCase",
    "StudyMap",
    "as_study_map",
    "averaging_error_euler_poinsot",
    "averaging_error_lagrange",
    "chi_minus_3_line",
    "decay_time_ratio",
    "drag_from_ratios",
    "equilibrium_line",
    "equivalent_conductivity",
    "evaluate",
    "field_axes",
    "fitted_eddy_rate",
    "fitted_order",
    "grid_values",
    "observed_period",
    "predicted_period",
    "spin_end",
    "spin_end_predicted",
]

