"""The jump surface (6.3) and the exact boundary R = 0, and the scenes computed from them: against
closed forms and simulated crossings, for built-in and user bodies; bad input is refused naming
the argument."""

import math

import phasekit as pk
from phasekit import ParameterError
from phasekit.scenes import Scene, compute_scene, exact_boundary
from phasekit.theory import surface_n

import numpy as np
import pytest

from ..helpers import UserSpheroid, raises_param

NAN, INF = float("nan"), float("inf")
B = pk.Spheroid(1.5)


def _closed_form_6_3(a, Om, th):
    """(6.3) for the uniform spheroid written out: h_t = (1 - a^2) cos sin / h."""
    A, C = (1 + a * a) / 5, 0.4
    h = np.sqrt(a * a * np.cos(th) ** 2 + np.sin(th) ** 2)
    ht = (1 - a * a) * np.cos(th) * np.sin(th) / h
    return A / C * (Om * np.cos(th) + 1 / (Om * ht * np.sin(th)))


@pytest.mark.parametrize("a", [1.5, 2 / 3])
def test_exact_boundary_at_lambda_zero_is_6_3(a):
    """Two independent routes to R = 0 (root finding on the model's (6.1), and the closed form)."""
    body = pk.Spheroid(a)
    om = np.array([8.0, 12.0, 20.0])
    th = np.array([0.4, 0.9, 1.3]) if a > 1 else np.array([0.2, 0.5, 1.0])
    OM, TH = np.meshgrid(om, th)
    np.testing.assert_allclose(exact_boundary(body, 0.1, OM, TH, 0.0), surface_n(body, OM, TH), rtol=1e-11)
    # with Lambda != 0 the boundary moves by (A/C) h_tt Lambda^2 / (Omega h_t sin)
    lam = 0.2
    h, ht, htt = body.h(TH)
    expect = surface_n(body, OM, TH) + body.A / body.C * htt * lam**2 / (OM * ht * np.sin(TH))
    np.testing.assert_allclose(exact_boundary(body, 0.1, OM, TH, lam), expect, rtol=1e-10)


def test_crossings_lie_on_the_exact_boundary_and_near_6_3():
    d = compute_scene(Scene("prolate", 1.5, values=(11.0, 15.0, 30.0), show=frozenset({"crossings"})))
    assert d.n_simulations == 3 and not d.trajectories  # crossings need no dense output
    body = pk.Spheroid(1.5)
    for c in d.crossings:
        n_exact = exact_boundary(body, 0.1, c.Omega, c.theta, c.Lambda)
        assert n_exact == pytest.approx(c.n, rel=1e-8)
        assert c.rel_error < 5e-3  # (6.3) "detects the moment of jumping very well"


def test_scene_without_trajectories_computes_none(tmp_path):
    sc = Scene("prolate", 1.5, show=frozenset({"surface", "axes", "colorbar"}), resolution=30, omega_range=(8.0, 20.0))
    d = compute_scene(sc)
    assert d.n_simulations == 0 and d.trajectories == [] and d.crossings == []
    # the drawn surface is (6.3): n = (A/C)(Omega cos + 1/(Omega h_t sin)), checked from its closed
    # form for the spheroid, h_t = (1 - a^2) cos sin / h
    OM, TH, N = d.surface
    body = pk.Spheroid(1.5)
    h = np.sqrt(1.5**2 * np.cos(TH) ** 2 + np.sin(TH) ** 2)
    ht = (1 - 1.5**2) * np.cos(TH) * np.sin(TH) / h
    np.testing.assert_allclose(N, body.A / body.C * (OM * np.cos(TH) + 1 / (OM * ht * np.sin(TH))), rtol=1e-12)


def test_scene_of_a_user_body_equals_the_built_in_one():
    show = frozenset({"surface", "crossings", "fixed_points"})
    mine = compute_scene(Scene("prolate", values=(12.0,), resolution=15, show=show, body=UserSpheroid(1.5)))
    ref = compute_scene(Scene("prolate", 1.5, values=(12.0,), resolution=15, show=show))
    np.testing.assert_allclose(mine.surface[2], ref.surface[2], rtol=1e-12)
    assert mine.crossings[0].t == pytest.approx(ref.crossings[0].t, rel=1e-10)
    with pytest.raises(pk.ParameterError, match="`branch`"):
        Scene("oblate", body=UserSpheroid(1.5))


