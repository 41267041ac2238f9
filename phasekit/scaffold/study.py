"""The scaffold of a study script: its flags, output folder, resumable stores, Dask runs,
provenance, figures and tables, and the runner that turns Ctrl-C into one line saying how to resume.

A study is the science plus a few lines::

    import phasekit as pk

    def main(argv=None) -> dict:
        st = pk.scaffold.Study(__file__, __doc__, dask=True)    # --quick --out --no-progress --fresh, and
                                                            # --serial --scheduler --workers for Dask
        st.parser.add_argument("--seed", type=st.parser.integer(min=0), default=1)  # the study's own
        args = st.parse(argv)                               # checked at parse time; st.out made
        store = st.store(MyRow, {"grid": GRID})             # resumable rows + provenance manifest
        ran = st.run(specs, store, warm_up=compile_models)  # Dask (or --serial), only what is missing
        for case in st.progress(cases, desc="cases"): ...
        st.save(fig, "name.png"); st.csv("name.csv", header, rows); st.json("summary.json", d)

    if __name__ == "__main__":
        pk.scaffold.run_study(main)

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
import os
import shlex
import sys
import time
from collections.abc import Mapping
from pathlib import Path

from .._runtime.interrupts import interrupt_guard
from .._runtime.watch import progress_bar
from ..errors import ParameterError, PhasekitError
from ..sweep import ResultStore, provenance, run_pending
from ..sweep.stores import stored_rows
from ..viz import save_figure
from .parser import EXIT_FAILED, EXIT_USAGE, Current, output_dir, study_parser
from .writers import write_csv, write_json

#: exit code of a run ended by Ctrl-C (128 + SIGINT), as shells report it
EXIT_INTERRUPTED = 130
#: the result stores the study running in this process opened (run_study names them on Ctrl-C)
_STORES: list = []


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
    >>> st = pk.scaffold.Study("studies/demo.py", "A demo study.", dask=True)
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
        return progress_bar(total, iterable=iterable, desc=desc, unit="it", progress=self.show)

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
    known = Current.parser._option_string_actions if Current.parser is not None else {}
    return guess if guess in known else f"`{param}`"


def _fail(message: str, code: int):
    prog = (Current.parser.prog if Current.parser is not None else None) or Path(sys.argv[0]).name or "study"
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
    >>> pk.scaffold.run_study(lambda argv: print("ran with", argv), ["--quick"])
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
