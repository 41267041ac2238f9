"""A command's inputs from its parsed arguments: the body, the friction law, values typed with
units, the start of a run and where the body stands on the table.

Each check refuses with a :class:`~phasekit.cli.parser.UsageError` naming the flag typed.
"""

from __future__ import annotations

import math
import re
import warnings

from .flags import FLAGS
from .options import DISSIPATION_FLAGS, WithUnits
from .parser import UsageError

#: the smallest --A and --C, units M b^2 (a body's own are ~0.1-0.5): rates of order 1/C follow
#: from smaller ones, and the steady states' residuals grow as 1/C^2 (measured: 4e-8 at C = 1e-9,
#: 4e+283 and an overflow at C = 1e-300), beyond what double precision resolves
MOMENT_MIN = 1e-6


#: the bodies whose --radius is the unit of length, and what it is for each
RADIUS_OF = {"disk": "the disk's radius", "cone": "the cone's base radius"}


def _make_body(args, A=None, C=None):
    """The body of --body: the library's built-in ones (phasekit.bodies.by_name.make_body) and the
    cone (--height, --on), whose flags are refused on another body."""
    from .._runtime.validate import check_choice
    from ..bodies.by_name import BODIES, make_body
    from ..bodies.cone import Cone
    from ..errors import ParameterError

    check_choice("body", args.body, tuple(dict.fromkeys((*BODIES, "cone"))))
    if args.body == "cone":
        for name in ("a", "offset", "w", "thickness", "flat_angle", "stem_length", "stem_radius"):
            if getattr(args, name, None) is not None:
                raise ParameterError(name, "does not apply to the cone body (its parameters: height, on)",
                                     getattr(args, name))
        return Cone(1.0 if args.height is None else args.height, "rim" if args.on is None else args.on, A=A, C=C)
    for name in ("height", "on"):
        if getattr(args, name, None) is not None:
            raise ParameterError(name, f"does not apply to the {args.body} body (it is the cone's: --body cone)",
                                 getattr(args, name))
    stem = {"stem_length": getattr(args, "stem_length", None), "stem_radius": getattr(args, "stem_radius", None)}
    if args.body == "tippe-top":  # the toy, with its stem (bodies.compound); --stem-length 0: the ball alone
        stem = _stem(**stem)
    return make_body(args.body, a=args.a, offset=args.offset, w=args.w, thickness=args.thickness,
                     flat_angle=getattr(args, "flat_angle", None), A=A, C=C, **stem)


def _stem(stem_length, stem_radius) -> dict:
    """The tippe top's stem flags as make_body takes them: the default stem when neither is
    given, none (the ball alone, EccentricSphere) with --stem-length 0."""
    from .._runtime.validate import check_range
    from ..bodies.compound import STEM, STEM_LENGTH_MAX
    from ..errors import ParameterError

    if stem_length is not None:  # 0 is the CLI's "no stem": its range is the API's with 0
        check_range("stem_length", stem_length, 0.0, STEM_LENGTH_MAX, closed="lr",
                    label=f"[0, {STEM_LENGTH_MAX:g}] (over the ball's radius; 0: the ball alone)")
    if stem_length == 0.0:
        if stem_radius is not None:
            raise ParameterError("stem_radius", "does not apply with --stem-length 0 (the ball alone, no stem)",
                                 stem_radius)
        return {"stem_length": None, "stem_radius": None}
    return {"stem_length": STEM[0] if stem_length is None else stem_length, "stem_radius": stem_radius}


def body_of(args):
    from ..errors import ParameterError, plain

    try:
        body = _make_body(args, A=args.A, C=args.C)
    except ParameterError as exc:
        _moments_relation(args, exc)
        raise
    for name, moment in (("A", body.A), ("C", body.C)):  # after the library's checks: a relation of the two is said first
        if getattr(args, name) is not None and moment < MOMENT_MIN:
            raise UsageError(f"--{name} must be at least {MOMENT_MIN:g} (units M b^2; a smaller moment gives rates of "
                              f"order 1/{name} that double precision cannot follow), got {plain(getattr(args, name))}.",
                              f"--{name}")
    return body


