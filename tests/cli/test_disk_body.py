"""--body disk: a thin disk by default, --thickness over the radius or with units by --radius (the
unit of length, as --size, which it replaces); bad input is one line naming the flag typed, its
range and the value typed."""

import math

import phasekit as pk
from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json, usage_error

DISK = ["simulate", "--body", "disk", "--mu", "0.5", "--theta0", "1.0", "--spin-about-vertical", "5", "--t-end", "2"]
#: a disk of radius 3.7 cm and thickness 1.2 cm launched at 60 deg spinning at 5 rev/s about the vertical
REAL = ["--theta0", "60 deg", "--spin-about-vertical", "5 rev/s", "--t-end", "0.5 s", "--json"]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")



def test_a_disk_is_thin_by_default_and_its_thickness_is_in_radii():
    code, out, _ = run_cli(*DISK, "--json")
    model = strict_json(out)["model"]
    assert code == 0 and model["body"] == "disk" and model["thickness"] == 0.0 and (model["A"], model["C"]) == (0.25, 0.5)
    code, out, _ = run_cli(*DISK, "--thickness", "0.1", "--json")
    model = strict_json(out)["model"]
    assert code == 0 and model["thickness"] == 0.1 and model["A"] == pytest.approx(0.25 + 0.01 / 12, rel=1e-15)
    assert model["description"].startswith("disk, thickness 0.1 radii")


def test_radius_sets_the_unit_of_length_as_size_does():
    base = ["simulate", "--body", "disk", "--mu", "0.5"]
    code, out, _ = run_cli(*base, "--radius", "3.7 cm", "--thickness", "1.2 cm", *REAL, "--si")
    by_radius = strict_json(out)
    thickness = by_radius["model"]["thickness"]  # 1.2 cm / 3.7 cm, to rounding
    code_size, out, _ = run_cli(*base, "--size", "3.7 cm", "--thickness", repr(thickness), *REAL)
    by_size = strict_json(out)
    assert code == code_size == 0 and by_radius["model"]["thickness"] == pytest.approx(1.2 / 3.7, rel=1e-15)
    assert by_radius["model"] == by_size["model"] and by_radius["t_end"] == by_size["t_end"]
    assert by_radius["state_end"] == by_size["state_end"] and by_radius["si"]["b"] == "3.7 cm"
    # the launch in the disk's units: 5 rev/s = 10 pi rad/s in units sqrt(g/b), b = 3.7 cm, g = 9.81 m/s^2
    assert by_radius["start"]["theta"] == pytest.approx(math.pi / 3, rel=1e-15)
    assert by_radius["start"]["Omega"] == pytest.approx(10 * math.pi * math.sqrt(0.037 / 9.81), rel=1e-12)


@pytest.mark.parametrize("extra, flag, says", [
    (["--radius", "3.7 cm", "--size", "3 cm"], "--radius", "--radius and --size both set the unit of length"),
    (["--thickness", "1.2 cm"], "--thickness", "give the disk's radius with --radius"),
    (["--radius", "3.7 cm", "--thickness", "-1 cm"], "--thickness",
     "must lie in [0, 1000] (the full thickness over the radius), got '-1 cm' (-0.2702702702702703 in units of b)."),
    (["--thickness", "2e3"], "--thickness", "must lie in [0, 1000] (the full thickness over the radius), got 2000.0."),
    (["--thickness", "nan"], "--thickness", "must lie in [0, 1000]"),
    (["--radius", "3.7 s"], "--radius", "must be a length"),
    (["--radius", "3.7 cm", "--thickness", "2 s"], "--thickness", "must be a length"),
    (["--a", "1.5"], "--a", "does not apply to the disk body (its parameters: thickness, flat_angle)"),
    (["--flat-angle", "1e-8"], "--flat-angle", "must lie in [1e-06, 0.1] (radians), got 1e-08."),
    (["--flat-angle", "1 cm"], "--flat-angle", "must be an angle"),
    (["--mass", "20 g"], "--mass", "--mass needs --radius"),
    (["--A", "0.7", "--C", "1.2"], "--C", "must be at most 1"),
])
def test_bad_disk_input_names_the_flag_typed(extra, flag, says):
    msg = usage_error([*DISK, *extra], flag)
    assert msg.startswith(flag) and says in msg


@pytest.mark.parametrize("start, flag, says", [
    (["--thickness", "0.1", "--theta0", "100 deg", "--spin-about-vertical", "5"], "--theta0",
     "--theta0 must lie in (0, pi/2) for this disk (at 0 it lies flat, at pi/2 its side touches the table), got "
     "'100 deg' (1.7453292519943295 rad)."),
    (["--thickness", "0.1", "--state", "0", "0", "0", "0", "1.6", "0"], "--state (theta)",
     "--state (theta) must lie in (0, pi/2) for this disk"),
    (["--theta0", "0", "--spin-about-vertical", "5"], "--theta0", "--theta0 must lie in (0, pi) for this disk (at 0 and "
                                                                  "pi it lies flat), got 0.0."),
])
def test_a_start_beyond_the_disks_range_is_refused(start, flag, says):
    msg = usage_error(["simulate", "--body", "disk", "--mu", "0.5", "--t-end", "2", *start], flag.split(" (")[0])
    assert msg.startswith(says)


