"""One cache for every engine's compiled integrators: :func:`compiled` builds an entry once and keeps
it in memory and (heyoka's, whose LLVM compilation costs seconds to minutes) on disk, under
``$PHASEKIT_CACHE`` (default ``~/.cache/phasekit``; empty: no disk cache; at most
:data:`INTEGRATOR_CACHE_LIMIT` bytes, the least recently used deleted first). heyoka's own cache of
compiled object code lives under the same directory (``heyoka/``, at most :data:`HEYOKA_CACHE_LIMIT`
bytes), so that one place holds, shows and clears everything compiled. :func:`snapshot` and
:func:`install` move the picklable entries between processes (:class:`phasekit.sweep.ModelPack`).

A build that takes longer than ``$PHASEKIT_COMPILE_NOTICE`` seconds (default 1; ``off``: never)
says so in one line on stderr while it runs, and once more when it is done; the same two messages
go at INFO level to the ``compile`` child of the logger named ``phasekit`` (the hook for a program
that shows its own progress: ``logging.getLogger("phasekit").getChild("compile")``).
"""

from __future__ import annotations

import atexit
import contextlib
import hashlib
import logging
import os
import pickle
import shutil
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

from .taylor_build import load_heyoka

#: bump when the layout of the pickled cache entries, or how they are built, changes
CACHE_FORMAT = 6  # 6: integrators in scaled variables (engines/scaling.py)
#: bytes of heyoka's object-code cache under the cache directory (heyoka's own default is 20 GiB)
HEYOKA_CACHE_LIMIT = 1 << 30
#: bytes of phasekit's compiled integrators there: past it, the least recently used are deleted
#: when a new one is written (an integrator is 1-60 MB; 2.1 GB had gathered on one machine)
INTEGRATOR_CACHE_LIMIT = 1 << 30

_LOG = logging.getLogger("phasekit").getChild("compile")
_WHAT = {"taylor": "the Taylor integrator of this model", "taylor-batch": "the batch Taylor integrator of this model"}


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


def _place_heyoka_cache() -> None:
    """Point heyoka's disk cache into phasekit's cache directory, bounded (off when caching is)."""
    llvm = load_heyoka().llvm_state
    cache = _cache_dir()
    if cache is None:
        llvm.set_diskcache_enabled(False)
        return
    path = str(cache / "heyoka")
    if llvm.get_diskcache_path() != path:
        llvm.set_diskcache_path(path)
        llvm.set_diskcache_limit(HEYOKA_CACHE_LIMIT)


def _notice_after() -> float | None:
    """Seconds a build runs before it is announced (None: never), from $PHASEKIT_COMPILE_NOTICE."""
    raw = os.environ.get("PHASEKIT_COMPILE_NOTICE", "1").strip().lower()
    if raw in ("off", "none", "no"):
        return None
    try:
        after = float(raw)
    except ValueError:
        return 1.0
    return after if after >= 0 else None


def _announced(build: Callable[[], object], disk: str | None, label: str | None = None) -> object:
    """``build()``, announced on stderr and to the compile logger if it runs long (``label`` says
    what is compiled, by default the kind of ``disk``)."""
    after = _notice_after()
    if after is None:
        return build()
    said = threading.Event()

    def say():
        said.set()
        where = _cache_dir() if disk is not None else None
        text = (f"compiling {label or _WHAT.get(disk, 'the solver of this model')} "
                + (f"(heyoka/LLVM; once, then cached in {where}) ..." if where else "(once per process) ..."))
        _say(text)

    timer = threading.Timer(after, say)
    timer.daemon = True
    start = time.perf_counter()
    timer.start()
    try:
        return build()
    finally:
        timer.cancel()
        timer.join()  # a notice being printed is finished before its "compiled" line
        if said.is_set():
            _say(f"compiled in {time.perf_counter() - start:.1f} s")


_SAYING = threading.Lock()


def _say(text: str) -> None:
    """One notice line, written whole: print() writes the text and its newline separately, so two
    compilations in two threads could share a line."""
    _LOG.info(text)
    with _SAYING:
        sys.stderr.write(f"phasekit: {text}\n")
        sys.stderr.flush()


