"""Tables in and out: :func:`write_table` and :func:`read_table` for CSV, Parquet and NetCDF files.

What is written is read back as it was: the values, the dtypes, each column's ``units`` and
``long_name`` (``df.attrs["units"]``, ``df.attrs["long_names"]``: the CF attributes of each
variable) and the table's other attributes, typed (numbers as numbers, text as text, nested
structures such as a run's inputs as they were). Each format keeps them its own way: CSV in a
JSON sidecar ``x.csv.json`` (:mod:`phasekit.io.csvfile`), Parquet in its Arrow metadata
(:mod:`phasekit.io.parquet`), NetCDF as variable and global attributes
(:mod:`phasekit.io.netcdf`); what a table may hold is in :mod:`phasekit.io.schema`. A run's
sampled table is written with its inputs by :meth:`phasekit.core.Trajectory.to_netcdf` and
``to_parquet`` (:mod:`phasekit.core.trajectory_io`), so that ``pk.rerun(df.attrs["run"])``
repeats the run from the table read back.

Files another program wrote (the study tables in figures/ are plain CSVs) are read by inference:
booleans as booleans (pandas' nullable "boolean"), numbers as numbers, one spelling for missing.

Parquet needs pyarrow, NetCDF xarray with h5netcdf (or netCDF4): ``pip install "phasekit[data]"``.
"""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path

from ..errors import ParameterError, PhasekitError
from .csvfile import read_csv, write_csv
from .netcdf import dataset, read_netcdf, write_netcdf
from .parquet import read_parquet, write_parquet
from .schema import describe

#: the optional packages of each file type
DATA_EXTRA = {".parquet": ("pyarrow",), ".nc": ("xarray", "h5netcdf", "h5py")}
TABLE_SUFFIXES = (".csv", ".parquet", ".nc")
WRITERS = {".csv": write_csv, ".parquet": write_parquet, ".nc": write_netcdf}
READERS = {".csv": read_csv, ".parquet": read_parquet, ".nc": read_netcdf}


def _need(suffix: str) -> None:
    missing = [m for m in DATA_EXTRA.get(suffix, ()) if importlib.util.find_spec(m) is None]
    if missing:
        raise PhasekitError(f"writing or reading {suffix} files needs {', '.join(missing)} (pip install "
                            "\"phasekit[data]\")")


def check_path(path, suffixes) -> Path:
    if not isinstance(path, (str, os.PathLike)) or Path(path).suffix.lower() not in suffixes:
        raise ParameterError("path", f"must be a file path ending in {', '.join(suffixes)}",
                             str(path) if isinstance(path, os.PathLike) else path)
    return Path(path)


def table_dataset(df):
    """``df`` as the xarray Dataset its NetCDF file holds (see :mod:`phasekit.io.netcdf`);
    ParameterError naming ``df`` for a table no file could give back as it is."""
    _need(".nc")
    return dataset(df, describe(df))


def write_table(df, path) -> Path:
    """Write a table (a DataFrame) as .csv, .parquet or .nc, so that :func:`read_table` gives it
    back: values, dtypes, each column's units and long name, and the other attributes.

    Per column, ``df.attrs["units"]`` and ``df.attrs["long_names"]`` (mappings from column names
    to text) become the CF attributes ``units`` and ``long_name`` (:meth:`phasekit.Scale.table`
    and :meth:`phasekit.core.Trajectory.sample` set the units). The other attributes are
    numbers, text, True/False, None, or lists and dicts (text keys) of these (a tuple is written
    as a list). The index is not written: rows come back numbered from 0.

    * CSV: a plain CSV (a missing cell empty) and, beside it, ``x.csv.json`` with the dtypes,
      units, long names and attributes. CSV spells missing text as an empty cell, so a text
      column may not hold empty strings (use None), nor carriage returns.
    * Parquet: units and long names in each field's metadata, the rest in the schema's
      metadata under ``phasekit``.
    * NetCDF: one dimension (``t`` with the times as coordinate when the first column is ``t``,
      else ``row``), each column a variable with ``units`` and ``long_name``; attributes that
      NetCDF holds (text, numbers) as global attributes, the others and the dtypes as JSON in
      the global attribute ``phasekit_json``. Text may not hold empty strings or NUL characters.

    Parameters
    ----------
    df : pandas.DataFrame
        The table: columns (named by non-empty, distinct text) of floats, integers (numpy's or
        pandas' nullable ones), booleans (numpy's or pandas' nullable "boolean") or text.
    path : str or os.PathLike
        The file, ending in .csv, .parquet or .nc (written atomically).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ParameterError
        If ``df`` is not a DataFrame or holds what the file could not give back as it is (no
        column, other dtypes, attributes of other types, text the format cannot hold), or
        ``path`` is not a file path ending in .csv, .parquet or .nc.
    PhasekitError
        If the optional packages of the file type are missing (.parquet: pyarrow; .nc: xarray,
        h5netcdf, h5py): ``pip install "phasekit[data]"``.

    See Also
    --------
    phasekit.scaffold.Study.csv
        a study's tables, written whole in its output folder

    Examples
    --------
    >>> import phasekit as pk
    >>> import pandas as pd, tempfile, pathlib
    >>> df = pd.DataFrame({'t': [0.0, 12.5], 'ok': [True, False]})
    >>> df.attrs = {'units': {'t': 'ms'}, 'status': 'jumped'}
    >>> path = pk.write_table(df, pathlib.Path(tempfile.mkdtemp()) / 't.csv')
    >>> pk.read_table(path).attrs
    {'status': 'jumped', 'units': {'t': 'ms'}}
    """
    schema = describe(df)
    path = check_path(path, TABLE_SUFFIXES)
    suffix = path.suffix.lower()
    _need(suffix)
    WRITERS[suffix](df, schema, path)
    return path


def read_table(path):
    """A table (.csv, .parquet or .nc) as a DataFrame: one :func:`write_table` wrote as it was
    (values, dtypes, ``attrs`` with ``units``, ``long_names`` and the other attributes), any
    other with inferred dtypes: booleans as pandas' nullable "boolean", numbers as numbers, text
    as strings, every missing cell NA (and the units and attributes the file holds).

    Parameters
    ----------
    path : str or os.PathLike
        An existing file ending in .csv, .parquet or .nc.

    Returns
    -------
    pandas.DataFrame
        The table, its units and attributes in ``attrs``.

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
    path = check_path(path, TABLE_SUFFIXES)
    if not path.exists():
        raise ParameterError("path", "must be an existing file", str(path))
    suffix = path.suffix.lower()
    _need(suffix)
    return READERS[suffix](path)
