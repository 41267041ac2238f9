"""Bad input: every invalid parameter raises ValueError naming it (API), or one line and exit 2 (CLI)."""

import contextlib
import io
import json
import math
import subprocess
import sys

import phasekit as pk
from phasekit.cli import main
from phasekit.core import starts
from phasekit.friction import laws as friction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

NAN, INF = float("nan"), float("inf")
VALID = dict(a=1.5, mu=0.1, friction="coulomb", slip_eps=None, A=None, C=None, theta0=1.0, omega0=8.0, t_end=5.0, rtol=1e-9)

# (parameter, strategy of bad values)
BAD = {
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


bad_sets = st.sampled_from(sorted(BAD)).flatmap(lambda name: BAD[name].map(lambda v: (name, v)))


@settings(max_examples=200, deadline=None)
@given(bad_sets)
def test_api_rejects_bad_parameter_by_name(bad):
    name, value = bad
    params = dict(VALID, **{name: value})
    with pytest.raises(ValueError) as info:
        api_call(params)
    assert str(info.value).startswith(f"`{API_NAMES.get(name, name)}` ")


@settings(max_examples=200, deadline=None)
@given(bad_sets)
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