def _moments_relation(args, exc) -> None:
    """C <= 2A fails: name the moment typed (the library names C, typed or not), and say which
    value is the body's default."""
    from ..errors import plain

    if exc.param != "C" or "C <= 2A" not in exc.expected or (args.A is None and args.C is None):
        return
    try:  # the body's own moments, where a flag leaves one out
        own = _make_body(args)
    except ValueError:
        return
    A, C = (own.A if args.A is None else args.A), (own.C if args.C is None else args.C)
    a_text = f"the default A = {A:.6g}" if args.A is None else f"--A {plain(args.A)}"
    c_text = f"the default C = {C:.6g}" if args.C is None else f"--C {plain(args.C)}"
    flag = "--A" if args.C is None else "--C"
    first, second = (a_text, c_text) if flag == "--A" else (c_text, a_text)
    fix = f"--A >= {C / 2:.6g}" if flag == "--A" else f"--C <= {2 * A:.6g}"
    raise UsageError(f"{first} with {second} violates C <= 2A (triangle inequality of principal moments): give "
                      f"{fix}" + ("" if args.A is not None and args.C is not None else
                                  f", or give {'--C' if flag == '--A' else '--A'} too") + ".", flag)


def law_args(args) -> tuple[str, float, float | None]:
    """(friction, mu, slip_eps), warning (and dropping) --slip-eps where it does nothing."""
    eps = args.slip_eps
    if eps is not None and args.friction == "viscous":
        from .._runtime.validate import check_positive

        check_positive("eps", eps, upper=1.0)
        warnings.warn("--slip-eps has no effect with --friction viscous (it regularises Coulomb friction only)")
        eps = None
    return args.friction, args.mu, eps


def dissipation_of(args) -> dict:
    """The coefficients of the dissipation laws given (flag dest -> value, in phasekit's units):
    what :func:`phasekit.cli.params._law_of` builds the laws from; ``hertz``: the patch radius at
    principal radii of b (:func:`hertz_of`)."""
    out = {dest: getattr(args, dest) for dest in DISSIPATION_FLAGS if getattr(args, dest, None) is not None}
    if getattr(args, "hertz", None) is not None:
        out["hertz"] = args.hertz
    return out


def hertz_of(text: str, scale) -> float:
    """--hertz "BODY, TABLE" (materials by name) or "E1, nu1, E2, nu2" (Pa) as the Hertz patch radius
    at principal radii of b under the weight (units b), from --size and --mass."""
    from ..friction.hertz import MATERIALS, unit_patch_radius

    parts = [p.strip() for p in str(text).split(",")]
    try:
        if len(parts) == 2:
            (E1, nu1), (E2, nu2) = ((MATERIALS[p.lower()].E, MATERIALS[p.lower()].nu) for p in parts)
        elif len(parts) == 4:
            E1, nu1, E2, nu2 = (float(p) for p in parts)
        else:
            raise ValueError
    except (KeyError, ValueError):
        raise UsageError(f"--hertz must be two materials among {', '.join(MATERIALS)} (the body's, then the "
                          f"table's) or 'E1, nu1, E2, nu2' (Pa), got {text!r}.", "--hertz") from None
    if scale is None or scale.mass is None:
        raise UsageError(f"--hertz needs the body's weight: give --size and --mass, got --hertz {text!r}.", "--hertz")
    weight = float((scale.mass * scale.g).to("N").magnitude)
    from ..errors import ParameterError

    try:
        return unit_patch_radius(weight, float(scale.b.to("m").magnitude), E1, nu1, E2, nu2)
    except ParameterError as exc:
        raise UsageError(f"--hertz {text!r}: {exc}", "--hertz") from None


