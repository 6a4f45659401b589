"""Plotting helpers: compute functions return data, these draw it on a given (or new) ``Axes``.

Every helper is available at the top level (``rigidbody.plotting.hodograph_3d``) and in the submodule of
its analysis (``rigidbody.plotting.euler_poinsot.hodograph_3d``). :mod:`rigidbody.plotting.common` holds
what every module uses (axes creation, the unit sphere, time series). Matplotlib is imported by these
modules only; ``import rigidbody`` does not import them.
"""

from . import common, euler_poinsot, gyrostat, lagrange, viscous
from .common import get_ax, time_series, unit_sphere
from .euler_poinsot import (
    hodograph,
    hodograph_3d,
    hodograph_projection,
    separatrix_passage,
    slow_variables,
    spiral_axis,
)
from .gyrostat import VERDICT_COLORS, dumbbell_side_view, normalized_map_plot, stability_map_plot
from .lagrange import plot_integrals, plot_roots, slow_time_axis
from .viscous import look_from, quasi_coordinate_histories, sphere_path, turn_solid_angle

__all__ = [
    "VERDICT_COLORS",
    "common",
    "dumbbell_side_view",
    "euler_poinsot",
    "get_ax",
    "gyrostat",
    "hodograph",
    "hodograph_3d",
    "hodograph_projection",
    "lagrange",
    "look_from",
    "normalized_map_plot",
    "plot_integrals",
    "plot_roots",
    "quasi_coordinate_histories",
    "separatrix_passage",
    "slow_time_axis",
    "slow_variables",
    "sphere_path",
    "spiral_axis",
    "stability_map_plot",
    "time_series",
    "turn_solid_angle",
    "unit_sphere",
    "viscous",
]
