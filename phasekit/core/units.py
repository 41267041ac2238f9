"""Real units: millimetres, grams, revolutions per second in and out, by pint.

phasekit computes in the paper's units: mass M, length b (the equatorial radius of a spheroid or egg, the
radius of a tippe top's ball), acceleration g, hence time sqrt(b/g), rates sqrt(g/b), speeds sqrt(g b), forces
M g, energies M g b, moments of inertia M b^2, and the dissipation laws' coefficients (lengths b; air drag in
M, b, g). A :class:`Scale` holds b, g (and M for forces, energies and drag) as pint quantities and converts
both ways by dimensional analysis, so that a user never converts by hand::

    sc = pk.Scale("21.5 mm")                  # g = 9.81 m/s^2
    sc.dimensionless("30 rev/s")              # -> 8.82..., a spin in units sqrt(g/b)
    sc.quantity(9.7, "rate").to("rev/s")      # -> 33.0... rev/s
    sc.to_real(traj.sample(ts)["t"], "time")  # a column (or any array) in ms
    sc.table(traj.sample(ts))                 # a whole sampled table in ms, mm, rev/s, m/s
    egg, sc = pk.core.egg_of_size("57 mm", "43 mm", w=0.05, mass="57 g")

Every quantity a Scale returns is in one simple unit per kind (:data:`DISPLAY_UNITS`: ms, mm,
rev/s, ...), never in pint's unsimplified product of the inputs' units (``mm ** 0.5 * s / m ** 0.5``),
and prints in pint's short form ("46.81 ms", "m/s²", "cm²·g"), which pint also reads back.

Angles: pint takes the radian as dimensionless, so 1 rev/s = 2 pi rad/s = 2 pi (1/s). A rate in hertz is
refused: pint converts 1 Hz to 1 rad/s, which is a factor 2 pi away from one revolution per second; write
"rev/s" (or "rps", "rpm", "rad/s"). pint is imported on first use (building its registry takes ~0.6 s),
not with phasekit.
"""

from __future__ import annotations

import functools
import math
import re

import numpy as np

from .._runtime.validate import check_array, check_finite
from ..errors import ParameterError

#: g used unless another is given (the value the issue and most experiments quote)
STANDARD_GRAVITY = "9.81 m/s**2"

#: kinds of quantity and their unit in phasekit: (pint dimensionality, factor as powers of (b, g, M))
KINDS = {
    "length": ("[length]", (1, 0, 0)), "time": ("[time]", (0.5, -0.5, 0)), "rate": ("1 / [time]", (-0.5, 0.5, 0)),
    "speed": ("[length] / [time]", (0.5, 0.5, 0)), "acceleration": ("[length] / [time] ** 2", (0, 1, 0)),
    "mass": ("[mass]", (0, 0, 1)), "force": ("[mass] * [length] / [time] ** 2", (0, 1, 1)),
    "energy": ("[length] ** 2 * [mass] / [time] ** 2", (1, 1, 1)), "inertia": ("[length] ** 2 * [mass]", (2, 0, 1)),
    "angular_momentum": ("[length] ** 2 * [mass] / [time]", (1.5, 0.5, 1)),
    "power": ("[length] ** 2 * [mass] / [time] ** 3", (0.5, 1.5, 1)),
    # the coefficients of the dissipation laws (phasekit.friction.dissipation): delta and mu_s are
    # lengths; air drag's couple per rate (k1, as the air layer's k) and per rate squared (k2), force per speed (c1, c2)
    "rolling_resistance": ("[length]", (1, 0, 0)), "spin_friction": ("[length]", (1, 0, 0)), "patch": ("[length]", (1, 0, 0)),
    "air_drag": ("[length] ** 2 * [mass] / [time]", (1.5, 0.5, 1)), "air_layer": ("[length] ** 2 * [mass] / [time]", (1.5, 0.5, 1)),
    "air_drag_quadratic": ("[length] ** 2 * [mass]", (2, 0, 1)),
    "air_drag_force": ("[mass] / [time]", (-0.5, 0.5, 1)), "air_drag_force_quadratic": ("[mass] / [length]", (-1, 0, 1)),
}
#: the unit each kind is shown in (times of a spinning body are milliseconds, its size millimetres,
#: its spin revolutions per second: the units experiments quote)
DISPLAY_UNITS = {"length": "mm", "time": "ms", "rate": "rev/s", "speed": "m/s", "acceleration": "m/s**2", "mass": "g",
                 "force": "N", "energy": "mJ", "inertia": "g*cm**2", "angular_momentum": "g*cm**2/s", "power": "mW",
                 "rolling_resistance": "mm", "spin_friction": "mm", "patch": "mm", "air_drag": "N*m*s", "air_layer": "N*m*s", "air_drag_quadratic": "N*m*s**2",
                 "air_drag_force": "N*s/m", "air_drag_force_quadratic": "N*s**2/m**2"}
