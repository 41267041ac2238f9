"""Generated cases over the Python API of issue 24: ``ensemble``, ``find_threshold`` and
``find_stick_boundary`` with budgets, ``Scale``, ``Scene``/``compute_scene``,
``Trajectory.sample``, the new solver options (settle, bounces, switch budget) and hopping runs.

Each case ends in one of the three outcomes of tests/test_fuzz.py (a valid result with no NaN
or inf, a run "failed" with its reason, or a ParameterError naming an argument of the call),
within a hang guard; a valid result is also checked against an independent computation
where one is cheap (a row against its single run, a bracket against its outcomes, a unit
round trip, a sample against ``Trajectory.at``), so that a silent wrong answer fails too.
Derandomised; ``pytest -s`` prints the counts (PHASEKIT_FUZZ_REPORT=FILE writes them).
"""

import collections
import json
import math
import os

import phasekit as pk
from phasekit import cli

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from .test_fuzz import (
    BODIES,
    LAWS,
    SIM_NAMES,
    check_trajectory,
    classify_api,
    finite_everywhere,
    fuzz_settings,
    mostly,
    real_or_wrong,
    reals,
    wrong,
)

COUNTS: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
NULLABLE = {"reason", "t_jump"}  # ensemble columns that may be missing (None -> NaN in pandas)


def record(suite: str, outcome: str) -> None:
    COUNTS[suite][outcome] += 1


@pytest.fixture(scope="module", autouse=True)
def _report():
    yield
    total = collections.Counter()
    lines = ["", "generated API cases (valid / failed with a reason / clear error):"]
    for suite, c in sorted(COUNTS.items()):
        total.update(c)
        lines.append(f"  {suite:<28s} {sum(c.values()):5d} cases: {c['valid']:4d} valid, {c['failed']:4d} failed, "
                     f"{c['error']:4d} error")
    lines.append(f"  {'total':<28s} {sum(total.values()):5d} cases: {total['valid']:4d} valid, "
                 f"{total['failed']:4d} failed, {total['error']:4d} error")
    print("\n".join(lines))
    path = os.environ.get("PHASEKIT_FUZZ_REPORT")
    if path:
        path = path + ".api.json" if not path.endswith(".json") else path.replace(".json", ".api.json")
        with open(path, "w") as fh:
            json.dump({"suites": {k: dict(v) for k, v in COUNTS.items()}, "total": dict(total)}, fh, indent=2)


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


PROLATE, OBLATE = BODIES["prolate"], BODIES["oblate"]


def starts():
    """Lists of 1-3 starts: mostly gyroscopic ones of the prolate body, sometimes junk."""
    good = st.lists(st.sampled_from([9.0, 10.5, 12.0, 20.0]), min_size=1, max_size=3).map(
        lambda ws: [pk.gyroscopic_start(PROLATE, np.pi / 2 - 0.01, omega0=w) for w in ws])
    return mostly(good, st.just([]), st.just([[1.0, 2.0]]), st.just([[0, 0, 10, 0, math.nan, 0]]), wrong(), n_good=30)


ENSEMBLE_NAMES = SIM_NAMES | {"starts", "scheduler", "processes", "progress", "max_wall_total"}


@fuzz_settings(150)
@given(st.sampled_from(sorted(LAWS)), starts(),
       mostly(st.sampled_from([1.0, 3.0, 50.0]), st.sampled_from([0.0, -1.0, math.nan, math.inf, -1e300]), wrong(),
              n_good=12), st.fixed_dictionaries({}, optional={
    "processes": mostly(st.sampled_from([1, 1, 2]), st.sampled_from([0, -1, 2.5, "2", True]), n_good=20),
    "progress": mostly(st.sampled_from([None, False, True]), st.just("yes"), n_good=10),
    "max_wall_total": mostly(st.sampled_from([None, 30.0, 1e-6]), st.sampled_from([0.0, -1.0, math.nan, "x"]), n_good=16),
    "stop_at": mostly(st.sampled_from(["jump", "none", "touchdown"]), st.just("bad"), n_good=10),
    "restitution": mostly(st.sampled_from([0.5, 0.0, 0.9]), st.sampled_from([-1.0, math.nan]), n_good=10),
    "max_steps": mostly(st.sampled_from([100, 5000, 5_000_000]), st.just(0), n_good=10),
    "events": mostly(st.sampled_from([(), [pk.Event("theta", 1.0, terminal=False, name="th")]]), st.just([1]), n_good=10),
    "scheduler": mostly(st.none(), st.sampled_from([3.0, "", "not an address"]), n_good=20),
    "t_eval": mostly(st.none(), st.just([0.5]), n_good=10)}))
