"""``phasekit steady-states``: its JSON against the API, bad input, and generated command lines
that all end in a structure or one line naming a flag typed."""

import json

import phasekit as pk
from phasekit.steady.branches import precession_on_branch

import numpy as np
import pytest

from ..generated_inputs import generated, st
from ..helpers import run_cli, strict_json, usage_error


def test_cli_steady_states_json_and_bad_input():
    code, out, err = run_cli("steady-states", "--body", "spheroid", "--a", "1.5", "--offset", "0.2", "--A", "0.61",
                              "--C", "0.4", "--mu", "0.1", "--friction", "viscous", "--json")
    assert code == 0 and err == ""
    d = json.loads(out)
    assert d["signature"] == "pole0-inf | static-polePi"
    for b in d["branches"]:
        kinds = [e["kind"] for e in b["ends"]]
        assert all(k in ("pole", "static", "infinite-spin") for k in kinds)
        assert b["ends"][0]["theta"] < b["ends"][1]["theta"]
        th = np.array([s["theta"] for s in b["samples"]])
        om, n = precession_on_branch(pk.Spheroid(1.5, offset=0.2, A=0.61, C=0.4), th)
        assert np.array([s["Omega"] for s in b["samples"]]) == pytest.approx(om, rel=1e-14)
        assert np.array([s["n"] for s in b["samples"]]) == pytest.approx(n, rel=1e-12, abs=1e-14)
        model = pk.Model(pk.Spheroid(1.5, offset=0.2, A=0.61, C=0.4), pk.Viscous(0.1))
        for s in b["samples"][5::20]:  # the stability reported is the pointwise linearisation's
            if min(s["theta"], np.pi - s["theta"]) >= 0.05:
                assert s["stable"] == pk.steady.linearise(model, [0, 0, s["Omega"], 0, s["theta"], s["n"]]).stable
    assert [s["kind"] for s in d["static_equilibria"]] == ["pole", "tilted", "pole"]
    code, out, err = run_cli("steady-states", "--a", "1.5", "--offset", "1.6", "--mu", "0.1")
    assert code == 2 and "--offset" in err and len(err.strip().splitlines()) == 1


def _numbers():
    return st.one_of(st.floats(allow_nan=True, allow_infinity=True, width=32), st.sampled_from(["0", "-1", "1e9", "abc", ""]))


def _structure_argv():
    return st.composite(_draw_structure_argv)()


def _draw_structure_argv(draw):
    body = draw(st.sampled_from(["spheroid", "tippe-top", "egg"]))
    argv = ["steady-states", "--body", body, "--mu", draw(st.sampled_from(["0.1", "0.3", "0", "-1", "nan"]))]
    options = {"spheroid": ["--a", "--offset", "--A", "--C"], "tippe-top": ["--offset", "--A", "--C"], "egg": ["--a", "--w"]}
    for flag in draw(st.lists(st.sampled_from(options[body] + ["--a", "--w"]), unique=True, max_size=4)):
        value = draw(st.one_of(st.floats(0.05, 3.0).map(lambda v: f"{v:.4g}"), _numbers().map(str)))
        argv += [flag, value]
    argv += draw(st.sampled_from([[], ["--friction", "viscous"], ["--slip-eps", "1e-3"], ["--friction", "magic"]]))
    argv += draw(st.sampled_from([[], ["--omega0", "2"], ["--n0", "3"]]))
    return [*argv, "--json"]


