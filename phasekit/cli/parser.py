"""The CLI's argument parser: every subcommand's flags and help, one-line usage errors.

:func:`build_parser` builds the parser of ``phasekit`` and its subcommands; :class:`_Parser`
turns argparse's errors into one :class:`UsageError` naming the flag, with a suggestion;
:func:`refuse_repeats` refuses an option given twice.
"""

from __future__ import annotations

import argparse
import difflib
import json
import math
import re

from .flags import typed_text
from .options import (
    STABILITY,
    add_body,
    add_friction,
    add_movie_options,
    add_run_options,
    add_units,
    add_wall,
    real,
    real_or_units,
)

EXAMPLES = """examples:
  phasekit simulate --a 1.5 --mu 0.1 --gyroscopic --theta0 1.5607963 --omega0 10.5 --json
  phasekit simulate --a 1.5 --mu 0.1 --paper-start 5.2 --slip-eps 1e-3 --t-end 300
  phasekit simulate --a 1.5 --mu 0.1 --state 0 0 0 0 1.0 0 --t-end 5
  phasekit simulate --body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --slip-eps 1e-8 \\
      --theta0 0.1 --spin-about-vertical 15 --stop-at theta=0.4 --t-end 30 --rtol 1e-10 --json
  phasekit simulate --body disk --radius "3.7 cm" --thickness "1.2 cm" --mu 0.5 --theta0 "60 deg" \\
      --spin-about-vertical "5 rev/s" --t-end "2 s"
  phasekit simulate --body disk --radius "37.5 mm" --thickness "12 mm" --mu 0.3 --theta0 "30 deg" \\
      --spinning-in-place --t-end "2 s"
  phasekit simulate --body cone --on tip --radius "2 cm" --height "3 cm" --mu 0.5 --theta0 "175 deg" \\
      --spun-about-axis "40 rev/s" --t-end "2 s" --si
  phasekit simulate --body disk --radius "12 mm" --thickness "1.5 mm" --mu 0.3 --theta0 "85 deg" \\
      --rolled "0.5 m/s" --t-end "1 s" --si
  phasekit fixed-points --a 1.5 --mu 0.1 --omega0 10 --json
  phasekit steady-states --body spheroid --a 1.5 --offset 0.2 --mu 0.1 --friction viscous
  phasekit steady-states --body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --json
  phasekit gyroscopic --a 1.5 --mu 0.1 --omega0 10.5 --theta0 1.5607963 --t 0 10 40
"""


class UsageError(Exception):
    def __init__(self, message: str, flag: str | None = None):
        super().__init__(message)
        self.flag = flag


class _Parser(argparse.ArgumentParser):
    """One-line errors; a subcommand's parser reports its own unknown options (so that a
    suggestion comes from its flags, and a flag of another subcommand is said to be one)."""

    command: str | None = None  # the subcommand this parser reads (None: the top level)
    commands: dict = {}  # every subcommand's parser, by name (set by build_parser)
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
            self._stray = extras[0]  # whole: a value may hold a space ('41 rev/s')
            self.error("unrecognized arguments: " + " ".join(extras))
        return namespace, extras

    def error(self, message):  # one line, no usage block
        flag = re.search(r"argument (--[\w-]+)|required: (--[\w-]+)$|unrecognized arguments: (\S+)", message)
        flag = next((g for g in flag.groups() if g), None) if flag else None
        if message.startswith("unrecognized arguments") and flag:
            flag = getattr(self, "_stray", None) or flag
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
        raise UsageError(message, flag)

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
        raise EarlyExit(0)


class EarlyExit(Exception):
    """End the CLI with this exit code (what argparse's own version action does with SystemExit)."""

    def __init__(self, code: int):
        super().__init__(code)
        self.code = code


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


def build_parser() -> _Parser:
    """The command line's parser: one sub-parser per command (:data:`phasekit.cli.commands.COMMANDS`),
    each knowing every command's parser (``commands``) and the parser knowing every flag."""
    from .. import __version__

    parser = _Parser(prog="phasekit", description="Phase space of an axisymmetric body spinning on a table.",
                     epilog=EXAMPLES)
    parser.add_argument("--version", action=_Version, nargs=0, version=__version__,
                        help="print the version and exit (a JSON object with --json)")
    sub = parser.add_subparsers(dest="command", parser_class=_Parser,
                                metavar="{simulate,animate,fixed-points,steady-states,gyroscopic,cache}")
    commands = {"simulate": _simulate_parser(sub), "animate": _animate_parser(sub),
                "fixed-points": _fixed_points_parser(sub), "steady-states": _steady_states_parser(sub),
                "gyroscopic": _gyroscopic_parser(sub), "cache": _cache_parser(sub)}
    for name, p in commands.items():
        p.command = name
    for p in (parser, *commands.values()):
        p.commands = commands
    parser.known_flags = {f for p in commands.values() for f in p._option_string_actions if f.startswith("--")}
    return parser


def _simulate_parser(sub):
    sim = sub.add_parser("simulate", help="integrate the exact equations from a start",
                         description="Integrate the contact dynamics (2.7) from a start, through stick, slip, "
                                     "lift-off and impacts, to a jump, a stop or --t-end.",
                         epilog=STABILITY + "\n" + UNITS_HELP + "\n" + EXAMPLES)
    add_run_options(sim)
    o = sim.add_argument_group("output")
    o.add_argument("--json", action="store_true", help="print one JSON object")
    o.add_argument("--events", action="store_true", help="list every event (human output)")
    o.add_argument("--si", action="store_true", help="also report times, gaps, positions and spins in ms, mm, m/s and "
                                                     "rev/s (needs --size)")
    return sim


