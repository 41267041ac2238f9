"""Coulomb friction over a circular contact patch (phasekit.friction.patch): the exact force and
couple against an independent 2-D quadrature of the traction, their limits, the smooth approximants'
measured errors, the CasADi expressions, Hertz contact and the principal radii of a body of revolution.

The brute-force quadrature below integrates the local traction -p u/|u| itself, in polar coordinates
about the centre of rotation c (where u = 0), so that the integrand is smooth: it shares no formula
with the module's ring-by-ring elliptic kernels or closed forms.
"""

import math

import phasekit as pk  # noqa: F401  (installs the package's start-up, as every test module does)
from phasekit.friction.hertz import MATERIALS, effective_modulus, hertz_ellipse, hertz_radius, principal_radii
from phasekit.friction.patch import APPROXIMANT_ERRORS, PATCH_LIMITS, patch_friction, patch_resultant

import casadi as ca
import numpy as np
import pytest
from numpy.polynomial.legendre import leggauss

PRESSURES = ("uniform", "hertz")
#: ratios s = |v|/(a |omega|) with the centre of rotation inside (s < 1) and outside the patch
BRUTE_S = (0.25, 0.8, 0.95, 1.6, 5.0)


def brute_force(s, pressure, n_phi=400, n_t=40, n_theta=200):
    """(f, g, d, transverse force) on the unit patch with omega = 1, v = (s, 0), so c = (0, s).

    s < 1: rays from c, rho = c + t e(phi), t in [0, L(phi)] with t = L (1 - w^2) (smooth at the rim
    for Hertz's square root), trapezoids in phi (periodic). s > 1: the rays that cross the patch,
    at angle psi to -c with sin(psi) = sin(theta)/s, t = mid - half cos(alpha); Gauss in theta, alpha.
    """
    c = np.array([0.0, s])
    xg, wg = leggauss(n_t)
    if s < 1:
        phi = 2 * np.pi * np.arange(n_phi) / n_phi
        e = np.stack([np.cos(phi), np.sin(phi)], -1)
        ce = e @ c
        root = np.sqrt(ce**2 + 1 - s * s)
        far, back = -ce + root, ce + root
        w, ww = (xg + 1) / 2, wg / 2
        t = far[:, None] * (1 - w**2)
        dt = 2 * far[:, None] * w * ww
        one_minus_r2 = (far[:, None] - t) * (t + back[:, None])
        weights = (2 * np.pi / n_phi) * dt * t
    else:
        th, wth = leggauss(n_theta)
        th, wth = th * np.pi / 2, wth * np.pi / 2
        spsi = np.sin(th) / s
        cpsi = np.sqrt(1 - spsi**2)
        e = np.stack([spsi, -cpsi], -1)
        mid, half = s * cpsi, np.cos(th)
        alpha, walpha = (xg + 1) / 2 * np.pi, wg / 2 * np.pi
        t = mid[:, None] - half[:, None] * np.cos(alpha)
        dt = half[:, None] * np.sin(alpha) * walpha
        one_minus_r2 = half[:, None] ** 2 * np.sin(alpha) ** 2
        weights = (wth * np.cos(th) / (s * cpsi))[:, None] * dt * t
    rho = c + t[..., None] * e[:, None, :]
    p = np.full(t.shape, 1 / np.pi) if pressure == "uniform" else 3 / (2 * np.pi) * np.sqrt(one_minus_r2)
    u = np.array([s, 0.0]) + np.stack([-rho[..., 1], rho[..., 0]], -1)  # v + e_z x rho
    speed = np.linalg.norm(u, axis=-1)
    traction = -p[..., None] * u / speed[..., None]
    F = (weights[..., None] * traction).sum((0, 1))
    M = (weights * (rho[..., 0] * traction[..., 1] - rho[..., 1] * traction[..., 0])).sum()
    return -F[0], -M, (weights * p * speed).sum(), F[1]