#: options that take a value with units: dest -> kind (angles need no --size; the dissipation laws'
#: coefficients are kinds of phasekit.Scale of their own, air drag's need --mass)
UNIT_OPTIONS = {"theta0": "angle", "omega0": "rate", "n0": "rate", "spin_about_vertical": "rate", "spun_about_axis": "rate",
                "spun_on_edge": "rate", "rolled": "speed", "t_end": "time",
                "psi0": "angle", "phi0": "angle", "X0": "length", "Y0": "length", "thickness": "length", "flat_angle": "angle",
                "height": "length", "stem_length": "length", "stem_radius": "length",
                **{dest: dest for dest in DISSIPATION_FLAGS}}


def _scale_of(args):
    """The Scale of --size (or a disk's or a cone's --radius) and --g, or None without either."""
    from ..core.units import STANDARD_GRAVITY, Scale

    radius = getattr(args, "radius", None)
    if radius is not None:
        if args.body not in RADIUS_OF:
            raise UsageError(f"--radius is a disk's or a cone's radius (with --body disk or cone); the unit of length "
                              f"of the {args.body} body is --size, got --radius {radius!r}.", "--radius")
        if args.size is not None:
            raise UsageError(f"--radius and --size both set the unit of length b ({RADIUS_OF[args.body]}): give one "
                              f"of them, got --radius {radius!r} and --size {args.size!r}.", "--radius")
    b = args.size if args.size is not None else radius
    if b is None:
        size = _size_flag(args)
        for flag, value in (("--g", args.g), ("--mass", getattr(args, "mass", None))):
            if value is not None:
                raise UsageError(f"{flag} needs {size}, got {value!r}.", flag)
        return None
    return Scale(b, g=STANDARD_GRAVITY if args.g is None else args.g, mass=getattr(args, "mass", None))


def apply_units(args):
    """Replace every value typed with units by its number in phasekit's units; returns the Scale."""
    from ..core.units import as_quantity

    scale = _scale_of(args)
    args.typed_units = {}  # the values as typed, for messages (the args then hold numbers)
    for dest, kind in UNIT_OPTIONS.items():
        value = getattr(args, dest, None)
        if not isinstance(value, WithUnits):
            continue
        args.typed_units[dest] = str(value)
        flag = FLAGS[dest]
        if kind == "angle":
            q = as_quantity(str(value), dest)
            if not q.dimensionless:
                raise UsageError(f"{flag} must be an angle in radians or with units such as '89.4 deg', got "
                                  f"{str(value)!r}.", flag)
            setattr(args, dest, float(q.to("rad").magnitude))
        elif scale is None:
            size = f"{RADIUS_OF[args.body]} with --radius (e.g. --radius '3.7 cm')" if args.body in RADIUS_OF else \
                "the body's size with --size (e.g. --size '21.5 mm')"
            raise UsageError(f"{flag} {str(value)!r} has units: give {size} to express it in units of b and sqrt(b/g), "
                              f"or type a plain number.", flag)
        else:
            setattr(args, dest, _in_phasekit_units(scale, str(value), kind, dest))
    if getattr(args, "si", False) and scale is None:
        raise UsageError(f"--si needs {_size_flag(args)}.", "--si")
    if getattr(args, "hertz", None) is not None:
        args.hertz = hertz_of(args.hertz, scale)
    return scale


def _size_flag(args) -> str:
    """The flag that gives the body's unit of length, as a message says it."""
    if args.body in RADIUS_OF:
        return f"--radius ({RADIUS_OF[args.body]}, e.g. --radius '3.7 cm')"
    return "--size (the body's unit of length, e.g. --size '21.5 mm')"


def _in_phasekit_units(scale, value: str, kind: str, dest: str) -> float:
    """``value`` in phasekit's units by ``scale``; an air-drag coefficient typed with units without
    --mass is refused naming its flag (its unit holds the body's mass M)."""
    from ..errors import ParameterError

    try:
        return scale._dimensionless(value, kind, dest)
    except ParameterError as exc:
        if exc.param != "mass":
            raise
        unit = DISSIPATION_FLAGS[dest][2]
        raise UsageError(f"{FLAGS[dest]} {value!r} needs the body's mass to be expressed in phasekit's {unit}: give "
                          f"--mass (e.g. --mass '57 g'), or type a plain number.", FLAGS[dest]) from None


