"""Ten everyday task commands, typed as a new user types them (SI units, short end times), and
every kind of summary line they print checked against the run's own data: each line's claim is
recomputed from the trajectory's samples (a fine grid of its dense output), its events or the
body, never read back from the summary's own numbers.

The commands are listed in docs/cli.md ("Ten everyday commands"). The CLI has no command of its
own for a Dask cluster, NetCDF/Parquet files or a notebook: those tasks start from the run given
here (the run a sweep's task repeats, whose samples a file keeps, that a notebook makes first),
and the Parquet file's samples are checked against the summary too.
"""

import math
import re
import warnings

import phasekit as pk
import phasekit.cli.params as params
from phasekit.bodies.by_name import make_body
from phasekit.cli.inputs import _stem

import numpy as np
import pandas as pd
import pytest

from ..helpers import run_cli

#: the ten commands (argv after "phasekit"), by task
COMMANDS = {
    "tippe top": "simulate --body tippe-top --size '12.5 mm' --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --slip-eps 1e-3 "
                 "--theta0 '5 deg' --spin-about-vertical '25 rev/s' --stop-at none --t-end '1 s' --si",
    "Euler's disk": "simulate --body disk --radius '37.5 mm' --thickness '12 mm' --mu 0.3 --theta0 '30 deg' "
                    "--spinning-in-place --air-layer 1e-4 --t-end '1 s' --si",
    "coin": "simulate --body disk --radius '12 mm' --thickness '1.5 mm' --mu 0.3 --theta0 '80 deg' "
            "--spun-on-edge '5 rev/s' --t-end '1 s' --si",
    "egg": "simulate --body egg --size '2.2 cm' --a 1.3 --w 0.1 --mu 0.3 --slip-eps 1e-4 --theta0 '80 deg' "
           "--spin-about-vertical '8 rev/s' --t-end '1 s' --si",
    "energy per mechanism": "simulate --a 1.5 --size '2 cm' --mass '20 g' --mu 0.3 --theta0 '90 deg' "
                            "--spin-about-vertical '2 rev/s' --spin-friction '1 mm' --rolling-resistance '0.5 mm' "
                            "--air-drag '1e-8 N*m*s' --t-end '2 s' --si",
    "Dask cluster": "simulate --a 1.5 --size '2 cm' --mu 0.1 --slip-eps 1e-3 --gyroscopic --theta0 '89 deg' "
                    "--omega0 '15 rev/s' --t-end '1 s' --si",
    "NetCDF/Parquet": "simulate --a 1.5 --size '3 cm' --mu 0.1 --theta0 '60 deg' --spin-about-vertical '10 rev/s' "
                      "--stop-at none --t-end '1 s' --si",
    "spinning top": "simulate --body cone --on tip --radius '2 cm' --height '3 cm' --mu 0.5 --theta0 '175 deg' "
                    "--spun-about-axis '40 rev/s' --t-end '2 s' --si",
    "stemmed tippe top's steady states": "steady-states --body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3",
    "notebook": "simulate --a 0.6 --size '2 cm' --mu 0.2 --theta0 '10 deg' --spun-about-axis '5 rev/s' "
                "--t-end '1 s' --si",
}
RUNS = [k for k, v in COMMANDS.items() if v.startswith("simulate")]
N = 20001  # samples on the grid


def _argv(text):
    return [a.strip("'") for a in re.findall(r"'[^']*'|\S+", text)]


@pytest.fixture(scope="module")
def runs():
    """Each command run once: (its text output, its trajectory, the samples on a grid)."""
    out = {}
    original = params.run_start
    for task, command in COMMANDS.items():
        caught = {}

        def grab(**kw):
            res = original(**kw)
            caught["traj"] = res[0]
            return res

        params.run_start = grab
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                code, text, _ = run_cli(*_argv(command))
        finally:
            params.run_start = original
        assert code == 0, (task, text)
        traj = caught.get("traj")
        samples = None if traj is None else traj.sample(np.linspace(traj.t0, traj.t, N))
        out[task] = (text.splitlines(), traj, samples)
    return out


