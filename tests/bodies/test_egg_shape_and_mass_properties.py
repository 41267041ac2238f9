"""Egg (Hugelschaffer's curve): spheroid limit, support function, curvature, mass properties,
orientation and bad input. Reference values are computed here from Narushin's formula
y(x) = (B/2) sqrt((L^2 - 4x^2) / (L^2 + 8wx + 4w^2)) directly, not from phasekit.bodies.egg's own
parametrisation, so that the two can disagree."""


from phasekit import ParameterError
from phasekit.bodies import Egg, Spheroid
from phasekit.bodies.egg import mass_properties
from phasekit.bodies.egg_shape import W_GUARANTEED, clenshaw

import casadi as ca
import numpy as np
import pytest
from numpy.polynomial import chebyshev

# (a, w/L) covering the documented range, and one beyond W_GUARANTEED that a near 1.3 allows
EGGS = [(1.3, 0.1), (0.3, 0.08), (0.5, 0.05), (2.5, 0.08), (3.0, 0.03), (1.0, 0.2), (1.3, 0.25)]


def narushin(x, L, B, w):
    """Narushin et al. (2021) eq. (5) without the pyriform factor: the meridian radius."""
    return 0.5 * B * np.sqrt((L * L - 4 * x * x) / (L * L + 8 * w * x + 4 * w * w))


def curve(a, w_rel):
    """(L, B, w) of the curve for phasekit's (a, w/L), in units b = B/2 = 1."""
    L = 2.0 * a
    return L, 2.0, w_rel * L


def brute_force_support(theta, a, w_rel, x_G, n=1_000_001):
    """max over a fine meridian of -(x - x_G) cos(theta) + y sin(theta). The points are
    x = (L/2) sin(phi), phi uniform, dense at the tips where y(x) is steep; the grid maximum
    is within ~a (pi/n)^2 / 8 ~ 1e-12 of the true one."""
    L, B, w = curve(a, w_rel)
    x = 0.5 * L * np.sin(np.linspace(-np.pi / 2, np.pi / 2, n))
    y = narushin(x, L, B, w)
    return np.array([np.max(-(x - x_G) * np.cos(t) + y * np.sin(t)) for t in np.atleast_1d(theta)])


# -- (i) the spheroid limit --------------------------------------------------------------------
@pytest.mark.parametrize("a", [0.3, 0.5, 0.8, 1.3, 2.0, 3.0])
def test_w0_is_the_spheroid(a):
    egg, sph = Egg(a, 0.0), Spheroid(a)
    theta = np.concatenate([np.linspace(0.0, np.pi, 181), np.random.default_rng(0).uniform(0, np.pi, 50)])
    for got, want in zip(egg.h(theta), sph.h(theta)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)
    assert abs(egg.A - (1 + a * a) / 5) < 1e-12 and abs(egg.A - sph.A) < 1e-12
    assert abs(egg.C - 0.4) < 1e-12
    assert egg.x_G == 0.0 and egg.flip_symmetric
    assert abs(egg.volume - 4 * np.pi * a / 3) < 1e-12


# -- (ii) the fitted support function ----------------------------------------------------------
@pytest.mark.parametrize("a, w", EGGS)
def test_fit_matches_brute_force_maximisation(a, w):
    egg = Egg(a, w)
    theta = np.concatenate([[0.0, np.pi], np.random.default_rng(1).uniform(0, np.pi, 10)])
    h_fit = egg.h(theta)[0]
    np.testing.assert_allclose(h_fit, brute_force_support(theta, a, w, egg.x_G), rtol=0, atol=1e-10)
    assert egg.fit_error < 1e-12


@pytest.mark.parametrize("a, w", EGGS)
def test_fit_derivatives_match_direct_solve(a, w):
    """h_theta and h_thetatheta of the series against the direct Newton solve, whose own
    derivative formulas are checked against finite differences of its h."""
    egg = Egg(a, w)
    theta = np.random.default_rng(2).uniform(0.05, np.pi - 0.05, 40)
    h, h1, h2 = egg.support_direct(theta)
    for got, want in zip(egg.h(theta), (h, h1, h2)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-10)
    d = 1e-4
    hp, h1p, _ = egg.support_direct(theta + d)
    hm, h1m, _ = egg.support_direct(theta - d)
    np.testing.assert_allclose(h1, (hp - hm) / (2 * d), atol=1e-7)
    np.testing.assert_allclose(h2, (h1p - h1m) / (2 * d), atol=1e-6 * max(1.0, np.max(np.abs(h2))))


