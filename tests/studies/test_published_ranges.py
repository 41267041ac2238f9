"""A published range drawn in a figure is labelled as our reading of the text, not as reported
numbers: the egg's flights against Mitsui et al. 2006 ("a fraction of a millimetre" for "up to
a few hundredths of a second"), and any label in a study or its figures that cites a paper."""

import ast
import importlib.util
from pathlib import Path

import phasekit.studies as ps
from phasekit.viz import pyplot

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
ROWS = [dict(lever="spin", value=50.0, e=0.5, first_flight_ms=2.0, first_gap_mm=0.01, longest_flight_ms=15.0,
             largest_gap_mm=0.2)]


def _box(fig):
    """The shaded experiment box: its label and its extent (flight ms, gap mm)."""
    ax = fig.axes[0]
    [poly] = [c for c in ax.collections if c.get_label() and not c.get_label().startswith("_")
              and type(c).__name__ in ("PolyCollection", "FillBetweenPolyCollection")]
    xy = np.vstack([p.vertices for p in poly.get_paths()])
    return poly.get_label(), (xy[:, 0].min(), xy[:, 0].max()), (xy[:, 1].min(), xy[:, 1].max())


def test_the_egg_study_draws_its_reading_of_the_experiment_and_says_so():
    spec = importlib.util.spec_from_file_location("egg_jumps_study", ROOT / "studies" / "egg_jumps.py")
    study = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(study)
    fig = ps.plot_flights(ROWS, experiment=study.EXPERIMENT, title="t")
    try:
        label, flight, gap = _box(fig)
        assert label.startswith("our reading of Mitsui et al. 2006")
        assert "'a fraction of a millimetre'" in label and "a few hundredths of a second'" in label
        assert "0.05-0.5 mm, 5-30 ms" in label  # the numbers drawn are named as ours
        np.testing.assert_allclose([*flight, *gap], [*study.EXPERIMENT["flight_ms"], *study.EXPERIMENT["gap_mm"]])
        bare = ps.plot_flights(ROWS, experiment=dict(gap_mm=(0.1, 0.2), flight_ms=(1.0, 2.0)), title="t")
        assert _box(bare)[0].startswith("our reading")
    finally:
        pyplot().close("all")


def _labels(path: Path):
    """The string literals given as a label (``label=...`` or a dict's "label") in a module."""
    for node in ast.walk(ast.parse(path.read_text())):
        values = []
        if isinstance(node, ast.Call):  # also dict(label=...)
            values = [k.value for k in node.keywords if k.arg == "label"]
        elif isinstance(node, ast.Dict):
            values = [v for k, v in zip(node.keys, node.values) if isinstance(k, ast.Constant) and k.value == "label"]
        for v in values:
            text = "".join(c.value for c in ast.walk(v) if isinstance(c, ast.Constant) and isinstance(c.value, str))
            if text:
                yield text


def test_no_figure_labels_a_paper_s_range_as_reported():
    files = [*(ROOT / "studies").glob("*.py"), *(ROOT / "phasekit" / "studies").glob("figures_*.py")]
    cited = [(p.name, t) for p in files for t in _labels(p) if "et al" in t]
    assert cited and all("our reading" in t for _, t in cited), cited
    assert not any("reported range" in p.read_text() for p in files)