def _lines(runs, pattern, tasks=RUNS):
    """(task, match, trajectory, samples) for every line matching ``pattern``; at least one."""
    found = [(task, m, runs[task][1], runs[task][2]) for task in tasks for line in runs[task][0]
             if (m := re.match(pattern, line))]
    assert found, pattern
    return found


def _time_unit(command: str) -> float:
    """sqrt(b/g) in seconds from the size typed (mm or cm)."""
    value, unit = re.search(r"--(?:size|radius) '([\d.]+) (mm|cm)'", command).groups()
    return math.sqrt(float(value) * {"mm": 1e-3, "cm": 1e-2}[unit] / 9.81)


def test_every_command_runs_and_is_checked():
    assert len(COMMANDS) == 10 and len(RUNS) == 9


def test_status_lines_match_the_run_and_a_rest_is_at_the_runs_end(runs):
    pattern = r"status: (\w+)(?: \((.*)\))?$"
    for task, m, traj, df in _lines(runs, pattern):
        assert m[1] == traj.status.value, task
        if m[1] in ("rest", "stopped"):  # "at rest at t = X: ...", "... not integrated (t = X)": X the run's end
            assert float(re.search(r"t = ([\d.e+-]+)", m[2])[1]) == pytest.approx(df["t"].iloc[-1], rel=1e-9)
    # the tippe top reaches its stem and rests on ball and stem: the one-point model's limit
    assert {m[1] for _, m, _, _ in _lines(runs, pattern)} == {"completed", "rest", "stopped"}


def test_theta_lines_say_how_the_tilt_changed_over_the_samples(runs):
    pattern = r"theta (grew|fell|did not change)(?: by ([\d.e+-]+) rad)?, ([\d.e+-]+) -> ([\d.e+-]+)( \(the axis passed)?"
    for task, m, traj, df in _lines(runs, pattern):
        theta = df["theta"].to_numpy()
        change = theta[-1] - theta[0]
        assert float(m[3]) == pytest.approx(theta[0], rel=1e-5) and float(m[4]) == pytest.approx(theta[-1], rel=1e-5)
        if m[1] == "did not change":  # a steady state held: it held all along, not only at the ends
            assert np.abs(theta - theta[0]).max() < 1e-7, task
        else:
            assert (change > 0) == (m[1] == "grew") and float(m[2]) == pytest.approx(abs(change), rel=1e-3), task
        assert bool(m[5]) == bool((theta[0] - np.pi / 2) * (theta[-1] - np.pi / 2) < 0), task
    assert {m[1] for _, m, _, _ in _lines(runs, pattern)} == {"grew", "fell", "did not change"}


def test_holding_lines_give_the_share_of_the_samples_held_and_how_little_they_slip(runs):
    pattern = (r".*; (rolling without slip|rolling or pivoting without slip|slipping slowly \(slip below 10 eps[^)]*\)|"
               r"creeping \([^)]*\)) "
               r"([\d.]+)% of the run(?:, first from t = ([\d.e+-]+)| \(it never stuck\))$")
    kinds = set()
    for task, m, traj, df in _lines(runs, pattern):
        held = df["mode"].isin(["rolling", "rolling_no_pivot", "pivoting"]).to_numpy()  # the modes without slip
        assert 100 * held.mean() == pytest.approx(float(m[2]), abs=0.1), task
        dt = (traj.t - traj.t0) / (N - 1)
        if m[3] is None:
            assert not held.any()
        else:
            first = df["t"].to_numpy()[held][0]
            assert float(m[3]) - 1e-5 * abs(float(m[3])) - 1e-9 <= first <= float(m[3]) + dt + 1e-9, task
        slip = df["slip"].to_numpy()[held]
        word = m[1].split()[0]
        kinds.add(word)
        bound = 1e-7 if word == "rolling" else 10 * traj.model.friction.eps
        assert slip.max() < bound, (task, slip.max(), bound)
        # creeping: the regularised law's slip stays of order eps (neither 0 nor many eps)
        if word == "creeping":
            assert 0.01 * traj.model.friction.eps < np.median(slip) < 2 * traj.model.friction.eps, task
        if "pivoting" in m[1]:  # in place: G still, the axis's tilt held
            assert (df["mode"] == "pivoting").any() and np.ptp(df["X"]) < 1e-9 and np.ptp(df["theta"]) < 1e-9, task
    assert kinds == {"rolling", "slipping", "creeping"}


