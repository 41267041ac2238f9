"""studies/reproduce.py --check: every study rerun from scratch writes exactly the tables committed
in figures/ (wall times and provenance excepted), and every committed table is some study's.

It reruns every study at full size, one after another (15 to 30 minutes on two cores, measured),
so it is in the full run only."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}


@pytest.mark.slow
@pytest.mark.timeout(3 * 3600)  # a hang guard: every study, full size
def test_every_committed_table_is_what_a_fresh_run_of_its_study_writes():
    before = {f: f.stat().st_mtime_ns for f in (ROOT / "figures").rglob("*") if f.is_file()}
    p = subprocess.run([sys.executable, str(ROOT / "studies" / "reproduce.py"), "--check", "--no-progress"], cwd=ROOT,
                       env=ENV, capture_output=True, text=True, stdin=subprocess.DEVNULL)
    assert p.returncode == 0, p.stdout[-6000:] + p.stderr[-2000:]
    assert "every table checked is identical" in p.stdout
    assert {f: f.stat().st_mtime_ns for f in (ROOT / "figures").rglob("*") if f.is_file()} == before
