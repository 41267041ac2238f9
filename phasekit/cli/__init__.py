"""Command line: ``phasekit <command> ... [--json]`` (also ``python -m phasekit``).

Every command prints one JSON object with ``--json`` (and nothing else on stdout: library
output is sent to stderr while it runs). Exit codes and what stderr holds:

0    a result (stderr: at most one ``phasekit: warning:`` line per option that has no
     effect in the chosen mode, e.g. ``--restitution`` with ``--stop-at jump``);
1    a run that failed (status "failed" and its reason), or a solver error in one line;
2    bad input: one line naming the flag as typed, its valid range and the value as typed
     (a value typed with units also in phasekit's units); no warning line precedes it;
130  interrupted.
Warnings are held while the command computes and printed (before the result) only when the
inputs were accepted, so a refused command line prints its one error line and nothing else.
With ``--json`` an error is also one JSON object on stdout: status "error" with the flag
(``parameter``) and the ``message``, or "failed" / "interrupted" with its ``reason`` too.
A flag is named as typed (``--spin-about-vertical``, not the ``--n0`` it stands for); a
value-taking option given twice is refused. A non-finite number never reaches the output:
the run is reported failed, saying where. An unexpected exception (a bug) prints one line
too; set PHASEKIT_DEBUG=1 for its traceback (the tests do).
"""

from __future__ import annotations

import functools
import json
import os
import sys
import warnings

from .._runtime.watch import heartbeats
from .commands import COMMANDS
from .flags import FLAGS, flag_names, typed_value
from .output import (
    finite_json,
    json_default,
    nonfinite,
    plain_types,
    print_error,
    print_human,
    show_warning,
    stdout_to_stderr,
)
from .parser import EarlyExit, UsageError, build_parser, refuse_repeats

__all__ = ["main", "main_entry"]

#: set (to anything) to let unexpected exceptions propagate with their traceback (debugging, tests)
DEBUG_ENV = "PHASEKIT_DEBUG"
#: seconds between the lines a long run writes on stderr where no progress bar is shown
#: ($PHASEKIT_HEARTBEAT overrides it; the tests make it short)
HEARTBEAT_EVERY = float(os.environ.get("PHASEKIT_HEARTBEAT", "10"))


def _run(argv, as_json: bool):
    """Parse and compute: (output dict, args), or raise."""
    parser = build_parser()
    for p in (parser, *parser.commands.values()):
        p.argv = tuple(argv)
    args = parser.parse_args(argv)
    if args.command is None:
        raise UsageError("a command is required: " + ", ".join(COMMANDS))
    refuse_repeats(parser.commands[args.command], argv)
    with stdout_to_stderr():
        out = plain_types(COMMANDS[args.command](args))
    where = nonfinite(out)
    if where is not None and out.get("status") != "failed":
        # a non-finite number is never a result: the run failed there
        out["status"], out["reason"] = "failed", f"non-finite value in the result at {where}"
    if out.get("status") == "failed" and not out.get("reason"):
        out["reason"] = "the computation could not continue"  # every failed result says why
    return finite_json(out), args


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
            return print_error("interrupted (a single run keeps nothing: run it again)", None, "--json" in (argv or sys.argv),
                          code=130)


