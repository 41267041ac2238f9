"""Output shared by the studies: an argument parser with --quick/--out, a progress bar,
matplotlib off-screen, figures and CSV tables written so that a kill leaves no torn file."""

from __future__ import annotations

import argparse
import csv
import os
import sys
from pathlib import Path

__all__ = ["study_parser", "output_dir", "pyplot", "save_figure", "write_csv", "progress"]


def study_parser(doc: str, *, default_out: Path, quick: bool = True) -> argparse.ArgumentParser:
    """An argument parser with the options every study has: ``--quick`` (a reduced run, written
    to a temporary-named directory unless ``--out`` is given, never over the committed
    results), ``--out DIR`` and ``--no-progress``."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter, allow_abbrev=False)
    if quick:
        ap.add_argument("--quick", action="store_true", help="a reduced run (minutes); writes to figures/quick/ unless --out")
    ap.add_argument("--out", default=None, help=f"directory for the figures and tables (default: {default_out})")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar")
    ap.set_defaults(default_out=str(default_out))
    return ap


def output_dir(args) -> Path:
    """Where a study writes: --out, else figures/ for a full run and figures/quick/ for --quick
    (so that a quick run never overwrites the committed results)."""
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


def _atomic(path: Path, write) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        write(tmp)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    return path


def save_figure(fig, path, *, dpi: int = 130) -> Path:
    """Save ``fig`` (written to a temporary file, then renamed) and close it."""
    import matplotlib.pyplot as plt

    fmt = Path(path).suffix.lstrip(".") or "png"
    out = _atomic(Path(path), lambda tmp: fig.savefig(tmp, dpi=dpi, format=fmt))
    plt.close(fig)
    return out


def write_csv(path, header, rows) -> Path:
    """Write a whole table at once (temporary file, then rename)."""

    def write(tmp):
        with open(tmp, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(header)
            w.writerows(rows)

    return _atomic(Path(path), write)


def progress(iterable=None, *, total=None, desc: str = "", enabled: bool = True):
    """A tqdm progress bar on stderr."""
    from tqdm import tqdm

    return tqdm(iterable, total=total, desc=desc, disable=not enabled, file=sys.stderr, leave=False)
