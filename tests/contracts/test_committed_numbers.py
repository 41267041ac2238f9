"""The committed Markdown holds its generated numbers and tables (docs/_ext/pkdocs/inplace.py), so
that a page reads on its own; they are exactly what the committed data give (a stale number fails
here), the CLI's recorded runs are what the CLI prints now, and the docs build reads the markers
back as the roles and directives that compute them."""

import json
import math
import re
import shutil
import sys
from pathlib import Path

import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS / "_ext"))  # pkdocs

from pkdocs import cli_schema, inplace  # noqa: E402
from pkdocs.sources import Sources  # noqa: E402

RESULTS = sorted((DOCS / "results").glob("*.md"))


def test_every_page_with_generated_values_holds_them():
    names = {p.name: [n for n, _ in inplace.values(p.read_text())] for p in inplace.files()}
    for page in RESULTS:  # every results page has values, each of them non-empty text
        assert names[page.name], page.name
        assert all(body.strip() for _, body in inplace.values(page.read_text())), page.name
    assert {f"cli.{c}" for c in cli_schema.RUNS} <= set(names["cli.md"])
    assert names["architecture.md"] == ["events.table"]


def test_the_committed_values_are_those_of_the_committed_data():
    """Each value between its markers is what the generator writes from figures/, docs/data/ and
    the code: a number left behind by a rerun study fails (python docs/_ext/pkdocs/inplace.py --write)."""
    assert inplace.stale(Sources()) == {}


def test_no_placeholder_is_left_for_the_build_to_fill():
    """What a reader of the repository sees: no role or directive that only the built site fills."""
    pattern = re.compile(r"\{pk\}`|```\{(?:pk-table|pk-event-table|pk-cli-schema|csv-table)\}")
    pages = [ROOT / "README.md", *DOCS.glob("*.md"), *RESULTS]
    assert {p.name: pattern.findall(p.read_text()) for p in pages if pattern.search(p.read_text())} == {}


def _copy_figures(tmp: Path) -> Path:
    figs = tmp / "figures"
    shutil.copytree(ROOT / "figures", figs, ignore=shutil.ignore_patterns("*.png", "*.gif", "quick"))
    return figs


def test_a_changed_number_in_the_data_makes_the_pages_stale(tmp_path):
    """One threshold moved and one cell of a table shown whole, in a copy of figures/: exactly the
    values that read them are stale, and the rewritten text carries the new numbers."""
    figs = _copy_figures(tmp_path)
    d = pd.read_csv(figs / "threshold_vs_aspect.csv")
    k = d.index[(d["name"] == "sliding") & (d["a"] == 1.5)][0]
    d.loc[k, "threshold"] = 9.8765432
    d.to_csv(figs / "threshold_vs_aspect.csv", index=False)
    text = (figs / "euler_disk_table.csv").read_text()
    (figs / "euler_disk_table.csv").write_text(text.replace("193.011", "193.456", 1))
    src = Sources(figs)
    found = {p.name: names for p, names in inplace.stale(src).items()}
    assert "aspect.table" in found["maps.md"] and "aspect.a15" in found["findings.md"]
    assert found["euler_disk.md"] == ["csv.euler_disk_table"]
    assert "dissipation.md" not in found and "cli.md" not in found
    maps = inplace.render((DOCS / "results" / "maps.md").read_text(), src)
    assert "9.8765" in dict(inplace.values(maps))["aspect.table"]
    disk = dict(inplace.values(inplace.render((DOCS / "results" / "euler_disk.md").read_text(), src)))
    assert "| 193.456 |" in disk["csv.euler_disk_table"] and "193.011" not in disk["csv.euler_disk_table"]


def test_a_table_shown_whole_keeps_every_cell_as_written():
    rows = list(pd.read_csv(ROOT / "figures" / "spin_down_checks.csv", dtype=str, keep_default_na=False).itertuples(index=False))
    shown = dict(inplace.values((DOCS / "results" / "dissipation.md").read_text()))["csv.spin_down_checks"]
    lines = shown.splitlines()
    assert len(lines) == 2 + len(rows)
    for line, row in zip(lines[2:], rows):
        assert [c.strip() for c in line.strip("|").split(" | ")] == list(row)