#: the kind of each column of a sampled table (Trajectory.sample); angles stay in radians and
#: columns not listed (mode) are left as they are
COLUMN_KINDS = {"t": "time", "U": "speed", "V": "speed", "slip": "speed", "Omega": "rate", "Lambda": "rate",
                "n": "rate", "X": "length", "Y": "length", "X_P": "length", "Y_P": "length", "h": "length",
                "gap": "length", "t_jump": "time", "t_end": "time", "t_flight": "time", "longest_flight": "time",
                "gap_max": "length", "R": "force", "R_min": "force", "energy": "energy", "jellett": "angular_momentum",
                "L_Z": "angular_momentum"}
#: each kind named with its article, for the messages ("an air drag")
NAMED = {k: f"{'an' if k[0] in 'aeiou' else 'a'} {k.replace('_', ' ')}" for k in KINDS}
#: an example of each kind, for the messages
EXAMPLES = {"length": "21.5 mm", "time": "12 ms", "rate": "30 rev/s", "speed": "0.5 m/s", "acceleration": "9.81 m/s**2",
            "mass": "57 g", "force": "0.5 N", "energy": "1 mJ", "inertia": "2 g*cm**2", "angular_momentum": "1e-4 kg*m**2/s",
            "power": "1 mW", "rolling_resistance": "0.2 mm", "spin_friction": "0.5 mm", "patch": "0.1 mm", "air_drag": "1e-7 N*m*s", "air_layer": "1e-9 N*m*s",
            "air_drag_quadratic": "1e-9 N*m*s**2", "air_drag_force": "1e-4 N*s/m",
            "air_drag_force_quadratic": "1e-3 N*s**2/m**2"}


@functools.lru_cache(maxsize=1)
def units():
    """phasekit's pint UnitRegistry (built once, on first use)."""
    import pint

    ureg = pint.UnitRegistry()
    ureg.define("rev = revolution")  # "30 rev/s", as people write it
    # print "46.81 ms", not "46.81 millisecond": the symbols people write (and pint parses back)
    ureg.formatter.default_format = "~P"
    return ureg


def is_number(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))


def _is_unit(text: str) -> bool:
    """Is ``text`` a unit with no number ("mm", "m/s**2", ""), which pint would read as one of it?"""
    if re.search(r"\d", re.sub(r"(\*\*|\^)\s*[-+]?[\d.]+", "", text)):
        return False  # a number outside the exponents
    try:
        units().Unit(text)
    except Exception:
        return False
    return True


