"""Parallel runs that cannot hang.

``pk.ensemble`` on local worker processes from every way a user calls Python: a script with
and without a main guard, a script read from standard input, ``python -c``, and a notebook
executed by a real Jupyter kernel; each gives the rows a single run gives. A worker killed in
mid-run ends the call with a WorkerError naming it. Timeouts here are hang guards (the calls
take about a second), not performance assertions; a wall budget is checked by the rows' reasons.
"""

import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import phasekit as pk

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
HANG_GUARD = 120  # s: a call that has not returned by then hangs (it takes ~2 s)
#: a user's script: an ensemble at the top level, no main guard; prints its rows as JSON
SCRIPT = textwrap.dedent("""\
    import json, numpy as np, phasekit as pk
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    starts = [pk.gyroscopic_start(body, 1.56, omega0=w) for w in (9, 10, 11, 12)]
    df = pk.ensemble(model, starts, 100.0, processes=2, progress=False)
    print(json.dumps({"status": list(df["status"]), "t_jump": [None if np.isnan(t) else t for t in df["t_jump"]],
                      "n_steps": [int(n) for n in df["n_steps"]]}))
""")


@pytest.fixture(scope="module")
def expected():
    """The rows of single runs in this process."""
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    runs = [pk.simulate(model, pk.gyroscopic_start(body, 1.56, omega0=w), 100.0, dense=False) for w in (9, 10, 11, 12)]
    return {"status": [r.status.value for r in runs], "t_jump": [r.t_jump for r in runs],
            "n_steps": [int(r.n_steps) for r in runs]}


def _env():
    env = dict(os.environ, PYTHONPATH=str(ROOT), PHASEKIT_DEBUG="1")
    env.pop("PYTHONSTARTUP", None)
    return env


def _rows(proc: subprocess.CompletedProcess) -> dict:
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.strip().splitlines()[-1])


def test_ensemble_from_a_script_without_a_main_guard(tmp_path, expected):
    path = tmp_path / "run.py"
    path.write_text(SCRIPT)
    proc = subprocess.run([sys.executable, str(path)], cwd=tmp_path, env=_env(), capture_output=True, text=True,
                          timeout=HANG_GUARD)
    assert _rows(proc) == expected


def test_ensemble_from_a_script_read_on_standard_input(tmp_path, expected):
    proc = subprocess.run([sys.executable, "-"], input=SCRIPT, cwd=tmp_path, env=_env(), capture_output=True, text=True,
                          timeout=HANG_GUARD)
    assert _rows(proc) == expected


def test_ensemble_from_python_c(tmp_path, expected):
    proc = subprocess.run([sys.executable, "-c", SCRIPT], cwd=tmp_path, env=_env(), capture_output=True, text=True,
                          timeout=HANG_GUARD)
    assert _rows(proc) == expected


def test_ensemble_from_a_script_with_a_main_guard_and_a_function_of_its_own(tmp_path, expected):
    """A start built by a function of the script itself (it travels by value to no worker:
    only the starts do) and the main guard the README used to require."""
    body = "\n".join("    " + line for line in SCRIPT.splitlines())
    path = tmp_path / "guarded.py"
    path.write_text(f"def main():\n{body}\n\nif __name__ == '__main__':\n    main()\n")
    proc = subprocess.run([sys.executable, str(path)], cwd=tmp_path, env=_env(), capture_output=True, text=True,
                          timeout=HANG_GUARD)
    assert _rows(proc) == expected


