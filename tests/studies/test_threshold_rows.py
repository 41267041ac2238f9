"""The main study's threshold rows (phasekit/studies/threshold_rows.py): the self-consistency check
runs at a ten times tighter tolerance, so that a threshold set by the integration error fails it;
one that fails it in the paper's variables is searched again in the vector chart."""

from dataclasses import asdict, replace

import phasekit as pk
import phasekit.studies as ps

SEARCH = dict(hi=120.0, tol=0.01)


def test_a_threshold_set_by_the_integration_error_is_searched_again_in_the_vector_chart():
    # the paper's literal recipe near a = 1 (eps = 1e-3, a = 1.05): in the paper's variables (the
    # Euler chart) the search finds a transition at rtol 1e-9 that 1.02 x of it does not keep at
    # rtol 1e-10 (docs/results/maps.md: 46.8 at 1e-9, 52.2 at 1e-10); the vector chart gives 49.16
    # at both tolerances
    defn = pk.Definition("literal-eps1e-3", "literal", eps=1e-3)
    body = pk.Spheroid(1.05)
    row = ps.threshold_task(None, asdict(defn), 1.05, "main", False, SEARCH)
    assert row.status == "converged" and row.chart == "vector" and row.consistent is True
    assert 40.0 < row.euler_threshold < 48.0 and abs(row.threshold / 49.16 - 1) < 0.011
    assert row.check_rtol == 1e-10 and row.n_check_sims == 4
    # the failed check, directly: above the Euler threshold the outcome changes with the tolerance
    # alone, while the vector chart gives the same outcome at both (below its threshold: no jump)
    above = 1.02 * row.euler_threshold
    assert defn.outcome(body, above).jumped
    assert not ps.check_definition(defn).outcome(body, above).jumped
    vector = replace(defn, chart="vector")
    assert not vector.outcome(body, above).jumped
    assert not ps.check_definition(vector).outcome(body, above).jumped


def test_a_threshold_set_by_the_body_passes_its_check_in_the_papers_variables():
    defn = pk.Definition("sliding", "sliding")
    row = ps.threshold_task(None, asdict(defn), 1.5, "main", True, SEARCH)
    assert row.check_rtol == 1e-10 and row.consistent is True and row.chart is None
    assert row.check_above_jumped is True and row.check_below_jumped is False and row.euler_threshold is None
    # the published default threshold at a = 1.5 (figures/threshold_vs_aspect.csv: 9.7477 to 1e-3)
    assert abs(row.threshold / 9.7477 - 1) < 0.011


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
