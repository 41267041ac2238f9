"""Study tables shown whole on the results pages (``csv.STEM``: ``figures/STEM.csv`` as a Markdown
table, every cell as the study wrote it), for pkdocs.facts."""

from __future__ import annotations

from .fmt import table
from .registry import group
from .sources import Sources

#: the tables of figures/ that a page shows whole (docs/results/dissipation.md, euler_disk.md)
WHOLE = ("spin_down_checks", "spin_down_egg_table", "spin_down_top_table", "euler_disk_table")


@group("csv")
def whole_tables(src: Sources) -> dict:
    out = {}
    for stem in WHOLE:
        header, *rows = src.cells(f"{stem}.csv")
        out[stem] = table(header, rows)
    return out