@pytest.mark.parametrize("pressure", PRESSURES)
@pytest.mark.parametrize("s", BRUTE_S)
def test_exact_force_couple_and_dissipation_match_a_brute_force_2d_quadrature(pressure, s):
    f, g, d = patch_resultant(s, pressure, dissipation=True)
    fb, gb, db, transverse = brute_force(s, pressure)
    assert fb == pytest.approx(f, rel=1e-10)
    assert gb == pytest.approx(g, rel=1e-10)
    assert db == pytest.approx(d, rel=1e-10)
    assert abs(transverse) < 1e-12  # the force is along v: the symmetry the module's (f, g) rests on


def test_uniform_closed_forms_agree_with_the_ring_quadrature():
    s = np.concatenate([np.geomspace(1e-6, 1e6, 61), [1 - 1e-9, 1.0, 1 + 1e-9, 2**0.5 - 1e-12, 2**0.5 + 1e-12]])
    closed = patch_resultant(s, "uniform", method="closed", dissipation=True)
    ring = patch_resultant(s, "uniform", method="quadrature", dissipation=True)
    for a, b in zip(closed, ring):
        np.testing.assert_allclose(a, b, rtol=2e-13)


def test_uniform_closed_forms_take_their_textbook_values_at_s_equal_one():
    f, g = patch_resultant(1.0)
    assert (f, g) == (pytest.approx(8 / (3 * math.pi), rel=1e-14), pytest.approx(8 / (9 * math.pi), rel=1e-14))
    assert patch_resultant(1.0, dissipation=True)[2] == pytest.approx(32 / (9 * math.pi), rel=1e-14)


def test_uniform_force_satisfies_the_inversion_symmetry():
    """f(s) = s f(1/s): s 2F1(-1/2, 1/2; 2; s^2) on one side, 2F1(.; 1/s^2) on the other."""
    s = np.geomspace(1e-3, 0.999, 40)
    f, _ = patch_resultant(s)
    f_inv, _ = patch_resultant(1 / s)
    np.testing.assert_allclose(f_inv, f / s, rtol=1e-13)


@pytest.mark.parametrize("s", [1e-4, 0.5, 0.999, 1.0, 1.001, 3.0, 1e4])
def test_hertz_quadrature_converges_to_machine_precision(s):
    coarse = patch_resultant(s, "hertz", level=4)
    fine = patch_resultant(s, "hertz", level=8)
    np.testing.assert_allclose(coarse, fine, rtol=1e-13)


@pytest.mark.parametrize("pressure", PRESSURES)
def test_force_is_the_slope_of_the_dissipation(pressure):
    """F = -dD/dv: f = d'(s), by a central difference of the dissipation alone."""
    s = np.array([0.3, 0.7, 1.4, 3.0])
    h = 1e-5
    d_plus, d_minus = (patch_resultant(x, pressure, dissipation=True)[2] for x in (s + h, s - h))
    slope = (d_plus - d_minus) / (2 * h)
    np.testing.assert_allclose(slope, patch_resultant(s, pressure)[0], rtol=1e-8)


@pytest.mark.parametrize("pressure, couple_at_infinity", [("uniform", 1 / 4), ("hertz", 1 / 5)])
def test_pure_slip_gives_the_full_coulomb_force_and_a_couple_linear_in_spin(pressure, couple_at_infinity):
    s = np.array([1e4, 1e5, 1e6])
    f, g = patch_resultant(s, pressure)
    np.testing.assert_allclose(f, 1.0, atol=2e-9)
    np.testing.assert_allclose(g * s, couple_at_infinity, rtol=1e-8)  # M = -mu R a^2 k_w omega/|v|
    assert PATCH_LIMITS[pressure].couple_slope == pytest.approx(couple_at_infinity, rel=1e-15)


