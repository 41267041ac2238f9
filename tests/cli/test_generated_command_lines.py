"""Generated command lines: every case (extreme magnitudes, NaN, inf, zero, negative, junk text,
wrong lengths, flags of other commands) of ``phasekit simulate``, ``fixed-points`` and
``gyroscopic`` must end in one of three outcomes:

* ``valid``  - exit 0 and a result, with no NaN or inf anywhere in it;
* ``failed`` - exit 1: a run with status "failed" and its reason (a run that hits its
  ``--max-wall`` budget says so), or one line naming the solver's error;
* ``error``  - exit 2: one line on stderr naming the flag exactly as typed (with ``--json``, the
  same message as strict JSON on stdout).

Anything else (a traceback, NaN on stdout, two JSON documents, a flag the message invents)
fails the test; a hang fails it by its timeout. Cases are bounded by small end times and
step/wall budgets. The examples are derandomised, so the counts printed at the end
(``pytest -s``) are reproducible; set PHASEKIT_FUZZ_REPORT=FILE to also write them to FILE as
JSON, PHASEKIT_FUZZ_LOG=FILE to append every case to FILE before it runs.
"""

import collections
import contextlib
import io
import math
import os
import re
import subprocess
import sys
import time
import warnings
from pathlib import Path

from phasekit import cli

import pytest

from ..generated_inputs import (
    SCALE,
    fuzz,
    generated,
    hang_guard,
    mostly,
    reals,
    report,
    st,
    text_of,
    thin_suites,
    weighted,
)
from ..helpers import strict_json

ROOT = Path(__file__).resolve().parents[2]
COUNTS: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
SLOWEST: list = []  # (seconds, argv) of the slowest in-process cases, reported at the end


@pytest.fixture(scope="module", autouse=True)
def _report():
    yield
    slowest = ["slowest CLI cases:"] + [f"  {sec:6.2f} s  {' '.join(argv)}" for sec, argv in SLOWEST]
    report(COUNTS, "generated command lines (valid / failed with a reason / clear error):",
           os.environ.get("PHASEKIT_FUZZ_REPORT"), {"scale": SCALE}, slowest)