def test_symbolic_clenshaw_equals_numpy_chebval():
    coef = np.random.default_rng(3).normal(size=17)
    c, sh = ca.SX.sym("c"), ca.SX.sym("shape", coef.size)
    f = ca.Function("H", [c, sh], [clenshaw(c, sh)])
    for x in (-1.0, -0.3, 0.0, 0.71, 1.0):
        assert abs(float(f(x, coef)) - chebyshev.chebval(x, coef)) < 1e-13
    # only + - * in the expression (CasADi writes 2*x as OP_TWICE)
    ops = {f.instruction_id(k) for k in range(f.n_instructions())}
    assert ops <= {ca.OP_INPUT, ca.OP_OUTPUT, ca.OP_CONST, ca.OP_ADD, ca.OP_SUB, ca.OP_MUL, ca.OP_TWICE}


def test_height_translates_to_heyoka():
    hy = pytest.importorskip("heyoka")
    from phasekit.core.engines.translate import to_heyoka

    egg = Egg(1.3, 0.02)
    c, sh = ca.SX.sym("c"), ca.SX.sym("shape", egg.n_shape)
    H = egg.height(c, sh)
    f = ca.Function("H", [c, sh], [ca.vertcat(H, ca.jacobian(H, c))])
    x = hy.make_vars("x")
    cf = hy.cfunc(to_heyoka(f, [[x], [hy.par[i] for i in range(egg.n_shape)]])[0], vars=[x])
    cs = np.linspace(-1, 1, 7)
    got = cf(cs[None, :], pars=np.tile(np.array(egg.shape_params)[:, None], (1, cs.size)))
    want = np.array([np.asarray(f(ci, egg.shape_params)).ravel() for ci in cs]).T
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-14)
    np.testing.assert_allclose(got[0], [egg.height_slope(ci)[0] for ci in cs], rtol=0, atol=1e-14)


def test_equal_degree_shares_the_compiled_structure():
    e1, e2, e3 = Egg(1.3, 0.02), Egg(1.35, 0.03), Egg(1.3, 0.1)
    assert e1.degree == e2.degree == 64 and e3.degree == 128
    assert e1.structure_key == e2.structure_key != e3.structure_key
    assert e1 != e2 and e1 == Egg(1.3, 0.02)


# -- (iii) curvature ---------------------------------------------------------------------------
@pytest.mark.parametrize("a", [0.3, 0.7, 1.3, 2.0, 3.0])
@pytest.mark.parametrize("w", [0.0, 0.03, W_GUARANTEED])
def test_radii_of_curvature_positive_over_documented_range(a, w):
    r1, r2 = Egg(a, w).radii_of_curvature(np.linspace(0.0, np.pi, 721))
    assert np.all(r1 > 0) and np.all(r2 > 0)


@pytest.mark.parametrize("a, w", EGGS)
def test_pole_radius_equals_tip_curvature_of_the_curve(a, w):
    """Near a tip at distance s along the axis, y^2 = 2 R s + O(s^2): from the formula,
    R = B^2 L / (2 (L -+ 2w)^2) at the fat (x = -L/2) and thin (x = +L/2) tips."""
    L, B, wa = curve(a, w)
    R_fat, R_thin = B * B * L / (2 * (L - 2 * wa) ** 2), B * B * L / (2 * (L + 2 * wa) ** 2)
    s = 1e-7  # the limit y^2 / 2s, as an independent check of the two closed forms
    assert narushin(-L / 2 + s, L, B, wa) ** 2 / (2 * s) == pytest.approx(R_fat, rel=1e-5)
    assert narushin(L / 2 - s, L, B, wa) ** 2 / (2 * s) == pytest.approx(R_thin, rel=1e-5)
    egg = Egg(a, w)
    (r_fat, r_thin), (r2_fat, r2_thin) = egg.radii_of_curvature(np.array([0.0, np.pi]))
    assert r_fat == pytest.approx(R_fat, rel=1e-10) and r_thin == pytest.approx(R_thin, rel=1e-10)
    assert (r2_fat, r2_thin) == (r_fat, r_thin)


