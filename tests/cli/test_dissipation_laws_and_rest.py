"""Rolling resistance, spin friction and air drag on the command line: each flag takes a number in
phasekit's units or a value with units (lengths with --size, air drag with --size and --mass), the
run ends at rest at the closed-form time with its energy budget, and a bad value is one line naming
the flag as typed, its range and the value typed."""

import math

import phasekit as pk
from phasekit import cli
from phasekit.cli.options import DISSIPATION_FLAGS
from phasekit.cli.params import _law_of
from phasekit.cli.parser import build_parser
from phasekit.friction import AirDrag, RollingResistance, SpinFriction

import numpy as np
import pytest

from ..helpers import run_cli, strict_json, usage_error

BALL = ["simulate", "--body", "tippe-top", "--offset", "0", "--stem-length", "0", "--mu", "0.2",  # a uniform sphere
        "--max-wall", "120"]
#: rolling straight along -e_Y at speed V0 (axis horizontal along e_X, spin n = V0: no slip at the contact)
V0 = 0.5
ROLLING = [*BALL, "--state", "0", repr(-V0), "0", "0", repr(math.pi / 2), repr(V0), "--t-end", "100"]
#: spinning in place about the vertical at N0
N0 = 3.0
SPINNING = [*BALL, "--theta0", "0", "--spin-about-vertical", repr(N0)]
C = 0.4  # the uniform sphere's moments A = C = 2/5


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def _json(*args):
    code, out, err = run_cli(*args, "--json")
    assert code == 0, err
    return strict_json(out)


@pytest.fixture(scope="module")
def rolling_run():
    """The ball rolling with rolling resistance delta = 0.01 (0.1 mm on a 1 cm ball, 20 g), --si."""
    code, out, err = run_cli(*ROLLING, "--rolling-resistance", "0.1 mm", "--size", "1 cm", "--mass", "20 g", "--si",
                             "--stop-at", "rest", "--json")
    assert code == 0, err
    return strict_json(out)


@pytest.mark.timeout(600)
def test_a_ball_rolling_with_rolling_resistance_rests_at_the_closed_form_time(rolling_run):
    """It decelerates at (5/7) g delta / r: at rest at t = V0 / ((5/7) delta), having lost its
    kinetic energy (7/10) V0^2 to rolling resistance alone (none to sliding: it never slips)."""
    d, delta = rolling_run, 0.01
    assert d["status"] == "rest" and d["stop_at"] == "rest" and d["mode_end"] == "rolling"
    assert d["model"]["dissipation"] == [{"law": "rolling-resistance", "delta": pytest.approx(delta, rel=1e-15)}]
    assert d["t_rest"] == pytest.approx(V0 / (5 / 7 * delta), rel=1e-8) and d["t_end"] == d["t_rest"]
    budget = d["energy_budget"]
    assert budget["lost"] == pytest.approx(0.7 * V0**2, rel=1e-10)
    assert budget["dissipated"]["rolling-resistance"] == pytest.approx(budget["lost"], rel=1e-8)
    assert abs(budget["dissipated"]["sliding friction"]) < 1e-12
    assert abs(budget["residual"]) < 1e-8 * budget["lost"]
    assert d["rests_on"] is None and d["rolling_fraction"] == 1.0  # it rolls, but not in pure rolling: energy goes
    assert d["state_end"]["V"] == pytest.approx(0.0, abs=1e-9) and d["state_end"]["n"] == pytest.approx(0.0, abs=1e-9)


@pytest.mark.timeout(600)
def test_si_reports_the_time_of_rest_and_the_energies_in_real_units(rolling_run):
    """b = 1 cm, M = 20 g: the time unit sqrt(b/g), energies in mJ (M g b = 1.962 mJ)."""
    d, si = rolling_run, rolling_run["si"]
    unit = math.sqrt(0.01 / 9.81)
    assert si["t_rest"] == pytest.approx(d["t_rest"] * unit * 1e3, rel=1e-12) and si["units"]["energy"] == "mJ"
    mgb = 0.02 * 9.81 * 0.01 * 1e3
    assert si["energy_budget"]["lost"] == pytest.approx(d["energy_budget"]["lost"] * mgb, rel=1e-12)
    assert si["energy_budget"]["dissipated"]["rolling-resistance"] == pytest.approx(
        d["energy_budget"]["dissipated"]["rolling-resistance"] * mgb, rel=1e-12)


