"""Real units: Scale converts by dimension (values, arrays, columns, tables), bodies are made from
their size, and bad quantities are refused naming the argument."""

import math

import phasekit as pk
from phasekit.core import units

import numpy as np
import pytest

from ..helpers import raises_param

B, G = 0.0215, 9.81  # 21.5 mm, standard gravity: the time unit is sqrt(b/g) seconds
T = math.sqrt(B / G)
NAN, INF = float("nan"), float("inf")


# -- real units ----------------------------------------------------------------------------------
def test_scale_converts_by_dimension():
    """phasekit.Scale against hand conversion: time unit sqrt(b/g), rates, lengths, forces."""
    sc = pk.Scale("21.5 mm", mass="57 g")
    T = math.sqrt(0.0215 / 9.81)
    assert sc.time_unit.to("s").magnitude == pytest.approx(T, rel=1e-14)
    assert sc.dimensionless("30 rev/s") == pytest.approx(30 * 2 * math.pi * T, rel=1e-14)
    assert sc.dimensionless("1800 rpm") == pytest.approx(sc.dimensionless("30 rev/s"), rel=1e-14)
    assert sc.dimensionless("12 ms") == pytest.approx(0.012 / T, rel=1e-14)
    assert sc.dimensionless("0.1 mm") == pytest.approx(0.1 / 21.5, rel=1e-14)
    assert sc.quantity(9.7, "rate").to("rev/s").magnitude == pytest.approx(9.7 / T / (2 * math.pi), rel=1e-14)
    assert sc.quantity(1.0, "force").to("N").magnitude == pytest.approx(0.057 * 9.81, rel=1e-14)
    assert sc.quantity(0.4, "inertia").to("kg*m**2").magnitude == pytest.approx(0.4 * 0.057 * 0.0215**2, rel=1e-14)
    for kind in ("time", "length", "rate", "speed", "energy"):
        q = sc.quantity(0.37, kind)
        assert sc.dimensionless(q, kind) == pytest.approx(0.37, rel=1e-14)


def test_scale_converts_arrays_columns_and_tables():
    import pandas as pd

    sc = pk.Scale("21.5 mm")
    assert f"{sc.time_unit:.4g~P}" == "46.81 ms" and "ms" in repr(sc) and "**" not in repr(sc)
    q = sc.to_real(np.array([0.0, 1.0, 2.0]), "time")
    assert str(q.units) == "ms"
    np.testing.assert_allclose(q.magnitude, np.array([0.0, 1.0, 2.0]) * T * 1e3, rtol=1e-14)
    np.testing.assert_allclose(sc.quantity([1.0, 2.0], "length").to("m").magnitude, [B, 2 * B], rtol=1e-14)
    col = sc.to_real(pd.Series([1.0, 3.0], name="Omega"), "rate")
    assert col.name == "Omega" and col.attrs["unit"] == "rev/s"
    np.testing.assert_allclose(col.to_numpy(), np.array([1.0, 3.0]) / T / (2 * math.pi), rtol=1e-14)
    body = pk.Spheroid(1.5)
    traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.5, omega0=10.5), 3.0)
    df = traj.sample([0.0, 1.5, 3.0])
    real = sc.table(df)
    assert real.attrs["units"]["t"] == "ms" and real.attrs["units"]["X"] == "mm" and real.attrs["units"]["n"] == "rev/s"
    assert real.attrs["units"]["theta"] == "rad" and real.attrs["units"]["R"] == "M g"  # no mass given
    np.testing.assert_allclose(real["gap"], df["gap"] * B * 1e3)
    np.testing.assert_allclose(real["t"], df["t"] * T * 1e3, rtol=1e-14)
    np.testing.assert_array_equal(real["theta"], df["theta"])
    heavy = pk.Scale("21.5 mm", mass="57 g").table(df)
    np.testing.assert_allclose(heavy["R"], df["R"] * 0.057 * G, rtol=1e-12)
    assert heavy.attrs["units"]["R"] == "N"
    with pytest.raises(pk.ParameterError, match="`unit`"):
        sc.to_real(1.0, "time", unit="mm")


