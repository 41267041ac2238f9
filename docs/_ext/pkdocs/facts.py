"""Every number and table of the results pages, computed from the committed data when the docs
build (``{pk}`group.name``` inline, ``{pk-table} group.name`` as a block).

A *group* is a function of :class:`~sources.Sources` returning a dict of named values: strings
(inline numbers, short phrases) or Markdown blocks (tables). Nothing here is typed from a
previous run: change a number in ``figures/`` and the page changes with it (tests/contracts/test_docs_site.py
does exactly that on a copy).
"""

from __future__ import annotations

# each registers its groups (cli: the commands' tables from docs/data/cli_schema.json; events: the event table;
# csv: study tables shown whole)
from . import cli_schema, events, facts_runs, facts_steady, facts_tables, facts_theory, facts_thresholds  # noqa: F401
from .registry import GROUPS, group, lookup, values  # noqa: F401  (the registry, as pkdocs and the tests read it)
