"""Each column's unit where plain pandas, pyarrow and xarray see it: a Parquet field's metadata
(``units``), the DataFrame's ``attrs`` pandas keeps in the file (``PANDAS_ATTRS``: pandas 2.1 and
later), a NetCDF variable's ``units``; and a run's table written in real units on request
(``scale=``), each column's unit named, the values checked against the Scale by hand."""

from __future__ import annotations

import json
import math

import phasekit as pk
from phasekit.core.trajectory_io import LONG_NAMES, UNITS

import numpy as np
import pandas as pd
import pytest

pq = pytest.importorskip("pyarrow.parquet")

B_MM, G = 21.5, 9.81  # the scale, by hand: sqrt(b/g) in ms
TIME_UNIT_MS = math.sqrt(B_MM * 1e-3 / G) * 1e3
RATE_UNIT_REV_S = math.sqrt(G / (B_MM * 1e-3)) / (2 * math.pi)
SPEED_UNIT_M_S = math.sqrt(G * B_MM * 1e-3)


def _pandas_keeps_attrs() -> bool:
    major, minor = (int(v) for v in pd.__version__.split(".")[:2])
    return (major, minor) >= (2, 1)


@pytest.fixture(scope="module")
def run():
    body = pk.Spheroid(1.5)
    return pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 20.0)


@pytest.fixture(scope="module")
def times(run):
    return np.linspace(0.0, run.t, 41)


def test_the_installed_pandas_round_trips_attrs_through_parquet(tmp_path):
    df = pd.DataFrame({"t": [0.0, 1.0]})
    df.attrs = {"units": {"t": "ms"}}
    df.to_parquet(tmp_path / "p.parquet")
    assert _pandas_keeps_attrs()
    assert pd.read_parquet(tmp_path / "p.parquet").attrs == {"units": {"t": "ms"}}
    # and phasekit reads what pandas wrote: its attrs, units included
    assert pk.read_table(tmp_path / "p.parquet").attrs["units"] == {"t": "ms"}


def test_write_table_units_seen_by_plain_pandas_and_pyarrow(tmp_path):
    df = pd.DataFrame({"t": [0.0, 12.5], "theta": [0.1, 0.2], "ok": [True, False]})
    df.attrs = {"units": {"t": "ms", "theta": "rad"}, "long_names": {"t": "time"}, "status": "jumped"}
    path = pk.write_table(df, tmp_path / "t.parquet")
    back = pd.read_parquet(path)  # plain pandas, no phasekit
    pd.testing.assert_frame_equal(back, df)
    assert back.attrs == {"status": "jumped", "units": {"t": "ms", "theta": "rad"}, "long_names": {"t": "time"}}
    schema = pq.read_schema(path)  # plain pyarrow
    assert schema.field("t").metadata == {b"units": b"ms", b"long_name": b"time"}
    assert schema.field("theta").metadata == {b"units": b"rad"}
    assert not schema.field("ok").metadata
    assert pk.read_table(path).attrs == back.attrs  # phasekit's reader gives the same


def test_a_run_in_phasekit_units_names_them_for_pandas_and_pyarrow(run, times, tmp_path):
    path = run.to_parquet(tmp_path / "r.parquet", times)
    back = pd.read_parquet(path)
    assert back.attrs["units"] == {c: UNITS[c] for c in back.columns}
    assert back.attrs["units"]["t"] == "sqrt(b/g)" and back.attrs["units"]["Omega"] == "sqrt(g/b)"
    assert back.attrs["long_names"] == {c: LONG_NAMES[c] for c in back.columns}
    assert back.attrs["run"]["model"] == run.to_dict()["model"]  # the inputs too
    fields = {f.name: f.metadata[b"units"].decode() for f in pq.read_schema(path)}
    assert fields == back.attrs["units"]


def test_a_run_in_real_units_on_request(run, times, tmp_path):
    sc = pk.Scale(f"{B_MM} mm")
    plain = run.sample(times)
    path = run.to_parquet(tmp_path / "real.parquet", times, scale=sc)
    back = pd.read_parquet(path)
    units = back.attrs["units"]
    assert units["t"] == "ms" and units["Omega"] == units["n"] == "rev/s" and units["U"] == "m/s"
    assert units["h"] == units["X"] == "mm" and units["theta"] == "rad" and units["mode"] == ""
    assert units["R"] == "M g" and units["energy"] == "M g b"  # no mass given: these stay in phasekit's units
    assert back.attrs["scale"] == {"b": "21.5 mm", "g": "9.81 m/s²", "mass": None}
    np.testing.assert_allclose(back["t"], plain["t"] * TIME_UNIT_MS, rtol=1e-12)  # t_ms = t sqrt(b/g) 1000
    np.testing.assert_allclose(back["Omega"], plain["Omega"] * RATE_UNIT_REV_S, rtol=1e-12)
    np.testing.assert_allclose(back["U"], plain["U"] * SPEED_UNIT_M_S, rtol=1e-12)
    np.testing.assert_allclose(back["h"], plain["h"] * B_MM, rtol=1e-12)
    np.testing.assert_array_equal(back["theta"], plain["theta"])
    schema = pq.read_schema(path)
    assert {f.name: f.metadata[b"units"].decode() for f in schema} == units
    assert schema.field("t").metadata[b"units"] == b"ms"
    # the run is still repeatable: its inputs stay in phasekit's units
    meta = json.loads(schema.metadata[b"phasekit"])["attrs"]
    assert meta["run"] == back.attrs["run"] and pk.rerun(back.attrs["run"]).t == run.t
    again = pk.read_table(path)
    assert again.attrs["units"] == units
    pd.testing.assert_frame_equal(again, back)


def test_real_units_with_a_mass_name_forces_and_energies(run, times, tmp_path):
    sc = pk.Scale(f"{B_MM} mm", mass="57 g")
    back = pd.read_parquet(run.to_parquet(tmp_path / "m.parquet", times, scale=sc))
    assert back.attrs["units"]["R"] == "N" and back.attrs["units"]["energy"] == "mJ"
    np.testing.assert_allclose(back["R"], run.sample(times)["R"] * 0.057 * G, rtol=1e-12)


def test_netcdf_in_real_units_seen_by_plain_xarray(run, times, tmp_path):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("h5netcdf")
    sc = pk.Scale(f"{B_MM} mm")
    path = run.to_netcdf(tmp_path / "real.nc", times, scale=sc)
    plain = run.sample(times)
    with xr.open_dataset(path) as ds:  # plain xarray: "ms" stays a float column with its unit
        assert ds["t"].dtype == np.float64 and ds["t"].attrs["units"] == "ms"
        assert ds["Omega"].attrs["units"] == "rev/s" and ds["theta"].attrs["units"] == "rad"
        np.testing.assert_allclose(ds["t"].values, plain["t"] * TIME_UNIT_MS, rtol=1e-12)
    assert pk.read_table(path).attrs["units"]["t"] == "ms"
    with xr.open_dataset(run.to_netcdf(tmp_path / "b.nc", times)) as ds:
        assert ds["t"].attrs["units"] == "sqrt(b/g)"


def test_csv_in_real_units_and_a_bad_scale_is_named(run, times, tmp_path):
    path = run.to_csv(tmp_path / "real.csv", times, scale=pk.Scale(f"{B_MM} mm"))
    assert pk.read_table(path).attrs["units"]["t"] == "ms"
    with pytest.raises(pk.ParameterError, match="`scale`"):
        run.to_parquet(tmp_path / "x.parquet", times, scale="21.5 mm")
    assert not (tmp_path / "x.parquet").exists()
