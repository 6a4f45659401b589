"""core.quadform.inertia refuses a non-symmetric matrix instead of classifying it silently."""

import numpy as np
import pytest

from rigidbody.core.quadform import inertia


def test_inertia_rejects_non_symmetric_and_accepts_scaled_symmetric():
    with pytest.raises(ValueError, match="symmetric"):
        inertia(np.array([[1.0, 2.0], [0.0, 1.0]]))
    # symmetric with entries over 20 decades (SI Hessians): accepted, inertia (1 positive, 1 negative)
    H = np.array([[1e10, 1e-3], [1e-3, -1e-10]])
    pos, neg, zero = inertia(H)
    assert (int(pos), int(neg), int(zero)) == (1, 1, 0)
