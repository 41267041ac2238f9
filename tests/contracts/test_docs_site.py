"""The documentation site builds without a warning, with everything generated where it should be:
the gallery runs every example and shows its figures, the CLI page describes real runs (each
example value one run's own), the results pages read their numbers from figures/ (a changed
number in a copy changes the page), the event table comes from the declarations, the examples in
the docstrings run, every ``pk.X`` a reader sees exists, and the build says what it is doing
while it runs the examples."""

import doctest
import importlib
import json
import re
import shutil
import subprocess
import sys
from html import unescape
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS / "_ext"))  # pkdocs, imported by the tests that use it

RESULTS = ["reproduction", "findings", "maps", "bodies", "steady_structure", "performance", "robustness", "dissipation", "euler_disk"]


def sphinx(out: Path, *options: str, quiet: bool = True) -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", *(["-q"] if quiet else []), "-b", "html", *options,
           str(DOCS), str(out)]
    return subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=1200)


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    """The whole site, as a user builds it (the examples and the CLI runs executed), and what
    the build printed on stdout (its progress: not quiet)."""
    out = tmp_path_factory.mktemp("site")
    p = sphinx(out, quiet=False)
    assert p.returncode == 0, p.stderr[-4000:]
    assert p.stderr.strip() == ""
    return out, p.stdout


@pytest.fixture(scope="module")
def site(build):
    return build[0]


def text(site: Path, page: str) -> str:
    return (site / f"{page}.html").read_text()


def plain(html: str) -> str:
    """What a reader sees: the page without its tags, block elements (a term and its description,
    paragraphs, cells) apart as on the screen."""
    html = re.sub(r"</?(?:p|dt|dd|li|div|td|th|tr|h\d)\b[^>]*>", "\n", html)
    return unescape(re.sub(r"<[^>]+>", "", html))


API_PAGES = ["top", "io", "bodies", "friction", "core", "core.engines", "theory", "theory.tippetop", "baseline", "steady",
             "thresholds", "sweep", "viz"]


def test_api_reference(site):
    index = text(site, "api/index")
    for page in API_PAGES:
        assert f'href="{page}.html"' in index, page
    # each entry is on the page of its package, with its anchor; the top level's own names on api/top
    for page, names in {
        "top": ("phasekit.paper_start", "phasekit.Scene.add_trajectory", "phasekit.PhasekitError"),
        "core": ("phasekit.core.simulate", "phasekit.core.Trajectory.sample", "phasekit.core.poincare"),
        "sweep": ("phasekit.sweep.ensemble", "phasekit.sweep.rerun"),
        "bodies": ("phasekit.bodies.Body",),
        "theory": ("phasekit.theory.PAPER_CASES",),
        "theory.tippetop": ("phasekit.theory.tippetop.classical_inversion",),
        "viz": tuple(f"phasekit.viz.{n}" for n in ("plot_timeseries", "plot_events", "plot_section", "render_scene",
                                                   "animate", "film_strip")),
    }.items():
        api = text(site, f"api/{page}")
        for name in names:
            assert f'id="{name}"' in api, (page, name)
    top = text(site, "api/top")  # the re-exports are shown there, and documented (with their anchors) at home
    assert "phasekit.simulate" in plain(top) and 'id="phasekit.simulate"' not in top


def test_markdown_pages_are_part_of_the_site(site):
    assert "Stability of the steady states" in text(site, "physics")
    assert "Where things plug in" in text(site, "architecture")
    assert "Using phasekit" in text(site, "guide")
    changelog = text(site, "changelog")
    assert "Changelog" in changelog and "Documentation site" in changelog
    index = text(site, "index")
    for page in ["guide", "gallery/index", "cli", "physics", "architecture", "api/index", "changelog",
                 *(f"results/{r}" for r in RESULTS)]:
        assert f'href="{page}.html"' in index, page


def test_every_example_has_a_gallery_page_with_what_it_made(site):
    from pkdocs import gallery

    scripts = gallery.scripts()
    assert {p.name for p in scripts} == {p.name for p in (ROOT / "examples").iterdir() if p.suffix in (".py", ".sh")}
    index = text(site, "gallery/index")
    for p in scripts:
        page = text(site, f"gallery/{p.stem}")
        assert f'href="{p.stem}.html"' in index, p.name
        absent = [prog for prog in gallery.needs(p) if shutil.which(prog) is None]
        if absent:  # .ci/run installs them; elsewhere the page says why the script did not run
            assert f"{', '.join(absent)} is not installed here" in plain(page)
            continue
        assert re.search(r"ran in [\d.]+ s when these pages were built \(exit status 0\)", page), p.name
        if p.suffix == ".py":  # every Python example draws: its images are on its page, and copied into the site
            imgs = re.findall(r'<img[^>]+src="([^"]+)"', page)
            assert imgs, f"{p.name}: no image on its page"
            for src in imgs:
                assert (site / "gallery" / src).resolve().is_file(), src
            assert any(Path(src).suffix in (".png", ".gif") for src in imgs)
        else:  # the shell example's JSON output is shown
            assert "t_jump" in page and "jumped" in page
    movie = text(site, "gallery/animate_body")
    assert "rise.gif" in movie and "strip.png" in movie


