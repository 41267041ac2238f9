"""VTK and PyVista are imported only to draw in 3-D: not by ``import phasekit``, ``pk.viz``, the
CLI's parameters or computing a scene."""

import subprocess
import sys


def test_viz_is_an_attribute_that_loads_no_vtk():
    """`pk.viz` after `import phasekit as pk`, lazily: neither import loads VTK or PyVista."""
    import subprocess
    import sys

    code = ("import sys, phasekit as pk; assert 'phasekit.viz' not in sys.modules; pk.viz.animate; "
            "bad = [m for m in sys.modules if m.split('.')[0] in ('vtk', 'vtkmodules', 'pyvista')]; print(bad)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


def test_pyvista_is_imported_only_to_draw_3d():
    code = (
        "import sys, phasekit, phasekit.cli.params, phasekit.viz\n"
        "from phasekit.scenes import Scene, compute_scene\n"
        "compute_scene(Scene(show=frozenset({'surface'}), resolution=20))\n"
        "print('pyvista' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.strip().splitlines()[-1] == "False", out.stderr