def _animate_parser(sub):
    anim = sub.add_parser("animate", help="simulate, then write a movie (GIF, MP4) or film strip (PNG) of the body",
                          description="Run a simulation as `simulate` does and draw the body turning, precessing, "
                                      "travelling and lifting off, on a table with the contact path traced.",
                          epilog=UNITS_HELP + "\n" + ANIMATE_EXAMPLES)
    anim.add_argument("out", metavar="OUT", help="the file to write: .gif, .mp4 (needs phasekit[movie]) or .png "
                                                 "(a film strip)")
    add_run_options(anim)
    add_movie_options(anim)
    return anim


def _fixed_points_parser(sub):
    fx = sub.add_parser("fixed-points", help="steady states and their linear stability",
                        description="Steady states (vertical, horizontal, intermediate) at one Omega0 or n0, "
                                    "with the eigenvalues of their linearisation.", epilog=STABILITY + "\n" + EXAMPLES)
    add_body(fx, units=True)
    add_friction(fx)
    grp = fx.add_mutually_exclusive_group(required=True)
    grp.add_argument("--omega0", type=real_or_units, help="precession rate of the family (or e.g. '41 rev/s' with --size)")
    grp.add_argument("--n0", type=real_or_units, help="spin of the family (units as --omega0)")
    add_units(fx, mass=False)
    add_wall(fx)
    fx.add_argument("--json", action="store_true", help="print one JSON object")
    return fx


def _steady_states_parser(sub):
    ss = sub.add_parser("steady-states", help="the steady-state structure: branches, their ends, stability along them",
                        description="Every branch of steady precessions over 0 <= theta <= pi with its two ends (pole, "
                                    "static, infinite-spin), the stability along it and where it changes, the static "
                                    "equilibria, the spins about the vertical, and the structure's signature.",
                        epilog=STABILITY + "\n" + EXAMPLES)
    add_body(ss, units=True)
    add_friction(ss)
    g3 = ss.add_mutually_exclusive_group()
    g3.add_argument("--omega0", type=real_or_units, help="also list the states on the structure with this precession "
                                                          "rate (or e.g. '41 rev/s' with --size)")
    g3.add_argument("--n0", type=real_or_units, help="also list the states on the structure with this spin (units as "
                                                      "--omega0)")
    add_units(ss, mass=False)
    add_wall(ss)
    ss.add_argument("--json", action="store_true", help="print one JSON object")
    return ss


def _gyroscopic_parser(sub):
    gy = sub.add_parser("gyroscopic", help="gyroscopic mean solution theta-bar(t), Omega-bar(t) and J", epilog=EXAMPLES)
    add_body(gy)
    gy.add_argument("--mu", type=real, required=True, help="friction coefficient mu > 0 (sets the slow time mu t)")
    g2 = gy.add_mutually_exclusive_group(required=True)
    g2.add_argument("--omega0", type=real, help="precession rate (prolate), 0 < |OMEGA0| <= 1e12 (the mean solution "
                                                "is closed-form; simulate takes up to 1e5)")
    g2.add_argument("--n0", type=real, help="spin (oblate), 0 < |N0| <= 1e12, with |Omega| <= 1e12 on the fast branch")
    gy.add_argument("--theta0", type=real, required=True, help="initial inclination, radians, in (0, pi)")
    gy.add_argument("--t", type=real, nargs="+", required=True, help="times (units sqrt(b/g))")
    gy.add_argument("--json", action="store_true", help="print one JSON object")
    return gy


def _cache_parser(sub):
    ca = sub.add_parser("cache", help="show (or --clear) the compiled integrators kept on disk",
                        description="The disk cache of compiled integrators ($PHASEKIT_CACHE, default "
                                    "~/.cache/phasekit): phasekit's and heyoka's object code, in files and bytes.")
    ca.add_argument("--clear", action="store_true", help="delete them (the next run of each model compiles again)")
    ca.add_argument("--json", action="store_true", help="print one JSON object")
    return ca


def refuse_repeats(parser: _Parser, argv) -> None:
    """An option given twice is refused: a value-taking one (argparse would keep the last
    silently) and a switch too (``--json --json`` is a typing slip, as the README says); an
    option and its other name (``--chart`` and ``--formulation``) count as the same option."""
    typed = typed_text(argv)
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
            raise UsageError(f"{names} are names of the same option, given {len(flags)} times ({given}): give it "
                              "once", flags[1])
    for flag in dict.fromkeys(typed):
        action = parser._option_string_actions.get(flag)
        if action is None or typed.count(flag) < 2:
            continue
        if action.nargs == 0:
            raise UsageError(f"{flag} is given {typed.count(flag)} times: give it once", flag)
        if action.nargs is None:
            values = [t.split("=", 1)[1] if "=" in t else nxt for t, nxt in zip(argv, [*argv[1:], ""])
                      if t.split("=", 1)[0] == flag]
            raise UsageError(f"{flag} takes one value and is given {len(values)} times (got "
                              f"{', then '.join(values)}): give it once", flag)
        raise UsageError(f"{flag} is given {typed.count(flag)} times: give it once, with all its values", flag)
