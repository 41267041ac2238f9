"""Drawing the body: its mesh is the support function's surface; GIF, MP4 and film strips of a
run, through the API and the CLI, turn it by its pose; scenes draw it on its trajectory."""

import phasekit as pk
from phasekit.core import pose
from phasekit.viz.mesh import BODY_COLORS

import numpy as np
import pytest
from PIL import Image

from ..helpers import run_cli, strict_json

pytestmark = pytest.mark.render
SMALL = (240, 180)


@pytest.fixture(scope="module")
def jump_run():
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    return pk.simulate(model, pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 60.0, stop_at="touchdown")


def _body_pixels(img: np.ndarray, width: int) -> int:
    """Pixels of the 3-D view (left ``width`` columns) of the body's warm hue: both sector
    colours (BODY_COLORS, orange and light orange) under any shading, and nothing else drawn
    (grey table, blue path, black text)."""
    assert all(int(c[1:3], 16) - int(c[5:7], 16) > 80 for c in BODY_COLORS)
    view = img[:, :width, :3].astype(int)
    return int(np.sum((view[..., 0] - view[..., 2] > 50) & (view[..., 0] > 80)))


def _gif_frames(path) -> list[np.ndarray]:
    im = Image.open(path)
    out = []
    for k in range(im.n_frames):
        im.seek(k)
        out.append(np.asarray(im.convert("RGB")))
    return out


def test_gif_has_distinct_frames_with_the_body_in_each(jump_run, tmp_path):
    info = pk.viz.animate(jump_run, tmp_path / "x.gif", frames=24, window_size=SMALL, panel="R", gap_scale=100,
                          progress=False)
    frames = _gif_frames(tmp_path / "x.gif")
    assert len(frames) == info.n_frames == 24
    flat = [f.tobytes() for f in frames]
    assert len(set(flat)) == 24  # every frame differs (the body turns, the clock runs)
    for f in frames:
        assert _body_pixels(f, SMALL[0]) > 2000  # the body (~10^4 pixels) is drawn in every frame
    assert info.frame_size == (SMALL[0] + SMALL[1], SMALL[1])  # the panel is a square beside the view
    np.testing.assert_allclose(info.times, np.linspace(0.0, jump_run.t, 24))


def test_mp4_reads_back_with_every_frame(jump_run, tmp_path):
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")
    info = pk.viz.animate(jump_run, tmp_path / "x.mp4", frames=24, window_size=SMALL, progress=False)
    reader = imageio_ffmpeg.read_frames(str(tmp_path / "x.mp4"))
    meta = next(reader)
    frames = [np.frombuffer(f, np.uint8).reshape(meta["size"][1], meta["size"][0], 3) for f in reader]
    assert len(frames) == info.n_frames == 24
    assert all(_body_pixels(f, SMALL[0]) > 2000 for f in frames)


def test_film_strip_places_the_body_by_its_pose(jump_run, tmp_path):
    info = pk.viz.film_strip(jump_run, tmp_path / "s.png", frames=4, window_size=SMALL, title="strip")
    img = np.asarray(Image.open(tmp_path / "s.png").convert("RGB"))
    assert img.shape[1] == 4 * SMALL[0] and info.n_frames == 4
    for k in range(4):
        assert _body_pixels(img[30:, k * SMALL[0]:], SMALL[0]) > 2000


def _elongation(view: np.ndarray) -> float:
    """Ratio of the principal second moments of the body's pixels: how long it looks."""
    v = view.astype(int)
    yy, xx = np.nonzero((v[..., 0] - v[..., 2] > 50) & (v[..., 0] > 80))
    w = np.linalg.eigvalsh(np.cov(np.vstack([xx - xx.mean(), yy - yy.mean()])))
    return float(w[1] / w[0])


def test_film_strip_turns_the_body_with_its_azimuth(jump_run, tmp_path):
    """Seen by a fixed camera, the prolate body looks end-on and then broadside a quarter turn of
    psi later: the drawing follows the pose, not just the trajectory."""
    ts = np.linspace(1.0, 5.0, 400)
    psi = jump_run.pose(ts)["psi"].to_numpy()
    t2 = ts[np.argmin(np.abs(psi - psi[0] - np.pi / 2))]
    pk.viz.film_strip(jump_run, tmp_path / "q.png", times=[ts[0], t2], window_size=(320, 240), camera="fixed")
    img = np.asarray(Image.open(tmp_path / "q.png").convert("RGB"))
    first, second = _elongation(img[30:, :320]), _elongation(img[30:, 320:640])
    assert max(first, second) > 1.5 * min(first, second)


