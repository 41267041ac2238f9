"""Where a tippe top's energy goes, over time: the guide's tippe top (a ball of radius 1.5 cm, G
0.3 radii below its centre, A = 0.38, C = 0.4; exact Coulomb friction mu = 0.3) with spin
friction (mu_s = 0.005 b, 75 um) and rolling resistance (delta = 0.002 b, 30 um), spun at
30 rev/s about the vertical from theta0 = 0.1. It inverts while sliding, then the spin dies and
it comes to rest on its ball. One call of ``plot_energy`` (in ``phasekit.viz``) draws the energy
and what each mechanism has taken out so far; the table is ``traj.energy_series()``.

    python examples/energy_over_time.py            # writes examples/out/energy_over_time/ (git-ignored)
    python examples/energy_over_time.py --out /tmp/energy
"""

import argparse
from pathlib import Path

import phasekit as pk
from phasekit.core import to_chart, vertical_spin_start
from phasekit.viz import plot_energy, pyplot, save_figure

#: where the outputs go without --out (git-ignored)
DEFAULT_OUT = Path(__file__).resolve().parent / "out" / "energy_over_time"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="directory for energy_over_time.png and .csv (default: examples/out/energy_over_time)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    top = pk.EccentricSphere(0.3, A=0.38, C=0.4)
    scale = pk.Scale("1.5 cm")
    law = pk.Coulomb(0.3).with_dissipation(pk.SpinFriction(0.005), pk.RollingResistance(0.002))
    model = pk.Model(top, law, "vector")  # the vector chart is regular at theta = 0 and pi
    x0 = to_chart("vector", vertical_spin_start(0.1, scale.dimensionless("30 rev/s")))
    traj = pk.simulate(model, x0, 1e5, stop_at="rest", max_wall=300.0)
    traj.energy_series().to_csv(out / "energy_over_time.csv", index=False)

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 4.5))
    plot_energy(traj, ax=ax)
    seconds = scale.quantity(traj.t, "time").to("s").magnitude
    ax.set_title(f"Tippe top spun at 30 rev/s (ball 1.5 cm): at rest after t = {traj.t:.0f} ({seconds:.1f} s)",
                 fontsize=10)
    fig.tight_layout()
    save_figure(fig, out / "energy_over_time.png")

    b = traj.energy_budget()
    shares = ", ".join(f"{name} {d / b.lost:.1%}" for name, d in zip(b.laws, b.dissipated))
    print(f"status {traj.status}, t = {traj.t:.2f} ({seconds:.1f} s); energy {b.energy_start:.4f} -> {b.energy_end:.4f}"
          f" M g b; lost to {shares}; at events {b.at_events:.1e}; |residual| <= {b.residual_max:.1e}")


if __name__ == "__main__":
    main()
