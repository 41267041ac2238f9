"""Ensembles (``pk.ensemble``) equal their single runs row by row, locally and on a Dask client,
take tables of starts and report failures; ``pk.rerun`` repeats a run from its JSON or an
ensemble's row."""

import json

import phasekit as pk
from phasekit import ParameterError

import numpy as np
import pytest


@pytest.fixture(scope="module")
def model(prolate):
    return pk.Model(prolate, pk.Coulomb(0.1))


@pytest.fixture(scope="module")
def ten_starts(prolate):
    return [pk.gyroscopic_start(prolate, np.pi / 2 - 0.01, omega0=w) for w in np.linspace(9.0, 14.0, 10)]


def test_ensemble_equals_single_runs_row_by_row(model, ten_starts):
    ev = pk.Event("theta", 1.0, direction=-1, terminal=False, name="theta1")
    df = pk.ensemble(model, ten_starts, 200.0, events=[ev], processes=2, progress=False)
    assert list(df["i"]) == list(range(10))
    for i, x0 in enumerate(ten_starts):
        tr = pk.simulate(model, x0, 200.0, events=[ev])
        row = df.iloc[i]
        assert row["status"] == tr.status.value and row["stuck"] == tr.stuck and row["n_events"] == len(tr.events)
        assert row["t_end"] == tr.t and row["R_min"] == tr.R_min and row["n_steps"] == tr.n_steps
        assert (np.isnan(row["t_jump"]) if tr.t_jump is None else row["t_jump"] == tr.t_jump)
        first = tr.events_named("theta1")
        assert row["t_theta1"] == first[0].t if first else np.isnan(row["t_theta1"])
        np.testing.assert_array_equal(row[list(pk.core.PAPER_NAMES)].to_numpy(float), x0)
    assert set(df["status"]) == {"jumped", "completed"}  # both outcomes occur in this range


def test_ensemble_takes_a_table_of_starts_and_reports_failures(model, ten_starts):
    import pandas as pd

    table = pd.DataFrame(ten_starts[:3], columns=list(pk.core.PAPER_NAMES))
    df = pk.ensemble(model, table, 200.0, processes=1, progress=False, max_steps=50)
    assert list(df["status"]) == ["failed"] * 3 and all("step limit" in r for r in df["reason"])
    with pytest.raises(ParameterError, match="`starts`"):
        pk.ensemble(model, [[1.0, 2.0]], 10.0, progress=False)
    with pytest.raises(ParameterError, match="`t_eval`"):
        pk.ensemble(model, ten_starts[:1], 10.0, t_eval=[1.0], progress=False)
    with pytest.raises(ParameterError, match="`rtoll`"):
        pk.ensemble(model, ten_starts[:1], 10.0, rtoll=1e-9, progress=False)


def test_rerun_reproduces_a_result_from_its_json_and_an_ensemble_row(model, ten_starts):
    tr = pk.simulate(model, ten_starts[5], 200.0, events=[pk.Event("theta", 1.2, terminal=False)], rtol=1e-10)
    d = json.loads(json.dumps(tr.to_dict()))  # what the CLI prints, read back
    again = pk.rerun(d)
    assert again.t_jump == tr.t_jump and again.options == tr.options and len(again.events) == len(tr.events)
    df = pk.ensemble(model, ten_starts[4:7], 200.0, processes=1, progress=False)
    assert pk.rerun(df, 2).t_jump == df["t_jump"].iloc[2]
    with pytest.raises(ParameterError, match="`index`"):
        pk.rerun(df)
    # one row, taken out of a filtered table: its position there is not its start's
    row = df.iloc[1:].iloc[1]
    again = pk.rerun(row)
    assert row["i"] == 2 and again.t_jump == df["t_jump"].iloc[2] and again.R_min == df["R_min"].iloc[2]
    with pytest.raises(ParameterError, match="`source`"):
        pk.rerun(df.iloc[2].drop("i"))


def test_ensemble_on_a_dask_client_equals_the_local_run(model, ten_starts):
    from dask.distributed import Client

    with Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=None) as client:
        on_dask = pk.ensemble(model, ten_starts[:4], 200.0, scheduler=client, progress=False)
    here = pk.ensemble(model, ten_starts[:4], 200.0, processes=1, progress=False)
    cols = [c for c in here.columns if c != "wall_s"]
    assert on_dask[cols].equals(here[cols])
    with pytest.raises(ParameterError, match="`scheduler`"):
        pk.ensemble(model, ten_starts[:1], 10.0, scheduler=3.0, progress=False)


def test_rerun_takes_a_new_end_and_names_a_wrong_keyword(model, ten_starts):
    """`pk.rerun(d, t_end=...)` ends the same run earlier (the state there is the first run's, read
    from its dense output); a keyword simulate does not take is named, not a TypeError."""
    full = pk.simulate(model, ten_starts[0], 20.0, dense=True)
    short = pk.rerun(full.to_dict(), t_end=7.5)
    assert short.t_end == 7.5 and short.status == "completed"
    assert np.allclose(short.x, full.states([7.5])[0], rtol=1e-7, atol=1e-9)
    with pytest.raises(ParameterError, match=r"^`t_ende` is not a keyword of phasekit.simulate"):
        pk.rerun(full.to_dict(), t_ende=7.5)
