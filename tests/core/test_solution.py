"""The result type: built by keywords with its producer and declared optional fields, the positional form kept,
a member of a batch carrying its own entries."""

import math

import numpy as np
import pytest

from rigidbody.core.batch import integrate_batch
from rigidbody.core.ode import OPTIONAL_FIELDS, Event, Solution, integrate

T = np.linspace(0.0, 1.0, 5)


def test_build_by_keywords_records_the_producer_and_the_optional_fields():
    sol = Solution.build(producer="tests.by_hand", time=T, y=np.vstack([T, 2 * T]), status=1, message="stopped",
                         fields={"x": T}, event="wall", time_name="tau", crossings=[{"tau": 0.5}], quad_error=1e-9,
                         last_step=0.25)
    assert sol.producer == "tests.by_hand" and sol.batch_shape == () and sol.tau is sol.time
    assert sol.status == 1 and sol.success and sol.event == "wall" and sol.x is sol["x"]
    assert sol.crossings == [{"tau": 0.5}] and sol.quad_error == 1e-9 and sol.last_step == 0.25
    # what a producer does not record takes the declared default
    assert sol.resonances == [] and sol.t_final is None and sol.y_final is None
    assert set(OPTIONAL_FIELDS) == {"crossings", "quad_error", "resonances"}
    plain = Solution.build(producer="tests.by_hand", time=T, y=T[None, :], status=0, message="")
    assert plain.crossings == [] and plain.quad_error == 0.0 and plain.resonances == [] and plain.last_step is None
    assert plain.t_events == {} and plain.fields == () and plain.event is None
    # a default is a new object per result, not one shared list
    plain.crossings.append("x")
    assert Solution.build(producer="p", time=T, y=T[None, :], status=0, message="").crossings == []


def test_build_refuses_what_does_not_fit():
    kw = dict(time=T, y=T[None, :], status=0, message="")
    with pytest.raises(TypeError, match="producer"):
        Solution.build(producer="", **kw)
    with pytest.raises(TypeError, match=r"unknown field.*'crosings'"):
        Solution.build(producer="p", crosings=[], **kw)
    with pytest.raises(ValueError, match="y must have shape"):
        Solution.build(producer="p", time=T, y=np.ones((2, 4)), status=0, message="")
    with pytest.raises(ValueError, match="message must have one entry per member"):
        Solution.build(producer="p", time=T, y=np.ones((3, 1, 5)), status=np.zeros(3, int), message="one for all",
                       nfev=np.zeros(3, int))


def test_the_positional_form_still_builds_a_result():
    sol = Solution("t", T, T[None, :], {"x": T}, 0, "done", None, {}, {}, None, 7, t_final=1.0)
    assert sol.producer is None and sol.t_final == 1.0 and sol.nfev == 7 and sol.crossings == []
    sol.crossings = [{"tau": 0.1}]  # producers not yet converted set optional fields afterwards
    assert sol.crossings == [{"tau": 0.1}]


def test_the_integrators_record_themselves():
    one = integrate(lambda t, y: [-y[0]], (0.0, 1.0), [1.0], engine="python")
    batch = integrate_batch(lambda t, y: -y, (0.0, 1.0), np.ones((2, 1)))
    assert one.producer == "core.ode.integrate" and batch.producer == "core.batch.integrate_batch"
    assert batch[1].producer == "core.batch.integrate_batch"


def test_a_member_carries_its_own_entries_of_the_per_member_fields():
    # a batch that ends its members at different times: each member's t_final, last_step and an optional field
    # set per member are that member's, as a single run would hold them
    lam = np.array([0.5, 2.0])
    ev = Event(lambda t, y, lam: y[:, 0] - 0.5, "half", direction=-1.0)
    s = integrate_batch(lambda t, y, lam: -lam[:, None] * y, (0.0, 3.0), np.ones((2, 1)), args=(lam,), events=[ev])
    s.quad_error = np.array([1e-8, 2e-8])
    s.crossings = np.empty(2, dtype=object)
    s.crossings[0], s.crossings[1] = [], [{"tau": 0.1}]
    for i in range(2):
        m = s[i]
        assert m.t_final == s.t_final[i] and isinstance(m.t_final, float)
        assert m.last_step == s.last_step[i] and isinstance(m.last_step, float)
        np.testing.assert_array_equal(m.y_final, s.y_final[i])
        assert m.quad_error == s.quad_error[i] and m.crossings is s.crossings[i]
    assert s[1].t_final == pytest.approx(math.log(2) / 2.0, rel=1e-9, abs=0)  # the event's time, rtol-1e-10 run
    # a batch that records none has per-member defaults
    assert s.resonances.shape == (2,) and s[0].resonances == [] and s[1].resonances == []
