"""The CLI's argument parser: every subcommand's flags and help, one-line usage errors.

:func:`_build_parser` builds the parser of ``phasekit`` and its subcommands; :class:`_Parser`
turns argparse's errors into one :class:`_UsageError` naming the flag, with a suggestion;
:func:`_refuse_repeats` refuses an option given twice.
"""

from __future__ import annotations

import argparse
import difflib
import json
import math
import re

from .flags import _typed

EXAMPLES = """examples:
  phasekit simulate --a 1.5 --mu 0.1 --gyroscopic --theta0 1.5607963 --omega0 10.5 --json
  phasekit simulate --a 1.5 --mu 0.1 --paper-start 5.2 --slip-eps 1e-3 --t-end 300
  phasekit simulate --a 1.5 --mu 0.1 --state 0 0 0 0 1.0 0 --t-end 5
  phasekit simulate --body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --slip-eps 1e-8 \\
      --theta0 0.1 --spin-about-vertical 15 --stop-at theta=0.4 --t-end 30 --rtol 1e-10 --json
  phasekit simulate --body disk --radius "3.7 cm" --thickness "1.2 cm" --mu 0.5 --theta0 "60 deg" \\
      --spin-about-vertical "5 rev/s" --t-end "2 s"
  phasekit simulate --body cone --on tip --radius "2 cm" --height "3 cm" --mu 0.5 --theta0 "175 deg" \
      --spin-about-vertical "40 rev/s" --t-end "2 s"
  phasekit fixed-points --a 1.5 --mu 0.1 --omega0 10 --json
  phasekit steady-states --body spheroid --a 1.5 --offset 0.2 --mu 0.1 --friction viscous
  phasekit steady-states --body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --json
  phasekit gyroscopic --a 1.5 --mu 0.1 --omega0 10.5 --theta0 1.5607963 --t 0 10 40
"""


class _UsageError(Exception):
    def __init__(self, message: str, flag: str | None = None):
        super().__init__(message)
        self.flag = flag


