"""A trajectory through xarray, NetCDF and Parquet: the sampled table with the inputs that repeat
the run."""

import json

import phasekit as pk

import numpy as np
import pytest


@pytest.fixture(scope="module")
def run():
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    return pk.simulate(model, pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 60.0, stop_at="none",
                       restitution=0.3, pose0=dict(psi=0.2, X=1.0))


def test_to_xarray_round_trips_through_netcdf_with_attributes(run, tmp_path):
    pytest.importorskip("xarray")
    pytest.importorskip("h5netcdf")
    import xarray as xr

    ts = np.linspace(0.0, run.t, 301)
    ds = run.to_xarray(ts)
    df = run.sample(ts)
    assert set(ds.data_vars) == set(df.columns) - {"t"}
    np.testing.assert_array_equal(ds["t"].values, ts)
    np.testing.assert_array_equal(ds["psi"].values, df["psi"].to_numpy())
    run.to_netcdf(tmp_path / "r.nc", ts)
    with xr.open_dataset(tmp_path / "r.nc") as back:
        for name in ds.data_vars:
            np.testing.assert_array_equal(back[name].values, ds[name].values)
        assert back.attrs == ds.attrs
        assert json.loads(back.attrs["pose0"]) == {"psi": 0.2, "phi": 0.0, "X": 1.0, "Y": 0.0}
        assert json.loads(back.attrs["model"])["a"] == 1.5
        again = pk.rerun(json.loads(back.attrs["run"]))  # the attributes are enough to repeat the run
    assert again.t == run.t and [e.t for e in again.events] == [e.t for e in run.events]


def test_parquet_keeps_the_table_and_the_inputs(run, tmp_path):
    import pandas as pd

    pytest.importorskip("pyarrow")
    import pyarrow.parquet as pq

    ts = np.linspace(0.0, run.t, 101)
    run.to_parquet(tmp_path / "r.parquet", ts)
    back = pd.read_parquet(tmp_path / "r.parquet")
    pd.testing.assert_frame_equal(back, run.sample(ts), check_dtype=False)
    meta = json.loads(pq.read_schema(tmp_path / "r.parquet").metadata[b"phasekit"])
    assert json.loads(meta["status"]) == "completed"
    assert json.loads(meta["model"])["a"] == 1.5 and json.loads(meta["pose0"])["X"] == 1.0
    again = pk.rerun(json.loads(meta["run"]))  # the metadata are enough to repeat the run
    assert again.t == run.t and [e.t for e in again.events] == [e.t for e in run.events]
