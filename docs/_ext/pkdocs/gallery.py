"""The gallery: every script in ``examples/`` run as a user runs it (no arguments, in its own
process; it writes into ``examples/out/<name>/``), and one page per script with what it printed,
the figures and movies it wrote, the other files it wrote, and its source.

Scripts run two at a time (``pk_jobs``); a script that fails fails the docs build. With
``pk_execute = False`` the pages are written without running anything (for quick builds of the
prose); the tests build with execution on.
"""

from __future__ import annotations

import ast
import concurrent.futures as cf
import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from .sources import ROOT

EXAMPLES = ROOT / "examples"
IMAGES = (".png", ".gif", ".jpg", ".svg")
SHOWN_TEXT = (".json", ".jsonl", ".tsv", ".txt")
MAX_OUTPUT_LINES = 60


@dataclass
class Run:
    name: str  # script file name
    stem: str
    seconds: float = 0.0
    returncode: int | None = None
    stdout: str = ""
    stderr: str = ""
    files: list[Path] = field(default_factory=list)
    missing: str = ""           # a program the script needs that is not installed (it was not run)

    @property
    def images(self) -> list[Path]:
        return [f for f in self.files if f.suffix in IMAGES]


def scripts() -> list[Path]:
    return sorted(p for p in EXAMPLES.iterdir() if p.suffix in (".py", ".sh") and p.is_file())


def docstring(path: Path) -> str:
    """The module docstring (Python) or the leading comment block (shell)."""
    text = path.read_text()
    if path.suffix == ".py":
        return ast.get_docstring(ast.parse(text)) or ""
    lines = []
    for line in text.splitlines()[1:]:
        if not line.startswith("#"):
            break
        text_ = line[2:] if line.startswith("# ") else line[1:]
        lines.append("  " + text_ if text_.startswith("  ") else text_)  # indented command lines: a code block
    return "\n".join(lines).strip()


def out_dir(path: Path) -> Path:
    return EXAMPLES / "out" / path.stem


def needs(path: Path) -> list[str]:
    """Programs a shell script checks for itself (``command -v jq >/dev/null || ...``)."""
    return re.findall(r"command -v (\S+) >/dev/null", path.read_text()) if path.suffix == ".sh" else []


def run(path: Path, timeout: float = 600.0) -> Run:
    """Run one script with no arguments, as the README says a user does."""
    r = Run(path.name, path.stem)
    absent = [prog for prog in needs(path) if shutil.which(prog) is None]
    if absent:
        r.missing = ", ".join(absent)
        return r
    env = {
        **os.environ,
        "MPLBACKEND": "Agg",
        "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])),
        "PYTHON": sys.executable,
    }
    cmd = [sys.executable, str(path)] if path.suffix == ".py" else ["bash", str(path)]
    start = time.time()
    try:
        p = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout)
        r.returncode, r.stdout, r.stderr = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        r.returncode, r.stderr = -1, f"timed out after {timeout:g} s\n{e.stderr or ''}"
    r.seconds = time.time() - start
    d = out_dir(path)
    if d.is_dir():  # what this run wrote (the folder may hold older files of other runs)
        r.files = sorted(f for f in d.rglob("*") if f.is_file() and f.stat().st_mtime >= start - 1)
    return r


def run_all(paths: list[Path], jobs: int = 2, log=None) -> dict[str, Run]:
    """Every script, ``jobs`` at a time, the slowest started first; ``log(line)`` is told of
    each as it ends (the build shows it is working)."""
    order = sorted(paths, key=lambda p: p.stat().st_size, reverse=True)
    with cf.ThreadPoolExecutor(max_workers=max(1, jobs)) as ex:
        futs = [ex.submit(run, p) for p in order]
        for i, f in enumerate(cf.as_completed(futs), 1):
            r = f.result()
            if log:
                what = f"not run ({r.missing} is not installed)" if r.missing else \
                    f"ran in {r.seconds:.1f} s (exit {r.returncode})"
                log(f"pkdocs: [{i}/{len(futs)}] examples/{r.name} {what}")
        runs = [f.result() for f in futs]
    return {r.name: r for r in runs}


# -- pages ---------------------------------------------------------------------------------------

_MD_SPECIAL = re.compile(r"([\\`*_\[\]<>|#])")


def _escape(text: str) -> str:
    return _MD_SPECIAL.sub(r"\\\1", text)


def prose(doc: str) -> str:
    """A docstring as Markdown: paragraphs as text (special characters escaped), indented lines
    (command lines) as a code block."""
    out = []
    for block in re.split(r"\n\s*\n", doc.strip()):
        lines = block.splitlines()
        if all(line.startswith("    ") or not line.strip() for line in lines):
            out.append("```text\n" + "\n".join(line[4:] for line in lines) + "\n```")
        else:
            out.append(_escape(" ".join(line.strip() for line in lines)))
    return "\n\n".join(out)


def summary(doc: str) -> str:
    first = re.split(r"\n\s*\n", doc.strip())[0].replace("\n", " ")
    # the first clause: up to a colon, or a full stop that ends a sentence (not "Fig. 4")
    m = re.match(r"(.+?)(:\s|(?<!Fig)(?<!Eq)\.\s+(?=[A-Z(])|\.?$)", first)
    return (m.group(1) if m else first).rstrip(":.")


