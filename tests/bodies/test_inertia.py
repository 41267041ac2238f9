"""The moments of uniform solids of revolution and of bodies assembled from them on one axis:
each piece against its closed form and against an integration over the solid (exact:
Gauss-Legendre on polynomial integrands, and sympy's symbolic integrals), the assembly by the
parallel-axis theorem against a ball with a stem integrated as one body, and the disk's and the
cone's moments against the pieces."""

import math

import phasekit as pk
from phasekit.bodies import inertia

import numpy as np
import pytest

REL = 1e-12


def close(a, b, rel=REL):
    return abs(a - b) <= rel * max(abs(a), abs(b))


def integrate_solid(profile, z0, z1, n=12):
    """(mass, z_G, A about G, C) per unit mass of the uniform solid of revolution whose section at
    z in [z0, z1] is the disc of radius profile(z), by Gauss-Legendre over the solid in (u, z),
    r = profile(z) u: dV = 2 pi rho^2 u du dz. Exact to rounding when rho^2 is a polynomial of
    degree <= 2 (ball, cone, cylinder), as every integrand is then a polynomial of low degree."""
    x, w = np.polynomial.legendre.leggauss(n)
    u, wu = 0.5 * (x + 1.0), 0.5 * w
    z, wz = z0 + 0.5 * (z1 - z0) * (x + 1.0), 0.5 * (z1 - z0) * w
    U, Z = np.meshgrid(u, z, indexing="ij")
    rho2 = profile(Z) ** 2
    W = 2 * np.pi * rho2 * U * np.outer(wu, wz)
    R2 = rho2 * U * U
    m = W.sum()
    zG = np.sum(W * Z) / m
    return m, zG, np.sum(W * (0.5 * R2 + (Z - zG) ** 2)) / m, np.sum(W * R2) / m


def assert_solid(solid, mass, z, A, C):
    assert close(solid.mass, mass) and close(solid.A, A) and close(solid.C, C), (solid, mass, A, C)
    assert abs(solid.z - z) <= REL * max(1.0, abs(z)), (solid.z, z)


@pytest.mark.parametrize("r, L", [(1.0, 0.0), (1.0, 0.1), (0.7, 2.5), (2.0, 30.0)])
def test_a_cylinder_and_a_disk_are_the_closed_forms(r, L):
    """C = r^2/2, A = r^2/4 + L^2/12 per unit mass (a thin disk: L = 0, its mass given)."""
    s = inertia.cylinder(r, L, z=0.3, mass=None if L else 2.0)
    assert_solid(s, math.pi * r * r * L if L else 2.0, 0.3, r * r / 4 + L * L / 12, r * r / 2)
    if L:
        assert_solid(s, *integrate_solid(lambda z: r + 0 * z, 0.3 - L / 2, 0.3 + L / 2))


@pytest.mark.parametrize("r, h", [(1.0, 1.0), (1.0, 2.0), (0.6, 5.0), (1.5, -0.4)])
def test_a_cone_is_the_closed_form_about_its_centre_at_a_quarter_height(r, h):
    """C = 3 r^2/10, A = 3/20 (r^2 + h^2/4) about G at h/4 from the base (h < 0: pointing down)."""
    s = inertia.cone(r, h, base=-0.2)
    assert_solid(s, math.pi * r * r * abs(h) / 3, -0.2 + h / 4, 0.15 * (r * r + h * h / 4), 0.3 * r * r)
    lo, hi = sorted((-0.2, -0.2 + h))
    assert_solid(s, *integrate_solid(lambda z: r * (1 - (z + 0.2) / h), lo, hi))


def test_a_ball_and_a_rod_are_the_closed_forms():
    assert_solid(inertia.ball(0.8, z=1.0), 4 * math.pi * 0.8**3 / 3, 1.0, 0.4 * 0.64, 0.4 * 0.64)
    assert_solid(inertia.ball(0.8, z=1.0), *integrate_solid(lambda z: np.sqrt(np.clip(0.64 - (z - 1.0) ** 2, 0, None)),
                                                           0.2, 1.8, n=4))
    assert_solid(inertia.rod(1.2, z=-0.5, mass=0.3), 0.3, -0.5, 1.44 / 12, 0.0)