def test_ensemble_in_a_jupyter_kernel(tmp_path, expected):
    """A notebook executed cell by cell by a real IPython kernel (nbclient + ipykernel)."""
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(SCRIPT)]
    client = nbclient.NotebookClient(nb, timeout=HANG_GUARD, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    outputs = [o for o in nb.cells[0].outputs if o.get("name") == "stdout"]
    assert outputs, nb.cells[0].outputs
    assert json.loads(outputs[-1]["text"].strip().splitlines()[-1]) == expected


def _loky_workers():
    import psutil

    return [p for p in psutil.Process().children(recursive=True)
            if p.is_running() and "LokyProcess" in " ".join(p.cmdline())]


@pytest.mark.timeout(600)  # a hang guard: loky notices a dead worker within ~0.1 s; the test takes ~1 min
def test_a_worker_killed_mid_run_ends_the_ensemble_with_an_error_naming_it():
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    # hopping runs of a few seconds each, so that the kill lands while they run
    starts = [pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=w) for w in (28.0, 29.0, 30.0, 31.0, 32.0, 33.0)]
    killed, ensemble_ended = {}, threading.Event()

    def kill_one():
        # both workers up, then a second more: each is in a run then (6 hopping runs of seconds
        # each for 2 workers keep both busy well past that), whatever the machine's load
        while not ensemble_ended.is_set():
            workers = _loky_workers()
            if len(workers) >= 2:
                time.sleep(1.0)
                killed["pid"] = workers[0].pid
                os.kill(workers[0].pid, signal.SIGKILL)
                return
            time.sleep(0.05)

    killer = threading.Thread(target=kill_one, daemon=True)
    killer.start()
    try:
        with pytest.raises(pk.WorkerError) as info:
            pk.ensemble(model, starts, 400.0, stop_at="none", restitution=0.5, processes=2, progress=False)
    finally:
        ensemble_ended.set()
        killer.join(5)
    assert "pid" in killed, "no busy worker to kill"
    message = str(info.value)
    assert "worker process died" in message and "SIGKILL" in message
    table = info.value.result
    assert list(table["i"]) == list(range(len(starts)))
    unfinished = table[table["reason"].fillna("").str.startswith("not finished")]
    assert 1 <= len(unfinished) <= len(starts)
    # the rows that finished are those of single runs
    for _, row in table.drop(unfinished.index).iterrows():
        single = pk.simulate(model, starts[int(row["i"])], 400.0, stop_at="none", restitution=0.5, dense=False)
        assert row["status"] == single.status.value and row["n_steps"] == single.n_steps
    # and the next ensemble, in this same process, starts new workers
    starts = [pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=w) for w in (10.0, 11.0, 12.0)]
    df = pk.ensemble(model, starts, 100.0, processes=2, progress=False)
    single = [pk.simulate(model, x, 100.0, dense=False).t_jump for x in starts]
    assert list(df["t_jump"]) == single


@pytest.mark.timeout(10 * HANG_GUARD)  # a hang guard; the budget is checked by the rows' reasons
def test_an_ensemble_wall_budget_ends_the_call_with_the_rows_it_had():
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    starts = [pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=w) for w in (28.0, 29.0, 30.0, 31.0)]
    df = pk.ensemble(model, starts, 400.0, stop_at="none", restitution=0.5, processes=2, progress=False,
                     max_wall_total=0.5)
    late = df[df["reason"].fillna("").str.contains("max_wall_total = 0.5 s")]
    assert len(late) >= 2 and set(late["status"]) == {"failed"}


DASK_SCRIPT = textwrap.dedent("""\
    import phasekit as pk
    client, cluster = pk.sweep.make_client(workers=2)
    print(client.submit(sum, [1, 2, 3]).result(), len(client.scheduler_info()["workers"]))
    client.close(); cluster.close()
""")


@pytest.mark.parametrize("how", ["stdin", "no-guard"])
def test_a_local_dask_cluster_starts_from_standard_input_and_without_a_main_guard(tmp_path, how):
    """Dask's LocalCluster spawns its workers too: they must not re-import the calling script."""
    pytest.importorskip("dask.distributed")
    if how == "stdin":
        cmd, kw = [sys.executable, "-"], {"input": DASK_SCRIPT}
    else:
        (tmp_path / "cluster.py").write_text(DASK_SCRIPT)
        cmd, kw = [sys.executable, str(tmp_path / "cluster.py")], {}
    proc = subprocess.run(cmd, cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=HANG_GUARD, **kw)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["6", "2"]
