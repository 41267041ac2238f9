"""Where the results pages read their numbers: the committed study outputs in ``figures/``
(CSV tables with their JSON manifests) and the measured reports in ``docs/data/`` (fuzz counts,
benchmarks). No Sphinx here, so that a test can render a page's numbers from a copy."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pandas as pd

DOCS = Path(__file__).resolve().parents[2]
ROOT = DOCS.parent


class MissingData(LookupError):
    """A file a results page needs is not there."""


class Sources:
    """The data files of one docs build. Every file read is recorded in ``read`` (Sphinx
    rebuilds a page when one of its files changes)."""

    def __init__(self, figures: str | Path | None = None, data: str | Path | None = None):
        self.figures = Path(figures) if figures else ROOT / "figures"
        self.data = Path(data) if data else DOCS / "data"
        self.read: set[Path] = set()
        self._cache: dict = {}

    def _path(self, base: Path, name: str) -> Path:
        p = base / name
        if not p.is_file():
            raise MissingData(f"{p} is missing (written by the study or report named in the page)")
        self.read.add(p)
        return p

    def csv(self, name: str) -> pd.DataFrame:
        key = ("csv", name)
        if key not in self._cache:
            self._cache[key] = pd.read_csv(self._path(self.figures, name))
        return self._cache[key].copy()

    def cells(self, name: str) -> list[list[str]]:
        """The rows of a CSV table in figures/ as written (the text of each cell, not parsed)."""
        key = ("cells", name)
        if key not in self._cache:
            with self._path(self.figures, name).open(newline="") as f:
                self._cache[key] = list(csv.reader(f))
        return [list(r) for r in self._cache[key]]

    def json(self, name: str) -> dict:
        key = ("json", name)
        if key not in self._cache:
            self._cache[key] = json.loads(self._path(self.figures, name).read_text())
        return self._cache[key]

    def report(self, name: str) -> dict:
        """A measured report in docs/data/ (fuzz counts, benchmarks)."""
        key = ("report", name)
        if key not in self._cache:
            self._cache[key] = json.loads(self._path(self.data, name).read_text())
        return self._cache[key]

    def memo(self, key, fn):
        if key not in self._cache:
            self._cache[key] = fn()
        return self._cache[key]
