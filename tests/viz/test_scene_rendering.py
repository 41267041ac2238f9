"""Rendering scenes off screen (``render_scene``): full scenes, a user's trajectory and body, the drawn
box, glTF and HTML exports; bad arguments are refused before anything is drawn or written."""

import math
import os
import subprocess
import sys
from pathlib import Path

import phasekit as pk
from phasekit.scenes import Scene, compute_scene

import numpy as np
import pytest

from ..helpers import raises_param

NAN = float("nan")


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


def test_drawn_box_holds_every_point_and_given_ranges_clip():
    """The oblate scene once drew a trajectory segment outside its axes box: the box now holds
    every drawn point, and given ranges cut the trajectories exactly at the faces."""
    from phasekit.viz.pv import inside_runs

    d = compute_scene(Scene("oblate", 2 / 3, values=(9.0, 20.0, 40.0), resolution=20,
                            show=frozenset({"trajectories", "crossings", "fixed_points", "axes"})))
    lo, hi = np.array(d.bounds[0::2]), np.array(d.bounds[1::2])
    for P in [*d.trajectories, d.fixed_points, np.array([[c.Omega, c.theta, c.n] for c in d.crossings])]:
        assert np.all((P >= lo) & (P <= hi))
    bounds = (10.0, 20.0, 0.0, 1.0, 0.0, 30.0)
    P = np.column_stack([np.linspace(5.0, 25.0, 201), np.full(201, 0.5), np.full(201, 10.0)])
    [run] = inside_runs(P, bounds)
    assert run[0, 0] == pytest.approx(10.0, abs=1e-12) and run[-1, 0] == pytest.approx(20.0, abs=1e-12)
    assert np.all((run[:, 0] >= 10.0 - 1e-12) & (run[:, 0] <= 20.0 + 1e-12))


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
                         cwd=str(Path(__file__).resolve().parents[2]), env={**os.environ, "DISPLAY": ""})
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


@pytest.fixture(scope="module")
def scene_data():
    return compute_scene(Scene("prolate", 1.5, values=(), show=frozenset({"surface", "axes"}), resolution=12))


@pytest.mark.parametrize("name, kwargs", [
    ("path", dict(path="/proc/x/a.png")),
    ("path", dict(path="{tmp}/a.txt")),
    ("path", dict(path="{tmp}")),
    ("path", dict(path=5)),
    ("window_size", dict(window_size="big")),
    ("window_size", dict(window_size=(0, -5))),
    ("window_size", dict(window_size=(300,))),
    ("window_size", dict(window_size=(300.5, 200))),
    ("window_size", dict(window_size=(100_000, 200))),
    ("camera", dict(camera="top")),
    ("camera", dict(camera=[[0, 0, 0], [0, 0, 0], [0, 0, 1]])),
    ("camera", dict(camera=[[1, 0, 0], [0, 0, 0], [1, 0, 0]])),  # view up along the line of sight
    ("camera", dict(camera=[0, 0, NAN])),
    ("camera", dict(camera=5)),
    ("title", dict(title=123)),
    ("gltf", dict(gltf="/proc/x/a.gltf")),
    ("gltf", dict(gltf="{tmp}/a.png")),
    ("gltf", dict(gltf="{tmp}/missing/a.gltf")),
    ("html", dict(html="{tmp}/a.gltf")),
    ("off_screen", dict(off_screen="yes")),
])
def test_render_scene_rejects_before_drawing(name, kwargs, tmp_path, scene_data):
    from phasekit.viz import render_scene

    kwargs = {k: v.format(tmp=tmp_path) if isinstance(v, str) else v for k, v in kwargs.items()}
    path = kwargs.pop("path", tmp_path / "x.png")
    raises_param(name, lambda: render_scene(scene_data, path, **kwargs))
    assert list(tmp_path.iterdir()) == []  # nothing written


def test_render_scene_rejects_bad_data_and_exports_without_path(tmp_path, scene_data):
    from phasekit.viz import render_scene

    raises_param("data", lambda: render_scene("scene", tmp_path / "x.png"))
    raises_param("gltf", lambda: render_scene(scene_data, None, gltf=str(tmp_path / "x.gltf")))
    err = raises_param("gltf", lambda: render_scene(scene_data, tmp_path / "x.png", gltf=str(tmp_path / "m" / "x.gltf")))
    assert isinstance(err, pk.PhasekitError)  # an unwritable target is a PhasekitError too, as before


@pytest.mark.render
def test_render_scene_valid_writes_the_asked_size(tmp_path, scene_data):
    from phasekit.viz import render_scene

    info = render_scene(scene_data, tmp_path / "new" / "s.png", window_size=(120, 90), camera="iso", title="t")
    assert info.image_shape[:2] == (90, 120) and (tmp_path / "new" / "s.png").is_file()
    assert info.bounds[:4] == (8.0, 30.0, 0.35, math.pi / 2 - 0.03)  # the prolate default box without data