def _tail(text: str, n: int = MAX_OUTPUT_LINES) -> str:
    lines = text.rstrip().splitlines()
    if len(lines) <= n:
        return "\n".join(lines)
    return "\n".join(lines[: n // 2] + [f"... ({len(lines) - n} lines left out) ..."] + lines[-n // 2 :])


def page(path: Path, r: Run | None, image_dir: Path, docs_gallery: Path) -> str:
    """The Markdown page of one script; its images are copied into ``image_dir``."""
    stem, doc = path.stem, docstring(path)
    lang = "python" if path.suffix == ".py" else "bash"
    how = f"python examples/{path.name}" if path.suffix == ".py" else f"bash examples/{path.name}"
    lines = [f"(gallery-{stem})=", f"# {path.name}", "", prose(doc), ""]
    if r is None or r.missing:
        why = f"{r.missing} is not installed here" if r else "`pk_execute = False`"
        lines += ["```{note}", f"Not run in this build ({why}).", "```", ""]
    else:
        lines += [
            f"`{how}` ran in {r.seconds:.1f} s when these pages were built (exit status {r.returncode}) "
            f"and wrote {len(r.files)} file{'s' if len(r.files) != 1 else ''} into `examples/out/{stem}/`.",
            "",
        ]
        for img in r.images:
            dest = image_dir / stem / img.name
            dest.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(img, dest)
            rel = dest.relative_to(docs_gallery).as_posix()
            lines += [
                f"```{{figure}} {rel}",
                f":alt: {img.name} written by {path.name}",
                "",
                f"`{img.name}`",
                "```",
                "",
            ]
        if r.stdout.strip():
            lines += ["What it printed:", "", "```text", _tail(r.stdout), "```", ""]
        others = [f for f in r.files if f.suffix not in IMAGES]
        if others:
            lines += ["Other files it wrote:", ""]
            for f in others:
                size = f.stat().st_size
                lines.append(f"- `{f.relative_to(out_dir(path)).as_posix()}` ({size:,} bytes)")
            lines.append("")
            for f in others:
                if f.suffix in SHOWN_TEXT and f.stat().st_size <= 2000:
                    lines += [f"`{f.name}`:", "", "```text", f.read_text().rstrip(), "```", ""]
    rel_src = os.path.relpath(path, docs_gallery)
    lines += ["The script:", "", f"```{{literalinclude}} {rel_src}", f":language: {lang}", "```", ""]
    return "\n".join(lines)


def index(paths: list[Path], runs: dict[str, Run] | None, image_dir: Path, docs_gallery: Path) -> str:
    lines = [
        "# Gallery",
        "",
        "Every script in `examples/`, run when these pages were built, as a user runs it: with no arguments, "
        "in its own process, writing into `examples/out/<name>/` (git-ignored; `--out DIR` elsewhere). "
        "Each page shows what the script printed, the figures and movies it wrote, and its source. "
        "`tests/contracts/test_examples.py` checks what they compute.",
        "",
    ]
    if runs:
        total = sum(r.seconds for r in runs.values())
        lines += [f"Run time of all {len(runs)} scripts in this build: {total:.0f} s (two at a time).", ""]
    lines += [
        "````{list-table}",
        ":header-rows: 1",
        ":widths: 20 50 30",
        "",
        "* - script",
        "  - what it shows",
        "  - figure",
    ]
    for p in paths:
        r = runs.get(p.name) if runs else None
        lines += [f"* - {{ref}}`{p.name} <gallery-{p.stem}>`", f"  - {_escape(summary(docstring(p)))}"]
        if r and r.images and not r.missing:
            first = next((i for i in r.images if i.suffix == ".png"), r.images[0])
            rel = (image_dir / p.stem / first.name).relative_to(docs_gallery).as_posix()
            lines += [f"  - ```{{image}} {rel}", "    :width: 240px", f"    :alt: {first.name}", "    ```"]
        else:
            lines.append("  - (text output)" if r else "  - (not run)")
    lines += ["````", "", "```{toctree}", ":hidden:", "", *(p.stem for p in paths), "```", ""]
    return "\n".join(lines)


def build(docs: Path, execute: bool = True, jobs: int = 2, log=None) -> dict[str, Run]:
    """Run the scripts and (re)write docs/gallery/, telling ``log(line)`` of each script run and
    each page written. Returns the runs (empty when not executed)."""
    gal = docs / "gallery"
    if gal.exists():
        shutil.rmtree(gal)
    image_dir = gal / "images"
    image_dir.mkdir(parents=True)
    paths = scripts()
    runs = run_all(paths, jobs, log) if execute else {}
    for p in paths:
        (gal / f"{p.stem}.md").write_text(page(p, runs.get(p.name), image_dir, gal))
        if log:
            log(f"pkdocs: wrote gallery/{p.stem}.md")
    (gal / "index.md").write_text(index(paths, runs, image_dir, gal))
    return runs
