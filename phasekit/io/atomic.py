"""Atomic writes: every result file is written to a temporary path beside it and renamed onto it,
so that a kill at any moment leaves the old file or the new one, never half of one."""

from __future__ import annotations

import contextlib
import os
from pathlib import Path


@contextlib.contextmanager
def atomic_path(path):
    """A temporary path next to ``path`` to write to; renamed onto ``path`` when the block
    ends without an exception, removed otherwise. A kill at any moment leaves either the old
    file or the new one, never a torn one.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write; its directory is created if missing.

    Yields
    ------
    pathlib.Path
        The temporary path, in the same directory and with the same suffix as ``path``.

    Examples
    --------
    >>> import tempfile, pathlib, phasekit as pk
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "note.txt"
    >>> with pk.io.atomic_path(target) as tmp:
    ...     _ = tmp.write_text("whole")
    >>> target.read_text()
    'whole'
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
