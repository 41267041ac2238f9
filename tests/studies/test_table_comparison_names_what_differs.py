"""The comparison behind studies/reproduce.py (phasekit.studies.reproduce_tables) on small tables:
a changed cell is found and named by column and row, wall times and a manifest's provenance are
not compared, missing and extra rows are reported, identical tables pass; and the script itself,
on a repository of one tiny study, exits 0, 1 or 2 and never writes into figures/ unless told to."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

from phasekit.studies import reproduce_tables as rt

ROOT = Path(__file__).resolve().parents[2]


def _pair(tmp_path: Path, committed: str, rerun: str, suffix: str = ".csv") -> rt.TableDiff:
    a, b = tmp_path / "committed", tmp_path / "rerun"
    a.mkdir(exist_ok=True)
    b.mkdir(exist_ok=True)
    (a / f"t{suffix}").write_text(committed)
    (b / f"t{suffix}").write_text(rerun)
    return rt.compare_table(a / f"t{suffix}", b / f"t{suffix}")


TABLE = "key,x,status,wall_s\nk1,0.1,ok,0.25\nk2,1.5,ok,0.5\nk3,2.0,stuck,0.75\n"


def test_a_changed_cell_is_found_and_named(tmp_path):
    diff = _pair(tmp_path, TABLE, TABLE.replace("k2,1.5,", "k2,1.5000000000000002,"))
    assert not diff.identical
    assert diff.cells == [rt.Cell("x", "k2", "1.5", "1.5000000000000002")]
    assert diff.n_compared == 6  # 3 rows x (x, status): the key names the row, wall_s is excepted
    text = "\n".join(rt.describe(diff, "demo"))
    assert "DIFFERS: 1 of 6 cells differ in 1 of 3 rows" in text
    assert "x [k2]: committed 1.5 rerun 1.5000000000000002" in text
    assert abs(diff.largest()[0] - 1.48e-16) < 1e-17


def test_a_wall_time_column_is_ignored_and_named(tmp_path):
    diff = _pair(tmp_path, TABLE, TABLE.replace("0.25", "9.5").replace("0.75", "3"))
    assert diff.identical and diff.cells == []
    assert diff.excepted == ["wall_s"]
    assert "not compared: wall_s" in rt.describe(diff, "demo")[0]
    assert any("wall_s" in line for line in rt.excepted_lines())


def test_a_missing_row_and_an_extra_row_are_reported(tmp_path):
    rerun = TABLE.replace("k3,2.0,stuck,0.75\n", "k4,2.0,stuck,0.75\n")
    diff = _pair(tmp_path, TABLE, rerun)
    assert not diff.identical
    assert (diff.missing, diff.extra, diff.cells) == (["k3"], ["k4"], [])
    text = "\n".join(rt.describe(diff, "demo"))
    assert "1 rows missing from the rerun" in text and "rows missing from the rerun: k3" in text
    assert "rows only in the rerun: k4" in text


def test_identical_tables_pass_whatever_their_row_order_and_line_ends(tmp_path):
    lines = TABLE.splitlines()
    shuffled = "\r\n".join([lines[0], lines[3], lines[1], lines[2]]) + "\r\n"  # a store appends as tasks end
    diff = _pair(tmp_path, TABLE, shuffled)
    assert diff.identical and diff.matched_by == "key" and diff.n_rows == 3
    assert rt.describe(diff, "demo")[0].startswith("t.csv (demo): identical (3 rows, 6 cells, rows by 'key'")


def test_floats_are_compared_as_the_text_written(tmp_path):
    diff = _pair(tmp_path, TABLE, TABLE.replace("k3,2.0,", "k3,2,"))
    assert [(c.column, c.row, c.committed, c.rerun) for c in diff.cells] == [("x", "k3", "2.0", "2")]


def test_rows_without_a_key_column_are_matched_by_order_and_named_by_their_first_cell(tmp_path):
    table = "case,t\nfirst,1.0\nsecond,2.0\n"
    diff = _pair(tmp_path, table, "case,t\nfirst,1.0\nsecond,2.5\n")
    assert diff.matched_by == "order"
    assert diff.cells == [rt.Cell("t", "row 2 (case=second)", "2.0", "2.5")]
    short = _pair(tmp_path, table, "case,t\nfirst,1.0\n")
    assert short.missing == ["row 2"] and short.cells == []


def test_the_same_rows_in_another_order_are_named_as_moved_not_counted_as_differing(tmp_path):
    """A study that writes rows in the order its Dask tasks finish writes the same table in another order."""
    table = "case,t,wall_s\nfirst,1.0,0.1\nsecond,2.0,0.1\nthird,3.0,0.1\n"
    diff = _pair(tmp_path, table, "case,t,wall_s\nfirst,1.0,0.5\nthird,3.0,0.5\nsecond,2.0,0.5\n")
    assert diff.identical and diff.cells == [] and diff.moved == [(2, 3), (3, 2)]
    line = rt.describe(diff, "demo")[0]
    assert "identical" in line and "the same 3 rows in another order (2 moved: committed row -> rerun row 2 -> 3, 3 -> 2)" in line
    changed = _pair(tmp_path, table, "case,t,wall_s\nfirst,1.0,0.1\nthird,3.0,0.1\nsecond,2.5,0.1\n")
    assert changed.moved == [] and len(changed.cells) == 4 and not changed.identical  # not a permutation


def test_a_row_whose_run_a_wall_time_budget_cut_is_named_not_compared(tmp_path):
    table = ("method,rtol,error,n_rhs,status,reason\nA,1e-12,2e-12,427066,ok,\nB,1e-12,3e-12,100,ok,\n"
             "C,1e-9,1e-9,50,failed,wall-time limit (60 s) reached at t = 12.5\n")
    rerun = table.replace("A,1e-12,2e-12,427066,ok,", "A,1e-12,,417200,capped,").replace("12.5", "11.9")
    diff = _pair(tmp_path, table, rerun)
    assert diff.identical and diff.cut == ["row 1 (method=A)", "row 3 (method=C)"] and diff.n_compared == 6
    assert "2 rows cut by a wall-time budget not compared: row 1 (method=A), row 3 (method=C)" in rt.describe(diff, "demo")[0]
    other = _pair(tmp_path, table, rerun.replace("B,1e-12,3e-12", "B,1e-12,4e-12"))
    assert other.cells == [rt.Cell("error", "row 2 (method=B)", "3e-12", "4e-12")]  # the other rows still are


def test_a_long_text_is_shown_where_it_differs(tmp_path):
    common = "alpha=0.2 gamma=1.15 n0=15: measured partial " + "x" * 80
    diff = _pair(tmp_path, json.dumps({"notes": [common + " (theta_end 2.840)"]}),
                 json.dumps({"notes": [common + " (theta_end 2.839)"]}), ".json")
    line = next(ln for ln in rt.describe(diff, "demo") if "notes[0]:" in ln)
    assert "2.840" in line and "2.839" in line


def test_a_repeated_key_is_matched_occurrence_by_occurrence(tmp_path):
    table = "key,x\na,1\na,2\n"
    assert _pair(tmp_path, table, table).identical
    diff = _pair(tmp_path, table, "key,x\na,1\na,3\n")
    assert diff.cells == [rt.Cell("x", "a #2", "2", "3")]


def test_a_renamed_column_is_reported(tmp_path):
    diff = _pair(tmp_path, TABLE, TABLE.replace("key,x,status", "key,x,outcome"))
    assert (diff.missing_columns, diff.extra_columns) == (["status"], ["outcome"])
    assert not diff.identical


def test_json_fields_are_compared_by_path_with_wall_times_and_a_manifest_s_provenance_excepted(tmp_path):
    committed = {"git_commit": "abc", "command": "studies/x.py", "runs": [{"rows_added": 3}], "n_rows": 3,
                 "summary": {"fit": [0.5, 1.25], "wall_s": 12.0}, "checks": [{"phasekit": 60.0, "wall_s": 1}]}
    rerun = {**committed, "git_commit": "def", "command": "/tmp/scratch/x.py --fresh", "runs": [],
             "summary": {"fit": [0.5, 1.2500000000000002], "wall_s": 30.5}, "checks": [{"phasekit": 60.00000000001, "wall_s": 2}]}
    diff = _pair(tmp_path, json.dumps(committed), json.dumps(rerun), ".json")
    assert [(c.column, c.committed, c.rerun) for c in diff.cells] == [
        ("summary.fit[1]", "1.25", "1.2500000000000002"), ("checks[0].phasekit", "60.0", "60.00000000001")]
    assert set(diff.excepted) == {"git_commit", "command", "runs", "wall_s"}
    assert "summary.fit[1]: committed 1.25 rerun 1.2500000000000002" in "\n".join(rt.describe(diff, "demo"))


def test_json_outside_a_manifest_compares_runs_and_reports_missing_fields(tmp_path):
    committed = {"runs": {"air": {"t0": 193.0}}, "max": 1}
    diff = _pair(tmp_path, json.dumps(committed), json.dumps({"runs": {"air": {"t0": 193.5}}, "max": "1"}), ".json")
    assert [(c.column, c.committed, c.rerun) for c in diff.cells] == [("runs.air.t0", "193.0", "193.5"), ("max", "1", '"1"')]
    gone = _pair(tmp_path, json.dumps(committed), json.dumps({"runs": {"air": {"t0": 193.0}}}), ".json")
    assert gone.missing == ["max"] and not gone.identical
    assert _pair(tmp_path, json.dumps(committed), json.dumps(committed), ".json").identical


def test_a_table_that_does_not_parse_is_reported_not_raised(tmp_path):
    diff = _pair(tmp_path, '{"a": 1}', '{"a": ', ".json")
    assert diff.error and not diff.identical
    assert "NOT COMPARED" in rt.describe(diff, "demo")[0]


def test_each_committed_table_is_owned_by_exactly_one_study():
    own = rt.owners({"a": ["a.csv", "both.json", "new.csv"], "b": ["b.csv", "both.json"], "c": []},
                    ["a.csv", "b.csv", "both.json", "orphan.csv"])
    assert own.owner == {"a.csv": "a", "b.csv": "b"}
    assert own.shared == {"both.json": ["a", "b"]}
    assert own.unowned == ["orphan.csv"]
    assert own.uncommitted == {"a": ["new.csv"]}


# -- the script, on a repository of one tiny study ---------------------------------------------------

TINY = '''"""A tiny study: two tables and a figure."""

import phasekit as pk


def main(argv=None):
    st = pk.scaffold.Study(__file__, __doc__, resumable=True)
    st.parse(argv)
    st.csv("tiny.csv", ["key", "x", "wall_s"], [["a", 0.1 + 0.2, st.wall], ["b", 1.5, st.wall]])
    st.json("tiny.json", {"x": 0.5, "wall_s": st.wall})
    (st.out / "tiny.png").write_bytes(b"not compared")


if __name__ == "__main__":
    pk.scaffold.run_study(main)
'''


def _repo(tmp_path: Path) -> Path:
    repo = tmp_path / "repo"
    (repo / "studies").mkdir(parents=True)
    (repo / "figures").mkdir()
    shutil.copy(ROOT / "studies" / "reproduce.py", repo / "studies" / "reproduce.py")
    (repo / "studies" / "tiny.py").write_text(TINY)
    (repo / "figures" / "tiny.csv").write_text("key,x,wall_s\nb,1.5,0.1\na,0.30000000000000004,0.1\n")
    (repo / "figures" / "tiny.json").write_text('{"x": 0.5, "wall_s": 7}')
    return repo


def _check(repo: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
    return subprocess.run([sys.executable, str(repo / "studies" / "reproduce.py"), *args, "--no-progress"], cwd=repo,
                          env=env, capture_output=True, text=True, timeout=300)


def _state(folder: Path) -> dict:
    return {p.name: p.read_bytes() for p in folder.iterdir()}


def test_the_script_passes_identical_tables_and_fails_a_changed_cell_or_an_unowned_table(tmp_path):
    repo = _repo(tmp_path)
    ok = _check(repo, "--check")
    assert ok.returncode == 0, ok.stdout + ok.stderr
    assert "tiny.csv (tiny): identical" in ok.stdout and "tiny.json (tiny): identical" in ok.stdout
    assert "wall_s" in ok.stdout and "git_commit" in ok.stdout  # the exceptions are named
    assert "tiny" in ok.stdout.split("Wall time per study:")[1]
    assert "Result: every table checked is identical (2 tables)" in ok.stdout

    (repo / "figures" / "tiny.csv").write_text("key,x,wall_s\na,0.30000000000000004,0.1\nb,1.25,0.1\n")
    (repo / "figures" / "orphan.csv").write_text("x\n1\n")
    before = _state(repo / "figures")
    bad = _check(repo, "--check", "--scratch", str(tmp_path / "scratch"))
    assert bad.returncode == 1, bad.stdout + bad.stderr
    assert "x [b]: committed 1.25 rerun 1.5" in bad.stdout
    assert "ERROR: orphan.csv: committed, but no study writes it" in bad.stdout
    assert "Result: 1 of 2 tables checked identical; 1 differ: tiny.csv" in bad.stdout
    assert _state(repo / "figures") == before  # the rerun went to the scratch folder
    assert (tmp_path / "scratch" / "tiny" / "tiny.csv").is_file()

    updated = _check(repo, "--update", "--only", "tiny", "--scratch", str(tmp_path / "scratch"))
    assert updated.returncode == 0, updated.stdout + updated.stderr
    assert (repo / "figures" / "tiny.png").read_bytes() == b"not compared"
    again = _check(repo, "--check", "--only", "tiny")
    assert again.returncode == 0 and "tiny.csv (tiny): identical" in again.stdout


#: a stand-in for the docs' generator: it notes its arguments and what figures/tiny.csv held then
FAKE_INPLACE = """import pathlib, sys
root = pathlib.Path(__file__).resolve().parents[3]
(root / "pages.txt").write_text(" ".join(sys.argv[1:]) + "\\n" + (root / "figures" / "tiny.csv").read_text())
print("wrote README.md")
sys.exit(int((root / "fail").exists()))
"""


def test_an_update_writes_the_fresh_numbers_into_the_pages(tmp_path):
    """--update runs docs/_ext/pkdocs/inplace.py --write after copying the tables (so the pages get
    the fresh numbers), and fails, naming it, when that fails."""
    repo = _repo(tmp_path)
    (repo / "docs" / "_ext" / "pkdocs").mkdir(parents=True)
    (repo / "docs" / "_ext" / "pkdocs" / "inplace.py").write_text(FAKE_INPLACE)
    (repo / "figures" / "tiny.csv").write_text("key,x,wall_s\na,0.3,0.1\nb,1.25,0.1\n")
    updated = _check(repo, "--update", "--only", "tiny")
    assert updated.returncode == 0, updated.stdout + updated.stderr
    assert "update: wrote README.md" in updated.stdout
    args, header, *rows = (repo / "pages.txt").read_text().splitlines()
    assert args == "--write" and [r.split(",")[:2] for r in rows] == [["a", "0.30000000000000004"], ["b", "1.5"]]
    (repo / "fail").write_text("")
    failed = _check(repo, "--update", "--only", "tiny")
    assert failed.returncode == 1
    assert "update: the pages' numbers were not rewritten (exit 1)" in failed.stdout


def test_the_script_refuses_bad_input_in_one_line_naming_the_flag(tmp_path):
    repo = _repo(tmp_path)
    for args, says in ((["--check", "--only", "nope"], "argument --only: invalid choice: 'nope' (choose from 'tiny')"),
                       (["--check", "--scratch", str(repo / "figures" / "x")], "argument --scratch: must not be figures/"),
                       (["--update"], "argument --update: needs --only"),
                       (["--check", "--quick"], "argument --quick: not accepted")):
        p = _check(repo, *args)
        lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
        assert p.returncode == 2 and len(lines) == 1 and says in lines[0], (args, p.stderr)
    assert sorted(p.name for p in (repo / "figures").iterdir()) == ["tiny.csv", "tiny.json"]
