"""The starts people use, by name and in SI units: a top spun about its own axis
(--spun-about-axis, with its slow precession or none and a warning), a coin spun on its edge about
a vertical diameter (--spun-on-edge) or rolled at a speed (--rolled); the warning for a top spun
below its fast-top condition."""

import math

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json, usage_error

TOP = ["simulate", "--body", "cone", "--on", "tip", "--radius", "2 cm", "--height", "3 cm", "--mu", "0.5",
       "--theta0", "175 deg", "--t-end", "0.2 s", "--json"]
UNIT = math.sqrt(0.02 / 9.81)  # the time unit sqrt(b/g) of a 2 cm radius, s
L, A, C = 1.125, 0.15 * (1 + 1.5**2 / 4), 0.3  # the point 3/4 of the height from G; the cone's moments


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def test_a_fast_top_starts_on_the_lagrange_tops_slow_precession_and_holds_it():
    code, out, err = run_cli(*TOP, "--spun-about-axis", "50 rev/s")
    d = strict_json(out)
    st = d["start"]
    n = 50 * 2 * math.pi * UNIT
    assert code == 0 and "warning" not in err and st["n"] == pytest.approx(n, rel=1e-12)
    # (A + l^2) cos(theta) Omega^2 - C n Omega - l = 0, its slow root, G circling the point at V = -l Omega sin(theta)
    Om, c = st["Omega"], math.cos(st["theta"])
    assert (A + L * L) * c * Om**2 - C * n * Om - L == pytest.approx(0.0, abs=1e-12)
    other = -L / ((A + L * L) * c) / Om  # the fast root: the product of the two is -l / ((A + l^2) cos(theta))
    assert abs(Om) < 0.2 * abs(other) and st["V"] == pytest.approx(-L * Om * math.sin(st["theta"]), rel=1e-12)
    assert d["status"] == "completed" and abs(d["theta_end"] - st["theta"]) < 1e-8  # a steady state: theta held


def test_a_top_below_its_fast_top_condition_is_warned_in_one_line_with_the_condition_in_rev_per_s():
    code, out, err = run_cli(*TOP, "--spun-about-axis", "20 rev/s")
    lines = [x for x in err.splitlines() if x.startswith("phasekit: warning:")]
    n_c = math.sqrt(4 * (A + L * L) * L) / C  # C^2 n^2 > 4 A' M g l
    assert code == 0 and len(lines) == 2 and len(err.splitlines()) == 2
    assert "no slow precession" in lines[0] and "zero precession" in lines[0]
    assert f"|n| > {n_c:.6g} ({n_c / (2 * math.pi * UNIT):.4g} rev/s)" in lines[1] and "(20 rev/s)" in lines[1]
    assert strict_json(out)["start"]["Omega"] == 0.0
    code, _, err = run_cli(*TOP, "--spun-about-axis", "31 rev/s")  # just above 30.53 rev/s
    assert code == 0 and "fast-top" not in err


def test_a_coin_spun_on_its_edge_about_a_vertical_diameter():
    code, out, _ = run_cli("simulate", "--body", "disk", "--radius", "12 mm", "--mu", "0.3", "--spun-on-edge",
                           "5 rev/s", "--t-end", "0.1 s", "--json")
    st = strict_json(out)["start"]
    rate = 5 * 2 * math.pi * math.sqrt(0.012 / 9.81)
    assert code == 0 and st["theta"] == pytest.approx(math.pi / 2, rel=1e-15)
    assert st["Omega"] == pytest.approx(rate, rel=1e-12) and abs(st["n"]) < 1e-12 and st["U"] == st["V"] == 0.0


def test_a_coin_rolled_at_a_speed_rolls_without_slip_from_the_start():
    code, out, _ = run_cli("simulate", "--body", "disk", "--radius", "12 mm", "--thickness", "1.5 mm", "--mu", "0.3",
                           "--theta0", "85 deg", "--rolled", "0.5 m/s", "--t-end", "0.1 s", "--json", "--events")
    d = strict_json(out)
    st, speed = d["start"], 0.5 / math.sqrt(9.81 * 0.012)
    assert code == 0 and st["V"] == pytest.approx(-speed, rel=1e-12) and st["Omega"] == st["Lambda"] == 0.0
    th = math.radians(85)
    h, h_t = math.sin(th) + 0.0625 * math.cos(th), math.cos(th) - 0.0625 * math.sin(th)  # the rim, t/2 = 0.0625
    x_p = h * math.sin(th) + h_t * math.cos(th)  # = 1: the rim's contact is one radius from the axis
    assert st["n"] == pytest.approx(speed / x_p, rel=1e-12) and d["rolling_fraction"] == 1.0


@pytest.mark.parametrize("args, flag, says", [
    (["--spun-about-axis", "40 rev/s"], "--spun-about-axis", "needs --theta0"),
    (["--spun-on-edge", "5 rev/s", "--thickness", "2 mm"], "--spun-on-edge", "cannot stand upright on its edge"),
    (["--rolled", "0.5 m/s", "--thickness", "2 mm"], "--rolled", "give a tilt in (0, 1.5708)"),
    (["--rolled", "0.5 rev/s", "--theta0", "80 deg"], "--rolled", "must be a speed"),
    (["--spun-on-edge", "5 rev/s", "--n0", "3"], "--n0", "does not go with --spun-on-edge"),
    (["--rolled", "0", "--theta0", "80 deg"], "--rolled", "must be a finite nonzero number, got 0.0."),
    (["--spun-on-edge", "nan"], "--spun-on-edge", "must be a finite nonzero number, got nan."),
])
def test_bad_named_starts_name_the_flag_typed(args, flag, says):
    msg = usage_error(["simulate", "--body", "disk", "--radius", "12 mm", "--mu", "0.3", "--t-end", "0.1 s", *args], flag)
    assert says in msg


@pytest.mark.parametrize("n0, word", [(7.0, "unstable"), (12.0, "stable")])
def test_fixed_points_state_the_fast_top_condition_as_the_rolling_linearisation_finds_it(n0, word):
    """The closed form's word (rolling) and the exact linearisation's classification agree on either
    side of n_c = 8.660254 for the cone on its tip."""
    code, out, _ = run_cli("fixed-points", "--body", "cone", "--on", "tip", "--height", "1.5", "--mu", "0.5", "--n0",
                           str(n0), "--json")
    [fp] = strict_json(out)["fixed_points"]
    assert code == 0 and fp["parameter"]["stable_rolling"] == (word == "stable")
    assert fp["parameter"]["rolling_critical_spin"] == pytest.approx(8.660254037844386, rel=1e-14)
    assert fp["classification"].startswith("neutral" if word == "stable" else "unstable")
    _, text, _ = run_cli("fixed-points", "--body", "cone", "--on", "tip", "--height", "1.5", "--mu", "0.5", "--n0",
                         str(n0))
    assert f"rolling: {word} (fast-top condition |n| > 8.660254)" in text
