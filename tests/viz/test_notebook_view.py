"""The 3-D view in a notebook: without ``phasekit[notebook]`` (anywidget, ipywidgets, trame-pyvista)
a plotter of ``render_scene`` shows a static image, where pyvista would pick its trame backend
whenever trame-pyvista is installed and then fail for want of anywidget; with it, the "html"
backend (nothing downloaded, unlike the trame server's start); a backend the user chose is kept; the extra installs what the check looks for. A notebook kernel is stood in for by
pyvista's own switch (``pyvista.global_theme.notebook``), which a plotter reads before asking
whether it runs in a kernel; the packages present, by ``importlib.util.find_spec``."""

import importlib.util
import re
import tomllib
from pathlib import Path

import phasekit as pk
from phasekit.viz import pv as pkpv

import numpy as np
import pytest

pytestmark = pytest.mark.render
ROOT = Path(__file__).resolve().parents[2]
pv = pytest.importorskip("pyvista")


@pytest.fixture(scope="module")
def data():
    return pk.compute_scene(pk.Scene("prolate", 1.5, values=(12.0,), resolution=20))


@pytest.fixture
def in_notebook(monkeypatch):
    monkeypatch.setattr(pv.global_theme, "_notebook", True)
    monkeypatch.setattr(pv.global_theme, "_jupyter_backend", None)


def _installed(monkeypatch, missing: set[str]):
    """find_spec as if the packages ``missing`` were not installed and the rest of NOTEBOOK_EXTRA were."""
    real = importlib.util.find_spec

    def find_spec(name, *args, **kwargs):
        if name in missing:
            return None
        if name in pkpv.NOTEBOOK_EXTRA:
            return real("json")  # any spec: the package is there
        return real(name, *args, **kwargs)

    monkeypatch.setattr(pkpv.importlib.util, "find_spec", find_spec)


@pytest.mark.parametrize("missing", [{"anywidget"}, {"ipywidgets"}, {"trame_pyvista"}, set(pkpv.NOTEBOOK_EXTRA)])
def test_without_the_notebook_extra_the_plotter_shows_a_static_image(data, in_notebook, monkeypatch, missing):
    _installed(monkeypatch, missing)
    assert pkpv.notebook_backend() == "static"
    pl = pk.viz.render_scene(data, window_size=(200, 150))
    assert pl.notebook and pl.theme.jupyter_backend == "static"
    image = pl.show(return_viewer=True)  # what the cell displays: an image made in the kernel
    assert image.size == (200, 150)
    colours = np.unique(np.asarray(image).reshape(-1, np.asarray(image).shape[-1]), axis=0)
    assert len(colours) > 10  # the scene, not a blank frame


def test_with_the_notebook_extra_the_plotter_shows_the_scene_in_the_browser(data, in_notebook, monkeypatch):
    """The "html" backend (vtk.js in the browser), not pyvista's own choice "trame", whose server
    downloads VTK's WebAssembly build when it starts."""
    _installed(monkeypatch, set())
    assert pkpv.notebook_backend() == "html"
    pl = pk.viz.render_scene(data, window_size=(200, 150))
    assert pl.notebook and pl.theme.jupyter_backend == "html"
    pl.close()


def test_a_backend_the_user_chose_is_kept(data, in_notebook, monkeypatch):
    _installed(monkeypatch, {"anywidget"})
    monkeypatch.setattr(pv.global_theme, "_jupyter_backend", "none")
    pl = pk.viz.render_scene(data, window_size=(200, 150))
    assert pl.theme.jupyter_backend == "none"
    pl.close()


def test_outside_a_notebook_the_plotter_is_left_alone(data, monkeypatch):
    monkeypatch.setattr(pv.global_theme, "_notebook", False)
    monkeypatch.setattr(pv.global_theme, "_jupyter_backend", None)
    _installed(monkeypatch, {"anywidget"})
    pl = pk.viz.render_scene(data, window_size=(200, 150), off_screen=True)
    assert not pl.notebook and pl.theme.jupyter_backend is None
    pl.close()


def test_the_notebook_extra_installs_what_the_check_looks_for():
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    names = {re.split(r"[\[<>=~! ]", req, maxsplit=1)[0].lower() for req in extras["notebook"]}
    assert {m.replace("_", "-") for m in pkpv.NOTEBOOK_EXTRA} <= names
    assert "phasekit[viz]" in extras["notebook"]
