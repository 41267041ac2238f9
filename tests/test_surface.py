"""Issue 8: the jump surface (6.3), the exact boundary, scenes and off-screen rendering."""

import os
import subprocess
import sys
from pathlib import Path

import phasekit as pk
from phasekit.theory.jump_surface import exact_boundary, surface_n
from phasekit.theory.surface import Scene, compute_scene

import numpy as np
import pytest

from .helpers import UserSpheroid


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
        "import sys, phasekit, phasekit.cli.params, phasekit.viz\n"
        "from phasekit.theory.surface import Scene, compute_scene\n"
        "compute_scene(Scene(show=frozenset({'surface'}), resolution=20))\n"
        "print('pyvista' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.strip().splitlines()[-1] == "False", out.stderr


# -- issue 18: scenes of any body, law and trajectory; the render fixes -------------------------


def test_drawn_box_holds_every_point_and_given_ranges_clip():
    """The oblate scene once drew a trajectory segment outside its axes box: the box now holds
    every drawn point, and given ranges cut the trajectories exactly at the faces."""
    from phasekit.viz.pv import _inside_runs

    d = compute_scene(Scene("oblate", 2 / 3, values=(9.0, 20.0, 40.0), resolution=20,
                            show=frozenset({"trajectories", "crossings", "fixed_points", "axes"})))
    lo, hi = np.array(d.bounds[0::2]), np.array(d.bounds[1::2])
    for P in [*d.trajectories, d.fixed_points, np.array([[c.Omega, c.theta, c.n] for c in d.crossings])]:
        assert np.all((P >= lo) & (P <= hi))
    bounds = (10.0, 20.0, 0.0, 1.0, 0.0, 30.0)
    P = np.column_stack([np.linspace(5.0, 25.0, 201), np.full(201, 0.5), np.full(201, 10.0)])
    [run] = _inside_runs(P, bounds)
    assert run[0, 0] == pytest.approx(10.0, abs=1e-12) and run[-1, 0] == pytest.approx(20.0, abs=1e-12)
    assert np.all((run[:, 0] >= 10.0 - 1e-12) & (run[:, 0] <= 20.0 + 1e-12))


def test_scene_of_a_user_body_equals_the_built_in_one():
    show = frozenset({"surface", "crossings", "fixed_points"})
    mine = compute_scene(Scene("prolate", values=(12.0,), resolution=15, show=show, body=UserSpheroid(1.5)))
    ref = compute_scene(Scene("prolate", 1.5, values=(12.0,), resolution=15, show=show))
    np.testing.assert_allclose(mine.surface[2], ref.surface[2], rtol=1e-12)
    assert mine.crossings[0].t == pytest.approx(ref.crossings[0].t, rel=1e-10)
    with pytest.raises(pk.ParameterError, match="`branch`"):
        Scene("oblate", body=UserSpheroid(1.5))


@pytest.mark.render
def test_render_own_trajectory_quietly_with_title_margin_and_gltf_axes(tmp_path):
    """A user's trajectory (own law) in a scene of a user body; no VTK/X warning on stderr; the
    title's first row of pixels is below the top margin; the glTF carries the axes."""
    import json

    code = f"""
import numpy as np, phasekit as pk, casadi as ca
from phasekit.viz import render_scene
from tests.helpers import UserSpheroid
body = UserSpheroid(1.5)
law = pk.RegularisedCoulomb(0.1, 1e-3)
traj = pk.simulate(pk.Model(body, law), pk.gyroscopic_start(body, 1.5, omega0=12.0), 200.0)
sc = pk.Scene("prolate", values=(), body=body, friction=law, resolution=20,
              show=frozenset({{"surface", "trajectories", "crossings", "axes"}})).add_trajectory(traj)
info = render_scene(sc, r"{tmp_path / 'own.png'}", window_size=(500, 400), title="TITLE",
                    gltf=r"{tmp_path / 'own.gltf'}")
print(info.n_points["trajectories"], info.n_points["crossings"], traj.t_jump is not None)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                         cwd=str(Path(__file__).resolve().parents[1]), env={**os.environ, "DISPLAY": ""})
    assert out.returncode == 0, out.stderr
    assert out.stderr.strip() == ""  # no 'bad X server connection', no VTK warning
    n_traj, n_cross, jumped = out.stdout.split()
    assert int(n_traj) > 100 and int(n_cross) == 1 and jumped == "True"
    from PIL import Image

    img = np.asarray(Image.open(tmp_path / "own.png").convert("L"))
    dark_rows = np.flatnonzero((img < 128).any(axis=1))
    assert dark_rows[0] >= 8  # the title does not touch the top edge
    doc = json.loads((tmp_path / "own.gltf").read_text())
    assert [a["unit"] for a in doc["asset"]["extras"]["phasekit_axes"]] == ["sqrt(g/b)", "rad", "sqrt(g/b)"]


@pytest.mark.render
def test_render_without_a_path_returns_the_plotter_and_exports_fail_early(tmp_path):
    from phasekit.viz import render_scene

    import pyvista as pv

    d = compute_scene(Scene("prolate", 1.5, show=frozenset({"surface", "axes"}), resolution=15))
    pl = render_scene(d, off_screen=True, window_size=(300, 200))
    try:
        assert isinstance(pl, pv.Plotter) and len(pl.renderer.actors) >= 1
    finally:
        pl.close()
    with pytest.raises(pk.PhasekitError, match="cannot write the gltf export"):
        render_scene(d, tmp_path / "x.png", gltf=str(tmp_path / "missing" / "x.gltf"))
    assert not (tmp_path / "x.png").exists()
