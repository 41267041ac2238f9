"""Generated tables through the table writers and readers: frames with columns of floats (NaN,
inf, -0.0, extremes), integers, booleans (with missing cells), text (empty, unicode, quotes,
newlines, NUL), odd column names, units, long names and typed attributes, written as CSV, Parquet
and NetCDF and read back. Every case must end in one of two outcomes:

* ``valid`` - :func:`phasekit.read_table` gives back the very table: values bit for bit, dtypes,
  column order, units, long names and attributes (numbers as numbers, text as text, nested
  structures as they were);
* ``error`` - a one-line ParameterError naming ``df`` (or ``path``) and what the file cannot hold.

Anything else (another exception, a table that comes back changed) fails the test; a hang fails
it by its timeout. Derandomised; ``pytest -s`` prints the counts.
"""

import collections
import json
import os

import phasekit as pk

import numpy as np
import pytest

from ..generated_inputs import SPECIAL, fuzz, generated, hang_guard, mostly, report, st, weighted

pytest.importorskip("pyarrow")
pytest.importorskip("xarray")
pytest.importorskip("h5netcdf")

COUNTS: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
FORMATS = (".csv", ".parquet", ".nc")


@pytest.fixture(scope="module", autouse=True)
def _report():
    yield
    path = os.environ.get("PHASEKIT_FUZZ_REPORT")
    if path:
        path = path + ".tables.json" if not path.endswith(".json") else path.replace(".json", ".tables.json")
    report(COUNTS, "generated tables (faithful round trip / clear error):", path)


# -- strategies ------------------------------------------------------------------------------------

ODD_NAMES = ["a b", "é", "x.y", "1", "_x", "t", "row", "row_", "a,b", 'q"q', "#c", " lead", "trail ", "tab\t",
             "new\nline", "Unnamed: 0", "ü/ö", "a:b", "NaN", "True"]
BAD_NAMES = ["", 5, None, ".", "cr\r", "nul\x00", "\ud800"]
ODD_TEXT = ["", " ", "a,b", 'say "hi"', "line\nbreak", "cr\rlf", "nul\x00", "é€😀", "True", "False", "1.5", "nan",
            "NA", "None", "#", "  padded  "]


def floats():
    return st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(SPECIAL))


def texts():
    return weighted((st.text(min_size=1, max_size=6), 6), (st.sampled_from(ODD_TEXT), 2), (st.none(), 2),
                    (st.just(""), 1))


def columns(n):
    """(dtype, values) of one column of ``n`` rows; rarely of a dtype no file holds."""
    import pandas as pd

    kinds = {
        "float64": st.lists(floats(), min_size=n, max_size=n).map(lambda v: np.array(v, dtype="float64")),
        "float32": st.lists(st.floats(width=32, allow_nan=True, allow_infinity=True), min_size=n, max_size=n)
        .map(lambda v: np.array(v, dtype="float32")),
        "int64": st.lists(st.integers(-(2**63), 2**63 - 1), min_size=n, max_size=n)
        .map(lambda v: np.array(v, dtype="int64")),
        "int8": st.lists(st.integers(-128, 127), min_size=n, max_size=n).map(lambda v: np.array(v, dtype="int8")),
        "uint64": st.lists(st.integers(0, 2**64 - 1), min_size=n, max_size=n).map(lambda v: np.array(v, dtype="uint64")),
        "bool": st.lists(st.booleans(), min_size=n, max_size=n).map(lambda v: np.array(v, dtype=bool)),
        "boolean": st.lists(st.one_of(st.booleans(), st.none()), min_size=n, max_size=n)
        .map(lambda v: pd.array(v, dtype="boolean")),
        "Int64": st.lists(st.one_of(st.integers(-(2**63), 2**63 - 1), st.none()), min_size=n, max_size=n)
        .map(lambda v: pd.array(v, dtype="Int64")),
        "str": st.lists(texts(), min_size=n, max_size=n).map(lambda v: pd.array(v, dtype="str")),
        "object": st.lists(texts(), min_size=n, max_size=n).map(lambda v: pd.Series(v, dtype=object).to_numpy()),
    }
    bad = st.sampled_from(["complex", "datetime", "mixed"]).map(lambda k: {
        "complex": np.full(n, 1 + 2j), "datetime": pd.date_range("2020", periods=n).to_numpy(),
        "mixed": np.array([1, "a"] * n, dtype=object)[:n] if n else np.array([1.5], dtype=object)[:0]}[k])
    good = st.sampled_from(sorted(kinds)).flatmap(lambda k: kinds[k])
    return mostly(good, bad, n_good=40)


def attr_values():
    scalars = st.one_of(st.none(), st.booleans(), st.integers(-(2**70), 2**70), floats(), texts().filter(bool),
                        st.sampled_from(["", "nul\x00", "é"]))
    return st.recursive(scalars, lambda inner: st.one_of(st.lists(inner, max_size=3),
                                                         st.dictionaries(st.text(max_size=4), inner, max_size=3)),
                        max_leaves=8)