@pytest.mark.timeout(600)
def test_the_text_says_where_the_energy_went_and_when_the_body_rests():
    code, out, err = run_cli(*ROLLING, "--rolling-resistance", "0.1 mm", "--size", "1 cm", "--mass", "20 g", "--si")
    assert code == 0, err
    lines = out.splitlines()
    [energy] = [ln for ln in lines if ln.startswith("energy: ")]
    start, end = (0.7 * V0**2 + 1.0) * 1.962, 1.962  # mJ: kinetic + potential (G at height b), then potential
    assert energy.startswith(f"energy: {start:.8g} -> {end:.8g} mJ, lost {start - end:.6g}: ") and "rolling-resistance" in energy
    [rest] = [ln for ln in lines if ln.startswith("at rest at t = ")]
    assert float(rest.split("= ")[1].removesuffix(" s")) == pytest.approx(70 * math.sqrt(0.01 / 9.81), rel=1e-5)
    assert lines[0].startswith("status: rest (at rest at t = 70")
    assert not any(ln.startswith("pure rolling") for ln in lines)


# the spinning sphere compiles its own integrators (~14 s cold each): the full run only; the closed forms are
# tests/friction/test_dissipation_laws.py's, the flags' units test_air_drag_typed_with_units_is_converted_with_the_mass
@pytest.mark.slow
@pytest.mark.timeout(600)
def test_spin_friction_in_mm_with_size_is_the_same_run_as_in_units_of_b():
    """--spin-friction '0.5 mm' with --size '1 cm' is mu_s = 0.05; a sphere spinning in place
    about the vertical at n0 stops at t = C n0 / (mu_s R) (R = 1)."""
    plain = _json(*SPINNING, "--spin-friction", "0.05", "--stop-at", "rest", "--t-end", "100")
    units = _json(*SPINNING, "--spin-friction", "0.5 mm", "--size", "1 cm", "--stop-at", "rest", "--t-end", "100")
    assert units["model"]["dissipation"] == [{"law": "spin-friction", "mu_s": pytest.approx(0.05, rel=1e-15)}]
    assert plain["model"]["dissipation"] == [{"law": "spin-friction", "mu_s": 0.05}]
    assert plain["status"] == units["status"] == "rest"
    assert plain["t_rest"] == pytest.approx(C * N0 / 0.05, rel=1e-8)
    assert units["t_rest"] == pytest.approx(plain["t_rest"], rel=1e-13)
    budget = plain["energy_budget"]
    assert budget["lost"] == pytest.approx(0.5 * C * N0**2, rel=1e-12)
    assert abs(budget["residual"]) < 1e-8 * budget["lost"]


@pytest.mark.slow  # see above
@pytest.mark.timeout(600)
def test_linear_air_drag_spins_a_sphere_down_exponentially():
    """--air-drag K1 is the couple -K1 w: a sphere spinning in place slows as n0 exp(-K1 t / C)."""
    k1, t_end = 0.01, 5.0
    d = _json(*SPINNING, "--air-drag", repr(k1), "--stop-at", "none", "--t-end", repr(t_end))
    assert d["model"]["dissipation"] == [{"law": "air-drag", "rotation": k1, "rotation_quadratic": 0.0,
                                          "translation": 0.0, "translation_quadratic": 0.0}]
    assert d["status"] == "completed" and d["t_rest"] is None
    assert d["state_end"]["n"] == pytest.approx(N0 * math.exp(-k1 * t_end / C), rel=1e-8)
    budget = d["energy_budget"]
    assert budget["dissipated"]["air-drag"] == pytest.approx(0.5 * C * N0**2 * (1 - math.exp(-2 * k1 * t_end / C)),
                                                             rel=1e-8)
    assert abs(budget["residual"]) < 1e-8 * budget["lost"]


