"""Command line: ``phasekit <command> ... [--json]`` (also ``python -m phasekit``).

Every command prints one JSON object with ``--json`` (and nothing else on stdout: library
output is sent to stderr while it runs). Exit codes and what stderr holds:

0    a result (stderr: at most one ``phasekit: warning:`` line per option that has no
     effect in the chosen mode, e.g. ``--restitution`` with ``--stop-at jump``);
1    a run that failed (status "failed" and its reason), or a solver error in one line;
2    bad input: one line naming the flag as typed, its valid range and the plain value;
130  interrupted.
With ``--json`` an error is also one JSON object on stdout: status "error" with the flag
(``parameter``) and the ``message``, or "failed" / "interrupted" with its ``reason`` too.
A flag is named as typed (``--spin-about-vertical``, not the ``--n0`` it stands for); a
value-taking option given twice is refused. A non-finite number never reaches the output:
the run is reported failed, saying where. An unexpected exception (a bug) prints one line
too; set PHASEKIT_DEBUG=1 for its traceback (the tests do).
"""

from __future__ import annotations

import argparse
import contextlib
import difflib
import functools
import json
import math
import os
import re
import sys
import warnings

__all__ = ["main", "main_entry"]

EXAMPLES = """examples:
  phasekit simulate --a 1.5 --mu 0.1 --gyroscopic --theta0 1.5607963 --omega0 10.5 --json
  phasekit simulate --a 1.5 --mu 0.1 --paper-start 5.2 --slip-eps 1e-3 --t-end 300
  phasekit simulate --a 1.5 --mu 0.1 --state 0 0 0 0 1.0 0 --t-end 5
  phasekit simulate --body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --slip-eps 1e-8 \\
      --theta0 0.1 --spin-about-vertical 15 --stop-at theta=0.4 --t-end 30 --rtol 1e-10 --json
  phasekit fixed-points --a 1.5 --mu 0.1 --omega0 10 --json
  phasekit steady-states --body spheroid --a 1.5 --offset 0.2 --mu 0.1 --friction viscous
  phasekit steady-states --body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --json
  phasekit gyroscopic --a 1.5 --mu 0.1 --omega0 10.5 --theta0 1.5607963 --t 0 10 40
"""

#: Python parameter names -> the flag a user typed (the CLI rewords API errors with these)
FLAGS = {
    "a": "--a", "A": "--A", "C": "--C", "offset": "--offset", "w": "--w", "body": "--body", "mu": "--mu",
    "eps": "--slip-eps", "friction": "--friction", "theta0": "--theta0", "omega0": "--omega0", "n0": "--n0",
    "t_end": "--t-end", "rtol": "--rtol", "atol": "--atol", "restitution": "--restitution", "stop_at": "--stop-at",
    "backend": "--backend", "state": "--state", "x0": "--state", "theta": "--state (theta)", "U": "--state (U)",
    "V": "--state (V)", "Omega": "--state (Omega)", "Lambda": "--state (Lambda)", "n": "--state (n)",
    "delta": "--delta", "branch": "--branch", "seed_law": "--seed-law", "chart": "--chart",
    "max_steps": "--max-steps", "max_wall": "--max-wall", "unstable_manifold": "--unstable-manifold",
    "t": "--t", "T": "--t", "label": "--paper-start", "level": "--stop-at", "max_switches": "--max-switches",
    "b": "--size", "g": "--g", "pose0.psi": "--psi0", "pose0.phi": "--phi0", "pose0.X": "--X0", "pose0.Y": "--Y0",
    "psi0": "--psi0", "phi0": "--phi0", "X0": "--X0", "Y0": "--Y0", "spin_about_vertical": "--spin-about-vertical",
    "frames": "--frames", "fps": "--fps", "out": "OUT", "gap_scale": "--gap-scale", "camera": "--camera",
    "panel": "--panel", "timing": "--timing", "window_size": "--window-size", "path": "OUT",
}
#: API parameters that more than one flag feeds: (flag typed, name to print), the first typed one wins
#: (e.g. `n0` is --spin-about-vertical's value in that start, and theta its --theta0)
SOURCES = {
    "chart": (("--formulation", "--formulation"), ("--chart", "--chart")),  # --formulation: the old name
    "n0": (("--spin-about-vertical", "--spin-about-vertical"), ("--n0", "--n0")),
    "theta": (("--state", "--state (theta)"), ("--theta0", "--theta0")),
    "Omega": (("--state", "--state (Omega)"), ("--spin-about-vertical", "--spin-about-vertical")),
    "n": (("--state", "--state (n)"), ("--spin-about-vertical", "--spin-about-vertical")),
}