def test_bodies_of_a_given_size():
    egg, sc = pk.core.egg_of_size("57 mm", "4.3 cm", w=0.05, mass="57 g")
    assert egg.a == pytest.approx(57 / 43, rel=1e-14) and egg.w == 0.05
    assert sc.b.to("mm").magnitude == pytest.approx(21.5, rel=1e-14)
    top, sc = pk.core.sizes.eccentric_sphere_of_size("15 mm", "4.5 mm", A=0.38, C=0.4)
    assert top.offset == pytest.approx(0.3, rel=1e-14) and (top.A, top.C) == (0.38, 0.4)
    top, sc = pk.core.sizes.eccentric_sphere_of_size("15 mm", "4.5 mm", A="0.38 * 20 g * (15 mm)**2", C=0.4, mass="20 g")
    assert top.A == pytest.approx(0.38, rel=1e-14)


@pytest.mark.parametrize("call, param", [
    (lambda: pk.Scale("3 s"), "b"),
    (lambda: pk.Scale("21.5 mm", g="9.81 m/s"), "g"),
    (lambda: pk.Scale("-1 mm"), "b"),
    (lambda: pk.Scale("21.5 mm").dimensionless("30 Hz"), "value"),  # pint reads 1 Hz as 1 rad/s
    (lambda: pk.Scale("21.5 mm").dimensionless("3 kg", "length"), "value"),  # the value is what does not fit the kind
    (lambda: pk.Scale("21.5 mm").quantity(1.0, "force"), "mass"),
    (lambda: pk.Scale("twenty mm"), "b"),
])
def test_scale_rejects_bad_quantities_by_name(call, param):
    with pytest.raises(pk.ParameterError) as err:
        call()
    assert err.value.param == param


@pytest.mark.parametrize("name, call", [
    ("length", lambda: pk.core.egg_of_size("57 s", "43 mm")),
    ("breadth", lambda: pk.core.egg_of_size("57 mm", "43 rev/s")),
    ("breadth", lambda: pk.core.egg_of_size("57 mm", "-43 mm")),
    ("length", lambda: pk.core.egg_of_size("nan mm", "43 mm")),
    ("length", lambda: pk.core.egg_of_size(57, "43 mm")),
    ("length", lambda: pk.core.egg_of_size("570 mm", "43 mm")),  # aspect ratio out of range
    ("mass", lambda: pk.core.egg_of_size("57 mm", "43 mm", mass="57 mm")),
    ("g", lambda: pk.core.egg_of_size("57 mm", "43 mm", g="9.81 m/s")),
    ("w", lambda: pk.core.egg_of_size("57 mm", "43 mm", w=NAN)),
    ("radius", lambda: pk.core.sizes.eccentric_sphere_of_size("15 s", "3 mm")),
    ("offset", lambda: pk.core.sizes.eccentric_sphere_of_size("15 mm", "3 s")),
    ("offset", lambda: pk.core.sizes.eccentric_sphere_of_size("15 mm", "30 mm")),
    ("A", lambda: pk.core.sizes.eccentric_sphere_of_size("15 mm", "3 mm", A="2 g")),
    ("A", lambda: pk.core.sizes.eccentric_sphere_of_size("15 mm", "3 mm", A=True)),
    ("C", lambda: pk.core.sizes.eccentric_sphere_of_size("15 mm", "3 mm", C=NAN)),
    ("b", lambda: pk.Scale("21.5 s")),
    ("b", lambda: pk.Scale(21.5)),
    ("b", lambda: pk.Scale("0 mm")),
    ("g", lambda: pk.Scale("21.5 mm", g="9.81 m")),
    ("mass", lambda: pk.Scale("21.5 mm", mass="inf g")),
    ("kind", lambda: pk.Scale("21.5 mm").unit("foo")),
    ("kind", lambda: pk.Scale("21.5 mm").unit(["rate"])),
    ("kind", lambda: pk.Scale("21.5 mm").dimensionless("30 rev/s", "foo")),
    ("value", lambda: pk.Scale("21.5 mm").dimensionless("30 rev/s", "speed")),
    ("value", lambda: pk.Scale("21.5 mm").dimensionless("3")),
    ("value", lambda: pk.Scale("21.5 mm").dimensionless("30 Hz")),
    ("value", lambda: pk.Scale("21.5 mm").quantity(NAN, "rate")),
    ("value", lambda: pk.Scale("21.5 mm").quantity("x", "rate")),
    ("default_unit", lambda: units.as_quantity(3, "x", "foo")),
    ("x", lambda: units.as_quantity("3j mm", "x")),
    ("name", lambda: units.as_quantity("3 mm", 5)),
])
def test_units_reject(name, call):
    raises_param(name, call)


