"""The main study's threshold rows (phasekit/studies/threshold_rows.py) carry the library's check
of each threshold (pk.find_threshold's verification), not a check of their own."""

from dataclasses import asdict, replace

import phasekit as pk
import phasekit.studies as ps

SEARCH = dict(hi=120.0, tol=0.01)


def test_a_row_carries_the_library_s_check_of_its_bracket():
    defn = pk.Definition("sliding", "sliding")
    row = ps.threshold_task(None, asdict(defn), 1.5, "main", True, SEARCH)
    assert row.check_rtol == 1e-10 and row.consistent is True and row.first_threshold is None
    assert row.check_above_jumped is True and row.check_below_jumped is False and row.n_check_sims == 2
    assert 0.0 <= row.check_worst < 1e-6  # the ends' jump and rise times at rtol 1e-9 against 1e-10
    # the published default threshold at a = 1.5 (figures/threshold_vs_aspect.csv: 9.7477 to 1e-3)
    assert abs(row.threshold / 9.7477 - 1) < 0.011


def test_near_a_sphere_the_papers_variables_and_the_vector_chart_agree():
    """The literal recipe at a = 1.05 (eps = 1e-3): before the integrators scaled their states the
    paper's variables gave 46.8 at rtol 1e-9 and 52.2 at 1e-10 (docs/results/maps.md); the vector
    chart 49.16 at both. Now both charts' searches land on it, each verified."""
    defn = pk.Definition("literal-eps1e-3", "literal", eps=1e-3)
    rows = [ps.threshold_task(None, asdict(d), 1.05, "main", False, SEARCH) for d in (defn, replace(defn, chart="vector"))]
    for row in rows:
        assert row.status == "converged" and row.consistent is True
        assert abs(row.threshold / 49.16 - 1) < 0.011
    assert abs(rows[0].threshold / rows[1].threshold - 1) < 0.011


def test_the_vector_chart_is_part_of_a_definitions_key_and_label_and_its_seed_is_the_same():
    euler = pk.Definition("literal-eps1e-4", "literal", eps=1e-4)
    vector = replace(euler, chart="vector")
    assert "chart" not in euler.key() and "chart=vector" in vector.key()
    assert vector.label == euler.label + "; vector chart"
    (m1, x1), (m2, x2) = euler.start(1.5, 10.0), vector.start(1.5, 10.0)  # the start's chart: Euler here
    assert m1.chart.name == "euler" and m2.chart.name == "vector"
    # the same state: its paper's variables agree to rounding
    assert abs(pk.core.to_paper(m2.chart, x2) - x1).max() < 1e-12
    # asked for by name, the paper's variables are a chart of their own key, with the same start
    named = replace(euler, chart="euler")
    assert "chart=euler" in named.key() and named.start(1.5, 10.0)[0].chart.name == "euler"
    assert abs(named.start(1.5, 10.0)[1] - x1).max() == 0.0