class _Parser(argparse.ArgumentParser):
    """One-line errors; a subcommand's parser reports its own unknown options (so that a
    suggestion comes from its flags, and a flag of another subcommand is said to be one)."""

    command: str | None = None  # the subcommand this parser reads (None: the top level)
    commands: dict = {}  # every subcommand's parser, by name (set by _build_parser)
    argv: tuple = ()

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        kwargs.setdefault("formatter_class", argparse.RawDescriptionHelpFormatter)
        super().__init__(*args, **kwargs)
        # argparse's own pattern misses exponents, so "--state ... -1e-4 ..." would read
        # -1e-4 as an option; accept any negative float literal as a value.
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|nan)$", re.I)

    def parse_known_args(self, args=None, namespace=None):
        namespace, extras = super().parse_known_args(args, namespace)
        if extras and self.command is not None:  # argparse would report them from the top level
            self.error("unrecognized arguments: " + " ".join(extras))
        return namespace, extras

    def error(self, message):  # one line, no usage block
        flag = re.search(r"argument (--[\w-]+)|required: (--[\w-]+)$|unrecognized arguments: (\S+)", message)
        flag = next((g for g in flag.groups() if g), None) if flag else None
        if message.startswith("unrecognized arguments") and flag:
            if flag.startswith("-") and not self._negative_number_matcher.match(flag):
                flag = flag.split("=", 1)[0]
                message += f" ({self._unknown_option(flag)})"
            else:  # a stray value: more values than the option before it takes
                flag = self._owner_of(flag)
                counts = {f: 0 if a.nargs == 0 else 1 if a.nargs is None else a.nargs
                          for f, a in self._option_string_actions.items()}
                takes = {0: "no value", 1: "one value"}.get(counts.get(flag), f"exactly {counts.get(flag)} numbers")
                message += f" (a value too many after {flag}, which takes {takes})" if flag else \
                    " (a value that follows no option)"
        raise _UsageError(message, flag)

    def _unknown_option(self, flag: str) -> str:
        """Why ``flag`` is refused: it belongs to other commands, or the nearest own flag."""
        owners = [name for name, p in self.commands.items() if name != self.command and flag in p._option_string_actions]
        if owners and self.command is None:
            return f"{flag} is an option of the commands ({', '.join(owners)}), not of phasekit itself: write it " \
                   f"after the command, e.g. phasekit {owners[0]} ... {flag}"
        if owners:
            return f"{flag} is not an option of {self.command}: it is one of {', '.join(owners)}"
        own = sorted(f for f in self._option_string_actions if f.startswith("--") and f != flag)
        close = difflib.get_close_matches(flag, own, n=1)
        where = f"of {self.command}" if self.command else "of phasekit: give a command first"
        return f"did you mean {close[0]}?" if close else f"not an option {where} (see --help)"

    def _owner_of(self, token: str) -> str | None:
        """The option a stray ``token`` follows: the command line read as argparse reads it
        (each option takes its number of values, then this command's positionals theirs), the
        first value taken by nothing that equals ``token`` (not merely the first equal text:
        in ``--offset 0.3 --mu 0.3 0.3`` the stray 0.3 follows --mu)."""
        argv = list(self.argv)
        argv = argv[:argv.index("--")] if "--" in argv else argv
        if self.command is not None and self.command in argv:
            argv = argv[argv.index(self.command) + 1:]
        positionals = sum(1 for a in self._actions if not a.option_strings)
        owner, left = None, 0
        for tok in argv:
            if tok.startswith("-") and len(tok) > 1 and not self._negative_number_matcher.match(tok):
                owner = tok.split("=", 1)[0]
                action = self._option_string_actions.get(owner)
                n = 0 if action is None or "=" in tok else action.nargs
                left = {None: 1, "?": 1, "+": math.inf, "*": math.inf}.get(n, n)
            elif left:
                left -= 1
            elif positionals:
                positionals -= 1
            elif tok == token:
                return owner
        return owner if token in argv else None


class _Version(argparse.Action):
    """--version: "phasekit X.Y.Z", or {"program": "phasekit", "version": "X.Y.Z"} when --json is
    anywhere on the command line (stdout then holds JSON only); the rest is not read."""

    def __init__(self, option_strings, version, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, **kw):
        super().__init__(option_strings, dest=dest, default=default, **kw)
        self.version = version

    def __call__(self, parser, namespace, values, option_string=None):
        if "--json" in parser.argv:
            print(json.dumps({"program": "phasekit", "version": self.version}))
        else:
            print(f"phasekit {self.version}")
        raise _Exit(0)


class _Exit(Exception):
    """End the CLI with this exit code (what argparse's own version action does with SystemExit)."""

    def __init__(self, code: int):
        super().__init__(code)
        self.code = code


def _real(text: str) -> float:
    """A real number as typed (inf and nan are refused later by range checks, with the flag)."""
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, got {text!r}") from None


class _WithUnits(str):
    """An option value typed with units ("41 rev/s", "2500 rpm", "89.4 deg"), converted to
    phasekit's units once --size and --g are known (:func:`phasekit.cli.inputs._apply_units`)."""


#: the powers in a unit ("m/s^2", "s**-1"): digits that are not the value's number
_POWERS = re.compile(r"(\*\*|\^)\s*\(?\s*[-+]?[\d.]+\s*\)?")


def _has_number(text: str) -> bool:
    """Whether a value with units has a number of its own: pint reads a unit alone ("mm",
    "rev/s") as one of it, which is never what a user typing a flag's value meant."""
    return bool(re.search(r"\d|\b(inf|infinity|nan)\b", _POWERS.sub("", text), flags=re.I))