def test_units_valid_by_hand():
    sc = pk.Scale("21.5 mm")
    # 30 rev/s in units sqrt(g/b): 30 * 2 pi * sqrt(b/g)
    assert sc.dimensionless("30 rev/s") == pytest.approx(30 * 2 * math.pi * math.sqrt(0.0215 / 9.81), rel=1e-12)
    assert sc.dimensionless("30 rev/s", "rate") == pytest.approx(30 * 2 * math.pi * math.sqrt(0.0215 / 9.81), rel=1e-12)
    assert sc.quantity(1.0, "time").to("s").magnitude == pytest.approx(math.sqrt(0.0215 / 9.81), rel=1e-12)
    egg, sc2 = pk.core.egg_of_size("57 mm", "43 mm", w=0.05, mass="57 g")
    assert egg.a == pytest.approx(57 / 43, rel=1e-14) and sc2.b.to("mm").magnitude == pytest.approx(21.5, rel=1e-14)
    top, sc3 = pk.core.sizes.eccentric_sphere_of_size("15 mm", "3 mm")
    assert top.offset == pytest.approx(0.2, rel=1e-14) and top.A == pytest.approx(0.4 - 0.2**2, rel=1e-14)


# -- units printed simplified --------------------------------------------------------------------
SIZES = ["2.25 mm", "21.5 mm", "0.7 cm", "4.3 cm", "0.0215 m", "1.2 m", "1 inch", "0.85 inch",
         "(2 mm * 8 mm)**0.5", "30 um"]
KIND_NAMES = list(units.KINDS)


@pytest.mark.parametrize("size", SIZES)
def test_every_unit_a_scale_returns_prints_simplified(size):
    """unit, quantity, to_real, time_unit, b, g, mass and repr print one simple unit per kind (the
    kind's display unit, "46.81 ms", "m/s", "rev/s"), never pint's product of roots of the inputs'
    units; the values equal the unsimplified product b^pb g^pg M^pm to 1e-15 relative."""
    ureg = units.units()
    sc = pk.Scale(size, g="981 cm/s**2", mass="0.057 kg")
    b, g, m = ureg.Quantity(size), ureg.Quantity("981 cm/s**2"), ureg.Quantity("0.057 kg")
    printed = [str(sc.b), str(sc.g), str(sc.mass), repr(sc), str(sc.time_unit), f"{sc.time_unit}"]
    for kind in KIND_NAMES:
        pb, pg, pm = units.KINDS[kind][1]
        raw = b**pb * g**pg * m**pm  # pint's unsimplified product of the inputs' units
        for q in (sc.unit(kind), sc.quantity(0.37, kind), sc.quantity([0.37, -2.0], kind), sc.to_real(0.37, kind)):
            assert str(q.units) == f"{ureg.Unit(units.DISPLAY_UNITS[kind]):~P}", (kind, str(q))
            printed.append(str(q))
        assert sc.unit(kind).magnitude == pytest.approx(raw.to(units.DISPLAY_UNITS[kind]).magnitude, rel=1e-15, abs=0)
        assert (sc.quantity(0.37, kind) / (0.37 * raw)).to("dimensionless").magnitude == pytest.approx(1.0, rel=1e-15)
    for p in printed:
        assert "**" not in p and "^" not in p and "sqrt" not in p and "millimeter" not in p, p
    assert str(sc.unit("rate").units) == "rev/s" and str(sc.unit("speed").units) == "m/s"
    assert str(sc.time_unit).endswith(" ms") and str(sc.unit("time")) == str(sc.time_unit)
    real = sc.table(pd_frame())
    assert all("**" not in u for u in real.attrs["units"].values())


