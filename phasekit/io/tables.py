"""Data out: trajectories as xarray Datasets, Parquet and NetCDF files; study tables with honest dtypes.

A trajectory becomes a table by sampling its dense output (:meth:`Trajectory.sample`): one row
per time, every observable a column (the state, R, energy, ..., the pose). As an xarray
Dataset the time is the coordinate ``t``, each column a variable, and the inputs that make the
run repeatable (model, start, options, pose0, status) are attributes holding JSON strings
(NetCDF attributes cannot hold nested objects). Study tables (the CSVs in figures/) are read
back by :func:`read_table` with booleans as booleans (pandas' nullable "boolean"), numbers as
numbers and one spelling for missing (an empty cell), and written as CSV, Parquet or NetCDF.

Parquet needs pyarrow, NetCDF xarray with h5netcdf (or netCDF4): ``pip install "phasekit[data]"``.
"""

from __future__ import annotations

import contextlib
import importlib.util
import json
import os
from pathlib import Path

import numpy as np

from .._runtime.errors import ParameterError, PhasekitError
from .._runtime.validate import check_int

__all__ = ["to_xarray", "write_trajectory", "write_table", "read_table", "atomic_path", "DATA_EXTRA", "TABLE_SUFFIXES"]

#: the optional packages of each file type
DATA_EXTRA = {".parquet": ("pyarrow",), ".nc": ("xarray", "h5netcdf", "h5py")}
TABLE_SUFFIXES = (".csv", ".parquet", ".nc")
#: the attributes of a trajectory's Dataset (JSON strings)
ATTRS = ("model", "start", "options", "pose0", "status", "reason", "t_jump", "stop_at", "restitution")