@pytest.mark.parametrize("pressure, slip_slope, spin_couple", [
    ("uniform", 1.0, 2 / 3),                              # int r dA/(pi a^2) = 2a/3
    ("hertz", 3 * math.pi / 8, 3 * math.pi / 16),        # 3 int r^2 sqrt(1 - r^2) dr = 3 pi/16
])
def test_pure_spin_gives_the_pivoting_couple_and_a_force_linear_in_slip(pressure, slip_slope, spin_couple):
    s = np.array([1e-7, 2e-7, 4e-7])
    f, g = patch_resultant(s, pressure)
    np.testing.assert_allclose(f / s, slip_slope, rtol=1e-12)  # linear: a regularised law, eps = a|omega|/k_v
    np.testing.assert_allclose(g, spin_couple, rtol=1e-12)
    assert PATCH_LIMITS[pressure].slip_slope == pytest.approx(slip_slope, rel=1e-15)
    assert PATCH_LIMITS[pressure].spin_couple == pytest.approx(spin_couple, rel=1e-15)


def test_uniform_patch_regularises_slip_over_a_omega_not_8_a_omega_over_3_pi():
    """eps = 8 a|omega|/(3 pi) is Hertz pressure's; uniform pressure's is a|omega| (derivation note)."""
    s = 1e-6
    f_uniform, _ = patch_resultant(s)
    f_hertz, _ = patch_resultant(s, "hertz")
    assert s / f_uniform == pytest.approx(1.0, rel=1e-10)
    assert s / f_hertz == pytest.approx(8 / (3 * math.pi), rel=1e-10)


# ----------------------------------------------------------------------------------------------
# approximants

#: the approximants' validation grid: log-spaced over the whole plane and clustered at s = 1,
#: none of it the fitting grid (uniform in atan(s), plus 1e-9..1e-1 off x = 0)
VALID_S = np.unique(np.concatenate([np.geomspace(1e-6, 1e6, 4001), 1 - np.geomspace(1e-11, 0.05, 200),
                                    1 + np.geomspace(1e-11, 0.05, 200)]))


@pytest.fixture(scope="module")
def exact_on_grid():
    return {p: patch_resultant(VALID_S, p) for p in PRESSURES}


@pytest.mark.parametrize("pressure", PRESSURES)
def test_rational_approximant_error_is_below_its_stated_bound(pressure, exact_on_grid):
    f, g = exact_on_grid[pressure]
    fa, ga = patch_resultant(VALID_S, pressure, approximant="rational")
    bound_f, bound_g = APPROXIMANT_ERRORS[pressure]["rational"]
    assert np.max(np.abs(fa / f - 1)) <= bound_f
    assert np.max(np.abs(ga / g - 1)) <= bound_g
    assert max(bound_f, bound_g) < 1e-5


@pytest.mark.parametrize("pressure", PRESSURES)
@pytest.mark.parametrize("approximant", ["pade1", "pade2"])
def test_pade_approximants_errors_are_as_stated(pressure, approximant, exact_on_grid):
    f, g = exact_on_grid[pressure]
    fa, ga = patch_resultant(VALID_S, pressure, approximant=approximant)
    stated_f, stated_g = APPROXIMANT_ERRORS[pressure][approximant]
    assert np.max(np.abs(fa / f - 1)) == pytest.approx(stated_f, abs=2e-3)
    assert np.max(np.abs(ga / g - 1)) == pytest.approx(stated_g, abs=2e-3)


@pytest.mark.parametrize("pressure", PRESSURES)
@pytest.mark.parametrize("approximant", ["rational", "pade1", "pade2"])
def test_approximants_take_the_exact_limits(pressure, approximant):
    lim = PATCH_LIMITS[pressure]
    f0, g0 = patch_resultant(np.array([1e-9]), pressure, approximant=approximant)
    f1, g1 = patch_resultant(np.array([1e9]), pressure, approximant=approximant)
    assert f0[0] / 1e-9 == pytest.approx(lim.slip_slope, rel=1e-8)
    assert g0[0] == pytest.approx(lim.spin_couple, rel=1e-8)
    assert f1[0] == pytest.approx(1.0, rel=1e-8)
    assert g1[0] * 1e9 == pytest.approx(lim.couple_slope, rel=1e-8)


