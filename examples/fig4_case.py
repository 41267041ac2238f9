"""The Fig. 4 case: a prolate spheroid (a = 1.5, mu = 0.1) rising from the horizontal with
Omega0 = 10.5, with theta(t) and the normal reaction R(t) until it jumps.

Started on the sliding branch next to the horizontal precession (theta0 = pi/2 - 0.01, n from
the gyroscopic balance), exact Coulomb friction. (The printed start (5.2) sticks under exact
Coulomb friction: see examples/paper_start_rounding.py.)

    python examples/fig4_case.py            # writes examples/out/fig4_case/ (git-ignored)
    python examples/fig4_case.py --out /tmp/fig4
"""

import argparse
from pathlib import Path

import phasekit as pk
from phasekit.viz import plot_events, plot_minima, plot_timeseries, pyplot, save_figure

import numpy as np

#: where the outputs go without --out (git-ignored)
DEFAULT_OUT = Path(__file__).resolve().parent / "out" / "fig4_case"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="directory for fig4_case.png and fig4_case.csv (default: examples/out/fig4_case)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    x0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    traj = pk.simulate(model, x0, 200.0)  # stops at the first lift-off (R = 0, dR/dt < 0)
    df = traj.sample(np.linspace(0.0, traj.t, 5000))
    df.to_csv(out / "fig4_case.csv", index=False)

    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    plot_timeseries(ax1, traj, ["theta"], lw=1)
    plot_timeseries(ax2, traj, ["R"], lw=0.6)
    plot_minima(ax2, traj, s=6)
    plot_events(ax2, traj, ["lift-off"])
    ax2.axhline(0.0, color="0.4", lw=0.5)
    fig.suptitle(f"a = 1.5, mu = 0.1, Omega0 = 10.5 (sliding-branch start): jumps at t = {traj.t_jump:.4f}")
    fig.tight_layout()
    save_figure(fig, out / "fig4_case.png")
    print(
        f"status {traj.status}, t_jump = {traj.t_jump:.6f}, "
        f"theta at the jump = {traj.at(traj.t_jump)['theta']:.4f} rad, "
        f"{len(traj.minima)} minima of R located"
    )


if __name__ == "__main__":
    main()
