"""--body cone: on the rim of its base by default or on its tip (--on tip), --height over the base's
radius or with units by --radius (the unit of length, as --size, which it replaces); a start off
the contact's range of theta is refused; bad input is one line naming the flag typed, its range
and the value typed."""

import math

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json, usage_error

CONE = ["simulate", "--body", "cone", "--mu", "0.5", "--theta0", "1.0", "--spin-about-vertical", "5", "--t-end", "2"]
#: a cone of base radius 2 cm and height 4 cm on its tip, launched at 170 deg spinning at 20 rev/s
REAL = ["--on", "tip", "--theta0", "170 deg", "--spin-about-vertical", "20 rev/s", "--t-end", "0.05 s", "--json"]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")



def test_a_cone_is_on_its_rim_by_default_and_its_height_is_in_radii():
    code, out, _ = run_cli(*CONE, "--json")
    model = strict_json(out)["model"]
    assert code == 0 and model["body"] == "cone" and (model["height"], model["on"]) == (1.0, "rim")
    assert (model["A"], model["C"]) == (pytest.approx(0.15 * 1.25, rel=1e-15), 0.3)  # 3/20 (1 + l^2/4), 3/10
    code, out, _ = run_cli(*CONE, "--height", "2", "--json")
    model = strict_json(out)["model"]
    assert code == 0 and model["height"] == 2.0 and model["A"] == pytest.approx(0.3, rel=1e-15)
    assert model["description"] == "cone, height 2 radii (on its rim), A=0.3, C=0.3"


def test_radius_sets_the_unit_of_length_as_size_does():
    base = ["simulate", "--body", "cone", "--mu", "0.3"]
    code, out, _ = run_cli(*base, "--radius", "2 cm", "--height", "4 cm", *REAL, "--si")
    by_radius = strict_json(out)
    code_size, out, _ = run_cli(*base, "--size", "2 cm", "--height", "2", *REAL)
    by_size = strict_json(out)
    assert code == code_size == 0 and by_radius["model"]["height"] == pytest.approx(2.0, rel=1e-15)
    assert by_radius["model"]["on"] == "tip" and by_radius["model"] == by_size["model"]
    assert by_radius["state_end"] == by_size["state_end"] and by_radius["si"]["b"] == "2 cm"
    # the launch in the cone's units: 20 rev/s = 40 pi rad/s in units sqrt(g/b), b = 2 cm, about the
    # vertical (Omega), whose part along the axis pointing down to the tip is the spin n = Omega cos(theta) < 0
    rate, theta = 40 * math.pi * math.sqrt(0.02 / 9.81), math.pi * 17 / 18
    assert by_radius["start"]["theta"] == pytest.approx(theta, rel=1e-15)
    assert by_radius["start"]["Omega"] == pytest.approx(rate, rel=1e-12)
    assert by_radius["start"]["n"] == pytest.approx(rate * math.cos(theta), rel=1e-12)


def test_a_top_sleeping_on_its_point_stays_upright():
    """On its tip at theta = pi (the vector chart), spinning: it sticks and stays."""
    code, out, _ = run_cli("simulate", "--body", "cone", "--on", "tip", "--height", "2", "--mu", "0.5", "--theta0",
                           "180 deg", "--spin-about-vertical", "5", "--t-end", "2", "--json")
    d = strict_json(out)
    assert code == 0 and d["status"] == "completed" and d["chart"] == "vector" and d["mode_end"] == "rolling"
    assert d["theta_end"] == pytest.approx(math.pi, rel=1e-13) and d["R_min"] == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize("extra, flag, says", [
    (["--radius", "2 cm", "--size", "3 cm"], "--radius", "--radius and --size both set the unit of length b (the "
                                                         "cone's base radius)"),
    (["--height", "1.2 cm"], "--height", "give the cone's base radius with --radius"),
    (["--radius", "2 cm", "--height", "-1 cm"], "--height",
     "must lie in (0, 1000] (from the base to the tip over the base's radius), got '-1 cm' (-0.5 in units of b)."),
    (["--height", "0"], "--height", "must lie in (0, 1000] (from the base to the tip over the base's radius), got 0.0."),
    (["--height", "2e3"], "--height", "must lie in (0, 1000]"),
    (["--height", "nan"], "--height", "must lie in (0, 1000]"),
    (["--radius", "2 cm", "--height", "2 s"], "--height", "must be a length"),
    (["--on", "side"], "--on", "must be one of rim, tip, got 'side'."),
    (["--thickness", "0.1"], "--thickness", "does not apply to the cone body (its parameters: height, on)"),
    (["--a", "1.5"], "--a", "does not apply to the cone body"),
    (["--mass", "20 g"], "--mass", "--mass needs --radius (the cone's base radius"),
    (["--A", "0.7", "--C", "1.2"], "--C", "must be at most 1"),
])
def test_bad_cone_input_names_the_flag_typed(extra, flag, says):
    msg = usage_error([*CONE, *extra], flag)
    assert msg.startswith(flag) and says in msg