_LOCK = threading.Lock()
_MEMORY: dict = {}  # key -> compiled entry (what ``build`` returned)
_BUILDING: dict = {}  # key -> threading.Event, set when the build under way has finished (or failed)
_PERSISTENT: set = set()  # the keys whose entries are picklable (heyoka's), for snapshot()
RECORDERS: dict = {}  # id(integrator) -> the monitor recorder inside it (looked up once)


def compiled(key: tuple, build: Callable[[], object], *, disk: str | None = None, label: str | None = None):
    """The compiled entry ``key`` of an engine: from memory, else (``disk`` names the file kind)
    from the on-disk cache, else ``build()`` (then stored in both). Disk files are written under
    a temporary name and renamed, so processes sharing the cache never read a torn one."""
    while True:  # one build per key: a second caller waits for the first (a background prefetch)
        with _LOCK:
            entry = _MEMORY.get(key)
            if entry is not None:
                return entry
            pending = _BUILDING.get(key)
            if pending is None:
                _BUILDING[key] = threading.Event()
                break
        pending.wait()
    try:
        return _load_or_build(key, build, disk, label)
    finally:
        with _LOCK:
            _BUILDING.pop(key).set()


def prefetch(key: tuple, build: Callable[[], object], *, disk: str | None = None, label: str | None = None) -> None:
    """:func:`compiled` in a background thread: the entry is ready (or being built) when it is asked
    for. heyoka compiles with the GIL released, so on two cores a run's next mode compiles while
    the first one runs. The process waits for builds under way when it exits (an LLVM build
    cannot be interrupted)."""
    with _LOCK:
        if key in _MEMORY or key in _BUILDING:
            return
    thread = threading.Thread(target=_quietly, args=(key, build, disk, label), name="phasekit-prefetch", daemon=True)
    _THREADS.append(thread)
    thread.start()


_THREADS: list = []


def _quietly(key, build, disk, label) -> None:
    try:
        compiled(key, build, disk=disk, label=label)
    except Exception as exc:  # the run that needs it builds it again and sees the error itself
        _LOG.debug("prefetch of %r failed: %s", key, exc)


@atexit.register
def _join_prefetches() -> None:
    for thread in _THREADS:
        thread.join()


def _load_or_build(key: tuple, build: Callable[[], object], disk: str | None, label: str | None = None):
    entry = path = None
    if disk is not None:
        hy = load_heyoka()
        digest = hashlib.sha256(repr((CACHE_FORMAT, key, hy.__version__)).encode()).hexdigest()[:24]
        cache = _cache_dir()
        path = cache / f"{disk}-{digest}.pkl" if cache else None
    entry = _loaded(path)
    if entry is None and path is not None:
        with _machine_lock(path):  # one process of the machine builds it; the others wait, then load it
            entry = _loaded(path)
            if entry is None:
                entry = _built(build, disk, label, path)
    elif entry is None:
        entry = _built(build, disk, label, path)
    with _LOCK:
        entry = _MEMORY.setdefault(key, entry)
        if disk is not None:
            _PERSISTENT.add(key)
    return entry


def _loaded(path: Path | None):
    """The entry stored at ``path``, or None (no file, or a stale or partial one: rebuilt)."""
    if path is None or not path.exists():
        return None
    try:
        with open(path, "rb") as fh:
            entry = pickle.load(fh)
        os.utime(path)  # used now: the last to be trimmed
    except Exception:
        return None
    return entry


#: how long a process waits for another one's build of the same integrator before building it too
LOCK_WAIT = 900.0


@contextlib.contextmanager
def _machine_lock(path: Path):
    """An exclusive lock on ``path``'s build shared by the machine's processes (Dask workers, a
    study's pool, two terminals): without it each compiled the same integrators (issue 45 counted
    38 compilations, 131 s, for the main study from an empty cache). An advisory lock (flock) that the kernel drops
    when its holder dies; where there is none (not POSIX) or it cannot be taken within
    LOCK_WAIT, the build goes ahead unlocked, as before."""
    try:
        import fcntl
    except ImportError:  # not POSIX
        yield
        return
    try:
        fh = open(path.with_suffix(".lock"), "a")
    except OSError:
        yield
        return
    held, deadline = False, time.monotonic() + LOCK_WAIT
    try:
        while not held:
            try:
                fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
                held = True
            except BlockingIOError:
                if time.monotonic() > deadline:
                    break
                time.sleep(0.05)
        yield
    finally:
        if held:
            fcntl.flock(fh, fcntl.LOCK_UN)
        fh.close()


