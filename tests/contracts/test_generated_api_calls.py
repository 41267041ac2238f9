"""Generated calls of the public API: every case (extreme magnitudes, NaN, inf, zero, negative,
wrong types and lengths) of simulate, the starts, fixed points and linearisation, threshold
definitions and searches (with their budgets), bodies, friction laws, solver options, events,
ensembles, units, scenes and trajectory samples must end in one of three outcomes:

* ``valid``  - a returned object whose status is not "failed", with no NaN or inf anywhere in it;
* ``failed`` - a result with status "failed" and its reason, or a solver error with its reason;
* ``error``  - a ParameterError whose message starts with the name of an argument of the call.

Anything else (another exception, a message of two lines, NaN in a result) fails the test; a
hang fails it by its timeout. A valid result is also checked against an independent
computation where one is cheap (an ensemble row against its single run, a converged bracket
against its own outcomes, a unit round trip, a sample against ``Trajectory.at``), so that a
silent wrong answer fails too. Derandomised; ``pytest -s`` prints the counts
(PHASEKIT_FUZZ_REPORT=FILE.json writes them to FILE.api.json).
"""

import collections
import json
import math
import os
import warnings

import phasekit as pk
from phasekit import cli
from phasekit.core import charts
from phasekit.friction import laws as friction

import numpy as np
import pytest

from ..generated_inputs import (
    finite_everywhere,
    fuzz,
    generated,
    hang_guard,
    mostly,
    real_or_wrong,
    reals,
    report,
    st,
    thin_suites,
    weighted,
    wrong,
)

COUNTS: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
NULLABLE = {"reason", "t_jump"}  # ensemble columns that may be missing (None -> NaN in pandas)


def record(suite: str, outcome: str) -> None:
    COUNTS[suite][outcome] += 1


