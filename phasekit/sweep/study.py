"""The scaffold of a study script: its flags, output folder, resumable stores, Dask runs,
provenance, figures and tables, and the runner that turns Ctrl-C into one line saying how to resume.

A study is the science plus a few lines::

    import phasekit as pk

    def main(argv=None) -> dict:
        st = pk.sweep.Study(__file__, __doc__, dask=True)    # --quick --out --no-progress --fresh, and
                                                            # --serial --scheduler --workers for Dask
        st.parser.add_argument("--seed", type=st.parser.integer(min=0), default=1)  # the study's own
        args = st.parse(argv)                               # checked at parse time; st.out made
        store = st.store(MyRow, {"grid": GRID})             # resumable rows + provenance manifest
        ran = st.run(specs, store, warm_up=compile_models)  # Dask (or --serial), only what is missing
        for case in st.progress(cases, desc="cases"): ...
        st.save(fig, "name.png"); st.csv("name.csv", header, rows); st.json("summary.json", d)

    if __name__ == "__main__":
        pk.sweep.run_study(main)

Everything a study writes goes to ``figures/`` next to its folder (``figures/quick/`` with
``--quick``, or ``--out DIR``), each file written whole under a temporary name and renamed.

Bad input ends a study with one line on stderr naming the flag as typed, its valid range and
the value, and exit code 2: argparse errors (the parser prints no usage block), the number
types ``st.parser.integer`` / ``st.parser.real``, an ``--out`` that cannot be used, and any
:class:`phasekit.ParameterError` that escapes ``main`` (its parameter is named by the study's
flag). Another :class:`phasekit.PhasekitError` is one line and exit code 1. Ctrl-C is one line
and exit code 130, saying which result files keep the finished rows (those of the stores the
study opened) and the command that resumes (:mod:`phasekit._runtime.interrupts` keeps it from being lost).
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import json
import math
import os
import re
import shlex
import sys
import time
from collections.abc import Mapping
from pathlib import Path

from .._runtime.errors import ParameterError, PhasekitError
from .._runtime.interrupts import interrupt_guard
from ..io.tables import atomic_path
from .stores import ResultStore, provenance, stored_rows
from .tasks import run_pending

__all__ = ["Study", "study_parser", "StudyParser", "output_dir", "save_figure", "write_csv", "write_json", "atomic_path",
           "progress", "run_study"]

#: exit code of a run ended by Ctrl-C (128 + SIGINT), as shells report it
EXIT_INTERRUPTED = 130
#: exit code of bad input (argparse's), and of another phasekit error
EXIT_USAGE, EXIT_FAILED = 2, 1

#: the parser of the study running in this process (run_study names API parameters by its flags)
_PARSER: argparse.ArgumentParser | None = None
#: the result stores the study running in this process opened (run_study names them on Ctrl-C)
_STORES: list = []


def _typed(text: str) -> str:
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
                raise argparse.ArgumentTypeError(f"must be {want}, got {_typed(text)}") from None
            if (min is not None and value < min) or (max is not None and value > max):
                raise argparse.ArgumentTypeError(f"must be {want}, got {_typed(text)}")
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
                raise argparse.ArgumentTypeError(f"must be {want}, got {_typed(text)}") from None
            bad = not math.isfinite(value)
            if min is not None:
                bad = bad or value < min or (min_open and value == min)
            if max is not None:
                bad = bad or value > max or (max_open and value == max)
            if bad:
                raise argparse.ArgumentTypeError(f"must be {want}, got {_typed(text)}")
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
    global _PARSER
    ap = StudyParser(description=doc)
    if quick:
        ap.add_argument("--quick", action="store_true",
                        help=(quick_help or "a reduced run") + f"; writes to {Path(default_out) / 'quick'} unless --out is given")
    ap.add_argument("--out", default=None, type=_directory_name, metavar="DIR",
                    help=f"directory for the figures and tables (default: {default_out})")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    ap.set_defaults(default_out=str(default_out))
    _PARSER = ap
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


def save_figure(fig, path, *, dpi: int = 130, **savefig_kwargs) -> Path:
    """Save a matplotlib figure atomically (see :func:`atomic_path`) and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : path-like
        The file; its suffix gives the format (png if it has none).
    dpi : int, optional
        Resolution, dots per inch.
    **savefig_kwargs
        Go to ``Figure.savefig`` (e.g. ``bbox_inches="tight"``).

    Returns
    -------
    pathlib.Path
        ``path``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from phasekit.viz import pyplot, save_figure
    >>> fig, ax = pyplot().subplots()
    >>> save_figure(fig, pathlib.Path(tempfile.mkdtemp()) / "line.png").name
    'line.png'
    """
    import matplotlib.pyplot as plt

    path = Path(path)
    fmt = path.suffix.lstrip(".") or "png"
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, format=fmt, **savefig_kwargs)
    plt.close(fig)
    return path


def write_csv(path, header, rows) -> Path:
    """Write a whole table at once, atomically. A missing value (None or NaN) is an empty cell.

    Parameters
    ----------
    path : path-like
        The CSV file.
    header : sequence of str
        The column names.
    rows : iterable
        Sequences in the order of ``header``, or mappings (their keys outside ``header`` are left
        out, missing ones empty).

    Returns
    -------
    pathlib.Path
        ``path``.

    Examples
    --------
    >>> import phasekit as pk
    >>> import tempfile, pathlib
    >>> path = pk.sweep.write_csv(pathlib.Path(tempfile.mkdtemp()) / 't.csv', ['a', 'b'], [[1, None], {'a': 2, 'b': 'x'}])
    >>> print(path.read_text(), end="")
    a,b
    1,
    2,x
    """

    def blank(v):  # one spelling of missing: an empty cell (None and NaN alike)
        return "" if v is None or (isinstance(v, float) and math.isnan(v)) else v

    def cells(row):
        if isinstance(row, Mapping):
            return [blank(row.get(k)) for k in header]
        return [blank(v) for v in row]

    with atomic_path(path) as tmp:
        with open(tmp, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(header)
            w.writerows(cells(r) for r in rows)
            fh.flush()
            os.fsync(fh.fileno())
    return Path(path)


def write_json(path, obj, *, indent: int = 1, default=str) -> Path:
    """Write ``obj`` as JSON at once, atomically.

    Parameters
    ----------
    path : path-like
        The JSON file.
    obj : object
        What to write.
    indent : int, optional
        Indentation of ``json.dumps``.
    default : callable, optional
        Turns what JSON cannot hold into text.

    Returns
    -------
    pathlib.Path
        ``path``.

    Examples
    --------
    >>> import tempfile, pathlib, phasekit as pk
    >>> path = pk.sweep.write_json(pathlib.Path(tempfile.mkdtemp()) / "s.json", {"a": 1.5})
    >>> print(path.read_text())
    {
     "a": 1.5
    }
    """
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(obj, indent=indent, default=default))
    return Path(path)


def progress(iterable=None, *, total=None, desc: str = "", enabled: bool = True):
    """A tqdm progress bar on stderr (stdout stays the study's report); cleared when done."""
    from tqdm import tqdm

    return tqdm(iterable, total=total, desc=desc, disable=not enabled, file=sys.stderr, leave=False, dynamic_ncols=True)


class Study:
    """The scaffold of a study script (module notes): its flags, output folder, stores, runs and files.

    Parameters
    ----------
    script : str or Path
        The study's ``__file__``: its name names the study, and its results go to ``figures/``
        beside its folder (``figures/quick/`` with ``--quick``, or ``--out DIR``).
    doc : str
        The study's ``__doc__`` (its ``--help``).
    quick_help : str, optional
        What ``--quick`` reduces.
    quick : bool
        False: the study has no quick mode.
    resumable : bool
        It keeps finished rows (:meth:`store`): adds ``--fresh``.
    dask : bool
        It runs tasks on Dask (:meth:`run`): adds ``--serial``, ``--scheduler``, ``--workers``
        and ``--fresh``.

    Examples
    --------
    >>> import tempfile, phasekit as pk
    >>> st = pk.sweep.Study("studies/demo.py", "A demo study.", dask=True)
    >>> args = st.parse(["--quick", "--out", tempfile.mkdtemp(), "--serial"])
    >>> st.name, args.quick, args.serial, st.show
    ('demo', True, True, True)
    """

    def __init__(self, script, doc: str, *, quick_help: str | None = None, quick: bool = True, resumable: bool = False,
                 dask: bool = False):
        script = Path(script)
        self.name = script.stem
        self.parser = study_parser(doc, default_out=script.resolve().parents[1] / "figures", quick=quick,
                                   quick_help=quick_help)
        if dask:
            self.parser.add_argument("--serial", action="store_true", help="run in this process, without Dask")
            self.parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                                     help="address of a running Dask scheduler (host:port)")
            self.parser.add_argument("--workers", type=self.parser.integer(min=1), default=None, metavar="N",
                                     help="LocalCluster workers (default: one per core)")
        if resumable or dask:
            self.parser.add_argument("--fresh", action="store_true", help="discard stored results and recompute everything")
        self.args = self.out = None
        self.t0 = time.perf_counter()

    def parse(self, argv=None, check=None) -> argparse.Namespace:
        """Parse the command line (bad input: one line, exit code 2), call ``check(args)`` (the
        study's own checks of its flags through the API, before anything is made), and make
        the output folder.

        Parameters
        ----------
        argv : list of str, optional
            The arguments; by default ``sys.argv[1:]``.
        check : callable, optional
            ``check(args)``.
        """
        self.args = self.parser.parse_args(argv)
        if check is not None:
            check(self.args)
        self.out = output_dir(self.args)
        self.t0 = time.perf_counter()
        return self.args

    @property
    def quick(self) -> bool:
        return bool(getattr(self.args, "quick", False))

    @property
    def show(self) -> bool:
        """Whether progress bars are shown (``--no-progress`` turns them off)."""
        return not self.args.no_progress

    @property
    def wall(self) -> float:
        """Seconds since the command line was parsed."""
        return time.perf_counter() - self.t0

    def path(self, name: str) -> Path:
        return self.out / name

    def store(self, row_type, meta: dict | None = None, *, name: str | None = None):
        """The :class:`phasekit.sweep.ResultStore` ``<name>.csv`` (default: the study's name) of
        ``row_type`` rows in the output folder, its manifest carrying the provenance and ``meta``;
        emptied first with ``--fresh``. Ctrl-C then says that its rows are kept.

        Parameters
        ----------
        row_type : type
            The dataclass of a row (:class:`phasekit.sweep.ResultStore`).
        meta : dict, optional
            Further manifest entries.
        name : str, optional
            The file name without suffix.
        """
        stem = name or self.name
        store = ResultStore(self.out / f"{stem}.csv", self.out / f"{stem}.json", row_type,
                            provenance({"study": self.name, **(meta or {})}), fresh=bool(getattr(self.args, "fresh", False)))
        _STORES.append(store)
        return store

    def run(self, specs, *stores, members: dict | None = None, warm_up=None, desc: str = "tasks"):
        """Run the tasks whose rows are not stored yet (:func:`phasekit.sweep.run_pending`: on Dask,
        or in this process with ``--serial`` or without the Dask flags), each finished row added to
        the store of its type at once. A task's rows are ``members[task key]`` (row keys), or the
        one row keyed like the task. Returns the :class:`phasekit.sweep.tasks.PendingRun`.

        Parameters
        ----------
        specs : list of TaskSpec
            The tasks.
        *stores : ResultStore
            The stores of the rows.
        members : dict, optional
            Task key -> row keys.
        warm_up : callable, optional
            Compiles the models (:func:`phasekit.sweep.run_pending`).
        desc : str, optional
            The progress bar's label.
        """
        get, on_result = stored_rows(stores, members)
        a = self.args
        return run_pending(specs, store_get=get, on_result=on_result, warm_up=warm_up or (lambda: None),
                           serial=getattr(a, "serial", True), scheduler=getattr(a, "scheduler", None),
                           workers=getattr(a, "workers", None), progress=self.show, desc=desc)

    def sweep(self, specs, store, *, members: dict | None = None, warm_up=None, desc: str = "tasks"):
        """Run the tasks (:meth:`run`) and return the rows they produce, as ``store`` holds them
        (in the order stored; a store may hold other runs' rows too), and the
        :class:`phasekit.sweep.tasks.PendingRun`.

        Parameters
        ----------
        specs : list of TaskSpec
            The tasks.
        store : ResultStore
            The store of the rows.
        members, warm_up, desc
            As for :meth:`run`.
        """
        ran = self.run(specs, store, members=members, warm_up=warm_up, desc=desc)
        keys = [k for ks in members.values() for k in ks] if members else [s.key for s in specs]
        return store.rows(keys), ran

    def progress(self, iterable=None, *, total=None, desc: str = ""):
        """A progress bar on stderr, unless ``--no-progress``."""
        return progress(iterable, total=total, desc=desc, enabled=self.show)

    def save(self, fig, name: str, **savefig_kwargs) -> Path:
        """Save a matplotlib figure in the output folder (:func:`save_figure`)."""
        return save_figure(fig, self.out / name, **savefig_kwargs)

    def csv(self, name: str, header, rows) -> Path:
        """Write a table in the output folder (:func:`write_csv`)."""
        return write_csv(self.out / name, header, rows)

    def json(self, name: str, obj, **kw) -> Path:
        """Write a JSON summary in the output folder (:func:`write_json`)."""
        return write_json(self.out / name, obj, **kw)


