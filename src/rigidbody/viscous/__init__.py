"""Axisymmetric rigid body in a linearly viscous medium (A. M. Krivtsov, PMM 2000).

Torque ``M = -B·ω`` with ``B = B12 (E - nn) + B3 nn`` (1.1), motion ``(θ·ω)˙ = -B·ω`` (1.2).

Model
    :class:`Body` (θ12, θ3), :class:`Medium` (B12, B3), :func:`ball_and_rod` (fig. 1, section 2),
    :func:`regime`, :func:`decay_rates`.
Closed forms
    :func:`Omega`, :func:`v`, :func:`f3`, :func:`F4`, :func:`omega2` (3.3)-(3.5); :func:`curvature` (4.5);
    :func:`spiral_radius` (5.2); :func:`quasi_coordinates` (5.1) and :func:`limits`.
Paths
    :func:`axis_path` — the axis path rebuilt from v(t), k(t) alone; :func:`turn` — one turn of the
    spiral, its solid angle and the axial rotation (solid-angle theorem).
Simulation
    :func:`simulate` — the full equations with a quaternion attitude; :func:`axial_rotation`.

See :doc:`/viscous` for the equations, conventions (sign of k) and :doc:`/errata` for the misprints.
"""

from ._closed import F4, Omega, curvature, f3, limits, omega2, quasi_coordinates, spiral_radius, v
from ._model import Body, Medium, ball_and_rod, decay_rates, regime
from ._path import Turn, axis_path, turn
from ._simulate import axial_rotation, simulate

__all__ = [
    "F4",
    "Body",
    "Medium",
    "Omega",
    "Turn",
    "axial_rotation",
    "axis_path",
    "ball_and_rod",
    "curvature",
    "decay_rates",
    "f3",
    "limits",
    "omega2",
    "quasi_coordinates",
    "regime",
    "simulate",
    "spiral_radius",
    "turn",
    "v",
]
