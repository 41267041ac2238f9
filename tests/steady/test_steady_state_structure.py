"""The steady-state structure (phasekit.steady.structure) against independent computations: the
vector chart's Newton-Euler equations, the tippe top's closed forms and energy criterion, the
pole criterion, closed-form statics, and the pointwise fixed points."""

import phasekit as pk
from phasekit.core import Mode, charts
from phasekit.steady import steady_structure
from phasekit.steady.branch_stability import linearise_precession
from phasekit.steady.branches import precession_on_branch
from phasekit.steady.rolling import rolling_state
from phasekit.theory import tippetop

import numpy as np
import pytest

ROT = np.zeros((8, 8))  # generator of rotations about the vertical on (k, w, v)


for i in (0, 3):
    ROT[i, i + 1], ROT[i + 1, i] = -1.0, 1.0


ROT[6, 7], ROT[7, 6] = -1.0, 1.0


def vector_residual(body, theta, om, n):
    """|f(x) - Omega G x| / scale in the vector chart (Newton-Euler in fixed axes, derived
    independently of (2.7)): zero exactly for a steady precession (a relative equilibrium)."""
    model = pk.Model(body, pk.Viscous(1.0), "vector")
    x = charts.euler_to_vector([0.0, 0.0, om, 0.0, theta, n])
    r = model.rhs(x, Mode.SLIDING) - om * ROT @ x
    return float(np.max(np.abs(r))) / max(1.0, om * om, n * n)


def vector_precession(body, theta, guess):
    """(Omega, n) of the steady precession at theta, by Newton on the vector chart alone."""
    from scipy.optimize import least_squares

    model = pk.Model(body, pk.Viscous(1.0), "vector")

    def res(p):
        x = charts.euler_to_vector([0.0, 0.0, p[0], 0.0, theta, p[1]])
        return (model.rhs(x, Mode.SLIDING) - p[0] * ROT @ x)[[3, 4, 5]]

    sol = least_squares(res, guess, xtol=1e-15, ftol=1e-15, gtol=1e-15)
    return sol.x


TOPS = [(0.3, 0.38, 0.4), (0.3, 0.2, 0.4), (0.3, 0.6, 0.4), (0.1, 0.35, 0.4), (0.5, 0.2, 0.4), (0.45, 0.62, 0.4)]


@pytest.mark.parametrize("alpha,A,C", TOPS)
def test_tippe_top_structures_follow_the_inversion_interval(alpha, A, C):
    s = steady_structure(pk.EccentricSphere(alpha, A=A, C=C), pk.Viscous(0.3), stability=False)
    lo, hi = tippetop.inversion.inversion_interval(alpha)
    expected = "pole0-polePi" if lo < A / C < hi else "inf-polePi" if A / C <= lo else "pole0-inf"
    assert s.signature == expected
    # the infinite-spin asymptote in closed form: D = (A - C) cos + C alpha = 0
    for e in (e for b in s.branches for e in b.ends if e.kind == "infinite-spin"):
        assert e.theta == pytest.approx(np.arccos(-C * alpha / (A - C)), abs=1e-12)
    # the pole ends are the closed-form critical spins of the upright and inverted states
    for e in (e for b in s.branches for e in b.ends if e.kind == "pole"):
        ref = tippetop.upright_unstable_spin(alpha, A, C) if e.pole == "0" else tippetop.inverted_stable_spin(alpha, A, C)
        assert abs(e.n) == pytest.approx(ref, rel=1e-12)


def test_tippe_top_stability_along_the_branch_is_the_energy_criterion():
    """Viscous friction: an intermediate state is stable iff g'(z) < 0 (tippetop: energy and
    Jellett's integral, a Lyapunov argument independent of the linearisation)."""
    for alpha, A, C in [(0.3, 0.38, 0.4), (0.3, 0.2, 0.4), (0.45, 0.62, 0.4)]:
        s = steady_structure(pk.EccentricSphere(alpha, A=A, C=C), pk.Viscous(0.3))
        for b in s.branches:
            z = np.cos(b.theta)
            dz = 1e-6
            gp = (tippetop.steady.steady_state_jellett_sq(alpha, A, C, z + dz) - tippetop.steady.steady_state_jellett_sq(alpha, A, C, z - dz))
            decided = np.abs(gp) > 1e-6 * np.abs(tippetop.steady.steady_state_jellett_sq(alpha, A, C, z))
            assert np.array_equal(b.stable[decided], (gp < 0)[decided])
            assert decided.sum() > 0.9 * b.theta.size


