"""Regression tests for the cases of issue 17, each named after the bug it pins."""

import ast
import dataclasses
import pathlib
import re
import subprocess
import sys

import phasekit as pk
import phasekit.studies as ps
from phasekit import cli
from phasekit.core.hybrid import Mode
from phasekit.core.resets import project_no_slip, sliding_direction
from phasekit.steady import fixedpoints, precessions
from phasekit.sweep import ResultStore
from phasekit.theory import gyroscopic

import numpy as np
import pytest

from .helpers import run_cli, strict_json

ROOT = pathlib.Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception inside the CLI is a test failure, not a one-line message."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def run_subprocess(*args):
    p = subprocess.run([sys.executable, "-m", "phasekit", *map(str, args)], capture_output=True, text=True,
                       timeout=300, cwd=ROOT)
    return p.returncode, p.stdout, p.stderr


# -- 1. zero slip -------------------------------------------------------------------------------

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


# -- 2. Newton at every scale -------------------------------------------------------------------


@pytest.mark.parametrize("args", [
    ["--a", 1e3, "--mu", 0.1, "--omega0", 10],
    ["--a", 1.5, "--mu", 0.1, "--omega0", 1e6],
    ["--a", 1.5, "--mu", 0.1, "--omega0", 10, "--slip-eps", 1e-12],
    ["--a", 1.5, "--mu", 1e3, "--omega0", 10, "--friction", "viscous"],
    ["--a", 0.6, "--mu", 0.1, "--n0", 1e5],
], ids=["a=1e3", "omega0=1e6", "eps=1e-12", "viscous-mu=1e3", "n0=1e5"])
def test_newton_absolute_residual_missed_fixed_points_at_large_scales(args):
    code, out, err = run_cli("fixed-points", *args, "--json")
    assert code == 0, err
    d = strict_json(out)
    value = float(args[args.index("--omega0") + 1]) if "--omega0" in args else float(args[args.index("--n0") + 1])
    kind = "horizontal" if "--omega0" in args else "vertical"
    [fp] = [p for p in d["fixed_points"] if p["kind"] == kind]
    st = fp["state"]
    if kind == "horizontal":
        assert st["Omega"] == pytest.approx(value, rel=1e-12) and st["theta"] == pytest.approx(np.pi / 2, abs=1e-12)
        # the exact state (U = V = Lambda = n = 0 above); its residual is the rounding of terms
        # ~ Omega^2, or with eps = 1e-12 of mu R u/eps with u ~ Omega 1e-16: never an absolute 1e-10
        if "--slip-eps" not in args:
            assert fp["residual"] <= 1e-13 * max(1.0, value**2)
        assert all(st[k] == 0.0 for k in ("U", "V", "Lambda", "n"))
    else:
        assert st["n"] == pytest.approx(value, rel=1e-12) and st["theta"] == 0.0
    assert d["linearised_law"] == ("viscous" if "viscous" in args else
                                   "coulomb-regularised" if "--slip-eps" in args else "coulomb-rolling")


def test_intermediate_states_found_by_newton_satisfy_the_closed_form_balance():
    body = pk.Spheroid(0.3)
    [inter] = [p for p in pk.fixed_points(pk.Model(body, pk.Viscous(0.1)), omega0=3.0) if p.kind == "intermediate"]
    assert ps.intermediate_omega(body, inter.y[4]) == pytest.approx(3.0, rel=1e-12)
    assert inter.residual < 1e-14


def test_mu_beyond_the_cap_is_a_clear_error_not_a_convergence_error():
    code, out, err = run_cli("fixed-points", "--a", 1.5, "--mu", 1e6, "--omega0", 10, "--json")
    assert code == 2 and strict_json(out)["parameter"] == "--mu"
    assert err.strip() == "phasekit: error: --mu must lie in [0, 1000], got 1000000.0."