@generated(_structure_argv, max_examples=40, deadline=None, derandomize=True, suppress_health_check="all")
def test_generated_steady_states_command_lines_end_in_a_result_or_one_line(argv):
    """Every generated command line gives strict JSON: a structure (ends ordered and of the three
    kinds, and switches on the tippe top with its stem, finite samples) with exit 0, or an error
    naming one of the flags typed with exit 2."""
    code, out, err = run_cli(*argv)
    d = json.loads(out, parse_constant=lambda name: (_ for _ in ()).throw(ValueError(name)))
    if code == 0:
        for b in d["branches"]:
            assert b["ends"][0]["theta"] < b["ends"][1]["theta"]
            kinds = {"pole", "static", "infinite-spin"} | ({"switch"} if argv[2] == "tippe-top" else set())
            assert {e["kind"] for e in b["ends"]} <= kinds
            assert all(np.isfinite([s["theta"], s["Omega"], s["n"]]).all() for s in b["samples"])
        assert d["signature"] == " | ".join(b["label"] for b in d["branches"]) or d["signature"] == "none"
    else:
        from phasekit import cli

        flags = cli.build_parser().commands["steady-states"]._option_string_actions
        # the flag typed, or a required one left out (e.g. --a for a spheroid)
        assert code == 2 and d["status"] == "error" and d["parameter"] in flags, (argv, d)
        required = {"spheroid": "--a", "tippe-top": "--offset"}.get(argv[argv.index("--body") + 1])
        assert d["parameter"] in argv or (d["parameter"] == required and required not in argv), (argv, d)
        assert len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("options", [
    ["--a", 1.5, "--offset", 0.2, "--mu", 0.1, "--friction", "viscous", "--omega0", 1000],  # next to an asymptote
    ["--a", 1.5, "--offset", 0.2, "--mu", 0.1, "--friction", "viscous", "--omega0", 1e12],
    ["--body", "egg", "--a", 1.3, "--w", 0.05, "--mu", 0.1, "--n0", 1e-3],  # a pair around a point of spin 0
    ["--body", "tippe-top", "--offset", 0.3, "--A", 0.38, "--C", 0.4, "--mu", 0.3, "--n0", 1.04],
    ["--a", 0.6, "--mu", 0.1, "--slip-eps", 1e-3, "--omega0", 1e-6],
    ["--a", 1, "--mu", 0.1, "--omega0", 10],  # a sphere: its isolated states only
], ids=["omega0=1e3", "omega0=1e12", "egg-n0=1e-3", "tippe-top", "oblate-omega0=1e-6", "sphere"])
def test_steady_states_at_a_rate_lists_what_fixed_points_lists(options):
    code, out, err = run_cli("steady-states", *options, "--json")
    assert code == 0 and err == "", err
    states = strict_json(out)["states"]
    code, out, err = run_cli("fixed-points", *options, "--json")
    assert code == 0 and err == "", err
    ref = strict_json(out)["fixed_points"]
    keys = ("kind", "classification", "n_unstable", "stable")
    assert [[p[k] for k in keys] for p in states] == [[p[k] for k in keys] for p in ref]
    for p, r in zip(states, ref):
        for name, v in r["state"].items():  # Omega is null at the vertical (undefined at theta = 0)
            assert p["state"][name] == (v if v is None else pytest.approx(v, rel=1e-9, abs=1e-9)), name
    if "--omega0" in options and options[options.index("--omega0") + 1] == 1000:
        assert [p["n_unstable"] for p in states] == [1]  # the unstable state the structure once left out


@pytest.mark.timeout(300)
def test_a_sphere_is_reported_as_a_continuum_of_steady_states():
    """A sphere with G at its centre: every orientation is static, so there are no branches to
    sample; the command says so at once (the report's budget, 60 s, is only a hang guard)."""
    from phasekit.cli.params import steady_structure_report

    code, out, err = run_cli("steady-states", "--a", "1", "--mu", "0.1", "--json")
    d = strict_json(out)
    assert code == 0 and d["status"] == "completed" and d["signature"] == "degenerate" and d["branches"] == []
    assert "every orientation is a static equilibrium" in d["degenerate"]
    d = steady_structure_report(body=pk.EccentricSphere(0.0), mu=0.1, n0=5.0, max_wall=60.0)
    assert d["status"] == "completed" and d["signature"] == "degenerate"
    assert [s["kind"] for s in d["states"]] == ["vertical"]


def test_the_report_keeps_its_wall_budget():
    from phasekit.cli.params import steady_structure_report

    d = steady_structure_report(body=pk.Spheroid(1.5, offset=0.2), mu=0.1, omega0=3.0, max_wall=1e-6)
    assert d["status"] == "failed" and "max_wall = 1e-06 s" in d["reason"] and "states" not in d
    with pytest.raises(pk.ParameterError, match="`max_wall`"):
        steady_structure_report(body=pk.Spheroid(1.5), mu=0.1, max_wall=0.0)


def test_steady_states_and_fixed_points_take_lengths_and_rates_with_units():
    """--stem-length "10 mm" with --size "12.5 mm" is the stem of 0.8 ball radii; --omega0 in rev/s
    with --size is 2 pi f sqrt(b/g) (the horizontal fixed point's Omega); without --size a value with units is refused naming its flag."""
    import math

    top = ["--body", "tippe-top", "--offset", "0.3", "--A", "0.38", "--C", "0.4", "--mu", "0.3", "--json"]
    code, out, _ = run_cli("steady-states", *top, "--stem-length", "10 mm", "--size", "12.5 mm")
    code_plain, plain, _ = run_cli("steady-states", *top, "--stem-length", "0.8")
    assert code == 0 and code_plain == 0
    a, b = strict_json(out), strict_json(plain)
    assert a["signature"] == b["signature"] and a["branches"] == b["branches"]
    usage_error(["steady-states", *top[:-1], "--stem-length", "10 mm"], "--stem-length")
    code, out, _ = run_cli("fixed-points", "--a", "1.5", "--mu", "0.1", "--omega0", "41 rev/s", "--size", "21.5 mm", "--json")
    omega = 2 * math.pi * 41 * math.sqrt(0.0215 / 9.81)  # g as the help says: 9.81 m/s^2 by default
    [horizontal] = [f for f in strict_json(out)["fixed_points"] if f["kind"] == "horizontal"]
    assert code == 0 and horizontal["state"]["Omega"] == pytest.approx(omega, rel=1e-12)
