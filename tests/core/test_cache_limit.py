"""The disk cache of compiled integrators stays under its limit: writing a new entry deletes the
least recently used ones (a load counts as a use), never the one just written."""

from __future__ import annotations

import os
import time

from phasekit.core.engines import cache

import pytest


def _entry(key, size):
    """Write a cache entry of about ``size`` bytes through the cache's own path."""
    cache.compiled(("limit-test", key), lambda: b"x" * size, disk="taylor")


def test_writing_past_the_limit_deletes_the_least_recently_used(tmp_path, monkeypatch):
    monkeypatch.setenv("PHASEKIT_CACHE", str(tmp_path))
    monkeypatch.setattr(cache, "INTEGRATOR_CACHE_LIMIT", 3500)
    monkeypatch.setattr(cache, "_place_heyoka_cache", lambda: None)
    cache.forget()
    try:
        for key in "abc":
            _entry(key, 1000)
        files = sorted(tmp_path.glob("*.pkl"), key=lambda q: q.stat().st_mtime)
        assert len(files) == 3
        oldest, middle, newest = files
        past = time.time() - 100
        for age, q in enumerate(files):  # distinct times, whatever the file system's resolution
            os.utime(q, (past + age, past + age))
        cache.forget()
        _entry("a", 1000)  # loaded from disk: now the most recently used
        assert oldest.stat().st_mtime > newest.stat().st_mtime
        _entry("d", 1000)  # 4 entries > 3500 bytes: one must go
        left = set(tmp_path.glob("*.pkl"))
        assert middle not in left and {oldest, newest} <= left and len(left) == 3
        assert sum(q.stat().st_size for q in left) <= cache.INTEGRATOR_CACHE_LIMIT
        assert cache.disk_usage()["integrators_limit_bytes"] == 3500
    finally:
        cache.forget()


@pytest.mark.parametrize("limit", [0, 10])
def test_the_entry_just_written_is_kept_even_alone_over_the_limit(tmp_path, monkeypatch, limit):
    monkeypatch.setenv("PHASEKIT_CACHE", str(tmp_path))
    monkeypatch.setattr(cache, "INTEGRATOR_CACHE_LIMIT", limit)
    monkeypatch.setattr(cache, "_place_heyoka_cache", lambda: None)
    cache.forget()
    try:
        _entry("a", 1000)
        first = set(tmp_path.glob("*.pkl"))
        _entry("b", 1000)
        left = set(tmp_path.glob("*.pkl"))
        assert len(first) == len(left) == 1 and not first & left and next(iter(left)).stat().st_size > 1000
    finally:
        cache.forget()