def test_convergence_error_states_the_tolerance_and_reads_an_intermediate():
    model = pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1))
    guess = precessions.intermediate_state(model.body, 0.8)  # Omega* ~ 2.0 here; ask for Omega = 1: no such state
    with pytest.raises(pk.ConvergenceError) as info:
        pk.steady.find_fixed_point(model, guess, kind="intermediate", value=1.0)
    msg = str(info.value)
    assert msg.startswith("Newton did not converge to an intermediate fixed point with Omega = 1")
    assert "above the tolerance 1e-10" in msg


def test_unstable_manifold_start_beyond_a_simulation_is_one_line_not_a_traceback():
    code, out, err = run_subprocess("simulate", "--a", 1.5, "--mu", 0.1, "--unstable-manifold", "horizontal",
                                    "--omega0", 1e6)
    assert code == 2 and out == ""
    assert err.strip().splitlines() == [err.strip()] and err.startswith("phasekit: error: --omega0 ")


# -- 3. stdout holds only JSON; no NaN or inf ---------------------------------------------------


@pytest.mark.parametrize("flag, value", [("--mu", "1e308"), ("--omega0", "1e300"), ("--omega0", "1e-300")])
def test_extreme_values_give_one_json_error_on_stdout_and_one_line_on_stderr(flag, value):
    args = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--json"]
    args[args.index(flag) + 1] = value
    code, out, err = run_subprocess(*args)
    d = strict_json(out)
    assert code == 2 and d["status"] == "error" and d["parameter"] == flag
    assert err.strip() == f"phasekit: error: {d['message']}" and f"got {float(value)!r}" in d["message"]


def test_stdout_is_strict_json_for_a_run_that_computes(tmp_path):
    # a fresh compiled-integrator cache: compiling must not print on stdout either
    p = subprocess.run([sys.executable, "-m", "phasekit", "simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic",
                        "--theta0", "1.5", "--omega0", "10", "--t-end", "30", "--json"], capture_output=True, text=True,
                       timeout=300, cwd=ROOT, env={**__import__("os").environ, "PHASEKIT_CACHE": str(tmp_path)})
    assert p.returncode == 0 and strict_json(p.stdout)["status"] == "jumped"


def test_non_finite_result_ends_failed_saying_where(monkeypatch):
    monkeypatch.setitem(cli.COMMANDS, "gyroscopic",
                        lambda args: {"status": "completed", "theta": [1.0, float("nan")], "J": 1.0})
    code, out, _ = run_cli("gyroscopic", "--a", 1.5, "--mu", 0.1, "--omega0", 10, "--theta0", 1.5, "--t", 0, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and d["reason"] == "non-finite value in the result at theta[1]"
    assert d["theta"] == [1.0, None]


# -- 4. nothing hangs ---------------------------------------------------------------------------


def test_rtol_beyond_double_precision_is_refused_instead_of_running_forever():
    code, _, err = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 10,
                           "--rtol", 1e-300)
    assert code == 2 and err.strip() == "phasekit: error: --rtol must lie in [1e-16, 0.1], got 1e-300."


@pytest.mark.parametrize("kw, name", [(dict(tol=0.0), "tol"), (dict(tol=-1e-3), "tol"), (dict(n_coarse=0), "n_coarse"),
                                      (dict(n_coarse=1), "n_coarse")])
def test_threshold_search_refuses_tolerances_and_counts_that_loop_or_mislead(kw, name):
    with pytest.raises(pk.ParameterError, match=f"^`{name}` "):
        pk.find_threshold(pk.thresholds.DEFAULT_DEFINITIONS[0], 1.5, **kw)


@pytest.mark.parametrize("budget, reason", [(["--max-steps", 3000], "step limit"), (["--max-wall", 0.3], "wall-time")])
def test_long_stop_at_none_run_ends_failed_at_its_budget(budget, reason):
    code, out, _ = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 10,
                           "--stop-at", "none", "--t-end", 1e5, *budget, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and reason in d["reason"] and d["t_end"] < 1e5


