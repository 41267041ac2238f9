"""Tables written and read back in every format (CSV, Parquet, NetCDF) by :func:`phasekit.read_table`:
a run with flights (in phasekit's units and in real ones) and a study table in real units come
back with identical values and dtypes, every column's unit and the inputs that repeat them (a
rerun gives the same numbers); plain xarray shows each variable's units; the CSV's sidecar."""

import csv
import json
import math
import warnings
from pathlib import Path

import phasekit as pk
from phasekit.core.trajectory_files import write_run_table
from phasekit.core.trajectory_io import LONG_NAMES, UNITS, run_table

import numpy as np
import pytest

pytest.importorskip("pyarrow")
pytest.importorskip("xarray")
pytest.importorskip("h5netcdf")

ROOT = Path(__file__).resolve().parents[2]
FORMATS = (".csv", ".parquet", ".nc")
SCALE = "21.5 mm"


@pytest.fixture(scope="module")
def run():
    """A prolate spheroid past its jump, on to t = 60 with impacts: many flights."""
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    r = pk.simulate(model, pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 60.0, stop_at="none",
                    restitution=0.3)
    assert len(r.flights) > 10
    return r


@pytest.fixture(scope="module")
def study():
    """An ensemble's table (one row per start, its inputs in attrs) in real units."""
    body = pk.Spheroid(1.5)
    starts = [pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=w) for w in (10.5, 12.0, 5.0)]
    df = pk.ensemble(pk.Model(body, pk.Coulomb(0.1)), starts, 200.0, processes=1, progress=False)
    return pk.Scale(SCALE).table(df)


def _write_run(run, path, ts):
    """The run's own writers where it has them (to_netcdf, to_parquet), else the table with its inputs."""
    if path.suffix == ".nc":
        return run.to_netcdf(path, ts)
    if path.suffix == ".parquet":
        return run.to_parquet(path, ts)
    return write_run_table(run, path, ts)


def _identical(back, df) -> None:
    """Same columns, dtypes and values bit for bit (-0.0 is not 0.0; NaN where NaN was)."""
    import pandas as pd

    pd.testing.assert_frame_equal(back, df, check_exact=True)
    for c in df.columns:
        if df[c].dtype.kind == "f":
            assert np.array_equal(back[c].to_numpy().view("u8"), df[c].to_numpy().view("u8")), c


@pytest.mark.parametrize("suffix", FORMATS)
def test_a_run_with_flights_comes_back_whole_and_reruns(run, suffix, tmp_path):
    ts = np.linspace(0.0, run.t, 401)
    back = pk.read_table(_write_run(run, tmp_path / f"run{suffix}", ts))
    _identical(back, run.sample(ts))
    assert back.attrs["units"] == {c: UNITS[c] for c in back.columns}
    assert back.attrs["long_names"] == {c: LONG_NAMES[c] for c in back.columns}
    # typed: numbers as numbers, text as plain text
    assert back.attrs["status"] == "completed" and back.attrs["stop_at"] == "none"
    assert type(back.attrs["n_flights"]) is int and back.attrs["n_flights"] == len(run.flights)
    assert type(back.attrs["t_jump"]) is float and back.attrs["t_jump"] == run.t_jump
    assert back.attrs["restitution"] == 0.3 and back.attrs["model"] == run.model.to_dict()
    assert len(back.attrs["events"]) == len(run.events)
    again = pk.rerun(back.attrs["run"])
    assert again.t_jump == run.t_jump and len(again.flights) == len(run.flights)
    _identical(again.sample(back["t"].to_numpy()), back)


@pytest.mark.parametrize("suffix", FORMATS)
def test_a_run_in_real_units_keeps_its_units_and_reruns(run, suffix, tmp_path):
    sc = pk.Scale(SCALE)
    ts = np.linspace(0.0, run.t, 201)
    real = sc.table(run_table(run, ts))
    back = pk.read_table(pk.write_table(real, tmp_path / f"real{suffix}"))
    _identical(back, real)
    assert back.attrs["units"] == real.attrs["units"]
    assert back.attrs["units"]["t"] == "ms" and back.attrs["units"]["Omega"] == "rev/s"
    assert back.attrs["units"]["gap"] == "mm" and back.attrs["units"]["theta"] == "rad"
    _identical(sc.table(pk.rerun(back.attrs["run"]).sample(ts)), back)


