"""Issue 8: the jump surface (6.3), the exact boundary, scenes and off-screen rendering."""

import subprocess
import sys

import numpy as np
import pytest

import phasekit as pk
from phasekit.surface import Scene, compute_scene, exact_boundary, surface_n


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


@pytest.mark.render
def test_offscreen_render_of_a_full_scene(tmp_path):
    from phasekit.viz import render_scene

    sc = Scene("prolate", 1.5, values=(12.0, 20.0), resolution=40, omega_range=(8.0, 22.0),
               show=frozenset({"surface", "exact_boundary", "trajectories", "crossings", "fixed_points", "axes", "colorbar"}))
    d = compute_scene(sc)
    info = render_scene(d, tmp_path / "scene.png", window_size=(500, 400))
    assert (tmp_path / "scene.png").stat().st_size > 10_000
    assert info.image_shape == (400, 500, 3) and info.image_std > 10  # not blank
    assert info.n_points["crossings"] == 2 and info.n_points["fixed_points"] == 2
    assert info.n_points["trajectories"] > 100 and info.n_points["surface"] > 100
    # a surface-only scene draws only the surface
    d2 = compute_scene(Scene("prolate", 1.5, show=frozenset({"surface"}), resolution=30))
    info2 = render_scene(d2, tmp_path / "surface.png", window_size=(300, 200))
    assert set(info2.n_points) == {"surface"} and info2.image_std > 5


def test_pyvista_is_imported_only_to_draw_3d():
    code = (
        "import sys, phasekit, phasekit.api, phasekit.viz\n"
        "from phasekit.surface import Scene, compute_scene\n"
        "compute_scene(Scene(show=frozenset({'surface'}), resolution=20))\n"
        "print('pyvista' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.strip().splitlines()[-1] == "False", out.stderr