def test_gyroscopic_numeric_with_no_times_is_refused_instead_of_hanging():
    with pytest.raises(pk.ParameterError, match="^`T` "):
        gyroscopic.gyroscopic_numeric(pk.Spheroid(1.5), 1.0, 10.0, None)


# -- 5. result files survive a kill -------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class Row:
    key: str
    value: float
    note: str


@pytest.mark.parametrize("cut", ["inside the last text field", "inside a number"])
def test_torn_last_row_is_recomputed_and_the_next_row_starts_a_new_line(tmp_path, cut):
    csv, manifest = tmp_path / "rows.csv", tmp_path / "rows.json"
    store = ResultStore(csv, manifest, Row, {})
    store.add(Row("a", 1.0, "first"))
    store.add(Row("b", 2.5, "second row"))
    text = csv.read_text()
    # a kill mid-write: the cut text field still parses, so the missing newline must decide
    cut_at = len(text) - 5 if cut == "inside the last text field" else text.index("2.5") + 2
    csv.write_text(text[:cut_at])
    store = ResultStore(csv, manifest, Row, {})
    assert store.dropped == 1 and "a" in store and "b" not in store
    store.add(Row("c", 3.0, "third"))
    lines = csv.read_text().splitlines()
    assert lines == ["key,value,note", "a,1.0,first", "c,3.0,third"]


# -- 6. the public API validates its arguments ---------------------------------------------------

M = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))
Y = [0.0, 0.0, 10.0, 0.0, 1.5, 0.0]


@pytest.mark.parametrize("call, name", [
    (lambda: pk.simulate(None, Y, 1.0), "model"),
    (lambda: pk.simulate(M, Y, 1.0, restitution=None), "restitution"),
    (lambda: pk.simulate(M, [0, 0, 1, 0, 0.0, 1], 1.0), "x0"),  # theta = 0 in the Euler chart
    (lambda: pk.simulate(M, Y, 1.0, t0=-1e300), "t0"),
    (lambda: pk.simulate(M, Y, 1.0, mode="bad"), "mode"),
    (lambda: pk.simulate(M, Y, 1.0, events=pk.Event("theta", 0.4)), "events"),
    (lambda: pk.simulate(M, Y, 1.0, throw="yes"), "throw"),
    (lambda: pk.steady.find_fixed_point(M, [1.0, 2.0, 3.0], kind="horizontal", value=10.0), "guess"),
    (lambda: pk.steady.find_fixed_point(M, pk.steady.horizontal_state(10.0), kind="xyz", value=10.0), "kind"),
    (lambda: pk.steady.find_fixed_point(M, pk.steady.horizontal_state(10.0), kind="horizontal", value=10.0, fixed="q"), "fixed"),
    (lambda: pk.steady.find_fixed_point(M.with_chart("vector"), pk.steady.vertical_state(10.0), kind="horizontal", value=10.0),
     "kind"),  # the vector chart's Newton system is the vertical family's
    (lambda: pk.steady.linearise(M, [np.nan] * 6), "x"),
    (lambda: pk.steady.linearise(M, [0, 0, 1e308, 0, 1, 1e308]), "x"),  # finite, but the Jacobian overflows
    (lambda: pk.steady.linearise(None, Y), "model"),
    (lambda: pk.theory.gyroscopic_solution(pk.Spheroid(1.5), 1.5, omega0=10.0, T=[]), "T"),
    (lambda: pk.theory.gyroscopic_solution(pk.Spheroid(1.5), 1.5, omega0=10.0, T=[np.nan]), "T"),
    (lambda: pk.theory.gyroscopic_closed(1.5, 0.0, 1.0, [0.0, 1.0]), "J"),
    (lambda: gyroscopic.rise_time(1.0, 1.0, 1.0), "a"),
    (lambda: fixedpoints.continue_family(M, "horizontal", []), "values"),
    (lambda: fixedpoints.continue_family(M, "intermediate", [2.0, 2.1]), "start"),
    (lambda: pk.Definition("x", "viscous", rtol=0), "rtol"),
    (lambda: pk.core.to_chart("xyz", Y), "chart"),
    (lambda: pk.steady.unstable_manifold_start(pk.Spheroid(1.5), pk.Coulomb(0.1), state="horizontal", delta=0.01), "omega0"),
    (lambda: pk.steady.unstable_manifold_start(pk.Spheroid(1.5), pk.Coulomb(0.1), state="horizontal", delta=0.01,
                                        omega0=10.0, branch="x"), "branch"),
    (lambda: pk.theory.horizontal_stability_threshold(-1.0, 0.4, 1.5), "A"),
])
def test_public_api_raises_parameter_error_naming_the_argument(call, name):
    with pytest.raises(pk.ParameterError) as info:
        call()
    assert info.value.param == name and str(info.value).startswith(f"`{name}` ")
    assert "np.float64" not in str(info.value)


