"""The states on a structure at one rate or spin (SteadyStructure.at, found along the branches
between their ends' exact limits) against fixed_points (a scan of the precession residual over
theta): the same states, kinds and stability labels over a grid of bodies, laws and rates from 0
to 1e12, and both against the tippe top's closed forms where the states crowd an end or a point
of spin 0."""

import phasekit as pk
from phasekit.steady.branches import precession_geometry

import numpy as np
import pytest

LAWS = [pk.Viscous(0.1), pk.Coulomb(0.1), pk.RegularisedCoulomb(0.1, 1e-3)]
BODIES = [
    pk.Spheroid(1.5, offset=0.2), pk.Spheroid(0.6), pk.Spheroid(1.5), pk.Spheroid(0.6, offset=0.1),
    pk.Spheroid(3.0, offset=0.5), pk.Spheroid(1.5, 0.4, 0.4, offset=0.2),  # A = C: a precession family at a static
    pk.EccentricSphere(0.3, A=0.38, C=0.4), pk.EccentricSphere(0.3, A=0.2, C=0.4), pk.EccentricSphere(0.3, A=0.6, C=0.4),
    pk.EccentricSphere(0.3, A=0.4, C=0.4), pk.Egg(1.3, 0.05), pk.Egg(0.5, 0.08),
]
#: every scale: zero, tiny, around the critical rates, at the ends' asymptotes, and negative
OMEGAS = [0.0, 1e-12, 1e-3, 0.7, 2.5, 10.0, 1e3, 1e6, 1e12, -3.0]
#: spins below ~1e-7 near the horizontal family of a flip-symmetric body are resolved only to
#: ~1e-16 / n0 by the Euler chart (theta's rounding near pi/2), so the smallest nonzero spin is 1e-6
SPINS = [0.0, 1e-6, 0.05, 1.0, 3.0, 10.0, 1e3, 1e6, 1e12, -2.0]


def same_states(mine, ref):
    assert [p.kind for p in mine] == [p.kind for p in ref]
    for p, r in zip(mine, ref):
        assert np.all(np.abs(p.x - r.x) <= 1e-9 * np.maximum(np.abs(r.x), 1.0)), (p.x, r.x)
        assert (p.n_unstable, p.stable, p.classification) == (r.n_unstable, r.stable, r.classification)


def test_a_state_next_to_an_infinite_spin_end_is_listed():
    """Omega0 = 1000 on the offset spheroid lies ~1e-7 from its infinite-spin asymptote, beyond
    the last sample of the branch: it is listed, unstable, and is fixed_points' state."""
    body, law = pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1)
    s = pk.steady_structure(body, law)
    [branch] = [b for b in s.branches if b.ends[1].kind == "infinite-spin"]
    [state] = s.at(omega0=1000.0)
    assert branch.theta[-1] < state.x[4] < branch.ends[1].theta
    assert state.kind == "horizontal-like" and state.n_unstable == 1 and state.x[2] == 1000.0
    same_states([state], pk.fixed_points(pk.Model(body, law), omega0=1000.0))


@pytest.mark.timeout(600)
# the oblate egg (the last body, ~8 s of scans of its series): the full run only; the prolate egg stays
@pytest.mark.parametrize("i", [pytest.param(i, marks=pytest.mark.slow) if i == len(BODIES) - 1 else i
                               for i in range(len(BODIES))], ids=[repr(b) for b in BODIES])
def test_structure_and_fixed_points_list_the_same_states(i):
    body, law = BODIES[i], LAWS[i % 3]
    s = pk.steady_structure(body, law, samples=False)
    model = pk.Model(body, law)
    for key, values in (("omega0", OMEGAS), ("n0", SPINS)):
        for v in values:
            same_states(s.at(**{key: v}), pk.fixed_points(model, **{key: v}))


