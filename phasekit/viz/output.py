"""Output shared by the studies and benchmarks: an argument parser with --quick/--out/--no-progress,
a progress bar, matplotlib off-screen, figures and tables written so that a kill leaves no torn
file, and a runner that turns Ctrl-C into one line saying how to resume.

A study is ``main(argv) -> result`` written with these helpers and ended by
``run_study(main)`` under ``if __name__ == "__main__":``::

    ap = study_parser(__doc__, default_out=FIGURES)
    args = ap.parse_args(argv)
    out = output_dir(args)                       # figures/, figures/quick/ or --out
    for case in progress(cases, desc="cases", enabled=not args.no_progress): ...
    save_figure(fig, out / "name.png")
    write_csv(out / "name.csv", header, rows)
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import os
import shlex
import sys
from collections.abc import Mapping
from pathlib import Path

__all__ = ["study_parser", "output_dir", "pyplot", "save_figure", "write_csv", "atomic_path", "progress", "run_study"]

#: exit code of a run ended by Ctrl-C (128 + SIGINT), as shells report it
EXIT_INTERRUPTED = 130


def study_parser(doc: str, *, default_out: Path, quick: bool = True, quick_help: str | None = None) -> argparse.ArgumentParser:
    """An argument parser with the options every study has: ``--quick`` (a reduced run, written
    to ``figures/quick/`` unless ``--out`` is given, never over the committed results),
    ``--out DIR`` and ``--no-progress``. Abbreviated options are refused (``--q`` is not
    ``--quick``)."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter, allow_abbrev=False)
    if quick:
        ap.add_argument("--quick", action="store_true",
                        help=(quick_help or "a reduced run") + f"; writes to {Path(default_out) / 'quick'} unless --out is given")
    ap.add_argument("--out", default=None, metavar="DIR", help=f"directory for the figures and tables (default: {default_out})")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    ap.set_defaults(default_out=str(default_out))
    return ap


def output_dir(args) -> Path:
    """Where a study writes: --out, else figures/ for a full run and figures/quick/ for --quick
    (so that a quick run never overwrites the committed results). Created if missing."""
    if args.out:
        out = Path(args.out)
    elif getattr(args, "quick", False):
        out = Path(args.default_out) / "quick"
    else:
        out = Path(args.default_out)
    out.mkdir(parents=True, exist_ok=True)
    return out


def pyplot():
    """matplotlib.pyplot with the off-screen Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


@contextlib.contextmanager
def atomic_path(path):
    """A temporary path next to ``path`` to write to; renamed onto ``path`` when the block
    ends without an exception, removed otherwise. A kill at any moment leaves either the old
    file or the new one, never a torn one.

    >>> with atomic_path("figures/scene.png") as tmp:  # doctest: +SKIP
    ...     render_scene(data, tmp)
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # keep the suffix: writers (matplotlib, VTK) pick the format from it
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def save_figure(fig, path, *, dpi: int = 130, **savefig_kwargs) -> Path:
    """Save ``fig`` atomically (see :func:`atomic_path`) and close it; ``savefig_kwargs`` go to
    ``Figure.savefig`` (e.g. ``bbox_inches="tight"``)."""
    import matplotlib.pyplot as plt

    path = Path(path)
    fmt = path.suffix.lstrip(".") or "png"
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, format=fmt, **savefig_kwargs)
    plt.close(fig)
    return path


def write_csv(path, header, rows) -> Path:
    """Write a whole table at once, atomically. ``rows`` are sequences in the order of
    ``header``, or mappings (their keys outside ``header`` are left out, missing ones empty)."""

    def cells(row):
        if isinstance(row, Mapping):
            return ["" if row.get(k) is None else row[k] for k in header]
        return list(row)

    with atomic_path(path) as tmp:
        with open(tmp, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(header)
            w.writerows(cells(r) for r in rows)
            fh.flush()
            os.fsync(fh.fileno())
    return Path(path)


def progress(iterable=None, *, total=None, desc: str = "", enabled: bool = True):
    """A tqdm progress bar on stderr (stdout stays the study's report); cleared when done."""
    from tqdm import tqdm

    return tqdm(iterable, total=total, desc=desc, disable=not enabled, file=sys.stderr, leave=False, dynamic_ncols=True)


def _command(argv) -> str:
    script = Path(sys.argv[0])
    with contextlib.suppress(ValueError):
        script = script.resolve().relative_to(Path.cwd())
    return shlex.join(["python", str(script), *argv])


def run_study(main, argv=None, *, resume: str | None = None) -> None:
    """Run ``main(argv)`` as a command: Ctrl-C ends it with one line on stderr (no traceback)
    saying what was kept and how to resume, and exit code 130; a closed stdout pipe ends it
    quietly.

    ``resume`` says how a rerun picks up (for a study that keeps finished work); the default
    is for studies that write their files whole at the end: nothing was changed, rerun.
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        main(argv)
    except KeyboardInterrupt:
        how = resume or "no result file was changed (each is written whole, at the end); to resume, run it again"
        sys.stderr.write(f"\ninterrupted: {how}: {_command(argv)}\n")
        sys.stderr.flush()
        raise SystemExit(EXIT_INTERRUPTED) from None
    except BrokenPipeError:  # the reader went away (e.g. `| head`): stop quietly (Python docs' recipe)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        raise SystemExit(1) from None