# -- 7. silently wrong --------------------------------------------------------------------------


def test_fixed_points_without_a_vector_model_returns_the_vertical_state():
    pts = pk.fixed_points(pk.Model(pk.Spheroid(0.6), pk.Coulomb(0.1)), n0=10.0)
    [v] = [p for p in pts if p.kind == "vertical"]
    assert v.y[4] == 0.0 and v.y[5] == pytest.approx(10.0, rel=1e-14)


def test_omega_is_not_taken_for_omega0_by_abbreviation():
    code, out, err = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega", 10,
                             "--json")
    assert code == 2 and strict_json(out)["parameter"] == "--omega"
    assert err.strip() == "phasekit: error: unrecognized arguments: --omega 10 (did you mean --omega0?)"


@pytest.mark.parametrize("extra, flag", [(["--restitution", "0.5"], "--restitution"),
                                         (["--slip-eps", "1e-3", "--friction", "viscous"], "--slip-eps")])
def test_options_without_effect_warn_in_one_line_on_stderr(extra, flag):
    code, out, err = run_subprocess("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5,
                                    "--omega0", 10, "--t-end", 5, "--json", *extra)
    assert code == 0 and strict_json(out)["status"] == "completed"
    [line] = err.strip().splitlines()
    assert line.startswith(f"phasekit: warning: {flag} has no effect")


def test_error_names_the_flag_typed_and_prints_plain_numbers():
    code, _, err = run_cli("simulate", "--a", 1e308, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 10)
    assert code == 2 and err.strip() == "phasekit: error: --a must lie in [0.0001, 10000], got 1e+308."
    code, _, err = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 0.0)
    assert code == 2 and err.strip().endswith("got 0.0.") and "np.float64" not in err


# -- 8. defaults that agree and say so -----------------------------------------------------------


def test_cli_fixed_points_and_api_agree_by_default_on_coulomb():
    code, out, _ = run_cli("fixed-points", "--a", 0.5, "--mu", 0.1, "--n0", 8, "--json")
    d = strict_json(out)
    [v] = [p for p in d["fixed_points"] if p["kind"] == "vertical"]
    [api] = [p for p in pk.fixed_points(pk.Model(pk.Spheroid(0.5), pk.Coulomb(0.1)), n0=8.0) if p.kind == "vertical"]
    assert code == 0 and d["model"]["law"] == "coulomb" and d["linearised_law"] == "coulomb-rolling"
    assert v["classification"] == api.classification and v["n_unstable"] == api.n_unstable == 0
    code, out, _ = run_cli("simulate", "--a", 0.5, "--mu", 0.1, "--gyroscopic", "--theta0", 0.1, "--n0", 8,
                           "--t-end", 1, "--json")
    assert strict_json(out)["model"]["law"] == "coulomb"


