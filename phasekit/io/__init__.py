"""Tables on disk (``phasekit.io``): CSV, Parquet and NetCDF with units and run inputs, and the
atomic writers every result file goes through (a kill at any moment leaves the old file or the
new one, never half of one).

Examples
--------
>>> import pandas as pd, tempfile, pathlib, phasekit as pk
>>> path = pathlib.Path(tempfile.mkdtemp()) / "t.csv"
>>> _ = pk.io.write_table(pd.DataFrame({"t": [0.0, 1.0]}), path)
>>> list(pk.io.read_table(path)["t"])
[0.0, 1.0]
"""

from .tables import atomic_path, read_table, write_table

__all__ = ["read_table", "write_table", "atomic_path"]