def _typed(argv) -> list[str]:
    """The options as typed (``--name`` of ``--name=value`` too), up to a bare ``--``."""
    argv = list(argv)
    argv = argv[:argv.index("--")] if "--" in argv else argv
    return [a.split("=", 1)[0] for a in argv if isinstance(a, str) and a.startswith("--") and len(a) > 2]


def _flag_names(argv) -> dict:
    """FLAGS for this command line: a parameter fed by several flags is named by the one typed."""
    typed = set(_typed(argv))
    names = dict(FLAGS)
    for param, sources in SOURCES.items():
        names[param] = next((shown for flag, shown in sources if flag in typed), FLAGS.get(param, f"`{param}`"))
    return names


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
                message += f" (a value that follows no option: {flag} takes {takes})" if flag else \
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
        """The option written last before a stray ``token`` on the command line."""
        argv = list(self.argv)
        if token not in argv:
            return None
        before = [a for a in argv[:argv.index(token)] if a.startswith("--")]
        return before[-1] if before else None


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
    phasekit's units once --size and --g are known (:func:`_apply_units`)."""


def _real_or_units(text: str):
    """A plain number (phasekit's units), or a value with units such as '41 rev/s'."""
    try:
        return float(text)
    except ValueError:
        if re.search(r"[A-Za-z]", text):
            return _WithUnits(text.strip())
        raise argparse.ArgumentTypeError(f"must be a number or a value with units such as '41 rev/s', got {text!r}") \
            from None


def _count(text: str) -> int:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}") from None
    if not math.isfinite(value) or value != int(value):
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}")
    return int(value)


def _add_body(p):
    g = p.add_argument_group("body (units: mass M, length b = equatorial radius or ball radius, time sqrt(b/g))")
    g.add_argument("--body", default="spheroid", help="spheroid | tippe-top | egg (default: %(default)s)")
    g.add_argument("--a", type=_real, default=None, help="aspect ratio: spheroid semi-axes (1, 1, a), egg length/breadth")
    g.add_argument("--offset", type=_real, default=None, help="tippe-top: centre of mass below the ball's centre, in [0, 1); spheroid: centre of mass "
                        "displaced from the centre toward the end at -k, in [0, a) (default 0)")
    g.add_argument("--w", type=_real, default=None, help="egg: asymmetry (shift of the widest section over the length)")
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


def _add_friction(p):
    g = p.add_argument_group("friction")
    g.add_argument("--mu", type=_real, required=True,
                   help="friction coefficient mu (coulomb) or drag coefficient (viscous), in [0, 1000]")
    g.add_argument("--friction", default="coulomb",
                   help="coulomb: exact stick-slip, F = -mu R u/|u| while sliding | viscous: part I's wet friction "
                        "F = -mu u (default: %(default)s; see 'stability' below for what stability means with each)")
    g.add_argument("--slip-eps", type=_real, default=None,
                   help="regularise Coulomb friction as -mu R u/sqrt(|u|^2+eps^2), eps in [1e-14, 1] "
                        "(default: exact stick-slip; no effect with --friction viscous)")


def _add_solver(p):
    g = p.add_argument_group("solver (every run is bounded by steps and wall time)")
    g.add_argument("--rtol", type=_real, default=1e-9, help="tolerance in [1e-16, 0.1] (default: %(default)s)")
    g.add_argument("--atol", type=_real, default=None, help="absolute tolerance of CVODES/IDAS (default: rtol/100)")
    g.add_argument("--backend", default="auto", help="auto | taylor | cvodes | cvodes-adams | idas (default: %(default)s)")
    g.add_argument("--chart", "--formulation", dest="chart", default="auto",
                   help="the state's chart: euler | vector | auto (vector within 1e-5 of the poles; --formulation is "
                        "its old name) (default: %(default)s)")
    g.add_argument("--max-steps", type=_count, default=5_000_000,
                   help="step budget of the run: Taylor steps (heyoka), or CVODES/IDAS internal steps, which are "
                        "counted after each chunk of 100 output points, so those may pass it by one chunk (the reason "
                        "gives the count) (default: %(default)s)")
    g.add_argument("--max-wall", type=_real, default=600.0,
                   help="wall-time budget in seconds; a --t-end it cannot reach is said at once (default: %(default)s)")