@contextlib.contextmanager
def atomic_path(path):
    """A temporary path next to ``path`` to write to; renamed onto ``path`` when the block
    ends without an exception, removed otherwise. A kill at any moment leaves either the old
    file or the new one, never a torn one.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write; its directory is created if missing.

    Yields
    ------
    pathlib.Path
        The temporary path, in the same directory and with the same suffix as ``path``.

    Examples
    --------
    >>> import tempfile, pathlib, phasekit as pk
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "note.txt"
    >>> with pk.io.atomic_path(target) as tmp:
    ...     _ = tmp.write_text("whole")
    >>> target.read_text()
    'whole'
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # keep the suffix: writers (matplotlib, VTK) pick the format from it
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def _need(suffix: str) -> None:
    missing = [m for m in DATA_EXTRA.get(suffix, ()) if importlib.util.find_spec(m) is None]
    if missing:
        raise PhasekitError(f"writing or reading {suffix} files needs {', '.join(missing)} (pip install "
                            "\"phasekit[data]\")")


def _times(traj, times, n):
    if times is not None:
        return times
    n = check_int("n", n, minimum=2, maximum=10_000_000)
    return np.linspace(traj.t0, traj.t, n)


def _check_path(path, suffixes) -> Path:
    if not isinstance(path, (str, os.PathLike)) or Path(path).suffix.lower() not in suffixes:
        raise ParameterError("path", f"must be a file path ending in {', '.join(suffixes)}", path)
    return Path(path)


def to_xarray(traj, times=None, *, n: int = 2001):
    """The trajectory sampled at ``times`` (default ``n`` instants uniform over the run) as an
    xarray Dataset: coordinate ``t``, one variable per column of :meth:`Trajectory.sample`
    (``mode`` as strings) and the run's inputs as JSON-string attributes.

    Parameters
    ----------
    traj : Trajectory
        The run, with its dense output.
    times : array_like, optional
        The sampling times; default ``n`` instants uniform over the run.
    n : int, optional
        The number of instants without ``times``, in [2, 1e7] (default 2001).

    Returns
    -------
    xarray.Dataset
        The sampled trajectory.

    Raises
    ------
    ParameterError
        If ``times`` is None and ``n`` is not an integer in [2, 1e7].
    """
    import xarray as xr

    df = traj.sample(_times(traj, times, n))
    d = traj.to_dict(events=False)
    ds = xr.Dataset({c: ("t", df[c].to_numpy(dtype=str if c == "mode" else float)) for c in df.columns if c != "t"},
                    coords={"t": df["t"].to_numpy()})
    ds.attrs = {k: json.dumps(d.get(k)) for k in ATTRS}
    ds.attrs["events"] = json.dumps([e.to_dict() for e in traj.events])
    ds.attrs["run"] = json.dumps(d)  # the whole result: pk.rerun(json.loads(ds.attrs["run"])) repeats it
    ds.attrs["units"] = "phasekit's: lengths b, times sqrt(b/g), rates sqrt(g/b), angles rad, forces M g"
    ds["t"].attrs["long_name"] = "time"
    return ds


def write_trajectory(traj, path, times=None, *, n: int = 2001) -> Path:
    """Write the sampled trajectory to ``path``: .nc (NetCDF, the Dataset of :func:`to_xarray`),
    .parquet (the table, the attributes in its metadata) or .csv.

    Parameters
    ----------
    traj : Trajectory
        The run, with its dense output.
    path : str or os.PathLike
        The file, ending in .csv, .parquet or .nc (written atomically).
    times : array_like, optional
        The sampling times; default ``n`` instants uniform over the run.
    n : int, optional
        The number of instants without ``times``, in [2, 1e7] (default 2001).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ParameterError
        If ``path`` is not a file path ending in .csv, .parquet or .nc, or ``times`` is None
        and ``n`` is not an integer in [2, 1e7].
    PhasekitError
        If the optional packages of the file type are missing (.parquet: pyarrow; .nc: xarray,
        h5netcdf, h5py): ``pip install "phasekit[data]"``.
    """
    path = _check_path(path, TABLE_SUFFIXES)
    suffix = path.suffix.lower()
    _need(suffix)
    with atomic_path(path) as tmp:
        if suffix == ".nc":
            to_xarray(traj, times, n=n).to_netcdf(tmp, engine=_netcdf_engine())
        else:
            df = traj.sample(_times(traj, times, n))
            d = traj.to_dict(events=False)
            df.attrs = {k: json.dumps(v) for k, v in d.items() if k in ATTRS}
            df.attrs["run"] = json.dumps(d)  # as in the NetCDF file: enough to repeat the run
            _write_frame(df, tmp, suffix)
    return path


def _netcdf_engine() -> str:
    return "h5netcdf" if importlib.util.find_spec("h5netcdf") else "netcdf4"


def _write_frame(df, path: Path, suffix: str) -> None:
    if suffix == ".csv":
        df.to_csv(path, index=False, na_rep="")
    elif suffix == ".parquet":
        import pyarrow as pa
        import pyarrow.parquet as pq

        table = pa.Table.from_pandas(df, preserve_index=False)
        meta = {**(table.schema.metadata or {}), b"phasekit": json.dumps(dict(df.attrs)).encode()}
        pq.write_table(table.replace_schema_metadata(meta), path)
    else:
        import xarray as xr

        ds = xr.Dataset.from_dataframe(df.reset_index(drop=True))
        ds.attrs = {k: v if isinstance(v, str) else json.dumps(v) for k, v in df.attrs.items()}
        ds.to_netcdf(path, engine=_netcdf_engine())


def _honest(df):
    """Columns as what they hold: True/False (with missing cells) as nullable booleans, numbers as
    floats or ints, the rest as strings; every missing cell is NA."""
    import pandas as pd

    out = df.copy()
    for c in out.columns:
        col = out[c]
        if pd.api.types.is_bool_dtype(col) or pd.api.types.is_numeric_dtype(col):
            continue
        vals = set(col.dropna().astype(str).unique())
        if vals and vals <= {"True", "False"}:
            out[c] = col.map({"True": True, "False": False, True: True, False: False}).astype("boolean")
    return out


def write_table(df, path) -> Path:
    """Write a study table (a DataFrame) as .csv (missing cells empty), .parquet or .nc, with
    honest dtypes (:func:`read_table`'s).

    Parameters
    ----------
    df : pandas.DataFrame
        The table.
    path : str or os.PathLike
        The file, ending in .csv, .parquet or .nc (written atomically).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ParameterError
        If ``df`` is not a DataFrame, or ``path`` is not a file path ending in .csv, .parquet
        or .nc.
    PhasekitError
        If the optional packages of the file type are missing (.parquet: pyarrow; .nc: xarray,
        h5netcdf, h5py): ``pip install "phasekit[data]"``.

    Examples
    --------
    >>> import phasekit as pk
    >>> import pandas as pd, tempfile, pathlib
    >>> pk.write_table(pd.DataFrame({'a': [1.5]}), pathlib.Path(tempfile.mkdtemp()) / 't.csv').name
    't.csv'
    """
    if not hasattr(df, "columns"):
        raise ParameterError("df", "must be a pandas DataFrame", type(df).__name__)
    path = _check_path(path, TABLE_SUFFIXES)
    suffix = path.suffix.lower()
    _need(suffix)
    table = _honest(df)
    if suffix == ".nc":  # NetCDF has no nullable booleans or NA strings: missing -> NaN / ""
        table = table.apply(lambda c: c.astype(float) if str(c.dtype) == "boolean" else c)
        table = table.apply(lambda c: c.fillna("") if c.dtype == object or str(c.dtype).startswith("str") else c)
    with atomic_path(path) as tmp:
        _write_frame(table, tmp, suffix)
    return path


def read_table(path):
    """A study table (.csv, .parquet or .nc) as a DataFrame with honest dtypes: booleans as
    pandas' nullable "boolean", numbers as numbers, text as strings, every missing cell NA.

    Parameters
    ----------
    path : str or os.PathLike
        An existing file ending in .csv, .parquet or .nc.

    Returns
    -------
    pandas.DataFrame
        The table.

    Raises
    ------
    ParameterError
        If ``path`` is not a file path ending in .csv, .parquet or .nc, or the file does not
        exist.
    PhasekitError
        If the optional packages of the file type are missing (.parquet: pyarrow; .nc: xarray,
        h5netcdf, h5py): ``pip install "phasekit[data]"``.

    Examples
    --------
    >>> import phasekit as pk
    >>> import pandas as pd, tempfile, pathlib
    >>> path = pk.write_table(pd.DataFrame({'a': [1.5], 'ok': [True]}), pathlib.Path(tempfile.mkdtemp()) / 't.csv')
    >>> pk.read_table(path).dtypes.astype(str).tolist()
    ['float64', 'bool']
    """
    import pandas as pd

    path = _check_path(path, TABLE_SUFFIXES)
    if not path.exists():
        raise ParameterError("path", "must be an existing file", str(path))
    suffix = path.suffix.lower()
    _need(suffix)
    if suffix == ".csv":
        df = pd.read_csv(path, keep_default_na=False, na_values=[""])
    elif suffix == ".parquet":
        df = pd.read_parquet(path)
    else:
        import xarray as xr

        with xr.open_dataset(path, engine=_netcdf_engine()) as ds:
            df = ds.to_dataframe().reset_index(drop=True)
    return _honest(df)