def test_stored_rational_coefficients_are_what_the_minimax_fit_produces():
    """Their provenance: the linear programme of ``_fit_rational`` (private: how the table was made)."""
    from phasekit.friction.patch import RATIONAL_COEFFICIENTS, _fit_rational

    coefficients, errors = _fit_rational("uniform")
    assert errors[0] <= APPROXIMANT_ERRORS["uniform"]["rational"][0]
    assert errors[1] <= APPROXIMANT_ERRORS["uniform"]["rational"][1]
    for fitted, stored in zip(coefficients, RATIONAL_COEFFICIENTS["uniform"]):
        np.testing.assert_allclose(fitted, stored, atol=1e-6)


@pytest.fixture(scope="module")
def casadi_law():
    v, w, a = ca.SX.sym("v", 2), ca.SX.sym("w"), ca.SX.sym("a")
    out = {}
    for pressure in PRESSURES:
        for approximant in ("rational", "pade1", "pade2"):
            F, M = patch_friction(v, w, 0.4, 2.0, a, pressure=pressure, approximant=approximant)
            out[pressure, approximant] = ca.Function("patch", [v, w, a], [F, M, ca.jacobian(F, v)])
    return out


@pytest.mark.parametrize("pressure", PRESSURES)
@pytest.mark.parametrize("approximant", ["rational", "pade1", "pade2"])
def test_casadi_expressions_give_the_approximant_along_minus_v_and_against_the_spin(pressure, approximant,
                                                                                    casadi_law):
    rng = np.random.default_rng(7)
    for _ in range(20):
        speed, angle, a = 10 ** rng.uniform(-3, 1), rng.uniform(0, 2 * np.pi), 10 ** rng.uniform(-3, -1)
        omega = rng.choice([-1, 1]) * 10 ** rng.uniform(-2, 2)
        v = speed * np.array([np.cos(angle), np.sin(angle)])
        F, M, _ = casadi_law[pressure, approximant](v, omega, a)
        f, g = patch_resultant(np.array([speed / (a * abs(omega))]), pressure, approximant=approximant)
        np.testing.assert_allclose(np.asarray(F).ravel(), -0.4 * 2.0 * f[0] * v / speed, rtol=1e-11)
        assert float(M) == pytest.approx(-0.4 * 2.0 * a * g[0] * np.sign(omega), rel=1e-11)


@pytest.mark.parametrize("pressure", PRESSURES)
def test_casadi_force_is_linear_in_slip_near_pure_spin_and_couple_linear_in_spin_near_pure_slip(pressure, casadi_law):
    fun, lim = casadi_law[pressure, "rational"], PATCH_LIMITS[pressure]
    a, omega = 0.01, 3.0
    for speed in (1e-7, 2e-7):
        F, _, _ = fun([speed, 0.0], omega, a)
        assert float(F[0]) / speed == pytest.approx(-0.8 * lim.slip_slope / (a * omega), rel=1e-8)
    for omega in (1e-6, 2e-6):
        _, M, _ = fun([0.5, 0.0], omega, a)
        assert float(M) / omega == pytest.approx(-0.8 * a * a * lim.couple_slope / 0.5, rel=1e-8)


def test_casadi_law_at_rest_is_a_finite_steep_viscous_law():
    """At v = omega = 0 the floor (1e-9) stands for the set-valued law: F = 0 with a finite Jacobian
    -mu R phi(0)/floor, phi(0) = f(1)/sin(pi/4) = sqrt 2 8/(3 pi) for uniform pressure."""
    v, w = ca.SX.sym("v", 2), ca.SX.sym("w")
    F, M = patch_friction(v, w, 0.4, 2.0, 0.01)
    fun = ca.Function("rest", [v, w], [F, M, ca.jacobian(F, v)])
    F0, M0, J0 = fun([0.0, 0.0], 0.0)
    assert np.all(np.asarray(F0) == 0) and float(M0) == 0.0
    phi0 = math.sqrt(2) * 8 / (3 * math.pi)
    np.testing.assert_allclose(np.asarray(J0), -0.8 * phi0 / 1e-9 * np.eye(2), rtol=1e-5)