def _add_run_options(sim) -> None:
    """The options of a run (simulate and animate): body, friction, start, run, solver, units."""
    _add_body(sim)
    _add_friction(sim)
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
                   help="jump | touchdown | none | NAME=VALUE: stop when an observable first reaches a value, "
                        "e.g. theta=0.4 (runs through flights) (default: %(default)s)")
    r.add_argument("--restitution", type=_real, default=None, help="Newton's e in [0, 1] at impacts (with --stop-at none; "
                                                                     "default 0)")
    u = sim.add_argument_group("real units (see 'units' below)")
    u.add_argument("--size", default=None, help="the body's unit of length b with its unit: the equatorial radius "
                                                "(spheroid, egg) or the ball's radius (tippe top), e.g. '21.5 mm'")
    u.add_argument("--g", default=None, help="gravity with its unit (default: 9.81 m/s^2; with --size)")
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
                                metavar="{simulate,animate,fixed-points,steady-states,gyroscopic}")

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
    commands = {"simulate": sim, "animate": anim, "fixed-points": fx, "steady-states": ss, "gyroscopic": gy}
    for name, p in commands.items():
        p.command = name
    for p in (parser, *commands.values()):
        p.commands = commands
    parser.known_flags = {f for p in commands.values() for f in p._option_string_actions if f.startswith("--")}
    return parser


def _body(args):
    from ..core.model import make_body

    return make_body(args.body, a=args.a, offset=args.offset, w=args.w, A=args.A, C=args.C)


def _law_args(args) -> tuple[str, float, float | None]:
    """(friction, mu, slip_eps), warning (and dropping) --slip-eps where it does nothing."""
    eps = args.slip_eps
    if eps is not None and args.friction == "viscous":
        from .._runtime.validate import check_positive

        check_positive("eps", eps, upper=1.0)
        warnings.warn("--slip-eps has no effect with --friction viscous (it regularises Coulomb friction only)")
        eps = None
    return args.friction, args.mu, eps


#: options that take a value with units: dest -> kind (angles need no --size)
UNIT_OPTIONS = {"theta0": "angle", "omega0": "rate", "n0": "rate", "spin_about_vertical": "rate", "t_end": "time",
                "psi0": "angle", "phi0": "angle", "X0": "length", "Y0": "length"}


def _scale_of(args):
    """The Scale of --size and --g, or None without --size."""
    from ..core.units import STANDARD_GRAVITY, Scale

    if args.size is None:
        if args.g is not None:
            raise _UsageError(f"--g needs --size (the body's unit of length, e.g. --size '21.5 mm'), got {args.g!r}.",
                              "--g")
        return None
    return Scale(args.size, g=STANDARD_GRAVITY if args.g is None else args.g)


def _apply_units(args):
    """Replace every value typed with units by its number in phasekit's units; returns the Scale."""
    from ..core.units import as_quantity

    scale = _scale_of(args)
    for dest, kind in UNIT_OPTIONS.items():
        value = getattr(args, dest, None)
        if not isinstance(value, _WithUnits):
            continue
        flag = FLAGS[dest]
        if kind == "angle":
            q = as_quantity(str(value), dest)
            if not q.dimensionless:
                raise _UsageError(f"{flag} must be an angle in radians or with units such as '89.4 deg', got "
                                  f"{str(value)!r}.", flag)
            setattr(args, dest, float(q.to("rad").magnitude))
        elif scale is None:
            raise _UsageError(f"{flag} {str(value)!r} has units: give the body's size with --size (e.g. --size "
                              f"'21.5 mm') to express it in units of b and sqrt(b/g), or type a plain number.", flag)
        else:
            setattr(args, dest, scale._dimensionless(str(value), kind, dest))
    if getattr(args, "si", False) and scale is None:
        raise _UsageError("--si needs --size (the body's unit of length, e.g. --size '21.5 mm').", "--si")
    return scale


def _pose_of(args) -> dict:
    return {k: v for k, v in (("psi", args.psi0), ("phi", args.phi0), ("X", args.X0), ("Y", args.Y0)) if v is not None}


def _cmd_simulate(args) -> dict:
    from .params import simulate_start

    scale = _apply_units(args)
    out = _simulate_args(args, simulate_start)
    if args.si:
        from .params import real_units_report

        out["si"] = real_units_report(out, scale)
    return out


