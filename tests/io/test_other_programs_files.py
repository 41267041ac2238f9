"""Files phasekit did not write (by plain pandas, xarray or pyarrow, or by hand) read by
:func:`phasekit.read_table`: inferred dtypes, the units and attributes the file holds, typed; and
a run's JSON (``simulate --json``, ``Trajectory.to_dict``) repeating the run."""

import json

import phasekit as pk

import numpy as np
import pytest


def test_a_netcdf_file_from_plain_xarray_keeps_its_coordinate_units_and_attributes(tmp_path):
    pytest.importorskip("h5netcdf")
    import xarray as xr

    ds = xr.Dataset({"gap": ("t", [0.0, 0.5, 0.0], {"units": "mm", "long_name": "gap"}),
                     "ok": ("t", np.array(["True", "False", "True"], dtype=object))},
                    coords={"t": ("t", [0.0, 1.0, 2.0], {"units": "ms"})}, attrs={"n": 3, "who": "lab"})
    ds.to_netcdf(tmp_path / "x.nc", engine="h5netcdf")
    df = pk.read_table(tmp_path / "x.nc")
    assert list(df.columns) == ["t", "gap", "ok"] and list(df["t"]) == [0.0, 1.0, 2.0]
    assert str(df["ok"].dtype) == "boolean" and list(df["ok"]) == [True, False, True]
    assert df.attrs == {"n": 3, "who": "lab", "units": {"t": "ms", "gap": "mm"}, "long_names": {"gap": "gap"}}
    assert type(df.attrs["n"]) is int
    # pandas' default index, made a coordinate "index" by xarray, numbers rows only
    xr.Dataset.from_dataframe(df[["gap"]]).to_netcdf(tmp_path / "y.nc", engine="h5netcdf")
    assert list(pk.read_table(tmp_path / "y.nc").columns) == ["gap"]


def test_plain_parquet_and_csv_files_are_read_by_inference(tmp_path):
    import pandas as pd

    pytest.importorskip("pyarrow")
    df = pd.DataFrame({"a": [1.5, None], "flag": ["True", None], "n": [1, 2]})
    df.to_parquet(tmp_path / "x.parquet")
    df.to_csv(tmp_path / "x.csv", index=False)
    for name in ("x.parquet", "x.csv"):
        back = pk.read_table(tmp_path / name)
        assert [str(t) for t in back.dtypes] == ["float64", "boolean", "int64"], name
        assert back["flag"].isna().tolist() == [False, True] and back.attrs == {}, name


def test_a_run_repeats_from_its_json(tmp_path):
    body = pk.Spheroid(1.5)
    run = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0),
                      60.0, stop_at="none", restitution=0.3)
    (tmp_path / "run.json").write_text(json.dumps(run.to_dict()))
    again = pk.rerun(json.loads((tmp_path / "run.json").read_text()))
    assert len(run.flights) > 10 and len(again.flights) == len(run.flights)
    assert [e.t for e in again.events] == [e.t for e in run.events] and again.t_jump == run.t_jump


def test_reading_names_the_path(tmp_path):
    with pytest.raises(pk.ParameterError, match="`path` must be an existing file"):
        pk.read_table(tmp_path / "missing.csv")
    with pytest.raises(pk.ParameterError, match=r"`path` must be a file path ending in \.csv, \.parquet, \.nc"):
        pk.read_table(tmp_path / "x.xlsx")