#: the bodies by their repr, each made when its test runs (an egg's fit takes a moment)
BODIES = {
    "Spheroid(a=1.5, offset=0.2, A=0.61, C=0.4)": lambda: pk.Spheroid(1.5, offset=0.2),
    "Spheroid(a=0.6, offset=0.1, A=0.262, C=0.4)": lambda: pk.Spheroid(0.6, offset=0.1),
    "Spheroid(a=2.5, offset=0.6, A=1.2, C=0.5)": lambda: pk.Spheroid(2.5, offset=0.6, A=1.2, C=0.5),
    "Spheroid(a=0.5, offset=0.02, A=0.3, C=0.35)": lambda: pk.Spheroid(0.5, offset=0.02, A=0.3, C=0.35),
    "EccentricSphere(offset=0.3, A=0.38, C=0.4)": lambda: pk.EccentricSphere(0.3, A=0.38, C=0.4),
    "Egg(a=1.3, w=0.05)": lambda: pk.Egg(1.3, 0.05),
}


def made(name: str):
    """The body ``BODIES[name]`` makes, which is the one its name says."""
    body = BODIES[name]()
    assert repr(body) == name
    return body


@pytest.mark.parametrize("name", list(BODIES))
def test_every_sample_is_a_steady_precession_of_the_vector_chart(name):
    body = made(name)
    s = steady_structure(body, pk.Viscous(0.1), stability=False)
    assert s.branches
    for b in s.branches:
        assert b.theta.size >= 30 and np.all(np.diff(b.theta) > 0)
        worst = max(vector_residual(body, t, o, m) for t, o, m in zip(b.theta, b.Omega, b.n))
        assert worst < 1e-12
        for k in np.linspace(0, b.theta.size - 1, 7).astype(int)[1:-1]:
            om, n = vector_precession(body, b.theta[k], [1.01 * b.Omega[k], 0.99 * b.n[k] + 0.01])
            assert om == pytest.approx(b.Omega[k], rel=1e-10) and n == pytest.approx(b.n[k], rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("name", list(BODIES)[:4])
def test_ends_are_zeros_of_the_closed_forms_and_poles_meet_the_pole_criterion(name):
    body = made(name)
    s = steady_structure(body, pk.Viscous(0.1), stability=False)
    a, alpha = body.a, body.offset
    k = a * a - 1
    c_static = alpha / np.sqrt(k * (k - alpha**2)) if k * (k - alpha**2) > 0 else None
    for b in s.branches:
        lo, hi = b.ends
        assert lo.theta < hi.theta
        for e in b.ends:
            if e.kind == "static":  # h_theta = 0: (a^2 - 1) c / sqrt(1 + (a^2 - 1) c^2) = offset
                assert abs(np.cos(e.theta)) == pytest.approx(c_static, abs=1e-12)
            elif e.kind == "pole":  # the pole criterion, from h and h_tt at the pole
                crit = pk.theory.pole_stability_threshold(body, "upright" if e.pole == "0" else "inverted")
                assert abs(e.n) == pytest.approx(crit.threshold, rel=1e-11)
        # Omega tends to 0 at a static end and diverges at an infinite-spin end
        if lo.kind == "static":
            assert b.Omega[0] < 1e-2
        if hi.kind == "infinite-spin":
            assert b.Omega[-1] > 1e2
    statics = [e.theta for e in s.static_equilibria if e.kind == "tilted"]
    assert len(statics) == (0 if c_static is None or c_static >= 1 else 1)


def test_static_equilibria_of_a_body_with_many():
    """H(c) = 1 + eps T_k(c): a convex body (eps k^2 < 1) with k + 1 static equilibria, at the
    extrema of the Chebyshev polynomial, alternately minima and maxima of the height."""
    k, eps = 9, 0.004
    body = pk.CustomBody(lambda c: 1 + eps * _cheb(k, c), A=0.4, C=0.4, variable="cos")
    s = steady_structure(body, pk.Viscous(0.1), stability=False)
    thetas = np.array([e.theta for e in s.static_equilibria])
    expected = np.sort(np.arccos(np.cos(np.pi * np.arange(k + 1) / k)))
    assert thetas == pytest.approx(expected, abs=1e-10)
    stable = [e.stable for e in s.static_equilibria]
    assert all(stable[i] != stable[i + 1] for i in range(k))


def _cheb(k, c):
    t0, t1 = 1, c
    for _ in range(k - 1):
        t0, t1 = t1, 2 * c * t1 - t0
    return t1


@pytest.mark.parametrize("a", [1.5, 2 / 3, 3.0])
def test_flip_symmetric_spheroid_reproduces_part_one_and_the_fixed_points(a):
    body = pk.Spheroid(a)
    law = pk.Viscous(0.1)
    s = steady_structure(body, law)
    # one branch from pole to pole crossing the horizontal family at Omega0^2 = (a^2 - 1)/(a^2 C - A)
    assert s.signature == "pole0-cross-polePi"
    [b] = s.branches
    assert b.crossings == (np.pi / 2,)
    [fam] = [f for f in s.families if f.kind == "precession"]
    assert fam.critical == pytest.approx(pk.theory.horizontal_stability_threshold(body.A, body.C, a), rel=1e-9)
    for e in b.ends:
        assert abs(e.n) == pytest.approx(pk.theory.vertical_stability_threshold(body.A, body.C, a), rel=1e-12)
    # uniform spheroids: Omega^2 = 5 / h along the whole branch
    assert b.Omega**2 == pytest.approx(5 / body.h(b.theta)[0], rel=1e-12)
    model = pk.Model(body, law)
    for kw in ({"omega0": 0.999 * fam.critical}, {"omega0": 0.5 * (b.Omega.min() + b.Omega.max())}, {"omega0": 3.0},
               {"n0": 0.5 * abs(b.ends[0].n)}, {"n0": 1.3}):
        mine, ref = s.at(**kw), pk.fixed_points(model, **kw)
        assert [p.kind for p in mine] == [p.kind for p in ref]
        for p, r in zip(mine, ref):
            assert p.x == pytest.approx(r.x, rel=1e-12, abs=1e-12)
            assert np.max(np.abs(p.eigenvalues - r.eigenvalues)) <= 1e-12 * max(1.0, np.max(np.abs(r.eigenvalues)))


@pytest.mark.parametrize("name,law", [("Spheroid(a=1.5, offset=0.2, A=0.61, C=0.4)", pk.Viscous(0.1)),
                                      ("Spheroid(a=0.6, offset=0.1, A=0.262, C=0.4)", pk.Viscous(0.1)),
                                      ("Egg(a=1.3, w=0.05)", pk.Viscous(0.2)),
                                      ("Spheroid(a=0.6, offset=0.1, A=0.262, C=0.4)", pk.Coulomb(0.1)),
                                      ("Spheroid(a=1.5)", pk.RegularisedCoulomb(0.1, 1e-3))], ids=str)
def test_stability_along_branches_matches_the_pointwise_linearisation(name, law):
    body = pk.Spheroid(1.5) if name == "Spheroid(a=1.5)" else made(name)
    s = steady_structure(body, law)
    model = pk.Model(body, law)
    rng = np.random.default_rng(7)
    for b in s.branches:
        compared = 0
        for t in rng.uniform(b.theta[0], b.theta[-1], 20):
            if min(t, np.pi - t) < 0.05 or any(abs(t - c.theta) < 1e-6 for c in b.changes):
                continue  # the rotating chart there; or too near a change
            om, n = precession_on_branch(body, np.array([t]))
            fps = [p for p in pk.fixed_points(model, omega0=float(om[0])) if abs(p.x[4] - t) < 1e-8]
            if body.flip_symmetric and t > np.pi / 2:
                fps = [pk.steady.linearise(model, [0, 0, om[0], 0, t, n[0]])]
            [fp] = fps
            assert fp.n_unstable == b.n_unstable_at(t)
            compared += 1
        assert compared >= 5
        for c in b.changes:  # states of opposite stability bracket every change, within 1e-8
            lo, hi = c.bracket
            assert hi - lo <= 1e-8
            om_lo, n_lo = (float(v[0]) for v in precession_on_branch(body, np.array([lo])))
            om_hi, n_hi = (float(v[0]) for v in precession_on_branch(body, np.array([hi])))
            # pointwise, in the paper's chart (the structure bisected with linearise_precession)
            chart = "euler" if min(lo, np.pi - hi) >= 0.05 else "rotating"
            f_lo = pk.steady.linearise(model, [0, 0, om_lo, 0, lo, n_lo]) if chart == "euler" else \
                linearise_precession(s.model, lo, om_lo, n_lo, chart=chart)
            f_hi = pk.steady.linearise(model, [0, 0, om_hi, 0, hi, n_hi]) if chart == "euler" else \
                linearise_precession(s.model, hi, om_hi, n_hi, chart=chart)
            assert f_lo.n_unstable != f_hi.n_unstable
            assert (f_lo.n_unstable, f_hi.n_unstable) == (c.below, c.above)


def test_euler_and_rotating_vector_charts_give_the_same_stability():
    body, law = pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1)
    model = pk.Model(body, law)
    for t in (0.02, 0.1, 0.5, 0.9, 1.2, 2.0, 3.0):
        om, n = (float(v[0]) for v in precession_on_branch(body, np.array([t])))
        if not np.isfinite(om):
            continue
        e = linearise_precession(model, t, om, n, chart="euler")
        r = linearise_precession(model, t, om, n, chart="rotating")
        # the rotating chart has two more zero eigenvalues (|k| and the azimuth): compare the others
        re_e = np.sort(e.eigenvalues[np.abs(e.eigenvalues) > 1e-6].real)
        re_r = np.sort(r.eigenvalues[np.abs(r.eigenvalues) > 1e-6].real)
        assert re_e.size == 5 and re_r == pytest.approx(re_e, abs=1e-9 * max(1.0, om * om))
        assert e.n_unstable == r.n_unstable


