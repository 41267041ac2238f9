"""Checks of phasekit.theory.tippetop's closed forms against an independent model.

The reference model (newton_euler_tippe_top.py) is the full 3-D Newton-Euler system of an
eccentric sphere on a plane with a viscous sliding-friction law. It shares no code with the
module: stability boundaries are checked by eigenvalues of its numerical Jacobian, the
classification by integrating it.
"""

import math

from phasekit import ParameterError
from phasekit.theory import tippetop as tt

import numpy as np
import pytest

from .newton_euler_tippe_top import (
    EZ,
    final_theta,
    jacobian,
    jellett_of_state,
    pole_max_real,
    rhs,
    rotating_rhs,
    vertical_start,
)

CASES = [(0.3, 0.38, 0.4), (0.3, 0.31, 0.4), (0.1, 0.37, 0.4), (0.5, 0.5, 0.4)]


def test_inversion_interval_endpoints():
    assert tt.inversion.inversion_interval(0.3) == pytest.approx((0.7, 1.3))
    assert tt.inversion.inversion_interval(0.0) == (1.0, 1.0)
    C = 0.4
    assert not tt.classical_inversion(0.3, 0.7 * C, C)  # open at both ends
    assert not tt.classical_inversion(0.3, 1.3 * C, C)
    assert tt.classical_inversion(0.3, 0.7 * C * (1 + 1e-9), C)
    assert tt.classical_inversion(0.3, 1.3 * C * (1 - 1e-9), C)
    assert tt.classical_inversion(0.3, 0.38, 0.4) and tt.classical_inversion(0.3, 0.31, 0.4)
    assert not tt.classical_inversion(0.3, 0.2, 0.4)


def test_default_eccentric_sphere_moments():
    # phasekit's default EccentricSphere: moments about O of a uniform ball -> A = 0.4 - a^2, C = 0.4,
    # gamma = 1 - 2.5 a^2 lies in (1 - a, 1 + a) iff a < 0.4.
    for a, expect in [(0.1, True), (0.3, True), (0.39, True), (0.41, False)]:
        A, C = tt.inversion.moments_about_G(a, 0.4, 0.4)
        assert A == pytest.approx(0.4 - a * a)
        assert tt.classical_inversion(a, A, C) is expect


def test_interval_is_where_both_critical_spins_are_finite():
    for a in (0.05, 0.3, 0.6):
        for gam in np.linspace(0.2, 2.0, 37):
            A, C = gam * 0.4, 0.4
            up, inv = tt.upright_unstable_spin(a, A, C), tt.inverted_stable_spin(a, A, C)
            assert math.isfinite(up) == (gam > 1 - a)
            assert math.isfinite(inv) == (gam < 1 + a)
            both = math.isfinite(up) and math.isfinite(inv)
            assert both == tt.classical_inversion(a, A, C) == (tt.ueda_group_limit(a, A, C) == "II")


@pytest.mark.parametrize("alpha,A,C", CASES)
@pytest.mark.parametrize("kappa", [0.3, 2.0])
def test_upright_instability_spin_matches_eigenvalues(alpha, A, C, kappa):
    n_up = tt.upright_unstable_spin(alpha, A, C)
    assert pole_max_real(alpha, A, C, 0.97 * n_up, False, kappa) < 0
    assert pole_max_real(alpha, A, C, 1.03 * n_up, False, kappa) > 0


@pytest.mark.parametrize("alpha,A,C", CASES)
@pytest.mark.parametrize("kappa", [0.3, 2.0])
def test_inverted_stability_spin_matches_eigenvalues(alpha, A, C, kappa):
    n_inv = tt.inverted_stable_spin(alpha, A, C)
    assert pole_max_real(alpha, A, C, 0.97 * n_inv, True, kappa) > 0
    assert pole_max_real(alpha, A, C, 1.03 * n_inv, True, kappa) < 0


def test_outside_interval_the_poles_never_switch():
    # gamma < 1 - alpha: upright stable at all spins; gamma > 1 + alpha: inverted unstable at all spins
    for spin in (0.5, 3.0, 20.0):
        assert pole_max_real(0.3, 0.2, 0.4, spin, False) < 0
        assert pole_max_real(0.3, 0.56, 0.4, spin, True) > 0


