"""The moving body as a movie: a prolate spheroid (a = 1.5, Coulomb mu = 0.1, Omega0 = 11) rising
from the horizontal until it jumps, flies and lands (restitution 0.5), drawn from its pose
(psi, phi, X, Y: the azimuth of the axis, the spin about it and where G is) with the contact
point's path on the table and R(t) beside it; and a film strip of the same run.

    python examples/animate_body.py            # writes examples/out/animate_body/ (git-ignored)
    python examples/animate_body.py --out /tmp/movie [--mp4]

The flight lasts about 0.03 sqrt(b/g) with a gap of ~1e-7 b: the last frames zoom into it and
draw the gap a million times larger (printed on those frames).
"""

import argparse
from pathlib import Path

import phasekit as pk
from phasekit.viz import animate, film_strip

import numpy as np

#: where the outputs go without --out (git-ignored)
DEFAULT_OUT = Path(__file__).resolve().parent / "out" / "animate_body"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="directory for rise.gif, landing.gif and strip.png (default: examples/out/animate_body)")
    ap.add_argument("--mp4", action="store_true", help="also write rise.mp4 (needs pip install 'phasekit[movie]')")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    x0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0)
    # through the first flight and the bounces after it (the run stops a little after landing)
    traj = pk.simulate(model, x0, 42.5, stop_at="none", restitution=0.5)
    lift = traj.events_named("lift-off")[0]
    print(f"{traj.status.value} at t = {traj.t:.4f}; first lift-off at t = {lift.t:.6f}, "
          f"{len(traj.events_named('touchdown'))} touchdowns")
    sc = pk.Scale("21.5 mm")  # a body of the size of an egg, to read the clock in ms
    a = animate(traj, out / "rise.gif", frames=32, window_size=(320, 240), panel="R", scale=sc, progress=False,
                title="a = 1.5, mu = 0.1, Omega0 = 11: the rise")
    land = traj.events_named("touchdown")[0]
    b = animate(traj, out / "landing.gif", frames=16, t_span=(lift.t - 0.01, land.t + 0.01), window_size=(320, 240),
                gap_scale=1e6, scale=sc, progress=False, title="the first flight (gap drawn larger)")
    s = film_strip(traj, out / "strip.png", frames=5, window_size=(300, 240), title="a = 1.5, mu = 0.1, Omega0 = 11")
    for info in (a, b, s):
        print(f"wrote {info.path}: {info.n_frames} frames, {info.bytes / 1e3:.0f} kB")
    if args.mp4:
        m = animate(traj, out / "rise.mp4", frames=96, scale=sc, panel="R", progress=False)
        print(f"wrote {m.path}: {m.n_frames} frames, {m.bytes / 1e3:.0f} kB")


if __name__ == "__main__":
    main()