def _real_or_units(text: str):
    """A plain number (phasekit's units), or a value with units such as '41 rev/s'."""
    try:
        return float(text)
    except ValueError:
        if re.search(r"[A-Za-z]", text):
            if not _has_number(text):
                raise argparse.ArgumentTypeError(f"must be a number, or a number with units such as '41 rev/s', got "
                                                 f"{text!r} (a unit needs its number)") from None
            return _WithUnits(text.strip())
        raise argparse.ArgumentTypeError(f"must be a number or a value with units such as '41 rev/s', got {text!r}") \
            from None


def _quantity_text(text: str) -> str:
    """A quantity typed with its number and unit (--size '21.5 mm', --g '9.81 m/s^2')."""
    if not _has_number(text):
        raise argparse.ArgumentTypeError(f"must be a number with its unit such as '21.5 mm' or '9.81 m/s^2', got "
                                         f"{text!r} (a unit needs its number)")
    return text


def _count(text: str) -> int:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}") from None
    if not math.isfinite(value) or value != int(value):
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}")
    return int(value)


def _add_body(p, units: bool = False):
    """The body's flags; with ``units`` (simulate, animate) the disk's --thickness and the cone's
    --height may be typed with units and --radius gives their radius (the unit of length, as --size)."""
    g = p.add_argument_group("body (units: mass M, length b = equatorial radius, ball radius or disk or cone radius, "
                             "time sqrt(b/g))")
    g.add_argument("--body", default="spheroid", help="spheroid | tippe-top | egg | disk | cone (default: %(default)s)")
    g.add_argument("--a", type=_real, default=None, help="aspect ratio: spheroid semi-axes (1, 1, a), egg length/breadth")
    g.add_argument("--offset", type=_real, default=None, help="tippe-top: centre of mass below the ball's centre, in [0, 1); spheroid: centre of mass "
                        "displaced from the centre toward the end at -k, in [0, a) (default 0)")
    g.add_argument("--w", type=_real, default=None, help="egg: asymmetry (shift of the widest section over the length)")
    typed = ", or e.g. '1.2 cm' with --radius" if units else ""
    g.add_argument("--thickness", type=_real_or_units if units else _real, default=None,
                   help=f"disk: full thickness over the radius, in [0, 1000] (0: a thin disk, Euler's disk; a coin "
                        f"~0.1; default 0){typed}")
    g.add_argument("--flat-angle", dest="flat_angle", type=_real_or_units if units else _real, default=None,
                   help="disk: the tilt at which its face is taken to be down and a run stops, radians in [1e-6, 0.1] "
                        "(default 1e-3; lower follows more of Euler's disk's end)" + (", or e.g. '0.01 deg'" if units else ""))
    g.add_argument("--height", type=_real_or_units if units else _real, default=None,
                   help=f"cone: from the base to the tip over the base's radius, in (0, 1000] (default 1){typed}")
    g.add_argument("--on", default=None, help="cone: where it touches the table, rim (of its base, theta below the "
                                              "angle pi - atan(height) where its side lies on the table; default) or "
                                              "tip (theta above it, up to pi: a top on its point)")
    with_size = " (or with units, e.g. '12 mm', with --size)" if units else ""
    g.add_argument("--stem-length", dest="stem_length", type=_real_or_units if units else _real, default=None,
                   help="tippe-top: how far its stem stands out of the ball, over the ball's radius, in [0, 10] "
                        "(default 0.375, a common commercial top; 0: the ball alone, no stem, as the tippe top was "
                        f"modelled before it had one){with_size}")
    g.add_argument("--stem-radius", dest="stem_radius", type=_real_or_units if units else _real, default=None,
                   help=f"tippe-top: the radius of the stem's rounded end over the ball's radius, in (0, 1) (default 0.2)"
                        f"{with_size}")
    if units:
        g.add_argument("--radius", type=_quantity_text, default=None,
                       help="disk, cone: its (base's) radius with its unit, e.g. '3.7 cm': the unit of length b (as "
                            "--size, which it replaces)")
    g.add_argument("--A", dest="A", type=_real, default=None,
                   help="transverse moment of inertia about G, units M b^2 (default: the body's, e.g. (1+a^2)/5)")
    g.add_argument("--C", dest="C", type=_real, default=None, help="axial moment of inertia about G (default: the body's, e.g. 2/5)")