def test_help_says_for_which_law_each_stability_statement_holds():
    code, out, _ = run_subprocess("fixed-points", "--help")
    assert code == 0
    text = " ".join(out.split())
    assert "--friction coulomb (default) exact stick-slip" in text and "rolling (no-slip) linearisation" in text
    assert "--friction viscous part I's wet friction" in text and "Omega0 > sqrt(5) (prolate)" in text
    assert "weak friction (mu below ~0.8)" in text
    assert "(default: coulomb" in text


def _library_messages():
    """String pieces of every raise and warnings.warn in the library outside the CLI and the
    scaffold of study scripts (both speak to a command line)."""
    for path in sorted((ROOT / "phasekit").rglob("*.py")):
        if path.parent.name in ("cli", "studies") or path.name == "study.py":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            is_warn = isinstance(node, ast.Call) and getattr(node.func, "attr", None) == "warn"
            if isinstance(node, ast.Raise) or is_warn:
                for sub in ast.walk(node):
                    if isinstance(sub, ast.Constant) and isinstance(sub.value, str):
                        yield path.name, sub.value


def test_library_messages_give_python_advice_not_cli_flags():
    # (naming the format of `simulate --json` output is not advice)
    flagged = [(f, s) for f, s in _library_messages() if re.search(r"(?<![\w-])--(?!json\b)[A-Za-z]", s)]
    assert flagged == []


def test_prolate_start_given_n0_warns():
    with pytest.warns(UserWarning, match="`n0` given for a prolate body"):
        pk.gyroscopic_start(pk.Spheroid(1.5), 1.0, n0=10.0)


# -- 9. human output ----------------------------------------------------------------------------


def test_human_output_is_a_short_summary_and_events_lists_every_event():
    args = ["simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 10, "--stop-at", "none",
            "--t-end", 40]
    code, out, _ = run_cli(*args)
    n_events = int(re.search(r"^(\d+) events", out, re.M).group(1))
    assert code == 0 and n_events > 30 and len(out.splitlines()) <= 10
    code, out_events, _ = run_cli(*args, "--events")
    assert len(out_events.splitlines()) == len(out.splitlines()) + n_events


def test_version_flag():
    code, out, _ = run_subprocess("--version")
    assert code == 0 and out.strip() == f"phasekit {pk.__version__}"


# -- the CLI never shows a traceback --------------------------------------------------------------


def test_unexpected_exception_is_one_line_with_exit_1(monkeypatch):
    monkeypatch.delenv(cli.DEBUG_ENV)

    def boom(args):
        raise RuntimeError("a bug\nwith a second line")

    monkeypatch.setitem(cli.COMMANDS, "fixed-points", boom)
    code, out, err = run_cli("fixed-points", "--a", 1.5, "--mu", 0.1, "--omega0", 10, "--json")
    assert code == 1 and strict_json(out)["status"] == "failed"
    line = "phasekit: error: internal error: RuntimeError: a bug (please report it; set PHASEKIT_DEBUG=1 for the traceback)"
    assert err.strip().splitlines() == [line]
    monkeypatch.setenv(cli.DEBUG_ENV, "1")  # and tests see the real exception
    with pytest.raises(RuntimeError):
        run_cli("fixed-points", "--a", 1.5, "--mu", 0.1, "--omega0", 10)


def test_interrupt_is_one_line_with_exit_130(monkeypatch):
    def interrupted(args):
        raise KeyboardInterrupt

    monkeypatch.setitem(cli.COMMANDS, "simulate", interrupted)
    code, out, err = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--state", *REST, "--json")
    assert code == 130 and strict_json(out)["status"] == "interrupted" and len(err.strip().splitlines()) == 1


def test_solver_failure_is_one_line_with_exit_1(monkeypatch):
    import phasekit.steady.fixedpoints as fpm

    monkeypatch.setattr(fpm, "NEWTON_RTOL", -1.0)  # no iterate can pass: Newton "fails"
    code, out, err = run_cli("fixed-points", "--a", 1.5, "--mu", 0.1, "--omega0", 10, "--json")
    assert code == 1 and strict_json(out)["status"] == "failed"
    [line] = err.strip().splitlines()
    assert line.startswith("phasekit: error: Newton did not converge to a horizontal fixed point with Omega = 10: ")


