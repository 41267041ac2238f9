"""Every script in examples/ runs (in a subprocess, writing to a temporary directory) and
produces what it says."""

import importlib.util
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}


def run(args, tmp_path, **kw):
    out = subprocess.run(args, cwd=ROOT, env={**ENV, **kw.pop("env", {})}, capture_output=True, text=True,
                         timeout=kw.pop("timeout", 300))
    return out


def run_example(name, tmp_path, *extra):
    out = run([sys.executable, str(EXAMPLES / name), "--out", str(tmp_path), *extra], tmp_path)
    assert out.returncode == 0, out.stderr
    return out


def test_every_example_is_tested():
    tested = {"fig4_case.py", "fixed_points.py", "threshold.py", "sweep_to_dataframe.py", "scene_own_trajectory.py",
              "cli_jq.sh", "section.py", "paper_start_rounding.py", "animate_body.py", "energy_over_time.py"}
    assert {p.name for p in EXAMPLES.iterdir() if p.suffix in (".py", ".sh")} == tested


def test_examples_run_without_arguments_into_examples_out(tmp_path):
    """Like gallery examples, a script run as is (from any directory) writes into the documented
    default folder examples/out/<name>/ (git-ignored)."""
    import shutil

    import pandas as pd

    copy = tmp_path / "examples"  # a copy, so that concurrent runs never share the source tree's out/
    copy.mkdir()
    shutil.copy(EXAMPLES / "section.py", copy / "section.py")
    out = subprocess.run([sys.executable, str(copy / "section.py")], cwd=tmp_path, env=ENV, capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    written = copy / "out" / "section" / "section.csv"
    assert len(pd.read_csv(written)) == 14
    assert "examples/out/" in (ROOT / ".gitignore").read_text().split()


def test_animate_body(tmp_path):
    from PIL import Image

    out = run_example("animate_body.py", tmp_path)
    assert "wrote" in out.stdout
    assert Image.open(tmp_path / "rise.gif").n_frames == 32 and Image.open(tmp_path / "landing.gif").n_frames == 16
    assert (tmp_path / "strip.png").stat().st_size > 20_000


def test_fig4_case(tmp_path):
    import pandas as pd

    out = run_example("fig4_case.py", tmp_path)
    df = pd.read_csv(tmp_path / "fig4_case.csv")
    assert "t_jump = 45.256004" in out.stdout  # the sliding-branch start of the README
    assert abs(df["R"].iloc[-1]) < 1e-9 and df["R"].max() > 1.5  # R oscillates with growing amplitude to 0
    assert (tmp_path / "fig4_case.png").stat().st_size > 20_000


def test_energy_over_time(tmp_path):
    """The tippe top's energy series: the balance holds at every row, the three mechanisms took
    out all that was lost (nothing at events), and the figure was drawn."""
    import pandas as pd

    out = run_example("energy_over_time.py", tmp_path)
    df = pd.read_csv(tmp_path / "energy_over_time.csv")
    laws = ["sliding friction", "spin-friction", "rolling-resistance"]
    assert list(df.columns) == ["t", "energy", *laws, "at_events", "residual"]
    E0, lost = df["energy"].iloc[0], df["energy"].iloc[0] - df["energy"].iloc[-1]
    assert lost > 0.9 * E0 and df["residual"].abs().max() < 1e-8 * lost
    assert all(df[name].iloc[-1] > 0.05 * lost for name in laws) and df["at_events"].abs().max() < 1e-9 * E0
    assert out.stdout.startswith("status rest") and "(38.5 s)" in out.stdout  # tests/core/test_coming_to_rest.py
    assert (tmp_path / "energy_over_time.png").stat().st_size > 20_000


def test_fixed_points_and_an_unstable_seed(tmp_path):
    out = run_example("fixed_points.py", tmp_path)
    lines = out.stdout.splitlines()
    assert lines[0].startswith("horizontal") and "1 real unstable" in lines[0]
    lam, rate = (float(w) for w in lines[-1].replace(";", "").split() if w[0].isdigit())
    assert rate == pytest.approx(lam, rel=1e-3)  # the seed leaves along the eigenvector at its rate


def test_threshold(tmp_path):
    run_example("threshold.py", tmp_path)
    d = json.loads((tmp_path / "threshold.json").read_text())
    assert d["status"] == "converged" and d["value"] == pytest.approx(9.7433, rel=1e-3)  # README table, a = 1.5
    assert d["bracket"][1] / d["bracket"][0] - 1 <= 1e-3


def test_sweep_to_dataframe(tmp_path):
    import pandas as pd

    run_example("sweep_to_dataframe.py", tmp_path, "--processes", "2")
    df = pd.read_csv(tmp_path / "sweep.csv")
    assert len(df) == 16 and list(df["i"]) == list(range(16))
    jumped = df[df["status"] == "jumped"]
    # the threshold (9.7433) separates the outcomes; t_jump falls with Omega0
    assert set(df.loc[df["Omega"] < 9.74, "status"]) == {"stopped"} and (jumped["Omega"] > 9.74).all()
    assert jumped["t_jump"].is_monotonic_decreasing


def test_scene_with_ones_own_trajectory(tmp_path):
    out = run_example("scene_own_trajectory.py", tmp_path, "--gltf")
    assert (tmp_path / "scene.png").stat().st_size > 30_000
    assert "bad X server" not in out.stderr and "WARN" not in out.stderr
    doc = json.loads((tmp_path / "scene.gltf").read_text())
    axes = doc["asset"]["extras"]["phasekit_axes"]
    assert [(a["name"], a["unit"]) for a in axes] == [("Omega", "sqrt(g/b)"), ("theta", "rad"), ("n", "sqrt(g/b)")]
    assert len(doc["meshes"]) > 20  # the axes, ticks and titles travel as geometry


def test_html_export_fails_in_one_line_without_its_extra(tmp_path):
    if importlib.util.find_spec("trame_pyvista") is not None:
        pytest.skip("phasekit[html] is installed here")
    out = run([sys.executable, str(EXAMPLES / "scene_own_trajectory.py"), "--out", str(tmp_path), "--html"], tmp_path)
    assert out.returncode == 1
    assert out.stderr.strip().count("\n") == 0 and 'pip install "phasekit[html]"' in out.stderr
    assert not (tmp_path / "scene.png").exists()  # refused before rendering


def test_section(tmp_path):
    import pandas as pd

    run_example("section.py", tmp_path)
    df = pd.read_csv(tmp_path / "section.csv")
    assert len(df) == 14 and (df["Lambda"].abs() < 1e-12).all()
    assert df["theta"].iloc[1:].is_monotonic_decreasing  # the minima of theta fall as the body rises


def test_paper_start_rounding_quick(tmp_path):
    import pandas as pd

    out = run_example("paper_start_rounding.py", tmp_path, "--quick")
    df = pd.read_csv(tmp_path / "rounding.csv")
    t = dict(zip(df["label"], df["t_jump"]))
    assert t["(5.2) printed"] == pytest.approx(52.34, abs=0.01)  # README: eps = 1e-3 jumps at 52.34
    assert t["eigenvector delta=0.02"] == pytest.approx(64.16, abs=0.01)
    # rounding theta alone turns the eigenvector start's jump into (5.2)'s
    assert t["eigenvector, theta rounded"] == pytest.approx(t["(5.2) printed"], abs=0.01)
    assert abs(t["eigenvector, U rounded"] - t["eigenvector delta=0.02"]) < 0.05
    assert "t_jump" in out.stdout


def test_cli_piped_to_json_tools(tmp_path):
    """The pipeline of examples/cli_jq.sh; the JSON is read with Python here, and with jq
    when it is installed (the script itself)."""
    out = run([sys.executable, "-m", "phasekit", "simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0",
               "1.5607963", "--omega0", "10.5", "--json"], tmp_path)
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert d["status"] == "jumped" and d["t_jump"] == pytest.approx(45.256, abs=1e-3)
    assert d["model"]["a"] == 1.5 and d["options"]["rtol"] == 1e-9  # a result carries its inputs
    if shutil.which("jq") is None:
        pytest.skip("jq is not installed: the shell script was not run")
    res = run(["bash", str(EXAMPLES / "cli_jq.sh"), "--out", str(tmp_path)], tmp_path, env={"PYTHON": sys.executable})
    assert res.returncode == 0, res.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["t_jump"] == d["t_jump"] and summary["status"] == "jumped"
    sweep = [json.loads(line) for line in (tmp_path / "sweep.jsonl").read_text().splitlines()]
    assert [s["omega0"] for s in sweep] == [10.5, 12, 15] and all(s["status"] == "jumped" for s in sweep)
    assert (tmp_path / "events.tsv").read_text().startswith("lift-off\t")