def pose_of(args) -> dict:
    return {k: v for k, v in (("psi", args.psi0), ("phi", args.phi0), ("X", args.X0), ("Y", args.Y0)) if v is not None}


def _refuse(args, names, why):
    for name in names:
        if getattr(args, name) is not None:
            raise UsageError(f"{FLAGS[name]} {why}", FLAGS[name])


def paper_body(args) -> None:
    """The printed start fixes its body (a uniform spheroid of one aspect ratio): refuse, naming
    it, a flag that says otherwise; --a defaults to the start's."""
    from ..errors import plain
    from ..theory.paper import PAPER_CASES

    label = args.paper_start[1:-1] if re.fullmatch(r"\(.*\)", args.paper_start) else args.paper_start
    if label not in PAPER_CASES:
        raise UsageError(f"--paper-start must be one of {', '.join(PAPER_CASES)} (the paper's printed starts), "
                          f"got {plain(args.paper_start)}.", "--paper-start")
    case = PAPER_CASES[label]
    args.paper_start = label
    which = f"with --paper-start {label} (its body is the uniform spheroid a = {case.a:.6g})"
    if args.body != "spheroid":
        raise UsageError(f"--body must be spheroid {which}, got {plain(args.body)}.", "--body")
    for name in ("A", "C", "offset", "w", "thickness", "flat_angle", "height", "on", "stem_length", "stem_radius"):
        if getattr(args, name, None) is not None:
            raise UsageError(f"{FLAGS[name]} must be left out {which}, got {plain(getattr(args, name))}.", FLAGS[name])
    if args.a is None:
        args.a = case.a
    elif not abs(args.a - case.a) <= 1e-4 * case.a:  # the API's tolerance; also refuses nan
        raise UsageError(f"--a must be {case.a:.6g} {which}, got {plain(args.a)}.", "--a")


def _manifold_states(body) -> tuple[str, ...]:
    """The steady states of ``body`` that --unstable-manifold can start from (phasekit.steady.precessions:
    horizontal only where h_theta(pi/2) = 0, horizontal-like only for a body without flip symmetry
    that can lie on its side)."""
    from ..steady.precessions import side_equilibrium

    level = body.flip_symmetric or abs(body.h(math.pi / 2)[1]) < 1e-14
    like = not body.flip_symmetric and math.isfinite(side_equilibrium(body)[0])
    return ("horizontal",) * level + ("vertical", "inverted") + ("horizontal-like",) * like


def _manifold_start(args, body) -> dict:
    from ..errors import plain

    _refuse(args, ["theta0"], "does not go with --unstable-manifold (the fixed point fixes theta)")
    states = ("vertical", "inverted") if args.unstable_manifold in ("vertical", "inverted") else _manifold_states(body)
    if args.unstable_manifold not in states:
        why = {"horizontal": " (it has no horizontal state: with its axis level its centre of mass is not above the "
                             "contact point" + ("; horizontal-like is the precession that continues it)"
                                                if "horizontal-like" in states else ")"),
               "horizontal-like": " (horizontal-like is for a body without flip symmetry that can lie on its side)"
               }.get(args.unstable_manifold, "")
        raise UsageError(f"--unstable-manifold must be one of {', '.join(states)} for the {args.body} body{why}, "
                          f"got {plain(args.unstable_manifold)}.", "--unstable-manifold")
    rate, wrong = ("--n0", "--omega0") if args.unstable_manifold in ("vertical", "inverted") else ("--omega0", "--n0")
    if getattr(args, wrong[2:]) is not None:
        raise UsageError(f"{wrong} does not go with --unstable-manifold {args.unstable_manifold}: its steady state is "
                          f"given by {rate}", wrong)
    if getattr(args, rate[2:]) is None:
        raise UsageError(f"--unstable-manifold {args.unstable_manifold} needs {rate} (the "
                          f"{'spin n0' if rate == '--n0' else 'precession rate Omega0'} of its steady state)",
                          "--unstable-manifold")
    return dict(kind="unstable-manifold", state=args.unstable_manifold,
                delta=0.01 if args.delta is None else args.delta, omega0=args.omega0, n0=args.n0,
                branch="+0" if args.branch is None else args.branch,
                seed_law="viscous" if args.seed_law is None else args.seed_law)