def _command(argv) -> str:
    script = Path(sys.argv[0])
    with contextlib.suppress(ValueError):
        script = script.resolve().relative_to(Path.cwd())
    return shlex.join(["python", str(script), *argv])


def _flag(param: str, flags: Mapping[str, str] | None) -> str:
    """The flag a user typed for an API parameter: ``flags[param]``, else ``--param`` (with _ as
    -) if the study has that flag, else the parameter as the API names it."""
    if flags and param in flags:
        return flags[param]
    guess = "--" + param.replace("_", "-")
    known = getattr(_PARSER, "_option_string_actions", {})
    return guess if guess in known else f"`{param}`"


def _fail(message: str, code: int):
    prog = getattr(_PARSER, "prog", None) or Path(sys.argv[0]).name or "study"
    sys.stdout.flush()
    sys.stderr.write(f"{prog}: error: {' '.join(str(message).split())}\n")
    sys.stderr.flush()
    raise SystemExit(code) from None


def run_study(main, argv=None, *, resume: str | None = None, flags: Mapping[str, str] | None = None) -> None:
    """Run ``main(argv)`` as a command: Ctrl-C ends it with one line on stderr (no traceback)
    saying what was kept and how to resume, and exit code 130; a closed stdout pipe ends it
    quietly.

    A :class:`phasekit.ParameterError` that escapes ``main`` ends it with one line naming the
    flag the user typed and exit code 2; another :class:`phasekit.PhasekitError` with one line
    and exit code 1.

    Parameters
    ----------
    main : callable
        ``main(argv)``, the study.
    argv : list of str, optional
        The arguments; by default ``sys.argv[1:]``.
    resume : str, optional
        Says how a rerun picks up (for a study that keeps finished work; the command
        shown then leaves out ``--fresh``, which would discard it). By default it names the result
        stores the study opened (:meth:`Study.store`); a study that opened none writes its files
        whole at the end: nothing was changed, rerun.
    flags : mapping of str to str, optional
        Maps API parameter names to flags where ``--name`` is not it.

    Raises
    ------
    SystemExit
        With code 130 on Ctrl-C, 2 for a ParameterError, 1 for another PhasekitError or a closed stdout pipe.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.sweep.run_study(lambda argv: print("ran with", argv), ["--quick"])
    ran with ['--quick']
    """
    from .._runtime import startup as _startup

    _startup.started()  # Ctrl-C is a KeyboardInterrupt from here on, turned into one line below
    argv = sys.argv[1:] if argv is None else list(argv)
    _STORES.clear()
    try:
        with interrupt_guard() as guard:
            try:
                main(argv)
            except Exception:
                if guard.get("seen"):  # CasADi's dispatch turned the KeyboardInterrupt into an error of its own
                    raise KeyboardInterrupt from None
                raise
            if guard.get("seen"):  # a Ctrl-C that compiled code swallowed: the user still asked to stop
                raise KeyboardInterrupt
    except KeyboardInterrupt:
        if resume is None and _STORES:
            kept = " and ".join(Path(store.csv_path).name for store in _STORES)
            resume = f"the finished rows are kept in {kept} (in the output folder); rerunning the command resumes from them"
        how = resume or "no result file was changed (each is written whole, at the end); to resume, run it again"
        again = [a for a in argv if a != "--fresh"] if resume else argv
        with contextlib.suppress(Exception):
            sys.stdout.flush()
        sys.stderr.write(f"\ninterrupted: {how}: {_command(again)}\n")
        sys.stderr.flush()
        raise SystemExit(EXIT_INTERRUPTED) from None
    except BrokenPipeError:  # the reader went away (e.g. `| head`): stop quietly (Python docs' recipe)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        raise SystemExit(1) from None
    except ParameterError as exc:
        _fail(exc.render(_flag(exc.param, flags)), EXIT_USAGE)
    except PhasekitError as exc:
        _fail(str(exc), EXIT_FAILED)