@pytest.mark.parametrize("args, flag", [
    (["simulate", "--a", "1.5", "--radius", "2 cm", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10"],
     "--radius"),
    (["simulate", "--a", "1.5", "--thickness", "0.1", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10"],
     "--thickness"),
    (["simulate", "--thickness", "0.1", "--mu", "0.1", "--paper-start", "5.2"], "--thickness"),
    (["steady-states", "--body", "disk", "--thickness", "1.2 cm", "--mu", "0.1"], "--thickness"),
])
def test_disk_flags_elsewhere_are_refused_naming_them(args, flag):
    usage_error(args, flag)


def test_a_disk_run_stopped_as_the_face_comes_down():
    """Euler's disk spinning in place at 30 deg with rolling resistance, stopped at theta = 1e-3."""
    omega = 1 / math.sqrt(0.25 * 0.5)  # Omega^2 = 1 / (A sin theta)
    state = ["0", "0", repr(omega), "0", repr(math.pi / 6), "0"]
    code, out, _ = run_cli("simulate", "--body", "disk", "--friction", "viscous", "--mu", "1", "--rolling-resistance",
                           "0.05", "--state", *state, "--stop-at", "theta=0.001", "--t-end", "500", "--rtol", "1e-12",
                           "--json")
    d = strict_json(out)
    assert code == 0 and d["status"] == "stopped" and d["t_end"] == pytest.approx(20.8348090098, rel=1e-9)
    assert d["state_end"]["theta"] == pytest.approx(1e-3, rel=1e-9) and d["state_end"]["Omega"] > 20 * omega


def test_the_face_comes_down_at_the_flat_angle_typed():
    """A disk released at rest at 2 deg falls flat: the run ends at the --flat-angle typed (1 deg),
    which the model's description carries (pk.rerun rebuilds the same limit)."""
    code, out, _ = run_cli("simulate", "--body", "disk", "--mu", "0.5", "--state", "0", "0", "0", "0", "0.035", "0",
                           "--t-end", "5", "--flat-angle", "1 deg", "--json")
    d = strict_json(out)
    assert code == 0 and d["status"] == "stopped" and d["events"][-1]["kind"] == "face down"
    assert d["state_end"]["theta"] == pytest.approx(math.radians(1.0), rel=1e-9)
    assert d["model"]["flat_angle"] == pytest.approx(math.radians(1.0), rel=1e-15)


TOY = ["simulate", "--body", "disk", "--radius", "37.5 mm", "--thickness", "12 mm", "--mu", "0.3", "--theta0", "30 deg",
       "--mass", "416 g"]


def test_eulers_disk_toy_spins_in_place_from_the_cli():
    """The toy (75 mm across, 12 mm thick, 416 g) started spinning in place at 30 deg: on its steady
    branch G stays at rest and the tilt holds (exact Coulomb friction, no loss). A thin disk so
    started precesses at the classical rate of a uniform disk rolling with its centre at rest,
    Omega^2 = 4 g / (a sin(alpha)), alpha the angle between disk and table (Moffatt, Nature 2000)."""
    code, out, err = run_cli(*TOY, "--spinning-in-place", "--t-end", "2 s", "--json")
    d = strict_json(out)
    assert code == 0 and d["status"] == "completed" and "leaves the table" not in err
    assert abs(d["theta_change"]) < 1e-9 and abs(d["pose_end"]["X"]) < 1e-9 and abs(d["pose_end"]["Y"]) < 1e-9
    code, out, err = run_cli("simulate", "--body", "disk", "--thickness", "0", "--mu", "0.3", "--theta0", "30 deg",
                             "--spinning-in-place", "--t-end", "5", "--json")
    d = strict_json(out)
    assert code == 0 and d["state_end"]["Omega"] == pytest.approx(math.sqrt(4 / math.sin(math.radians(30))), rel=1e-12)


def test_a_start_that_leaves_the_table_at_once_warns():
    """Spun about the vertical at 30 deg with G at rest, the toy's reaction is negative at t = 0: the
    run says so on stderr, in one line, and still gives its result."""
    code, out, err = run_cli(*TOY, "--spin-about-vertical", "5 rev/s", "--t-end", "0.2 s", "--json")
    d = strict_json(out)
    warned = [ln for ln in err.splitlines() if "leaves the table at once" in ln]
    assert code == 0 and d["events"][0]["t"] == 0.0 and d["events"][0]["kind"] == "lift-off" and len(warned) == 1
    assert warned[0].startswith("phasekit: warning: ")


FALLING = ["simulate", "--body", "disk", "--mu", "0.5", "--rolling-resistance", "0.05", "--spinning-in-place",
           "--theta0", "0.3", "--t-end", "100", "--stop-at", "rest"]


def test_with_stop_at_rest_a_disk_that_comes_down_flat_slides_and_spins_on_its_face_to_rest():
    """Euler's disk brought down by rolling resistance: with --stop-at rest it lands on its face and
    slides and spins there to rest (phasekit.core.face); the summary says so, the energy line has the
    face's friction, and the strict JSON carries the face phase and reruns to the same end."""
    code, text, err = run_cli(*FALLING)
    assert code == 0 and "status: rest (lies flat; slid and spun on its face to rest at t = 15.468" in text
    assert "on its face from t = 15.44696" in text and "face friction" in text and "mode_end: face" in text
    assert "never comes to rest" not in err
    code, out, _ = run_cli(*FALLING, "--json")
    d = strict_json(out)
    f = d["face"]
    assert code == 0 and d["status"] == "rest" and d["t_end"] == f["t_end"] and d["mode_end"] == "face"
    assert abs(f["t_stop_slide"] - f["t_stop_spin"]) < 1e-9 and f["t_start"] == d["events"][-3]["t"]
    assert [e["kind"] for e in d["events"][-3:]] == ["face down", "on its face", "at rest"]
    b = d["energy_budget"]
    assert b["dissipated"]["face friction"] == pytest.approx(f["energy_start"], rel=1e-9) and abs(b["residual"]) < 1e-8
    assert pk.rerun(d).t == d["t_end"]
