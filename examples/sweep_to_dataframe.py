"""A sweep over starts to a table: 16 starts of a prolate spheroid (a = 1.5, Coulomb mu = 0.1)
on the sliding branch, Omega0 from 8 to 16, run in parallel by pk.ensemble (local processes;
pass --scheduler ADDRESS for a Dask cluster), one row per start, written as CSV, t_jump plotted.

    python examples/sweep_to_dataframe.py            # writes examples/out/sweep_to_dataframe/ (git-ignored)
    python examples/sweep_to_dataframe.py --out /tmp/sweep
"""

import argparse
from pathlib import Path

import phasekit as pk
from phasekit.viz import plot_section, pyplot, save_figure

import numpy as np

#: where the outputs go without --out (git-ignored)
DEFAULT_OUT = Path(__file__).resolve().parent / "out" / "sweep_to_dataframe"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="directory for sweep.csv and sweep.png (default: examples/out/sweep_to_dataframe)")
    ap.add_argument("--processes", type=int, default=2, help="local worker processes (default 2)")
    ap.add_argument("--scheduler", default=None, help="address of a Dask scheduler (default: local processes)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    omegas = np.linspace(8.0, 16.0, 16)
    starts = [pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=w) for w in omegas]
    rise = pk.Event("theta", 0.1, direction=-1, name="risen")  # stop: the rise is complete
    df = pk.ensemble(model, starts, 400.0, events=[rise], processes=args.processes, scheduler=args.scheduler)
    df.to_csv(out / "sweep.csv", index=False)
    print(df[["Omega", "status", "t_jump", "R_min", "stuck", "t_risen"]].to_string(index=False))

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    plot_section(ax, df[df["status"] == "jumped"], "Omega", "t_jump", label="jumped: t_jump")
    plot_section(
        ax,
        df[df["status"] == "stopped"],
        "Omega",
        "t_risen",
        marker="x",
        color="C3",
        label="rose without jumping: time theta reached 0.1",
    )
    ax.set_xlabel("Omega0 [sqrt(g/b)]")
    ax.set_ylabel("time [sqrt(b/g)]")
    ax.legend(fontsize=8)
    ax.set_title("a = 1.5, Coulomb mu = 0.1, sliding-branch starts at d = 0.01", fontsize=9)
    fig.tight_layout()
    save_figure(fig, out / "sweep.png")


if __name__ == "__main__":
    main()
