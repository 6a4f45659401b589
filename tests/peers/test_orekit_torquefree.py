"""Orekit's torque-free attitude tests, ported (cases and reference values, not code).

Source: CS-SI/Orekit, ``src/test/java/org/orekit/attitudes/TorqueFreeTest.java`` at commit
fe4aee843fbf8f7e9dfddaa92725ef3dda20d52b (Orekit 13.x development line). Orekit's conventions mapped: a Hipparchus
``Rotation(q0, q1, q2, q3)`` (scalar first) of an ``Attitude`` takes inertial to body components, so the body ->
inertial attitude is SciPy's ``Rotation.from_quat([q1, q2, q3, q0])``; the spin is in body axes; an ``Inertia`` of
three ``InertiaAxis(I, a)`` is the tensor sum I a a^T; ``Rotation.distance`` is the angle of r1 r2^-1; dates are
seconds from the initial date. ``testField`` (the same model in Hipparchus' Binary64 field against double) has no
counterpart here (there is one arithmetic) and is not ported.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from rigidbody.euler_poinsot import EulerPoinsot

Q0 = (0.9, 0.437, 0.0, 0.0)  # new Rotation(0.9, 0.437, 0.0, 0.0, true): normalised
SPIN = (0.05, 0.0, 0.04)
AXES = ((3.0 / 8.0, (1.0, 0.0, 0.0)), (1.0 / 2.0, (0.0, 1.0, 0.0)), (5.0 / 8.0, (0.0, 0.0, 1.0)))


def attitude(q):
    return Rotation.from_quat([q[1], q[2], q[3], q[0]])


def tensor(axes):
    return sum(i * np.outer(a, a) for i, a in axes)


def java_range(start, stop, step):
    """``for (double dt = start; dt < stop; dt += step)`` with the same accumulated rounding."""
    out, dt = [], start
    while dt < stop:
        out.append(dt)
        dt += step
    return np.array(out)


def hipparchus_angle(v1, v2):
    """``Vector3D.angle``: acos of the normalised dot product, asin of the cross product near 0 and pi."""
    n = np.linalg.norm(v1, axis=-1) * np.linalg.norm(v2, axis=-1)
    dot = (v1 * v2).sum(-1)
    cross = np.linalg.norm(np.cross(v1, v2), axis=-1) / n
    near = np.abs(dot) > 0.9999 * n
    small = np.where(dot >= 0, np.arcsin(cross), math.pi - np.arcsin(cross))
    return np.where(near, small, np.arccos(np.clip(dot / n, -1.0, 1.0)))


def test_local_behavior():
    R0 = attitude(Q0)
    m = EulerPoinsot.from_state(tensor(AXES), SPIN, R0)
    # the model gives the initial attitude and spin back (Orekit: 1e-10)
    assert (m.rotation(0.0) * R0.inv()).magnitude() < 1e-10
    assert np.linalg.norm(m.omega(0.0) - SPIN) < 1e-10
    # close to the constant-spin extrapolation (Attitude.shiftedBy: R0 exp(spin dt)) near the initial date: the
    # largest distance is 5.0e-6 over [-0.1, 0.1) and 5.0e-4 over [-1, 1), each within Orekit's 1e-7
    for half, expected in ((0.1, 5.0e-6), (1.0, 5.0e-4)):
        dt = java_range(-half, half, 0.001)
        linear = R0 * Rotation.from_rotvec(dt[:, None] * np.asarray(SPIN)[None, :])
        err = (linear * m.rotation(dt).inv()).magnitude().max()
        assert abs(err - expected) <= 1.0e-7


def permuted_inertias():
    """Orekit's ``permute(Inertia)``: the axes permuted as a whole (outer loop), the moments within a triad
    (inner loop): 36 inertias."""
    for ia in itertools.permutations(AXES):
        for i in itertools.permutations(range(3)):
            yield tuple((ia[i[k]][0], ia[k][1]) for k in range(3))


@pytest.mark.parametrize("step", [0.1, pytest.param(0.01, marks=pytest.mark.slow)])
def test_momentum(step):
    """Torque-free motion keeps the angular momentum fixed in inertial axes: angle <= 1.6e-15 rad (Orekit's
    tolerance) over [-40, 40) in steps of 0.01 (Orekit's; the default run every 0.1), for every permutation of the
    spin, of the quaternion's components and of the inertia."""
    cases = [(tensor(AXES), s, Q0) for s in itertools.permutations(SPIN)]
    cases += [(tensor(AXES), SPIN, q) for q in itertools.permutations(Q0)]
    cases += [(tensor(ax), SPIN, Q0) for ax in permuted_inertias()]
    assert len(cases) == 6 + 24 + 36
    dt = java_range(-40.0, 40.0, step)
    for J, spin, q in cases:
        R0 = attitude(q)
        m = EulerPoinsot.from_state(J, spin, R0)
        initial = R0.apply(J @ np.asarray(spin))
        momentum = m.rotation(dt).apply(m.omega(dt) @ J.T)
        assert hipparchus_angle(momentum, initial[None, :]).max() <= 1.6e-15
