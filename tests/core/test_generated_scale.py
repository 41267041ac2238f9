"""Generated cases of real units (Hypothesis, derandomised): Scales of any size, gravity and mass in
any unit pint knows, and every kind of value a Scale converts (numbers, arrays, pandas columns,
sampled tables, quantities typed as text). Each case ends in one of two outcomes:

* a correct conversion: printed in the kind's one simple unit (never pint's product of roots of
  the inputs' units), and back to phasekit's units equal to the input to 1e-12 relative;
* a ParameterError whose one-line message starts with the name of an argument of the call.

Anything else (another exception, a wrong round trip, an unsimplified unit) fails the test."""

import collections
import math

import phasekit as pk
from phasekit.core import units

import numpy as np
import pytest

from ..generated_inputs import fuzz, generated, hang_guard, mostly, report, st, thin_suites, weighted, wrong

COUNTS: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)


@pytest.fixture(scope="module", autouse=True)
def _report():
    """Print the outcome counts (``pytest -s``); every conversion must have valid cases."""
    yield
    report(COUNTS, "generated Scale cases (valid / clear error):", None)
    assert thin_suites(COUNTS) == {}

LENGTH_UNITS = ["mm", "cm", "m", "inch", "um", "km", "ft"]
G_UNITS = ["m/s**2", "cm/s**2", "ft/s**2", "N/kg", "mm/ms**2"]
MASS_UNITS = ["g", "kg", "mg", "lb"]
#: a unit of each kind to type a quantity in, besides its display unit
TYPED_UNITS = {"length": ["mm", "inch", "m"], "time": ["ms", "s", "min"], "rate": ["rev/s", "rpm", "rad/s"],
               "speed": ["m/s", "km/h", "mm/ms"], "acceleration": ["m/s**2", "ft/s**2"], "mass": ["g", "kg"],
               "force": ["N", "mN", "dyn"], "energy": ["mJ", "J", "erg"], "inertia": ["g*cm**2", "kg*m**2"],
               "angular_momentum": ["g*cm**2/s", "kg*m**2/s"]}
BAD_QUANTITIES = ["-1 mm", "0 mm", "3 s", "30 Hz", "nan mm", "inf mm", "1e400 m", "mm", "", "abc", "3j mm",
                  "1e-300 mm", "1e40 m", "5 kg", "[1, 2] mm"]


def magnitudes(lo: float, hi: float):
    """Positive magnitudes over [lo, hi], evenly in the logarithm."""
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda e: float(f"{10 ** e:.6g}"))


def quantity_text(lo, hi, unit_names):
    return st.tuples(magnitudes(lo, hi), st.sampled_from(unit_names)).map(lambda t: f"{t[0]!r} {t[1]}")


def sizes():
    return mostly(quantity_text(1e-3, 1e4, LENGTH_UNITS), st.sampled_from(BAD_QUANTITIES), wrong(), n_good=14)


def gravities():
    return mostly(st.sampled_from([None, "9.81 m/s**2"]) | quantity_text(0.1, 300.0, G_UNITS),
                  st.sampled_from(BAD_QUANTITIES + ["9.81 m/s"]), n_good=14)


def masses():
    return mostly(st.sampled_from([None]) | quantity_text(1e-2, 1e5, MASS_UNITS),
                  st.sampled_from(BAD_QUANTITIES + ["57 mm"]), n_good=14)


def kinds():
    return mostly(st.sampled_from(sorted(units.KINDS)), st.sampled_from(["bogus", "Rate", "", None, ["rate"], 3]),
                  n_good=18)


def numbers():
    """Phasekit values: zero or |x| in [1e-9, 1e6] of either sign (no subnormal end)."""
    return st.one_of(st.just(0.0), st.tuples(magnitudes(1e-9, 1e6), st.booleans()).map(lambda t: -t[0] if t[1] else t[0]))


def values():
    """A number, a list, an array (any shape), a column (pandas Series), or a bad value."""
    good = weighted((numbers(), 3), (st.lists(numbers(), max_size=6), 2),
                    (st.lists(numbers(), min_size=4, max_size=4).map(lambda v: np.array(v).reshape(2, 2)), 1),
                    (st.lists(numbers(), max_size=5).map(lambda v: ("series", v)), 3))
    bad = st.sampled_from([math.nan, math.inf, [1.0, math.nan], "1.5", None, True, ("series", [1.0, math.inf]),
                           1e308, -1e300, 1e-310, [1e-320, 1.0]])
    return mostly(good, bad, n_good=16)


def ops():
    return st.sampled_from(["unit", "quantity", "to_real", "to_real_unit", "dimensionless", "table"])


def scale_or_error(b, g, mass):
    kw = {} if g is None else {"g": g}
    try:
        return pk.Scale(b, mass=mass, **kw)
    except pk.ParameterError as err:
        check_error(err, {"b", "g", "mass"})
        return None


def check_error(err: pk.ParameterError, allowed: set[str]) -> None:
    """A clear error: names an argument of the call, in one line that starts with it."""
    msg = str(err)
    assert err.param in allowed, f"names `{err.param}`, not one of {sorted(allowed)}: {msg}"
    assert msg.startswith(f"`{err.param}` ") and "\n" not in msg and "np.float64" not in msg, msg