STABILITY = """stability (which law each statement is for):
  --friction coulomb (default)  exact stick-slip. The steady states have zero slip and static
      friction holds them, so small disturbances roll: stability is that of the rolling
      (no-slip) linearisation, in which the zero-slip states are neutral (no growth, no decay).
  --friction coulomb --slip-eps E  the regularised field's linearisation: the rolling spectrum
      plus two fast slip modes (rates ~ mu/E).
  --friction viscous  part I's wet friction F = -mu u: friction drives or damps the modes; for
      uniform spheroids and weak friction (mu below ~0.8) the horizontal state is unstable for
      Omega0 > sqrt(5) (prolate) and the vertical spin for n0 > sqrt(5 a^3) (oblate).
  Unstable-manifold starts take their direction from the viscous linearisation by default
  (--seed-law viscous), since exact Coulomb friction gives none.
"""


def _add_friction(p, units: bool = False):
    """--mu, --friction, --slip-eps and the dissipation laws (values with units with ``units``)."""
    g = p.add_argument_group("friction")
    g.add_argument("--mu", type=_real, required=True,
                   help="friction coefficient mu (coulomb) or drag coefficient (viscous), in [0, 1000]")
    g.add_argument("--friction", default="coulomb",
                   help="coulomb: exact stick-slip, F = -mu R u/|u| while sliding | viscous: part I's wet friction "
                        "F = -mu u (default: %(default)s; see 'stability' below for what stability means with each)")
    g.add_argument("--slip-eps", type=_real, default=None,
                   help="regularise Coulomb friction as -mu R u/sqrt(|u|^2+eps^2), eps in [1e-14, 1] "
                        "(default: exact stick-slip; no effect with --friction viscous)")
    _add_dissipation(p, units)


#: the dissipation laws' flags (phasekit.friction.dissipation): dest -> (metavar, what, phasekit's unit, example with
#: units); each in [0, 1000], 0 or absent: the law is left out
DISSIPATION_FLAGS = {
    "rolling_resistance": ("DELTA", "rolling resistance: a couple -DELTA R w_h/|w_h| against the rolling part w_h of "
                           "the angular velocity (DELTA: the pressure's offset ahead of the contact point)",
                           "a length, units b", "'0.2 mm'"),
    "spin_friction": ("MU_S", "spin (pivoting) friction: a couple -MU_S R sign(w_Z) about the vertical (MU_S = "
                      "3 pi mu a/16 for a contact patch of radius a)", "a length, units b", "'0.5 mm'"),
    "air_drag": ("K1", "air drag on the rotation: a couple -K1 w", "units M b^2 sqrt(g/b)", "'1e-7 N*m*s'"),
    "air_layer": ("K", "the air layer under a disk on its rim (Moffatt): a couple whose power is -K psidot^2/sin(theta)",
                  "units M b^2 sqrt(g/b)", "'1e-9 N*m*s'"),
    "air_drag_quadratic": ("K2", "quadratic air drag on the rotation: a couple -K2 |w| w", "units M b^2",
                           "'1e-9 N*m*s^2'"),
    "air_drag_force": ("C1", "air drag on the centre of mass: a force -C1 v at G", "units M sqrt(g/b)",
                       "'1e-4 N*s/m'"),
    "air_drag_force_quadratic": ("C2", "quadratic air drag on the centre of mass: a force -C2 |v| v at G",
                                 "units M/b", "'1e-3 N*s^2/m^2'"),
}