def test_a_run_said_to_be_at_rest_has_no_kinetic_energy_left(runs):
    for task, m, traj, df in _lines(runs, r"at rest at t = ([\d.e+-]+) s$"):
        assert float(m[1]) == pytest.approx(traj.t * _time_unit(COMMANDS[task]), rel=1e-5), task
        kinetic = df["energy"].to_numpy() - df["h"].to_numpy()  # units M g b, G's height the potential
        assert kinetic[-1] < 1e-9 * kinetic[0] and kinetic[0] > 0, (task, kinetic[-1])
        assert traj.status.value == "rest"


def test_a_run_said_to_roll_purely_keeps_its_energy_while_it_rolls(runs):
    for task, _, traj, df in _lines(runs, r"pure rolling: energy is conserved"):
        modes = df["mode"].to_numpy()
        assert modes[-1].startswith("rolling") and not traj.model.friction.dissipation, task
        start = len(modes) - np.argmax(~np.char.startswith(modes[::-1].astype(str), "rolling"))
        start = 0 if np.char.startswith(modes.astype(str), "rolling").all() else start
        energy = df["energy"].to_numpy()[start:]
        assert np.ptp(energy) <= 1e-8 * abs(energy).max(), (task, np.ptp(energy))


def test_energy_lines_give_the_samples_energies_and_what_was_lost(runs):
    pattern = (r"energy: ([\d.e+-]+) -> ([\d.e+-]+) (mJ|M g b), lost ([\d.e+-]+): (.*), at events ([\d.e+-]+) "
               r"\(balance residual")
    for task, m, traj, df in _lines(runs, pattern):
        unit = 1.0
        if m[3] == "mJ":  # M g b in mJ: the mass and radius typed
            mass = float(re.search(r"--mass '([\d.]+) g'", COMMANDS[task])[1]) * 1e-3
            unit = mass * 9.81 * _time_unit(COMMANDS[task]) ** 2 * 9.81 * 1e3
        e = df["energy"].to_numpy() * unit
        assert float(m[1]) == pytest.approx(e[0], rel=1e-7) and float(m[2]) == pytest.approx(e[-1], rel=1e-7), task
        assert float(m[4]) == pytest.approx(e[0] - e[-1], rel=1e-5), task
        parts = [float(x.rsplit(" ", 1)[1]) for x in m[5].split(", ")] + [float(m[6])]
        assert sum(parts) == pytest.approx(e[0] - e[-1], rel=1e-3), task
    assert {m[3] for _, m, _, _ in _lines(runs, pattern)} == {"mJ", "M g b"}


def test_passage_lines_are_at_the_switch_and_the_end_piece_is_the_lower_one(runs):
    for task, m, traj, df in _lines(runs, r"the contact passed (?:between the .* (\d+) times, first|ball|stem)"):
        body = traj.model.body
        times = [float(t) for line in runs[task][0] if line.startswith("the contact passed")
                 for t in re.findall(r"at t = ([\d.e+-]+)", line)]
        at = traj.sample(np.clip(times, traj.t0, traj.t))  # a time printed to 6 digits can round past the end
        # the times are printed to 6 digits: theta is within |Lambda| x that rounding of the switch angle
        slack = np.abs(at["Lambda"].to_numpy()) * 5e-6 * np.array(times) + 1e-8
        assert (np.abs(at["theta"].to_numpy() - body.theta_switch) <= slack).all(), task
    for task, m, traj, df in _lines(runs, r"at the end it is on the (\w+)$"):
        h_ball, h_stem = traj.model.body.piece_heights(df["theta"].iloc[-1])
        assert m[1] == ("ball" if h_ball > h_stem else "stem"), task


