"""The exports of a 3-D scene: the HTML page carries the title once, as its header, and its scene no
title geometry (the glTF, which has no 2-D text, does); the axes' tick values are round numbers
inside each range, away from the corner where the three axes meet."""

import base64
import io
import json
import re
import zipfile

import phasekit as pk
from phasekit.viz.export import CORNER_GAP, tick_values

import numpy as np
import pytest

TITLE = "Jump surface: one title"


@pytest.mark.parametrize("lo, hi", [(6.759, 31.5), (-2.978, 12.9), (0.35, np.pi / 2), (0.0, 1.221), (-0.1623, 24.65),
                                    (1e-3, 2e-3), (-5e4, 3e5), (0.0, np.pi)])
def test_tick_values_are_round_inside_the_range_and_clear_of_the_corner(lo, hi):
    v = tick_values(lo, hi)
    assert 2 <= len(v) <= 6
    assert np.all(v >= lo + CORNER_GAP * (hi - lo) - 1e-12 * (hi - lo)) and np.all(v <= hi * (1 + 1e-12) + 1e-300)
    step = np.diff(v)
    np.testing.assert_allclose(step, step[0], rtol=1e-9)
    mantissa = step[0] / 10 ** np.floor(np.log10(step[0]))
    assert min(abs(mantissa - m) for m in (1, 2, 2.5, 5, 10)) < 1e-9  # 1, 2, 2.5 or 5 times a power of ten
    np.testing.assert_allclose(v / step[0], np.round(v / step[0]), atol=1e-9)  # multiples of the step


def _scene_actors(page) -> int:
    """The actors of the vtk.js scene embedded in an exported page."""
    data = re.search(r'const base64Str = "([^"]+)"', page.read_text()).group(1)
    scene = json.loads(zipfile.ZipFile(io.BytesIO(base64.b64decode(data))).read("index.json"))["scene"]
    renderer = scene["dependencies"][0]
    return sum(1 for d in renderer["dependencies"] if "Actor" in d["type"] and "ScalarBar" not in d["type"])


@pytest.mark.render
def test_the_html_title_is_the_page_header_only_and_the_gltf_keeps_it_as_text(tmp_path):
    pytest.importorskip("trame_pyvista")
    from phasekit.viz import render_scene

    data = pk.compute_scene(pk.Scene("prolate", 1.5, values=(12.0,), resolution=20))
    for name, title in (("titled", TITLE), ("plain", None)):
        render_scene(data, tmp_path / f"{name}.png", html=tmp_path / f"{name}.html", gltf=tmp_path / f"{name}.gltf",
                     window_size=(400, 300), title=title)
    assert _scene_actors(tmp_path / "titled.html") == _scene_actors(tmp_path / "plain.html") > 10
    page = (tmp_path / "titled.html").read_text()
    body = page.split("<body>", 1)[1]
    assert body.count(TITLE) == 1 and f"<title>{TITLE}</title>" in page
    header = re.search(r'<div id="phasekit-caption"[^>]*>(.*?)</div></div>', body).group(1)
    assert header.startswith(f"<div>{TITLE}</div>")
    meshes = {name: len(json.loads((tmp_path / f"{name}.gltf").read_text())["meshes"]) for name in ("titled", "plain")}
    assert meshes["titled"] == meshes["plain"] + 1