def test_jellett_threshold_is_the_published_formula_and_the_inverted_boundary():
    for a, A, C in CASES:
        gam = A / C
        m = g = R = 1.0
        published = math.sqrt(m * g * R**3 * C * a) * (1 + a) ** 2 / math.sqrt(1 + a - gam)  # [RR14] abstract
        lam = tt.steady.jellett_threshold(a, A, C)
        assert lam == pytest.approx(published, rel=1e-14)
        assert lam == pytest.approx(math.sqrt(a * C * (1 + a) ** 4 / (1 + a - gam)), rel=1e-14)
        assert lam == pytest.approx(C * (1 + a) * tt.inverted_stable_spin(a, A, C), rel=1e-14)
        assert lam**2 == pytest.approx(tt.steady.steady_state_jellett_sq(a, A, C, -1.0), rel=1e-12)
        assert tt.steady.upright_unstable_jellett(a, A, C) ** 2 == pytest.approx(tt.steady.steady_state_jellett_sq(a, A, C, 1.0))
        assert tt.steady.upright_unstable_jellett(a, A, C) == pytest.approx(C * (1 - a) * tt.upright_unstable_spin(a, A, C))
    assert tt.steady.jellett_threshold(0.3, 0.52, 0.4) == math.inf


def test_small_alpha_limit():
    C, gam = 0.4, 0.9
    for a in (1e-2, 1e-4, 1e-6):
        lam = tt.steady.jellett_threshold(a, gam * C, C)
        assert lam / math.sqrt(a) == pytest.approx(math.sqrt(C / (1 - gam)), rel=5 * a)
    assert tt.steady.jellett_threshold(1e-12, gam * C, C) == pytest.approx(2e-6, rel=1e-6)


def test_jellett_of_vertical_start_against_the_vector_state_and_conservation():
    a, A, C = 0.3, 0.38, 0.4
    for th0, n0 in [(0.0, 3.0), (0.1, 3.0), (1.0, -2.0), (2.5, 1.5)]:
        x = vertical_start(th0, n0)
        assert tt.jellett_of_vertical_start(a, A, C, th0, n0) == pytest.approx(jellett_of_state(x, a, A, C), abs=1e-14)
    assert tt.jellett_of_vertical_start(a, A, C, 0.0, 2.0) == pytest.approx(C * 2.0 * (1 - a))
    _, sol = final_theta(a, A, C, 0.1, 3.0, 40.0)
    lam = [jellett_of_state(sol.y[:, i], a, A, C) for i in range(sol.y.shape[1])]
    assert np.ptp(lam) < 1e-6 * abs(lam[0])


def test_critical_spin_from_jellett():
    a, A, C = 0.3, 0.38, 0.4
    assert tt.inversion.critical_spin_from_jellett(a, A, C, 0.0) == pytest.approx(
        (1 + a) ** 2 * math.sqrt(a / (C * (1 + a - A / C))) / (1 - a), rel=1e-14)
    for th0 in (0.0, 0.05, 0.1, 0.3):
        n0 = tt.inversion.critical_spin_from_jellett(a, A, C, th0)
        assert abs(tt.jellett_of_vertical_start(a, A, C, th0, n0)) == pytest.approx(tt.steady.jellett_threshold(a, A, C))


