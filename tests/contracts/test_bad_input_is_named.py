"""Bad input is named: every invalid parameter raises a ParameterError (a ValueError) naming it
(API), or one line and exit 2 (CLI); the library's messages give Python advice, never CLI flags;
options that mislead warn."""

from __future__ import annotations

import ast
import contextlib
import io
import json
import math
import pathlib
import re
import subprocess
import sys

import phasekit as pk
from phasekit.cli import main
from phasekit.core import starts
from phasekit.friction import laws as friction
from phasekit.steady import fixedpoints
from phasekit.theory import gyroscopic

import numpy as np
import pytest

from ..generated_inputs import generated, st

ROOT = pathlib.Path(__file__).resolve().parents[2]
NAN, INF = float("nan"), float("inf")
VALID = dict(a=1.5, mu=0.1, friction="coulomb", slip_eps=None, A=None, C=None, theta0=1.0, omega0=8.0, t_end=5.0, rtol=1e-9)


def bad_values():
    """(parameter, strategy of bad values)"""
    return {
        "a": st.sampled_from([0.0, -1.0, NAN, INF, -INF]) | st.floats(max_value=0.0, allow_nan=False),
        "mu": st.sampled_from([NAN, INF, -1e-9]) | st.floats(max_value=-1e-12, allow_nan=False),
        "slip_eps": st.sampled_from([0.0, NAN, INF]) | st.floats(max_value=0.0, allow_nan=False),
        "theta0": st.sampled_from([0.0, math.pi, NAN, INF]) | st.floats(min_value=math.pi, allow_nan=False) | st.floats(max_value=0.0, allow_nan=False),
        "rtol": st.sampled_from([0.0, 1.0, NAN, INF]) | st.floats(min_value=1.0, allow_nan=False) | st.floats(max_value=0.0, allow_nan=False),
        "t_end": st.sampled_from([0.0, NAN, INF]) | st.floats(max_value=0.0, allow_nan=False),
        "friction": st.text(min_size=1, max_size=8).filter(lambda s: s not in ("coulomb", "viscous") and s.strip() == s and not s.startswith("-")),
        "A": st.sampled_from([0.0, -0.5, NAN, INF]),
        "C": st.sampled_from([0.0, -0.5, NAN, 5.0]),
        "omega0": st.sampled_from([0.0, NAN, INF]),
    }


# the parameter as the Python API names it, and the flag the CLI must name
API_NAMES = {"slip_eps": "eps"}
FLAGS = {"a": "--a", "mu": "--mu", "slip_eps": "--slip-eps", "theta0": "--theta0", "rtol": "--rtol", "t_end": "--t-end",
         "friction": "--friction", "A": "--A", "C": "--C", "omega0": "--omega0"}


def api_call(params):
    body = pk.Spheroid(params["a"], A=params["A"], C=params["C"])
    law = friction.friction_law(params["friction"], params["mu"], params["slip_eps"])
    y0 = pk.gyroscopic_start(body, params["theta0"], omega0=params["omega0"])
    return pk.simulate(pk.Model(body, law), y0, params["t_end"], rtol=params["rtol"])


def cli_args(params):
    args = ["simulate", "--a", repr(params["a"]), "--mu", repr(params["mu"]), "--friction", params["friction"],
            "--gyroscopic", "--theta0", repr(params["theta0"]), "--omega0", repr(params["omega0"]),
            "--t-end", repr(params["t_end"]), "--rtol", repr(params["rtol"]), "--json"]
    for k, flag in (("slip_eps", "--slip-eps"), ("A", "--A"), ("C", "--C")):
        if params[k] is not None:
            args += [flag, repr(params[k])]
    return args


def bad_sets():
    """(parameter, one of its bad values)"""
    bad = bad_values()
    return st.sampled_from(sorted(bad)).flatmap(lambda name: bad[name].map(lambda v: (name, v)))


