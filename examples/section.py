"""A Poincare section: every upward crossing of Lambda = dtheta/dt = 0 (a minimum of theta in
each nutation) along the rise of a prolate spheroid (a = 1.5, Coulomb mu = 0.1, Omega0 = 10.5,
sliding-branch start), as a table with the state and R at each crossing.

    python examples/section.py            # writes examples/out/section/ (git-ignored)
    python examples/section.py --out /tmp/section
"""

import argparse
from pathlib import Path

import phasekit as pk
from phasekit.viz import plot_section, pyplot, save_figure

import numpy as np

#: where the outputs go without --out (git-ignored)
DEFAULT_OUT = Path(__file__).resolve().parent / "out" / "section"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="directory for section.csv and section.png (default: examples/out/section)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    x0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    df, traj = pk.core.poincare(model, x0, 200.0, on="Lambda", value=0.0, direction=+1, return_trajectory=True)
    df.to_csv(out / "section.csv", index=False)
    print(
        f"{len(df)} crossings of Lambda = 0 (upward) until the run ended ({traj.status}, t = {traj.t:.3f});"
        f" max |Lambda| at them {df['Lambda'].abs().max():.1e}"
    )
    print(df[["t", "theta", "Omega", "n", "R"]].tail(5).to_string(index=False))

    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    df = df[df["t"] > 0]  # the start lies on the section too (Lambda = 0, rising): not drawn
    art = plot_section(ax1, df, "theta", "Omega", c="t", cmap="viridis")
    fig.colorbar(art, ax=ax1, label="t [sqrt(b/g)]")
    plot_section(ax2, df, "t", "R")
    ax2.axhline(0.0, color="0.4", lw=0.5)
    fig.suptitle(
        "Section Lambda = 0 (upward) of a = 1.5, Omega0 = 10.5: the minima of theta in each nutation", fontsize=10
    )
    fig.tight_layout()
    save_figure(fig, out / "section.png")


if __name__ == "__main__":
    main()