@pytest.mark.parametrize("suffix", FORMATS)
def test_a_study_table_in_real_units_comes_back_whole_and_reruns(study, suffix, tmp_path):
    back = pk.read_table(pk.write_table(study, tmp_path / f"study{suffix}"))
    _identical(back, study)
    assert back.attrs["units"] == study.attrs["units"] and back.attrs["units"]["Omega"] == "rev/s"
    assert back.attrs["units"]["t_jump"] == "ms" and back.attrs["units"]["R_min"] == "M g"
    assert back.attrs["inputs"] == study.attrs["inputs"] and back.attrs["wall_s"] == study.attrs["wall_s"]
    sc = pk.Scale(SCALE)
    for k in range(len(study)):
        again = pk.rerun(back, k)
        assert again.status.value == back["status"][k]
        t_jump = back["t_jump"][k]  # in ms: the rerun's own t_jump converted the same way
        assert (again.t_jump is None and math.isnan(t_jump)) or sc.to_real(again.t_jump, "time").magnitude == pytest.approx(t_jump, rel=1e-15)


def test_plain_xarray_shows_units_on_every_variable_and_no_dummy_dimension(run, study, tmp_path):
    import xarray as xr

    run.to_netcdf(tmp_path / "run.nc", np.linspace(0.0, run.t, 11))
    pk.write_table(study, tmp_path / "study.nc")
    with xr.open_dataset(tmp_path / "run.nc") as ds:
        assert dict(ds.sizes) == {"t": 11} and list(ds.coords) == ["t"]
        assert {v: ds[v].attrs["units"] for v in ds.variables} == {v: UNITS[v] for v in ds.variables}
        assert all(ds[v].attrs["long_name"] == LONG_NAMES[v] for v in ds.variables)
    with xr.open_dataset(tmp_path / "study.nc") as ds:
        assert dict(ds.sizes) == {"row": len(study)} and "index" not in ds.variables and not ds.coords
        assert {v: ds[v].attrs["units"] for v in ds.variables} == study.attrs["units"]
        assert ds.attrs["wall_s"] == study.attrs["wall_s"]  # a number, not JSON in a string
        assert json.loads(ds.attrs["phasekit_json"])["attrs"]["inputs"] == study.attrs["inputs"]


def test_a_csv_is_plain_and_its_sidecar_says_the_rest(study, tmp_path):
    import pandas as pd

    path = pk.write_table(study, tmp_path / "study.csv")
    side = json.loads((tmp_path / "study.csv.json").read_text())
    assert side["phasekit_table"] == 1 and side["csv"] == "study.csv"
    assert [c["name"] for c in side["columns"]] == list(study.columns)
    assert {c["name"]: c["units"] for c in side["columns"]} == study.attrs["units"]
    assert side["attrs"]["inputs"] == study.attrs["inputs"]
    plain = pd.read_csv(path)  # any CSV reader gets the numbers
    np.testing.assert_array_equal(plain["Omega"].to_numpy(), study["Omega"].to_numpy())
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.csv", "study.csv.json"]  # no temporary files
    # a CSV changed after its sidecar was written: the sidecar no longer applies, and says so
    path.write_text(path.read_text().replace("jumped", "stopped"))
    with pytest.warns(UserWarning, match="study.csv.json does not describe study.csv"):
        back = pk.read_table(path)
    assert "units" not in back.attrs and list(back["status"]) == ["stopped", "stopped", "completed"]


def test_a_failed_write_leaves_the_old_csv_and_sidecar(study, tmp_path, monkeypatch):
    from phasekit.io import csvfile

    path = pk.write_table(study, tmp_path / "study.csv")
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}

    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(csvfile, "dumps", broken)  # fails after the new CSV is written, before the sidecar
    with pytest.raises(OSError, match="disk full"):
        pk.write_table(study.head(1), path)
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


def _cells_agree(a: str, b: str) -> bool:
    if a == b:
        return True
    try:
        return float(a) == float(b)
    except ValueError:
        return False


@pytest.mark.parametrize("path", sorted((ROOT / "figures").glob("*.csv")), ids=lambda p: p.name)
def test_committed_study_tables_rewrite_to_the_same_cells(path, tmp_path):
    """A committed study table read and written again: the same table back from every format,
    and a CSV with the same cells (empty where missing, True/False, the same numbers)."""
    df = pk.read_table(path)
    for suffix in FORMATS:
        out = pk.write_table(df, tmp_path / f"t{suffix}")
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            _identical(pk.read_table(out), df)
    with open(path, newline="") as fa, open(tmp_path / "t.csv", newline="") as fb:
        old, new = list(csv.reader(fa)), list(csv.reader(fb))
    assert old[0] == new[0] and len(old) == len(new)
    for ra, rb in zip(old[1:], new[1:]):
        assert len(ra) == len(rb) and all(_cells_agree(x, y) for x, y in zip(ra, rb)), (ra, rb)