def test_api_ensemble(law, x0s, t_end, kw):
    model = pk.Model(PROLATE, LAWS[law])
    kw.setdefault("processes", 1)
    if kw.get("t_eval") is None:
        kw.pop("t_eval", None)
    outcome, df = classify_api(ENSEMBLE_NAMES, lambda: pk.ensemble(model, x0s, t_end, max_wall=5.0, **kw))
    if outcome == "valid":
        assert list(df["i"]) == list(range(len(x0s))) and list(df.columns[:7]) == ["i", *pk.core.PAPER_NAMES]
        assert set(df["status"]) <= {s.value for s in pk.Status}
        ran = df[df["status"] != "failed"]  # a row that never ran has its status and reason only
        numeric = ran.drop(columns=["reason", "mode_end", "status", *[c for c in df.columns if c.startswith("t_")
                                                                      and c != "t_end"]])
        assert np.all(np.isfinite(numeric.to_numpy(dtype=float))), numeric
        assert all(isinstance(r, str) and r for r in df.loc[df["status"] == "failed", "reason"])
        row = df.iloc[0]
        if kw.get("max_wall_total") is None and row["status"] != "failed":  # the row is its single run
            args = {k: v for k, v in kw.items() if k in ("stop_at", "restitution", "max_steps", "events")}
            single = pk.simulate(model, x0s[0], t_end, dense=False, max_wall=5.0, progress=False, **args)
            assert row["status"] == single.status.value and row["t_end"] == single.t
            assert row["n_flights"] == single.hops["n_flights"]
        outcome = "failed" if (df["status"] == "failed").all() else "valid"
    record("api ensemble", outcome)


DEF_KW = st.fixed_dictionaries({"seed": st.sampled_from(["sliding", "sliding", "viscous", "literal"])}, optional={
    "mu": reals(0.1, 0.3), "amplitude": reals(0.01, 0.05),
    "settle": st.sampled_from([pk.core.Settle(), None, True, pk.core.Settle(window=1.0), {"window": -1.0}, "x"]),
    "t_max": st.sampled_from([5.0, 20.0])})


def _threshold_checks(th) -> str:
    assert isinstance(th, pk.thresholds.Threshold) and th.status in pk.SearchStatus
    assert th.value is None or math.isfinite(th.value)
    assert all(b is None or math.isfinite(b) for b in th.bracket)
    if th.status is pk.SearchStatus.CONVERGED:
        lo, hi = th.bracket
        assert lo < th.value < hi
        at = {o.value: o for o in th.outcomes}
        assert at[lo].jumped is False and at[hi].jumped is True  # the bracket its own runs give
    if th.status in (pk.SearchStatus.FAILED, pk.SearchStatus.BRACKET_ONLY):
        assert th.reason
    return "failed" if th.status is pk.SearchStatus.FAILED else "valid"


@fuzz_settings(120)
@given(DEF_KW, st.sampled_from([1.5, 0.6, 2.0]), st.fixed_dictionaries({}, optional={
    "max_wall": mostly(st.sampled_from([None, 5.0, 1e-3]), st.sampled_from([0.0, -1.0, math.nan, "x", True]), n_good=8),
    "progress": st.sampled_from([None, False, True, 1]),
    "engine": st.sampled_from(["scalar", "scalar", "batch", "x"]),
    "levels": st.sampled_from([1, 2, 0, 9]), "tol": st.sampled_from([0.05, 0.2, 0.0]),
    "guess": st.sampled_from([None, 9.7, 8.5, -1.0])}))
def test_api_find_threshold_with_budgets(defn_kw, a, kw):
    kw = {"n_coarse": 2, "tol": 0.05, **kw}
    outcome, defn = classify_api({"seed", "mu", "amplitude", "settle", "t_max", "window"},
                                 lambda: pk.Definition("fuzz", max_steps=3000, **defn_kw))
    if outcome == "valid":
        outcome, th = classify_api({"body", "a", "max_wall", "progress", "engine", "levels", "tol", "guess", "omega0",
                                    "n0"}, lambda: pk.find_threshold(defn, a, **kw))
        if outcome == "valid":
            outcome = _threshold_checks(th)
    record("api find_threshold budgets", outcome)


