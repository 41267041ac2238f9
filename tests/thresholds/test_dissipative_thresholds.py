"""Jump thresholds with dissipation laws: a Definition carries them into every run (the seed is
the one without them), the search runs, vanishing coefficients give the threshold without them,
and spin friction moves it; a definition without them keeps its key (stored results stay valid).
"""

from dataclasses import asdict

import phasekit as pk
from phasekit.thresholds import evaluate_outcomes

import pytest

from ..helpers import raises_param


def _laws(c):
    """Every law with coefficient c: rolling resistance, spin friction, air drag in all forms."""
    return (pk.RollingResistance(c), pk.SpinFriction(c), pk.AirDrag(c, c, c, c))


#: the search of the docs' example (prolate a = 1.5, sliding-branch seeds)
SEARCH = dict(hi=120.0, guess=9.74, tol=1e-2, max_wall=300.0, progress=False)


def test_a_definition_carries_its_dissipation_laws_into_the_law_its_label_and_its_key():
    plain = pk.Definition("sliding", "sliding")
    assert plain.key() == ("amplitude=0.01;eps=None;max_steps=20000000;mu=0.1;rise_margin=0.1;rtol=1e-09;"
                           "seed=sliding;t_max=3000.0")  # as before the laws existed
    d = pk.Definition("sliding", "sliding", dissipation=[pk.SpinFriction(0.01)])
    assert d.dissipation == (pk.SpinFriction(0.01),)
    assert d.friction() == pk.Coulomb(0.1).with_dissipation(pk.SpinFriction(0.01))
    assert d.label == "coulomb mu=0.1 exact + spin-friction(mu_s=0.01); seed: sliding branch d=0.01"
    assert d.key() == plain.key().replace("amplitude=0.01;", "amplitude=0.01;dissipation=['spin-friction(mu_s=0.01)'];")
    assert pk.Definition(**asdict(d)) == d and pk.Definition(**asdict(plain)) == plain
    v = pk.Definition("v", "viscous", dissipation=(pk.RollingResistance(0.002),))
    assert v.friction() == pk.Viscous(0.1).with_dissipation(pk.RollingResistance(0.002))
    model, _ = d.start(1.5, 12.0)
    assert model.friction.dissipation == (pk.SpinFriction(0.01),)
    raises_param("dissipation", lambda: pk.Definition("x", "sliding", dissipation=[0.01]))


@pytest.mark.timeout(600)
def test_vanishing_dissipation_gives_the_threshold_without_it():
    """Coefficients 1e-9 (every law): the same outcomes on the same grid, so the same bracket."""
    bare = pk.find_threshold(pk.Definition("sliding", "sliding"), 1.5, **SEARCH)
    tiny = pk.find_threshold(pk.Definition("sliding", "sliding", dissipation=_laws(1e-9)), 1.5, **SEARCH)
    assert bare.status.value == tiny.status.value == "converged"
    lo, hi = bare.bracket
    assert lo < tiny.value < hi and tiny.bracket[0] < bare.value < tiny.bracket[1]
    assert abs(tiny.value - bare.value) <= hi - lo


@pytest.mark.timeout(600)
def test_spin_friction_raises_the_threshold_of_jumping():
    """Spin friction mu_s = 0.01 takes energy from the spin: a start that jumped without it
    (Omega0 = 10.03) completes its rise, and the threshold moves above the bracket without it
    (measured: 10.21 against 9.78)."""
    bare = pk.find_threshold(pk.Definition("sliding", "sliding"), 1.5, **SEARCH)
    spun = pk.find_threshold(pk.Definition("sliding", "sliding", dissipation=[pk.SpinFriction(0.01)]), 1.5, **SEARCH)
    assert spun.status.value == "converged"
    assert spun.bracket[0] > bare.bracket[1]
    assert spun.value == pytest.approx(10.21, abs=0.05)


@pytest.mark.timeout(300)
def test_the_batch_engine_runs_a_dissipative_definition_one_by_one():
    """The batch integrator has no rest or pivot resets: a dissipative definition's runs are made
    one by one, with the same outcomes as the scalar engine."""
    d = pk.Definition("sliding", "sliding", dissipation=[pk.SpinFriction(0.01)])
    jobs = [(d, 1.5, 12.0), (d, 1.5, 9.5)]
    batch, scalar = (evaluate_outcomes(jobs, engine=e) for e in ("batch", "scalar"))
    assert [o.kind for o in batch] == [o.kind for o in scalar] == ["jump", "rise"]
    assert [o.t for o in batch] == [o.t for o in scalar]


def test_a_run_that_comes_to_rest_counts_as_no_jump():
    o = pk.thresholds.Outcome(8.0, False, pk.Status.REST, 614.9, True, "at rest at t = 614.9", 1.0, 0.05, 0.97)
    assert o.how == "rest" and o.kind == "stuck"