def _add_dissipation(p, units: bool) -> None:
    """The dissipation laws acting besides sliding friction; with ``units`` (simulate, animate) a
    value may be typed with units (a length with --size, air drag with --size and --mass)."""
    rest = "; a run with any of them ends when the body comes to rest, status \"rest\"" if units else ""
    g = p.add_argument_group(f"dissipation besides sliding friction (each in [0, 1000]; 0 or absent: none{rest})")
    for dest, (metavar, what, unit, example) in DISSIPATION_FLAGS.items():
        needs = "--size" if "length" in unit else "--size and --mass"
        typed = f", or e.g. {example} with {needs}" if units else ""
        g.add_argument("--" + dest.replace("_", "-"), dest=dest, metavar=metavar, default=None,
                       type=_real_or_units if units else _real, help=f"{what}; {unit}{typed}")


def _add_solver(p):
    g = p.add_argument_group("solver (every run is bounded by steps and wall time)")
    g.add_argument("--rtol", type=_real, default=1e-9, help="tolerance in [1e-16, 0.1] (default: %(default)s)")
    g.add_argument("--atol", type=_real, default=None, help="absolute tolerance of CVODES/IDAS (default: rtol/100)")
    g.add_argument("--backend", default="auto", help="auto | taylor | cvodes | cvodes-adams | idas (default: %(default)s)")
    g.add_argument("--chart", "--formulation", dest="chart", default="auto",
                   help="the state's chart: euler | vector | auto (vector within 1e-5 of the poles; --formulation is "
                        "its old name) (default: %(default)s)")
    g.add_argument("--max-steps", type=_count, default=5_000_000,
                   help="step budget of the run: Taylor steps (heyoka), or CVODES/IDAS internal steps (counted per "
                        "chunk of 100 output points: a chunk that would pass the budget is not taken, so the run "
                        "ends within it; the reason gives the count) (default: %(default)s)")
    g.add_argument("--max-wall", type=_real, default=600.0,
                   help="wall-time budget in seconds; a --t-end it cannot reach is refused at once (default: "
                        "%(default)s)")
    g.add_argument("--verify", action="store_true",
                   help="repeat the run at rtol/10 in the other chart and report how far it is from converged "
                        "(\"converged to ~X\", or \"not converged\" with what differs); costs that run")
    g.add_argument("--no-creep", action="store_true",
                   help="a stiff regularised law (mu/eps > 500) integrates its own field at zero slip instead of "
                        "creeping on its slow manifold (docs/physics.md)")


def _add_wall(p) -> None:
    """--max-wall of the commands that search for steady states (the meaning and checks of simulate's)."""
    p.add_argument("--max-wall", type=_real, default=600.0,
                   help="wall-time budget in seconds, > 0: past it the command ends \"failed\" with the reason "
                        "(default: %(default)s)")


