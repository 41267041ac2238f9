"""Every number and table of the results pages, computed from the committed data when the docs
build (``{pk}`group.name``` inline, ``{pk-table} group.name`` as a block).

A *group* is a function of :class:`~sources.Sources` returning a dict of named values: strings
(inline numbers, short phrases) or Markdown blocks (tables). Nothing here is typed from a
previous run: change a number in ``figures/`` and the page changes with it (tests/contracts/test_docs_site.py
does exactly that on a copy).
"""

from __future__ import annotations

from . import facts_runs, facts_steady, facts_theory, facts_thresholds  # noqa: F401  (each registers its groups)
from .registry import GROUPS, group, lookup, values  # noqa: F401  (the registry, as pkdocs and the tests read it)