def test_each_flag_builds_its_law_and_zero_leaves_it_out():
    law = _law_of("coulomb", 0.2, None, {"rolling_resistance": 0.01, "spin_friction": 0.0, "air_drag": 0.0,
                                         "air_drag_force": 0.3, "air_drag_force_quadratic": 0.4})
    assert law.dissipation == (RollingResistance(0.01), AirDrag(translation=0.3, translation_quadratic=0.4))
    law = _law_of("coulomb", 0.2, None, {"air_drag": 1.0, "air_drag_quadratic": 2.0, "spin_friction": 0.02})
    assert law.dissipation == (AirDrag(rotation=1.0, rotation_quadratic=2.0), SpinFriction(0.02))
    assert _law_of("viscous", 0.2, None, {"spin_friction": 0.0, "air_drag": 0.0}).dissipation == ()


def _parsed(*args):
    """The simulate arguments after the CLI's conversion of values with units."""
    from phasekit.cli.inputs import apply_units

    args = build_parser().parse_args(["simulate", "--a", "1.5", "--mu", "0.1", "--state", *"000010", *args])
    apply_units(args)
    return args


def test_air_drag_typed_with_units_is_converted_with_the_mass():
    """b = 1 cm, M = 20 g, g = 9.81: k1 in M b^2 sqrt(g/b), k2 in M b^2, c1 in M sqrt(g/b), c2 in M/b."""
    M, b, g = 0.02, 0.01, 9.81
    args = _parsed("--size", "1 cm", "--mass", "20 g", "--air-drag", "3e-6 N*m*s", "--air-drag-quadratic",
                   "4e-7 kg*m^2", "--air-drag-force", "0.05 N*s/m", "--air-drag-force-quadratic", "0.2 kg/m",
                   "--rolling-resistance", "20 um", "--spin-friction", "0.3 mm")
    assert args.air_drag == pytest.approx(3e-6 / (M * b**2 * math.sqrt(g / b)), rel=1e-14)
    assert args.air_drag_quadratic == pytest.approx(4e-7 / (M * b**2), rel=1e-14)
    assert args.air_drag_force == pytest.approx(0.05 / (M * math.sqrt(g / b)), rel=1e-14)
    assert args.air_drag_force_quadratic == pytest.approx(0.2 / (M / b), rel=1e-14)
    assert args.rolling_resistance == pytest.approx(0.002, rel=1e-14) and args.spin_friction == pytest.approx(0.03)
    assert _parsed("--air-drag", "0.25").air_drag == 0.25  # a bare number is in phasekit's units



UNITS = {"rolling_resistance": "b", "spin_friction": "b", "patch": "b", "air_drag": "M b^2 sqrt(g/b)", "air_layer": "M b^2 sqrt(g/b)",
         "air_drag_quadratic": "M b^2",
         "air_drag_force": "M sqrt(g/b)", "air_drag_force_quadratic": "M/b"}


@pytest.mark.parametrize("value", ["-0.01", "nan", "inf", "1001"])
@pytest.mark.parametrize("dest", sorted(DISSIPATION_FLAGS))
@pytest.mark.parametrize("command", ["simulate", "steady-states"])
def test_a_bad_coefficient_is_one_line_naming_the_flag_its_range_and_the_value(command, dest, value):
    flag = "--" + dest.replace("_", "-")
    base = SPINNING if command == "simulate" else ["steady-states", "--a", "1.5", "--mu", "0.1"]
    msg = usage_error([*base, flag, value], flag)
    upper = "0.5" if dest == "patch" else "1000"  # a patch as wide as the body is not a contact patch
    assert msg == f"{flag} must lie in [0, {upper}] (units {UNITS[dest]}), got {float(value)!r}."