def _built(build, disk, label, path: Path | None):
    """``build()``, announced, and written to ``path`` (whole, under a temporary name)."""
    if disk is not None:
        _place_heyoka_cache()
    start = time.perf_counter()
    entry = _announced(build, disk, label)
    if path is not None:
        _tally(path, time.perf_counter() - start, label or _WHAT.get(disk, disk))
        try:
            tmp = path.with_suffix(f".{os.getpid()}.tmp")
            with open(tmp, "wb") as fh:
                pickle.dump(entry, fh)
            os.replace(tmp, path)
            _trim(path.parent, keep=path)
        except Exception:
            pass
    return entry


#: one line per build in the disk cache's folder (file, pid, seconds, what): how often each
#: integrator was compiled, read by benchmarks/bench_cold_cache.py
BUILD_LOG = "builds.log"


def _tally(path: Path, seconds: float, what: str | None) -> None:
    """Append this build to the cache's :data:`BUILD_LOG` (one short write in append mode: the
    processes sharing the cache never interleave within a line)."""
    try:
        with open(path.parent / BUILD_LOG, "a") as fh:
            fh.write(f"{path.stem}\t{os.getpid()}\t{seconds:.2f}\t{what}\n")
    except OSError:
        pass


def _trim(cache: Path, keep: Path) -> None:
    """Delete the least recently used integrators (oldest modification time: a load touches its
    file) until they hold at most INTEGRATOR_CACHE_LIMIT bytes; ``keep`` (just written) stays."""
    files = []
    for q in cache.glob("*.pkl"):
        try:
            st = q.stat()
        except OSError:  # another process trimmed it
            continue
        files.append((st.st_mtime, st.st_size, q))
    total = sum(size for _, size, _ in files)
    for _, size, q in sorted(files, key=lambda f: f[0]):
        if total <= INTEGRATOR_CACHE_LIMIT:
            break
        if q != keep:
            q.unlink(missing_ok=True)
            total -= size


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


def _files(root: Path) -> dict:
    """Files and bytes under ``root`` (0 and 0 where it does not exist)."""
    paths = [q for q in root.rglob("*") if q.is_file()] if root.is_dir() else []
    return {"files": len(paths), "bytes": sum(q.stat().st_size for q in paths)}


def disk_usage() -> dict:
    """What the disk cache holds: its directory (None: caching is off), phasekit's compiled
    integrators and heyoka's object code, each as files and bytes (``phasekit cache``)."""
    cache = _cache_dir()
    if cache is None:
        return {"directory": None, "integrators": {"files": 0, "bytes": 0}, "heyoka": {"files": 0, "bytes": 0}}
    pickles = [q for q in cache.glob("*.pkl") if q.is_file()]
    log = cache / BUILD_LOG  # their build log counted with them (bytes, not files)
    return {"directory": str(cache), "heyoka_limit_bytes": HEYOKA_CACHE_LIMIT, "integrators_limit_bytes": INTEGRATOR_CACHE_LIMIT,
            "integrators": {"files": len(pickles),
                            "bytes": sum(q.stat().st_size for q in pickles) + (log.stat().st_size if log.is_file() else 0)},
            "heyoka": _files(cache / "heyoka")}


def clear_disk() -> dict:
    """Delete the disk cache's compiled integrators and heyoka's object code (the next run of each
    model compiles again); returns :func:`disk_usage` as it was before. The in-memory cache of
    this process is emptied too."""
    before = disk_usage()
    if before["directory"] is not None:
        cache = Path(before["directory"])
        for q in [*cache.glob("*.pkl"), *cache.glob("*.tmp"), *cache.glob("*.lock"), cache / BUILD_LOG]:
            q.unlink(missing_ok=True)
        hy, objects = sys.modules.get("heyoka"), cache / "heyoka"
        if hy is not None and hy.llvm_state.get_diskcache_path() == str(objects):
            hy.llvm_state.clear_diskcache()  # its database is open in this process: heyoka empties it
        else:
            shutil.rmtree(objects, ignore_errors=True)
    forget()
    return before


def forget() -> None:
    """Empty the in-memory cache (the next use reloads from disk; tests of the disk cache)."""
    with _LOCK:
        _MEMORY.clear()
        _PERSISTENT.clear()
        RECORDERS.clear()