@fuzz_settings(60)
@given(mostly(st.sampled_from([8.0, 12.0]), st.sampled_from([-1.0, math.nan]), n_good=6),
       st.fixed_dictionaries({}, optional={
           "max_wall": mostly(st.sampled_from([None, 2.0, 1e-3]), st.just(-1.0), n_good=6),
           "lo": mostly(st.sampled_from([1e-3, 0.01]), st.sampled_from([0.3, 0.6]), n_good=6),
           "hi": mostly(st.sampled_from([0.05, 0.2]), st.just(0.0), n_good=6),
           "tol": mostly(st.sampled_from([0.2, 0.5]), st.just(0.0), n_good=6),
           "progress": st.sampled_from([None, False])}))
def test_api_find_stick_boundary(value, kw):
    defn = pk.Definition("fuzz", "sliding", t_max=5.0, max_steps=3000)
    outcome, th = classify_api({"value", "max_wall", "lo", "hi", "tol", "progress", "n_coarse"},
                               lambda: pk.thresholds.find_stick_boundary(defn, PROLATE, value, n_coarse=2, **kw))
    if outcome == "valid":
        import inspect

        defaults = inspect.signature(pk.thresholds.find_stick_boundary).parameters
        lo = kw.get("lo", defaults["lo"].default)
        hi = kw.get("hi", defaults["hi"].default)
        assert th.value is None or lo <= th.value <= hi
        outcome = _threshold_checks(th)
    record("api find_stick_boundary", outcome)


LENGTHS = st.sampled_from(["21.5 mm", "0.02 m", "1 inch", "-1 mm", "0 mm", "1 s", "", "mm", "1e400 m", "nan m", "abc"])
KIND_VALUES = {"length": "57 mm", "time": "12 ms", "rate": "30 rev/s", "speed": "0.5 m/s", "mass": "57 g",
               "force": "0.5 N", "energy": "1 mJ"}


@fuzz_settings(200)
@given(mostly(st.sampled_from(["21.5 mm", "0.02 m", "1 inch", "3 km", "1e-6 mm"]), LENGTHS, wrong(), st.just(21.5),
              n_good=12),
       mostly(st.sampled_from([None, "9.81 m/s**2", "1.62 m/s**2"]), st.sampled_from(["9.81 m", "-9.81 m/s**2"]), n_good=10),
       mostly(st.sampled_from([None, "57 g", "2 kg"]), st.sampled_from(["0 g", "5 m"]), n_good=10),
       mostly(st.sampled_from(sorted(KIND_VALUES)), st.sampled_from(["bogus", None]), n_good=14),
       reals(1.0, 12.5, 0.0, -3.0))
def test_api_scale(b, g, mass, kind, x):
    kw = {} if g is None else {"g": g}
    outcome, sc = classify_api({"b", "g", "mass"}, lambda: pk.Scale(b, mass=mass, **kw))
    if outcome == "valid":
        outcome, back = classify_api({"value", "kind", "mass"}, lambda: (sc.quantity(x, kind),
                                                                           sc.dimensionless(sc.quantity(x, kind), kind)))
        if outcome == "valid":
            q, y = back
            assert math.isfinite(q.magnitude) and math.isfinite(y)
            assert y == pytest.approx(x, rel=1e-12, abs=1e-300)  # the round trip returns the value
        if kind in KIND_VALUES:
            outcome2, v = classify_api({"value", "kind", "mass"}, lambda: sc.dimensionless(KIND_VALUES[kind]))
            if outcome2 == "valid":
                assert math.isfinite(v) and v > 0
    record("api Scale", outcome)


