"""The interactive HTML export opened in a real browser (headless Chromium): it renders, and
it shows the title once and the axes' true ranges, not the drawn box's 0..1.4 coordinates."""

import os
import shutil
import subprocess

import phasekit as pk

import numpy as np
import pytest

pytestmark = pytest.mark.render
#: Chromium with no network, no GPU, a fresh profile (the CI machine's flags)
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--enable-unsafe-swiftshader"]


def _chromium():
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        if os.environ.get("CI"):
            pytest.fail("CI must have Chromium (.ci/run installs the Debian packages chromium, chromium-driver)")
        pytest.skip("no Chromium on this machine (apt-get install chromium)")
    return exe


def _browser(exe, page, tmp_path, *args):
    profile = tmp_path / f"profile-{len(list(tmp_path.iterdir()))}"
    out = subprocess.run([exe, *FLAGS, f"--user-data-dir={profile}", "--virtual-time-budget=20000", *args,
                          page.as_uri()], capture_output=True, timeout=180)
    assert out.returncode == 0, out.stderr.decode(errors="replace")[-2000:]
    return out.stdout.decode(errors="replace")


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    pytest.importorskip("trame_pyvista")
    from phasekit.viz import render_scene

    tmp = tmp_path_factory.mktemp("html")
    data = pk.compute_scene(pk.Scene("prolate", 1.5, values=(12.0,), resolution=20))
    info = render_scene(data, tmp / "s.png", html=tmp / "s.html", gltf=tmp / "s.gltf", window_size=(600, 450),
                        title="Jump surface a=1.5")
    return data, info, tmp


def test_html_export_renders_with_true_ranges_in_the_browser(exported, tmp_path):
    exe = _chromium()
    data, info, tmp = exported
    page = tmp / "s.html"
    dom = _browser(exe, page, tmp_path, "--dump-dom")
    assert "<canvas" in dom  # vtk.js made its view
    lo, hi = np.array(data.bounds[0::2]), np.array(data.bounds[1::2])
    for name, a, b in zip(("Omega [sqrt(g/b)]", "theta [rad]", "n [sqrt(g/b)]"), lo, hi):
        assert f"{name}: {a:.4g} to {b:.4g}" in dom
    assert dom.split("<body", 1)[1].count("Jump surface a=1.5") == 1  # one title: the page's header
    assert hi[0] > 1.5  # the data's Omega range, not the drawn box (0 to 1.4)
    shot = tmp_path / "shot.png"
    _browser(exe, page, tmp_path, "--window-size=900,700", f"--screenshot={shot}")
    from PIL import Image

    img = np.asarray(Image.open(shot).convert("RGB")).astype(int)
    view = img[150:, :]  # below the caption: the WebGL drawing
    coloured = np.abs(view - view.mean(axis=2, keepdims=True)).sum(axis=2) > 40  # the surface's colour map
    assert coloured.sum() > 5000 and view.std() > 20


def test_exports_carry_titles_and_ranges(exported):
    import json

    data, info, tmp = exported
    text = (tmp / "s.html").read_text()
    assert "<title>Jump surface a=1.5</title>" in text
    doc = json.loads((tmp / "s.gltf").read_text())
    extras = doc["asset"]["extras"]
    assert extras["phasekit_title"] == "Jump surface a=1.5"
    ranges = [a["range"] for a in extras["phasekit_axes"]]
    np.testing.assert_allclose(np.ravel(ranges), data.bounds)
    assert "colour bar" in extras["phasekit_note"]
