"""Parquet tables: each column's ``units`` and ``long_name`` in its Arrow field's metadata, the
dtypes and the other attributes as JSON under the schema's metadata key ``phasekit``::

    {"phasekit_table": 1, "dtypes": {"t": "float64", ...}, "attrs": {"status": "jumped", ...}}

and the table's whole ``attrs`` (``units`` and ``long_names`` per column, and the others) as
JSON under ``PANDAS_ATTRS``, where pandas (2.1 and later) looks for them: plain
``pandas.read_parquet(path).attrs["units"]`` names each column's unit, as
``pyarrow.parquet.read_schema(path).field("t").metadata[b"units"]`` does.

(Parquet files keep text, missing cells and every dtype of a table as they are.)
"""

from __future__ import annotations

import json
from pathlib import Path

from .atomic import atomic_path
from .schema import MARK, Schema, dumps, infer_dtypes, python_scalar, restore, schema_from_json

#: the key of the table's metadata in the Parquet schema
KEY = b"phasekit"
FIELD_KEYS = {"units": b"units", "long_names": b"long_name"}
#: the key under which pandas keeps a DataFrame's ``attrs`` in the Parquet schema (pandas >= 2.1)
PANDAS_ATTRS = b"PANDAS_ATTRS"


def write_parquet(df, schema: Schema, path: Path) -> None:
    """Write ``df`` (checked as ``schema``) atomically."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    plain = df.copy(deep=False)
    plain.attrs = {}  # the attributes go under KEY, typed, not into pandas' own metadata
    table = pa.Table.from_pandas(plain, preserve_index=False)
    fields = []
    for f in table.schema:
        meta = {FIELD_KEYS[key]: per[f.name].encode() for key, per in (("units", schema.units),
                                                                      ("long_names", schema.long_names))
                if f.name in per}
        fields.append(f.with_metadata({**(f.metadata or {}), **meta}) if meta else f)
    meta = {MARK: 1, "dtypes": schema.dtypes, "attrs": schema.attrs}
    attrs = schema.frame_attrs()  # for plain pandas: what read_table gives back as attrs
    arrow_schema = pa.schema(fields, metadata={**(table.schema.metadata or {}), KEY: dumps(meta).encode(),
                                               **({PANDAS_ATTRS: dumps(attrs).encode()} if attrs else {})})
    with atomic_path(path) as tmp:
        pq.write_table(pa.Table.from_arrays(table.columns, schema=arrow_schema), tmp)


def read_parquet(path: Path):
    """The table of the Parquet file ``path``, with the dtypes, units and attributes it holds."""
    import pyarrow.parquet as pq

    table = pq.read_table(path)
    df = table.to_pandas()
    per = {key: {f.name: f.metadata[k].decode() for f in table.schema if f.metadata and k in f.metadata}
           for key, k in FIELD_KEYS.items()}
    raw = (table.schema.metadata or {}).get(KEY)
    meta = json.loads(raw) if raw else {}
    if not raw and PANDAS_ATTRS in (table.schema.metadata or {}):  # pandas' own: its DataFrame's attrs
        meta = json.loads(table.schema.metadata[PANDAS_ATTRS])
    if isinstance(meta, dict) and meta.get(MARK) == 1:
        return restore(df, schema_from_json(meta, list(df.columns), per["units"], per["long_names"]))
    # a file another program (or an older phasekit) wrote: infer, keep what attributes there are
    df = infer_dtypes(df)
    df.attrs = {k: python_scalar(v) for k, v in (meta.items() if isinstance(meta, dict) else ())}
    df.attrs.update({key: v for key, v in per.items() if v})
    return df
