"""Progress bars where a person waits (``progress``), and only there."""

import importlib

import phasekit as pk
from phasekit._runtime.watch import show_progress

import pytest


def test_progress_is_shown_where_asked_and_only_there(capsys, prolate):
    assert show_progress(None) is False  # pytest captures stderr: not a terminal, not a notebook
    assert show_progress(True) is True and show_progress(False) is False
    with pytest.raises(pk.ParameterError, match="`progress`"):
        show_progress("yes")
    defn = pk.Definition("sliding", "sliding")
    pk.find_threshold(defn, prolate, guess=9.74, window=1.01, n_coarse=2, tol=5e-3, progress=True)
    err = capsys.readouterr().err
    assert "threshold a=1.5" in err and "run" in err
    pk.find_threshold(defn, prolate, guess=9.74, window=1.01, n_coarse=2, tol=5e-3)
    assert capsys.readouterr().err == ""


def test_a_single_long_run_shows_its_progress(capsys, monkeypatch, prolate, standard_start):
    monkeypatch.setattr(importlib.import_module("phasekit.core.simulate"), "PROGRESS_DELAY", 0.0)
    pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), standard_start, 40.0, progress=True)
    assert "simulate" in capsys.readouterr().err
    pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), standard_start, 40.0)
    assert capsys.readouterr().err == ""