# -- (iv) mass properties ----------------------------------------------------------------------
@pytest.mark.parametrize("a, w", EGGS + [(1.3, 0.0), (2.0, 0.4)])
def test_mass_properties_against_gauss_legendre_in_phi(a, w):
    """Gauss-Legendre in phi, x = (L/2) sin(phi) (the quad in phasekit.bodies.egg works in x)."""
    from scipy.special import roots_legendre

    L, B, wa = curve(a, w)
    nodes, weights = roots_legendre(400)
    phi = 0.5 * np.pi * nodes
    x, dx = 0.5 * L * np.sin(phi), 0.5 * L * np.cos(phi) * 0.5 * np.pi * weights
    y2 = narushin(x, L, B, wa) ** 2
    V = np.pi * np.sum(y2 * dx)
    x_G = np.pi * np.sum(x * y2 * dx) / V
    C = 0.5 * np.pi * np.sum(y2 * y2 * dx) / V
    A = np.pi * np.sum(y2 * (y2 / 4 + (x - x_G) ** 2) * dx) / V
    got = mass_properties(a, w)
    np.testing.assert_allclose([got.volume, got.x_G, got.A, got.C], [V, x_G, A, C], rtol=1e-12, atol=1e-13)
    egg = Egg(a, w) if w < 0.3 else None
    if egg is not None:
        assert (egg.volume, egg.x_G, egg.A, egg.C) == (got.volume, got.x_G, got.A, got.C)


def test_mass_properties_monte_carlo():
    """A cruder, fully independent check: points uniform in the bounding cylinder."""
    a, w = 1.3, 0.1
    L, B, wa = curve(a, w)
    rng = np.random.default_rng(4)
    n = 2_000_000
    x, r2 = rng.uniform(-L / 2, L / 2, n), rng.uniform(0, 1, n)  # r^2 uniform: uniform in the disc
    inside = r2 < narushin(x, L, B, wa) ** 2
    V = np.pi * L * inside.mean()
    props = mass_properties(a, w)
    assert abs(V - props.volume) < 4 * np.pi * L * np.sqrt(0.25 / n)  # ~4 sigma
    assert abs(x[inside].mean() - props.x_G) < 4 * L / np.sqrt(12 * inside.sum())


# -- (v) asymmetry and orientation -------------------------------------------------------------
@pytest.mark.parametrize("a, w", EGGS)
def test_fat_end_is_down_at_theta0_and_lower(a, w):
    egg = Egg(a, w)
    h_fat, h_thin = egg.h(0.0)[0], egg.h(np.pi)[0]
    assert egg.x_G < 0  # G toward the fat end
    assert abs(h_fat - (a + egg.x_G)) < 1e-13 and abs(h_thin - (a - egg.x_G)) < 1e-13
    assert h_thin - h_fat > 1e-3 * w  # not flip-symmetric, fat end lower
    assert not egg.flip_symmetric
    assert (egg.lower_end(0.0), egg.lower_end(1.0), egg.lower_end(2.0), egg.lower_end(np.pi)) == (
        "fat",
        "fat",
        "thin",
        "thin",
    )


def test_fat_end_is_at_minus_k():
    """The meridian is widest at x = -w L (B/2 = 1 there) and blunter at x = -a than at +a."""
    egg = Egg(1.3, 0.1)
    x = np.linspace(-1.3, 1.3, 200001)
    y = egg.meridian(x)
    assert abs(x[np.argmax(y)] - (-0.1 * 2.6)) < 2e-5 and abs(y.max() - 1.0) < 1e-12
    assert egg.meridian(-1.3 + 0.05) > egg.meridian(1.3 - 0.05)


