"""The wall budget of the steady-state searches: a structure whose budget runs out ends with status
"failed" and a reason naming the budget (checked by the structure's own status, never by a clock
in the test), its states are not invented, and a bad budget is refused naming ``max_wall``."""

import math

import phasekit as pk
from phasekit._runtime.watch import check_deadline, wall_deadline

import pytest

from ..helpers import raises_param


@pytest.mark.timeout(300)
def test_a_structure_out_of_budget_fails_with_the_reason():
    body, law = pk.Egg(1.3, 0.05), pk.Coulomb(0.1)
    s = pk.steady_structure(body, law, max_wall=1e-6)
    assert s.status is pk.Status.FAILED and s.branches == ()
    assert s.reason == "not finished: the call's wall budget (max_wall = 1e-06 s) ran out"
    assert s.to_dict()["status"] == "failed" and s.to_dict()["reason"] == s.reason
    with pytest.raises(pk.ConvergenceError, match="did not complete"):
        s.at(omega0=2.0)
    # a generous budget changes nothing: the same structure as without one
    full, free = pk.steady_structure(body, law, max_wall=600.0), pk.steady_structure(body, law)
    assert full.status is pk.Status.COMPLETED and full.signature == free.signature
    assert [b.theta.tolist() for b in full.branches] == [b.theta.tolist() for b in free.branches]


@pytest.mark.timeout(300)
def test_a_callers_earlier_deadline_holds_inside():
    with wall_deadline(1e-6):
        s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1), max_wall=600.0)
        assert s.status is pk.Status.FAILED and "max_wall = 1e-06 s" in s.reason
        with pytest.raises(TimeoutError, match="wall budget"):
            pk.fixed_points(pk.Model(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1)), omega0=3.0)
    check_deadline()  # no deadline in force: nothing to spend


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf, "1"])
def test_a_bad_budget_is_refused_naming_it(bad):
    raises_param("max_wall", lambda: pk.steady_structure(pk.Spheroid(1.5), pk.Viscous(0.1), max_wall=bad))
