"""The README's generated blocks: ``<!-- pk:NAME -->`` ... ``<!-- /pk -->`` holds the value NAME of
:mod:`pkdocs.facts` (e.g. ``repro.table``), computed from the committed data like the results pages.

    python docs/_ext/pkdocs/readme.py            # exit 1 and list the blocks that differ
    python docs/_ext/pkdocs/readme.py --write    # rewrite them in README.md
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

if __package__ in (None, ""):  # run as a script
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    __package__ = "pkdocs"

from pkdocs import facts  # noqa: E402
from pkdocs.sources import ROOT, Sources  # noqa: E402

BLOCK = re.compile(r"(<!-- pk:(?P<name>[\w.-]+) -->\n)(?P<body>(?:(?!<!-- pk:).)*?)\n?(<!-- /pk -->)", re.S)


def blocks(text: str) -> list[tuple[str, str]]:
    """(name, body) of every generated block."""
    return [(m["name"], m["body"]) for m in BLOCK.finditer(text)]


def render(text: str, src: Sources) -> str:
    return BLOCK.sub(lambda m: m.group(1) + facts.lookup(src, m["name"]) + "\n" + m.group(4), text)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    path = ROOT / "README.md"
    text = path.read_text()
    new = render(text, Sources())
    if "--write" in argv:
        path.write_text(new)
        return 0
    stale = [name for (name, a), (_, b) in zip(blocks(text), blocks(new)) if a != b]
    for name in stale:
        print(f"README.md: the block {name} differs from the data (python docs/_ext/pkdocs/readme.py --write)")
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
