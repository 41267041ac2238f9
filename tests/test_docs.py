"""The API reference builds from the docstrings without a warning, and the examples in the
docstrings of the toolkit modules run."""

import doctest
import importlib
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_api_reference_builds_without_warnings(tmp_path):
    out = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(ROOT / "docs"),
                          str(tmp_path / "html")], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stderr.strip() == ""
    api = (tmp_path / "html" / "api.html").read_text()
    for name in ("phasekit.simulate", "phasekit.Trajectory.sample", "phasekit.poincare", "phasekit.ensemble",
                 "phasekit.rerun", "phasekit.paper_start", "phasekit.Scene.add_trajectory", "phasekit.Body"):
        assert f'id="{name}"' in api, name
    viz = (tmp_path / "html" / "viz.html").read_text()
    for name in ("plot_timeseries", "plot_events", "plot_section", "render_scene", "animate", "film_strip"):
        assert name in viz


@pytest.mark.parametrize("module", ["phasekit.sections", "phasekit.ensemble", "phasekit.viz.mpl", "phasekit.paper",
                                    "phasekit.surface", "phasekit.units"])
def test_docstring_examples_run(module):
    mod = importlib.import_module(module)
    res = doctest.testmod(mod, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert res.attempted > 0 and res.failed == 0