def as_quantity(value, name: str, default_unit: str | None = None):
    """A pint Quantity from a Quantity, a string such as "21.5 mm", or a number in
    ``default_unit``. ParameterError naming ``name`` if it does not parse, is a unit with no
    number ("mm"), is not one finite real number, or is in hertz."""
    import pint

    if not isinstance(name, str) or not name:
        raise ParameterError("name", "must be the name of the quantity (a non-empty string)", name)
    ureg = units()
    if default_unit is not None:
        try:
            ureg.Unit(default_unit if isinstance(default_unit, str) else None)
        except Exception:
            raise ParameterError("default_unit", "must be a unit such as 'mm' or 'rev/s' (or None)", default_unit) from None
    if isinstance(value, pint.Quantity):
        try:
            q = value if value._REGISTRY is ureg else ureg.Quantity(value.magnitude, str(value.units))
        except Exception:
            raise ParameterError(name, "must be a quantity in units phasekit's pint registry knows", str(value)) from None
    elif isinstance(value, str):
        if _is_unit(value):  # pint reads "mm" as 1 mm: a unit alone is no value
            raise ParameterError(name, "must be a number with units, such as '21.5 mm' (a unit alone is no value)",
                                 value)
        try:
            q = ureg.Quantity(value)
        except Exception:
            raise ParameterError(name, "must be a quantity such as '21.5 mm' or '30 rev/s'", value) from None
    elif is_number(value) and default_unit is not None:
        q = ureg.Quantity(float(value), default_unit)
    else:
        expected = "must be a pint Quantity or a string with units such as '21.5 mm'"
        raise ParameterError(name, expected + (f" (or a number in {default_unit})" if default_unit else ""), value)
    if not is_number(q.magnitude):
        raise ParameterError(name, "must be one real number with units, such as '21.5 mm'", str(q))
    if not math.isfinite(float(q.magnitude)):
        raise ParameterError(name, "must be finite", value if isinstance(value, str) else str(q))
    if "hertz" in str(q.units) or "Hz" in str(q.units):
        raise ParameterError(name, "must not be in hertz (pint reads 1 Hz as 1 rad/s): use rev/s, rpm or rad/s", value)
    return q


def of_kind(value, name: str, kind: str, *, positive: bool = False):
    """as_quantity, then a check of its dimension (that of ``kind``) and sign."""
    q = as_quantity(value, name)
    dim = KINDS[kind][0]
    typed = value if isinstance(value, str) else str(q)  # the value as the user wrote it
    if q.dimensionality != units().get_dimensionality(dim):
        raise ParameterError(name, f"must be {NAMED[kind]} (dimension {dim}, e.g. "
                                   f"'{EXAMPLES[kind]}'), not of dimension {q.dimensionality}", typed)
    if positive and not q.magnitude > 0:
        raise ParameterError(name, "must be > 0", typed)
    return q


#: the sizes, accelerations and masses a Scale takes, in SI units: wide enough for any body, narrow
#: enough that every unit derived from them (up to M b^2) is a normal float
SCALE_RANGE = (1e-30, 1e30)


def _scale_of(value, name: str, kind: str, si: str):
    """One scale of a Scale: a quantity of ``kind`` > 0 within :data:`SCALE_RANGE` (in ``si``),
    in its own unit if that is one unit per dimension with whole powers ("21.5 mm", "9.81 m/s**2"),
    else in the kind's display unit ("(2 mm * 8 mm)**0.5" -> 4 mm)."""
    q = of_kind(value, name, kind, positive=True)
    if not SCALE_RANGE[0] <= float(q.to(si).magnitude) <= SCALE_RANGE[1]:
        raise ParameterError(name, f"must lie between {SCALE_RANGE[0]:g} and {SCALE_RANGE[1]:g} {si}",
                             value if isinstance(value, str) else str(q))
    powers = dict(q._units).values()
    simple = len(powers) <= len(units().get_dimensionality(KINDS[kind][0])) and all(float(p).is_integer() for p in powers)
    return q if simple else q.to(DISPLAY_UNITS[kind])


def _representable(q, value, name: str, where: str):
    """``q`` (``value`` converted) if its magnitudes are finite and no nonzero value became
    subnormal or zero: a conversion that overflows or underflows is refused, not returned wrong."""
    mag, value = np.asarray(q.magnitude, dtype=float), np.asarray(value, dtype=float)
    with np.errstate(invalid="ignore"):
        if np.any(np.isinf(mag) & np.isfinite(value)):
            raise ParameterError(name, f"is too large to express {where}", show_value=False)
        if np.any((np.abs(mag) < np.finfo(float).tiny) & (value != 0) & np.isfinite(value)):
            raise ParameterError(name, f"is too small to express {where}", show_value=False)
    return q


def _check_kind(kind, name: str = "kind") -> str:
    if not isinstance(kind, str) or kind not in KINDS:
        raise ParameterError(name, f"must be one of {', '.join(KINDS)}", kind)
    return kind