def pd_frame():
    import pandas as pd

    return pd.DataFrame({"t": [0.0, 1.0], "Omega": [10.5, 10.4], "U": [0.0, 0.1], "gap": [0.0, 1e-6],
                         "R": [1.0, 0.9], "energy": [3.0, 2.9], "theta": [1.5, 1.4]})


def test_a_2_25_mm_body_has_a_time_unit_of_15_14_ms():
    """b = 2.25 mm: sqrt(b/g) = 15.14 ms, printed so (pint alone prints
    '0.4789 millimeter ** 0.5 * second / meter ** 0.5')."""
    sc = pk.Scale("2.25 mm")
    assert f"{sc.unit('time'):.4g~P}" == "15.14 ms" and str(sc.unit("time").round(2)) == "15.14 ms"
    assert sc.unit("time").to("s").magnitude == pytest.approx(math.sqrt(0.00225 / 9.81), rel=1e-15)
    assert str(sc.unit("rate").round(2)) == "10.51 rev/s"


def test_printed_units_read_back():
    """The short units a Scale prints (and puts in a table's attrs) are units pint parses back,
    to the same quantity."""
    ureg = units.units()
    sc = pk.Scale("21.5 mm", mass="57 g")
    for kind in KIND_NAMES:
        q = sc.quantity(0.37, kind)
        back = ureg.Quantity(str(q))
        assert back.units == q.units and back.magnitude == pytest.approx(q.magnitude, rel=1e-15), str(q)
    for unit in sc.table(pd_frame()).attrs["units"].values():
        if unit in ("", "rad"):
            continue
        assert ureg.Unit(unit).dimensionality in {ureg.get_dimensionality(d) for d, _ in units.KINDS.values()}, unit


# -- the dissipation laws' coefficients ----------------------------------------------------------
def test_scale_converts_the_dissipation_coefficients_by_hand():
    """delta and mu_s are lengths (b); air drag's k1 is in M b^2 sqrt(g/b) (N m s), k2 in M b^2
    (N m s^2), c1 in M sqrt(g/b) (N s/m), c2 in M/b (N s^2/m^2); a power is M g b / sqrt(b/g)."""
    M, b, g = 0.057, 0.0215, 9.81
    sc = pk.Scale("21.5 mm", mass="57 g")
    assert sc.dimensionless("0.2 mm", "rolling_resistance") == pytest.approx(0.2 / 21.5, rel=1e-14)
    assert sc.dimensionless("50 um", "spin_friction") == pytest.approx(0.05 / 21.5, rel=1e-14)
    by_hand = {"air_drag": ("N*m*s", M * b**2 * math.sqrt(g / b)), "air_drag_quadratic": ("N*m*s**2", M * b**2),
               "air_drag_force": ("N*s/m", M * math.sqrt(g / b)), "air_drag_force_quadratic": ("N*s**2/m**2", M / b),
               "power": ("W", M * g * b * math.sqrt(g / b))}
    for kind, (si, unit) in by_hand.items():
        assert sc.unit(kind).to(si).magnitude == pytest.approx(unit, rel=1e-14), kind
        assert sc.dimensionless(f"{2.5 * unit!r} {si}", kind) == pytest.approx(2.5, rel=1e-14), kind
        assert sc.quantity(0.37, kind).to(si).magnitude == pytest.approx(0.37 * unit, rel=1e-14), kind
    assert str(sc.unit("air_drag").units) == "m·N·s" and str(sc.unit("power").units) == "mW"


def test_a_coefficient_of_the_wrong_dimension_or_without_the_mass_is_refused_by_name():
    sc = pk.Scale("21.5 mm")
    err = raises_param("value", lambda: sc.dimensionless("3 s", "spin_friction"))
    assert err.expected.startswith("must be a spin friction (dimension [length]") and "'0.5 mm'" in err.expected
    err = raises_param("value", lambda: sc.dimensionless("1e-7 N*m", "air_drag"))
    assert err.expected.startswith("must be an air drag (")
    err = raises_param("mass", lambda: sc.dimensionless("1e-7 N*m*s", "air_drag"))
    assert "an air drag" in err.expected
    raises_param("mass", lambda: sc.quantity(1.0, "air_drag_force"))
    assert sc.dimensionless("0.43 mm", "rolling_resistance") == sc.dimensionless("0.43 mm", "length")