def test_cli_page_describes_real_runs_of_every_command(site, tmp_path):
    page = plain(text(site, "cli"))
    for command in ("simulate", "animate", "fixed-points", "steady-states", "gyroscopic"):
        assert f"phasekit {command}" in page
        schema = json.loads((site / "_downloads").glob(f"*/{command}.schema.json").__next__().read_text())
        assert schema["type"] == "object" and schema["properties"] and schema["$schema"].startswith("https://json-schema")
    # every key of a fresh run is on the page, with its nested keys
    p = subprocess.run([sys.executable, "-m", "phasekit", "steady-states", "--body", "tippe-top", "--offset", "0.25",
                        "--mu", "0.2", "--json"], capture_output=True, text=True, cwd=ROOT, timeout=300)
    out = json.loads(p.stdout)
    for key in out:
        assert re.search(rf"^{re.escape(key)}$", page, flags=re.M), key  # a row of the table starts with the key
    assert "branches[].ends[].kind" in page
    assert "Bad input (exit 2) prints instead" in page


def _table_rows(html: str, section: str) -> list[list[str]]:
    """The cells, as a reader sees them, of the first table in the page's section ``section``."""
    part = re.search(rf'<section id="{section}">(.*?)</section>', html, flags=re.S).group(1)
    table = re.search(r"<table.*?</table>", part, flags=re.S).group(0)
    return [[plain(c).strip() for c in re.findall(r"<t[dh][^>]*>(.*?)</t[dh]>", row, flags=re.S)]
            for row in re.findall(r"<tr[^>]*>(.*?)</tr>", table, flags=re.S)]


def _value_at(obj, parts: list[str]):
    """(found, value) at a key path of the schema table: ``a.b``, and ``a[]`` for the first item
    of a list that has the rest of the path."""
    if not parts:
        return True, obj
    head, rest = parts[0], parts[1:]
    key = head.removesuffix("[]")
    if not isinstance(obj, dict) or key not in obj:
        return False, None
    if key == head:
        return _value_at(obj[key], rest)
    for item in obj[key] if isinstance(obj[key], list) else []:
        found, value = _value_at(item, rest)
        if found:
            return True, value
    return False, None


def test_each_cli_example_is_one_runs_own_value(site):
    """Every example of the simulate table is what one run printed: unlabelled, that of the first
    run (checked against a fresh run with the same arguments), else labelled with its run (and
    then the first run has no such key). Only the wall time differs between two runs."""
    from pkdocs import cli_schema

    labels = [label for label, _ in cli_schema.RUNS["simulate"]]
    fresh = cli_schema._run("simulate", labels[0], cli_schema.RUNS["simulate"][0][1], "").output
    header, *rows = _table_rows(text(site, "cli"), "simulate")
    assert header[-1] == f"example (run {labels[0]}, unless named)"
    compared = 0
    for key, _types, _runs, example in rows:
        found, value = _value_at(fresh, key.split("."))
        named = re.fullmatch(r"(.*) \((.+)\)", example)
        if named and named.group(2) in labels[1:]:
            assert not found, (key, example)  # another run's value only where the first run has none
        elif example:
            assert found, (key, example)
            if key != "wall_s":
                assert example == json.dumps(value)[:40].rstrip(), (key, example, value)
                compared += 1
        else:
            assert not found or isinstance(value, (dict, list)), (key, value)
    assert compared > 40 and any(k == "t_jump" for k, *_ in rows)


def test_examples_of_merged_outputs_keep_to_one_run():
    """Two runs merged: a key the first run has shows the first run's value (null included), a
    key only the second has shows the second's, named."""
    from pkdocs import cli_schema

    node = cli_schema.merge([("jump", {"t_jump": 45.2, "reason": None, "items": [1, 2]}),
                             ("touchdown", {"t_jump": 42.1, "reason": "x", "flight": {"t": 3.5}, "items": [7]})])
    rows = {r[0]: r[3] for r in cli_schema.rows(node, ["jump", "touchdown"])}
    assert rows == {"`t_jump`": "`45.2`", "`reason`": "`null`", "`items`": "", "`items[]`": "`1`", "`flight`": "",
                    "`flight.t`": "`3.5` (touchdown)"}
    schema = cli_schema.json_schema(node, ["jump", "touchdown"])
    assert schema["properties"]["t_jump"]["examples"] == [45.2]
    assert schema["properties"]["flight"]["properties"]["t"]["examples"] == [3.5]