def _on_edge(args, body, name: str) -> float:
    """The default --theta0 of a start on the edge: pi/2 (standing on it), where the body's model
    holds it (a thick coin's side touches the table there: a line contact, not modelled)."""
    from ..steady.branches import holds_state

    if holds_state(body, math.pi / 2):
        return math.pi / 2
    lo, hi = body.theta_range
    raise UsageError(f"{FLAGS[name]} needs --theta0 for the {args.body} body: it cannot stand upright on its edge "
                      f"(at pi/2 its side touches the table, a line contact not modelled); give a tilt in ({lo:.6g}, "
                      f"{hi:.6g}), e.g. --theta0 '80 deg'", FLAGS[name])


def start_of(args, body) -> dict:
    if args.unstable_manifold is not None:
        return _manifold_start(args, body)
    _refuse(args, ["delta", "branch", "seed_law"], "goes with --unstable-manifold only")
    if args.gyroscopic:
        if args.theta0 is None:
            raise UsageError("--gyroscopic needs --theta0 (a number in (0, pi))", "--gyroscopic")
        if (args.omega0 is None) == (args.n0 is None):  # named: one typed (both), or --gyroscopic (neither)
            raise UsageError("--gyroscopic needs exactly one of --omega0 (prolate) or --n0 (oblate)",
                              "--gyroscopic" if args.omega0 is None else "--n0")
        return dict(kind="gyroscopic", theta0=args.theta0, omega0=args.omega0, n0=args.n0)
    if args.spin_about_vertical is not None:
        if args.theta0 is None:
            raise UsageError("--spin-about-vertical needs --theta0 (a number in [0, pi])", "--spin-about-vertical")
        _refuse(args, ["omega0", "n0"], "does not go with --spin-about-vertical (it sets the spin)")
        return dict(kind="spin-about-vertical", theta0=args.theta0, n0=args.spin_about_vertical)
    if args.spun_about_axis is not None:
        if args.theta0 is None:
            raise UsageError("--spun-about-axis needs --theta0 (the tilt, a number in [0, pi]; a cone on its tip: near "
                              "pi)", "--spun-about-axis")
        _refuse(args, ["omega0", "n0"], "does not go with --spun-about-axis (it sets the spin and the precession)")
        return dict(kind="spun-about-axis", theta0=args.theta0, n0=args.spun_about_axis)
    for name, kind, key in (("spun_on_edge", "spin-about-vertical", "n0"), ("rolled", "rolled", "speed")):
        if getattr(args, name) is not None:
            _refuse(args, ["omega0", "n0"], f"does not go with {FLAGS[name]} (it sets the rates)")
            return {"kind": kind, "theta0": _on_edge(args, body, name) if args.theta0 is None else args.theta0,
                    key: getattr(args, name)}
    if args.spinning_in_place:
        if args.theta0 is None:
            raise UsageError("--spinning-in-place needs --theta0 (the tilt it spins at)", "--spinning-in-place")
        _refuse(args, ["omega0", "n0"], "does not go with --spinning-in-place (the steady branch sets the rates)")
        return dict(kind="spinning-in-place", theta0=args.theta0)
    if args.paper_start is not None:
        _refuse(args, ["theta0"], "does not go with --paper-start (the printed start fixes theta)")
        return dict(kind="paper", label=args.paper_start, n0=args.n0, omega0=args.omega0)
    _refuse(args, ["theta0", "omega0", "n0"], "goes with --gyroscopic, --spin-about-vertical, --spinning-in-place or "
                                              "--unstable-manifold, not with --state")
    return dict(kind="state", state=args.state)