@pytest.fixture(scope="module", autouse=True)
def _report():
    yield
    path = os.environ.get("PHASEKIT_FUZZ_REPORT")
    if path:
        path = path + ".api.json" if not path.endswith(".json") else path.replace(".json", ".api.json")
    report(COUNTS, "generated API calls (valid / failed with a reason / clear error):", path)


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception must reach the test (it is a bug), not be printed."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def classify_api(allowed: set[str], call):
    """Run ``call``; return (outcome, result). ``allowed``: the parameter names a ParameterError
    may name (the arguments of the call)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            result = call()
    except pk.ParameterError as exc:
        assert exc.param in allowed, f"ParameterError names `{exc.param}`, not one of {sorted(allowed)}: {exc}"
        msg = str(exc)
        assert msg.startswith(f"`{exc.param}` ") and "\n" not in msg and "np.float64" not in msg, msg
        return "error", None
    except pk.PhasekitError as exc:
        assert str(exc) and "\n" not in str(exc), repr(exc)
        return "failed", None
    return "valid", result


def check_trajectory(r) -> str:
    assert isinstance(r, pk.core.Trajectory)
    d = r.to_dict()
    assert finite_everywhere(d), d
    assert np.all(np.isfinite(r.x))
    if r.status is pk.Status.FAILED:
        assert r.reason
        return "failed"
    return "valid"


# -- simulate, starts, steady states, thresholds, bodies, laws, options, events ------------------

BODIES = {"prolate": pk.Spheroid(1.5), "oblate": pk.Spheroid(0.6), "tippe": pk.EccentricSphere(0.3)}
LAWS = {"coulomb": pk.Coulomb(0.1), "viscous": pk.Viscous(0.1), "regularised": pk.RegularisedCoulomb(0.1, 1e-3)}


def models():
    return st.tuples(st.sampled_from(sorted(BODIES)), st.sampled_from(sorted(LAWS)),
                     st.sampled_from(["euler", "euler", "vector"])).map(
        lambda t: pk.Model(BODIES[t[0]], LAWS[t[1]], t[2]))


def states(n=6):
    good = st.tuples(reals(0.0, 0.01), reals(0.0, -0.01), reals(10.0, 3.0, 0.0), reals(0.0, 0.1),
                     reals(1.5, 1.0, 0.1, 3.0), reals(0.0, 5.0, 10.0)).map(list)
    return weighted((good, 8), (st.lists(reals(0.0, 1.0), min_size=0, max_size=9), 1), (wrong(), 1))


SIM_NAMES = {"model", "x0", "t_end", "t0", "stop_at", "restitution", "events", "t_eval", "mode", "options", "throw",
             *pk.SolverOptions.names()}


# the suites that run simulations (~95 s of the default run, much of it compiling integrators for
# their odd tolerances and laws) run in the full run only; the default run calls the same functions in
# the fixed cases of tests/core, tests/thresholds and tests/sweep, and keeps the other suites here
@pytest.mark.slow
@hang_guard(1200)
@generated(models,
          states,
          lambda: st.fixed_dictionaries({}, optional={
    "t0": real_or_wrong(0.0, 1.0),
    "stop_at": st.sampled_from(["jump", "none", "touchdown", "never", None, 3]),
    "restitution": real_or_wrong(0.5, 0.0),
    "rtol": real_or_wrong(1e-9, 1e-6, 1e-17),
    "max_steps": st.one_of(st.sampled_from([1, 100, 20000, 0, -1, 2.5, 1e4]), wrong()),
    "backend": st.sampled_from(["auto", "taylor", "cvodes", "rk4", None]),
    "t_eval": st.one_of(st.just([0.1, 0.5]), st.lists(reals(0.5), max_size=3), wrong()),
    "mode": st.sampled_from([None, "flight", "bad", 3]),
    "throw": st.sampled_from([False, True, "yes", None]),
    "events": st.sampled_from([(), [pk.Event("theta", 0.4)], pk.Event("theta", 0.4), [1], None]),
}),
          lambda: real_or_wrong(1.0, 5.0, 0.3),
          **fuzz(300))
def test_api_simulate(model, x0, kw, t_end):
    if model.chart.name == "vector" and isinstance(x0, list) and len(x0) == 6:
        x0 = list(charts.euler_to_vector(np.asarray(x0, float))) if np.all(np.isfinite(x0)) else x0 + [0.0, 0.0]
    outcome, r = classify_api(SIM_NAMES, lambda: pk.simulate(model, x0, t_end, max_wall=2.0, **kw))
    if outcome == "valid":
        outcome = check_trajectory(r)
        if r.ts is not None:
            assert np.all(np.isfinite(r.ys))
    record("api simulate", outcome)


@hang_guard(1800)
@generated(lambda: st.sampled_from(sorted(BODIES)),
          lambda: real_or_wrong(1.5, 0.1, 1.56, 0.0),
          lambda: st.sampled_from(["omega0", "n0", "both", "none"]),
          lambda: real_or_wrong(10.0, 3.0, 1e5),
          **fuzz(120))
def test_api_gyroscopic_start(body, theta0, which, value):
    kw = {"omega0": value, "n0": value} if which == "both" else {} if which == "none" else {which: value}
    outcome, y = classify_api({"body", "theta0", "omega0", "n0"},
                              lambda: pk.gyroscopic_start(BODIES[body], theta0, **kw))
    if outcome == "valid":
        assert y.shape == (6,) and np.all(np.isfinite(y))
    record("api gyroscopic_start", outcome)


def check_fixed_point(fp) -> str:
    assert isinstance(fp, pk.steady.FixedPoint)
    assert np.all(np.isfinite(fp.x)) and np.all(np.isfinite(fp.eigenvalues)) and math.isfinite(fp.residual)
    assert finite_everywhere(fp.to_dict())
    return "valid"


@hang_guard(1800)
@generated(models,
          lambda: st.one_of(states(), states(8)),
          lambda: st.sampled_from(["horizontal", "vertical", "intermediate", "xyz", None]),
          lambda: real_or_wrong(10.0, 2.0, 1e6),
          lambda: st.sampled_from([None, "Omega", "n", "q"]),
          **fuzz(120))
def test_api_find_fixed_point(model, guess, kind, value, fixed):
    outcome, fp = classify_api({"model", "guess", "kind", "value", "fixed"},
                               lambda: pk.steady.find_fixed_point(model, guess, kind=kind, value=value, fixed=fixed))
    if outcome == "valid":
        outcome = check_fixed_point(fp)
    record("api find_fixed_point", outcome)


@hang_guard(1800)
@generated(models,
          lambda: st.sampled_from(["omega0", "n0"]),
          lambda: mostly(reals(10.0, 2.0, 1e6, 12.0), st.sampled_from(["1.5", [1.0], True, 1j]), n_good=12),
          **fuzz(100))
def test_api_fixed_points(model, which, value):
    # exactly one family parameter (not None), of a valid model: fixed_points' own checks of
    # these are not ParameterErrors yet, and a family parameter beyond FAMILY_MAX is named
    # `value` by find_fixed_point
    outcome, pts = classify_api({"omega0", "n0", "value"}, lambda: pk.fixed_points(model, **{which: value}))
    if outcome == "valid":
        # a flip-symmetric body always has the horizontal (omega0) or vertical (n0) state
        assert (pts or not model.body.flip_symmetric) and all(check_fixed_point(p) == "valid" for p in pts)
    record("api fixed_points", outcome)


@hang_guard(1800)
@generated(models,
          lambda: st.one_of(states(), states(8)),
          lambda: st.sampled_from(["state", "horizontal", "", None]),
          **fuzz(100))
def test_api_linearise(model, x, kind):
    outcome, fp = classify_api({"model", "x", "kind"}, lambda: pk.steady.linearise(model, x, kind=kind))
    if outcome == "valid":
        outcome = check_fixed_point(fp)
    record("api linearise", outcome)


DEF_NAMES = {"name", "seed", "mu", "amplitude", "eps", "rtol", "rise_margin", "t_max", "max_steps"}


@pytest.mark.slow  # runs simulations: see test_api_simulate
@hang_guard(1200)
@generated(lambda: st.fixed_dictionaries({"seed": st.sampled_from(["viscous", "sliding", "literal", "other"])}, optional={
    "mu": real_or_wrong(0.1, 0.3), "amplitude": real_or_wrong(0.01, 0.1), "eps": real_or_wrong(1e-3, 1e-20),
    "rtol": real_or_wrong(1e-9, 0.0), "rise_margin": real_or_wrong(0.1), "t_max": real_or_wrong(5.0, 20.0),
    "max_steps": st.one_of(st.sampled_from([1, 1000, 0, -3]), wrong())}),
          lambda: st.fixed_dictionaries({}, optional={
        "tol": real_or_wrong(1e-3, 0.1, 0.0, -1e-3), "n_coarse": st.one_of(st.sampled_from([2, 3, 0, 1, 10**6]), wrong()),
        "hi": real_or_wrong(12.0, 8.0), "lo": real_or_wrong(3.0, 20.0), "window": real_or_wrong(1.5, 0.5)}),
          lambda: real_or_wrong(1.5, 0.6, 1.0),
          **fuzz(80))
def test_api_find_threshold(defn_kw, search_kw, body):
    defn_kw = {"t_max": 5.0, "max_steps": 3000, **defn_kw}  # small budgets unless the case picks its own
    search_kw = {"n_coarse": 2, "tol": 0.1, **search_kw}
    outcome, defn = classify_api(DEF_NAMES, lambda: pk.Definition("fuzz", **defn_kw))
    if outcome != "valid":
        record("api Definition", outcome)
        return
    record("api Definition", "valid")
    if not (isinstance(defn.t_max, float) and defn.t_max <= 20.0 and defn.max_steps <= 20000):
        return  # a valid definition with budgets too large to run in a fuzz case
    outcome, th = classify_api({"body", "a", "tol", "n_coarse", "hi", "lo", "guess", "window", "omega0", "n0"},
                               lambda: pk.find_threshold(defn, body, **search_kw))
    if outcome == "valid":
        assert th.value is None or math.isfinite(th.value)
        assert all(b is None or math.isfinite(b) for b in th.bracket)
        outcome = "failed" if th.status is pk.SearchStatus.FAILED else "valid"
        if outcome == "failed":
            assert th.reason
    record("api find_threshold", outcome)


@hang_guard(1800)
@generated(lambda: st.sampled_from(["spheroid", "eccentric", "custom"]),
          lambda: reals(1.5, 0.3, 0.6),
          lambda: st.one_of(st.none(), real_or_wrong(0.65, 0.4)),
          lambda: st.one_of(st.none(), real_or_wrong(0.4, 0.2)),
          **fuzz(120))
def test_api_bodies(kind, p, A, C):
    import casadi as ca

    def make():
        if kind == "spheroid":
            return pk.Spheroid(p, A=A, C=C)
        if kind == "eccentric":
            return pk.EccentricSphere(p, A=A, C=C)
        return pk.CustomBody(lambda th: ca.sqrt(p**2 * ca.cos(th) ** 2 + ca.sin(th) ** 2), A=A, C=C)

    outcome, body = classify_api({"a", "offset", "A", "C", "height"}, make)
    if outcome == "valid":
        assert math.isfinite(body.A) and math.isfinite(body.C) and all(map(math.isfinite, body.h(0.7)))
    record("api bodies", outcome)


@hang_guard(1800)
@generated(lambda: st.sampled_from(["Coulomb", "Viscous", "RegularisedCoulomb", "friction_law"]),
          lambda: real_or_wrong(0.1, 0.0, 1e3),
          lambda: real_or_wrong(1e-3, 1e-15),
          lambda: st.sampled_from(["coulomb", "viscous", "dry", None]),
          **fuzz(100))
def test_api_friction_laws(kind, mu, eps, name):
    def make():
        if kind == "RegularisedCoulomb":
            return pk.RegularisedCoulomb(mu, eps)
        if kind == "friction_law":
            return friction.friction_law(name, mu, eps)
        return getattr(pk, kind)(mu)

    outcome, law = classify_api({"mu", "eps", "friction", "name"}, make)
    if outcome == "valid":
        assert math.isfinite(law.mu) and np.all(np.isfinite(law.force([0.1, -0.2], 1.0)))
    record("api friction laws", outcome)


@hang_guard(1800)
@generated(lambda: st.fixed_dictionaries({}, optional={
    "rtol": real_or_wrong(1e-9, 1e-16, 0.1, 0.2), "atol": st.one_of(st.none(), real_or_wrong(1e-11)),
    "backend": st.sampled_from(["auto", "taylor", "cvodes", "idas", "rk4", None]),
    "max_steps": st.one_of(st.sampled_from([1, 10**7, 0, -1, 2.0, 2.5]), wrong()),
    "max_wall": real_or_wrong(2.0, 600.0), "max_switches": st.one_of(st.sampled_from([1, 0, 10]), wrong()),
    "track_minima": st.sampled_from([True, False, 1, None]), "dense": st.sampled_from([True, False, "no"])}),
          **fuzz(100))
def test_api_solver_options(kw):
    outcome, opts = classify_api(set(pk.SolverOptions.names()), lambda: pk.SolverOptions(**kw))
    if outcome == "valid":
        assert finite_everywhere(opts.to_dict())
    record("api SolverOptions", outcome)


@pytest.mark.slow  # runs simulations: see test_api_simulate
@hang_guard(1800)
@generated(lambda: mostly(st.sampled_from(["theta", "R", "Lambda", "energy"]), st.sampled_from(["", "nonsense"]), wrong(),
              n_good=10),
          lambda: real_or_wrong(0.4, 0.0, 1.0),
          lambda: mostly(st.sampled_from([-1, 0, 1]), st.sampled_from([2, True, 0.5]), n_good=8),
          lambda: mostly(st.sampled_from([True, False]), st.just("yes"), n_good=8),
          lambda: mostly(st.sampled_from([None, ["sliding"], ["rolling", "flight"]]), st.sampled_from([["bad"], 3]), n_good=8),
          **fuzz(100))
def test_api_events(on, level, direction, terminal, modes):
    outcome, ev = classify_api({"on", "level", "direction", "terminal", "name", "modes", "arm_after", "stop"},
                               lambda: pk.Event(on, level, direction=direction, terminal=terminal, modes=modes))
    if outcome == "valid":
        # an event on a name that is no observable is refused when a run watches it
        outcome, r = classify_api(SIM_NAMES | {"on", "name"}, lambda: pk.simulate(
            pk.Model(BODIES["prolate"], LAWS["coulomb"]), [0, 0, 10, 0, 1.5, 0], 0.5, events=[ev], max_wall=2.0))
        if outcome == "valid":
            outcome = check_trajectory(r)
    record("api Event", outcome)


@pytest.fixture(scope="module")
def trajectory():
    return pk.simulate(pk.Model(BODIES["prolate"], LAWS["coulomb"]), pk.gyroscopic_start(BODIES["prolate"], 1.5,
                                                                                           omega0=10.0), 5.0)


@hang_guard(1800)
@generated(lambda: st.one_of(st.lists(reals(0.0, 1.0, 2.5, 5.0, 6.0, -1.0), max_size=5), reals(2.0, 7.0), wrong()),
          **fuzz(120))
def test_api_trajectory_sample(trajectory, times):
    outcome, df = classify_api({"times"}, lambda: trajectory.sample(times))
    if outcome == "valid":
        assert np.all(np.isfinite(df.drop(columns=["mode"]).to_numpy(dtype=float)))
    record("api Trajectory.sample", outcome)


# -- long calls and their options: ensembles, searches with budgets, units, scenes, samples, hopping

PROLATE, OBLATE = BODIES["prolate"], BODIES["oblate"]


def starts():
    """Lists of 1-3 starts: mostly gyroscopic ones of the prolate body, sometimes junk."""
    good = st.lists(st.sampled_from([9.0, 10.5, 12.0, 20.0]), min_size=1, max_size=3).map(
        lambda ws: [pk.gyroscopic_start(PROLATE, np.pi / 2 - 0.01, omega0=w) for w in ws])
    return mostly(good, st.just([]), st.just([[1.0, 2.0]]), st.just([[0, 0, 10, 0, math.nan, 0]]), wrong(), n_good=30)


ENSEMBLE_NAMES = SIM_NAMES | {"starts", "scheduler", "processes", "progress", "max_wall_total"}


@pytest.mark.slow  # runs simulations: see test_api_simulate
@hang_guard(1200)
@generated(lambda: st.sampled_from(sorted(LAWS)),
          lambda: starts(),
          lambda: mostly(st.sampled_from([1.0, 3.0, 50.0]), st.sampled_from([0.0, -1.0, math.nan, math.inf, -1e300]), wrong(),
              n_good=12),
          lambda: st.fixed_dictionaries({}, optional={
    "processes": mostly(st.sampled_from([1, 1, 2]), st.sampled_from([0, -1, 2.5, "2", True]), n_good=20),
    "progress": mostly(st.sampled_from([None, False, True]), st.just("yes"), n_good=10),
    "max_wall_total": mostly(st.sampled_from([None, 30.0, 1e-6]), st.sampled_from([0.0, -1.0, math.nan, "x"]), n_good=16),
    "stop_at": mostly(st.sampled_from(["jump", "none", "touchdown"]), st.just("bad"), n_good=10),
    "restitution": mostly(st.sampled_from([0.5, 0.0, 0.9]), st.sampled_from([-1.0, math.nan]), n_good=10),
    "max_steps": mostly(st.sampled_from([100, 5000, 5_000_000]), st.just(0), n_good=10),
    "events": mostly(st.sampled_from([(), [pk.Event("theta", 1.0, terminal=False, name="th")]]), st.just([1]), n_good=10),
    "scheduler": mostly(st.none(), st.sampled_from([3.0, "", "not an address"]), n_good=20),
    "t_eval": mostly(st.none(), st.just([0.5]), n_good=10)}),
          **fuzz(150))
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


def definition_kwargs():
    return st.fixed_dictionaries({"seed": st.sampled_from(["sliding", "sliding", "viscous", "literal"])}, optional={
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


@pytest.mark.slow  # runs simulations: see test_api_simulate
@hang_guard(1200)
@generated(lambda: definition_kwargs(),
          lambda: st.sampled_from([1.5, 0.6, 2.0]),
          lambda: st.fixed_dictionaries({}, optional={
    "max_wall": mostly(st.sampled_from([None, 5.0, 1e-3]), st.sampled_from([0.0, -1.0, math.nan, "x", True]), n_good=8),
    "progress": st.sampled_from([None, False, True, 1]),
    "engine": st.sampled_from(["scalar", "scalar", "batch", "x"]),
    "levels": st.sampled_from([1, 2, 0, 9]), "tol": st.sampled_from([0.05, 0.2, 0.0]),
    "guess": st.sampled_from([None, 9.7, 8.5, -1.0])}),
          **fuzz(120))
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


@hang_guard(1200)
@generated(lambda: mostly(st.sampled_from([8.0, 12.0]), st.sampled_from([-1.0, math.nan]), n_good=6),
          lambda: st.fixed_dictionaries({}, optional={
           "max_wall": mostly(st.sampled_from([None, 2.0, 1e-3]), st.just(-1.0), n_good=6),
           "lo": mostly(st.sampled_from([1e-3, 0.01]), st.sampled_from([0.3, 0.6]), n_good=6),
           "hi": mostly(st.sampled_from([0.05, 0.2]), st.just(0.0), n_good=6),
           "tol": mostly(st.sampled_from([0.2, 0.5]), st.just(0.0), n_good=6),
           "progress": st.sampled_from([None, False])}),
          **fuzz(60))
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


def lengths():
    return st.sampled_from(["21.5 mm", "0.02 m", "1 inch", "-1 mm", "0 mm", "1 s", "", "mm", "1e400 m", "nan m", "abc"])


KIND_VALUES = {"length": "57 mm", "time": "12 ms", "rate": "30 rev/s", "speed": "0.5 m/s", "mass": "57 g",
               "force": "0.5 N", "energy": "1 mJ"}


@hang_guard(1800)
@generated(lambda: mostly(st.sampled_from(["21.5 mm", "0.02 m", "1 inch", "3 km", "1e-6 mm"]), lengths(), wrong(), st.just(21.5),
              n_good=12),
          lambda: mostly(st.sampled_from([None, "9.81 m/s**2", "1.62 m/s**2"]), st.sampled_from(["9.81 m", "-9.81 m/s**2"]), n_good=10),
          lambda: mostly(st.sampled_from([None, "57 g", "2 kg"]), st.sampled_from(["0 g", "5 m"]), n_good=10),
          lambda: mostly(st.sampled_from(sorted(KIND_VALUES)), st.sampled_from(["bogus", None]), n_good=14),
          lambda: reals(1.0, 12.5, 0.0, -3.0),
          **fuzz(200))
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


@hang_guard(1800)
@generated(lambda: mostly(st.sampled_from([("prolate", 1.5), ("prolate", 2.0), ("oblate", 0.6), ("oblate", 0.8)]),
              st.sampled_from([("prolate", 0.6), ("sideways", 1.5), ("prolate", 1.0)]), st.tuples(st.just("prolate"),
                                                                                                      reals(1.5)), n_good=10),
          lambda: mostly(st.sampled_from([(), (10.0,)]), st.sampled_from([(-1.0,), "abc", (math.nan,)]), n_good=10),
          lambda: mostly(st.sampled_from([frozenset({"surface", "axes"}), frozenset({"fixed_points"}), frozenset({"exact_boundary"}),
                               frozenset({"surface", "colorbar"}), frozenset({"trajectories"})]),
              st.sampled_from([{"bogus"}, "surface"]), n_good=10),
          lambda: st.fixed_dictionaries({}, optional={
           "resolution": mostly(st.sampled_from([2, 8, 12]), st.sampled_from([1, 5000]), n_good=8),
           "omega_range": mostly(st.sampled_from([None, (5.0, 20.0)]), st.sampled_from([(3.0, 1.0), (1, 2, 3)]), n_good=8),
           "theta_range": mostly(st.sampled_from([None, (0.1, 1.5)]), st.just((0.0, 4.0)), n_good=8),
           "exact_lambda": mostly(st.sampled_from([None, 0.0, 0.5]), st.sampled_from([1e4, math.nan]), n_good=8),
           "seed_distance": mostly(st.sampled_from([0.01, 0.05]), st.sampled_from([0.0, 2.0]), n_good=8),
           "mu": mostly(st.sampled_from([0.1, 0.3]), st.just(-0.1), n_good=8)}),
          **fuzz(100))
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


@hang_guard(1800)
@generated(lambda: st.sampled_from(["jump", "hops", "stuck", "vector", "regularised"]),
          lambda: st.one_of(st.lists(st.floats(-0.2, 1.2), min_size=0, max_size=6),
                 st.lists(reals(0.5, 0.0, 1.0), max_size=3), wrong()),
          **fuzz(200))
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


@hang_guard(1800)
@generated(lambda: st.fixed_dictionaries({}, optional={
    "settle": st.sampled_from([None, True, False, pk.core.Settle(), {"window": 5.0, "tol": 0.1}, {"windows": 1}, "x",
                               {"window": math.nan}]),
    "bounce_stop": mostly(st.sampled_from([1e-4, 1e-6, 1e-2]), st.sampled_from([0.0, -1.0, 2.0, math.nan, "x"])),
    "bounce_tail": mostly(st.sampled_from([None, 100, 3]), st.sampled_from([0, -1, 2.5, "x"])),
    "max_switches": mostly(st.sampled_from([None, 10, 10**6]), st.sampled_from([0, -1, 2.5, True])),
    "max_dense_mb": mostly(st.sampled_from([None, 1000.0, 0.5, 4]), st.sampled_from([0, -1.0, math.inf, math.nan, "x"])),
    "max_wall": real_or_wrong(2.0, 600.0)}),
          **fuzz(100))
def test_api_new_solver_options(kw):
    outcome, opts = classify_api(set(pk.SolverOptions.names()) | {"window", "tol", "R_floor"},
                                 lambda: pk.SolverOptions(**kw))
    if outcome == "valid":
        d = opts.to_dict()
        assert finite_everywhere(d) and json.loads(json.dumps(d)) == d
        assert opts.switch_limit(400.0) >= (opts.max_switches or 10_000)
        assert pk.SolverOptions(**{k: v for k, v in d.items()}) == opts  # from its JSON, the same options
    record("api SolverOptions (settle, bounces, switches)", outcome)


@pytest.mark.slow  # runs simulations: see test_api_simulate
@hang_guard(2400)
@generated(lambda: st.sampled_from([10.0, 20.0, 30.0]),
          lambda: real_or_wrong(0.5, 0.0, 0.95, 1.0),
          lambda: real_or_wrong(2.0, 5.0, 0.5),
          lambda: st.fixed_dictionaries({}, optional={
           "settle": st.sampled_from([None, True, pk.core.Settle(window=0.5, tol=0.5)]),
           "bounce_stop": st.sampled_from([1e-4, 1e-3, 1e-6]), "bounce_tail": st.sampled_from([None, 100, 2]),
           "max_switches": st.sampled_from([None, 50, 3]), "max_steps": st.sampled_from([5_000_000, 2000]),
           "stop_at": st.sampled_from(["none", "none", "touchdown", "jump"])}),
          **fuzz(150))
def test_api_hopping_runs(omega0, e, t_span, kw):
    """Hopping starts (a = 1.5, sliding branch) over a short span past the jump."""
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
    thin = thin_suites(COUNTS)
    assert not thin, thin
