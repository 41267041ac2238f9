"""The scaffold every study script runs on (phasekit.scaffold): output folders, atomic writes,
tables and figures, refused flags, and one line on stderr for an error or Ctrl-C."""

from __future__ import annotations

import csv
import signal
import sys
from pathlib import Path

import phasekit as pk
from phasekit.io import atomic_path
from phasekit.scaffold import run_study
from phasekit.scaffold.parser import output_dir, study_parser
from phasekit.scaffold.writers import write_csv
from phasekit.viz import save_figure

import pytest

ROOT = Path(__file__).resolve().parents[2]


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


@pytest.mark.parametrize("argv, flag", [(["--quick", "--quick"], "--quick"), (["--out", "a", "--out=b"], "--out")])
def test_a_study_refuses_a_repeated_flag_too(argv, flag, capsys):
    from phasekit.scaffold.parser import study_parser

    ap = study_parser("a study", default_out=ROOT / "figures")
    with pytest.raises(SystemExit) as info:
        ap.parse_args(argv)
    err = capsys.readouterr().err
    assert info.value.code == 2 and err.count("\n") == 1 and f"error: {flag} is given 2 times: give it once" in err


def _run(main, argv, capsys, **kw):
    with pytest.raises(SystemExit) as exc:
        run_study(main, argv, **kw)
    err = capsys.readouterr().err
    return exc.value.code, [ln for ln in err.splitlines() if ln.strip()], err


def test_an_api_error_is_named_by_the_studys_flag(tmp_path, capsys):
    ap = study_parser("doc", default_out=tmp_path)
    ap.add_argument("--slip-eps", type=float)

    def main(argv):
        ap.parse_args(argv)
        raise pk.ParameterError("slip_eps", "must be > 0", -1.0)

    code, lines, err = _run(main, ["--slip-eps", "-1"], capsys)
    assert code == 2 and "Traceback" not in err
    assert len(lines) == 1 and lines[0].endswith("error: --slip-eps must be > 0, got -1.0.")

    def internal(argv):  # a parameter the study has no flag for keeps the API's name
        ap.parse_args(argv)
        raise pk.ParameterError("theta0", "must lie in [0, pi]", 4.0)

    code, lines, _ = _run(internal, [], capsys, flags={"mu": "--mu"})
    assert code == 2 and len(lines) == 1 and "`theta0` must lie in [0, pi], got 4.0." in lines[0]

    def failed(argv):
        raise pk.ConvergenceError("Newton did not converge\nafter 50 steps")

    code, lines, _ = _run(failed, [], capsys)
    assert code == 1 and len(lines) == 1 and lines[0].endswith("error: Newton did not converge after 50 steps")


def test_the_resume_command_leaves_out_fresh(capsys):
    def main(argv):
        raise KeyboardInterrupt

    code, lines, _ = _run(main, ["--quick", "--fresh"], capsys, resume="rows are kept; rerunning resumes")
    assert code == 130 and len(lines) == 1
    assert lines[0].startswith("interrupted: rows are kept; rerunning resumes: python ") and lines[0].endswith("--quick")


def test_an_interrupt_that_compiled_code_swallows_still_ends_the_run(capsys):
    """CasADi turns a KeyboardInterrupt raised inside an integration into an error of its own;
    the run must still end (before the next line of the handler that catches that error)."""
    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        pytest.skip("SIGINT is handled by something else in this process")
    reached, tracer = [], sys.gettrace()

    def swallow():
        try:
            signal.raise_signal(signal.SIGINT)
        except KeyboardInterrupt:
            pass  # as compiled code does; it then reports a failure

    def main(argv):
        for _ in range(3):
            swallow()
            try:
                raise RuntimeError('CVode returned "CV_RHSFUNC_FAIL"')
            except RuntimeError:
                reached.append("handler")
            reached.append("stored a failed row")

    code, lines, err = _run(main, [], capsys)
    assert code == 130 and len(lines) == 1 and lines[0].startswith("interrupted:"), err
    assert "stored a failed row" not in reached
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler and sys.gettrace() is tracer


def test_an_interrupt_that_compiled_code_turns_into_another_error_ends_a_study_as_interrupted(capsys):
    """CasADi's argument dispatch turns a KeyboardInterrupt into NotImplementedError ("Wrong
    number or type of arguments"), which propagated as a traceback (found at 1.2 s into a study)."""
    from phasekit.scaffold import run_study

    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        pytest.skip("SIGINT is handled by something else in this process")

    def main(argv):
        try:
            signal.raise_signal(signal.SIGINT)
        except KeyboardInterrupt:
            raise NotImplementedError("Wrong number or type of arguments for function 'Function_call'") from None

    with pytest.raises(SystemExit) as info:
        run_study(main, [])
    lines = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert info.value.code == 130 and len(lines) == 1 and lines[0].startswith("interrupted:")