def test_the_build_says_what_it_is_doing(build):
    """While it runs the examples and the CLI (minutes), the build prints a line as each ends and
    as each generated page is written (sphinx's logger: quiet with -q)."""
    from pkdocs import cli_schema, gallery

    _, stdout = build
    scripts = gallery.scripts()
    n_cli = sum(len(r) for r in cli_schema.RUNS.values())
    for p in scripts:
        assert re.search(rf"^pkdocs: \[\d+/{len(scripts)}\] examples/{re.escape(p.name)} (ran in|not run)", stdout,
                         flags=re.M), p.name
        assert f"pkdocs: wrote gallery/{p.stem}.md" in stdout, p.name
    for command, runs in cli_schema.RUNS.items():
        for label, _ in runs:
            assert re.search(rf"^pkdocs: \[\d+/{n_cli}\] phasekit {command} \({re.escape(label)}\): exit \d$", stdout,
                             flags=re.M), (command, label)
        assert f"pkdocs: wrote _generated/schemas/{command}.schema.json" in stdout, command
    assert f"[{len(scripts)}/{len(scripts)}]" in stdout and f"[{n_cli}/{n_cli}]" in stdout


# -- names written in the docs ------------------------------------------------------------------

_NAME = re.compile(r"(?<![\w.])(?:pk|phasekit)((?:\.[A-Za-z_]\w*)+)")


def _resolves(path: str) -> bool:
    """Does ``phasekit.a.b.c`` exist: the longest importable module, then attributes?"""
    parts = path.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ModuleNotFoundError:
            continue
        for attr in parts[i:]:
            if not hasattr(obj, attr):
                return False
            obj = getattr(obj, attr)
        return True
    return False


def unresolved(text_: str) -> list[str]:
    """The ``pk.X...`` and ``phasekit.X...`` written in ``text_`` (prose, code, comments) that
    name nothing."""
    return sorted({m.group(0) for m in _NAME.finditer(text_) if not _resolves("phasekit" + m.group(1))})


def test_the_name_check_catches_a_name_in_a_comment():
    block = "# A and C default to the uniform solid's (pk.uniform_mass_properties);\nb = pk.Spheroid(1.5)"
    assert unresolved(block) == ["pk.uniform_mass_properties"]
    assert unresolved("phasekit.bodies.body.uniform_mass_properties, pk.viz.animate, pk.Scale(...).unit") == []


def test_every_name_written_in_the_doc_sources_exists():
    """Every page source, the examples the gallery shows and the text the docs extension
    generates (the changelog names what existed then)."""
    sources = [*DOCS.rglob("*.md"), *DOCS.rglob("*.rst"), *(DOCS / "_ext").rglob("*.py"), DOCS / "conf.py",
               *(ROOT / "examples").glob("*.py"), *(ROOT / "examples").glob("*.sh")]
    bad = {str(f.relative_to(ROOT)): unresolved(f.read_text()) for f in sources
           if "_build" not in f.parts and f.name != "changelog.md"}
    assert {f: names for f, names in bad.items() if names} == {}


def test_every_name_on_the_built_site_exists(site):
    """What a reader sees on every page, generated ones included (gallery, CLI, API, results):
    no ``pk.X`` that names nothing. The changelog, which names what existed then, is left out."""
    bad = {}
    for page in site.rglob("*.html"):
        if page.name == "changelog.html" or "_sources" in page.parts:
            continue
        html = re.sub(r"<(script|style)\b.*?</\1>", "", page.read_text(), flags=re.S)
        names = unresolved(plain(html))
        if names:
            bad[str(page.relative_to(site))] = names
    assert bad == {}


def test_results_pages_show_the_committed_numbers(site):
    import pandas as pd
    from pkdocs import facts
    from pkdocs.sources import Sources

    src = Sources()
    steady = text(site, "results/steady_structure")
    v = facts.values(src, "steady")
    assert f"<td><p>{v['spheroid_classes']}</p></td>" in steady and f"<td><p>{v['tippe_classes']}</p></td>" in steady
    maps = text(site, "results/maps")
    d = pd.read_csv(ROOT / "figures" / "threshold_vs_aspect.csv")
    default = d[(d["name"] == "sliding") & (d["status"] == "converged")]
    for t in default["threshold"]:
        assert f"{t:.4f}" in maps
    for r in RESULTS:
        page = text(site, f"results/{r}")
        assert "problematic" not in page and "pk:" not in page, r


def test_the_event_table_is_generated_once(site):
    from phasekit.core import system

    page = text(site, "architecture")
    model = __import__("phasekit").Model(__import__("phasekit").Spheroid(1.5), __import__("phasekit").Coulomb(0.1))
    for ev in system.declare(model, stop_at="none").events:
        assert ev.name in page and ev.on in page, ev.name
    # no hand-written copy left: not in the README, the architecture notes or system.py's docstring
    for f in (ROOT / "README.md", DOCS / "architecture.md"):
        assert not re.search(r"^\|\s*lift-off\s*\|", f.read_text(), flags=re.M), f
    assert "lift-off" not in (system.__doc__ or "")