def _cmd_animate(args) -> dict:
    """Simulate as `simulate` does, then write the movie (or film strip) of the run."""
    from ..viz.animate import animate, check_movie_options, film_strip
    from .params import run_start

    scale = _apply_units(args)
    if args.timing == "real" and scale is None:
        raise _UsageError("--timing real needs --size (the body's unit of length, e.g. --size '21.5 mm').", "--timing")
    size = (480, 360) if args.window_size is None else tuple(args.window_size)
    check_movie_options(args.out, frames=args.frames, fps=args.fps, timing=args.timing, gap_scale=args.gap_scale,
                        camera=args.camera, panel=args.panel, window_size=size, scale=scale)
    traj, seed = _simulate_args(args, run_start)
    out = traj.to_dict()
    if traj.status.value == "failed":
        return out
    if str(args.out).lower().endswith(".png"):
        info = film_strip(traj, args.out, frames=min(args.frames, 100), scale=scale, gap_scale=args.gap_scale,
                          camera=args.camera, window_size=size)
    else:
        info = animate(traj, args.out, frames=args.frames, fps=args.fps, timing=args.timing, scale=scale,
                       gap_scale=args.gap_scale, camera=args.camera, panel=args.panel, window_size=size,
                       progress=not args.no_progress)
    out["animation"] = {"path": info.path, "frames": info.n_frames, "frame_size": list(info.frame_size),
                        "fps": info.fps, "playback_speed": info.speed, "bytes": info.bytes}
    return out


def _simulate_args(args, runner):
    """Build the body, start and options from ``args`` and call ``runner`` (simulate_start or
    animate_start) with them."""
    if args.paper_start is not None:
        _paper_body(args)
    body = _body(args)
    start = _start_of(args, body)
    if args.restitution is not None and args.stop_at in ("jump", "touchdown"):
        warnings.warn(f"--restitution has no effect with --stop-at {args.stop_at} (impacts happen with --stop-at none "
                      "or --stop-at NAME=VALUE)")
    if args.atol is not None and args.backend == "taylor":
        warnings.warn("--atol has no effect with --backend taylor (the Taylor method has the one tolerance --rtol)")
    friction, mu, eps = _law_args(args)
    opts = dict(rtol=args.rtol, atol=args.atol, backend=args.backend, max_steps=args.max_steps, max_wall=args.max_wall)
    return runner(body=body, friction=friction, mu=mu, slip_eps=eps, start=start, t_end=args.t_end,
                  stop_at=args.stop_at, restitution=0.0 if args.restitution is None else args.restitution,
                  chart=args.chart, options=opts, pose0=_pose_of(args))


def _refuse(args, names, why):
    for name in names:
        if getattr(args, name) is not None:
            raise _UsageError(f"{FLAGS[name]} {why}", FLAGS[name])


def _paper_body(args) -> None:
    """The printed start fixes its body (a uniform spheroid of one aspect ratio): refuse, naming
    it, a flag that says otherwise; --a defaults to the start's."""
    from .._runtime.errors import plain
    from ..theory.paper import PAPER_CASES

    label = args.paper_start[1:-1] if re.fullmatch(r"\(.*\)", args.paper_start) else args.paper_start
    if label not in PAPER_CASES:
        raise _UsageError(f"--paper-start must be one of {', '.join(PAPER_CASES)} (the paper's printed starts), "
                          f"got {plain(args.paper_start)}.", "--paper-start")
    case = PAPER_CASES[label]
    args.paper_start = label
    which = f"with --paper-start {label} (its body is the uniform spheroid a = {case.a:.6g})"
    if args.body != "spheroid":
        raise _UsageError(f"--body must be spheroid {which}, got {plain(args.body)}.", "--body")
    for name in ("A", "C", "offset", "w"):
        if getattr(args, name) is not None:
            raise _UsageError(f"{FLAGS[name]} must be left out {which}, got {plain(getattr(args, name))}.", FLAGS[name])
    if args.a is None:
        args.a = case.a
    elif not abs(args.a - case.a) <= 1e-4 * case.a:  # the API's tolerance; also refuses nan
        raise _UsageError(f"--a must be {case.a:.6g} {which}, got {plain(args.a)}.", "--a")