@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """In-process, an unexpected exception must reach the test (it is a bug), not be printed."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


# -- the CLI, in-process ---------------------------------------------------------------------------


def body_args(egg: bool = True):
    """Body flags. ``egg=False`` for simulations: the egg's first run compiles a Taylor
    integrator of its Chebyshev series for minutes."""
    spheroid = st.tuples(st.just("--a"), text_of(reals(1.5, 0.6, 2 / 3, 3.0, 1.0, 1e-4, 1e4)))
    tippe = st.tuples(st.just("--body"), st.just("tippe-top"), st.just("--offset"), text_of(reals(0.3, 0.0, 0.2)))
    egg_args = st.tuples(st.just("--body"), st.just("egg"), st.just("--a"), text_of(reals(1.3, 1.6)), st.just("--w"),
                    text_of(reals(0.0, 0.1, 0.3)))
    moments = st.lists(st.tuples(st.sampled_from(["--A", "--C"]), text_of(reals(0.4, 0.65, 0.2))), max_size=1)
    return st.tuples(weighted((spheroid, 6), (tippe, 1), (egg_args, 1 if egg else 0)), moments).map(
        lambda t: [*t[0], *[x for pair in t[1] for x in pair]])


def friction_args():
    mu = st.tuples(st.just("--mu"), text_of(reals(0.1, 0.3, 0.0, 1e3, 2.0)))
    law = st.lists(st.tuples(st.just("--friction"), mostly(st.sampled_from(["coulomb", "viscous"]), st.just("dry"), n_good=12)), max_size=1)
    eps = st.lists(st.tuples(st.just("--slip-eps"), text_of(reals(1e-3, 1e-6, 1e-12, 1e-15, 1.0))), max_size=1)
    return st.tuples(mu, law, eps).map(lambda t: [*t[0], *[x for p in t[1] + t[2] for x in p]])


def start_args():
    rate = reals(10.0, 10.5, 3.0, 1e5, 0.5)
    state = st.lists(text_of(reals(0.0, 0.1, 1.0, 10.0, 1.5, -0.2)), min_size=5, max_size=7).map(
        lambda v: ["--state", *v])
    state6 = st.tuples(reals(0.0, 0.01), reals(0.0, 0.01), reals(10.0, 0.0, 3.0), reals(0.0, 0.1),
                       reals(1.0, 1.5, 0.1, 3.0, 0.0), reals(0.0, 10.0, 2.0)).map(lambda v: ["--state", *map(repr, v)])
    gyro = st.tuples(mostly(st.sampled_from([["--omega0"], ["--omega0"], ["--n0"]]),
                            st.sampled_from([["--omega0", "--n0"], []]), n_good=12), text_of(rate),
                     mostly(st.lists(text_of(reals(1.5, 1.56, 0.1, 0.05)), min_size=1, max_size=1), st.just([]),
                            n_good=12)).map(
        lambda t: ["--gyroscopic", *[x for f in t[0] for x in (f, t[1])], *[x for v in t[2] for x in ("--theta0", v)]])
    kind = mostly(st.sampled_from([("horizontal", "--omega0"), ("vertical", "--n0")]),
                  st.sampled_from([("horizontal", "--n0"), ("vertical", "--omega0"), ("inclined", "--n0")]), n_good=8)
    manifold = st.tuples(kind, text_of(rate), st.lists(mostly(
        st.sampled_from([["--delta", "0.01"], ["--delta", "0.05"], ["--branch", "-0"], ["--seed-law", "same"]]),
        st.sampled_from([["--delta", "-1"], ["--branch", "+7"], ["--seed-law", "dry"]]), n_good=6), max_size=2)).map(
        lambda t: ["--unstable-manifold", t[0][0], t[0][1], t[1], *[x for p in t[2] for x in p]])
    spin = st.tuples(text_of(reals(15.0, 5.0)), text_of(reals(0.1, 0.0, 3.0))).map(
        lambda t: ["--spin-about-vertical", t[0], "--theta0", t[1]])
    paper = st.sampled_from([["--paper-start", "5.2"], ["--paper-start", "5.1"], ["--paper-start", "5.3"]])
    return weighted((state6, 4), (gyro, 5), (manifold, 2), (spin, 1), (state, 1), (paper, 1))


def run_args():
    opts = {
        "--t-end": text_of(reals(2.0, 5.0, 0.5, 20.0)),
        "--stop-at": st.sampled_from(["jump", "none", "touchdown", "theta=0.4", "R=0.5", "energy=1", "foo=1",
                                      "theta=nan", "theta=", "theta=9"]),
        "--restitution": text_of(reals(0.5, 0.0, 1.0)),
        "--rtol": text_of(reals(1e-9, 1e-6, 1e-12, 1e-16, 0.1)),
        "--atol": text_of(reals(1e-11, 1e-8)),
        "--backend": st.sampled_from(["auto", "taylor", "cvodes", "cvodes-adams", "idas"] * 2 + ["rk4"]),
        "--formulation": st.sampled_from(["auto", "euler", "vector"] * 3 + ["polar"]),
        "--max-steps": st.sampled_from(["1", "1000", "20000", "1e4"] * 3 + ["0", "-5", "1.5", "x", "inf"]),
        "--max-wall": st.sampled_from(["0.5", "2"] * 4 + ["0", "-1", "nan", "inf", "x"]),
    }
    return st.dictionaries(st.sampled_from(sorted(opts)), st.none(), max_size=4).flatmap(
        lambda chosen: st.tuples(*[st.tuples(st.just(k), opts[k]) for k in sorted(chosen)])).map(
        lambda pairs: [x for p in pairs for x in p])


def simulate_argv():
    extra = mostly(st.sampled_from([[], ["--json"], ["--events"]]),
                   st.sampled_from([["--omega", "10"], ["--bogus"], ["--mu"], ["1.0"]]), n_good=12)
    return st.tuples(body_args(egg=False), friction_args(), start_args(), run_args(), extra).map(
        lambda t: ["simulate", *t[0], *t[1], *t[2], *t[3], *t[4]])


def fixed_points_argv():
    family = st.tuples(st.sampled_from([["--omega0"], ["--n0"], ["--omega0", "--n0"], []]),
                       text_of(reals(10.0, 2.0, 1e6, 1e-3, 12.0))).map(lambda t: [x for f in t[0] for x in (f, t[1])])
    return st.tuples(body_args(), friction_args(), family).map(lambda t: ["fixed-points", *t[0], *t[1], *t[2]])


def gyroscopic_argv():
    times = mostly(st.lists(text_of(reals(0.0, 10.0, 40.0, 1e3)), min_size=1, max_size=4), st.just([]), n_good=12).map(
        lambda v: ["--t", *v] if v else [])
    family = st.tuples(st.sampled_from(["--omega0", "--n0"]), text_of(reals(10.5, 10.0, 3.0))).map(list)
    return st.tuples(body_args(), st.tuples(st.just("--mu"), text_of(reals(0.1, 1.0))), family,
                     st.tuples(st.just("--theta0"), text_of(reals(1.5, 0.1, 1.56))), times).map(
        lambda t: ["gyroscopic", *t[0], *t[1], *t[2], *t[3], *t[4]])


def run_main(argv):
    out, err = io.StringIO(), io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
        code = cli.main(argv)
    return code, out.getvalue(), err.getvalue(), time.perf_counter() - t0


def flags_of(command: str) -> set[str]:
    parser = cli.build_parser()
    return set(parser.known_flags)


def wall_budget(argv: list[str]) -> float | None:
    """The wall budget a case gives (its last ``--max-wall``), if that is a finite number."""
    with contextlib.suppress(ValueError, IndexError):
        wall = float(argv[len(argv) - 1 - argv[::-1].index("--max-wall") + 1])
        return wall if math.isfinite(wall) else None
    return None


def check_wall_reason(argv: list[str], reason: str) -> None:
    """A run stopped by its wall budget says so: the budget it was given, and where it stopped."""
    m = re.search(r"wall-time limit (?:\((\S+) s\) )?reached at t = \S+", reason)
    assert m, (argv, reason)
    budget = wall_budget(argv)
    assert budget is not None and (m.group(1) is None or float(m.group(1)) == float(f"{budget:g}")), (argv, reason)


def classify_cli(argv: list[str], code: int, out: str, err: str) -> str:
    """The outcome of one CLI case, after checking every rule of the module docstring."""
    as_json = "--json" in argv
    err_lines = err.strip().splitlines()
    assert "Traceback" not in err and "np.float64" not in err + out
    assert all(ln.startswith(("phasekit: warning: ", "phasekit: error: ")) for ln in err_lines), err
    errors = [ln for ln in err_lines if ln.startswith("phasekit: error: ")]
    if code == 0:
        assert not errors
        if as_json:
            d = strict_json(out)
            assert d.get("status") != "failed"
        else:
            assert out.strip() and "nan" not in out.lower().split() and "inf" not in out.lower().split()
        return "valid"
    if code == 1:
        if errors:  # a solver error: one line
            assert len(errors) == 1 and err_lines[-1] == errors[0] and len(errors[0]) > len("phasekit: error: ") + 10
            if as_json:
                assert strict_json(out)["status"] == "failed"
        else:  # a failed run: its reason
            if as_json:
                d = strict_json(out)
                assert d["status"] == "failed" and d["reason"]
                reason = d["reason"]
            else:
                m = re.match(r"status: failed \((.+)\)", out)
                assert m
                reason = m.group(1)
            if "wall-time" in reason:
                check_wall_reason(argv, reason)
        return "failed"
    assert code == 2, (argv, code, err)
    assert len(errors) == 1 and err_lines[-1] == errors[0], err
    message = errors[0][len("phasekit: error: "):]
    named = re.findall(r"--[A-Za-z][\w-]*", message)
    known = flags_of(argv[0]) | {a for a in argv if a.startswith("--")}
    assert named and all(f in known for f in named), (argv, message)
    if as_json:
        d = strict_json(out)
        assert d["status"] == "error" and d["message"] == message
        if d["parameter"] is not None:
            assert d["parameter"] in named and message.find(d["parameter"]) >= 0
    else:
        assert out == ""
    return "error"


def check_cli(suite: str, argv: list[str]) -> None:
    argv = list(argv)
    if argv[0] == "simulate" and "--max-wall" not in argv:
        argv += ["--max-wall", "2"]  # every generated run is bounded in wall time
    if os.environ.get("PHASEKIT_FUZZ_LOG"):  # the case about to run, for finding a slow one
        with open(os.environ["PHASEKIT_FUZZ_LOG"], "a") as fh:
            fh.write(" ".join(argv) + "\n")
    code, out, err, seconds = run_main(argv)
    SLOWEST.append((seconds, argv))  # reported, not checked: a hang fails the test by its timeout
    SLOWEST.sort(key=lambda q: -q[0])
    del SLOWEST[5:]
    COUNTS[suite][classify_cli(argv, code, out, err)] += 1


# ~50 s of runs: the full run only (the default run keeps the fixed simulate cases of this file's
# real-process test, tests/cli's refusals and the generated fixed-points and gyroscopic suites)
@pytest.mark.slow
@hang_guard(1800)
@generated(simulate_argv, **fuzz(500))
def test_cli_simulate(argv):
    check_cli("cli simulate", argv)


@hang_guard(2400)
@generated(fixed_points_argv, **fuzz(250))
def test_cli_fixed_points(argv):
    check_cli("cli fixed-points", argv)


@hang_guard(1800)
@generated(gyroscopic_argv, **fuzz(200))
def test_cli_gyroscopic(argv):
    check_cli("cli gyroscopic", argv)


# -- the CLI in a real process: stdout, stderr and exit codes as a shell sees them ------------------

SUBPROCESS_CASES = [
    ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--t-end", "5",
     "--json"],
    ["simulate", "--a", "1.5", "--mu", "nan", "--state", "0", "0", "0", "0", "1", "0", "--json"],
    ["simulate", "--a", "1.5", "--mu", "0.1", "--state", "0", "0", "0", "0", "1", "0", "--t-end", "1e300",
     "--max-steps", "2000"],
    ["fixed-points", "--a", "1e3", "--mu", "0.1", "--omega0", "1e6", "--json"],
    ["fixed-points", "--a", "0.6", "--mu", "0.1", "--n0", "-inf"],
    ["gyroscopic", "--a", "1.5", "--mu", "0.1", "--omega0", "10", "--theta0", "1.5", "--t", "0", "5", "--json"],
    ["gyroscopic", "--a", "1.5", "--mu", "0.1", "--omega0", "10", "--theta0", "1.5", "--t", "-1"],
    ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--t-end", "5",
     "--slip-eps", "1e-3", "--friction", "viscous", "--restitution", "0.5", "--json"],
]


@pytest.mark.parametrize("argv", SUBPROCESS_CASES, ids=range(len(SUBPROCESS_CASES)))
def test_cli_in_a_real_process(argv):
    p = subprocess.run([sys.executable, "-m", "phasekit", *argv], capture_output=True, text=True, timeout=120, cwd=ROOT)
    COUNTS["cli subprocess"][classify_cli(argv, p.returncode, p.stdout, p.stderr)] += 1


def test_every_generated_suite_has_valid_cases():
    """Runs last (file order): a suite whose every case ended in a clear error would pass case by
    case with the feature refusing all input; each must have valid results too."""
    thin = thin_suites(COUNTS)
    assert not thin, thin