def test_the_markers_read_back_as_roles_and_directives():
    text = ("**Map**: <!-- pk:tippe.n_runs -->330<!-- /pk --> runs\n\n<!-- pk:repro.table -->\n| a |\n|---|\n<!-- /pk -->\n"
            "<!-- pk:cli.simulate -->\nruns\n<!-- /pk -->\n<!-- pk:events.table -->\n<!-- /pk -->\n")
    assert inplace.to_directives(text) == ("**Map**: {pk}`tippe.n_runs` runs\n\n```{pk-table} repro.table\n```\n"
                                           "```{pk-cli-schema} simulate\n```\n```{pk-event-table}\n```\n")
    for page in inplace.files():
        assert "<!-- pk:" not in inplace.to_directives(page.read_text()), page.name


def test_no_line_begins_with_an_inline_value():
    """A Markdown viewer takes a line that begins with ``<!--`` for raw HTML (the rest of the line
    unformatted, the paragraph broken): inline values sit within their lines."""
    assert inplace.line_starts("text\n<!-- pk:a.b -->3<!-- /pk --> more\n") == [2]
    assert inplace.line_starts("<!-- pk:a.b -->\n| x |\n<!-- /pk -->\n") == []
    assert {p.name: inplace.line_starts(p.read_text()) for p in inplace.files() if inplace.line_starts(p.read_text())} == {}


def test_a_value_of_several_lines_cannot_be_written_inline(tmp_path):
    with pytest.raises(ValueError, match="repro.table has several lines"):
        inplace.render("see <!-- pk:repro.table --><!-- /pk --> here", Sources())


# -- the CLI's recorded runs -----------------------------------------------------------------------

RECORD = json.loads((DOCS / "data" / cli_schema.RECORD).read_text())


@pytest.mark.parametrize("command", list(cli_schema.RUNS))
def test_the_committed_schema_files_are_those_of_the_record(command):
    committed = json.loads((cli_schema.SCHEMAS / f"{command}.schema.json").read_text())
    assert committed == cli_schema.schema_of(RECORD, command)
    assert committed["type"] == "object" and committed["required"]


def test_a_recorded_merge_renders_the_table_of_the_merge():
    outputs = [("jump", {"t_jump": 45.2, "reason": None, "items": [1, 2], "e": []}),
               ("touchdown", {"t_jump": 42.1, "reason": "x", "flight": {"t": 3.5}, "items": [7], "e": []})]
    node = cli_schema.merge(outputs)
    labels = ["jump", "touchdown"]
    again = cli_schema.node_from_dict(json.loads(json.dumps(cli_schema.node_dict(node, labels))))
    assert cli_schema.schema_table(again, labels) == cli_schema.schema_table(node, labels)
    assert cli_schema.json_schema(again, labels) == cli_schema.json_schema(node, labels)
    assert "`flight.t` | number | touchdown | `3.5` (touchdown)" in cli_schema.schema_table(again, labels)


def _same(a, b, path="") -> list[str]:
    """Where two records differ: floats to 1e-9 relative, the wall time's example not compared."""
    if isinstance(a, dict) and isinstance(b, dict):
        if a.keys() != b.keys():
            return [f"{path}: keys {sorted(a.keys() ^ b.keys())}"]
        return [d for k in a for d in _same(a[k], b[k], f"{path}.{k}")]
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{path}: {len(a)} items against {len(b)}"]
        if path.endswith(".wall_s.example"):
            return [] if a[0] == b[0] else [f"{path}: run {a[0]} against {b[0]}"]
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in _same(x, y, f"{path}[{i}]")]
    if isinstance(a, float) and isinstance(b, float):
        return [] if math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-300) else [f"{path}: {a!r} against {b!r}"]
    return [] if a == b and type(a) is type(b) else [f"{path}: {a!r} against {b!r}"]


def test_the_same_check_finds_a_changed_key_and_ignores_the_wall_time():
    rec = {"simulate": {"results": {"keys": {"wall_s": {"example": ["jump", 0.25]}, "t": {"example": ["jump", 1.0]}}}}}
    moved = json.loads(json.dumps(rec))
    moved["simulate"]["results"]["keys"]["wall_s"]["example"][1] = 0.5
    assert _same(rec, moved) == []
    moved["simulate"]["results"]["keys"]["t"]["example"][1] = 1.0 + 1e-6
    assert _same(rec, moved) == [".simulate.results.keys.t.example[1]: 1.0 against 1.000001"]


def test_the_recorded_runs_are_what_the_cli_prints_now():
    """Every run of the CLI page, rerun (about 20 s): the same commands, exit codes, statuses,
    keys, JSON types and example values as recorded (python docs/_ext/pkdocs/cli_schema.py --write)."""
    fresh = cli_schema.record(cli_schema.run_all(jobs=2))
    assert _same(RECORD, fresh) == []