def _main(argv, guard: dict) -> int:
    from ..errors import ParameterError, PhasekitError

    argv = list(sys.argv[1:] if argv is None else argv)
    as_json = "--json" in argv
    names = flag_names(argv)  # a parameter fed by several flags is named by the one typed
    held: list = []  # the warnings, printed once the inputs are accepted (never before a refusal)
    say = functools.partial(_say_held, held, names)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("default")
            warnings.showwarning = lambda message, *a, **k: held.append(message)
            with heartbeats(HEARTBEAT_EVERY):  # a long run into a log file is not silent
                out, args = _run(argv, as_json)
    except EarlyExit as exc:
        return exc.code
    except UsageError as exc:
        return print_error(str(exc), exc.flag, as_json, names=names)
    except ParameterError as exc:
        name = names.get(exc.param)  # None: a parameter the CLI does not set (named as in Python)
        flag = name and name.split(" (")[0]
        message = _as_typed(exc, name, typed_value(argv, flag))
        if flag:  # "|n0| <= ..." in the range: the flag typed, not the Python name
            message = message.replace(f"|{exc.param}|", f"|{flag}|")
        return print_error(message, flag, as_json, names=names)
    except PhasekitError as exc:
        say()
        return print_error(str(exc), None, as_json, code=1, names=names)
    except KeyboardInterrupt:  # one line: the warnings of an abandoned run (a file an interrupted import left open) go
        guard["handled"] = True
        return print_error("interrupted (a single run keeps nothing: run it again)", None, as_json, code=130)
    except Exception as exc:  # a bug: one line, not a traceback (PHASEKIT_DEBUG=1 shows it)
        if guard.get("seen"):  # Ctrl-C that compiled code turned into an error of its own
            return print_error("interrupted (a single run keeps nothing: run it again)", None, as_json, code=130)
        if os.environ.get(DEBUG_ENV):
            raise
        first = (str(exc).strip().splitlines() or [""])[0][:200]
        return print_error(f"internal error: {type(exc).__name__}: {first} (please report it; set {DEBUG_ENV}=1 for the "
                      "traceback)", None, as_json, code=1)
    say()
    if guard.get("seen"):  # a Ctrl-C that compiled code swallowed (the run went on): still an interrupted run
        return print_error("interrupted (a single run keeps nothing: run it again)", None, as_json, code=130)
    if as_json:
        print(json.dumps(out, default=json_default, allow_nan=False))
    else:
        print_human(out, getattr(args, "events", False))
    return 1 if out.get("status") == "failed" else 0


def _say_held(held: list, names: dict) -> None:
    """Print the warnings held while the command computed (each once, in order)."""
    for message in dict.fromkeys(str(m) for m in held):
        show_warning(message, UserWarning, "", 0, names=names)
    held.clear()


#: what a number typed with units is converted to, by the kind of its flag
CONVERTED = {"angle": "rad", "rate": "in units of sqrt(g/b)", "time": "in units of sqrt(b/g)", "length": "in units of b",
             "rolling_resistance": "in units of b", "spin_friction": "in units of b", "patch": "in units of b",
             "air_drag": "in units of M b^2 sqrt(g/b)", "air_layer": "in units of M b^2 sqrt(g/b)",
             "air_drag_quadratic": "in units of M b^2",
             "air_drag_force": "in units of M sqrt(g/b)", "air_drag_force_quadratic": "in units of M/b"}


def _as_typed(exc, name: str | None, typed: str | None) -> str:
    """The message of a refused value, ending with the value as typed: a value typed with units
    ('200 deg') is shown so, with its number in phasekit's units (not that number alone)."""
    from .inputs import UNIT_OPTIONS

    message = exc.render(name or f"`{exc.param}`")
    try:
        float(typed)
        return message  # a plain number: the value is what was typed (and None: nothing typed)
    except (TypeError, ValueError):
        if typed is None:
            return message
    kind = next((k for dest, k in UNIT_OPTIONS.items() if name and name.split(" (")[0] == FLAGS.get(dest)), None)
    value = exc.value
    converted = f" ({float(value)!r} {CONVERTED[kind]})" if kind and isinstance(value, (int, float)) and \
        not isinstance(value, bool) else ""
    return f"{name or f'`{exc.param}`'} {exc.expected}, got {typed!r}{converted}."


def main_entry() -> None:
    """Console-script entry point."""
    try:
        code = main()
        sys.stdout.flush()
    except BrokenPipeError:  # the reader went away (e.g. `| head`): stop quietly (Python docs' recipe)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        code = 1
    if code == 130:  # interrupted, its one line written: leave now. Python's shutdown waits for background
        # compilations and puts SIGINT's default action back, and a SIGINT then ends the process by the signal:
        # seen once in CI (the line, then exit -2; which SIGINT, not found). Nothing is left to write.
        sys.stderr.flush()
        os._exit(130)
    sys.exit(code)


if __name__ == "__main__":  # pragma: no cover
    main_entry()