def test_body_mesh_is_the_support_function_surface():
    """The drawn surface's lowest point below G is h(theta) for every tilt: the mesh is the
    body the dynamics uses (spheroid, egg, tippe-top ball)."""
    for body in (pk.Spheroid(1.5), pk.Egg(1.3, 0.05), pk.EccentricSphere(0.3)):
        pts = pk.viz.body_mesh(body, n_theta=181, n_azimuth=180).points
        for th in (0.0, 0.7, np.pi / 2, 2.5):
            R = pose.rotation_matrix(0.0, th, 0.0)
            low = -(pts @ R.T)[:, 2].max(), -(pts @ R.T)[:, 2].min()
            assert abs(low[1] - body.h(th)[0]) < 2e-4 * body.h(th)[0]


def test_cli_animate_writes_the_movie(tmp_path):
    out = tmp_path / "c.gif"
    code, text, err = run_cli("animate", out, "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963",
                              "--omega0", "11", "--stop-at", "touchdown", "--frames", "24", "--window-size", "160",
                              "120", "--json", "--no-progress")
    assert code == 0, err
    d = strict_json(text)
    assert d["status"] == "touchdown" and d["animation"]["frames"] == 24
    frames = _gif_frames(out)
    assert len(frames) == 24 and len({f.tobytes() for f in frames}) == 24
    assert all(_body_pixels(f, 160) > 800 for f in frames)


@pytest.mark.parametrize("args, flag", [
    (["x.avi"], "OUT"), (["x.gif", "--frames", "0"], "--frames"), (["x.gif", "--gap-scale", "0.5"], "--gap-scale"),
    (["x.gif", "--camera", "top"], "--camera"), (["x.gif", "--panel", "Q"], "--panel"),
    (["x.gif", "--timing", "real"], "--timing"), (["x.gif", "--window-size", "8", "8"], "--window-size"),
])
def test_cli_animate_bad_options_are_named_before_simulating(args, flag, tmp_path):
    code, text, err = run_cli("animate", tmp_path / args[0], *args[1:], "--a", "1.5", "--mu", "0.1", "--gyroscopic",
                              "--theta0", "1.56", "--omega0", "11", "--json")
    d = strict_json(text)
    assert code == 2 and d["status"] == "error" and d["parameter"] == flag and err.count("\n") == 1


def test_scene_draws_the_body_on_its_trajectory(jump_run, tmp_path):
    """pk.Scene draws the body itself at chosen times of a trajectory, turned by its pose."""
    from phasekit.viz import render_scene

    scene = pk.Scene("prolate", 1.5, values=(), show=frozenset({"trajectories", "axes"}))
    scene.add_trajectory(jump_run, bodies=[5.0, 25.0, 40.0])
    plain = pk.Scene("prolate", 1.5, values=(), show=frozenset({"trajectories", "axes"})).add_trajectory(jump_run)
    info = render_scene(scene, tmp_path / "b.png", window_size=(500, 400))
    render_scene(plain, tmp_path / "p.png", window_size=(500, 400))
    assert info.n_points["bodies"] == 3
    with_bodies = np.asarray(Image.open(tmp_path / "b.png").convert("RGB"))
    without = np.asarray(Image.open(tmp_path / "p.png").convert("RGB"))
    assert _body_pixels(with_bodies, 500) > _body_pixels(without, 500) + 300
    with pytest.raises(pk.ParameterError, match="`bodies`"):
        scene.add_trajectory(jump_run, bodies=[jump_run.t + 1.0])


def test_cli_animate_without_pyvista_names_bad_inputs_first_then_refuses_before_simulating(monkeypatch, tmp_path):
    """Without the [viz] extra: a bad input is still named (exit 2); valid inputs end in one line
    naming the extra (exit 1) before anything is simulated."""
    import importlib.util

    from phasekit.cli import params

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "pyvista" else real(name, *a))
    ran = []
    monkeypatch.setattr(params, "run_start", lambda **kw: ran.append(kw))
    start = ["--mu", "0.1", "--gyroscopic", "--theta0", "1.56", "--omega0", "11", "--json"]
    code, text, err = run_cli("animate", tmp_path / "x.gif", "--a", "-1", *start)
    assert code == 2 and strict_json(text)["parameter"] == "--a"
    code, text, err = run_cli("animate", tmp_path / "x.gif", "--a", "1.5", *start)
    assert code == 1 and err.count("\n") == 1 and 'pip install "phasekit[viz]"' in err and ran == []
