"""Steady states of any body: both poles, precessions without flip symmetry, the horizontal-like
state of an egg (the separatrix between its two ends rising), their linearisations, and the
closed-form criteria (general pole criterion; equator criterion and where it stops holding)."""


import phasekit as pk
from phasekit.bodies import Egg
from phasekit.steady import (
    fixed_points,
    horizontal_state,
    inverted_state,
    linearise,
    precession_angles,
    side_equilibrium,
    vertical_state,
)
from phasekit.steady.precessions import precession_residual
from phasekit.theory import horizontal_stability_threshold, pole_stability_threshold, vertical_stability_threshold
from phasekit.theory.criteria import equator_stability_threshold

import casadi as ca
import numpy as np
import pytest

EZ = np.array([0.0, 0.0, 1.0])


def lopsided(eps: float, A: float = 0.62, C: float = 0.4) -> pk.CustomBody:
    """A prolate spheroid's support function plus an odd term: no flip symmetry for eps != 0."""
    return pk.CustomBody(lambda c: ca.sqrt(1 + 1.25 * c * c) + eps * c * (1 - c * c), A=A, C=C, variable="cos",
                         name=f"lopsided {eps:g}")


BODIES = {
    "egg-prolate": lambda: Egg(1.3, 0.1),
    "egg-oblate": lambda: Egg(0.7, 0.05),
    "egg-moved-G": lambda: Egg(0.8, 0.1, A=0.5, C=0.45),
    "tippe-top": lambda: pk.EccentricSphere(0.3, A=0.38, C=0.4),
    "custom": lambda: pk.CustomBody(lambda c: 1 - 0.2 * c + 0.1 * c * c, variable="cos", A=0.35, C=0.4),
    "lopsided": lambda: lopsided(0.05),
}


def growth(fp) -> float:
    """Largest real part of the non-structural eigenvalues (see test_tippetop.max_growth)."""
    lam = fp.eigenvalues[np.abs(fp.eigenvalues) > 1e-10 * fp.scale]
    return float(np.max(lam.real))


def rotating_residual(body, y, law=pk.Viscous(0.1)) -> float:
    """|f(x) - Omega e_Z x x| in the vector chart: zero iff y is a steady precession at rate
    Omega (independent of the Euler chart in which it was found)."""
    m = pk.Model(body, law, "vector")
    x = pk.core.to_chart("vector", y)
    k, w, v = x[0:3], x[3:6], np.array([x[6], x[7], 0.0])
    Om = y[2]
    rot = np.concatenate([np.cross(Om * EZ, k), np.cross(Om * EZ, w), np.cross(Om * EZ, v)[:2]])
    return float(np.max(np.abs(m.rhs(x) - rot)))


# -- the poles -----------------------------------------------------------------------------------
@pytest.mark.parametrize("name", list(BODIES))
@pytest.mark.parametrize("law", [pk.Viscous(0.05), pk.Viscous(5.0), pk.RegularisedCoulomb(0.3, 1e-3)],
                         ids=["viscous-weak", "viscous-strong", "regularised"])
def test_pole_criterion_is_where_the_linearisation_changes_sign(name, law):
    """n0^2 rho (A rho - C h0) = h2 h0^2 (manifolds.pole_stability_threshold, derived from the
    zero-slip crossing) against the exact linearisation at theta = 0 and theta = pi, for bodies
    with and without flip symmetry and friction from weak to strong."""
    body = BODIES[name]()
    m = pk.Model(body, law, "vector")
    for pole, state in (("upright", vertical_state), ("inverted", inverted_state)):
        crit = pole_stability_threshold(body, pole)
        if crit.threshold is None:
            for n0 in (0.5, 3.0, 20.0):
                assert (growth(linearise(m, state(n0))) < 0) == crit.stable(n0)
            continue
        lo, hi = (growth(linearise(m, state(f * crit.threshold))) for f in (0.98, 1.02))
        assert (lo < 0) == crit.stable(0.98 * crit.threshold) and (hi < 0) == crit.stable(1.02 * crit.threshold)
        assert (lo < 0) != (hi < 0)