@pytest.mark.parametrize("start, flag, says", [
    (["--height", "2", "--theta0", "2.1", "--spin-about-vertical", "5"], "--theta0",
     "--theta0 must lie in (0, 2.03444) for this cone (on its rim; at 0 it stands on its base, at 2.03444 its side "
     "touches the table), got 2.1."),
    (["--height", "2", "--on", "tip", "--theta0", "100 deg", "--spin-about-vertical", "5"], "--theta0",
     "--theta0 must lie in (2.03444, pi] for this cone (on its tip; at 2.03444 its side touches the table), got "
     "'100 deg' (1.7453292519943295 rad)."),
    (["--height", "2", "--on", "tip", "--state", "0", "0", "0", "0", "1.6", "0"], "--state (theta)",
     "--state (theta) must lie in (2.03444, pi] for this cone"),
])
def test_a_start_beyond_the_contacts_range_is_refused(start, flag, says):
    msg = usage_error(["simulate", "--body", "cone", "--mu", "0.5", "--t-end", "2", *start], flag.split(" (")[0])
    assert msg.startswith(says)


@pytest.mark.parametrize("args, flag", [
    (["simulate", "--a", "1.5", "--height", "2", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10"],
     "--height"),
    (["simulate", "--body", "disk", "--on", "tip", "--mu", "0.1", "--theta0", "1.0", "--spin-about-vertical", "5"],
     "--on"),
    (["simulate", "--a", "1.5", "--radius", "2 cm", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10"],
     "--radius"),
    (["simulate", "--height", "2", "--mu", "0.1", "--paper-start", "5.2"], "--height"),
    (["steady-states", "--body", "cone", "--height", "1.2 cm", "--mu", "0.1"], "--height"),
    (["simulate", "--body", "pyramid", "--mu", "0.1", "--theta0", "1.0", "--spin-about-vertical", "5"], "--body"),
])
def test_cone_flags_elsewhere_are_refused_naming_them(args, flag):
    msg = usage_error(args, flag)
    if flag == "--body":
        assert "spheroid, tippe-top, egg, disk, cone" in msg


def test_the_steady_states_of_a_cone_on_its_rim_lie_on_its_rim():
    """fixed-points keeps the states inside the rim's range: at Omega = 3 the precession that
    continues the balance on the rim (tan(theta) = 4/l) and an intermediate one; steady-states gives
    the structure on the rim's range, its branch ending where the base and the side come down."""
    code, out, _ = run_cli("fixed-points", "--body", "cone", "--height", "2", "--mu", "0.3", "--omega0", "3", "--json")
    d = strict_json(out)
    assert code == 0 and d["model"]["body"] == "cone"
    thetas = sorted(fp["state"]["theta"] for fp in d["fixed_points"])
    assert len(thetas) == 2 and 0.0 < thetas[0] and thetas[1] < math.pi - math.atan(2.0)
    assert thetas[1] == pytest.approx(math.atan(2.0), rel=1e-12)  # h_theta = 0: the spin-free balance, spun
    code, out, _ = run_cli("steady-states", "--body", "cone", "--height", "2", "--mu", "0.3", "--json")
    d = strict_json(out)
    assert code == 0 and d["status"] == "completed" and d["signature"] == "limit-cross-limit"
    assert [e["limit"] for e in d["branches"][0]["ends"]] == ["face down", "side down"]
