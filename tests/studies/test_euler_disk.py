"""studies/euler_disk.py and its library: the closed forms of the quasi-static end agree with a
quadrature of the energy balance; a thin disk under Moffatt's air layer ends in a finite-time
singularity with his exponents; rolling resistance ends with the exponents of its own balance;
spin friction and sliding stop taking energy and never end; every run keeps its energy balance;
the quick run writes its outputs into --out and none into figures/."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

from phasekit.studies import euler_disk as ed

import pytest
from scipy import integrate

ROOT = Path(__file__).resolve().parents[2]
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
TH0 = math.pi / 6


@pytest.mark.parametrize("law, coef, power", [
    ("air-layer", 1e-4, lambda th: 1e-4 / (ed.THIN.A * math.sin(th) ** 2)),
    ("rolling-resistance", 0.01, lambda th: 0.01 * math.cos(th) * math.sqrt(math.sin(th) / ed.THIN.A)),
    ("spin-friction", 0.02, lambda th: 0.02 * math.sin(th) ** 1.5 / math.sqrt(ed.THIN.A))])
def test_the_quasi_static_times_are_the_energy_balance_integrated(law, coef, power):
    """t(theta) = int (3/2) cos(theta') dtheta' / P(theta') from theta to theta0, P the power on the
    spin-in-place manifold (Omega^2 = 1/(A sin), w_h = Omega sin cos, w_Z = Omega sin^2)."""
    for th in (0.3, 0.05, 0.001):
        quad, _ = integrate.quad(lambda x: 1.5 * math.cos(x) / power(x), th, TH0, epsrel=1e-12, limit=200)
        assert ed.quasi_static(law, coef, TH0, th) == pytest.approx(quad, rel=1e-9)


@pytest.fixture(scope="module")
def air():
    return ed.disk_report(ed.run_disk("air-layer", 1e-4, 10.0), "air-layer", 1e-4, 10.0, window=(3e-3, 0.3))


def test_the_air_layer_ends_in_moffatts_finite_time_singularity(air):
    assert air["status"] == "stopped" and air["t_face_down"] is not None and air["theta_end"] == pytest.approx(1e-3)
    assert air["decades"] >= 2.0
    for key, p in (("fit_theta", 1 / 3), ("fit_omega", -1 / 6)):
        fit = air[key]
        assert abs(fit["exponent"] - p) <= 0.03 and fit["ci95"] < 0.01 and fit["r2"] > 0.99, key
    # the extrapolated end precedes the face-down time (the disk falls from theta ~ 0.04 at the end) and
    # comes after the quasi-static estimate (the disk drifts off spinning in place, losing less)
    assert air["t0_quasi_static"] < air["t0_fit"] < air["t_face_down"]
    assert air["residual_max"] <= 1e-8 and air["t_first_slip"] is None and air["max_friction_ratio"] < 10.0


def test_rolling_resistance_ends_with_theta_falling_as_the_square_of_t0_minus_t():
    """Over two decades of t0 - t (face down at 1e-6: theta ~ (t0 - t)^2 needs it), within 0.02 of the
    balance's 2 and -1; rolling to the end (mu = 1000), the needed |F|/R is reported, not met."""
    traj = ed.run_disk("rolling-resistance", 0.01, 1000.0, flat_angle=1e-6)
    rep = ed.disk_report(traj, "rolling-resistance", 0.01, 1000.0, window=(1e-3, 0.3))
    assert rep["status"] == "stopped" and rep["theta_end"] == pytest.approx(1e-6, rel=1e-3) and rep["residual_max"] <= 1e-8
    assert rep["decades"] >= 2.0 and rep["t_first_slip"] is None
    for key, p in (("fit_theta", 2.0), ("fit_omega", -1.0)):
        assert abs(rep[key]["exponent"] - p) + rep[key]["ci95"] <= 0.02, key
    assert rep["t0_fit"] == pytest.approx(rep["t0_quasi_static"], rel=0.02) and rep["t0_fit"] > rep["t_face_down"]


@pytest.mark.parametrize("law, coef, mu, spin, event", [("spin-friction", 0.2, 10.0, 0.0, "t_pivot_stick"),
                                                        ("sliding", 0.0, 0.1, 0.5, "t_first_stick")])
def test_spin_friction_and_sliding_stop_taking_energy_and_never_end(law, coef, mu, spin, event):
    traj = ed.run_disk(law, coef, mu, t_end=60.0, spin=spin)
    rep = ed.disk_report(traj, law, coef, mu, window=(0.03, 0.9))
    assert rep["status"] == "completed" and rep["t_face_down"] is None and rep[event] is not None
    assert rep["residual_max"] <= 1e-8 and rep["energy_end"] < rep["energy_start"] - 0.01
    after = traj.sample([rep[event] + 1.0, 60.0])["energy"].to_numpy()
    assert abs(after[1] - after[0]) < 1e-9  # rolling on (the spin about the vertical held, or no slip): no loss


@pytest.mark.timeout(900)
def test_the_quick_run_writes_its_outputs_into_out_and_none_into_figures(tmp_path):
    before = {p: p.stat().st_mtime_ns for p in (ROOT / "figures").rglob("euler_disk*")}
    p = subprocess.run([sys.executable, str(ROOT / "studies" / "euler_disk.py"), "--quick", "--out", str(tmp_path), "--json"],
                       cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=800)
    assert p.returncode == 0, p.stderr[-3000:]
    out = json.loads(p.stdout, parse_constant=lambda c: pytest.fail(f"not strict JSON: {c}"))  # nothing else
    assert json.loads((tmp_path / "euler_disk.json").read_text())["runs"].keys() == out["runs"].keys()
    for name in ("euler_disk.json", "euler_disk_table.csv", "euler_disk_exponents.png"):
        assert (tmp_path / name).stat().st_size > 0
    assert out["max_energy_residual"] <= 1e-8
    assert abs(out["runs"]["air-layer"]["fit_theta"]["exponent"] - 1 / 3) <= 0.03
    assert before == {p: p.stat().st_mtime_ns for p in (ROOT / "figures").rglob("euler_disk*")}