@pytest.mark.parametrize("alpha,A,C", CASES + [(0.3, 0.56, 0.4), (0.3, 0.2, 0.4)])
def test_steady_precession_is_a_relative_equilibrium_with_predicted_stability(alpha, A, C):
    for z in np.linspace(-0.9, 0.9, 7):
        th = math.acos(z)
        try:
            st = tt.steady.steady_precession(alpha, A, C, th)
        except ParameterError:
            assert (A - C) * z + C * alpha <= 0
            continue
        k = np.array([math.sin(th), 0, z])
        x = np.concatenate([k, st["Omega"] * (EZ - alpha * k), [0, 0]])
        _, N, slip = rhs(x, alpha, A, C, 0.5)
        assert N == pytest.approx(1.0) and np.abs(slip).max() < 1e-12
        assert np.abs(rotating_rhs(x, alpha, A, C, 0.5, st["Omega"])).max() < 1e-12
        assert st["n"] == pytest.approx(x[3:6] @ k) and st["jellett"] == pytest.approx(jellett_of_state(x, alpha, A, C))
        assert st["jellett"] ** 2 == pytest.approx(tt.steady.steady_state_jellett_sq(alpha, A, C, z))
        # stable iff g'(z) < 0 (a minimum of V); skip near-marginal points
        h = 1e-5
        gp = (tt.steady.steady_state_jellett_sq(alpha, A, C, z + h) - tt.steady.steady_state_jellett_sq(alpha, A, C, z - h)) / (2 * h)
        if abs(gp) < 1e-2:
            continue
        ev = np.linalg.eigvals(jacobian(lambda y, Om=st["Omega"]: rotating_rhs(y, alpha, A, C, 0.5, Om), x))
        ev = ev[np.abs(ev) > 1e-6]  # drop the symmetry / family zeros
        assert (ev.real.max() < 0) == (gp < 0), (z, gp, ev)


def test_effective_potential_critical_points_are_the_steady_states():
    a, A, C = 0.3, 0.38, 0.4
    st = tt.steady.steady_precession(a, A, C, 1.2)
    h = 1e-5
    dV = (tt.steady.effective_potential(a, A, C, st["jellett"], 1.2 + h) - tt.steady.effective_potential(a, A, C, st["jellett"], 1.2 - h)) / (2 * h)
    assert abs(dV) < 1e-8


def test_group_limits():
    assert tt.ueda_group_limit(0.3, 0.2, 0.4) == "I"
    assert tt.ueda_group_limit(0.3, 0.38, 0.4) == "II"
    assert tt.ueda_group_limit(0.3, 0.56, 0.4) == "III"
    assert tt.ueda_group(0.3, 0.2, 0.4, 1e3) == "never"
    assert tt.ueda_group(0.3, 0.38, 0.4, 1e3) == "full"
    assert tt.ueda_group(0.3, 0.56, 0.4, 1e3) == "partial"
    lim = tt.groups.theta_f_limit(0.3, 0.56, 0.4)
    assert math.cos(lim) == pytest.approx(-0.3 / (1.4 - 1))
    assert tt.theta_f(0.3, 0.56, 0.4, 1e4) == pytest.approx(lim, abs=1e-4)
    assert math.isnan(tt.groups.theta_f_limit(0.3, 0.38, 0.4)) and math.isnan(tt.groups.theta_f_limit(0.3, 0.2, 0.4))


@pytest.mark.parametrize("alpha,A,C", CASES)
def test_group_boundaries_are_the_critical_spins(alpha, A, C):
    for th0 in (0.0, 0.1):
        n_up = tt.inversion.spin_for_jellett(alpha, A, C, tt.steady.upright_unstable_jellett(alpha, A, C), th0)
        n_c = tt.full_inversion_spin(alpha, A, C, theta0=th0)
        assert n_c >= n_up * (1 - 1e-12)
        assert tt.ueda_group(alpha, A, C, 0.999 * n_up, theta0=th0) == "never"
        assert tt.ueda_group(alpha, A, C, 1.001 * n_up, theta0=th0) != "never"
        assert tt.ueda_group(alpha, A, C, 1.001 * n_c, theta0=th0) == "full"
        if n_c > 1.01 * n_up:
            assert tt.ueda_group(alpha, A, C, 0.999 * n_c, theta0=th0) == "partial"
        if tt.inversion.full_inversion_jellett(alpha, A, C) == pytest.approx(tt.steady.jellett_threshold(alpha, A, C)):
            assert n_c == pytest.approx(tt.inversion.critical_spin_from_jellett(alpha, A, C, th0))