# ----------------------------------------------------------------------------------------------
# Hertz contact and the radii of curvature


def test_hertz_radius_of_a_steel_ball_on_glass_matches_the_hand_calculation():
    """10 mm steel ball (210 GPa, 0.30) on soda-lime glass (72 GPa, 0.23) under 1 N, by hand:
    (1 - 0.09)/210e9 = 4.3333e-12, (1 - 0.0529)/72e9 = 1.31542e-11, E* = 1/1.74875e-11 = 57.184 GPa;
    a^3 = 3 * 1 * 0.01/(4 * 57.184e9) = 1.31157e-13 m^3, a = 50.808 um."""
    assert effective_modulus(210e9, 0.30, 72e9, 0.23) == pytest.approx(57.184e9, rel=1e-4)
    assert hertz_radius(1.0, 210e9, 0.30, 72e9, 0.23, 0.01, 0.01) == pytest.approx(50.808e-6, rel=1e-4)


def test_hertz_radius_grows_as_the_cube_root_of_load_and_radius():
    a1 = hertz_radius(1.0, 210e9, 0.3, 72e9, 0.23, 0.01, 0.01)
    a8 = hertz_radius(8.0, 210e9, 0.3, 72e9, 0.23, 0.01, 0.01)
    a27 = hertz_radius(1.0, 210e9, 0.3, 72e9, 0.23, 0.27, 0.27)
    assert (a8 / a1, a27 / a1) == (pytest.approx(2.0, rel=1e-12), pytest.approx(3.0, rel=1e-12))


def _gap_curvatures(a, b, p0, E_star, n=400):
    """(A, B) of the surface displacement under p0 sqrt(1 - x^2/a^2 - y^2/b^2), from
    u = (1/(pi E*)) int p/|r - r0| dA at (0, 0), (a/2, 0), (0, b/2): Hertz's condition is
    u = delta - A x^2 - B y^2 inside the ellipse."""
    xg, wg = leggauss(60)
    w, ww = (xg + 1) / 2, wg / 2

    def u(x0, y0):
        phi = (np.arange(n) + 0.5) * 2 * np.pi / n
        c, s = np.cos(phi), np.sin(phi)
        gam, bet = (c / a) ** 2 + (s / b) ** 2, x0 * c / a**2 + y0 * s / b**2
        al = x0**2 / a**2 + y0**2 / b**2 - 1
        far = (-bet + np.sqrt(bet**2 - gam * al)) / gam
        t = far[:, None] * (1 - w**2)
        inner = np.sqrt(gam[:, None] * (t + far[:, None] + 2 * (bet / gam)[:, None])) * np.sqrt(far)[:, None] * w
        return p0 * (inner * 2 * far[:, None] * w * ww).sum() * 2 * np.pi / n / (np.pi * E_star)

    u0 = u(0.0, 0.0)
    return (u0 - u(a / 2, 0.0)) / (a / 2) ** 2, (u0 - u(0.0, b / 2)) / (b / 2) ** 2


@pytest.mark.parametrize("rho1, rho2", [(0.04, 0.01), (0.01, 0.1)])
def test_exact_hertz_ellipse_reproduces_the_gap_it_was_solved_for(rho1, rho2):
    a, b = hertz_ellipse(1.0, 210e9, 0.3, 72e9, 0.23, rho1, rho2)
    E_star = effective_modulus(210e9, 0.3, 72e9, 0.23)
    A, B = _gap_curvatures(a, b, 3 * 1.0 / (2 * np.pi * a * b), E_star)
    assert A == pytest.approx(1 / (2 * max(rho1, rho2)), rel=1e-9)
    assert B == pytest.approx(1 / (2 * min(rho1, rho2)), rel=1e-9)
    ratio = max(rho1, rho2) / min(rho1, rho2)
    assert b / a == pytest.approx(ratio ** (-2 / 3), rel=0.04)  # Johnson's approximation of the aspect