def _add_run_options(sim) -> None:
    """The options of a run (simulate and animate): body, friction, start, run, solver, units."""
    _add_body(sim, units=True)
    _add_friction(sim, units=True)
    g = sim.add_argument_group("start (exactly one)")
    start = g.add_mutually_exclusive_group(required=True)
    start.add_argument("--state", type=_real, nargs=6, metavar=("U", "V", "Omega", "Lambda", "theta", "n"),
                       help="the paper's state variables")
    start.add_argument("--gyroscopic", action="store_true", help="on the slow manifold at --theta0 with --omega0 or --n0")
    start.add_argument("--unstable-manifold", metavar="horizontal|vertical|inverted|horizontal-like",
                       help="fixed point + --delta x unstable eigenvector, with --omega0 (horizontal, horizontal-like) "
                            "or --n0 (vertical, inverted)")
    start.add_argument("--spin-about-vertical", type=_real_or_units, metavar="N0",
                       help="angular velocity N0 about the vertical at --theta0, centre of mass at rest (tippe top)")
    start.add_argument("--paper-start", metavar="5.1|5.2", help="the paper's printed start (5.1) with --n0, (5.2) with --omega0")
    g.add_argument("--theta0", type=_real_or_units, default=None, help="initial inclination of the axis, radians "
                                                                        "(or e.g. '89.4 deg')")
    g.add_argument("--omega0", type=_real_or_units, default=None,
                   help="precession rate Omega0 (prolate starts), |OMEGA0| <= 1e5; or e.g. '41 rev/s', '2500 rpm' with "
                        "--size")
    g.add_argument("--n0", type=_real_or_units, default=None, help="spin n0 (oblate starts), |N0| <= 1e5; units as --omega0")
    g.add_argument("--delta", type=_real, default=None,
                   help="seed amplitude on the unstable manifold (with --unstable-manifold; default: 0.01)")
    g.add_argument("--branch", default=None,
                   help="unstable direction and sign: +0, -0, +1, ... (with --unstable-manifold; default: +0)")
    g.add_argument("--seed-law", default=None,
                   help="linearisation giving the direction: viscous | same (with --unstable-manifold; default: viscous, "
                        "the only one with an unstable direction under exact Coulomb friction)")
    p = sim.add_argument_group("where the body starts on the table (default 0: the axis along +X, G at the origin)")
    p.add_argument("--psi0", type=_real_or_units, default=None, help="azimuth of the axis from X, rad (or '30 deg')")
    p.add_argument("--phi0", type=_real_or_units, default=None, help="spin angle about the axis, radians (or '30 deg')")
    p.add_argument("--X0", type=_real_or_units, default=None, help="centre of mass X, units b (or '5 mm' with --size)")
    p.add_argument("--Y0", type=_real_or_units, default=None, help="centre of mass Y, units b (or '5 mm' with --size)")
    r = sim.add_argument_group("run")
    r.add_argument("--t-end", type=_real_or_units, default=200.0,
                   help="end time, units sqrt(b/g) (or e.g. '2 s' with --size) (default: %(default)s)")
    r.add_argument("--stop-at", default="jump",
                   help="jump | touchdown | none | rest | NAME=VALUE: stop when an observable first reaches a value, "
                        "e.g. theta=0.4 (runs through flights); rest: through flights until the body comes to rest "
                        "(with a dissipation law; else as none) (default: %(default)s)")
    r.add_argument("--restitution", type=_real, default=None, help="Newton's e in [0, 1] at impacts (with --stop-at none; "
                                                                     "default 0)")
    u = sim.add_argument_group("real units (see 'units' below)")
    u.add_argument("--size", type=_quantity_text, default=None,
                   help="the body's unit of length b with its unit: the equatorial radius (spheroid, egg) or the "
                        "ball's radius (tippe top), e.g. '21.5 mm'")
    u.add_argument("--g", type=_quantity_text, default=None,
                   help="gravity with its unit (default: 9.81 m/s^2; with --size)")
    u.add_argument("--mass", type=_quantity_text, default=None,
                   help="the body's mass with its unit, e.g. '57 g' (with --size): air-drag coefficients typed with "
                        "units, and the energies of --si in mJ")
    _add_solver(sim)


def _add_movie_options(p) -> None:
    m = p.add_argument_group("movie")
    m.add_argument("--frames", type=_count, default=96, help="number of frames, in [1, 10000] (default: %(default)s)")
    m.add_argument("--fps", type=_real, default=24.0, help="frames per second of the movie (default: %(default)s)")
    m.add_argument("--timing", default="body",
                   help="the clock in the body's time (body) or also in seconds with the playback speed (real, needs "
                        "--size) (default: %(default)s)")
    m.add_argument("--gap-scale", type=_real, default=1.0, help="draw the gap in flight this many times larger, >= 1 "
                                                               "(printed on every frame when not 1) (default: 1)")
    m.add_argument("--camera", default="follow", help="follow (keeps G in view) | fixed (default: %(default)s)")
    m.add_argument("--panel", default="none", help="side panel: none | phase (Omega, theta, n) | R (R(t)) "
                                                   "(default: %(default)s)")
    m.add_argument("--window-size", type=_count, nargs=2, default=None, metavar=("W", "H"),
                   help="pixels of the 3-D view (default: 480 360)")
    m.add_argument("--json", action="store_true", help="print one JSON object (the run and the file written)")
    m.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")


