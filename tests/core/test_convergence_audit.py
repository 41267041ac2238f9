"""PHASEKIT_AUDIT (phasekit/core/audit.py): every run of a process made at rtol / 10, so that a study
rerun under it shows how far its numbers move (docs/results/robustness.md)."""

import phasekit as pk
from phasekit.core.audit import AUDIT_ENV

import numpy as np
import pytest


@pytest.fixture(scope="module")
def standard():
    body = pk.Spheroid(1.5)
    return pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)


def test_tight_runs_every_simulation_at_a_tenth_of_its_tolerance(standard, monkeypatch):
    model, x0 = standard
    plain = pk.simulate(model, x0, 200.0, rtol=1e-8, dense=False, track_minima=False)
    monkeypatch.setenv(AUDIT_ENV, "tight")
    tight = pk.simulate(model, x0, 200.0, rtol=1e-8, dense=False, track_minima=False)
    [batch] = pk.core.simulate_batch(model, [x0], 200.0, rtol=1e-8, track_minima=False, dense=False)
    assert plain.rtol == 1e-8 and tight.rtol == 1e-9 and batch.rtol == 1e-9
    assert tight.t_jump == pytest.approx(batch.t_jump, abs=1e-9) and tight.t_jump != plain.t_jump


def test_an_unknown_audit_is_named(standard, monkeypatch):
    model, x0 = standard
    monkeypatch.setenv(AUDIT_ENV, "chart")
    with pytest.raises(pk.ParameterError, match="PHASEKIT_AUDIT"):
        pk.simulate(model, x0, 1.0)
