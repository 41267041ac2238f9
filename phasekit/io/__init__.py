"""Tables on disk (``phasekit.io``): CSV, Parquet and NetCDF files that give back what was
written (values, dtypes, each column's units and long name, typed attributes such as a run's
inputs), and the atomic writes every result file goes through (a kill at any moment leaves the old
file or the new one, never half of one).

Examples
--------
>>> import pandas as pd, tempfile, pathlib, phasekit as pk
>>> path = pathlib.Path(tempfile.mkdtemp()) / "t.csv"
>>> df = pd.DataFrame({"t": [0.0, 1.0]})
>>> df.attrs = {"units": {"t": "ms"}}
>>> back = pk.io.read_table(pk.io.write_table(df, path))
>>> list(back["t"]), back.attrs["units"]
([0.0, 1.0], {'t': 'ms'})
"""

from .atomic import atomic_path
from .tables import read_table, write_table

__all__ = ["read_table", "write_table", "atomic_path"]