@pytest.mark.parametrize("kw", [{"omega0": 1e3}, {"omega0": 1e-3}, {"n0": 0.2}, {"n0": 1e6}, {"n0": 0.0}])
def test_a_structure_with_or_without_samples_gives_the_same_states(kw):
    body, law = pk.Egg(1.3, 0.05), pk.Coulomb(0.1)
    same_states(pk.steady_structure(body, law).at(**kw), pk.steady_structure(body, law, samples=False).at(**kw))


@pytest.mark.parametrize("omega0", [10.0, 1e3, 1e6, 1e9])
def test_fast_precessions_of_the_tippe_top_crowd_its_asymptote_as_the_closed_form_says(omega0):
    """Eccentric sphere: q = alpha, rho_2 = 1, so Omega^2 = alpha / ((A - C) cos + C alpha), and
    the state with rate Omega0 has cos(theta) = (alpha / Omega0^2 - C alpha) / (A - C)."""
    alpha, A, C = 0.3, 0.2, 0.4
    body = pk.EccentricSphere(alpha, A=A, C=C)
    theta = np.arccos((alpha / omega0**2 - C * alpha) / (A - C))
    for states in (pk.steady_structure(body, pk.Viscous(0.3), samples=False).at(omega0=omega0),
                   pk.fixed_points(pk.Model(body, pk.Viscous(0.3)), omega0=omega0)):
        [p] = states
        assert p.x[4] == pytest.approx(theta, abs=1e-12) and p.x[2] == omega0


@pytest.mark.parametrize("n0", [1e-9, 1e-4])
def test_two_states_straddle_a_point_of_spin_zero_at_a_small_spin(n0):
    """Eccentric sphere: z = cos - alpha, so the spin residual alpha (cos - alpha)^2 -
    n0^2 ((A - C) cos + C alpha) has the two roots cos = alpha +- n0 sqrt(A) (1 + O(n0)) around
    cos = alpha, closer together than any grid: both are found, with opposite rates (Omega = n0 / z)."""
    alpha, A, C = 0.3, 0.38, 0.4
    body = pk.EccentricSphere(alpha, A=A, C=C)
    # the roots of the quadratic in c = cos(theta), c = alpha + k/2 +- sqrt(n0^2 A + k^2/4),
    # k = n0^2 (A - C) / alpha (its discriminant written out: no cancellation)
    k = n0**2 * (A - C) / alpha
    roots = sorted(np.arccos(alpha + k / 2 + sgn * np.sqrt(n0**2 * A + k * k / 4)) for sgn in (1, -1))
    for states in (pk.steady_structure(body, pk.Coulomb(0.3), samples=False).at(n0=n0),
                   pk.fixed_points(pk.Model(body, pk.Coulomb(0.3)), n0=n0)):
        mid = [p for p in states if p.kind == "intermediate" and abs(p.x[4] - np.arccos(alpha)) < 1e-3]
        assert [p.x[4] for p in mid] == pytest.approx(roots, abs=1e-13)
        assert [np.sign(p.x[2]) for p in mid] == [1.0, -1.0] and all(p.x[5] == n0 for p in mid)


def test_a_state_next_to_a_pole_is_listed():
    """A spin just past the pole's (where the branch leaves the spin about the vertical) puts
    the precession within 1e-4 of the pole, inside the first cell of any grid."""
    body, law = pk.Spheroid(0.6, offset=0.1), pk.Viscous(0.1)
    s = pk.steady_structure(body, law)
    [end] = [e for b in s.branches for e in b.ends if e.kind == "pole" and e.pole == "0"]
    q, rho2, z, D = (float(v[0]) for v in precession_geometry(body, 1e-4)[:4])
    n0 = float(np.sqrt(q * rho2 / D) * z / rho2)  # the spin on the branch at theta = 1e-4
    assert abs(n0 - end.n) < 1e-6 * abs(end.n)
    states = s.at(n0=n0)
    [near] = [p for p in states if p.kind == "intermediate" and p.x[4] < 1e-3]
    assert near.x[4] == pytest.approx(1e-4, rel=1e-6)
    same_states(states, pk.fixed_points(pk.Model(body, law), n0=n0))
