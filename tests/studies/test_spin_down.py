"""studies/spin_down.py --quick: how long an egg and a tippe top spin under the dissipation laws.
The run's outputs hold the closed forms of the laws on a sphere, an energy balance for every run,
an egg that keeps its tilt while it rolls under exact Coulomb friction and rises under the
regularised law, a tippe top that comes to rest where rolling resistance can hold it, and a rerun
that resumes from the stored rows."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[2]
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
OUTPUTS = ("spin_down.csv", "spin_down.json", "spin_down_curves.csv", "spin_down_egg.png", "spin_down_top.png",
           "spin_down_times.png", "spin_down_egg_table.csv", "spin_down_top_table.csv", "spin_down_checks.csv",
           "spin_down_summary.json")


def _run(out: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ROOT / "studies" / "spin_down.py"), "--quick", "--serial", "--no-progress",
                           "--out", str(out)], cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=1200)


#: a hang guard (the quick run takes about a minute, more with empty caches: so the module is in the
#: full run only; the default run checks the egg's rise and the top's rest in tests/friction and
#: tests/core/test_coming_to_rest.py)
pytestmark = [pytest.mark.timeout(1500), pytest.mark.slow]


def _committed() -> dict:
    return {p: p.stat().st_mtime_ns for p in (ROOT / "figures").rglob("spin_down*")}


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("spin_down")
    before = _committed()
    p = _run(out)
    assert p.returncode == 0, p.stderr[-3000:]
    runs = pd.read_csv(out / "spin_down.csv")
    return {"out": out, "runs": runs, "curves": pd.read_csv(out / "spin_down_curves.csv"),
            "summary": json.loads((out / "spin_down_summary.json").read_text()), "committed": (before, _committed()),
            "by": {(r.body, r.case): r for r in runs.itertuples()}}


def test_every_output_is_written_into_the_out_folder_and_none_into_figures(study):
    for name in OUTPUTS:
        assert (study["out"] / name).stat().st_size > 0, name
    before, after = study["committed"]
    assert before == after


def test_the_closed_forms_of_the_laws_on_a_sphere(study):
    """Spin friction stops a sphere spinning in place at C n0 / mu_s, rolling resistance a rolling
    one at 7 v0 / (5 delta), linear air drag spins it down as n0 exp(-k1 t / C): to 1e-8."""
    checks = {c["quantity"]: c for c in study["summary"]["checks"]}
    assert checks["t_rest = C n0 / mu_s"]["closed_form"] == pytest.approx(0.4 * 3 / 0.02)
    assert checks["t_rest = 7 v0 / (5 delta)"]["closed_form"] == pytest.approx(70.0)
    assert checks["n(40) = n0 exp(-k1 t / C)"]["closed_form"] == pytest.approx(3 * math.exp(-1.0))
    for c in checks.values():
        assert c["rel_err"] < 1e-8 and abs(c["energy_residual"]) < 1e-8, c
    assert [c["status"] for c in checks.values()] == ["rest", "rest", "completed"]


def test_every_run_balances_its_energy(study):
    """energy lost = what the laws dissipated + the jumps at events, to 1e-8 of the start's energy,
    and every law takes energy out (never puts it in)."""
    runs = study["runs"]
    assert (np.abs(runs["residual"] / runs["energy_start"]) < 1e-8).all()
    for col in ("diss_sliding", "diss_spin", "diss_rolling", "diss_air"):
        assert (runs[col] >= -1e-12).all(), col
    lost = runs["energy_start"] - runs["energy_end"]
    np.testing.assert_allclose(lost, runs[["diss_sliding", "diss_spin", "diss_rolling", "diss_air"]].sum(axis=1)
                               + runs["at_events"] + runs["residual"], rtol=0, atol=1e-9)


def test_the_egg_rolls_at_constant_tilt_under_exact_coulomb_friction_and_says_why(study):
    r = study["by"][("egg", "exact Coulomb")]
    assert r.status == "completed" and r.t_first_stick_s < 0.01
    assert math.radians(r.theta_range_after_stick_deg) < 1e-6  # pure rolling: theta cannot change
    assert r.note.startswith("pure rolling: energy is conserved")
    curve = study["curves"][study["curves"]["run"] == r.key]
    rolling = curve[curve["t_s"] > r.t_first_stick_s]["energy"]
    assert np.ptp(rolling) < 1e-9 * r.energy_start


def test_the_egg_rises_under_the_regularised_law(study):
    r = study["by"][("egg", "regularised Coulomb eps 1e-3")]
    assert r.t_rise_s > 0 and math.radians(r.theta_end_deg) < 0.5 and r.theta_min_deg < 10.0


def test_spin_friction_stops_the_egg_spinning_without_raising_it(study):
    """Exact Coulomb + spin friction: the egg rolls, its spin about the vertical falls linearly and
    stops near A Omega0 / (mu_s M g) (its moment about the vertical lying on its side), and it
    does not rise: spin friction opposes the spin, not the tilt."""
    estimate = study["summary"]["egg_spin_stop_estimate_s_mm"]
    for mu_s in (0.2, 1.0):
        r = study["by"][("egg", f"spin friction {mu_s} mm")]
        assert r.t_spin_stop_s == pytest.approx(estimate / mu_s, rel=2e-3)
        assert r.diss_spin > 0.9 * (r.energy_start - r.energy_end) and r.theta_min_deg > 80.0
        assert pd.isna(r.t_rise_s)  # theta never fell below 10 deg


def test_a_run_cut_by_its_budget_says_so(study):
    """A run that crawls (rolling resistance on the pivoting egg: its rolling part held near zero by
    the regularised couple, the steps shrink) is cut by its step or wall budget, recorded as failed
    with the reason; rolling resistance lays the egg flatter, it does not raise it."""
    failed = study["runs"][study["runs"]["status"] == "failed"]
    for r in failed.itertuples():
        assert "step limit" in r.reason or "wall" in r.reason, r.reason
        assert study["summary"]["failed"][f"{r.body}: {r.case}"] == r.reason
    r = study["by"][("egg", "rolling resistance 0.2 mm")]
    assert r.theta_end_deg >= r.theta0_deg and pd.isna(r.t_rise_s)


def test_the_tippe_top_inverts_and_rests_where_rolling_resistance_holds_it(study):
    """Spin and rolling friction: the top turns over (theta > 90 deg), its spin about the vertical
    stops, it comes to rest (a time in seconds) with the weight's lever arm alpha sin(theta) <=
    delta, and its energy never rises (to the nudges at events)."""
    for mu_s in (0.2, 1.0):
        r = study["by"][("tippe-top", f"mu_s {mu_s} mm, delta 0.05 mm")]
        assert r.status == "rest" and r.t_over_s < r.t_spin_stop_s < r.t_rest_s <= r.t_end_s
        assert r.t_run_s == pytest.approx(r.t_rest_s)
        assert 0.3 * math.sin(math.radians(r.theta_end_deg)) <= 0.05 / 15 + 1e-9
        energy = study["curves"][study["curves"]["run"] == r.key].sort_values("t_s")["energy"].to_numpy()
        assert np.diff(energy).max() < 1e-6 * energy[0]
        # at rest all the energy is the height of G, h = 1 - alpha cos(theta)
        assert r.energy_end == pytest.approx(1 - 0.3 * math.cos(math.radians(r.theta_end_deg)), abs=1e-12)
    stronger = study["by"][("tippe-top", "mu_s 1.0 mm, delta 0.05 mm")]
    assert stronger.t_rest_s < study["by"][("tippe-top", "mu_s 0.2 mm, delta 0.05 mm")].t_rest_s


def test_without_rolling_resistance_the_top_never_rests(study):
    """Spin friction alone stops the spin about the vertical, then the top rocks on at constant
    energy (rocking is rolling); exact Coulomb alone keeps it spinning inverted."""
    spin = study["by"][("tippe-top", "spin friction 0.2 mm")]
    assert spin.status == "completed" and spin.t_spin_stop_s > 0 and pd.isna(spin.t_rest_s)
    coulomb = study["by"][("tippe-top", "exact Coulomb")]
    assert coulomb.theta_max_deg > 150 and abs(coulomb.spin_end_rev_s) > 10


def test_a_rerun_resumes_from_the_stored_rows(study):
    before = (study["out"] / "spin_down.csv").read_bytes()
    p = _run(study["out"])
    assert p.returncode == 0, p.stderr[-3000:]
    assert (study["out"] / "spin_down.csv").read_bytes() == before