def test_displaced_spheroid_breaks_part_ones_degenerate_structure():
    """The symmetric pitchfork at the horizontal state unfolds: a static equilibrium and an
    infinite-spin asymptote appear near pi/2 (part III's abstract), and A = C is the boundary
    where they meet again."""
    assert steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1), stability=False).signature == \
        "pole0-inf | static-polePi"
    at_boundary = steady_structure(pk.Spheroid(1.5, offset=0.5), pk.Viscous(0.1), stability=False)  # A = C = 0.4
    assert at_boundary.signature == "pole0-cross-polePi"
    assert [f.kind for f in at_boundary.families] == ["pole", "pole", "precession", "rolling"]


@pytest.mark.parametrize("a", [1.5, 2 / 3])
def test_part_one_four_classes_with_their_stability(a):
    """Part I's four classes of the flip-symmetric spheroid: the spin about the vertical, the
    horizontal precession, the intermediate precessions (the branch) and rolling on the equator
    along a straight line. Each family state is an exact steady state, and the located change
    of stability of the rolling family is bracketed by states of opposite stability."""
    body, law = pk.Spheroid(a), pk.Viscous(0.1)
    s = steady_structure(body, law)
    assert sorted(f.kind for f in s.families) == ["pole", "pole", "precession", "rolling"] and len(s.branches) == 1
    model = pk.Model(body, law)
    [roll] = [f for f in s.families if f.kind == "rolling"]
    assert roll.theta == np.pi / 2 and roll.criticals
    for n in (0.3, 3.0, 30.0):
        x = rolling_state(body, roll.theta, n)
        assert np.max(np.abs(model.rhs(x, Mode.SLIDING))) < 1e-14 * n * n + 1e-15
    for c in roll.criticals:
        lo = pk.steady.linearise(model, rolling_state(body, roll.theta, c * (1 - 1e-8)))
        hi = pk.steady.linearise(model, rolling_state(body, roll.theta, c * (1 + 1e-8)))
        assert lo.n_unstable != hi.n_unstable