def test_pole_criterion_reduces_to_the_spheroid_and_tippe_top_forms():
    for a, A, C in [(0.6, None, None), (2 / 3, None, None), (1.5, 0.4, 0.5), (0.5, 0.3, 0.45)]:
        body = pk.Spheroid(a, A=A, C=C)
        t = pole_stability_threshold(body).threshold
        assert t == pytest.approx(vertical_stability_threshold(body.A, body.C, a), rel=1e-13)
        assert pole_stability_threshold(body, "inverted").threshold == pytest.approx(t, rel=1e-13)
    for A in (0.31, 0.38):
        top = pk.EccentricSphere(0.3, A=A, C=0.4)
        assert pole_stability_threshold(top).threshold == pytest.approx(pk.theory.tippetop.upright_unstable_spin(0.3, A, 0.4), rel=1e-13)
        assert pole_stability_threshold(top, "inverted").threshold == pytest.approx(
            pk.theory.tippetop.inverted_stable_spin(0.3, A, 0.4), rel=1e-13)


def test_inverted_state_is_exact_and_reported_only_without_flip_symmetry():
    for name, make in BODIES.items():
        body = make()
        m = pk.Model(body, pk.Viscous(0.1), "vector")
        assert np.max(np.abs(m.rhs(inverted_state(4.0)))) < 1e-14
        kinds = [p.kind for p in fixed_points(pk.Model(body, pk.Viscous(0.1)), n0=4.0)]
        assert kinds[:2] == ["vertical", "inverted"], name
    assert "inverted" not in [p.kind for p in fixed_points(pk.Model(pk.Spheroid(0.6), pk.Viscous(0.1)), n0=4.0)]


# -- precessions of bodies without flip symmetry ---------------------------------------------------
@pytest.mark.parametrize("name", ["egg-prolate", "egg-oblate", "lopsided", "custom"])
@pytest.mark.parametrize("family", [{"omega0": 3.0}, {"omega0": 12.0}, {"n0": 2.0}, {"n0": 9.0}])
def test_every_precession_is_a_relative_equilibrium_of_the_vector_chart(name, family):
    """The precessions found from G(theta) = 0 in the Euler chart, checked in the vector chart
    (an independent formulation): the field there is rotation at Omega about e_Z, to 1e-11."""
    body = BODIES[name]()
    pts = [p for p in fixed_points(pk.Model(body, pk.Viscous(0.1)), **family) if p.kind in ("intermediate", "horizontal-like")]
    roots = precession_angles(body, **family)
    assert len(pts) == len(roots)
    for p in pts:
        assert p.residual < 1e-12
        assert rotating_residual(body, p.y) < 1e-11 * max(1.0, abs(p.y[2]) ** 2)
        key = "Omega" if "omega0" in family else "n"
        assert p.parameter[key] == next(iter(family.values()))


def test_precession_angles_find_every_sign_change():
    """Brute force: the residual on a 2 10^4-point grid changes sign exactly where the roots are."""
    body = Egg(1.3, 0.1)
    for fam in ({"omega0": 2.0}, {"omega0": 6.0}, {"n0": 3.0}):
        th = np.linspace(1e-4, np.pi - 1e-4, 20001)
        g = precession_residual(body, th, **fam)
        brute = th[:-1][np.sign(g[:-1]) != np.sign(g[1:])]
        roots = precession_angles(body, **fam)
        assert len(roots) == len(brute)
        np.testing.assert_allclose(roots, brute, atol=np.pi / 2e4)
        for r in roots:
            assert abs(precession_residual(body, r, **fam)) < 1e-13


def test_horizontal_like_state_continues_the_horizontal_state():
    """As the odd term eps -> 0 the horizontal-like state of the lopsided body tends to the
    horizontal state of the spheroid it perturbs (theta -> pi/2, n -> 0) with its spectrum."""
    ref = linearise(pk.Model(pk.Spheroid(1.5, A=0.62, C=0.4), pk.Viscous(0.1)), horizontal_state(8.0))
    def key(z):
        return round(z.real, 6), round(z.imag, 6)

    prev = None
    for eps in (1e-2, 1e-3, 1e-4):
        body = lopsided(eps)
        pts = [p for p in fixed_points(pk.Model(body, pk.Viscous(0.1)), omega0=8.0) if p.kind == "horizontal-like"]
        assert len(pts) == 1
        p = pts[0]
        dist = abs(p.x[4] - np.pi / 2) + abs(p.x[5])
        assert dist < 50 * eps
        if prev is not None:
            assert dist < 0.2 * prev  # shrinks linearly with eps
        prev = dist
        err = np.max(np.abs(np.array(sorted(p.eigenvalues, key=key)) - np.array(sorted(ref.eigenvalues, key=key))))
        assert err < 100 * eps
    assert p.n_unstable == ref.n_unstable == 1  # the rising mode (Omega0 > sqrt(5))


