"""Bad input and Ctrl-C on the studies (studies/*.py): one line on stderr naming the flag as it
was typed, exit code 2 (130 for Ctrl-C), never a traceback; nothing written to figures/.

The bad-input runs are started together in a small pool (each is an import and a refusal,
about a second) and checked one test each."""

from __future__ import annotations

import concurrent.futures
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
STUDIES = sorted(p.name for p in (ROOT / "studies").glob("*.py"))
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
RESUMABLE = {"egg.py", "steady_structure.py", "outcome_map.py", "paper_pairs.py", "threshold_vs_aspect.py", "threshold_vs_mu.py", "tippe_top.py",
             "spin_down.py"}
# (study, arguments, the flag the message must name, text the message must contain)
BAD_NUMBERS = [
    ("figure5_gap.py", ["--seed", "-1"], "--seed", "an integer >= 0, got -1"),
    ("figure5_gap.py", ["--seed", "1.5"], "--seed", "an integer >= 0, got 1.5"),
    ("threshold_vs_aspect.py", ["--workers", "0"], "--workers", "an integer >= 1, got 0"),
    ("threshold_vs_aspect.py", ["--levels", "9"], "--levels", "an integer in [1, 8], got 9"),
    ("outcome_map.py", ["--workers", "-2"], "--workers", "an integer >= 1, got -2"),
    ("threshold_vs_mu.py", ["--per-task", "0"], "--per-task", "an integer >= 1, got 0"),
    ("threshold_vs_mu.py", ["--workers", "two"], "--workers", "an integer >= 1, got 'two'"),
    ("stability_map.py", ["--mu", "nan"], "--mu", "a finite number, got nan"),
    # checked by the API (pk.Viscous): its ParameterError is reworded with the flag by run_study
    ("stability_map.py", ["--mu", "-1"], "--mu", "must lie in [0, 1000], got -1"),
    ("stability_map.py", ["--mu", "1e308"], "--mu", "must lie in [0, 1000], got 1e+308"),
]


def _study(script: str, *args: str, timeout: float = 60) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ROOT / "studies" / script), *args], cwd=ROOT, env=ENV,
                          capture_output=True, text=True, timeout=timeout)


@pytest.fixture(scope="module")
def refusals(tmp_path_factory):
    """Every bad-input run of this file, started at once on a pool of 4."""
    tmp = tmp_path_factory.mktemp("refusals")
    a_file = tmp / "a_file.txt"
    a_file.write_text("not a directory\n")
    runs = {}
    for s in STUDIES:
        runs[("file", s)] = (s, "--quick", "--no-progress", "--out", str(a_file))
        runs[("empty", s)] = (s, "--quick", "--no-progress", "--out", "")
    for path in ("/proc/phasekit-x", "/dev/null/x", str(a_file / "sub")):
        runs[("path", path)] = ("bouncing.py", "--quick", "--no-progress", "--out", path)
    for s, args, _, _ in BAD_NUMBERS:
        runs[("number", s, *args)] = (s, "--quick", "--no-progress", "--out", str(tmp / "never"), *args)
    runs[("scheduler",)] = ("outcome_map.py", "--quick", "--no-progress", "--out", str(tmp / "om"), "--scheduler",
                            "not-an-address")
    pool = concurrent.futures.ThreadPoolExecutor(4)
    futures = {k: pool.submit(_study, *v) for k, v in runs.items()}
    yield {"futures": futures, "file": a_file, "tmp": tmp}
    pool.shutdown(wait=True, cancel_futures=True)


