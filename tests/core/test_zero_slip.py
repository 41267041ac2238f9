"""Zero slip under exact Coulomb friction: the direction the slip takes when static friction cannot
hold (at the start and mid-run), and a start that must leave the table."""

import phasekit as pk
from phasekit import cli
from phasekit.core import Mode
from phasekit.core.zero_slip import project_no_slip, sliding_direction

import numpy as np
import pytest

from ..helpers import run_cli, strict_json


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception inside the CLI is a test failure, not a one-line message."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


REST = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0]  # released from rest, tilted: `--state 0 0 0 0 1.0 0`


@pytest.fixture(scope="module")
def released():
    """The prolate spheroid released from rest, up to just before it first sticks."""
    model = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))
    return model, pk.simulate(model, REST, 7.0, rtol=1e-12)


def test_release_from_rest_slides_instead_of_no_consistent_direction_cli():
    code, out, _ = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--state", *REST, "--t-end", 3, "--json")
    d = strict_json(out)
    assert code == 0 and d["status"] == "completed"
    assert d["events"][0]["kind"] == "slip" and d["events"][0]["mode_after"] == "sliding"


def test_release_from_rest_direction_wraps_at_pi_and_is_self_consistent(released):
    model, _ = released
    x = project_no_slip(model, REST)
    assert float(model.function("margin_rolling")(x, model.p)) < 0  # static friction cannot hold
    e, along = sliding_direction(model, x)
    # the slip develops backwards along the tilt: phi = pi, the end point of a linspace over
    # [-pi, pi] that the old search never bracketed
    assert e == pytest.approx([-1.0, 0.0], abs=1e-12)
    acc, R = (np.asarray(v).ravel() for v in model.function("slip_onset")(x, model.p, np.arctan2(e[1], e[0])))
    assert abs(e[0] * acc[1] - e[1] * acc[0]) < 1e-12 * np.linalg.norm(acc)  # a(e) parallel to e
    assert along == pytest.approx(e @ acc) and along > 0 and R[0] > 0


def test_release_from_rest_falls_slides_and_dissipates(released):
    model, r = released
    assert r.status is pk.Status.COMPLETED and all(s.mode is Mode.SLIDING for s in r.segments)
    df = r.sample(np.linspace(0.0, 7.0, 1401))
    assert np.all(np.isfinite(df[["U", "V", "Omega", "Lambda", "theta", "n", "R", "energy"]].to_numpy()))
    assert df.h.iloc[200] < df.h.iloc[0] - 0.05  # G falls
    assert np.all(np.diff(df.energy) < 1e-9)  # Coulomb friction only removes energy
    assert df.energy.iloc[-1] < df.energy.iloc[0] - 0.05
    # released in a vertical plane, it stays in it
    assert np.max(np.abs(df[["V", "Omega", "n"]].to_numpy())) < 1e-8
    # the slip grows along the direction chosen at t = 0
    u = model.evaluate("slip", r.states([0.05])[0])
    assert u[0] < 0 and abs(u[1]) < 1e-9 * abs(u[0])


def test_release_from_rest_agrees_with_regularised_coulomb_as_eps_vanishes(released):
    """Regularised Coulomb friction never asks for a sliding direction: its runs must converge
    to the exact law's (error ~ eps) if the direction chosen at zero slip is right."""
    model, r = released
    ts = np.linspace(0.0, 7.0, 29)
    exact = r.sample(ts).theta.to_numpy()
    errs = []
    for eps in (1e-5, 1e-6):
        reg = pk.simulate(pk.Model(model.body, pk.RegularisedCoulomb(0.1, eps)), REST, 7.0, rtol=1e-12)
        errs.append(np.max(np.abs(reg.sample(ts).theta.to_numpy() - exact)))
    assert errs[1] < 3e-6 and errs[0] / errs[1] > 5


def test_mid_run_zero_slip_with_rolling_infeasible_reverses_the_slip(released):
    """Mid-run the slip passes through zero where static friction cannot hold: the run goes on
    sliding, and (motion in a plane) the slip changes sign through zero."""
    model, r = released
    passes = [e for e in r.events if e.name == "slip" and e.mode_before == "sliding"]
    assert len(passes) == 2  # t ~ 2.34 and 5.36
    for e in passes:
        assert "rolling infeasible" in e.detail
        assert float(model.function("margin_rolling")(e.x, model.p)) < 0
        before, after = (model.evaluate("slip", r.states([e.t + dt])[0]) for dt in (-1e-3, 1e-3))
        assert before[0] * after[0] < 0 and abs(after[1]) < 1e-6 * abs(after[0])


def test_direction_search_steps_over_the_poles_of_R_instead_of_raising_nan():
    """Coulomb mu = 2: along some directions the sliding R has a pole (Painleve); the old
    search bracketed the pole as a root and Brent's method raised on NaN."""
    model = pk.Model(pk.Spheroid(0.3), pk.Coulomb(2.0))
    x = [-0.08729759498850069, -2.636069068272459, -30.258981677996463, -0.16536753311066726, 2.668832525553433,
         5.480704046506499]
    e, along = sliding_direction(model, project_no_slip(model, x))
    acc, R = (np.asarray(v).ravel() for v in model.function("slip_onset")(project_no_slip(model, x), model.p,
                                                                          np.arctan2(e[1], e[0])))
    assert abs(e[0] * acc[1] - e[1] * acc[0]) < 1e-10 * np.linalg.norm(acc) and R[0] > 0 and along > 0
    r = pk.simulate(model, x, 1.0)
    assert r.status is not pk.Status.FAILED and np.all(np.isfinite(r.x))


def test_zero_slip_start_that_needs_R_below_zero_lifts_off_instead_of_failing():
    """At zero slip with R < 0 in every contact mode the body leaves the table; it used to
    end "failed: no self-consistent sliding direction"."""
    model = pk.Model(pk.Spheroid(0.3), pk.Coulomb(0.1))
    x = project_no_slip(model, [0.0, 0.0, 0.0, 2.0, 1.0, 0.0])
    assert model.evaluate("R", x, Mode.ROLLING) < 0
    r = pk.simulate(model, x, 1.0)
    assert r.status is pk.Status.JUMPED and "R <= 0 at the start" in r.reason