def _manifold_states(body) -> tuple[str, ...]:
    """The steady states of ``body`` that --unstable-manifold can start from (phasekit.steady.fixedpoints:
    horizontal only where h_theta(pi/2) = 0, horizontal-like only for a body without flip symmetry
    that can lie on its side)."""
    from ..steady.fixedpoints import side_equilibrium

    level = body.flip_symmetric or abs(body.h(math.pi / 2)[1]) < 1e-14
    like = not body.flip_symmetric and math.isfinite(side_equilibrium(body)[0])
    return ("horizontal",) * level + ("vertical", "inverted") + ("horizontal-like",) * like


def _manifold_start(args, body) -> dict:
    from .._runtime.errors import plain

    _refuse(args, ["theta0"], "does not go with --unstable-manifold (the fixed point fixes theta)")
    states = ("vertical", "inverted") if args.unstable_manifold in ("vertical", "inverted") else _manifold_states(body)
    if args.unstable_manifold not in states:
        why = {"horizontal": " (it has no horizontal state: with its axis level its centre of mass is not above the "
                             "contact point" + ("; horizontal-like is the precession that continues it)"
                                                if "horizontal-like" in states else ")"),
               "horizontal-like": " (horizontal-like is for a body without flip symmetry that can lie on its side)"
               }.get(args.unstable_manifold, "")
        raise _UsageError(f"--unstable-manifold must be one of {', '.join(states)} for the {args.body} body{why}, "
                          f"got {plain(args.unstable_manifold)}.", "--unstable-manifold")
    return dict(kind="unstable-manifold", state=args.unstable_manifold,
                delta=0.01 if args.delta is None else args.delta, omega0=args.omega0, n0=args.n0,
                branch="+0" if args.branch is None else args.branch,
                seed_law="viscous" if args.seed_law is None else args.seed_law)


def _start_of(args, body) -> dict:
    if args.unstable_manifold is not None:
        return _manifold_start(args, body)
    _refuse(args, ["delta", "branch", "seed_law"], "goes with --unstable-manifold only")
    if args.gyroscopic:
        if args.theta0 is None:
            raise _UsageError("--theta0 is required with --gyroscopic (a number in (0, pi))", "--theta0")
        if (args.omega0 is None) == (args.n0 is None):
            raise _UsageError("--gyroscopic needs exactly one of --omega0 (prolate) or --n0 (oblate)", "--omega0")
        return dict(kind="gyroscopic", theta0=args.theta0, omega0=args.omega0, n0=args.n0)
    if args.spin_about_vertical is not None:
        if args.theta0 is None:
            raise _UsageError("--theta0 is required with --spin-about-vertical (a number in [0, pi])", "--theta0")
        _refuse(args, ["omega0", "n0"], "does not go with --spin-about-vertical (it sets the spin)")
        return dict(kind="spin-about-vertical", theta0=args.theta0, n0=args.spin_about_vertical)
    if args.paper_start is not None:
        _refuse(args, ["theta0"], "does not go with --paper-start (the printed start fixes theta)")
        return dict(kind="paper", label=args.paper_start, n0=args.n0, omega0=args.omega0)
    _refuse(args, ["theta0", "omega0", "n0"], "goes with --gyroscopic, --spin-about-vertical or --unstable-manifold, "
                                              "not with --state")
    return dict(kind="state", state=args.state)


def _cmd_fixed_points(args) -> dict:
    from .params import fixed_points_report

    friction, mu, eps = _law_args(args)
    return fixed_points_report(body=_body(args), mu=mu, friction=friction, slip_eps=eps, omega0=args.omega0, n0=args.n0)


def _cmd_steady_states(args) -> dict:
    from .params import steady_structure_report

    friction, mu, eps = _law_args(args)
    return steady_structure_report(body=_body(args), mu=mu, friction=friction, slip_eps=eps, omega0=args.omega0,
                                   n0=args.n0)


def _cmd_gyroscopic(args) -> dict:
    """The report at the times in the order given (the API returns them sorted)."""
    from .params import gyroscopic_report

    out = gyroscopic_report(body=_body(args), mu=args.mu, theta0=args.theta0, t=args.t, omega0=args.omega0, n0=args.n0)
    order = sorted(range(len(args.t)), key=args.t.__getitem__)  # the API's order (its times are finite)
    if len(out["t"]) == len(order) and order != sorted(order):
        for key in ("t", "T", "theta", "Omega"):
            values = [None] * len(order)
            for rank, i in enumerate(order):
                values[i] = out[key][rank]
            out[key] = values
    return out


def _fmt(v, spec: str = ".10g") -> str:
    return format(v, spec) if isinstance(v, float) else "undefined" if v is None else str(v)


