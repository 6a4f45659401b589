"""Plotting helpers: compute functions return data, these draw it on a given (or new) ``Axes``.

``plot_solution(sol)`` draws the standard figure of any result: this package is the default plotting backend
of results (``Solution.plot_backend = "rigidbody.plotting"``), whose ``plot_solution`` ``sol.plot()`` calls.
Every helper is available at the top level (``rigidbody.plotting.hodograph_3d``) and in the submodule of
its analysis (``rigidbody.plotting.euler_poinsot.hodograph_3d``). :mod:`rigidbody.plotting.common` holds
what every module uses (axes creation, the unit sphere, time series). Matplotlib is imported by these
modules only; ``import rigidbody`` does not import them.
"""

from . import common, euler_poinsot, gyrostat, lagrange, studies, viscous
from .common import STANDARD_PLOTS, get_ax, plot_solution, standard_plot, time_series, unit_sphere
from .euler_poinsot import (
    equal_3d,
    hodograph,
    hodograph_3d,
    hodograph_projection,
    hodograph_side_view,
    plane_basis,
    separatrix_passage,
    slow_variables,
    spiral_axis,
)
from .gyrostat import VERDICT_COLORS, dumbbell_side_view, normalized_map_plot, plot_satellite_motion, stability_map_plot
from .lagrange import plot_averaged, plot_integrals, plot_roots, plot_top_motion, slow_time_axis
from .studies import REGIME_COLORS, averaging_error_plot, scaled_error_map, spin_end_map
from .viscous import (
    ball_and_rod_sketch,
    look_from,
    plot_axis_path,
    quasi_coordinate_histories,
    sphere_path,
    turn_solid_angle,
)

__all__ = [
    "REGIME_COLORS",
    "STANDARD_PLOTS",
    "VERDICT_COLORS",
    "averaging_error_plot",
    "ball_and_rod_sketch",
    "common",
    "dumbbell_side_view",
    "equal_3d",
    "euler_poinsot",
    "get_ax",
    "gyrostat",
    "hodograph",
    "hodograph_3d",
    "hodograph_projection",
    "hodograph_side_view",
    "lagrange",
    "look_from",
    "normalized_map_plot",
    "plane_basis",
    "plot_averaged",
    "plot_axis_path",
    "plot_integrals",
    "plot_roots",
    "plot_satellite_motion",
    "plot_solution",
    "plot_top_motion",
    "quasi_coordinate_histories",
    "scaled_error_map",
    "separatrix_passage",
    "slow_time_axis",
    "slow_variables",
    "sphere_path",
    "spin_end_map",
    "spiral_axis",
    "stability_map_plot",
    "standard_plot",
    "studies",
    "time_series",
    "turn_solid_angle",
    "unit_sphere",
    "viscous",
]
