"""One status vocabulary per level: a run's, a search's and an engine's statuses, each a closed set
that every result at that level uses."""

from __future__ import annotations

import phasekit as pk
from phasekit.core import engines


def test_one_status_vocabulary_per_level():
    assert {s.value for s in pk.Status} == {"jumped", "touchdown", "stopped", "completed", "settled", "rest",
                                            "failed"}
    assert {s.value for s in pk.SearchStatus} == {"converged", "non_monotone", "bracket_only", "no_jump_in_range",
                                                  "jumps_at_lower_bound", "failed"}
    th = pk.find_threshold(pk.Definition("sliding", "sliding"), 1.5, hi=120.0, guess=9.74, tol=1e-2)
    assert th.status is pk.SearchStatus.CONVERGED and all(isinstance(o.status, pk.Status) for o in th.outcomes)
    s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1))
    assert isinstance(s, pk.steady.SteadyStructure) and s.status is pk.Status.COMPLETED
    assert all(c.status in pk.SearchStatus for b in s.branches for c in b.changes)
    prop = engines.engine_for("taylor", 1e-9)
    assert prop.name == "taylor" and {e.value for e in engines.End} == {"time", "event", "failed"}