def test_centre_of_mass_override():
    base = Egg(1.3, 0.1)
    moved = Egg(1.3, 0.1, centre_of_mass=-0.3)
    assert moved.x_G == -0.3 and not moved.uniform and base.uniform
    assert moved.A == pytest.approx(base.A - (0.3 + base.x_G) ** 2, abs=1e-15) and moved.C == base.C
    assert moved.h(0.0)[0] == pytest.approx(1.3 - 0.3, abs=1e-13)
    np.testing.assert_allclose(moved.h(1.0)[0] - base.h(1.0)[0], (-0.3 - base.x_G) * np.cos(1.0), atol=1e-14)
    given = Egg(1.3, 0.1, A=0.7, C=0.35)
    assert (given.A, given.C, given.x_G) == (0.7, 0.35, base.x_G)


# -- (vi) bad input ----------------------------------------------------------------------------
@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"a": 0.2, "w": 0.0}, "a"),
        ({"a": 3.5, "w": 0.0}, "a"),
        ({"a": float("nan"), "w": 0.0}, "a"),
        ({"a": "1.3", "w": 0.0}, "a"),
        ({"a": 1.3, "w": -0.01}, "w"),
        ({"a": 1.3, "w": 0.5}, "w"),
        ({"a": 1.3, "w": float("inf")}, "w"),
        ({"a": 0.3, "w": 0.2}, "w"),  # convex, but beyond the degree-256 fit
        ({"a": 1.3, "w": 0.1, "A": -1.0}, "A"),
        ({"a": 1.3, "w": 0.1, "C": 0.0}, "C"),
        ({"a": 1.3, "w": 0.1, "A": 0.1, "C": 0.5}, "C"),  # violates C <= 2A
        ({"a": 1.3, "w": 0.1, "centre_of_mass": 1.3}, "centre_of_mass"),
        ({"a": 1.3, "w": 0.1, "centre_of_mass": 0.6}, "centre_of_mass"),  # default A < C/2
    ],
)
def test_bad_input_names_parameter(kwargs, name):
    with pytest.raises(ParameterError, match=f"`{name}`") as info:
        Egg(**kwargs)
    assert info.value.param == name


def test_lower_end_rejects_horizontal_axis():
    with pytest.raises(ParameterError, match="`theta`"):
        Egg.lower_end(np.pi / 2)
    with pytest.raises(ParameterError, match="`theta`"):
        Egg.lower_end(4.0)


# -- reporting and speed -----------------------------------------------------------------------
def test_to_dict_repr_describe():
    egg = Egg(1.3, 0.1)
    d = egg.to_dict()
    assert d["body"] == "egg" and (d["a"], d["w"]) == (1.3, 0.1)
    assert (d["A"], d["C"], d["x_G"]) == (egg.A, egg.C, egg.x_G) and d["fit_error"] < 1e-12
    assert d["degree"] == egg.degree == len(egg.shape_params) - 1
    assert repr(egg) == "Egg(a=1.3, w=0.1)"
    assert "fat end down at theta=0" in egg.describe()
    assert repr(Egg(1.3, 0.1, A=0.7)).startswith("Egg(a=1.3, w=0.1, A=0.7")


@pytest.mark.timeout(600)  # a hang guard: three eggs take about a second
def test_construction_builds_no_compiled_function_of_its_own():
    """What keeps making an egg fast (~0.1 s): a new egg of a degree already seen computes its own
    fit, quadrature and convexity check, and builds no CasADi function and hashes no structure."""
    from phasekit.bodies import body, egg, egg_shape

    first = Egg(1.2, 0.07)  # builds the degree's CasADi functions once
    compiled = (dict(body._THETA_FUNCS), dict(body._SLOPE_FUNCS), dict(egg._STRUCTURE_KEYS))
    fits = egg_shape.fit_support.cache_info().misses
    for k in range(3):  # new (a, w) each time: fit, quadrature and convexity check
        new = Egg(1.2345 + 0.001 * k, 0.0678)
        assert new.degree == first.degree and new.structure_key == first.structure_key
    assert egg_shape.fit_support.cache_info().misses == fits + 3  # each egg fitted its own support function
    assert (body._THETA_FUNCS, body._SLOPE_FUNCS, egg._STRUCTURE_KEYS) == compiled