@fuzz_settings(100)
@given(mostly(st.sampled_from([("prolate", 1.5), ("prolate", 2.0), ("oblate", 0.6), ("oblate", 0.8)]),
              st.sampled_from([("prolate", 0.6), ("sideways", 1.5), ("prolate", 1.0)]), st.tuples(st.just("prolate"),
                                                                                                      reals(1.5)), n_good=10),
       mostly(st.sampled_from([(), (10.0,)]), st.sampled_from([(-1.0,), "abc", (math.nan,)]), n_good=10),
       mostly(st.sampled_from([frozenset({"surface", "axes"}), frozenset({"fixed_points"}), frozenset({"exact_boundary"}),
                               frozenset({"surface", "colorbar"}), frozenset({"trajectories"})]),
              st.sampled_from([{"bogus"}, "surface"]), n_good=10),
       st.fixed_dictionaries({}, optional={
           "resolution": mostly(st.sampled_from([2, 8, 12]), st.sampled_from([1, 5000]), n_good=8),
           "omega_range": mostly(st.sampled_from([None, (5.0, 20.0)]), st.sampled_from([(3.0, 1.0), (1, 2, 3)]), n_good=8),
           "theta_range": mostly(st.sampled_from([None, (0.1, 1.5)]), st.just((0.0, 4.0)), n_good=8),
           "exact_lambda": mostly(st.sampled_from([None, 0.0, 0.5]), st.sampled_from([1e4, math.nan]), n_good=8),
           "seed_distance": mostly(st.sampled_from([0.01, 0.05]), st.sampled_from([0.0, 2.0]), n_good=8),
           "mu": mostly(st.sampled_from([0.1, 0.3]), st.just(-0.1), n_good=8)}))
def test_api_scene(branch_a, values, show, kw):
    branch, a = branch_a
    kw = {"resolution": 8, **kw}
    names = {"branch", "a", "values", "show", "resolution", "omega_range", "theta_range", "exact_lambda",
             "seed_distance", "mu", "n_clip", "dt"}
    outcome, scene = classify_api(names, lambda: pk.Scene(branch, a, values=values, show=show, **kw))
    if outcome == "valid":
        assert scene.n_trajectories == len(scene.values)
        outcome, data = classify_api(names | {"scene"}, lambda: pk.compute_scene(scene) if not scene.values or
                                     not ({"trajectories", "crossings"} & scene.show) else None)
        if outcome == "valid" and data is not None:
            assert data.n_simulations == 0
            for arr in (data.surface or ()) + (data.exact or ()):
                assert not np.any(np.isinf(arr)) and np.isfinite(arr).any()  # masked cells are NaN by design
    record("api Scene", outcome)


@pytest.fixture(scope="module")
def runs():
    """Trajectories of every kind: a jump, a hopping run (flights), a stuck (rolling) one, the
    vector chart and a regularised law."""
    prolate = pk.Model(PROLATE, pk.Coulomb(0.1))
    out = {
        "jump": pk.simulate(prolate, pk.gyroscopic_start(PROLATE, 1.5, omega0=10.0), 10.0),
        "hops": pk.simulate(prolate, pk.gyroscopic_start(PROLATE, np.pi / 2 - 0.01, omega0=30.0), 33.0, stop_at="none",
                            restitution=0.5),
        "stuck": pk.simulate(prolate, pk.paper_start("5.2")[1], 3.0),
        "vector": pk.simulate(pk.Model(PROLATE, pk.Coulomb(0.1), "vector"),
                              pk.core.to_chart("vector", pk.gyroscopic_start(PROLATE, 1.5, omega0=10.0)), 5.0),
        "regularised": pk.simulate(pk.Model(OBLATE, pk.RegularisedCoulomb(0.1, 1e-3)),
                                   pk.gyroscopic_start(OBLATE, 0.05, n0=10.0), 5.0),
    }
    assert out["hops"].hops["n_flights"] > 3 and out["stuck"].stuck
    return out


@fuzz_settings(200)
@given(st.sampled_from(["jump", "hops", "stuck", "vector", "regularised"]),
       st.one_of(st.lists(st.floats(-0.2, 1.2), min_size=0, max_size=6),
                 st.lists(reals(0.5, 0.0, 1.0), max_size=3), wrong()))
def test_api_sample_of_every_kind_of_run(runs, which, fractions):
    """``fractions`` of the simulated span (outside [0, 1]: before the start or after the end)."""
    r = runs[which]
    span = r.t - r.t0
    times = [r.t0 + f * span if isinstance(f, float) and math.isfinite(f) and abs(f) < 10 else f for f in fractions] \
        if isinstance(fractions, list) else fractions
    outcome, df = classify_api({"times"}, lambda: r.sample(times))
    if outcome == "valid":
        values = df.drop(columns=["mode"]).to_numpy(dtype=float)
        assert np.all(np.isfinite(values)) and list(df["t"]) == sorted(df["t"])
        assert set(df["mode"]) <= {"sliding", "rolling", "flight"}
        if len(df):
            k = len(df) // 2
            at = r.at(float(df["t"].iloc[k]))
            assert np.array_equal(at[list(pk.core.PAPER_NAMES)].to_numpy(float),
                                  df.iloc[k][list(pk.core.PAPER_NAMES)].to_numpy(float))  # the same instant, the same row
            states = r.states(df["t"].to_numpy())
            assert states.shape[0] == len(df) and np.all(np.isfinite(states))
            assert all((df["gap"] > 0) <= (df["mode"] == "flight"))  # a gap only in flight
    record("api Trajectory.sample (kinds)", outcome)


