"""A trajectory through xarray, NetCDF and Parquet: the sampled table, each column's unit and long
name, and the inputs that repeat the run, readable by plain xarray and pyarrow as well."""

import json

import phasekit as pk
from phasekit.core.trajectory_io import LONG_NAMES, UNITS

import numpy as np
import pytest


@pytest.fixture(scope="module")
def run():
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    return pk.simulate(model, pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 60.0, stop_at="none",
                       restitution=0.3, pose0=dict(psi=0.2, X=1.0))


def test_a_sample_names_the_unit_and_meaning_of_every_column(run):
    df = run.sample(np.linspace(0.0, run.t, 5))
    assert df.attrs["units"] == {c: UNITS[c] for c in df.columns}
    assert df.attrs["long_names"] == {c: LONG_NAMES[c] for c in df.columns}
    assert df.attrs["units"]["t"] == "sqrt(b/g)" and df.attrs["units"]["theta"] == "rad"
    assert df.attrs["units"]["R"] == "M g" and df.attrs["units"]["gap"] == "b"
    pose = run.pose([0.0, run.t])
    assert pose.attrs["units"] == {c: UNITS[c] for c in pose.columns}
    # in real units the Scale's units replace phasekit's; what each column is stays
    real = pk.Scale("21.5 mm").table(df)
    assert real.attrs["units"]["t"] == "ms" and real.attrs["units"]["gap"] == "mm"
    assert real.attrs["long_names"] == df.attrs["long_names"]


def test_to_xarray_round_trips_through_netcdf_with_typed_attributes(run, tmp_path):
    pytest.importorskip("xarray")
    pytest.importorskip("h5netcdf")
    import xarray as xr

    ts = np.linspace(0.0, run.t, 301)
    ds = run.to_xarray(ts)
    df = run.sample(ts)
    assert set(ds.data_vars) == set(df.columns) - {"t"} and list(ds.dims) == ["t"]
    np.testing.assert_array_equal(ds["t"].values, ts)
    np.testing.assert_array_equal(ds["psi"].values, df["psi"].to_numpy())
    run.to_netcdf(tmp_path / "r.nc", ts)
    with xr.open_dataset(tmp_path / "r.nc") as back:  # plain xarray, no phasekit
        for name in ds.variables:
            np.testing.assert_array_equal(back[name].values, ds[name].values)
            assert back[name].attrs["units"] == UNITS[name] and back[name].attrs["long_name"] == LONG_NAMES[name]
        # numbers as numbers, text as text (not JSON inside strings)
        assert back.attrs["status"] == "completed" and back.attrs["stop_at"] == "none"
        assert back.attrs["restitution"] == 0.3 and back.attrs["n_flights"] == len(run.flights) > 1
        assert back.attrs["t_jump"] == run.t_jump
        nested = json.loads(back.attrs["phasekit_json"])["attrs"]  # the one JSON attribute
        assert nested["pose0"] == {"psi": 0.2, "phi": 0.0, "X": 1.0, "Y": 0.0} and nested["model"]["a"] == 1.5
        again = pk.rerun(nested["run"])  # the attributes are enough to repeat the run
    assert again.t == run.t and [e.t for e in again.events] == [e.t for e in run.events]


def test_parquet_keeps_the_table_its_units_and_the_inputs(run, tmp_path):
    import pandas as pd

    pytest.importorskip("pyarrow")
    import pyarrow.parquet as pq

    ts = np.linspace(0.0, run.t, 101)
    run.to_parquet(tmp_path / "r.parquet", ts)
    back = pd.read_parquet(tmp_path / "r.parquet")  # plain pandas
    pd.testing.assert_frame_equal(back, run.sample(ts), check_exact=True)
    schema = pq.read_schema(tmp_path / "r.parquet")
    assert {f.name: f.metadata[b"units"].decode() for f in schema} == {c: UNITS[c] for c in back.columns}
    meta = json.loads(schema.metadata[b"phasekit"])["attrs"]
    assert meta["status"] == "completed" and meta["model"]["a"] == 1.5 and meta["pose0"]["X"] == 1.0
    again = pk.rerun(meta["run"])  # the metadata are enough to repeat the run
    assert again.t == run.t and [e.t for e in again.events] == [e.t for e in run.events]


def test_export_paths_and_sample_counts_are_checked(run, tmp_path):
    pytest.importorskip("pyarrow")
    with pytest.raises(pk.ParameterError, match="`path` must be a file path ending in .nc"):
        run.to_netcdf(tmp_path / "r.parquet")
    with pytest.raises(pk.ParameterError, match="`path` must be a file path ending in .parquet"):
        run.to_parquet(tmp_path / "r.csv")
    with pytest.raises(pk.ParameterError, match="`n`"):
        run.to_parquet(tmp_path / "r.parquet", n=1)
    assert not list(tmp_path.iterdir())


def test_a_run_written_to_csv_reads_back_with_its_units_and_reruns(tmp_path):
    body = pk.Spheroid(1.5)
    run = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.5, omega0=10.5), 5.0)
    path = run.to_csv(tmp_path / "run.csv", n=21)
    assert (tmp_path / "run.csv.json").exists()
    back = pk.read_table(path)
    assert back.attrs["units"]["t"] == "sqrt(b/g)" and back.attrs["units"]["R"] == "M g"
    again = pk.rerun(back.attrs["run"])
    np.testing.assert_array_equal(again.sample(back["t"].to_numpy())["theta"].to_numpy(), back["theta"].to_numpy())
