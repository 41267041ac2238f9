"""The README is a front door: short, its two set-up commands as .ci/run reads them, its Python
runs as printed, its numbers generated from the committed data, its links inside the repository."""

import pathlib
import re
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
TEXT = (ROOT / "README.md").read_text()
BLOCKS = re.findall(r"^```python\n(.*?)^```", TEXT, flags=re.S | re.M)
VENV = "python3 -m venv .venv && . .venv/bin/activate && "
MAIN = VENV + 'pip install -e ".[sweep]" && python studies/threshold_vs_aspect.py'
TEST = VENV + 'pip install -e ".[test]" && python -m pytest -m "not slow" -q'

sys.path.insert(0, str(ROOT / "docs" / "_ext"))


def test_the_readme_is_at_most_200_lines():
    assert len(TEXT.splitlines()) <= 200


@pytest.mark.parametrize("marker, command", [("main-command", MAIN), ("test-command", TEST)])
def test_setup_commands_are_where_ci_reads_them(marker, command):
    """.ci/run takes the line two below the marker (awk: getline; getline; print)."""
    lines = TEXT.splitlines()
    [k] = [i for i, line in enumerate(lines) if line == f"<!-- {marker} -->"]
    assert lines[k + 1] == "```" and lines[k + 2] == command and lines[k + 3] == "```"
    ci = subprocess.run(["awk", f"/<!-- {marker} -->/{{getline; getline; print; exit}}", str(ROOT / "README.md")],
                        capture_output=True, text=True)
    assert ci.stdout.strip() == command


def test_the_readme_has_python_examples():
    assert len(BLOCKS) >= 1


@pytest.mark.parametrize("code", BLOCKS, ids=[f"block{i + 1}" for i in range(len(BLOCKS))])
def test_readme_python_block_runs(code):
    # -c, as typed into an interpreter: pk.ensemble's spawned workers need no __main__ guard there
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert p.returncode == 0, p.stderr[-2000:]


def test_generated_blocks_match_the_committed_data():
    """The reproduction table, the class counts, the egg's jumps and the fuzz counts are the values
    the docs compute from figures/ and docs/data/ (python docs/_ext/pkdocs/inplace.py --write)."""
    from pkdocs import inplace
    from pkdocs.sources import Sources

    names = [name for name, _ in inplace.values(TEXT)]
    assert {"repro.table", "readme.steady_counts", "readme.egg_jumps", "readme.robustness_counts"} <= set(names)
    for (name, body), (_, fresh) in zip(inplace.values(TEXT), inplace.values(inplace.render(TEXT, Sources()))):
        assert body == fresh, f"README block {name} is stale: python docs/_ext/pkdocs/inplace.py --write"


def test_the_readme_has_its_sections_and_figures():
    for needle in ("## Reproduction of the paper", "## Steady-state structure", "figures/steady_structure_atlas.png",
                   "figures/tippe_top_inversion_strip.png", "figures/egg_jump_strip.png",
                   "Egg jumps against experiment", "## Robustness", "## How to cite", "## Documentation",
                   "## A 30-second tour"):
        assert needle in TEXT, needle


def test_no_changelog_prose():
    """History belongs in CHANGELOG.md."""
    for pattern in (r"\bnow\b", r"\bno longer\b", r"\bafter the refactor\b", r"\bbefore issue\b", r"\bissue \d+\b"):
        assert not re.search(pattern, TEXT, flags=re.I), pattern


def _slug(heading: str) -> str:
    """GitHub's and MyST's anchor of a Markdown heading."""
    s = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return s.replace(" ", "-")


@pytest.mark.parametrize("target", sorted(set(re.findall(r"\]\(([^)\s]+)\)", TEXT))))
def test_links_point_inside_the_repository(target):
    assert not target.startswith(("http:", "https:")), "README links stay inside the repository"
    path, _, anchor = target.partition("#")
    f = ROOT / path
    assert f.is_file() or (f.is_dir() and not anchor), target
    if anchor:
        headings = re.findall(r"^#+ (.+)$", f.read_text(), flags=re.M)
        assert anchor in {_slug(h) for h in headings}, f"{target}: no heading with that anchor"
