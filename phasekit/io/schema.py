"""What a table is on disk: its columns (name, dtype, ``units``, ``long_name``) and its attributes,
checked once before any format writes them (:func:`describe`), and put back on the DataFrame a
file is read into (:func:`restore`).

A table's ``attrs`` may hold ``units`` and ``long_names``, each mapping column names to text (the
CF attributes ``units`` and ``long_name`` of each variable; :meth:`phasekit.Scale.table` and
:meth:`phasekit.core.Trajectory.sample` set ``units``); every other attribute is a number, text,
True/False, None, or a list or dict (text keys) of these, which every format gives back as it was
(a tuple comes back as a list). Columns hold numbers (numpy floats and integers, pandas' nullable
integers), booleans (numpy's, pandas' nullable "boolean") or text (pandas' string dtypes, or
object columns of strings), each with missing cells (NA) where its dtype has them.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError

#: the key that marks metadata phasekit wrote (its value is the version of this layout)
MARK = "phasekit_table"
TEXT_DTYPES = ("str", "string", "object")
NULLABLE_INTS = tuple(f"{u}Int{b}" for u in ("", "U") for b in (8, 16, 32, 64))
NUMPY_NUMBERS = ("float32", "float64", *(f"{u}int{b}" for u in ("", "u") for b in (8, 16, 32, 64)))
DTYPES = (*NUMPY_NUMBERS, "bool", "boolean", *NULLABLE_INTS, *TEXT_DTYPES)
#: attributes given per column (a mapping from column name to text)
PER_COLUMN = ("units", "long_names")
MAX_DEPTH = 64


def _refuse(expected: str):
    return ParameterError("df", expected, show_value=False)


def dumps(obj, indent: int | None = None) -> str:
    """JSON as phasekit writes it into files: UTF-8 text, NaN and Infinity as Python spells them."""
    return json.dumps(obj, ensure_ascii=False, allow_nan=True, indent=indent)


def python_scalar(value):
    """A numpy scalar as the Python number, bool or str it stands for (others unchanged)."""
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    if isinstance(value, np.str_):
        return str(value)
    return value


def _unicode(text: str, what: str) -> str:
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        raise _refuse(f"has {what} that is not valid Unicode (a lone surrogate)") from None
    return text


def _attr_value(value, where: str, depth: int = 0):
    """``value`` in the types every format gives back (numpy scalars as Python ones, tuples as
    lists); ParameterError for anything else."""
    if depth > MAX_DEPTH:
        raise _refuse(f"{where} is nested deeper than {MAX_DEPTH} levels")
    value = python_scalar(value)
    if value is None or isinstance(value, (bool, int, float)):
        return value
    if isinstance(value, str):
        return _unicode(value, f"text in {where}")
    if isinstance(value, (list, tuple)):
        return [_attr_value(v, f"{where}[{i}]", depth + 1) for i, v in enumerate(value)]
    if isinstance(value, dict):
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise _refuse(f"{where} has the key {k!r}: keys of table attributes must be text")
            out[_unicode(k, f"a key in {where}")] = _attr_value(v, f"{where}[{k!r}]", depth + 1)
        return out
    raise _refuse(f"{where} holds a {type(value).__name__}: table attributes are numbers, text, True/False, "
                  "None, and lists and dicts (text keys) of these")


@dataclass
class Schema:
    """A checked table: column names in order, their dtypes (pandas' names), the ``units`` and
    ``long_name`` of the columns that have them, and the other attributes."""

    columns: list
    dtypes: dict
    units: dict = field(default_factory=dict)
    long_names: dict = field(default_factory=dict)
    attrs: dict = field(default_factory=dict)

    def frame_attrs(self) -> dict:
        """The DataFrame attributes this schema stands for (what :func:`read_table` returns)."""
        out = dict(self.attrs)
        for key, per in (("units", self.units), ("long_names", self.long_names)):
            if per:
                out[key] = {c: per[c] for c in self.columns if c in per}
        return out

    def column(self, name: str) -> dict:
        """One column's description: name, dtype, and units and long_name when it has them."""
        d = {"name": name, "dtype": self.dtypes[name]}
        for key, per in (("units", self.units), ("long_name", self.long_names)):
            if name in per:
                d[key] = per[name]
        return d


def _per_column(attrs: dict, key: str, columns: list) -> dict:
    per = attrs.get(key)
    if per is None:
        return {}
    if not isinstance(per, dict) or not all(isinstance(k, str) and isinstance(v, str) for k, v in per.items()):
        raise _refuse(f"attrs[{key!r}] must map column names to text (e.g. {{'t': 'ms'}})")
    for name, text in per.items():
        if name not in columns:
            raise _refuse(f"attrs[{key!r}] names {name!r}, which is not a column")
        if "\x00" in text:
            raise _refuse(f"attrs[{key!r}][{name!r}] holds the NUL character")
        _unicode(text, f"text in attrs[{key!r}][{name!r}]")
    return dict(per)


def _dtype_of(col, name: str) -> str:
    dtype = str(col.dtype)
    if dtype not in DTYPES:
        raise _refuse(f"column {name!r} holds {dtype}: a table holds numbers (float32, float64, integers), "
                      "booleans and text")
    if dtype == "object":
        for v in col:
            if not (isinstance(v, str) or v is None or v is _na() or (isinstance(v, float) and math.isnan(v))):
                raise _refuse(f"column {name!r} holds a {type(v).__name__} among its objects: an object column "
                              "must hold text (str) or missing cells only")
    return dtype


def _na():
    import pandas as pd

    return pd.NA


def describe(df) -> Schema:
    """The :class:`Schema` of ``df``, checked: ParameterError naming ``df`` for a table a file
    could not give back as it is (no columns, a column name that is not non-empty text or
    repeats, an unsupported dtype, attributes of other types, text that is not Unicode)."""
    if not (hasattr(df, "columns") and hasattr(df, "attrs") and hasattr(df, "dtypes")):
        raise ParameterError("df", "must be a pandas DataFrame", type(df).__name__)
    columns = list(df.columns)
    if not columns:
        raise _refuse("must have at least one column (a file keeps the rows through its columns)")
    for name in columns:
        if not isinstance(name, str) or not name:
            raise _refuse(f"has the column name {name!r}: column names must be non-empty text")
        if "\x00" in name:
            raise _refuse(f"has the column name {name!r}, which holds the NUL character")
        _unicode(name, "a column name")
    if len(set(columns)) != len(columns):
        twice = sorted({c for c in columns if columns.count(c) > 1})
        raise _refuse(f"has the column names {twice} more than once")
    dtypes = {name: _dtype_of(df[name], name) for name in columns}
    for name, dtype in dtypes.items():
        if dtype in TEXT_DTYPES:
            for v in df[name].dropna():
                _unicode(v, f"text in column {name!r}")
    attrs = dict(df.attrs)
    for key in attrs:
        if not isinstance(key, str):
            raise _refuse(f"has the attribute key {key!r}: attribute keys must be text")
    per = {key: _per_column(attrs, key, columns) for key in PER_COLUMN}
    # an empty mapping has no column to go with: it is kept as an attribute like any other
    rest = {k: _attr_value(v, f"attrs[{k!r}]") for k, v in attrs.items() if k not in PER_COLUMN or not per[k]}
    for key in rest:
        _unicode(key, "an attribute key")
    return Schema(columns, dtypes, per["units"], per["long_names"], rest)


def check_text(df, schema: Schema, fmt: str, *, empty: bool = True, forbidden: str = "") -> None:
    """Refuse text a format cannot give back: empty strings (when ``empty``: the format's
    spelling of a missing cell) and the characters of ``forbidden``, in cells and names."""
    for name in schema.columns:
        bad = [ch for ch in forbidden if ch in name]
        if bad:
            raise _refuse(f"has the column name {name!r}: {fmt} names cannot hold {bad[0]!r}")
        if schema.dtypes[name] not in TEXT_DTYPES:
            continue
        cells = df[name].dropna()
        if empty and (cells == "").any():
            raise _refuse(f"column {name!r} holds empty strings, which {fmt} files spell as missing text: write "
                          "missing text as None (pd.NA), or use .parquet")
        for ch in forbidden:
            if cells.str.contains(ch, regex=False).any():
                raise _refuse(f"column {name!r} holds {ch!r}, which {fmt} files cannot hold in text: use .parquet")


def restore(df, schema: Schema):
    """``df`` (as a file was read) with the schema's column order, dtypes and attributes."""
    import pandas as pd

    out = pd.DataFrame({name: _as_dtype(df[name], schema.dtypes[name]) for name in schema.columns},
                       columns=schema.columns)
    out.attrs = schema.frame_attrs()
    return out


def _as_dtype(col, dtype: str):
    if str(col.dtype) == dtype:
        return col.reset_index(drop=True)
    if dtype == "object":  # text: missing cells as None, as a column built from Python lists has them
        return col.astype(object).where(col.notna(), None).reset_index(drop=True)
    if dtype == "bool" and str(col.dtype) == "object":
        col = col.map({"True": True, "False": False, True: True, False: False})
    return col.astype(dtype).reset_index(drop=True)


def schema_from_json(d: dict, columns=None, units=None, long_names=None) -> Schema:
    """A :class:`Schema` from the JSON phasekit wrote (``dtypes`` or ``columns`` entries)."""
    if isinstance(d.get("columns"), list) and d["columns"] and isinstance(d["columns"][0], dict):
        cols = d["columns"]
        names = [c["name"] for c in cols]
        return Schema(names, {c["name"]: c["dtype"] for c in cols},
                      {c["name"]: c["units"] for c in cols if "units" in c},
                      {c["name"]: c["long_name"] for c in cols if "long_name" in c}, dict(d.get("attrs", {})))
    names = list(columns if columns is not None else d["columns"])
    return Schema(names, dict(d["dtypes"]), dict(units or {}), dict(long_names or {}), dict(d.get("attrs", {})))


def infer_dtypes(df):
    """A table read without a description (a CSV without its sidecar, a file another program
    wrote): columns of True/False (with missing cells) as nullable booleans, numbers as floats or
    ints, the rest as text; every missing cell NA."""
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
