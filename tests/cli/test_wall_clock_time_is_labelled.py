"""The wall-clock time a run took is printed as such, on its own line after everything simulated
(never inside the "in real units" block, where it read as a simulated time), in ms below a
second and in s above."""

import re

from phasekit import cli
from phasekit.cli.output import _wall_clock

import pytest

from ..helpers import run_cli, strict_json

RUN = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963", "--omega0", "11",
       "--stop-at", "touchdown", "--size", "21.5 mm", "--si"]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


@pytest.mark.parametrize("seconds, shown", [(0.0123, "12.3 ms"), (0.5, "500 ms"), (0.9999, "1.0 s"), (1.0, "1.0 s"), (102.8137, "102.8 s"),
                                            (1234.0, "1234 s (20.6 min)")])
def test_a_wall_clock_time_reads_in_a_fitting_unit(seconds, shown):
    assert _wall_clock(seconds) == shown


def test_the_wall_clock_line_is_labelled_and_outside_the_real_units_block():
    code, out, err = run_cli(*RUN)
    assert code == 0, err
    lines = out.splitlines()
    m = re.fullmatch(r"computed in (\d+\.?\d*) (ms|s)( \(.*\))? of wall-clock time", lines[-1])
    assert m, lines[-1]
    block = lines[lines.index(next(ln for ln in lines if ln.startswith("in real units"))) + 1:-1]
    assert all("wall" not in ln for ln in block)
    [counts] = [ln for ln in lines if " events, " in ln]
    assert re.fullmatch(r"\d+ events, \d+ steps, \w+ chart, [\w+-]+( \(.*\))?", counts)  # no time among the counts
    d = strict_json(run_cli(*RUN, "--json")[1])
    assert "wall_s" in d and not any("wall" in k for k in d["si"])  # a wall time is no simulated time
