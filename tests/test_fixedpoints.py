"""Issue 4: fixed points, exact linearisation, stability, unstable-manifold seeds."""

import phasekit as pk
from phasekit.steady.fixedpoints import continue_family, find_fixed_point, fixed_points
from phasekit.steady.linearisation import linearise
from phasekit.steady.manifolds import unstable_manifold_start, unstable_seeds
from phasekit.steady.precessions import horizontal_state, intermediate_state, vertical_state
from phasekit.studies.linear_stability import vertical_is_stable
from phasekit.theory.criteria import (
    horizontal_stability_threshold,
    vertical_stability_threshold,
)

import numpy as np
import pytest

from .helpers import central_jacobian
from .reference_values import PAPER_START_5_2


@pytest.mark.parametrize("a", [1.5, 0.6])
@pytest.mark.parametrize("law", [pk.Viscous(0.1), pk.RegularisedCoulomb(0.1, 1e-4), pk.Coulomb(0.1)], ids=["viscous", "reg", "exact"])
def test_residuals_and_jacobians_at_fixed_points(a, law):
    body = pk.Spheroid(a)
    me, mv = pk.Model(body, law), pk.Model(body, law, "vector")
    pts = fixed_points(me, omega0=2.3) + fixed_points(me, mv, n0=6.0)
    assert {p.kind for p in pts} >= {"horizontal", "vertical"}
    for p in pts:
        assert p.residual < 1e-12, p
        if law.name == "viscous":  # the sliding field is smooth there: compare with differences
            m = mv if p.chart == "vector" else me
            J = m.jacobian(p.x)
            np.testing.assert_allclose(J, central_jacobian(m.rhs, p.x), atol=1e-6 * max(1, np.abs(J).max()))


def test_newton_from_a_rough_guess_and_intermediate_family_formula(prolate):
    m = pk.Model(prolate, pk.Viscous(0.1))
    exact = intermediate_state(prolate, 0.8)
    guess = exact + np.array([0.01, -0.01, 0.0, 0.02, 0.05, 0.1])
    fp = find_fixed_point(m, guess, kind="intermediate", value=exact[2])
    np.testing.assert_allclose(fp.x, exact, atol=1e-10)
    assert fp.residual < 1e-13
    # the family: Omega^2 = h_t / (sin [(A - C) cos + C h_t / x_P]) at every theta*
    br = continue_family(m, "intermediate", np.linspace(exact[2], exact[2] * 1.05, 6), start=exact)
    for p in br.points:
        np.testing.assert_allclose(p.x, intermediate_state(prolate, p.x[4]), atol=1e-9)


def test_prolate_horizontal_rising_mode_is_real_and_linear_in_mu(prolate):
    rates = []
    mus = np.array([1e-3, 3e-3, 1e-2, 3e-2, 0.1])
    for mu in mus:
        fp = linearise(pk.Model(prolate, pk.Viscous(mu)), horizontal_state(10.0), kind="horizontal")
        assert fp.n_unstable == 1 and fp.classification == "unstable: 1 real unstable"
        assert fp.eigenvalues[0].imag == 0.0
        rates.append(fp.eigenvalues[0].real)
    slope = np.polyfit(np.log(mus), np.log(rates), 1)[0]
    assert slope == pytest.approx(1.0, abs=0.01)
    assert 0.5 < rates[0] / mus[0] < 2  # O(mu), not just proportional


def test_oscillatory_frequencies_approach_3_30(prolate):
    """At theta = pi/2 (3.30) gives omega^2 = Omega0^2 + h_tt / A; the pairs approach it."""
    errs = []
    for om in (5.0, 10.0, 20.0, 40.0):
        fp = linearise(pk.Model(prolate, pk.Viscous(0.1)), horizontal_state(om))
        freqs = np.abs(fp.eigenvalues.imag[fp.eigenvalues.imag > 0])
        assert freqs.size == 2
        w = np.sqrt(om**2 + prolate.h(np.pi / 2)[2] / prolate.A)
        errs.append(np.max(np.abs(freqs - w)) / w)
    assert all(e2 < e1 / 3 for e1, e2 in zip(errs, errs[1:]))  # ~Omega0^-2
    assert errs[-1] < 1e-3


@pytest.mark.parametrize("a", [1.2, 1.5, 2.0, 3.0, 0.6, 0.9])
@pytest.mark.parametrize("mu", [0.01, 0.3])
def test_vertical_stability_criterion(a, mu):
    """Stability changes at (a^2 C - A) n0^2 = a^3 (a^2 - 1): n0 = sqrt(5 a^3) for the uniform
    spheroid, whatever mu: prolate stable above it, oblate unstable above it."""
    body = pk.Spheroid(a)
    nc = vertical_stability_threshold(body.A, body.C, a)
    assert nc == pytest.approx(np.sqrt(5 * a**3), rel=1e-12)
    m = pk.Model(body, pk.Viscous(mu), "vector")
    below = linearise(m, vertical_state(0.97 * nc))
    above = linearise(m, vertical_state(1.03 * nc))
    if a > 1:
        assert not below.stable and above.stable
    else:
        assert below.stable and not above.stable
    assert vertical_is_stable(body.A, body.C, a, 1.03 * nc) == above.stable


