"""A jump threshold: the smallest Omega0 for which a prolate spheroid (a = 1.5, Coulomb mu = 0.1)
started on the sliding branch next to the horizontal precession jumps before it has risen.

The default definition ("sliding", d = 0.01) bisected to 1e-3 relative, searched near a guess.
Writes threshold.json (the threshold, its bracket and status) and threshold.png (every start
simulated, in the order of the search, with its outcome: the bracket closes on the threshold).

    python examples/threshold.py            # writes examples/out/threshold/ (git-ignored)
    python examples/threshold.py --out /tmp/threshold
"""

import argparse
import json
from pathlib import Path

import phasekit as pk
from phasekit.viz import pyplot, save_figure

#: where the outputs go without --out (git-ignored)
DEFAULT_OUT = Path(__file__).resolve().parent / "out" / "threshold"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="directory for threshold.json and threshold.png (default: examples/out/threshold)")
    ap.add_argument("--a", type=float, default=1.5, help="aspect ratio (default 1.5)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    defn = pk.Definition("sliding", "sliding")  # Coulomb mu = 0.1, seed on the sliding branch at d = 0.01
    th = pk.find_threshold(defn, args.a, guess=9.7 if args.a == 1.5 else None, window=1.1, n_coarse=4, tol=1e-3)
    lo, hi = th.bracket
    print(
        f"a = {args.a:g}: Omega0* = {th.value:.4f}, bracket [{lo:.5f}, {hi:.5f}], {th.status}, {th.n_sims} simulations"
    )
    for o in sorted(th.outcomes, key=lambda o: o.value):
        print(f"  Omega0 = {o.value:8.4f}: {o.how}")
    (out / "threshold.json").write_text(
        json.dumps(
            {
                "a": args.a,
                "definition": defn.label,
                "value": th.value,
                "bracket": [lo, hi],
                "status": str(th.status),
                "n_sims": th.n_sims,
            }
        )
    )

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 3.6))
    for k, o in enumerate(th.outcomes):  # in the order they were simulated
        ax.plot(o.value, k, "o" if o.jumped else "s", color="#d73027" if o.jumped else "#4575b4", ms=6,
                label=("jumped" if o.jumped else o.how) if k == next(i for i, p in enumerate(th.outcomes)
                                                                    if p.jumped == o.jumped) else None)
    ax.axvspan(lo, hi, color="0.85", label=f"bracket [{lo:.4f}, {hi:.4f}]")
    ax.set_yticks(range(len(th.outcomes)))
    ax.axvline(th.value, color="k", lw=0.8)
    ax.set(xlabel=r"$\Omega_0$ ($\sqrt{g/b}$)", ylabel="simulation, in the order of the search",
           title=f"a = {args.a:g}: jump threshold {th.value:.4f} ({th.status}, {th.n_sims} simulations)")
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    save_figure(fig, out / "threshold.png")


if __name__ == "__main__":
    main()
