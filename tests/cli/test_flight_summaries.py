"""A run with many flights is summarised over all of them, not by its first: the JSON's
``flight_summary`` agrees with its ``flights`` list, and the text summary (and its ``--si`` block,
in ms and mm) prints one line with the count, the first lift-off, the time airborne and its share
of the run, the longest flight and the largest gap."""

import math
import re

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json

#: the tippe top of the README: 61 flights in 70 time units
TOP = ["simulate", "--body", "tippe-top", "--stem-length", "0", "--offset", "0.3", "--A", "0.38", "--C", "0.4", "--mu", "0.3", "--theta0",
       "0.1", "--spin-about-vertical", "15", "--stop-at", "none", "--t-end", "70"]
B = 0.015  # --size '15 mm': the time unit is sqrt(b/g) seconds
T = math.sqrt(B / 9.81)


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


@pytest.fixture(scope="module")
def top():
    """The run as JSON, as text, and as text with --si."""
    code, out, err = run_cli(*TOP, "--json")
    assert code == 0, err
    d = strict_json(out)
    runs = [run_cli(*TOP), run_cli(*TOP, "--size", "15 mm", "--si"), run_cli(*TOP, "--size", "15 mm", "--si", "--json")]
    assert [r[0] for r in runs] == [0, 0, 0], [r[2] for r in runs]
    return d, runs[0][1], runs[1][1], strict_json(runs[2][1])


@pytest.mark.timeout(900)  # a hang guard: four runs of a few seconds each
def test_the_summary_counts_every_flight_of_the_json(top):
    d, *_ = top
    fs, flights = d["flight_summary"], d["flights"]
    assert fs["n_flights"] == len(flights) == d["n_flights"] > 10
    assert fs["n_flights"] == sum(e["kind"] == "lift-off" for e in d["events"])  # no rebounds without restitution
    durations = [f["t_touchdown"] - f["t_liftoff"] for f in flights]
    assert fs["airborne_fraction"] == pytest.approx(sum(durations) / d["t_end"], rel=1e-12)
    assert fs["t_airborne"] == pytest.approx(sum(durations), rel=1e-12)
    assert fs["longest_flight"] == pytest.approx(max(durations), rel=1e-12)
    assert fs["t_longest_flight"] == flights[durations.index(max(durations))]["t_liftoff"]
    top_flight = max(flights, key=lambda f: f["gap_max"])
    assert (fs["gap_max"], fs["t_gap_max"]) == (top_flight["gap_max"], top_flight["t_gap_max"])
    assert fs["gap_max"] > 1e3 * d["flight"]["gap_max"]  # the first flight is not the largest
    assert fs["t_first_liftoff"] == flights[0]["t_liftoff"] == d["t_jump"]


def test_the_text_summary_prints_all_flights_on_one_line(top):
    d, text, *_ = top
    fs = d["flight_summary"]
    [line] = [ln for ln in text.splitlines() if ln.startswith("flights: ")]
    numbers = [float(x) for x in re.findall(r"[-+]?\d+\.?\d*(?:e[-+]?\d+)?", line)]
    assert numbers[0] == fs["n_flights"]
    assert f"{100 * fs['airborne_fraction']:.3g}% of the run" in line
    for key in ("t_first_liftoff", "t_airborne", "longest_flight", "gap_max", "t_gap_max"):
        assert any(v == pytest.approx(fs[key], rel=1e-3) for v in numbers), key
    assert f"largest gap {fs['gap_max']:.4g} b" in line


def test_the_si_summary_is_in_ms_and_mm(top):
    d, _, si_text, si_json = top
    fs, real = d["flight_summary"], si_json["si"]["flight_summary"]
    assert real["n_flights"] == fs["n_flights"] and real["airborne_fraction"] == pytest.approx(fs["airborne_fraction"])
    for key in ("t_first_liftoff", "t_airborne", "longest_flight", "t_gap_max", "t_longest_flight"):
        assert real[key] == pytest.approx(fs[key] * T * 1e3, rel=1e-9), key  # ms
    assert real["gap_max"] == pytest.approx(fs["gap_max"] * B * 1e3, rel=1e-9)  # mm
    block = si_text.split("in real units", 1)[1]
    [line] = [ln.strip() for ln in block.splitlines() if ln.strip().startswith("flights: ")]
    assert f"largest gap {real['gap_max']:.4g} mm" in line and f"airborne {real['t_airborne']:.4g} ms" in line


def test_a_run_without_flights_has_a_summary_of_none():
    code, out, err = run_cli("simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.0", "--omega0",
                             "3", "--t-end", "5", "--json")
    d = strict_json(out)
    assert code == 0 and d["flights"] == []
    assert d["flight_summary"] == {"n_flights": 0, "t_first_liftoff": None, "gap_max": None, "t_gap_max": None,
                                   "longest_flight": None, "t_longest_flight": None, "t_airborne": 0.0,
                                   "airborne_fraction": 0.0}
    assert "flights:" not in run_cli("simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.0",
                                     "--omega0", "3", "--t-end", "5")[1]