@pytest.mark.parametrize("args, flag, says", [
    (["--spin-friction", "3 s", "--size", "1 cm"], "--spin-friction", "must be a spin friction (dimension [length]"),
    (["--rolling-resistance", "2 g", "--size", "1 cm"], "--rolling-resistance", "must be a rolling resistance"),
    (["--air-drag", "1e-7 N*m", "--size", "1 cm", "--mass", "20 g"], "--air-drag", "must be an air drag"),
    (["--spin-friction", "0.5 mm"], "--spin-friction", "give the body's size with --size"),
    (["--air-drag", "1e-7 N*m*s", "--size", "1 cm"], "--air-drag", "needs the body's mass"),
    (["--air-drag-force", "1e-4 N*s/m", "--size", "1 cm"], "--air-drag-force", "units M sqrt(g/b): give --mass"),
    (["--rolling-resistance", "2 cm", "--size", "0.01 mm"], "--rolling-resistance", "got '2 cm' (2000.0 in units of b)"),
    (["--mass", "20 g"], "--mass", "--mass needs --size"),
    (["--mass", "20 mm", "--size", "1 cm"], "--mass", "must be a mass"),
])
def test_a_value_with_wrong_units_is_refused_naming_the_flag(args, flag, says):
    msg = usage_error([*SPINNING, *args], flag)
    assert msg.startswith(flag) and says in msg
    typed = args[args.index(flag) + 1]
    assert repr(typed) in msg


def test_stop_at_rest_without_a_dissipation_law_runs_as_none_and_says_so():
    code, out, err = run_cli("simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0",
                             "10", "--stop-at", "rest", "--t-end", "3", "--max-wall", "60", "--json")
    d = strict_json(out)
    assert code == 0 and d["status"] == "completed" and d["stop_at"] == "rest" and d["t_end"] == 3.0
    assert "t_rest" not in d and "energy_budget" not in d  # the JSON of a run without dissipation is as before
    assert err.startswith("phasekit: warning: --stop-at rest runs as --stop-at none") and err.count("\n") == 1


@pytest.mark.timeout(600)
def test_the_steady_state_commands_take_the_laws_into_their_model():
    rolling = {"law": "rolling-resistance", "delta": 0.02}
    d = _json("fixed-points", "--a", "1.5", "--mu", "0.1", "--omega0", "10", "--rolling-resistance", "0.02",
              "--spin-friction", "0", "--max-wall", "300")
    assert d["status"] == "completed" and d["model"]["dissipation"] == [rolling]
    d = _json("steady-states", "--a", "1.5", "--mu", "0.1", "--rolling-resistance", "0.02", "--air-drag", "0.001",
              "--max-wall", "300")
    assert d["model"]["dissipation"] == [rolling, {"law": "air-drag", "rotation": 0.001, "rotation_quadratic": 0.0,
                                                   "translation": 0.0, "translation_quadratic": 0.0}]


def test_a_dissipative_run_that_ends_at_its_start_has_an_energy_budget():
    """A flat disk spun about the vertical at a tilt lifts off at t = 0 (R < 0 there): the JSON
    still carries the budget, nothing lost, its energy that of the start (1/2 I w^2 + M g z_G),
    and the text output its energy line."""
    args = ["simulate", "--body", "disk", "--thickness", "0", "--mu", "0.5", "--rolling-resistance", "0.02",
            "--theta0", "0.5", "--spin-about-vertical", "4", "--t-end", "40"]
    code, out, err = run_cli(*args, "--json")
    d = strict_json(out)
    assert code == 0 and d["events"][0]["t"] == 0.0 and d["events"][0]["kind"] == "lift-off"
    b = d["energy_budget"]
    assert b["lost"] == 0.0 and b["energy_start"] == b["energy_end"]
    body = pk.Disk(0.0)
    # uniform thin disk of unit radius: A = 1/4, C = 1/2 (units M b^2); spin about the vertical at tilt theta
    theta, w = 0.5, 4.0
    A, C = body.A, body.C
    kinetic = 0.5 * (A * np.sin(theta) ** 2 + C * np.cos(theta) ** 2) * w ** 2
    assert b["energy_start"] == pytest.approx(kinetic + body.h(theta)[0], rel=1e-12)
    code, text, _ = run_cli(*args)
    assert code == 0 and "energy:" in text