def test_hertz_ellipse_of_equal_radii_is_the_circle_of_hertz_radius():
    a, b = hertz_ellipse(2.0, 110e9, 0.33, 9e9, 0.3, 0.02, 0.02)
    assert a == b == pytest.approx(hertz_radius(2.0, 110e9, 0.33, 9e9, 0.3, 0.02, 0.02), rel=1e-14)
    a, b = hertz_ellipse(2.0, 110e9, 0.33, 9e9, 0.3, 0.02, 0.02 * (1 + 1e-6))  # nearly a circle: the root
    assert b / a == pytest.approx(1.0, abs=1e-5)


@pytest.mark.parametrize("theta", [0.0, 0.3, np.pi / 2, 2.5, np.pi])
def test_principal_radii_of_an_eccentric_sphere_are_its_radius(theta):
    radius, off = 2.0, 0.5  # h = radius - off cos(theta): G off the centre along the axis
    h, h_t, h_tt = radius - off * np.cos(theta), off * np.sin(theta), off * np.cos(theta)
    assert principal_radii(h, h_t, h_tt, theta) == (pytest.approx(radius, rel=1e-14), pytest.approx(radius, rel=1e-14))


@pytest.mark.parametrize("A, C", [(1.0, 2.0), (1.5, 0.5)])
def test_principal_radii_of_an_ellipsoid_of_revolution_match_its_curvatures(A, C):
    """Semi-axes A (equator), C (axis): h = sqrt(C^2 cos^2 + A^2 sin^2), h_t = (A^2 - C^2) sin cos/h,
    h_tt = ((A^2 - C^2) cos 2theta - h_t^2)/h by hand; the closed forms are the ellipsoid's meridional
    radius A^2 C^2/q^3 and normal section A^2/q, q = sqrt(A^2 sin^2 + C^2 cos^2)."""
    theta = np.linspace(0.0, np.pi, 37)
    s, c = np.sin(theta), np.cos(theta)
    h = np.sqrt(C * C * c * c + A * A * s * s)
    h_t = (A * A - C * C) * s * c / h
    h_tt = ((A * A - C * C) * np.cos(2 * theta) - h_t**2) / h
    rho1, rho2 = principal_radii(h, h_t, h_tt, theta)
    q = np.sqrt(A * A * s * s + C * C * c * c)
    np.testing.assert_allclose(rho1, A * A * C * C / q**3, rtol=1e-13)
    np.testing.assert_allclose(rho2, A * A / q, rtol=1e-13)


def test_every_material_is_in_range_and_names_its_source():
    assert {"steel", "glass", "brass", "eggshell", "hardwood", "laminate", "abs", "pmma", "oak"} <= set(MATERIALS)
    for m in MATERIALS.values():
        assert 1e8 < m.E < 1e12 and 0 < m.nu <= 0.5
        assert len(m.source) > 20
    assert MATERIALS["steel"].E > MATERIALS["brass"].E > MATERIALS["glass"].E > MATERIALS["pmma"].E


@pytest.mark.parametrize("call, name", [
    (lambda: patch_resultant(-0.1), "s"),
    (lambda: patch_resultant(0.5, "parabolic"), "pressure"),
    (lambda: patch_resultant(0.5, "hertz", method="closed"), "method"),
    (lambda: patch_resultant(0.5, approximant="pade3"), "approximant"),
    (lambda: patch_friction([0.1, 0.0], 1.0, 0.3, 1.0, 0.01, floor=0.0), "floor"),
    (lambda: hertz_radius(1.0, 210e9, 0.6, 72e9, 0.23, 0.01, 0.01), "nu1"),
    (lambda: hertz_radius(1.0, 210e9, 0.3, 72e9, 0.23, -0.01, 0.01), "rho1"),
])
def test_bad_input_raises_parameter_error_naming_the_argument(call, name):
    with pytest.raises(pk.ParameterError) as err:
        call()
    assert err.value.param == name