@fuzz_settings(100)
@given(st.fixed_dictionaries({}, optional={
    "settle": st.sampled_from([None, True, False, pk.core.Settle(), {"window": 5.0, "tol": 0.1}, {"windows": 1}, "x",
                               {"window": math.nan}]),
    "bounce_stop": mostly(st.sampled_from([1e-4, 1e-6, 1e-2]), st.sampled_from([0.0, -1.0, 2.0, math.nan, "x"])),
    "bounce_tail": mostly(st.sampled_from([None, 100, 3]), st.sampled_from([0, -1, 2.5, "x"])),
    "max_switches": mostly(st.sampled_from([None, 10, 10**6]), st.sampled_from([0, -1, 2.5, True])),
    "max_wall": real_or_wrong(2.0, 600.0)}))
def test_api_new_solver_options(kw):
    outcome, opts = classify_api(set(pk.SolverOptions.names()) | {"window", "tol", "R_floor"},
                                 lambda: pk.SolverOptions(**kw))
    if outcome == "valid":
        d = opts.to_dict()
        assert finite_everywhere(d) and json.loads(json.dumps(d)) == d
        assert opts.switch_limit(400.0) >= (opts.max_switches or 10_000)
        assert pk.SolverOptions(**{k: v for k, v in d.items()}) == opts  # from its JSON, the same options
    record("api SolverOptions (issue 24)", outcome)


@fuzz_settings(150)
@given(st.sampled_from([10.0, 20.0, 30.0]), real_or_wrong(0.5, 0.0, 0.95, 1.0), real_or_wrong(2.0, 5.0, 0.5),
       st.fixed_dictionaries({}, optional={
           "settle": st.sampled_from([None, True, pk.core.Settle(window=0.5, tol=0.5)]),
           "bounce_stop": st.sampled_from([1e-4, 1e-3, 1e-6]), "bounce_tail": st.sampled_from([None, 100, 2]),
           "max_switches": st.sampled_from([None, 50, 3]), "max_steps": st.sampled_from([5_000_000, 2000]),
           "stop_at": st.sampled_from(["none", "none", "touchdown", "jump"])}))
def test_api_hopping_runs(omega0, e, t_span, kw):
    """Hopping starts of the issue (a = 1.5, sliding branch) over a short span past the jump."""
    model = pk.Model(PROLATE, pk.Coulomb(0.1))
    x0 = pk.gyroscopic_start(PROLATE, np.pi / 2 - 0.01, omega0=omega0)
    t_end = (28.0 if omega0 >= 20 else 42.0) + t_span if isinstance(t_span, float) and math.isfinite(t_span) else t_span
    outcome, r = classify_api(SIM_NAMES | {"window", "tol", "R_floor"},
                              lambda: pk.simulate(model, x0, t_end, restitution=e, dense=False, max_wall=5.0, **kw))
    if outcome == "valid":
        outcome = check_trajectory(r)
        hops = r.hops
        assert hops["n_flights"] == len(r.flights) and hops["n_liftoffs"] == len(r.events_named("lift-off"))
        assert hops["flight_fraction"] == pytest.approx(hops["t_flight"] / (r.t - r.t0), rel=1e-12, abs=1e-15)
        assert hops["t_flight"] <= r.t - r.t0 + 1e-12
        if r.status is pk.Status.FAILED and "mode switches" in r.reason:
            assert len(r.events) >= (kw.get("max_switches") or 10_000)
    record("api hopping runs", outcome)


def test_every_generated_suite_has_valid_cases():
    """Runs last (file order): a suite whose every case ended in a clear error would pass case by
    case with the feature refusing all input; each must have valid results too."""
    thin = {suite: dict(c) for suite, c in COUNTS.items() if c["valid"] < max(3, 0.1 * sum(c.values()))}
    assert not thin, thin
