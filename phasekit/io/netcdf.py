"""NetCDF tables: one dimension, each column a variable with the CF attributes ``units`` and
``long_name``, the table's attributes as global attributes.

The dimension is ``t`` when the first column is ``t`` (a sampled run: the times are its
coordinate), else ``row`` (a study table: one row per case; ``row_`` if a column is named
``row``). Global attributes that NetCDF holds as they are (text, integers, floats, under plain
names) are written as such; the others (True/False, None, lists, dicts such as a run's inputs)
and the layout (column order, pandas dtypes) go as JSON into the one global attribute
``phasekit_json``::

    {"phasekit_table": 1, "columns": ["t", ...], "dtypes": {"t": "float64", ...},
     "attrs": {"run": {...}, "reason": null}}

NetCDF has no missing booleans, integers or text: a nullable boolean is an int8 (1, 0) and a
nullable integer its own type, each with a ``_FillValue`` for the missing cells (plain xarray
shows them as NaN); missing text is the empty string.
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import numpy as np

from ..errors import ParameterError
from .atomic import atomic_path
from .schema import MARK, NULLABLE_INTS, TEXT_DTYPES, Schema, check_text, dumps, infer_dtypes, python_scalar, restore

#: the global attribute with the layout and the attributes NetCDF cannot hold as they are
JSON_ATTR = "phasekit_json"
INT64 = (-(2**63), 2**63 - 1)


def engine() -> str:
    """The xarray engine for NetCDF files: h5netcdf when installed, else netCDF4."""
    return "h5netcdf" if importlib.util.find_spec("h5netcdf") else "netcdf4"


def dimension(columns) -> str:
    """The table's dimension: ``t`` for a table that starts with the times, else ``row``."""
    if columns[0] == "t":
        return "t"
    name = "row"
    while name in columns:
        name += "_"
    return name


def _fill(np_dtype: str, present) -> np.generic:
    """A fill value of an integer type that no cell holds: its extreme (the netCDF convention),
    or the next one inward."""
    info, taken = np.iinfo(np_dtype), set(present.tolist())
    value, step = (info.min, 1) if info.min < 0 else (info.max, -1)
    while value in taken:
        value += step
    return np.dtype(np_dtype).type(value)


def _variable(col, dtype: str):
    """(values, attributes) of one column as NetCDF holds it."""
    if dtype == "boolean":
        values = np.where(col.isna().to_numpy(), -1, col.fillna(False).to_numpy(dtype=bool)).astype("int8")
        return values, {"_FillValue": np.int8(-1)}
    if dtype in NULLABLE_INTS:
        np_dtype = dtype.lower()
        fill = _fill(np_dtype, col.dropna().to_numpy(dtype=np_dtype))
        return col.to_numpy(dtype=np_dtype, na_value=fill), {"_FillValue": fill}
    if dtype in TEXT_DTYPES:
        # a text column holds strings and missing cells only (schema.describe checked it)
        return np.array([v if isinstance(v, str) else "" for v in col], dtype=object), {}
    return col.to_numpy(), {}


def _native(key: str, value) -> bool:
    """Whether a global attribute is written as it is (else into the JSON attribute)."""
    plain_name = key.isascii() and key.isidentifier() and not key.startswith("_") and key != JSON_ATTR
    if isinstance(value, str):
        return plain_name and "\x00" not in value
    if isinstance(value, int) and not isinstance(value, bool):
        return plain_name and INT64[0] <= value <= INT64[1]
    return plain_name and isinstance(value, float)


def dataset(df, schema: Schema):
    """The xarray Dataset of ``df`` (checked as ``schema``), as the NetCDF file holds it."""
    import xarray as xr

    dim = dimension(schema.columns)
    data_vars, coords = {}, {}
    for name in schema.columns:
        values, attrs = _variable(df[name], schema.dtypes[name])
        for key, per in (("units", schema.units), ("long_name", schema.long_names)):
            if name in per:
                attrs[key] = per[name]
        (coords if name == dim else data_vars)[name] = (dim, values, attrs)
    ds = xr.Dataset(data_vars, coords=coords)
    native = {k: v for k, v in schema.attrs.items() if _native(k, v)}
    rest = {k: v for k, v in schema.attrs.items() if k not in native}
    ds.attrs = {**native, JSON_ATTR: dumps({MARK: 1, "columns": schema.columns, "dtypes": schema.dtypes,
                                            "attrs": rest})}
    return ds


def write_netcdf(df, schema: Schema, path: Path) -> None:
    """Write ``df`` (checked as ``schema``) atomically."""
    # HDF5 names are paths ("/" separates, "." is the group itself); its strings end at a NUL
    check_text(df, schema, "NetCDF", forbidden="\x00")
    for name in schema.columns:
        if "/" in name or name in (".", ".."):
            raise ParameterError("df", f"has the column name {name!r}, which cannot name a NetCDF variable "
                                       "(no '/', not '.' or '..')", show_value=False)
    ds = dataset(df, schema)
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine=engine())


def _column(var, dtype: str):
    import pandas as pd

    values = var.values
    if dtype == "boolean" or dtype in NULLABLE_INTS:
        missing = values == var.attrs.get("_FillValue")
        col = pd.Series(values == 1 if dtype == "boolean" else values).astype(dtype)
        col[missing] = pd.NA
        return col
    if dtype in TEXT_DTYPES:
        col = pd.Series(values, dtype=object)
        return col.where(col != "", None)
    return pd.Series(values)


def read_netcdf(path: Path):
    """The table of the NetCDF file ``path``, with the dtypes, units and attributes it holds."""
    import xarray as xr

    with xr.open_dataset(path, engine=engine(), decode_cf=False) as ds:
        raw = ds.attrs.get(JSON_ATTR)
        meta = json.loads(raw) if isinstance(raw, str) else None
        if isinstance(meta, dict) and meta.get(MARK) == 1:
            return _ours(ds, meta)
    with xr.open_dataset(path, engine=engine(), decode_timedelta=False) as ds:
        return _foreign(ds)


def _ours(ds, meta: dict):
    import pandas as pd

    columns, dtypes = meta["columns"], meta["dtypes"]
    df = pd.DataFrame({name: _column(ds[name], dtypes[name]) for name in columns}, columns=columns)
    per = {key: {n: str(ds[n].attrs[attr]) for n in columns if attr in ds[n].attrs}
           for key, attr in (("units", "units"), ("long_names", "long_name"))}
    attrs = {k: python_scalar(v) for k, v in ds.attrs.items() if k != JSON_ATTR}
    attrs.update(meta.get("attrs", {}))
    return restore(df, Schema(columns, dtypes, per["units"], per["long_names"], attrs))


def _foreign(ds):
    """A NetCDF file another program wrote: its variables as columns (dimensions with a
    coordinate as columns too), dtypes inferred."""
    df = ds.to_dataframe().reset_index()
    # a dimension without coordinate numbers rows only, as does pandas' default index 0..n-1
    # (which xarray.Dataset.from_dataframe makes a coordinate "index")
    plain = [d for d in ds.dims if d not in ds.coords or (d == "index" and np.array_equal(ds[d].values,
                                                                                           np.arange(ds.sizes[d])))]
    df = df.drop(columns=[d for d in plain if d in df.columns])
    out = infer_dtypes(df)
    out.attrs = {k: python_scalar(v) for k, v in ds.attrs.items()}
    for key, attr in (("units", "units"), ("long_names", "long_name")):
        per = {n: str(ds[n].attrs[attr]) for n in out.columns if n in ds.variables and attr in ds[n].attrs}
        if per:
            out.attrs[key] = per
    return out