def test_a_diverging_integration_ends_failed_at_its_last_finite_state(monkeypatch):
    """A run whose integrator returns a non-finite time or state used to keep a NaN segment
    (t = nan in the result); it now ends "failed" where the state was last finite."""
    from phasekit.core.engines import TaylorEngine

    real = TaylorEngine.propagate

    def diverging(self, *args, **kwargs):
        prop = real(self, *args, **kwargs)
        prop.t, prop.x = float("nan"), prop.x * np.nan
        return prop

    monkeypatch.setattr(TaylorEngine, "propagate", diverging)
    model = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))
    x0 = pk.gyroscopic_start(model.body, 1.5, omega0=10.0)
    r = pk.simulate(model, x0, 5.0)
    assert r.status is pk.Status.FAILED and r.reason == "the integration diverged after t = 0 (non-finite state)"
    assert r.t == 0.0 and np.array_equal(r.x, x0)
    d = r.to_dict()
    assert d["t_end"] == 0.0 and all(np.isfinite(list(d["state_end"].values())))


def test_api_simulate_refuses_rates_beyond_double_precision():
    model = pk.Model(pk.Spheroid(0.6), pk.Coulomb(0.1))
    with pytest.raises(pk.ParameterError, match="^`x0` must have entries of at most 100000"):
        pk.simulate(model, [0.0, 0.0, 10.0, 76523426.0, 3.0, 5.0], 1.0)


@pytest.mark.parametrize("a, family, below, above", [(1.5, "--omega0", 2.2, 2.3), (0.6, "--n0", 1.0, 1.08)])
def test_help_stability_statements_hold_for_the_law_they_name(a, family, below, above):
    """--help: with --friction viscous the horizontal state of a uniform prolate spheroid loses
    stability at Omega0 = sqrt(5) (2.236) and the vertical oblate spin at n0 = sqrt(5 a^3)
    (1.039 for a = 0.6); with the default exact Coulomb law the same states are neutral."""
    kind = "horizontal" if family == "--omega0" else "vertical"

    def state(value, *law):
        code, out, _ = run_cli("fixed-points", "--a", a, "--mu", 0.1, family, value, *law, "--json")
        assert code == 0
        return next(p for p in strict_json(out)["fixed_points"] if p["kind"] == kind)

    assert state(below, "--friction", "viscous")["n_unstable"] == 0
    assert state(above, "--friction", "viscous")["n_unstable"] > 0
    for value in (below, above):
        assert state(value)["classification"] == "neutral (spectrally stable)"


def test_wall_budget_holds_for_runs_of_many_short_segments():
    """Stick-slip chatter (mu = 1000): ~1000 segments, each far below the 20 000-step chunk
    after which the integrator checked the clock, so --max-wall 0.5 let a 7 s run complete."""
    code, out, _ = run_cli("simulate", "--a", 0.6, "--mu", 1000, "--state", 0, 0, 10, 0, 1, 0, "--max-wall", 0.5, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and d["reason"].startswith("wall-time limit (0.5 s) reached at t = ")
    assert d["t_end"] < 200 and d["wall_s"] < 3.0


def test_reader_closing_the_pipe_early_ends_quietly_without_a_traceback():
    # `phasekit ... | head -c 20`: the reader leaves before the JSON is written
    p = subprocess.Popen([sys.executable, "-m", "phasekit", "simulate", "--a", "1.5", "--mu", "0.1", "--state", "0", "0",
                          "0", "0", "1.0", "0", "--t-end", "1", "--json"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.close()
    err = p.stderr.read().decode()
    assert p.wait(timeout=120) == 1
    assert "Traceback" not in err and "BrokenPipe" not in err