@pytest.mark.parametrize("a, A, C", [(2.0, 0.8, 0.5), (1.5, 0.5, 0.7), (1.1, 0.5, 0.45)])
def test_vertical_criterion_nonuniform(a, A, C):
    body = pk.Spheroid(a, A=A, C=C)
    nc = vertical_stability_threshold(A, C, a)
    m = pk.Model(body, pk.Viscous(0.05), "vector")
    assert not linearise(m, vertical_state(0.99 * nc)).stable
    assert linearise(m, vertical_state(1.01 * nc)).stable
    # the frictionless (sleeping-top) threshold C^2 n^2 = 4 A (a - 1/a) lies below it
    m0 = pk.Model(body, pk.Viscous(0.0), "vector")
    n_top = np.sqrt(4 * A * (a - 1 / a)) / C
    assert n_top <= nc and linearise(m0, vertical_state(1.01 * n_top)).n_unstable == 0


def test_roles_swap_between_prolate_and_oblate():
    for a, vertical_stable, horizontal_unstable in [(1.5, True, True), (0.6, False, False)]:
        body = pk.Spheroid(a)
        h = linearise(pk.Model(body, pk.Viscous(0.1)), horizontal_state(10.0))
        v = linearise(pk.Model(body, pk.Viscous(0.1), "vector"), vertical_state(10.0))
        assert v.stable is vertical_stable and (h.n_unstable > 0) is horizontal_unstable


def test_regularised_coulomb_spectrum_tends_to_rolling(prolate):
    roll = linearise(pk.Model(prolate, pk.Coulomb(0.1)), horizontal_state(10.0))
    assert roll.law == "coulomb-rolling" and roll.n_unstable == 0
    w_roll = roll.eigenvalues.imag.max()
    for eps in (1e-4, 1e-6):
        reg = linearise(pk.Model(prolate, pk.RegularisedCoulomb(0.1, eps)), horizontal_state(10.0))
        slow = reg.eigenvalues[np.abs(reg.eigenvalues) < 1 / eps * 1e-2]
        fast = reg.eigenvalues[np.abs(reg.eigenvalues) > 1 / eps * 1e-2]
        assert fast.size == 2 and np.all(fast.real < -0.1 / eps)  # slip relaxes at ~mu/eps
        assert abs(slow.imag.max() - w_roll) < 1e-6
        assert np.max(np.abs(slow.real)) < 200 * eps  # real parts -> 0 like eps


def test_seeds_leave_along_the_eigenvector(prolate):
    m, x0, fp = unstable_manifold_start(prolate, pk.Viscous(0.1), state="horizontal", delta=1e-6, omega0=10.0, seed_law="same")
    v = (x0 - fp.x) / np.linalg.norm(x0 - fp.x)
    lam = fp.eigenvalues[0].real
    T = np.log(100.0) / lam
    te = np.linspace(0, T, 30)
    r = pk.simulate(m, x0, T * 1.01, rtol=1e-12, t_eval=te)
    d = r.ys - fp.x
    norms = np.linalg.norm(d, axis=1)
    assert norms[-1] / norms[0] > 90
    cosang = np.abs(d @ v) / norms
    assert np.all(cosang > 0.99)


def test_paper_start_5_2_is_the_viscous_eigenvector(prolate):
    """(5.2) is the horizontal state at Omega0 = 10.5 plus 0.02 x the viscous unstable eigenvector,
    to the one significant figure printed."""
    _, x0, fp = unstable_manifold_start(prolate, pk.Coulomb(0.1), state="horizontal", delta=0.02, omega0=10.5)
    s = PAPER_START_5_2
    printed = np.array([s["U"], s["V"], 10.5, s["Lambda"], s["theta"], s["n"]])
    for i in (0, 1, 3, 5):
        assert x0[i] == pytest.approx(printed[i], rel=0.15)
    assert (np.pi / 2 - x0[4]) == pytest.approx(np.pi / 2 - printed[4], rel=0.2)


def test_seed_signs_and_vertical_seed():
    body = pk.Spheroid(0.6)
    fp = linearise(pk.Model(body, pk.Viscous(0.1), "vector"), vertical_state(12.0), kind="vertical")
    seeds = dict(unstable_seeds(fp, 0.01))
    assert set(seeds) == {"+0", "-0", "+1", "-1"}  # a complex pair spans two real directions
    assert seeds["+0"][0] > 0 and np.linalg.norm(seeds["+0"] - fp.x) == pytest.approx(0.01)
    with pytest.raises(ValueError, match="`n0` gives a vertical state without an unstable direction"):
        unstable_manifold_start(pk.Spheroid(1.5), pk.Viscous(0.1), state="vertical", delta=0.01, n0=10.0)


@pytest.mark.parametrize("a, A, C", [(1.5, None, None), (0.5, None, None), (2.0, 0.8, 0.5), (0.6, 0.3, 0.5)])
def test_horizontal_criterion(a, A, C):
    """The horizontal precession changes stability at (a^2 C - A) Omega0^2 = a^2 - 1 (sqrt 5 if uniform)."""
    body = pk.Spheroid(a, A=A, C=C)
    oc = horizontal_stability_threshold(body.A, body.C, a)
    if A is None:
        assert oc == pytest.approx(np.sqrt(5.0), rel=1e-12)
    m = pk.Model(body, pk.Viscous(0.1))
    lo, hi = linearise(m, horizontal_state(0.98 * oc)), linearise(m, horizontal_state(1.02 * oc))
    if a > 1:
        assert lo.stable and hi.n_unstable == 1
    else:
        assert lo.n_unstable == 1 and hi.stable