def _one_line(run: subprocess.CompletedProcess, flag: str, code: int = 2) -> str:
    """The run ended with ``code`` and exactly one line on stderr that names ``flag``."""
    assert "Traceback" not in run.stderr, run.stderr
    assert run.returncode == code, run.stderr
    lines = [ln for ln in run.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, run.stderr
    assert re.search(rf"(?<![\w-]){re.escape(flag)}(?![\w-])", lines[0]), lines[0]
    return lines[0]


@pytest.mark.parametrize("study", STUDIES)
def test_out_naming_a_file_is_refused(refusals, study):
    line = _one_line(refusals["futures"][("file", study)].result(), "--out")
    assert line.startswith(f"{study}: error: ") and "existing file" in line and str(refusals["file"]) in line
    assert refusals["file"].read_text() == "not a directory\n"


@pytest.mark.parametrize("study", STUDIES)
def test_an_empty_out_is_refused(refusals, study):
    line = _one_line(refusals["futures"][("empty", study)].result(), "--out")
    assert "must name a directory, got ''" in line


@pytest.mark.parametrize("path, why", [("/proc/phasekit-x", "cannot be created"), ("/dev/null/x", "is a file, not a directory"),
                                       ("a_file/sub", "is a file, not a directory")])
def test_out_that_cannot_be_created_is_refused(refusals, path, why):
    key = str(refusals["file"] / "sub") if path == "a_file/sub" else path
    line = _one_line(refusals["futures"][("path", key)].result(), "--out")
    assert why in line and key in line


@pytest.mark.parametrize("study, args, flag, says", BAD_NUMBERS, ids=[f"{s}{' '.join(a)}" for s, a, _, _ in BAD_NUMBERS])
def test_bad_numbers_are_refused_before_any_work(refusals, study, args, flag, says):
    line = _one_line(refusals["futures"][("number", study, *args)].result(), flag)
    assert says in line
    assert not (refusals["tmp"] / "never").exists()  # refused before the output folder was made


def test_a_malformed_scheduler_address_is_one_line(refusals):
    line = _one_line(refusals["futures"][("scheduler",)].result(), "--scheduler")
    assert "not-an-address" in line and "missing port number" in line


def test_every_study_ends_through_run_study():
    for s in STUDIES:
        text = (ROOT / "studies" / s).read_text()
        assert "run_study(main" in text.split('if __name__ == "__main__":')[-1], s
        # Ctrl-C names the result stores a study opened: the resumable ones open theirs
        assert ("st.store(" in text) == (s in RESUMABLE), s


def _interrupted(proc: subprocess.Popen, ready, *, group: bool, wait: float) -> tuple[str, str]:
    """Wait until ``ready()`` (a run that never gets going fails the test by its timeout), then
    ``wait`` s, then SIGINT (to the whole process group, as a terminal's Ctrl-C, if ``group``);
    the run's stdout and stderr."""
    try:
        while not ready():
            assert proc.poll() is None, proc.communicate()[1]
            time.sleep(0.2)
        time.sleep(wait)
        assert proc.poll() is None, "the run ended before it was interrupted"
        if group:
            os.killpg(proc.pid, signal.SIGINT)
        else:
            proc.send_signal(signal.SIGINT)
        return proc.communicate(timeout=45)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
        time.sleep(0.5)
        try:
            os.killpg(proc.pid, signal.SIGKILL)  # any worker left behind (there should be none)
        except ProcessLookupError:
            pass


def _one_interrupted_line(proc, err, study_file) -> str:
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "WARNING" not in err, err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    assert lines[0].startswith("interrupted: the finished rows are kept in ") and "rerunning the command resumes" in lines[0]
    assert f"{study_file} --quick --no-progress --out " in lines[0] and "--fresh" not in lines[0]
    return lines[0]


@pytest.mark.timeout(600)  # a hang guard: the study is interrupted within a minute of its start
def test_ctrl_c_on_a_dask_study_is_one_line_and_130(tmp_path):
    """Ctrl-C in a terminal reaches every process of the group, Dask's workers too."""
    import psutil

    cmd = [sys.executable, str(ROOT / "studies" / "outcome_map.py"), "--quick", "--no-progress", "--fresh", "--out", str(tmp_path)]
    proc = subprocess.Popen(cmd, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)

    table = tmp_path / "outcome_map.csv"

    def working():  # the workers are up and the first rows are kept (the interrupt lands mid-run)
        kids = psutil.Process(proc.pid).children()
        up = sum("spawn_main" in " ".join(k.cmdline()) for k in kids if k.is_running()) >= 2
        return up and table.exists() and len(table.read_text().splitlines()) >= 2

    out, err = _interrupted(proc, working, group=True, wait=0.5)
    _one_interrupted_line(proc, err, "outcome_map.py")
    assert len(table.read_text().splitlines()) >= 2


@pytest.mark.timeout(600)  # a hang guard: the study is interrupted within a minute of its start
def test_ctrl_c_inside_compiled_integrations_is_not_lost(tmp_path):
    """paper_pairs runs CasADi integrations in this process, where a SIGINT usually lands."""
    cmd = [sys.executable, str(ROOT / "studies" / "paper_pairs.py"), "--quick", "--no-progress", "--out", str(tmp_path)]
    proc = subprocess.Popen(cmd, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    table = tmp_path / "paper_pairs.csv"

    def running():
        return table.exists() and len(table.read_text().splitlines()) >= 3

    out, err = _interrupted(proc, running, group=False, wait=1.0)
    _one_interrupted_line(proc, err, "paper_pairs.py")
    assert "rhs failed" not in err
