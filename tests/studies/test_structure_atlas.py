"""The steady-structure atlases' bisection (phasekit.studies.trace_boundary) finds a boundary between
structures and names its bifurcation."""

import phasekit as pk
import phasekit.studies as ps
from phasekit.steady import steady_structure


def test_the_atlas_bisection_finds_the_boundary_a_equals_c_and_names_its_bifurcation():
    """ps.trace_boundary (studies/steady_structure.py's atlases) across A = C of the displaced
    spheroid (offset 0.5 at a = 1.5): the traced point brackets it, and the bifurcation is the one
    pk.steady.structure.bifurcation_between names for the structures on either side of the bracket."""
    def at(panel, x, y):  # x: offset / a
        return steady_structure(pk.Spheroid(1.5, offset=1.5 * x), pk.Viscous(0.1), stability=False)

    b = ps.trace_boundary(at, "demo", (0.3, 0.0), (0.36, 0.0), 0.06, xtol=1e-3, key="k")
    assert abs(b.x - 1 / 3) <= b.width / 2 + 1e-12 and b.width <= 0.06 * 1e-3
    lo, hi = at("demo", b.x - b.width / 2, 0.0), at("demo", b.x + b.width / 2, 0.0)
    assert (b.below, b.above) == (lo.signature, hi.signature) and b.bifurcation == pk.steady.structure.bifurcation_between(lo, hi)