def test_side_equilibrium_of_an_egg():
    """theta_1: the egg at rest on its side (h_theta = 0, a minimum of h); theta_2: where the
    horizontal-like precession goes as Omega grows."""
    egg = Egg(1.3, 0.05)
    th1, th2 = side_equilibrium(egg)
    h, h1, h2 = egg.h(th1)
    assert abs(h1) < 1e-13 and h2 > 0 and th1 > np.pi / 2  # the thin end tilts down at rest
    thetas = [precession_angles(egg, omega0=om) for om in (5.0, 20.0, 80.0)]
    near = [min(t, key=lambda x: abs(x - th2)) for t in thetas]
    assert abs(near[2] - th2) < abs(near[1] - th2) < abs(near[0] - th2) and abs(near[2] - th2) < 1e-3


# -- dynamics: which end rises -------------------------------------------------------------------
def test_the_horizontal_like_state_separates_the_two_ends():
    """Started on the sliding branch just below the horizontal-like precession theta_h(Omega0)
    the egg rises toward its fat end (theta decreases), just above it toward its thin end,
    although both starts have the thin end lower (theta0 > pi/2): the separatrix is not pi/2."""
    import phasekit as pk

    egg = Egg(57 / 43, 0.05)
    th_h = pk.steady.precessions.horizontal_like_angle(egg, pk.steady.precession_angles(egg, omega0=6.0))
    assert th_h - np.pi / 2 > 0.15
    ends = {}
    for d in (-0.02, 0.02):
        y0 = pk.gyroscopic_start(egg, th_h + d, omega0=6.0)
        r = pk.simulate(pk.Model(egg, pk.Coulomb(0.1)), y0, 60.0, rtol=1e-9, track_minima=False,
                        events=[pk.Event("theta", 1.2, direction=-1, name="fat"), pk.Event("theta", 2.4, direction=+1, name="thin")])
        assert r.status is pk.Status.STOPPED
        ends[d] = r.events[-1].name
    assert ends == {-0.02: "fat", 0.02: "thin"}


# -- the equator criterion, and where it stops holding ---------------------------------------------
def test_equator_criterion_holds_for_weak_friction_only():
    """(C rho_m / h_e - A) Omega0^2 = h2 (manifolds.equator_stability_threshold; the spheroid's
    (a^2 C - A) Omega0^2 = a^2 - 1) is where the horizontal state of a flip-symmetric body
    changes stability for viscous mu up to ~0.8 (a = 1.5); for stronger friction a second mode
    destabilises first (measured: mu = 1 gives 1.9652, mu = 5 gives 1.4710 instead of sqrt 5)."""
    scaled = pk.CustomBody(lambda c: 1.3 * ca.sqrt(1 + 0.8 * c * c), variable="cos", A=0.7, C=0.45)  # h_e = 1.3
    for body in (pk.Spheroid(1.5), scaled):
        oc = equator_stability_threshold(body)
        if isinstance(body, pk.Spheroid):
            assert oc == pytest.approx(horizontal_stability_threshold(body.A, body.C, 1.5), rel=1e-14)
        for mu in (0.05, 0.5):
            m = pk.Model(body, pk.Viscous(mu))
            assert growth(linearise(m, horizontal_state(0.99 * oc))) < 0 < growth(linearise(m, horizontal_state(1.01 * oc)))
    m = pk.Model(pk.Spheroid(1.5), pk.Viscous(1.0))
    assert growth(linearise(m, horizontal_state(1.95))) < 0 < growth(linearise(m, horizontal_state(1.98)))
    assert equator_stability_threshold(Egg(1.3, 0.05)) is None  # not balanced at pi/2
