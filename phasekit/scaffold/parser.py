"""A study's command line and output folder: :class:`StudyParser` (argparse with one-line errors,
checked number types, repeats refused), the flags every study has (:func:`study_parser`) and where
it writes (:func:`output_dir`)."""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
from pathlib import Path

from ..errors import ParameterError

#: exit code of bad input (argparse's), and of another phasekit error
EXIT_USAGE, EXIT_FAILED = 2, 1


class Current:
    """The parser of the study running in this process (:func:`phasekit.scaffold.run_study` names
    API parameters by its flags)."""

    parser: argparse.ArgumentParser | None = None


def typed_text(text: str) -> str:
    """A value as the user typed it: numbers plain, anything else quoted."""
    try:
        float(text)
    except ValueError:
        return repr(text)
    return text.strip()


class StudyParser(argparse.ArgumentParser):
    """argparse with one-line errors (``prog: error: argument --flag: ...``, exit code 2, no
    usage block) and checked number types for a study's flags: ``type=ap.integer(min=1)``,
    ``type=ap.real(min=0, min_open=True)``. Abbreviated options are refused."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        kwargs.setdefault("formatter_class", argparse.RawDescriptionHelpFormatter)
        super().__init__(*args, **kwargs)
        # argparse's own pattern misses exponents, so "--mu -1e-4" would read -1e-4 as an option
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|nan)$", re.I)

    def error(self, message):  # one line, no usage block
        self.exit(EXIT_USAGE, f"{self.prog}: error: {' '.join(str(message).split())}\n")

    def parse_args(self, args=None, namespace=None):
        """As argparse, and an option given twice is refused (argparse would keep the last
        silently), a switch too, as the CLI does."""
        argv = sys.argv[1:] if args is None else list(args)
        argv = argv[:argv.index("--")] if "--" in argv else argv
        typed = [a.split("=", 1)[0] for a in argv if isinstance(a, str) and a.startswith("--") and len(a) > 2]
        for flag in dict.fromkeys(typed):
            if flag in self._option_string_actions and typed.count(flag) > 1:
                self.error(f"{flag} is given {typed.count(flag)} times: give it once")
        return super().parse_args(args, namespace)

    @staticmethod
    def integer(min: int | None = None, max: int | None = None):
        """An argparse ``type``: an integer in [min, max] (either bound may be None)."""
        if min is not None and max is not None:
            want = f"an integer in [{min}, {max}]"
        else:
            want = "an integer" + (f" >= {min}" if min is not None else f" <= {max}" if max is not None else "")

        def integer(text: str) -> int:
            try:
                value = int(text)
            except ValueError:
                raise argparse.ArgumentTypeError(f"must be {want}, got {typed_text(text)}") from None
            if (min is not None and value < min) or (max is not None and value > max):
                raise argparse.ArgumentTypeError(f"must be {want}, got {typed_text(text)}")
            return value

        return integer

    @staticmethod
    def real(min: float | None = None, max: float | None = None, *, min_open: bool = False, max_open: bool = False):
        """An argparse ``type``: a finite number in the range given (bounds inclusive unless
        ``min_open`` / ``max_open``); nan and inf are refused."""
        parts = []
        if min is not None:
            parts.append(f"{'>' if min_open else '>='} {float(min):g}")
        if max is not None:
            parts.append(f"{'<' if max_open else '<='} {float(max):g}")
        want = "a finite number" + (" " + " and ".join(parts) if parts else "")

        def real(text: str) -> float:
            try:
                value = float(text)
            except ValueError:
                raise argparse.ArgumentTypeError(f"must be {want}, got {typed_text(text)}") from None
            bad = not math.isfinite(value)
            if min is not None:
                bad = bad or value < min or (min_open and value == min)
            if max is not None:
                bad = bad or value > max or (max_open and value == max)
            if bad:
                raise argparse.ArgumentTypeError(f"must be {want}, got {typed_text(text)}")
            return value

        return real


def _directory_name(text: str) -> str:
    """``--out``: a non-empty path (an empty one would silently mean the default folder)."""
    if not text.strip():
        raise argparse.ArgumentTypeError(f"must name a directory, got {text!r} (omit --out for the default folder)")
    return text


def study_parser(doc: str, *, default_out: Path, quick: bool = True, quick_help: str | None = None) -> StudyParser:
    """An argument parser (a :class:`StudyParser`) with the options every study has:
    ``--quick`` (a reduced run, written to ``figures/quick/`` unless ``--out`` is given, never
    over the committed results), ``--out DIR`` and ``--no-progress``. Abbreviated options are
    refused (``--q`` is not ``--quick``); an error is one line naming the flag, exit code 2."""
    ap = StudyParser(description=doc)
    if quick:
        ap.add_argument("--quick", action="store_true",
                        help=(quick_help or "a reduced run") + f"; writes to {Path(default_out) / 'quick'} unless --out is given")
    ap.add_argument("--out", default=None, type=_directory_name, metavar="DIR",
                    help=f"directory for the figures and tables (default: {default_out})")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    ap.set_defaults(default_out=str(default_out))
    Current.parser = ap
    return ap


def output_dir(args) -> Path:
    """Where a study writes: --out, else figures/ for a full run and figures/quick/ for --quick
    (so that a quick run never overwrites the committed results). Created if missing.

    Raises :class:`phasekit.ParameterError` (parameter ``out``) for an empty ``--out``, a path
    that is not a directory, cannot be created or is not writable."""
    given = getattr(args, "out", None)
    if given is not None:
        if not str(given).strip():
            raise ParameterError("out", "must name a directory (omit it for the default folder)", str(given))
        out = Path(given)
    elif getattr(args, "quick", False):
        out = Path(args.default_out) / "quick"
    else:
        out = Path(args.default_out)
    value = str(given) if given is not None else str(out)

    def refuse(why: str):
        return ParameterError("out", f"must be a writable directory, but {why}", value)

    try:
        out.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise refuse("it is an existing file, not a directory") from None
    except NotADirectoryError:
        raise refuse("it cannot be created: a part of the path is a file, not a directory") from None
    except PermissionError:
        raise refuse("it cannot be created: permission denied") from None
    except OSError as exc:
        raise refuse(f"it cannot be created ({(exc.strerror or type(exc).__name__).lower()})") from None
    if not out.is_dir():
        raise refuse("it is not a directory")
    if not os.access(out, os.W_OK | os.X_OK):
        raise refuse("it is not writable")
    return out