class Scale:
    """The dimensional scales of one body: length b, gravity g and (optionally) mass M.

    Parameters
    ----------
    b : quantity
        The unit of length: the equatorial radius (spheroid, egg: half the maximum breadth)
        or the ball's radius (tippe top). A pint Quantity or a string ("21.5 mm").
    g : quantity
        Gravity, default 9.81 m/s^2.
    mass : quantity, optional
        The body's mass, needed only for forces, energies, powers, moments of inertia and drag.

    Attributes
    ----------
    b, g, mass : Quantity
        The scales as given (in their own unit when it is a simple one, such as "21.5 mm",
        else in the kind's :data:`DISPLAY_UNITS` entry); ``mass`` is None when not given.
    time_unit : Quantity
        sqrt(b/g), phasekit's unit of time, in milliseconds.

    Raises
    ------
    ParameterError
        If ``b`` is not a length > 0, ``g`` not an acceleration > 0 or ``mass`` (when given)
        not a mass > 0: a quantity that does not parse, is not one finite real number, is in
        hertz or has another dimension; or if one lies outside :data:`SCALE_RANGE` (1e-30 to
        1e30 in SI units).

    Examples
    --------
    >>> import phasekit as pk
    >>> sc = pk.Scale('21.5 mm')
    >>> str(sc.quantity(1.0, 'time').round(2))
    '46.81 ms'
    >>> str(sc.unit('speed').round(4))
    '0.4593 m/s'
    >>> round(sc.dimensionless('50 rev/s'), 4)
    14.7074
    """

    def __init__(self, b, g=STANDARD_GRAVITY, mass=None):
        self.b = _scale_of(b, "b", "length", "m")
        self.g = _scale_of(g, "g", "acceleration", "m/s**2")
        self.mass = None if mass is None else _scale_of(mass, "mass", "mass", "kg")
        self.time_unit = self.unit("time")

    def unit(self, kind: str):
        """phasekit's unit of ``kind`` as a Quantity.

        Parameters
        ----------
        kind : str
            A key of :data:`KINDS`: "length", "time", "rate", ..., "energy", "power", and the
            dissipation laws' coefficients ("rolling_resistance", "spin_friction", "air_drag", ...).

        Returns
        -------
        pint.Quantity
            The unit, a product of powers of b, g and M (e.g. sqrt(b/g) for "time"), in the
            kind's :data:`DISPLAY_UNITS` entry (e.g. ms).

        Raises
        ------
        ParameterError
            If ``kind`` is not a key of :data:`KINDS`, or the kind involves the mass and the
            Scale has none.
        """
        _check_kind(kind)
        pb, pg, pm = KINDS[kind][1]
        if pm and self.mass is None:
            raise ParameterError("mass", f"is needed for {NAMED[kind]} (give Scale(..., mass=...))", show_value=False)
        q = self.b**pb * self.g**pg
        return (q * self.mass**pm if pm else q).to(DISPLAY_UNITS[kind])

    def quantity(self, value, kind: str):
        """A phasekit (dimensionless) value, or an array of them, as a Quantity of ``kind``, in
        the kind's :data:`DISPLAY_UNITS` entry (ms, mm, rev/s, ...).

        Parameters
        ----------
        value : float or array_like
            Finite values in phasekit's units (an empty array is allowed).
        kind : str
            A key of :data:`KINDS` ("time", "rate", "length", ...).

        Returns
        -------
        pint.Quantity
            ``value`` times the unit of ``kind``, in the kind's display unit.

        Raises
        ------
        ParameterError
            If ``value`` is not finite real numbers (or too large to express in real units),
            ``kind`` is not a key of :data:`KINDS`, or the kind involves the mass and the
            Scale has none.
        """
        value = check_finite("value", value) if np.ndim(value) == 0 else check_array("value", value, allow_empty=True)
        return _representable(value * self.unit(kind), value, "value", f"in {_unit_text(DISPLAY_UNITS[kind])}")

    def to_real(self, value, kind: str, unit: str | None = None):
        """phasekit values in real units: a number or array gives a Quantity in ``unit``
        (default the kind's :data:`DISPLAY_UNITS` entry, e.g. ms); a pandas Series gives a
        Series of the magnitudes (same name and index) with ``attrs["unit"]`` set.

        Parameters
        ----------
        value : float, array_like or pandas.Series
            Finite values in phasekit's units.
        kind : str
            A key of :data:`KINDS` ("time", "rate", "length", ...).
        unit : str, optional
            A unit of that kind's dimension, e.g. "ms" or "s" for a time.

        Returns
        -------
        pint.Quantity or pandas.Series
            The values in ``unit``: a Quantity, or for a Series a Series of the magnitudes.

        Raises
        ------
        ParameterError
            If ``kind`` is not a key of :data:`KINDS`, ``unit`` is not a unit of its
            dimension, ``value`` is not finite real numbers (or too large to express in
            ``unit``), or the kind involves the mass and the Scale has none.

        Examples
        --------
        >>> import phasekit as pk
        >>> print(f"{pk.Scale('21.5 mm').to_real(2.0, 'time'):.5~P}")
        93.63 ms
        """
        unit = self._display(_check_kind(kind), unit)
        if hasattr(value, "to_numpy") and hasattr(value, "index") and not hasattr(value, "columns"):
            out = value.copy()
            values = value.to_numpy(dtype=float)
            out[:] = _representable(self.quantity(values, kind).to(unit), values, "value", f"in {_unit_text(unit)}").magnitude
            out.attrs["unit"] = _unit_text(unit)
            return out
        return _representable(self.quantity(value, kind).to(unit), value, "value", f"in {_unit_text(unit)}")

    def flight(self, flight) -> dict:
        """A flight (:class:`phasekit.core.Flight`) in real units, as numbers: ``t_liftoff``,
        ``t_touchdown``, ``duration`` and ``t_gap_max`` in ms, ``gap_max`` in mm (each as
        :meth:`to_real` gives it; None where the flight has none: no touchdown, no located
        maximum), and ``theta_liftoff``, the axis angle at lift-off in radians.

        Parameters
        ----------
        flight : Flight
            One flight of a run, e.g. ``traj.flights[0]``.

        Returns
        -------
        dict
            The keys ``t_liftoff``, ``t_touchdown``, ``duration``, ``t_gap_max``, ``gap_max``
            and ``theta_liftoff``, as floats or None.

        Examples
        --------
        >>> import numpy as np, phasekit as pk
        >>> egg, sc = pk.core.egg_of_size("57 mm", "43 mm")
        >>> y0 = pk.gyroscopic_start(egg, np.pi / 2 - 0.01, omega0=sc.dimensionless("50 rev/s"))
        >>> r = pk.simulate(pk.Model(egg, pk.Coulomb(0.1)), y0, 400.0, stop_at="touchdown")
        >>> f = sc.flight(r.flights[0])
        >>> round(f["duration"], 1), round(f["gap_max"] * 1e3, 1)  # ms, micrometres
        (8.2, 16.4)
        """
        from .starts import to_paper

        def real(x, kind):
            return None if x is None else float(self.to_real(x, kind).magnitude)

        done = flight.t_touchdown is not None
        return {"t_liftoff": real(flight.t_liftoff, "time"), "t_touchdown": real(flight.t_touchdown, "time"),
                "duration": real(flight.t_touchdown - flight.t_liftoff, "time") if done else None,
                "gap_max": real(flight.gap_max, "length"), "t_gap_max": real(flight.t_gap_max, "time"),
                "theta_liftoff": float(to_paper("vector", flight.x_liftoff[:8])[4])}

    def table(self, df):
        """A sampled table (:meth:`phasekit.core.Trajectory.sample`, a section, any DataFrame with
        those column names) in real units: each column of :data:`COLUMN_KINDS` converted to its
        display unit, angles in radians, other columns as they are; ``attrs["units"]`` maps
        each column to its unit (forces, energies and angular momenta need the Scale's mass:
        without it they stay in units of M g, M g b and M sqrt(g b^3)).

        Parameters
        ----------
        df : pandas.DataFrame
            The table in phasekit's units, e.g. ``traj.sample(times)``.

        Returns
        -------
        pandas.DataFrame
            A copy in real units, with ``attrs["units"]`` mapping each column to its unit.

        Raises
        ------
        ParameterError
            If ``df`` is not a DataFrame, or a column to convert does not hold numbers or
            holds one too large to express in real units. Missing values (NaN) stay missing.
        """
        if not (hasattr(df, "columns") and hasattr(df, "copy")):
            raise ParameterError("df", "must be a pandas DataFrame such as traj.sample(times)", type(df).__name__)
        out, units_of = df.copy(), {}
        for col in df.columns:
            kind = COLUMN_KINDS.get(col)
            if kind is None or KINDS[kind][1][2] and self.mass is None:
                units_of[col] = {"theta": "rad", "theta_end": "rad", "psi": "rad", "phi": "rad", "R": "M g", "R_min": "M g",
                                 "energy": "M g b", "jellett": "M sqrt(g b^3)", "L_Z": "M sqrt(g b^3)"}.get(col, "")
                continue
            try:
                values = df[col].to_numpy(dtype=float)
            except (TypeError, ValueError):
                raise ParameterError("df", f"column {col!r} must hold numbers (a {kind} in phasekit's units)",
                                     show_value=False) from None
            with np.errstate(over="ignore", under="ignore", invalid="ignore"):  # a missing value (NaN) stays missing
                real = self.unit(kind) * values
            try:
                out[col] = _representable(real, values, "df", f"in {_unit_text(DISPLAY_UNITS[kind])}").magnitude
            except ParameterError as err:
                raise ParameterError("df", f"column {col!r} {err.expected}", show_value=False) from None
            units_of[col] = _unit_text(DISPLAY_UNITS[kind])
        out.attrs["units"] = units_of
        return out

    @staticmethod
    def _display(kind: str, unit) -> str:
        if unit is None:
            return DISPLAY_UNITS[kind]
        try:
            want = units().get_dimensionality(KINDS[kind][0])
            ok = isinstance(unit, str) and units().Unit(unit).dimensionality == want
        except Exception:
            ok = False
        if not ok:
            raise ParameterError("unit", f"must be a unit of {kind.replace('_', ' ')} such as "
                                         f"'{DISPLAY_UNITS[kind]}'", unit)
        return unit

    def dimensionless(self, value, kind: str | None = None) -> float:
        """A quantity (Quantity or string such as "30 rev/s", "57 mm", "12 ms") in phasekit's
        units; its kind is read from its dimensionality (or checked against ``kind``).

        Parameters
        ----------
        value : pint.Quantity or str
            One finite quantity with units, e.g. "30 rev/s" (not in hertz).
        kind : str, optional
            A key of :data:`KINDS` that the quantity must be of.

        Returns
        -------
        float
            The value in phasekit's units of its kind.

        Raises
        ------
        ParameterError
            If ``value`` does not parse, is not one finite real number with units, is in
            hertz, has the dimension of no kind (or not that of ``kind``), its kind involves
            the mass and the Scale has none, or it is too large to express in phasekit's
            units; or if ``kind`` is not a key of :data:`KINDS`.
        """
        return self._dimensionless(value, None if kind is None else _check_kind(kind), "value")

    def _dimensionless(self, value, kind: str | None, name: str) -> float:
        q = as_quantity(value, name)
        dims = {k: units().get_dimensionality(d) for k, (d, _) in KINDS.items()}
        found = [k for k, d in dims.items() if d == q.dimensionality]
        typed = value if isinstance(value, str) else str(q)  # the value as the user wrote it
        if not found:
            raise ParameterError(name, f"must have the dimension of one of {', '.join(KINDS)} (it has {q.dimensionality})",
                                 typed)
        if kind is not None and kind not in found:
            raise ParameterError(name, f"must be {NAMED[kind]} (dimension {KINDS[kind][0]}, e.g. "
                                       f"'{EXAMPLES[kind]}')", typed)
        with np.errstate(over="ignore", under="ignore"):
            out = float((q / self.unit(kind or found[0])).to("dimensionless").magnitude)
        _representable(units().Quantity(out), float(q.magnitude), name, "in phasekit's units")
        return out

    def __repr__(self) -> str:
        m = f", mass={self.mass:~P}" if self.mass is not None else ""
        return f"Scale(b={self.b:~P}, g={self.g:~P}{m}; time unit {self.time_unit:.4g~P})"


def _unit_text(unit: str) -> str:
    """A unit as people write it: 'ms', 'mm', 'rev/s', 'cm²·g'."""
    return f"{units().Unit(unit):~P}"
