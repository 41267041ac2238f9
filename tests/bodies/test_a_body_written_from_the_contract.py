"""A new body written from the Body docstring alone (the guide's example, docs/guide.md "A body
class of your own"): it declares only the numbered items it must (moments, shape, height), takes
every other capability's default, and runs through simulate, steady_structure and animate."""

import re
import subprocess
import sys
from pathlib import Path

import phasekit as pk

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _guide_block() -> str:
    text = (ROOT / "docs" / "guide.md").read_text()
    section = text.split("### A body class of your own", 1)[1]
    return re.search(r"^```python\n(.*?)^```", section, flags=re.S | re.M).group(1)


def test_the_body_contract_lists_what_a_subclass_gives_and_has_defaults():
    doc = pk.bodies.Body.__doc__
    assert all(f"\n    {k}. " in doc for k in range(1, 8))
    body = pk.Spheroid(1.5)
    assert (body.theta_range, body.limits, body.transfers, body.in_range(0.3)) == (None, (), (), True)
    z, r = body.outline(9)
    assert z.shape == r.shape == (9,) and r[0] == pytest.approx(0.0, abs=1e-15)


@pytest.mark.timeout(600)
def test_the_guides_new_body_runs_through_simulate_the_structure_and_a_movie():
    p = subprocess.run([sys.executable, "-c", _guide_block()], capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert p.returncode == 0, p.stderr[-2000:]
    assert p.stdout.split() == ["completed", "pole0-static", "|", "inf-polePi", "8"]
