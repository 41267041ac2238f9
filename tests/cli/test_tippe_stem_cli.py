"""--body tippe-top with --stem-length and --stem-radius: the top with its stem, over the ball's radius
or with units by --size; the issue's command inverts it onto its stem, which it has by default (a
common commercial top's); with --stem-length 0 the tippe top is the ball alone, every number as
before; bad input is one line naming the flag typed, its range and the value typed."""

import phasekit as pk
from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json, usage_error

TOP = ["simulate", "--body", "tippe-top", "--offset", "0.3", "--A", "0.38", "--C", "0.4", "--mu", "0.3", "--theta0", "0.1",
       "--spin-about-vertical", "15"]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")



@pytest.mark.timeout(600)
def test_the_issues_command_ends_on_the_stem():
    code, out, _ = run_cli(*TOP, "--stop-at", "none", "--t-end", "70", "--json")  # no stem flag: the default stem
    d = strict_json(out)
    assert code == 0 and d["status"] == "completed" and d["theta_end"] > 2.9
    assert (d["model"]["stem_length"], d["model"]["stem_radius"]) == (0.375, 0.2)
    kinds = [e["kind"] for e in d["events"]]
    assert "stem touches" in kinds and "ball touches" not in kinds[kinds.index("stem touches"):]
    # the summary says where the contact went and that the axis turned over, in words true for a top
    [touch] = [e for e in d["events"] if e["kind"] == "stem touches"]
    assert d["passages"][-1] == f"ball -> stem at t = {touch['t']:.6g}" and d["theta_change"] > 2.7
    code, text, _ = run_cli(*TOP, "--stop-at", "none", "--t-end", "70")
    lines = text.splitlines()
    assert code == 0 and f"the contact passed ball -> stem at t = {touch['t']:.6g}" in lines
    assert any(ln.startswith("theta grew by ") and "(the axis passed the horizontal)" in ln for ln in lines)
    assert not any("sank" in ln or "rose" in ln for ln in lines)


def test_the_stem_flags_take_units_with_size_and_default_to_the_commercial_top():
    code, out, _ = run_cli(*TOP, "--t-end", "1", "--size", "16 mm", "--stem-length", "6 mm", "--stem-radius", "3.2 mm",
                           "--json")
    model = strict_json(out)["model"]
    assert code == 0 and model["stem_length"] == pytest.approx(0.375, rel=1e-14)
    assert model["stem_radius"] == pytest.approx(0.2, rel=1e-14)
    code, out, _ = run_cli(*TOP, "--t-end", "1", "--stem-radius", "0.3", "--json")
    model = strict_json(out)["model"]
    assert code == 0 and (model["stem_length"], model["stem_radius"]) == (0.375, 0.3)


def test_with_stem_length_0_the_tippe_top_is_the_ball_alone():
    code, out, _ = run_cli(*TOP, "--t-end", "3", "--stem-length", "0", "--json")
    d = strict_json(out)
    assert code == 0 and "stem_length" not in d["model"] and d["model"]["body"] == "tippe-top"
    assert d["model"]["description"] == "EccentricSphere(offset=0.3, A=0.38, C=0.4)"
    # the same run as the library's ball alone, number for number
    top = pk.EccentricSphere(0.3, A=0.38, C=0.4)
    traj = pk.simulate(pk.Model(top, pk.Coulomb(0.3)), pk.core.vertical_spin_start(0.1, 15.0), 3.0)
    assert d["t_end"] == traj.t and list(d["state_end"].values()) == [float(v) for v in traj.x]
    message = usage_error([*TOP, "--t-end", "1", "--stem-length", "0", "--stem-radius", "0.2"], "--stem-radius")
    assert message == "--stem-radius does not apply with --stem-length 0 (the ball alone, no stem), got 0.2."


@pytest.mark.parametrize("flag, value, words", [
    ("--stem-radius", "1.5", "must lie in (0, 1) (over the ball's radius)"),
    ("--stem-radius", "0", "must lie in (0, 1) (over the ball's radius)"),
    ("--stem-length", "-0.1", "must lie in [0, 10] (over the ball's radius; 0: the ball alone)"),
    ("--stem-length", "12", "must lie in [0, 10] (over the ball's radius; 0: the ball alone)")])
def test_a_stem_out_of_range_is_refused_naming_the_flag(flag, value, words):
    message = usage_error([*TOP, "--t-end", "1", flag, value], flag)
    assert message == f"{flag} {words}, got {float(value)}."  # as --thickness prints it


def test_the_stem_flags_on_another_body_are_refused_naming_them():
    base = ["simulate", "--mu", "0.3", "--theta0", "0.5", "--spin-about-vertical", "5", "--t-end", "1"]
    message = usage_error([*base, "--body", "spheroid", "--a", "1.5", "--stem-length", "0.3"], "--stem-length")
    assert "does not apply to the spheroid body" in message and "0.3" in message
    message = usage_error([*base, "--body", "cone", "--stem-radius", "0.2"], "--stem-radius")
    assert "does not apply to the cone body" in message
    message = usage_error([*TOP, "--t-end", "1", "--stem-length", "6 mm"], "--stem-length")
    assert "--size" in message and "'6 mm'" in message
