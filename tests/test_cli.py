"""CLI: JSON contracts of the commands (in-process)."""

import contextlib
import io
import json

from phasekit.cli import main

import numpy as np
import pytest


def run_json(args):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(args)
    return code, json.loads(out.getvalue())


def test_simulate_json_keys():
    code, d = run_json(["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", str(np.pi / 2 - 0.01),
                        "--omega0", "10.5", "--t-end", "200", "--json"])
    assert code == 0
    for key in ("status", "t_jump", "state_at_jump", "R_min", "theta_end", "n_rhs", "wall_s", "events", "formulation"):
        assert key in d
    assert d["status"] == "jumped" and set(d["state_at_jump"]) == {"U", "V", "Omega", "Lambda", "theta", "n"}
    assert d["events"][-1]["kind"] == "lift-off"
    # the printed state at the jump has R = 0 (recomputed here from the model, not read back)
    import phasekit as pk

    y = np.array([d["state_at_jump"][k] for k in pk.core.PAPER_NAMES])
    assert abs(pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)).normal_reaction(y)) < 1e-8


def test_fixed_points_json_contract():
    code, d = run_json(["fixed-points", "--a", "1.5", "--mu", "0.1", "--friction", "viscous", "--omega0", "10", "--json"])
    assert code == 0
    [fp] = [p for p in d["fixed_points"] if p["kind"] == "horizontal"]
    assert fp["n_unstable"] == 1 and fp["stable"] is False and fp["residual"] < 1e-12
    assert all(len(ev) == 2 for ev in fp["eigenvalues"])
    code, d = run_json(["fixed-points", "--a", "0.6", "--mu", "0.1", "--friction", "coulomb", "--n0", "10", "--json"])
    [v] = [p for p in d["fixed_points"] if p["kind"] == "vertical"]
    assert v["state"]["Omega"] is None and v["linearised_law"] == "coulomb-rolling"


@pytest.mark.parametrize("which, extra", [("horizontal", ["--omega0", "12"]), ("vertical", ["--n0", "12"])])
def test_simulate_from_unstable_manifold(which, extra):
    a = "1.5" if which == "horizontal" else "0.6"
    code, d = run_json(["simulate", "--a", a, "--mu", "0.1", "--friction", "viscous", "--unstable-manifold", which,
                        *extra, "--delta", "0.01", "--t-end", "100", "--json"])
    assert code == 0 and d["seed"]["fixed_point"]["kind"] == which
    assert d["formulation"] == ("euler" if which == "horizontal" else "vector")
    assert abs(d["theta_end"] - d["start"]["theta"]) > 0.1  # it left the fixed point