@generated(bad_sets, max_examples=200, deadline=None)
def test_api_rejects_bad_parameter_by_name(bad):
    name, value = bad
    params = dict(VALID, **{name: value})
    with pytest.raises(ValueError) as info:
        api_call(params)
    assert str(info.value).startswith(f"`{API_NAMES.get(name, name)}` ")


@generated(bad_sets, max_examples=200, deadline=None)
def test_cli_rejects_bad_parameter_in_one_line(bad):
    name, value = bad
    params = dict(VALID, **{name: value})
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(cli_args(params))
    assert code == 2
    # --json: stdout holds one JSON object naming the flag, stderr one line
    assert json.loads(out.getvalue()) == {"status": "error", "parameter": FLAGS[name],
                                          "message": err.getvalue().strip()[len("phasekit: error: "):]}
    lines = err.getvalue().strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"phasekit: error: {FLAGS[name]} ")
    assert "np.float64" not in lines[0] and "Traceback" not in lines[0]


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda m: pk.simulate(m, [0, 0, 1, 0, 1], 1.0), "x0"),
        (lambda m: pk.simulate(m, [0, 0, 1, 0, 1, NAN], 1.0), "x0"),
        (lambda m: pk.simulate(m, [0, 0, 1, 0, 1, 1], 1.0, rtol=2.0), "rtol"),
        (lambda m: pk.simulate(m, [0, 0, 1, 0, 1, 1], -1.0), "t_end"),
        (lambda m: pk.simulate(m, [0, 0, 1, 0, 1, 1], 1.0, backend="rk4"), "backend"),
        (lambda m: pk.simulate(m, [0, 0, 1, 0, 1, 1], 1.0, stop_at="never"), "stop_at"),
        (lambda m: pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1), "polar"), "chart"),
        (lambda m: pk.gyroscopic_start(pk.Spheroid(0.6), 1.0, n0=-0.0), "n0"),
        (lambda m: pk.gyroscopic_start(pk.Spheroid(0.6), 1.8, n0=10.0), "theta0"),
        (lambda m: starts.raw_start([0, 0, 1, 0, 0.0, 1]), "theta"),
    ],
)
def test_public_api_errors_name_the_parameter(call, name):
    m = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))
    with pytest.raises(ValueError, match=f"`{name}`"):
        call(m)


@pytest.mark.parametrize(
    "args, name",
    [
        (["simulate", "--a", "-1", "--mu", "0.1", "--gyroscopic", "--theta0", "1", "--omega0", "9"], "--a "),
        (["simulate", "--a", "1.5", "--mu", "0.1", "--state", "0", "0", "1", "0", "1"], "--state"),
    ],
)
def test_cli_subprocess_prints_one_line_no_traceback(args, name):
    p = subprocess.run([sys.executable, "-m", "phasekit", *args], capture_output=True, text=True, timeout=120)
    assert p.returncode == 2
    assert p.stdout == ""
    assert len(p.stderr.strip().splitlines()) == 1 and name in p.stderr and "Traceback" not in p.stderr


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


def _library_messages():
    """String pieces of every raise and warnings.warn in the library outside the CLI and the
    scaffold of study scripts (both speak to a command line)."""
    for path in sorted((ROOT / "phasekit").rglob("*.py")):
        if path.parent.name in ("cli", "studies", "scaffold"):
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


@pytest.fixture(scope="module")
def standard():
    body = pk.Spheroid(1.5)
    return pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)


def test_repeated_keywords_give_the_same_validated_options_and_bad_ones_still_fail(standard):
    model, y0 = standard
    assert pk.simulate(model, y0, 1.0, rtol=1e-8).options.rtol == 1e-8
    assert pk.simulate(model, y0, 1.0, rtol=1e-10).options.rtol == 1e-10
    with pytest.raises(pk.ParameterError, match="rtol"):
        pk.simulate(model, y0, 1.0, rtol=0.0)
    with pytest.raises(pk.ParameterError, match="rtol"):
        pk.simulate(model, y0, 1.0, rtol=[1e-9])
