"""A compilation that makes a person wait says so on stderr (and to a logger), never on stdout;
heyoka's object-code cache lives in phasekit's cache directory."""

import json
import logging
import os
import subprocess
import sys

import phasekit as pk
from phasekit.core.engines import cache

import numpy as np
import pytest

RUN = ["-m", "phasekit", "simulate", "--a", "1.37", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5",
       "--omega0", "10", "--t-end", "5", "--json"]


def _run(cache, notice: str):
    env = {**os.environ, "PHASEKIT_CACHE": str(cache), "PHASEKIT_COMPILE_NOTICE": notice}
    return subprocess.run([sys.executable, *RUN], capture_output=True, text=True, env=env, timeout=900)


@pytest.mark.timeout(1200)
def test_a_cold_compilation_is_announced_and_the_warm_run_is_silent(tmp_path):
    cold = _run(tmp_path, "0")  # announce every compilation, however fast
    assert cold.returncode == 0, cold.stderr[-2000:]
    lines = cold.stderr.splitlines()
    starts = [ln for ln in lines if ln.startswith("phasekit: compiling the Taylor integrator")]
    ends = [ln for ln in lines if ln.startswith("phasekit: compiled in ")]
    assert starts and len(starts) == len(ends), cold.stderr
    assert str(tmp_path) in starts[0]
    assert json.loads(cold.stdout)["status"] == "completed"  # stdout stays one strict JSON object
    # heyoka's own cache is inside phasekit's directory, beside the pickled integrators
    assert (tmp_path / "heyoka").is_dir() and any(tmp_path.glob("taylor-*.pkl"))
    warm = _run(tmp_path, "0")
    assert warm.returncode == 0 and "compil" not in warm.stderr, warm.stderr
    assert json.loads(warm.stdout)["t_end"] == json.loads(cold.stdout)["t_end"]


def test_the_notice_can_be_turned_off(tmp_path):
    quiet = _run(tmp_path, "off")
    assert quiet.returncode == 0 and "compil" not in quiet.stderr, quiet.stderr


@pytest.mark.timeout(900)
def test_a_program_hears_of_a_compilation_through_the_logger(tmp_path, monkeypatch, caplog):
    monkeypatch.setenv("PHASEKIT_CACHE", str(tmp_path))
    monkeypatch.setenv("PHASEKIT_COMPILE_NOTICE", "0")
    cache.forget()
    body = pk.Spheroid(1.41)
    with caplog.at_level(logging.INFO, logger="phasekit"):
        pk.simulate(pk.Model(body, pk.Viscous(0.1)), pk.gyroscopic_start(body, 1.5, omega0=10.0), 1.0)
    said = [r.getMessage() for r in caplog.records if r.name.startswith("phasekit")]
    assert said and said[0].startswith("compiling the Taylor integrator") and said[-1].startswith("compiled in ")
    assert np.isfinite(float(said[-1].split()[2]))


def test_notices_of_compilations_in_two_threads_keep_a_line_each(monkeypatch, capsys):
    """Two compilations at once (the background one of a run's other mode beside the first) write
    whole lines: none shares a line with the other's."""
    import threading
    import time

    monkeypatch.setenv("PHASEKIT_COMPILE_NOTICE", "0")
    go = threading.Barrier(8)

    def build():
        go.wait()
        time.sleep(0.05)
        return object()

    threads = [threading.Thread(target=cache._announced, args=(build, None, f"part {k}")) for k in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 16
    assert all(ln.count("phasekit:") == 1 and (ln.startswith("phasekit: compiling part ")
                                               or ln.startswith("phasekit: compiled in ")) for ln in lines), lines
