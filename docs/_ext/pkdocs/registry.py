"""The registry of the generated values of the results pages: a *group* is a function of
:class:`~sources.Sources` returning a dict of named values, registered by :func:`group`
(pkdocs.facts imports every module that defines one)."""

from __future__ import annotations

from typing import Callable

from .sources import Sources

GROUPS: dict[str, Callable[[Sources], dict]] = {}


def group(name: str):
    def deco(fn):
        GROUPS[name] = fn
        return fn

    return deco


def values(src: Sources, name: str) -> dict:
    if name not in GROUPS:
        raise KeyError(f"no group of generated values named {name!r} (known: {', '.join(sorted(GROUPS))})")
    return src.memo(("group", name), lambda: GROUPS[name](src))


def lookup(src: Sources, key: str) -> str:
    """``"steady.spheroid_classes"`` -> its value as text."""
    name, _, item = key.partition(".")
    vals = values(src, name)
    if item not in vals:
        raise KeyError(f"group {name!r} has no value {item!r} (it has: {', '.join(sorted(vals))})")
    return str(vals[item])
