"""The study tables (figures/*.csv): read with honest dtypes, written as Parquet and NetCDF (that
their cells are what the code produces is studies/reproduce.py --check's, run by the slow tests)."""

from pathlib import Path

import phasekit as pk

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def _mixed(series) -> bool:
    """A text column some of whose cells are numbers: numbers stored as text."""
    import pandas as pd

    vals = series.dropna().astype(str)
    nums = pd.to_numeric(vals, errors="coerce").notna()
    return bool(nums.any() and not nums.all())


@pytest.mark.parametrize("path", sorted((ROOT / "figures").glob("*.csv")), ids=lambda p: p.name)
def test_study_tables_load_with_honest_dtypes(path):
    import pandas as pd

    df = pk.read_table(path)
    for col in df.columns:
        c = df[col]
        assert not _mixed(c), (path.name, col)
        if pd.api.types.is_numeric_dtype(c) or pd.api.types.is_bool_dtype(c):
            continue
        assert not set(c.dropna().astype(str)) <= {"True", "False"} or c.dropna().empty, (path.name, col)
    if "eps" in df.columns:
        assert pd.api.types.is_float_dtype(df["eps"]) or path.name == "work_precision.csv"
    if "check_above_jumped" in df.columns:
        assert str(df["check_above_jumped"].dtype) == "boolean"


def test_study_tables_write_as_parquet_and_netcdf(tmp_path):
    import pandas as pd

    pytest.importorskip("pyarrow")
    pytest.importorskip("xarray")
    df = pk.read_table(ROOT / "figures" / "threshold_vs_aspect.csv")
    pk.write_table(df, tmp_path / "t.parquet")
    back = pk.read_table(tmp_path / "t.parquet")
    pd.testing.assert_frame_equal(back, df, check_dtype=False)
    pk.write_table(df, tmp_path / "t.nc")
    nc = pk.read_table(tmp_path / "t.nc")
    np.testing.assert_array_equal(nc["threshold"].to_numpy(), df["threshold"].to_numpy())
    with pytest.raises(pk.ParameterError, match="`path`"):
        pk.write_table(df, tmp_path / "t.xlsx")