#: the units section of the help of simulate and animate
UNITS_HELP = """units:
  Numbers are in phasekit's units: length b (--size), time sqrt(b/g), rates sqrt(g/b), radians.
  With --size (and optionally --g) the rates, times and positions may be typed with units:
  --omega0 "41 rev/s" or "2500 rpm", --t-end "2 s", --X0 "3 mm"; angles take "deg" without it.
  The dissipation laws too: --rolling-resistance "0.2 mm", --spin-friction "0.5 mm" (lengths, with
  --size), --air-drag "1e-7 N*m*s" (with --size and --mass: its unit holds the mass M).
"""
ANIMATE_EXAMPLES = """examples:
  phasekit animate spin.gif --a 1.5 --mu 0.1 --gyroscopic --theta0 1.5607963 --omega0 11 --stop-at touchdown \\
      --frames 48 --gap-scale 200 --panel R
  phasekit animate egg.mp4 --body egg --a 1.3256 --w 0.05 --mu 0.1 --gyroscopic --theta0 1.56 \\
      --omega0 "45 rev/s" --size "21.5 mm" --timing real --stop-at none --t-end 60
"""


def _build_parser() -> _Parser:
    from .. import __version__

    parser = _Parser(prog="phasekit", description="Phase space of an axisymmetric body spinning on a table.",
                     epilog=EXAMPLES)
    parser.add_argument("--version", action=_Version, nargs=0, version=__version__,
                        help="print the version and exit (a JSON object with --json)")
    sub = parser.add_subparsers(dest="command", parser_class=_Parser,
                                metavar="{simulate,animate,fixed-points,steady-states,gyroscopic,cache}")

    sim = sub.add_parser("simulate", help="integrate the exact equations from a start",
                         description="Integrate the contact dynamics (2.7) from a start, through stick, slip, "
                                     "lift-off and impacts, to a jump, a stop or --t-end.",
                         epilog=STABILITY + "\n" + UNITS_HELP + "\n" + EXAMPLES)
    _add_run_options(sim)
    o = sim.add_argument_group("output")
    o.add_argument("--json", action="store_true", help="print one JSON object")
    o.add_argument("--events", action="store_true", help="list every event (human output)")
    o.add_argument("--si", action="store_true", help="also report times, gaps, positions and spins in ms, mm, m/s and "
                                                     "rev/s (needs --size)")
    anim = sub.add_parser("animate", help="simulate, then write a movie (GIF, MP4) or film strip (PNG) of the body",
                          description="Run a simulation as `simulate` does and draw the body turning, precessing, "
                                      "travelling and lifting off, on a table with the contact path traced.",
                          epilog=UNITS_HELP + "\n" + ANIMATE_EXAMPLES)
    anim.add_argument("out", metavar="OUT", help="the file to write: .gif, .mp4 (needs phasekit[movie]) or .png "
                                                 "(a film strip)")
    _add_run_options(anim)
    _add_movie_options(anim)

    fx = sub.add_parser("fixed-points", help="steady states and their linear stability",
                        description="Steady states (vertical, horizontal, intermediate) at one Omega0 or n0, "
                                    "with the eigenvalues of their linearisation.", epilog=STABILITY + "\n" + EXAMPLES)
    _add_body(fx)
    _add_friction(fx)
    grp = fx.add_mutually_exclusive_group(required=True)
    grp.add_argument("--omega0", type=_real, help="precession rate of the family")
    grp.add_argument("--n0", type=_real, help="spin of the family")
    _add_wall(fx)
    fx.add_argument("--json", action="store_true", help="print one JSON object")

    ss = sub.add_parser("steady-states", help="the steady-state structure: branches, their ends, stability along them",
                        description="Every branch of steady precessions over 0 <= theta <= pi with its two ends (pole, "
                                    "static, infinite-spin), the stability along it and where it changes, the static "
                                    "equilibria, the spins about the vertical, and the structure's signature.",
                        epilog=STABILITY + "\n" + EXAMPLES)
    _add_body(ss)
    _add_friction(ss)
    g3 = ss.add_mutually_exclusive_group()
    g3.add_argument("--omega0", type=_real, help="also list the states on the structure with this precession rate")
    g3.add_argument("--n0", type=_real, help="also list the states on the structure with this spin")
    _add_wall(ss)
    ss.add_argument("--json", action="store_true", help="print one JSON object")

    gy = sub.add_parser("gyroscopic", help="gyroscopic mean solution theta-bar(t), Omega-bar(t) and J", epilog=EXAMPLES)
    _add_body(gy)
    gy.add_argument("--mu", type=_real, required=True, help="friction coefficient mu > 0 (sets the slow time mu t)")
    g2 = gy.add_mutually_exclusive_group(required=True)
    g2.add_argument("--omega0", type=_real, help="precession rate (prolate), 0 < |OMEGA0| <= 1e12 (the mean solution "
                                                 "is closed-form; simulate takes up to 1e5)")
    g2.add_argument("--n0", type=_real, help="spin (oblate), 0 < |N0| <= 1e12, with |Omega| <= 1e12 on the fast branch")
    gy.add_argument("--theta0", type=_real, required=True, help="initial inclination, radians, in (0, pi)")
    gy.add_argument("--t", type=_real, nargs="+", required=True, help="times (units sqrt(b/g))")
    gy.add_argument("--json", action="store_true", help="print one JSON object")
    ca = sub.add_parser("cache", help="show (or --clear) the compiled integrators kept on disk",
                        description="The disk cache of compiled integrators ($PHASEKIT_CACHE, default "
                                    "~/.cache/phasekit): phasekit's and heyoka's object code, in files and bytes.")
    ca.add_argument("--clear", action="store_true", help="delete them (the next run of each model compiles again)")
    ca.add_argument("--json", action="store_true", help="print one JSON object")
    commands = {"simulate": sim, "animate": anim, "fixed-points": fx, "steady-states": ss, "gyroscopic": gy,
                "cache": ca}
    for name, p in commands.items():
        p.command = name
    for p in (parser, *commands.values()):
        p.commands = commands
    parser.known_flags = {f for p in commands.values() for f in p._option_string_actions if f.startswith("--")}
    return parser