def ball_and_stem_by_sympy(L, q, stem_radius=None):
    """(M, z_G, A about G, C) of a unit ball at the origin with a stem along +k from its pole
    (z = 1 to 1 + L) of mass q times the ball's: a thin rod (its mass on the axis), or a solid
    cylinder of radius ``stem_radius``, integrated over each solid symbolically."""
    import sympy as sp

    L, q = sp.nsimplify(L), sp.nsimplify(q)
    r, z = sp.symbols("r z", real=True)
    ball = lambda f: sp.integrate(sp.integrate(f * 2 * sp.pi * r, (r, 0, sp.sqrt(1 - z**2))), (z, -1, 1))  # noqa: E731
    mb = ball(1)
    if stem_radius is None:  # a line of density lam: moments of its points on the axis
        lam = q * mb / L
        stem = lambda f: sp.integrate(lam * f.subs(r, 0), (z, 1, 1 + L))  # noqa: E731
    else:
        a = sp.nsimplify(stem_radius)
        rho = q * mb / (sp.pi * a**2 * L)
        stem = lambda f: sp.integrate(sp.integrate(rho * f * 2 * sp.pi * r, (r, 0, a)), (z, 1, 1 + L))  # noqa: E731
    M = mb + stem(sp.Integer(1))
    zG = (ball(z) + stem(z)) / M
    A = (ball(r**2 / 2 + (z - zG) ** 2) + stem(r**2 / 2 + (z - zG) ** 2)) / M
    C = (ball(r**2) + stem(r**2)) / M
    return tuple(float(sp.N(sp.simplify(v), 30)) for v in (M, zG, A, C))


@pytest.mark.parametrize("L, q, stem_radius", [(1.0, 0.1, None), (0.6, 0.05, None), (0.8, 0.2, 0.15)])
def test_a_ball_with_a_stem_is_its_integral_over_the_whole_body(L, q, stem_radius):
    """The tippe top's ball and stem: the assembly (parallel-axis theorem) against sympy's integrals
    over the body, to 1e-12."""
    pytest.importorskip("sympy")
    ball = inertia.ball(1.0)
    stem = (inertia.rod(L, z=1 + L / 2, mass=q * ball.mass) if stem_radius is None else
            inertia.cylinder(stem_radius, L, z=1 + L / 2, mass=q * ball.mass))
    assert_solid(inertia.assemble(ball, stem), *ball_and_stem_by_sympy(L, q, stem_radius))


def test_a_ball_with_a_rod_by_hand():
    """M = m (1 + q), z_G = q (1 + L/2)/(1 + q), A = [2/5 + q (L^2/12 + (1 + L/2)^2)]/(1 + q) - z_G^2,
    C = (2/5)/(1 + q): the same numbers without the library's pieces."""
    L, q = 1.0, 0.1
    ball = inertia.ball(1.0)
    top = inertia.assemble(ball, inertia.rod(L, z=1 + L / 2, mass=q * ball.mass))
    zG = q * (1 + L / 2) / (1 + q)
    assert_solid(top, ball.mass * (1 + q), zG, (0.4 + q * (L * L / 12 + (1 + L / 2) ** 2)) / (1 + q) - zG**2,
                 0.4 / (1 + q))


def test_a_cone_is_a_stack_of_thin_disks_and_a_cylinder_its_halves():
    """Assembling is additive: two halves of a cylinder are the cylinder; a cone cut into a cone and
    a frustum (the big cone less the small one, by mass) is the cone again."""
    whole = inertia.cylinder(1.0, 2.0)
    halves = inertia.assemble(inertia.cylinder(1.0, 1.0, z=-0.5), inertia.cylinder(1.0, 1.0, z=0.5))
    assert_solid(halves, whole.mass, 0.0, whole.A, whole.C)
    big, tip = inertia.cone(1.0, 2.0), inertia.cone(0.5, 1.0, base=1.0)  # the top half of the big cone
    frustum_m = big.mass - tip.mass
    fz = (big.mass * big.z - tip.mass * tip.z) / frustum_m
    fA = (big.mass * big.moments_about(fz)[0] - tip.mass * tip.moments_about(fz)[0]) / frustum_m
    fC = (big.mass * big.C - tip.mass * tip.C) / frustum_m
    assert_solid(inertia.assemble(inertia.Solid(frustum_m, fz, fA, fC), tip), big.mass, big.z, big.A, big.C)


@pytest.mark.parametrize("L", [0.0, 0.1, 0.6, 2.0, 10.0])
def test_the_disks_moments_are_the_cylinders(L):
    disk, solid = pk.Disk(L), inertia.cylinder(1.0, L, mass=1.0)
    assert close(disk.A, solid.A) and close(disk.C, solid.C)


@pytest.mark.parametrize("h", [0.01, 0.5, 2.0, 40.0])
def test_the_cones_moments_are_the_closed_form(h):
    cone = pk.bodies.Cone(h)
    assert close(cone.C, 0.3) and close(cone.A, 0.15 * (1 + h * h / 4))
    assert cone.uniform and pk.bodies.Cone(h, A=cone.A * 1.1).uniform is False


@pytest.mark.parametrize("call, name", [
    (lambda: inertia.cylinder(1.0, 0.0), "mass"), (lambda: inertia.rod(1.0, mass=-1.0), "mass"),
    (lambda: inertia.ball(-1.0), "radius"), (lambda: inertia.cone(1.0, 0.0), "height"),
    (lambda: inertia.cylinder(1.0, float("nan")), "length"), (lambda: inertia.assemble(), "solids"),
    (lambda: inertia.ball(1.0, z=float("inf")), "z"),
])
def test_bad_pieces_are_refused_naming_the_parameter(call, name):
    with pytest.raises(pk.ParameterError) as err:
        call()
    assert err.value.param == name
