"""``phasekit cache`` shows what the disk cache holds and clears it; a run after a clear compiles
again and gives the same result."""

import os
import subprocess
import sys

from tests.helpers import ROOT, strict_json

import pytest

RUN = ["simulate", "--a", "1.43", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--t-end", "3",
       "--json"]


def _in(cache, *argv):
    """``python -m phasekit ARGV`` with its own cache directory (a separate process, as a user runs it)."""
    env = {**os.environ, "PHASEKIT_CACHE": str(cache)}
    return subprocess.run([sys.executable, "-m", "phasekit", *argv], capture_output=True, text=True, timeout=600,
                          cwd=ROOT, env=env)


def _bytes_under(root) -> int:
    return sum(p.stat().st_size for p in root.rglob("*") if p.is_file())


@pytest.mark.timeout(900)
def test_the_cache_command_counts_what_a_run_compiled_and_clears_it(tmp_path):
    first = _in(tmp_path, *RUN)
    assert first.returncode == 0, first.stderr
    shown = strict_json(_in(tmp_path, "cache", "--json").stdout)
    assert shown["directory"] == str(tmp_path) and shown["cleared"] is False
    assert shown["integrators"]["files"] == len(list(tmp_path.glob("*.pkl"))) >= 1
    assert shown["integrators"]["bytes"] + shown["heyoka"]["bytes"] == _bytes_under(tmp_path)
    # the build log names each compiled integrator, once (benchmarks/bench_cold_cache.py counts from it)
    logged = [line.split("\t")[0] for line in (tmp_path / "builds.log").read_text().splitlines()]
    assert sorted(logged) == sorted(p.stem for p in tmp_path.glob("*.pkl"))
    cleared = strict_json(_in(tmp_path, "cache", "--clear", "--json").stdout)
    assert cleared["cleared"] is True and cleared["integrators"] == shown["integrators"]
    after = strict_json(_in(tmp_path, "cache", "--json").stdout)
    assert after["integrators"] == {"files": 0, "bytes": 0} and after["heyoka"] == {"files": 0, "bytes": 0}
    again = _in(tmp_path, *RUN)
    assert again.returncode == 0, again.stderr
    recompiled = strict_json(_in(tmp_path, "cache", "--json").stdout)  # the run compiled again, as many files
    assert recompiled["integrators"]["files"] == shown["integrators"]["files"]
    assert strict_json(again.stdout)["t_end"] == strict_json(first.stdout)["t_end"]
    assert strict_json(again.stdout)["state_end"] == strict_json(first.stdout)["state_end"]


def test_with_caching_off_the_command_says_so():
    out = _in("", "cache")
    assert out.returncode == 0 and out.stdout.startswith("the disk cache is off"), out.stderr