def _refuse_repeats(parser: _Parser, argv) -> None:
    """An option given twice is refused: a value-taking one (argparse would keep the last
    silently) and a switch too (``--json --json`` is a typing slip, as the README says); an
    option and its other name (``--chart`` and ``--formulation``) count as the same option."""
    typed = _typed(argv)
    by_action: dict = {}
    for flag in typed:
        action = parser._option_string_actions.get(flag)
        if action is not None:
            by_action.setdefault(id(action), []).append(flag)
    for flags in by_action.values():
        if len(set(flags)) > 1:
            values = [t.split("=", 1)[1] if "=" in t else nxt for t, nxt in zip(argv, [*argv[1:], ""])
                      if t.split("=", 1)[0] in flags]
            given = ", then ".join(f"{f} {v}" if parser._option_string_actions[f].nargs is None else f
                                   for f, v in zip(flags, values))
            names = " and ".join(dict.fromkeys(flags))
            raise _UsageError(f"{names} are names of the same option, given {len(flags)} times ({given}): give it "
                              "once", flags[1])
    for flag in dict.fromkeys(typed):
        action = parser._option_string_actions.get(flag)
        if action is None or typed.count(flag) < 2:
            continue
        if action.nargs == 0:
            raise _UsageError(f"{flag} is given {typed.count(flag)} times: give it once", flag)
        if action.nargs is None:
            values = [t.split("=", 1)[1] if "=" in t else nxt for t, nxt in zip(argv, [*argv[1:], ""])
                      if t.split("=", 1)[0] == flag]
            raise _UsageError(f"{flag} takes one value and is given {len(values)} times (got "
                              f"{', then '.join(values)}): give it once", flag)
        raise _UsageError(f"{flag} is given {typed.count(flag)} times: give it once, with all its values", flag)