@pytest.mark.parametrize("alpha,A,C", CASES + [(0.3, 0.56, 0.4)])
def test_theta_f_solves_the_steady_state_equation(alpha, A, C):
    zs = np.linspace(-1, 1, 20001)
    g = tt.steady.steady_state_jellett_sq(alpha, A, C, zs)
    for n in np.linspace(0.2, 6.0, 30):
        lam2 = tt.jellett_of_vertical_start(alpha, A, C, 0.0, n) ** 2
        grp, th = tt.ueda_group(alpha, A, C, n), tt.theta_f(alpha, A, C, n)
        # brute force on a grid: first z (going down from 1) with g(z) >= lam2
        if lam2 <= g[-1]:
            assert grp == "never" and th == 0.0
            continue
        hit = np.nonzero(g >= lam2)[0]
        if hit.size == 0:
            assert grp == "full" and th == math.pi
            continue
        assert grp == "partial"
        assert math.cos(th) == pytest.approx(zs[hit.max()], abs=2e-4)
        assert tt.steady.steady_state_jellett_sq(alpha, A, C, math.cos(th)) == pytest.approx(lam2, rel=1e-8)


def test_full_inversion_jellett_is_the_max_of_g():
    for a, A, C in CASES:
        zs = np.linspace(-1, 1, 200001)
        assert tt.inversion.full_inversion_jellett(a, A, C) ** 2 == pytest.approx(np.max(tt.steady.steady_state_jellett_sq(a, A, C, zs)), rel=1e-8)
        assert tt.inversion.full_inversion_jellett(a, A, C) >= tt.steady.jellett_threshold(a, A, C) * (1 - 1e-12)
    # gamma >= 1: g is decreasing, so [RR14]'s threshold is the whole story
    assert tt.inversion.full_inversion_jellett(0.3, 0.44, 0.4) == pytest.approx(tt.steady.jellett_threshold(0.3, 0.44, 0.4))
    assert tt.inversion.full_inversion_jellett(0.3, 0.2, 0.4) == math.inf


@pytest.mark.parametrize("alpha,A,C,n0,T,expect", [
    (0.3, 0.38, 0.4, 0.8, 300.0, "never"),
    # upright stable although a stable intermediate state exists
    pytest.param(0.3, 0.31, 0.4, 2.0, 300.0, "never", marks=pytest.mark.slow),
    (0.3, 0.31, 0.4, 4.0, 300.0, "full"),
    (0.3, 0.38, 0.4, 6.0, 300.0, "full"),
    pytest.param(0.3, 0.31, 0.4, 2.6, 400.0, "partial", marks=pytest.mark.slow),
    pytest.param(0.3, 0.56, 0.4, 5.0, 400.0, "partial", marks=pytest.mark.slow),
])
def test_simulation_ends_where_predicted(alpha, A, C, n0, T, expect):
    th0 = 0.1
    assert tt.ueda_group(alpha, A, C, n0, theta0=th0) == expect
    th, _ = final_theta(alpha, A, C, th0, n0, T)
    if expect == "never":
        assert th < 0.05
    elif expect == "full":
        assert th > math.pi - 0.01
    else:
        assert th == pytest.approx(tt.theta_f(alpha, A, C, n0, theta0=th0), abs=0.01)


@pytest.mark.parametrize("call", [
    lambda: tt.classical_inversion(1.0, 0.3, 0.4),
    lambda: tt.classical_inversion(0.0, 0.3, 0.4),
    lambda: tt.classical_inversion(0.3, -0.3, 0.4),
    lambda: tt.steady.jellett_threshold(0.3, 0.3, 0.0),
    lambda: tt.ueda_group(0.3, 0.38, 0.4, float("nan")),
    lambda: tt.theta_f(0.3, 0.38, 0.4, 2.0, theta0=4.0),
    lambda: tt.inversion.critical_spin_from_jellett(0.3, 0.38, 0.4, -0.1),
    lambda: tt.steady.steady_precession(0.3, 0.2, 0.4, 0.1),
    lambda: tt.inversion.moments_about_G(0.5, 0.2, 0.4),
    lambda: tt.inversion.inversion_interval("0.3"),
])
def test_bad_input_raises_parameter_error(call):
    with pytest.raises(ParameterError):
        call()
