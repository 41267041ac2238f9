"""The studies' shared output helpers (phasekit.sweep.study) and the rule that studies and
benchmarks use the public API only (issue 14, item 3; issue 17, item 9)."""

from __future__ import annotations

import csv
from pathlib import Path

from phasekit.sweep.study import atomic_path, output_dir, run_study, save_figure, study_parser, write_csv

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_quick_runs_never_write_to_the_committed_directory(tmp_path):
    ap = study_parser("doc", default_out=tmp_path / "figures")
    assert output_dir(ap.parse_args([])) == tmp_path / "figures"
    assert output_dir(ap.parse_args(["--quick"])) == tmp_path / "figures" / "quick"
    assert output_dir(ap.parse_args(["--quick", "--out", str(tmp_path / "x")])) == tmp_path / "x"
    assert (tmp_path / "figures" / "quick").is_dir()


def test_abbreviated_options_are_refused(tmp_path, capsys):
    ap = study_parser("doc", default_out=tmp_path)
    with pytest.raises(SystemExit) as exc:
        ap.parse_args(["--qu"])
    assert exc.value.code == 2
    assert "--qu" in capsys.readouterr().err


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("old\n")
    with pytest.raises(RuntimeError):
        with atomic_path(target) as tmp:
            tmp.write_text("half a ta")
            raise RuntimeError("killed mid-write")
    assert target.read_text() == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]


def test_write_csv_takes_sequences_and_mappings(tmp_path):
    path = write_csv(tmp_path / "t.csv", ["a", "b", "c"], [[1, 2.5, "x"], {"a": 3, "c": "y", "extra": 9}])
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows == [["a", "b", "c"], ["1", "2.5", "x"], ["3", "", "y"]]


def test_save_figure_writes_a_png_and_closes_the_figure(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    path = save_figure(fig, tmp_path / "f.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not plt.fignum_exists(fig.number)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.png"]


def test_ctrl_c_ends_a_study_with_one_line_and_exit_code_130(capsys):
    def main(argv):
        raise KeyboardInterrupt

    with pytest.raises(SystemExit) as exc:
        run_study(main, ["--quick"])
    assert exc.value.code == 130
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1 and "Traceback" not in err
    assert lines[0].startswith("interrupted:") and lines[0].endswith("--quick")