def _print_structure(out: dict) -> None:
    print(f"signature: {out['signature']}   (linearisation: {out['linearised_law']})")
    for i, b in enumerate(out["branches"]):
        ends = " -> ".join(f"{e['kind']} at theta = {_fmt(e['theta'], '.10f')}"
                           + (f" (spin n = {_fmt(e['n'], '.8g')})" if e["kind"] == "pole" else "") for e in b["ends"])
        n_stable = sum(s["stable"] for s in b["samples"])
        print(f"branch {i + 1}: {ends}; {len(b['samples'])} samples, {n_stable} stable")
        for c in b["stability_changes"]:
            print(f"  stability changes at theta = {_fmt(c['theta'], '.9f')} ({c['kind']}; n_unstable "
                  f"{c['n_unstable_below']} -> {c['n_unstable_above']}; Omega = {_fmt(c['Omega'], '.6g')}, "
                  f"n = {_fmt(c['n'], '.6g')})")
    for st in out["static_equilibria"]:
        print(f"static equilibrium at theta = {_fmt(st['theta'], '.10f')} ({st['kind']}): {st['static_stability']}")
    for f in out["families"]:
        side = lambda v: "not computed" if v is None else "stable" if v else "unstable"  # noqa: E731
        crit = ("no change of stability: " + side(f["stable_on_intervals"][0])) if not f["criticals"] else (
            f"stability changes at |{f['parameter']}| = {', '.join(_fmt(c, '.10g') for c in f['criticals'])}; "
            f"{side(f['stable_above_critical'])} above")
        what = {"pole": "spin about the vertical", "precession": "precession", "rolling": "straight rolling"}[f["kind"]]
        print(f"{what} family at theta = {_fmt(f['theta'], '.6f')} (any {f['parameter']}): {crit}"
              + ("; a branch meets it there" if f["branch_meets"] else ""))
    if out.get("states"):
        for fp in out["states"]:
            print(f"state at {out['states_at']}: {fp['kind']} theta = {_fmt(fp['state']['theta'], '.10f')}: "
                  f"{fp['classification']}")


def _print_human(out: dict, events: bool) -> None:
    if "signature" in out:
        _print_structure(out)
        return
    if "fixed_points" in out:
        print(f"linearisation: {out['linearised_law']} ({out['stability']})")
        for fp in out["fixed_points"]:
            st = ", ".join(f"{k}={_fmt(v, '.8g')}" for k, v in fp["state"].items())
            line = f"{fp['kind']:<15s} {fp['classification']}; residual {_fmt(fp['residual'], '.1e')}  [{st}]"
            crit = (fp.get("parameter") or {}).get("stable_under_sliding_friction")
            if crit is not None:
                line += f"; closed-form criterion under sliding friction: {'stable' if crit else 'unstable'}"
            print(line)
        print(f"({out['note']})")
        return
    if "J" in out:
        print(f"J = {_fmt(out['J'])} ({out['J_definition']}), {out['method']}")
        for t, th, om in zip(out["t"], out["theta"], out["Omega"]):
            print(f"t = {_fmt(t, '12.6g')}   theta = {_fmt(th, '.12f')}   Omega = {_fmt(om, '.12f')}")
        return
    print(f"status: {out['status']}" + (f" ({out['reason']})" if out.get("reason") else ""))
    if out.get("animation"):
        an = out["animation"]
        speed = f", {an['playback_speed']:.3g}x real time" if an.get("playback_speed") else ""
        print(f"wrote {an['path']}: {an['frames']} frames of {an['frame_size'][0]}x{an['frame_size'][1]} pixels"
              f"{speed}, {an['bytes'] / 1e6:.2f} MB")
    for key in ("t_jump", "t_stop", "t_end", "theta_end", "R_min", "stuck", "mode_end"):
        if out.get(key) is not None:
            print(f"{key}: {_fmt(out[key])}")
    if out.get("flight"):
        print("flight: " + ", ".join(f"{k}={_fmt(v)}" for k, v in out["flight"].items()))
    if out.get("pose_end"):
        print("pose at the end: " + ", ".join(f"{k}={_fmt(v, '.8g')}" for k, v in out["pose_end"].items()))
    si = out.get("si")
    if si:
        u = si["units"]
        print(f"in real units (b = {si['b']}, g = {si['g']}, time unit {si['time_unit']}):")
        for key in ("t_jump", "t_stop", "t_end"):
            if si.get(key) is not None:
                print(f"  {key}: {_fmt(si[key], '.6g')} {u['time']}")
        fl = si.get("flight")
        if fl:
            print(f"  first flight: from {_fmt(fl['t_liftoff'], '.6g')} {u['time']}, lasting "
                  f"{_fmt(fl.get('duration'), '.4g')} {u['time']}, largest gap "
                  f"{_fmt(fl['gap_max'], '.4g')} {u['length']}")
        if si.get("state_end"):
            st = si["state_end"]
            print(f"  at the end: Omega={_fmt(st['Omega'], '.5g')} {u['rate']}, n={_fmt(st['n'], '.5g')} {u['rate']}")
    print(f"{out['n_events']} events, {out['n_steps']} steps, {out['wall_s'] * 1e3:.1f} ms, "
          f"{out['chart']} chart, {out['backend']}" + ("" if events else " (list the events with --events)"))
    if events:
        for e in out["events"]:
            print(f"  {e['kind']:<12s} t = {_fmt(e['t'])}  {e['mode_before']} -> {e['mode_after']}"
                  + (f"  ({e['detail']})" if e.get("detail") else ""))