@pytest.mark.parametrize("name, args", [
    ("theta", (12.0, NAN)),
    ("theta", (12.0, 0.0)),
    ("theta", (12.0, -0.3)),
    ("theta", (12.0, math.pi)),
    ("theta", (12.0, INF)),
    ("theta", (12.0, math.pi / 2)),  # h_theta = 0: (6.3) infinite
    ("theta", (12.0, "1.0")),
    ("theta", ([8.0, 9.0, 10.0], [1.0, 1.1])),  # shapes that do not broadcast
    ("Omega", (NAN, 1.0)),
    ("Omega", (0.0, 1.0)),
    ("Omega", ([8.0, INF], 1.0)),
    ("Omega", (None, 1.0)),
    ("Omega", (1e-320, 1.0)),  # overflows
])
def test_surface_n_rejects(name, args):
    raises_param(name, lambda: pk.theory.surface_n(B, *args))


def test_surface_n_rejects_a_non_body_and_a_sphere():
    raises_param("body", lambda: pk.theory.surface_n("spheroid", 12.0, 1.0))
    raises_param("theta", lambda: pk.theory.surface_n(pk.Spheroid(1.0), 12.0, 1.0))  # h_theta = 0 everywhere


def test_surface_n_valid_matches_closed_form():
    OM, TH = np.meshgrid([8.0, 12.0, 20.0], [0.4, 0.9, 1.3])
    np.testing.assert_allclose(pk.theory.surface_n(B, OM, TH), _closed_form_6_3(1.5, OM, TH), rtol=1e-13)
    assert float(pk.theory.surface_n(B, 12.0, 1.0)) == pytest.approx(float(_closed_form_6_3(1.5, 12.0, 1.0)), rel=1e-13)


@pytest.mark.parametrize("name, kwargs", [
    ("mu", dict(mu=NAN)),
    ("mu", dict(mu=-0.1)),
    ("theta", dict(theta=NAN)),
    ("theta", dict(theta=[0.5, 0.0])),
    ("Omega", dict(Omega=0.0)),
    ("Lambda", dict(Lambda=NAN)),
    ("Lambda", dict(Lambda="0")),
    ("friction", dict(friction="coulomb")),
    ("body", dict(body=None)),
])
def test_exact_boundary_rejects(name, kwargs):
    args = dict(body=B, mu=0.1, Omega=12.0, theta=1.0, Lambda=0.0) | kwargs
    raises_param(name, lambda: pk.scenes.exact_boundary(args.pop("body"), args.pop("mu"), args.pop("Omega"), args.pop("theta"),
                                            **args))


def test_exact_boundary_valid_is_6_3_at_lambda_zero():
    th = np.array([0.5, 1.0, 1.3])
    np.testing.assert_allclose(pk.scenes.exact_boundary(B, 0.1, 12.0, th), _closed_form_6_3(1.5, 12.0, th), rtol=1e-10)


@pytest.mark.parametrize("name, kwargs", [
    ("show", dict(show="surface")),
    ("show", dict(show=None)),
    ("values", dict(values=12.0)),
    ("values", dict(values=(12.0, NAN))),
    ("theta_range", dict(theta_range=(-1.0, 1.0))),
    ("theta_range", dict(theta_range=(0.5, 4.0))),
    ("resolution", dict(resolution=1)),
    ("mu", dict(mu=NAN)),
])
def test_scene_rejects(name, kwargs):
    raises_param(name, lambda: Scene("prolate", 1.5, **({"show": frozenset({"surface"})} | kwargs)))


def test_compute_scene_and_add_trajectory_reject():
    raises_param("scene", lambda: compute_scene("prolate"))
    raises_param("traj", lambda: Scene("prolate", 1.5, values=()).add_trajectory(None))


def test_scene_surface_unchanged_by_the_checks():
    """A box that touches theta = 0 is still drawn (the grid is not checked point by point)."""
    d = compute_scene(Scene("prolate", 1.5, values=(), show=frozenset({"surface"}), resolution=12,
                            omega_range=(8.0, 20.0), theta_range=(0.3, 1.4), n_clip=(-5.0, 40.0)))
    OM, TH, N = d.surface
    np.testing.assert_allclose(N, _closed_form_6_3(1.5, OM, TH), rtol=1e-12)


def test_scene_validation_names_the_argument():
    with pytest.raises(ParameterError, match="`dt`"):
        pk.Scene(dt=0)
    with pytest.raises(ParameterError, match="`resolution`"):
        pk.Scene(resolution=1)
    with pytest.raises(ParameterError, match="`omega_range`"):
        pk.Scene(omega_range=(20.0, 10.0))
    with pytest.raises(ParameterError, match="`branch`"):
        pk.Scene("oblate", 1.5)
    with pytest.raises(ParameterError, match="`values`"):
        pk.Scene(values=(10.0, -1.0))
    with pytest.raises(ParameterError, match="`traj`"):
        pk.Scene().add_trajectory("not a trajectory")
