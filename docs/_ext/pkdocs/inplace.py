"""The generated numbers and tables, written into the committed Markdown, so that a page reads on
its own (in the repository's web view, an editor, a diff) and not only on the built site.

A generated value stands between two HTML comments, which Markdown viewers do not show:

* inline, within a line: ``<!-- pk:tippe.n_runs -->96<!-- /pk -->``;
* a block (a table), the markers on lines of their own::

      <!-- pk:repro.table -->
      | ... |
      <!-- /pk -->

NAME is ``group.value`` of :mod:`pkdocs.facts`, computed from the committed data (``figures/``,
``docs/data/``, the event declarations). The docs build reads the markers back as the roles and
directives of :mod:`pkdocs` (:func:`to_directives`), so the site computes every value afresh
from the data it is pointed at; the committed text is checked against the committed data by
tests/contracts/test_committed_numbers.py.

    python docs/_ext/pkdocs/inplace.py            # exit 1 and list the values that differ
    python docs/_ext/pkdocs/inplace.py --write    # rewrite them in every file of FILES

``studies/reproduce.py --update`` runs the ``--write`` after copying fresh tables into figures/.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

if __package__ in (None, ""):  # run as a script
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    __package__ = "pkdocs"

from pkdocs import facts  # noqa: E402
from pkdocs.sources import DOCS, ROOT, Sources  # noqa: E402

_NAME = r"(?P<name>[\w.-]+)"
#: a block: both markers alone on their lines, no other marker inside
BLOCK = re.compile(rf"^(<!-- pk:{_NAME} -->\n)(?P<body>(?:(?!<!-- pk:).)*?)\n?^(<!-- /pk -->)$", re.S | re.M)
#: an inline value: on one line
INLINE = re.compile(rf"(<!-- pk:{_NAME} -->)(?P<body>[^\n]*?)(<!-- /pk -->)")

#: the groups whose blocks the docs build draws with a directive of their own, and its argument
#: (the others: ``pk-table NAME``)
DIRECTIVES = {"cli": ("pk-cli-schema", "{item}"), "events": ("pk-event-table", "")}


def files() -> list[Path]:
    """Every committed Markdown file with generated values."""
    return [ROOT / "README.md", DOCS / "architecture.md", DOCS / "cli.md", *sorted((DOCS / "results").glob("*.md"))]


def values(text: str) -> list[tuple[str, str]]:
    """(name, committed text) of every generated value, blocks first, in the order written."""
    blocks = [(m["name"], m["body"]) for m in BLOCK.finditer(text)]
    return blocks + [(m["name"], m["body"]) for m in INLINE.finditer(BLOCK.sub("", text))]


def _inline_value(src: Sources, name: str) -> str:
    value = facts.lookup(src, name)
    if "\n" in value:
        raise ValueError(f"the value {name} has several lines: write it as a block (its markers on lines of their own)")
    return value


def render(text: str, src: Sources) -> str:
    """``text`` with every generated value computed afresh from ``src``."""
    text = BLOCK.sub(lambda m: m.group(1) + facts.lookup(src, m["name"]) + "\n" + m.group(4), text)
    return INLINE.sub(lambda m: m.group(1) + _inline_value(src, m["name"]) + m.group(4), text)


def _directive(name: str) -> str:
    group, _, item = name.partition(".")
    directive, argument = DIRECTIVES.get(group, ("pk-table", "{name}"))
    return f"```{{{directive}}} {argument.format(name=name, item=item)}".rstrip() + "\n```"


def to_directives(text: str) -> str:
    """The page as the docs build reads it: each value's markers and committed text replaced by
    the role or directive that computes it (``{pk}`NAME```, ``{pk-table} NAME``, ...)."""
    text = BLOCK.sub(lambda m: _directive(m["name"]), text)
    return INLINE.sub(lambda m: f"{{pk}}`{m['name']}`", text)


def line_starts(text: str) -> list[int]:
    """The lines (1-based) that begin with an inline value: a Markdown viewer takes a line that
    begins with ``<!--`` for raw HTML, and would show the rest of it unformatted."""
    block_lines = {text.count("\n", 0, m.start()) + 1 for m in BLOCK.finditer(text)}
    return [i for i, line in enumerate(text.splitlines(), 1)
            if INLINE.match(line.lstrip()) and i not in block_lines]


def stale(src: Sources | None = None) -> dict[Path, list[str]]:
    """Per file, the names of the values whose committed text differs from what ``src`` gives."""
    src = src or Sources()
    out = {}
    for path in files():
        text = path.read_text()
        diff = [name for (name, a), (_, b) in zip(values(text), values(render(text, src))) if a != b]
        if diff:
            out[path] = diff
    return out


def write(src: Sources | None = None) -> list[Path]:
    """Rewrite every value of every file from ``src``; the files that changed."""
    src = src or Sources()
    changed = []
    for path in files():
        text = path.read_text()
        new = render(text, src)
        if new != text:
            path.write_text(new)
            changed.append(path)
    return changed


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if "--write" in argv:
        for path in write():
            print(f"wrote {path.relative_to(ROOT)}")
        return 0
    found = stale()
    for path, names in found.items():
        print(f"{path.relative_to(ROOT)}: {len(names)} value(s) differ from the data: {', '.join(names[:8])}"
              + (" ..." if len(names) > 8 else ""))
    if found:
        print("rewrite them: python docs/_ext/pkdocs/inplace.py --write")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
