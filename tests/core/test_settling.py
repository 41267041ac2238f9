"""Runs that have settled end as "settled" (:class:`phasekit.core.Settle`): an egg that rolls
tilted in a steady state stops there instead of stick-slipping to its end time; sliding and
regularised runs are left alone."""

import phasekit as pk

import numpy as np
import pytest


@pytest.fixture(scope="module")
def egg():
    return pk.core.egg_of_size("57 mm", "43 mm", w=0.05)[0]


def test_a_settled_egg_would_not_have_jumped(egg):
    """The settled run against the same run without the rule, to t = 180: it goes on rolling and
    re-slipping about the same tilted state, R far from 0 at every event, and never jumps."""
    model, x0 = pk.Definition("sliding", "sliding", mu=0.1).start(egg, 11.0)
    fast = pk.simulate(model, x0, 180.0, settle=True, track_minima=False)
    assert fast.status is pk.Status.SETTLED and fast.reason.startswith("settled: rolled in a steady state")
    assert fast.mode == "rolling" and fast.t < 150.0
    slow = pk.simulate(model, x0, 180.0, track_minima=False, dense=False)
    assert slow.status is pk.Status.COMPLETED and slow.t_jump is None
    later = [e for e in slow.events if e.t > fast.t and e.x is not None]
    theta = np.array([e.y[4] for e in later])
    assert len(later) > 50 and np.abs(theta - fast.euler_end[4]).max() < 2 * pk.core.Settle().tol
    R = [model.evaluate("R", e.x, e.mode_after) for e in later]
    assert min(R) > pk.core.Settle().R_floor


def test_the_settle_rule_leaves_sliding_and_regularised_runs_alone(prolate, standard_start):
    coulomb = pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), standard_start, 200.0, settle=True)
    assert coulomb.status is pk.Status.JUMPED
    # a regularised law keeps a small slip while "rolling": it never settles
    model, x0 = pk.paper_start("5.2")
    reg = pk.Model(model.body, pk.RegularisedCoulomb(0.1, 1e-3))
    r = pk.simulate(reg, x0, 120.0, settle=pk.core.Settle(window=5.0))
    assert r.status is not pk.Status.SETTLED and r.stuck


def test_settle_options_are_validated_and_reach_the_json():
    with pytest.raises(pk.ParameterError, match="`window`"):
        pk.core.Settle(window=-1.0)
    with pytest.raises(pk.ParameterError, match="`settle`"):
        pk.SolverOptions(settle="yes")
    opts = pk.SolverOptions(settle={"window": 30.0})
    assert opts.settle == pk.core.Settle(window=30.0) and opts.to_dict()["settle"]["window"] == 30.0


def test_a_roll_settles_one_period_in_and_rolls_on_periodically():
    """Rolling without slip is integrable for a body of revolution (phasekit.core.settle): the run
    with the rule ends at the second maximum of theta of its roll. The same run without the rule, to
    t = 300 (about 1250 periods of theta): no slip and no lift-off, R far from 0, and the state at
    every later maximum of theta is the settled state (drift measured 2e-11 per period)."""
    model, x0 = pk.Definition("literal", "literal").start(pk.Spheroid(0.85), 20.0)
    fast = pk.simulate(model, x0, 300.0, settle=True, track_minima=False, dense=False, progress=False)
    assert fast.status is pk.Status.SETTLED and "rolls periodically" in fast.reason
    assert [e.name for e in fast.events] == ["stick", "turn", "turn"] and fast.t < 1.0
    maxima = pk.Event("Lambda", 0.0, direction=-1, terminal=False, name="max")
    slow = pk.simulate(model, x0, 300.0, events=[maxima], track_minima=False, dense=False, progress=False)
    assert slow.status is pk.Status.COMPLETED and {e.name for e in slow.events} == {"stick", "max"}
    later = [e for e in slow.events if e.name == "max" and e.t > fast.t]
    Y = np.array([e.y for e in later])
    assert len(later) > 1000 and np.max(np.abs(Y - fast.euler_end)) < 1e-7  # measured 3.0e-8 (rates ~ 20)
    R = [float(model.evaluate("R", e.x, "rolling")) for e in later[::50]]
    assert min(R) > 0.5


def test_only_a_roll_that_is_periodic_is_watched_for_its_turns():
    """The turns of theta are watched where rolling is periodic: an exact rolling mode, no
    dissipation laws, one smooth piece of contact (a tippe top's contact passes to its stem)."""
    from phasekit.core.settle import rolls_periodically_here

    assert rolls_periodically_here(pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)))
    assert not rolls_periodically_here(pk.Model(pk.Spheroid(1.5), pk.RegularisedCoulomb(0.1, 1e-6)))
    assert not rolls_periodically_here(pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1).with_dissipation(pk.RollingResistance(0.01))))
    top = pk.Model(pk.bodies.TippeTop(0.3, A=0.38, C=0.4), pk.Coulomb(0.3))
    assert top.body.transfers and not rolls_periodically_here(top)
