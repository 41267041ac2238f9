"""One cache for every engine's compiled integrators: :func:`compiled` builds an entry once and keeps
it in memory and (heyoka's, whose LLVM compilation costs seconds to minutes) on disk, under
``$PHASEKIT_CACHE`` (default ``~/.cache/phasekit``; empty: no disk cache). :func:`snapshot` and
:func:`install` move the picklable entries between processes (:class:`phasekit.sweep.ModelPack`).
"""

from __future__ import annotations

import hashlib
import os
import pickle
import threading
from collections.abc import Callable
from pathlib import Path

from .taylor_build import _heyoka

#: bump when the layout of the pickled cache entries changes
CACHE_FORMAT = 4


def _cache_dir() -> Path | None:
    root = os.environ.get("PHASEKIT_CACHE")
    if root == "":
        return None  # caching disabled
    path = Path(root) if root else Path.home() / ".cache" / "phasekit"
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return path


_LOCK = threading.Lock()
_MEMORY: dict = {}  # key -> compiled entry (what ``build`` returned)
_PERSISTENT: set = set()  # the keys whose entries are picklable (heyoka's), for snapshot()
_RECORDERS: dict = {}  # id(integrator) -> the monitor recorder inside it (looked up once)


def compiled(key: tuple, build: Callable[[], object], *, disk: str | None = None):
    """The compiled entry ``key`` of an engine: from memory, else (``disk`` names the file kind)
    from the on-disk cache, else ``build()`` (then stored in both). Disk files are written under
    a temporary name and renamed, so processes sharing the cache never read a torn one."""
    with _LOCK:
        entry = _MEMORY.get(key)
    if entry is not None:
        return entry
    path = None
    if disk is not None:
        hy = _heyoka()
        digest = hashlib.sha256(repr((CACHE_FORMAT, key, hy.__version__)).encode()).hexdigest()[:24]
        cache = _cache_dir()
        path = cache / f"{disk}-{digest}.pkl" if cache else None
    if path is not None and path.exists():
        try:
            with open(path, "rb") as fh:
                entry = pickle.load(fh)
        except Exception:  # a stale or partial file: rebuild it
            entry = None
    if entry is None:
        entry = build()
        if path is not None:
            try:
                tmp = path.with_suffix(f".{os.getpid()}.tmp")
                with open(tmp, "wb") as fh:
                    pickle.dump(entry, fh)
                os.replace(tmp, path)
            except Exception:
                pass
    with _LOCK:
        entry = _MEMORY.setdefault(key, entry)
        if disk is not None:
            _PERSISTENT.add(key)
    return entry


def snapshot() -> dict:
    """The picklable compiled integrators of this process (for :class:`phasekit.sweep.ModelPack`)."""
    with _LOCK:
        return {k: _MEMORY[k] for k in _PERSISTENT}


def install(entries: dict) -> None:
    """Add a :func:`snapshot` of another process to this one's cache (entries already here are kept)."""
    with _LOCK:
        for k, v in entries.items():
            _MEMORY.setdefault(k, v)
            _PERSISTENT.add(k)


def forget() -> None:
    """Empty the in-memory cache (the next use reloads from disk; tests of the disk cache)."""
    with _LOCK:
        _MEMORY.clear()
        _PERSISTENT.clear()
        _RECORDERS.clear()