def attr_keys():
    return mostly(st.sampled_from(["status", "t_jump", "run", "a b", "_hidden", "phasekit_json", "n", "title"]),
                  st.text(max_size=5), st.sampled_from([3, ("a",)]), n_good=30)


def frames():
    return st.composite(_frame)()


def _frame(draw):
    import pandas as pd

    n = draw(st.integers(0, 5))
    k = draw(weighted((st.integers(1, 5), 20), (st.just(0), 1)))
    names = draw(st.lists(mostly(st.sampled_from(ODD_NAMES), st.text(min_size=1, max_size=5),
                                 st.sampled_from(BAD_NAMES), n_good=30), min_size=k, max_size=k, unique_by=repr))
    if k and draw(st.booleans()):
        names = [f"c{i}" for i in range(k)]
    if k and draw(st.booleans()):  # a sampled run's table starts with its times
        names = ["t", *[c for c in names[1:] if c != "t"]]
        names += [f"d{i}" for i in range(k - len(names))]
    if k > 1 and draw(st.integers(0, 30)) == 0:
        names[-1] = names[0]
    data = [draw(columns(n)) for _ in range(k)]
    df = pd.DataFrame(dict(zip(range(k), data)), index=pd.RangeIndex(n))
    df.columns = pd.Index(names, dtype=object)
    attrs = draw(st.dictionaries(attr_keys(), attr_values(), max_size=4))
    named = [c for c in dict.fromkeys(names) if isinstance(c, str)]
    for key in ("units", "long_names"):
        if named and draw(st.booleans()):
            per = draw(st.dictionaries(st.sampled_from(named), st.sampled_from(["ms", "mm", "rev/s", "", "cm²·g", "1"]),
                                       min_size=1))
            attrs[key] = draw(mostly(st.just(per), st.just({**per, "not a column": "s"}), st.just("mm"),
                                     st.just({named[0]: 1.5}), n_good=12))
    df.attrs = attrs
    return df


# -- the check -------------------------------------------------------------------------------------


def _plain(obj):
    """JSON of the attributes as a table should give them back (tuples as lists), NaN and -0.0
    kept apart from other values."""
    return json.dumps(obj, sort_keys=True, default=lambda o: o.item() if hasattr(o, "item") else repr(o))


def _same_values(a, b, name) -> None:
    import pandas as pd

    assert str(a.dtype) == str(b.dtype), (name, a.dtype, b.dtype)
    na, nb = pd.isna(a).to_numpy(dtype=bool), pd.isna(b).to_numpy(dtype=bool)
    assert np.array_equal(na, nb), name
    x, y = a[~na].to_numpy(), b[~nb].to_numpy()
    if a.dtype.kind == "f":  # bit for bit: -0.0 is not 0.0, every NaN is missing
        assert np.array_equal(x.view(f"u{x.dtype.itemsize}"), y.view(f"u{y.dtype.itemsize}")), name
    else:
        assert list(x) == list(y), name


def round_trip(df, suffix, tmp_path):
    """'valid' or 'error' (asserting what each must be)."""
    path = tmp_path / f"table{suffix}"
    expected_attrs = json.loads(_plain(df.attrs)) if all(isinstance(k, str) for k in df.attrs) else None
    try:
        pk.write_table(df, path)
    except pk.ParameterError as exc:
        msg = str(exc)
        assert exc.param in ("df", "path") and msg.startswith(f"`{exc.param}` ") and "\n" not in msg, msg
        assert not path.exists() and not any(p.name.startswith(".") for p in tmp_path.iterdir()), msg
        return "error"
    back = pk.read_table(path)
    assert list(back.columns) == list(df.columns)
    assert isinstance(back.index, type(df.index)) and len(back) == len(df)
    for name in df.columns:
        _same_values(df[name], back[name], name)
    assert _plain(back.attrs) == _plain(expected_attrs), (back.attrs, df.attrs)
    return "valid"


@hang_guard(900)
@pytest.mark.parametrize("suffix", FORMATS)
@generated(frames, lambda: weighted((st.just(None), 30), (st.sampled_from([".xlsx", ".CSV.gz", ""]), 1)), **fuzz(150))
def test_tables_round_trip_or_are_refused(tmp_path_factory, suffix, df, wrong_suffix):
    outcome = round_trip(df, suffix if wrong_suffix is None else wrong_suffix, tmp_path_factory.mktemp("t"))
    COUNTS[f"table {suffix}"][outcome] += 1


def test_the_suite_reaches_both_outcomes_in_every_format():
    """Run after the generated suite (same module): each format both gave tables back and
    refused some, so that neither outcome is vacuous."""
    if not COUNTS:
        pytest.skip("the generated suite did not run")
    for suffix in FORMATS:
        c = COUNTS[f"table {suffix}"]
        assert c["valid"] >= 0.4 * sum(c.values()) and c["error"] >= 3, (suffix, dict(c))
