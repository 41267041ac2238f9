"""Which study wrote each committed table (:func:`owners`), from what each study wrote in its own
scratch folder: the tables a rerun of ``studies/reproduce.py`` compares (:mod:`phasekit.studies.reproduce_tables`)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

# -- which study writes which table ---------------------------------------------------------------


@dataclass
class Ownership:
    """Which study wrote each committed table, from what each study wrote in its own folder.

    Attributes
    ----------
    owner : dict
        Committed table -> the one study that wrote it.
    shared : dict
        Committed table -> the studies that wrote it (more than one: an error).
    unowned : list of str
        Committed tables no study that ran wrote.
    uncommitted : dict
        Study -> the tables it wrote that are not in figures/.
    """

    owner: dict[str, str] = field(default_factory=dict)
    shared: dict[str, list[str]] = field(default_factory=dict)
    unowned: list[str] = field(default_factory=list)
    uncommitted: dict[str, list[str]] = field(default_factory=dict)


def owners(written: Mapping[str, Iterable[str]], committed: Iterable[str]) -> Ownership:
    """Map each committed table to the study that writes it.

    Parameters
    ----------
    written : mapping
        Study -> the names of the tables it wrote (in its own output folder).
    committed : iterable of str
        The names of the committed tables.

    Returns
    -------
    Ownership
        Every committed table owned by exactly one study, or listed as shared or unowned.

    Examples
    --------
    >>> o = owners({"a": ["a.csv", "new.csv"], "b": ["b.json"]}, ["a.csv", "b.json", "old.csv"])
    >>> o.owner, o.unowned, o.uncommitted
    ({'a.csv': 'a', 'b.json': 'b'}, ['old.csv'], {'a': ['new.csv']})
    """
    committed = list(committed)
    by_table: dict[str, list[str]] = {}
    for study, names in written.items():
        for name in names:
            by_table.setdefault(name, []).append(study)
    out = Ownership()
    for name in committed:
        who = by_table.get(name, [])
        if len(who) == 1:
            out.owner[name] = who[0]
        elif who:
            out.shared[name] = who
        else:
            out.unowned.append(name)
    for study, names in written.items():
        new = [n for n in names if n not in committed]
        if new:
            out.uncommitted[study] = new
    return out
