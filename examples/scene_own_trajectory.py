"""A 3-D scene with one's own trajectory: the jump surface (6.3) of a prolate spheroid in
(Omega, theta, n), with a trajectory simulated here added to the scene, rendered off-screen
to a PNG (and optionally exported as glTF with its axes, or interactive HTML).

    python examples/scene_own_trajectory.py            # writes examples/out/scene_own_trajectory/ (git-ignored)
    python examples/scene_own_trajectory.py --out /tmp/scene [--gltf] [--html]

Without --out's PNG, render_scene(scene) returns the PyVista plotter: plotter.show() opens it.
"""

import argparse
import sys
from pathlib import Path

import phasekit as pk
from phasekit.viz import render_scene

#: where the outputs go without --out (git-ignored)
DEFAULT_OUT = Path(__file__).resolve().parent / "out" / "scene_own_trajectory"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="directory for scene.png (and scene.gltf / scene.html) "
                         "(default: examples/out/scene_own_trajectory)")
    ap.add_argument("--gltf", action="store_true", help="also export scene.gltf (axes and units included)")
    ap.add_argument("--html", action="store_true", help="also export scene.html (needs pip install 'phasekit[html]')")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.RegularisedCoulomb(0.1, 1e-3))
    x0 = pk.gyroscopic_start(body, 1.45, omega0=14.0)
    x0[3] = 0.02  # one's own start: off the slow manifold (a nutation kick), and one's own law
    traj = pk.simulate(model, x0, 300.0)
    scene = pk.Scene(
        "prolate",
        1.5,
        values=(10.0, 20.0),
        resolution=60,
        show=frozenset({"surface", "trajectories", "crossings", "fixed_points", "axes", "colorbar"}),
    )
    scene.add_trajectory(traj, label="own start")
    try:
        info = render_scene(
            scene,
            out / "scene.png",
            window_size=(1000, 750),
            title=f"surface (6.3), a = 1.5: two sliding-branch runs and one's own (jumps at t = {traj.t_jump:.2f})",
            gltf=str(out / "scene.gltf") if args.gltf else None,
            html=str(out / "scene.html") if args.html else None,
        )
    except pk.PhasekitError as exc:
        print(f"scene_own_trajectory: error: {exc}", file=sys.stderr)
        return 1
    print(f"wrote {info.path} and {', '.join(info.exported) or 'no export'}; points drawn {info.n_points}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
