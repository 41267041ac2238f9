"""Bodies whose steady states fill a continuum (a sphere with G at its centre: h_theta = 0 at every
theta) are recognised and said to be such, with their isolated states listed the same way by the
structure and by fixed_points, instead of a continuum being sampled point by point."""

import phasekit as pk
from phasekit.steady.branches import precession_geometry

import numpy as np
import pytest

SPHERES = [pk.Spheroid(1.0), pk.Spheroid(1.0, A=0.5, C=0.4), pk.EccentricSphere(0.0),
           pk.EccentricSphere(0.0, A=0.3, C=0.4)]


@pytest.mark.timeout(300)
@pytest.mark.parametrize("body", SPHERES, ids=repr)
def test_a_sphere_with_g_at_its_centre_is_a_continuum_said_as_such(body):
    # the premise, from the closed forms: q = h_theta / sin vanishes at every theta
    q = precession_geometry(body, np.linspace(0.0, np.pi, 101))[0]
    assert np.max(np.abs(q)) <= 1e-15
    s = pk.steady_structure(body, pk.Coulomb(0.1), max_wall=60.0)
    assert s.status is pk.Status.COMPLETED and s.signature == "degenerate" and s.branches == ()
    assert "every orientation is a static equilibrium" in s.degenerate
    assert ("any rate Omega with n = Omega cos theta" in s.degenerate) == (body.A == body.C)
    d = s.to_dict()
    assert d["degenerate"] == s.degenerate and d["signature"] == "degenerate"
    model = pk.Model(body, pk.Viscous(0.1))
    s = pk.steady_structure(body, pk.Viscous(0.1), samples=False)
    for kw, kind in (({"omega0": 10.0}, "horizontal"), ({"n0": 3.0}, "vertical"), ({"omega0": 0.0}, "horizontal")):
        mine, ref = s.at(**kw), pk.fixed_points(model, **kw)
        assert [p.kind for p in mine] == [p.kind for p in ref] == [kind]
        assert np.array_equal(mine[0].x, ref[0].x) and mine[0].residual <= 1e-13  # the closed form, to rounding


def test_a_sphere_with_g_off_its_centre_has_branches():
    """The nearest bodies that are not degenerate: G a little off the centre, or a spheroid a
    little off a sphere, have one branch from pole to pole."""
    for body in (pk.EccentricSphere(1e-6, A=0.4, C=0.4), pk.Spheroid(1.0 + 1e-9)):
        s = pk.steady_structure(body, pk.Viscous(0.1), samples=False)
        assert s.degenerate is None and s.signature in ("pole0-polePi", "pole0-cross-polePi")