def check_simplified(q, kind: str) -> None:
    """Printed in the kind's display unit, in pint's short form, with no root of a unit."""
    want = f"{units.units().Unit(units.DISPLAY_UNITS[kind]):~P}"
    assert str(q.units) == want, (kind, str(q.units))
    text = str(q) + repr(q)
    assert "** 0.5" not in text and "**0.5" not in text and "** 1.5" not in text, text


def back(sc, q, kind: str) -> np.ndarray:
    """A real quantity in phasekit's units again: divided by the kind's unit."""
    return np.asarray((q / sc.unit(kind)).to("dimensionless").magnitude, dtype=float)


def same(x, y) -> None:
    np.testing.assert_allclose(np.asarray(y, dtype=float), np.asarray(x, dtype=float), rtol=1e-12, atol=0)


def convert(sc, op: str, kind, value, typed_unit: str):
    """Run one conversion and check it; return the outcome."""
    import pandas as pd

    series = isinstance(value, tuple) and value[0] == "series"
    x = pd.Series(value[1], dtype=float, name="c") if series else value
    if op == "unit":
        q = sc.unit(kind)
        check_simplified(q, kind)
        assert q.magnitude > 0 and math.isfinite(q.magnitude)
        same(1.0, back(sc, q, kind))
    elif op in ("quantity", "to_real"):
        q = (sc.quantity if op == "quantity" else sc.to_real)(x.to_numpy() if series else x, kind)
        check_simplified(q, kind)
        same(x, back(sc, q, kind))
    elif op == "to_real_unit":  # a unit of the user's choice: theirs, as asked
        q = sc.to_real(x, kind, unit=typed_unit)
        unit = typed_unit
        if series:
            assert q.name == "c" and list(q.index) == list(x.index)
            assert units.units().Unit(q.attrs["unit"]) == units.units().Unit(unit)
            q = units.units().Quantity(q.to_numpy(), q.attrs["unit"])
        same(x, back(sc, q, kind))
    elif op == "dimensionless":  # a quantity typed as text, read back and converted out again
        number = float(x.iloc[0]) if series and len(x) else (x if np.ndim(x) == 0 and not isinstance(x, str) else 1.0)
        y = sc.dimensionless(f"{number!r} {typed_unit}", kind)
        assert isinstance(y, float)
        same(number, sc.quantity(y, kind).to(typed_unit).magnitude)
    else:
        table(sc, x)
    return "valid"


def table(sc, x) -> None:
    """A sampled table's columns converted to their display units (those that need a mass only
    with one), others as they are; each converted column back in phasekit's units."""
    import pandas as pd

    col = np.ravel(np.asarray(x.to_numpy() if hasattr(x, "to_numpy") else x, dtype=object))
    n = len(col)
    df = pd.DataFrame({"t": col, "Omega": col, "gap": col, "R": col, "theta": col, "mode": ["sliding"] * n})
    real = sc.table(df)
    assert real.attrs["units"]["theta"] == "rad" and list(real["mode"]) == ["sliding"] * n
    for name in ("t", "Omega", "gap", "R"):
        kind = units.COLUMN_KINDS[name]
        if kind == "force" and sc.mass is None:
            assert real.attrs["units"][name] == "M g"
            same(df[name].to_numpy(dtype=float), real[name])
            continue
        unit = real.attrs["units"][name]
        assert unit == f"{units.units().Unit(units.DISPLAY_UNITS[kind]):~P}" and "**" not in unit
        same(df[name].to_numpy(dtype=float), back(sc, units.units().Quantity(real[name].to_numpy(), unit), kind))


@hang_guard(600)
@generated(sizes, gravities, masses, kinds, values, ops,
           lambda: st.sampled_from(range(3)), **fuzz(600))
def test_every_conversion_is_right_or_a_named_error(b, g, mass, kind, value, op, which):
    sc = scale_or_error(b, g, mass)
    if sc is None:
        COUNTS["Scale(b, g, mass)"]["error"] += 1
        return
    COUNTS["Scale(b, g, mass)"]["valid"] += 1
    known = isinstance(kind, str) and kind in TYPED_UNITS
    typed_unit = TYPED_UNITS[kind][which % len(TYPED_UNITS[kind])] if known else "mm"
    try:
        COUNTS[f"Scale.{op}"][convert(sc, op, kind, value, typed_unit)] += 1
    except pk.ParameterError as err:
        check_error(err, {"kind", "value", "mass", "unit", "df"})
        if err.param == "mass":
            assert sc.mass is None and units.KINDS[kind][1][2]
        if err.param == "df":
            assert op == "table"
        COUNTS[f"Scale.{op}"]["error"] += 1


@pytest.mark.parametrize("b", ["21.5 mm", "2.15 cm", "0.0215 m", "0.846456693 inch"])
def test_one_body_in_four_units_gives_one_scale(b):
    """The same size typed in mm, cm, m or inch: the same units of every kind, printed alike."""
    ref = pk.Scale("21.5 mm", mass="57 g")
    sc = pk.Scale(b, mass="57 g")
    for kind in units.KINDS:
        assert str(sc.unit(kind).units) == str(ref.unit(kind).units)
        assert sc.unit(kind).magnitude == pytest.approx(ref.unit(kind).magnitude, rel=1e-8)