def test_criteria_are_stated_once():
    """The pole criterion and the horizontal-precession threshold, as formulas, appear in the
    physics notes only; the other pages link there."""
    pole = "n0^2 rho (A rho - C h0) < h2 h0^2"
    horizontal = "Omega0^2 (C rho_m / h_e - A) > h2"
    pages = [ROOT / "README.md", *DOCS.glob("*.md"), *DOCS.glob("results/*.md")]
    where = {f.name for f in pages if pole in f.read_text() or horizontal in f.read_text()}
    assert where == {"physics.md"}


def _copy_figures(tmp: Path) -> Path:
    figs = tmp / "figures"
    shutil.copytree(ROOT / "figures", figs, ignore=shutil.ignore_patterns("*.png", "*.gif", "quick"))
    return figs


def _change_numbers(figs: Path) -> dict:
    """Change committed numbers in the copy: one class fewer, one threshold moved."""
    import pandas as pd

    atlas = json.loads((figs / "steady_structure_atlas.json").read_text())
    atlas["summary"]["classes"]["spheroid"] = atlas["summary"]["classes"]["spheroid"][:-1]
    (figs / "steady_structure_atlas.json").write_text(json.dumps(atlas))
    d = pd.read_csv(figs / "threshold_vs_aspect.csv")
    k = d.index[(d["name"] == "sliding") & (d["a"] == 1.5)][0]
    old = d.loc[k, "threshold"]
    d.loc[k, "threshold"] = 9.8765432
    d.to_csv(figs / "threshold_vs_aspect.csv", index=False)
    return {"classes": len(atlas["summary"]["classes"]["spheroid"]), "old": f"{old:.4f}", "new": "9.8765"}


def test_a_changed_manifest_changes_the_generated_numbers(tmp_path):
    from pkdocs import facts
    from pkdocs.sources import Sources

    figs = _copy_figures(tmp_path)
    before = Sources(figs)
    assert facts.lookup(before, "aspect.a15") == "9.743"
    changed = _change_numbers(figs)
    after = Sources(figs)
    assert facts.lookup(after, "steady.spheroid_classes") == str(changed["classes"])
    assert facts.lookup(after, "aspect.a15") == "9.877"
    assert changed["new"] in facts.lookup(after, "aspect.table")
    assert "9.877" in facts.lookup(after, "repro.table")
    # ... and the README's generated blocks would be flagged as stale
    from pkdocs import inplace

    readme_text = (ROOT / "README.md").read_text()
    assert inplace.render(readme_text, after) != readme_text


@pytest.mark.slow  # a second Sphinx build (~13 s); the generated numbers are checked without it above
def test_a_changed_manifest_changes_the_built_page(tmp_path):
    figs = _copy_figures(tmp_path)
    changed = _change_numbers(figs)
    out = tmp_path / "html"
    p = sphinx(out, "-D", f"pk_figures={figs}", "-D", "pk_execute=0")
    assert p.returncode == 0, p.stderr[-4000:]
    steady = (out / "results" / "steady_structure.html").read_text()
    assert f"<td><p>{changed['classes']}</p></td>" in steady
    maps = (out / "results" / "maps.html").read_text()
    assert changed["new"] in maps and changed["old"] not in maps
    assert "Not run in this build" in (out / "gallery" / "fig4_case.html").read_text()


def test_a_missing_data_file_fails_the_build(tmp_path):
    from pkdocs import facts
    from pkdocs.sources import Sources

    figs = _copy_figures(tmp_path)
    (figs / "bouncing.csv").unlink()
    with pytest.raises(LookupError, match="bouncing.csv"):
        facts.lookup(Sources(figs), "theory.mu_e_range")


GUIDE_BLOCKS = re.findall(r"^```python\n(.*?)^```", (DOCS / "guide.md").read_text(), flags=re.S | re.M)


@pytest.mark.parametrize("code", GUIDE_BLOCKS, ids=[f"guide-block{i + 1}" for i in range(len(GUIDE_BLOCKS))])
def test_guide_python_blocks_run(code):
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert p.returncode == 0, p.stderr[-2000:]


@pytest.mark.parametrize("module", ["phasekit.core.sections", "phasekit.sweep.ensemble", "phasekit.viz.mpl", "phasekit.viz.energy",
                                    "phasekit.theory.paper",
                                    "phasekit.scenes.scene", "phasekit.core.units"])
def test_docstring_examples_run(module):
    mod = importlib.import_module(module)
    res = doctest.testmod(mod, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert res.attempted > 0 and res.failed == 0
