"""``phasekit fixed-points``: its JSON, fixed points found at every scale, the same answer as the
API by default, and help text whose stability statements hold for the law they name."""

import contextlib
import io
import json

import phasekit as pk
from phasekit import cli
from phasekit.cli import main

import numpy as np
import pytest

from ..helpers import run_cli, run_module, strict_json


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception inside the CLI is a test failure, not a one-line message."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def run_json(args):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(args)
    return code, json.loads(out.getvalue())


def test_fixed_points_json_contract():
    code, d = run_json(["fixed-points", "--a", "1.5", "--mu", "0.1", "--friction", "viscous", "--omega0", "10", "--json"])
    assert code == 0
    [fp] = [p for p in d["fixed_points"] if p["kind"] == "horizontal"]
    assert fp["n_unstable"] == 1 and fp["stable"] is False and fp["residual"] < 1e-12
    assert all(len(ev) == 2 for ev in fp["eigenvalues"])
    code, d = run_json(["fixed-points", "--a", "0.6", "--mu", "0.1", "--friction", "coulomb", "--n0", "10", "--json"])
    [v] = [p for p in d["fixed_points"] if p["kind"] == "vertical"]
    assert v["state"]["Omega"] is None and v["linearised_law"] == "coulomb-rolling"


def test_cli_fixed_points_for_the_tippe_top():
    import contextlib
    import io
    import json

    from phasekit.cli import main

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main(["fixed-points", "--body", "tippe-top", "--offset", "0.3", "--stem-length", "0", "--mu", "0.3", "--n0", "5",
                     "--json"])
    assert code == 0
    out = json.loads(buf.getvalue())
    kinds = [p["kind"] for p in out["fixed_points"]]
    assert kinds[:2] == ["vertical", "inverted"]
    up, inv = out["fixed_points"][:2]
    assert up["state"]["theta"] == 0.0 and inv["state"]["theta"] == pytest.approx(np.pi)
    assert up["parameter"]["stable_under_sliding_friction"] is False
    assert inv["parameter"]["stable_under_sliding_friction"] is True


@pytest.mark.parametrize("args", [
    ["--a", 1e3, "--mu", 0.1, "--omega0", 10],
    ["--a", 1.5, "--mu", 0.1, "--omega0", 1e6],
    ["--a", 1.5, "--mu", 0.1, "--omega0", 10, "--slip-eps", 1e-12],
    ["--a", 1.5, "--mu", 1e3, "--omega0", 10, "--friction", "viscous"],
    ["--a", 0.6, "--mu", 0.1, "--n0", 1e5],
], ids=["a=1e3", "omega0=1e6", "eps=1e-12", "viscous-mu=1e3", "n0=1e5"])
def test_fixed_points_are_found_at_every_scale(args):
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
    code, out, _ = run_module("fixed-points", "--help")
    assert code == 0
    text = " ".join(out.split())
    assert "--friction coulomb (default) exact stick-slip" in text and "rolling (no-slip) linearisation" in text
    assert "--friction viscous part I's wet friction" in text and "Omega0 > sqrt(5) (prolate)" in text
    assert "weak friction (mu below ~0.8)" in text
    assert "(default: coulomb" in text


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


@pytest.mark.timeout(300)
def test_fixed_points_on_a_sphere_say_it_is_a_continuum():
    """A sphere with G at its centre: the horizontal state (with --omega0) or the vertical spin
    (with --n0) only, and a note that every orientation is steady, not a scan of a continuum."""
    from phasekit.cli.params import fixed_points_report

    code, d = run_json(["fixed-points", "--a", "1.0", "--A", "0.4", "--mu", "0.1", "--omega0", "10.0", "--json"])
    assert code == 0 and d["status"] == "completed"
    assert [p["kind"] for p in d["fixed_points"]] == ["horizontal"] and "static equilibrium" in d["degenerate"]
    assert d["degenerate"] in d["note"]
    d = fixed_points_report(body=pk.Spheroid(1.0), mu=0.1, n0=3.0, max_wall=60.0)
    assert d["status"] == "completed" and [p["kind"] for p in d["fixed_points"]] == ["vertical"]


def test_fixed_points_report_keeps_its_wall_budget():
    from phasekit.cli.params import fixed_points_report

    d = fixed_points_report(body=pk.Egg(1.3, 0.05), mu=0.1, omega0=6.0, max_wall=1e-9)
    assert d["status"] == "failed" and "max_wall = 1e-09 s" in d["reason"] and d["fixed_points"] == []
    d = fixed_points_report(body=pk.Egg(1.3, 0.05), mu=0.1, omega0=6.0, max_wall=600.0)
    assert d["status"] == "completed" and "reason" not in d
    assert [p["kind"] for p in d["fixed_points"]] == ["intermediate", "horizontal-like"]
    with pytest.raises(pk.ParameterError, match="`max_wall`"):
        fixed_points_report(body=pk.Spheroid(1.5), mu=0.1, omega0=1.0, max_wall=-1.0)