def test_end_lines_match_the_last_sample(runs):
    for task, m, traj, df in _lines(runs, r"(theta_end|R_min|mode_end|t_end): (\S+)$"):
        value = m[2]
        if m[1] == "theta_end":
            assert float(value) == pytest.approx(df["theta"].iloc[-1], rel=1e-9), task
        elif m[1] == "mode_end":
            assert value == df["mode"].iloc[-1], task
        elif m[1] == "t_end":
            assert float(value) == pytest.approx(df["t"].iloc[-1], rel=1e-9), task
        else:  # the exact minimum is at or below every sample, and the grid comes close to it
            r = df["R"].to_numpy()
            assert float(value) <= r.min() + 1e-9 and r.min() - float(value) < 1e-3, task


def test_real_unit_lines_convert_the_samples(runs):
    for task, m, traj, df in _lines(runs, r"in real units \(b = .*, time unit ([\d.]+) ms\):$"):
        unit = _time_unit(COMMANDS[task])
        assert float(m[1]) == pytest.approx(unit * 1e3, rel=1e-5), task
        lines = runs[task][0]
        [end] = [x for x in lines if x.startswith("  t_end:")]
        assert float(end.split()[1]) == pytest.approx(df["t"].iloc[-1] * unit * 1e3, rel=1e-5), task
        [rates] = [x for x in lines if x.startswith("  at the end:")]
        omega, n = (float(v) for v in re.findall(r"=([\d.e+-]+) rev/s", rates))
        per_rev = 1 / (2 * math.pi * unit)
        assert omega == pytest.approx(df["Omega"].iloc[-1] * per_rev, rel=1e-4, abs=1e-4), task
        assert n == pytest.approx(df["n"].iloc[-1] * per_rev, rel=1e-4, abs=1e-4), task


def test_a_parquet_file_of_the_run_tells_the_same_theta_line(runs, tmp_path):
    lines, traj, _ = runs["NetCDF/Parquet"]
    path = tmp_path / "run.parquet"
    traj.to_parquet(path, n=2001)
    theta = pd.read_parquet(path)["theta"].to_numpy()
    [line] = [x for x in lines if x.startswith("theta ")]
    a, b = (float(v) for v in re.search(r", ([\d.e+-]+) -> ([\d.e+-]+)", line).groups())
    assert (a, b) == (pytest.approx(theta[0], rel=1e-5), pytest.approx(theta[-1], rel=1e-5))
    assert line.startswith("theta fell") == (theta[-1] < theta[0])


def test_steady_state_family_lines_match_the_linearisation_on_each_side(runs):
    task = "stemmed tippe top's steady states"
    lines = runs[task][0]
    top = make_body("tippe-top", offset=0.3, A=0.38, C=0.4, **_stem(None, None))  # the CLI's default stem
    s = pk.steady_structure(top, pk.Coulomb(0.3), samples=False)
    checked = 0
    for line in lines:
        m = re.match(r"spin about the vertical family at theta = ([\d.]+) .*?: (?:stability changes at \|n\| = "
                     r"([\d.e+-]+); (stable|unstable) above|no change of stability: (stable|unstable))", line)
        if not m:
            continue
        kind = "vertical" if float(m[1]) < 1 else "inverted"

        def n_unstable(n):
            return [p for p in s.at(n0=n) if p.kind == kind][0].n_unstable

        if m[2]:
            n_c = float(m[2])
            assert (n_unstable(n_c * (1 - 1e-4)) == 0) == (m[3] == "unstable")
            assert (n_unstable(n_c * (1 + 1e-4)) == 0) == (m[3] == "stable")
        else:
            assert all((n_unstable(n) == 0) == (m[4] == "stable") for n in (0.5, 3.0, 30.0))
        checked += 1
    assert checked == 2
    for line in lines:
        m = re.match(r"static equilibrium at theta = ([\d.]+) .*: (minimum|maximum)", line)
        if m:
            assert (float(top.h(float(m[1]))[2]) > 0) == (m[2] == "minimum")
            checked += 1
    assert checked == 4
