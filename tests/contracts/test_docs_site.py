"""The documentation site builds without a warning, with everything generated where it should be:
the gallery runs every example and shows its figures, the CLI page describes real runs, the
results pages read their numbers from figures/ (a changed number in a copy changes the page),
the event table comes from the declarations, and the examples in the docstrings run."""

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

RESULTS = ["reproduction", "findings", "maps", "bodies", "steady_structure", "performance", "robustness"]


def sphinx(out: Path, *options: str) -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", *options, str(DOCS), str(out)]
    return subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=1200)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The whole site, as a user builds it: the examples and the CLI runs executed."""
    out = tmp_path_factory.mktemp("site")
    p = sphinx(out)
    assert p.returncode == 0, p.stderr[-4000:]
    assert p.stderr.strip() == ""
    return out


def text(site: Path, page: str) -> str:
    return (site / f"{page}.html").read_text()


def plain(html: str) -> str:
    """What a reader sees: the page without its tags."""
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
    from pkdocs import readme

    readme_text = (ROOT / "README.md").read_text()
    assert readme.render(readme_text, after) != readme_text


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


@pytest.mark.parametrize("module", ["phasekit.core.sections", "phasekit.sweep.ensemble", "phasekit.viz.mpl", "phasekit.theory.paper",
                                    "phasekit.theory.surface", "phasekit.core.units"])
def test_docstring_examples_run(module):
    mod = importlib.import_module(module)
    res = doctest.testmod(mod, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert res.attempted > 0 and res.failed == 0
