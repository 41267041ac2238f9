"""Fixed points and an unstable seed: the steady states at Omega0 = 10 of a prolate spheroid
(a = 1.5, viscous friction mu = 0.1, part I's setting), and a trajectory seeded on the
unstable manifold of the horizontal precession, whose distance from the fixed point grows at
the rate of the unstable eigenvalue.

    python examples/fixed_points.py            # writes examples/out/fixed_points/ (git-ignored)
    python examples/fixed_points.py --out /tmp/fixed
"""

import argparse
from pathlib import Path

import phasekit as pk
from phasekit.viz import pyplot, save_figure

import numpy as np

#: where the outputs go without --out (git-ignored)
DEFAULT_OUT = Path(__file__).resolve().parent / "out" / "fixed_points"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="directory for fixed_points.png (default: examples/out/fixed_points)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    body, law = pk.Spheroid(1.5), pk.Viscous(0.1)
    for fp in pk.fixed_points(pk.Model(body, law), omega0=10.0):
        print(
            f"{fp.kind:<13s} {fp.classification:<40s} residual {fp.residual:.1e}  eigenvalue max Re "
            f"{fp.eigenvalues.real.max():+.5f}"
        )

    model, x0, fp = pk.steady.unstable_manifold_start(body, law, state="horizontal", delta=1e-6, omega0=10.0)
    lam = fp.eigenvalues.real.max()
    traj = pk.simulate(model, x0, 12.0 / lam, rtol=1e-12)
    df = traj.sample(np.linspace(0.0, traj.t, 400))
    dist = np.linalg.norm(df[list(pk.core.PAPER_NAMES)].to_numpy() - fp.y, axis=1)
    rate = np.polyfit(df["t"], np.log(dist), 1)[0]
    print(f"unstable eigenvalue {lam:.6f}; growth rate of |x - x*| along the seeded trajectory {rate:.6f}")

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogy(df["t"], dist, label="|x(t) - x*| (simulated)")
    ax.semilogy(df["t"], dist[0] * np.exp(lam * df["t"]), "--", label=f"exp(lambda t), lambda = {lam:.4f}")
    ax.set_xlabel("t [sqrt(b/g)]")
    ax.set_ylabel("distance from the horizontal precession")
    ax.legend()
    ax.set_title("a = 1.5, viscous mu = 0.1, Omega0 = 10: seed 1e-6 along the unstable eigenvector", fontsize=9)
    fig.tight_layout()
    save_figure(fig, out / "fixed_points.png")


if __name__ == "__main__":
    main()
