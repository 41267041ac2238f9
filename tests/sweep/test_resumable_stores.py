"""Result stores survive a kill: finished rows are kept and not recomputed, a torn last row is
dropped and recomputed, and the next row starts on a line of its own; the manifest keeps every
run."""

import csv
import dataclasses
import json
from dataclasses import dataclass, replace

from phasekit.studies import SearchRow
from phasekit.sweep import ResultStore, TaskSpec, run_tasks

import pytest

from ..thresholds.synthetic_definitions import power_law


@dataclass(frozen=True)
class Row:
    key: str
    value: float


def _task(prev, value):
    return Row(f"k{value}", value + (prev.value if prev else 0.0))


def test_store_resumes_without_recomputing(tmp_path):
    csv_path, man = tmp_path / "r.csv", tmp_path / "r.json"
    specs = [TaskSpec(f"k{v}", _task, (v,), after=f"k{v - 1}" if v > 0 else None) for v in range(5)]
    store = ResultStore(csv_path, man, Row, {"study": "test"})
    calls = []

    def on_result(s, r):
        calls.append(s.key)
        store.add(r)
        if len(calls) == 3:
            raise KeyboardInterrupt  # the sweep is killed after three points

    with pytest.raises(KeyboardInterrupt):
        run_tasks(specs, store_get=store.get, on_result=on_result, progress=False)
    assert len(list(csv.DictReader(open(csv_path)))) == 3  # nothing lost
    store2 = ResultStore(csv_path, man, Row, {"study": "test"})
    again = []
    res = run_tasks(specs, store_get=store2.get, on_result=lambda s, r: (again.append(s.key), store2.add(r)), progress=False)
    assert again == ["k3", "k4"]  # finished points are skipped
    assert res["k4"].value == 0 + 1 + 2 + 3 + 4  # continuation used the stored (typed) results
    meta = json.loads(man.read_text())
    assert meta["n_rows"] == 5 and meta["study"] == "test"


@pytest.mark.parametrize("tail", ["k9,", "k9,1.2.3\n", "k9,\"unterminated"])
def test_store_drops_a_torn_last_row_and_appends_on_a_new_line(tmp_path, tail):
    """A kill in mid-write leaves a partial last line: on resume it is dropped (to be
    recomputed) and the next row starts on a line of its own."""
    csv_path, man = tmp_path / "r.csv", tmp_path / "r.json"
    store = ResultStore(csv_path, man, Row, {})
    for v in range(3):
        store.add(Row(f"k{v}", float(v)))
    with open(csv_path, "a") as fh:
        fh.write(tail)
    store2 = ResultStore(csv_path, man, Row, {})
    assert "k9" not in store2 and store2.dropped == 1 and len(store2.rows()) == 3
    store2.add(Row("k3", 3.0))
    rows = list(csv.reader(open(csv_path)))
    assert rows[0] == ["key", "value"] and [r[0] for r in rows[1:]] == ["k0", "k1", "k2", "k3"]
    assert ResultStore(csv_path, man, Row, {}).get("k3").value == 3.0


@dataclasses.dataclass(frozen=True)
class RowWithNote:
    key: str
    value: float
    note: str


@pytest.mark.parametrize("cut", ["inside the last text field", "inside a number"])
def test_torn_last_row_is_recomputed_and_the_next_row_starts_a_new_line(tmp_path, cut):
    csv, manifest = tmp_path / "rows.csv", tmp_path / "rows.json"
    store = ResultStore(csv, manifest, RowWithNote, {})
    store.add(RowWithNote("a", 1.0, "first"))
    store.add(RowWithNote("b", 2.5, "second row"))
    text = csv.read_text()
    # a kill mid-write: the cut text field still parses, so the missing newline must decide
    cut_at = len(text) - 5 if cut == "inside the last text field" else text.index("2.5") + 2
    csv.write_text(text[:cut_at])
    store = ResultStore(csv, manifest, RowWithNote, {})
    assert store.dropped == 1 and "a" in store and "b" not in store
    store.add(RowWithNote("c", 3.0, "third"))
    lines = csv.read_text().splitlines()
    assert lines == ["key,value,note", "a,1.0,first", "c,3.0,third"]


def test_search_rows_survive_a_kill_and_resume(tmp_path):
    """Independent tasks (longest first) into a store; killed after two rows; the rerun
    computes only the rest; a torn row is recomputed."""
    defn = power_law()
    specs = [TaskSpec(f"k{i}", _row_task, (i,), cost=float(i)) for i in range(5)]
    csv_path, man = tmp_path / "s.csv", tmp_path / "s.json"
    store = ResultStore(csv_path, man, SearchRow, {"study": "t"})
    done = []

    def on_result(s, r):
        store.add(r)
        done.append(s.key)
        if len(done) == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_tasks(specs, store_get=store.get, on_result=on_result, progress=False)
    assert done == ["k4", "k3"]  # the costliest first
    with open(csv_path, "a") as fh:
        fh.write("k9,t,threshold,prol")  # a kill in mid-write
    again = ResultStore(csv_path, man, SearchRow, {"study": "t"})
    assert again.dropped == 1 and again.get("k4") == _row_task(None, 4)
    later = []
    run_tasks(specs, store_get=again.get, on_result=lambda s, r: (later.append(s.key), again.add(r)), progress=False)
    assert later == ["k2", "k1", "k0"]
    with open(csv_path) as fh:
        rows = list(csv.DictReader(fh))
    assert [r["key"] for r in rows] == ["k4", "k3", "k2", "k1", "k0"] and rows[0]["sens_half"] == ""
    assert defn.key() != replace(defn, amplitude=0.1).key()
    # the manifest keeps both runs that computed rows: what each computed, and under which command
    runs = json.loads(man.read_text())["runs"]
    assert [(r["rows_at_start"], r["rows_added"]) for r in runs] == [(0, 2), (2, 3)]
    assert json.loads(man.read_text())["started"] == runs[0]["started"]
    # a redraw from the stored rows computes nothing and leaves the manifest (its provenance) as it is,
    # unless it annotates something new
    before = man.read_bytes()
    replot = ResultStore(csv_path, man, SearchRow, {"study": "t", "command": "replot"})
    replot.annotate(study="t")
    assert man.read_bytes() == before and len(replot.rows()) == 5
    replot.annotate(summary="a new summary")
    runs = json.loads(man.read_text())["runs"]
    assert runs[-1]["command"] == "replot" and runs[-1]["rows_added"] == 0
    assert json.loads(man.read_text())["summary"] == "a new summary"


def _row_task(prev, i):
    return SearchRow(key=f"k{i}", study="t", kind="threshold", branch="prolate", a=1.5, mu=0.1, d=0.01, value=None,
                     threshold=9.0 + i / 3, bracket_lo=9.0, bracket_hi=9.0 + i, status="converged", n_sims=15 + i, n_rounds=4,
                     levels=3, engine="batch", eps=None, rtol=1e-9, t_max=3000.0, transitions="[[9.0, 10.0]]",
                     stuck_near=False, sens_half=None, sens_double=None, sens_slope=-0.09, sens_shift=None,
                     sens_dominant="", wall_s=0.25, reason="")