def _nonfinite(obj, path: str = "") -> str | None:
    """The path of the first non-finite float in a JSON-ready object, or None."""
    if isinstance(obj, float):
        return None if math.isfinite(obj) else path or "(top)"
    if isinstance(obj, dict):
        items = obj.items()
    elif isinstance(obj, (list, tuple)):
        items = ((f"[{i}]", v) for i, v in enumerate(obj))
    else:
        return None
    for k, v in items:
        found = _nonfinite(v, f"{path}.{k}" if isinstance(obj, dict) and path else f"{path}{k}")
        if found:
            return found
    return None


def _finite_json(obj):
    """Replace non-finite floats by None: JSON has no NaN, and we never pass one off as a number."""
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, dict):
        return {k: _finite_json(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite_json(v) for v in obj]
    return obj


def _plain_types(obj):
    """numpy scalars and arrays -> Python floats, ints, lists (so that every check sees them)."""
    import numpy as np

    if isinstance(obj, dict):
        return {k: _plain_types(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain_types(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _plain_types(obj.tolist())
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.floating):
        return float(obj)
    return obj


def _json_default(obj):
    return str(obj)


@contextlib.contextmanager
def _stdout_to_stderr():
    """While computing, send everything written to stdout (Python or C++ libraries) to stderr,
    so that stdout holds only the result."""
    sys.stdout.flush()
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):  # no real file (e.g. captured in tests)
        with contextlib.redirect_stdout(sys.stderr):
            yield
        return
    saved = os.dup(fd)
    try:
        os.dup2(sys.stderr.fileno(), fd)
        with contextlib.redirect_stdout(sys.stderr):
            yield
    finally:
        sys.stdout.flush()
        os.dup2(saved, fd)
        os.close(saved)


def _flags_in(text: str, names: dict = FLAGS) -> str:
    """Python parameter names written `name` in a library message -> the CLI's flags."""
    text = re.sub(r"`(\w+)`\s*=\s*'([^']*)'", lambda m: f"{names[m.group(1)]} {m.group(2)}" if m.group(1) in names
                  else m.group(0), text)
    return re.sub(r"`(\w+)`", lambda m: names.get(m.group(1), m.group(0)), text)


def _error(message: str, flag: str | None, as_json: bool, code: int = 2, names: dict = FLAGS) -> int:
    """One line on stderr; with --json one object on stdout: status "error" (bad input) with the
    flag, or "failed" / "interrupted" with its reason."""
    message = " ".join(_flags_in(str(message), names).split())
    print(f"phasekit: error: {message}", file=sys.stderr)
    if as_json:
        status = "error" if code == 2 else "interrupted" if code == 130 else "failed"
        out = {"status": status, "parameter": flag, "message": message}
        print(json.dumps(out if code == 2 else {**out, "reason": message}))
    return code


def _show_warning(message, category, filename, lineno, file=None, line=None, names: dict = FLAGS):
    print(f"phasekit: warning: {' '.join(_flags_in(str(message), names).split())}", file=sys.stderr)


COMMANDS = {"simulate": _cmd_simulate, "animate": _cmd_animate, "fixed-points": _cmd_fixed_points,
            "steady-states": _cmd_steady_states,
            "gyroscopic": _cmd_gyroscopic}
#: set (to anything) to let unexpected exceptions propagate with their traceback (debugging, tests)
DEBUG_ENV = "PHASEKIT_DEBUG"


def _refuse_repeats(parser: _Parser, argv) -> None:
    """An option given twice is refused: a value-taking one (argparse would keep the last
    silently) and a switch too (``--json --json`` is a typing slip, as the README says)."""
    typed = _typed(argv)
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


def _run(argv, as_json: bool):
    """Parse and compute: (output dict, args), or raise."""
    parser = _build_parser()
    for p in (parser, *parser.commands.values()):
        p.argv = tuple(argv)
    args = parser.parse_args(argv)
    if args.command is None:
        raise _UsageError("a command is required: " + ", ".join(COMMANDS))
    _refuse_repeats(parser.commands[args.command], argv)
    with _stdout_to_stderr():
        out = _plain_types(COMMANDS[args.command](args))
    where = _nonfinite(out)
    if where is not None and out.get("status") != "failed":
        # a non-finite number is never a result: the run failed there
        out["status"], out["reason"] = "failed", f"non-finite value in the result at {where}"
    if out.get("status") == "failed" and not out.get("reason"):
        out["reason"] = "the computation could not continue"  # every failed result says why
    return _finite_json(out), args


def main(argv=None) -> int:
    """Run the CLI; returns the exit status (0 success, 1 failed run, 2 bad input, 130 interrupted)."""
    from .._runtime import startup as _startup

    _startup.started()  # from here on Ctrl-C is a KeyboardInterrupt, handled below
    from .._runtime.interrupts import interrupt_guard

    with interrupt_guard(mute=False) as guard:
        try:
            return _main(argv, guard)
        except KeyboardInterrupt:  # raised again by the guard after _main's own handlers
            guard["handled"] = True
            return _error("interrupted (a single run keeps nothing: run it again)", None, "--json" in (argv or sys.argv),
                          code=130)


def _main(argv, guard: dict) -> int:
    from .._runtime.errors import ParameterError, PhasekitError

    argv = list(sys.argv[1:] if argv is None else argv)
    as_json = "--json" in argv
    names = _flag_names(argv)  # a parameter fed by several flags is named by the one typed
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("default")
            warnings.showwarning = functools.partial(_show_warning, names=names)
            out, args = _run(argv, as_json)
    except _Exit as exc:
        return exc.code
    except _UsageError as exc:
        return _error(str(exc), exc.flag, as_json, names=names)
    except ParameterError as exc:
        name = names.get(exc.param)  # None: a parameter the CLI does not set (named as in Python)
        flag = name and name.split(" (")[0]
        message = exc.render(name or f"`{exc.param}`")
        if flag:  # "|n0| <= ..." in the range: the flag typed, not the Python name
            message = message.replace(f"|{exc.param}|", f"|{flag}|")
        return _error(message, flag, as_json, names=names)
    except PhasekitError as exc:
        return _error(str(exc), None, as_json, code=1, names=names)
    except KeyboardInterrupt:
        guard["handled"] = True
        return _error("interrupted (a single run keeps nothing: run it again)", None, as_json, code=130)
    except Exception as exc:  # a bug: one line, not a traceback (PHASEKIT_DEBUG=1 shows it)
        if guard.get("seen"):  # Ctrl-C that compiled code turned into an error of its own
            return _error("interrupted (a single run keeps nothing: run it again)", None, as_json, code=130)
        if os.environ.get(DEBUG_ENV):
            raise
        first = (str(exc).strip().splitlines() or [""])[0][:200]
        return _error(f"internal error: {type(exc).__name__}: {first} (please report it; set {DEBUG_ENV}=1 for the "
                      "traceback)", None, as_json, code=1)
    if guard.get("seen"):  # a Ctrl-C that compiled code swallowed (the run went on): still an interrupted run
        return _error("interrupted (a single run keeps nothing: run it again)", None, as_json, code=130)
    if as_json:
        print(json.dumps(out, default=_json_default, allow_nan=False))
    else:
        _print_human(out, getattr(args, "events", False))
    return 1 if out.get("status") == "failed" else 0


def main_entry() -> None:
    """Console-script entry point."""
    try:
        code = main()
        sys.stdout.flush()
    except BrokenPipeError:  # the reader went away (e.g. `| head`): stop quietly (Python docs' recipe)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        code = 1
    sys.exit(code)


if __name__ == "__main__":  # pragma: no cover
    main_entry()
