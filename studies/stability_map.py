"""Stability of the steady states over aspect ratio and spin (part I's classes, viscous friction).

Left: the horizontal steady precession over (a, Omega0), with the criterion
(a^2 C - A) Omega0^2 = a^2 - 1 (Omega0 = sqrt 5 for the uniform spheroid). Right: the
vertical spin over (a, n0), with (a^2 C - A) n0^2 = a^3 (a^2 - 1), i.e. n0 = sqrt(5 a^3),
drawn over the computed map. Colour: the dimension of the unstable subspace
of CasADi's exact linearisation. Writes stability_map.png and prints a summary
(including how many grid points disagree with the criterion).
"""

from __future__ import annotations

import phasekit as pk
from phasekit.viz import pyplot

import numpy as np


def stability_grid(kind, a_values, s_values, mu, bar):
    out = np.zeros((len(s_values), len(a_values)), dtype=int)
    for j, a in enumerate(a_values):
        body = pk.Spheroid(a)
        m = pk.Model(body, pk.Viscous(mu), "euler" if kind == "horizontal" else "vector")
        for i, s in enumerate(s_values):
            x = pk.theory.horizontal_state(s) if kind == "horizontal" else pk.theory.vertical_state(s)
            out[i, j] = pk.linearise(m, x, kind=kind).n_unstable
        bar.update(len(s_values))
    return out


def main(argv=None) -> dict:
    st = pk.sweep.Study(__file__, __doc__, quick_help="25x25 grids instead of 80x80")
    st.parser.add_argument("--mu", type=st.parser.real(), default=0.1, help="viscous friction coefficient (default 0.1)")
    args = st.parse(argv, check=lambda args: pk.Viscous(args.mu))  # mu checked before any work (named --mu)
    plt = pyplot()
    n = 25 if args.quick else 80
    a_vals = np.linspace(0.3, 3.0, n)
    om_vals = np.linspace(0.2, 15.0, n)
    n0_vals = np.linspace(0.2, 15.0, n)
    with st.progress(total=2 * n * n, desc="linearisations") as bar:
        H = stability_grid("horizontal", a_vals, om_vals, args.mu, bar)
        V = stability_grid("vertical", a_vals, n0_vals, args.mu, bar)
    wall = st.wall
    # agreement of the vertical map with the criterion
    bodies = [pk.Spheroid(a) for a in a_vals]
    crit_v = np.array([[pk.theory.vertical_is_stable(b.A, b.C, b.a, s) for b in bodies] for s in n0_vals])
    crit_h = np.array([[pk.theory.horizontal_is_unstable(b.A, b.C, b.a, s) for b in bodies] for s in om_vals])
    disagree = int(np.sum(crit_v != (V == 0))) + int(np.sum(crit_h != (H > 0)))

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6), sharey=True)
    cmap = plt.get_cmap("viridis", 3)
    for ax, M, ys, title, ylabel in [
        (axes[0], H, om_vals, "horizontal steady precession", r"precession rate $\Omega_0$ (units $\sqrt{g/b}$)"),
        (axes[1], V, n0_vals, "vertical spin", r"spin $n_0$ (units $\sqrt{g/b}$)"),
    ]:
        im = ax.pcolormesh(a_vals, ys, M, cmap=cmap, vmin=-0.5, vmax=2.5, shading="nearest")
        ax.axvline(1.0, color="w", lw=0.8, ls=":")
        ax.set_xlabel(r"aspect ratio $a$")
        ax.set_title(title, fontsize=10)
        ax.set_ylabel(ylabel)
    aa = np.linspace(a_vals[0], a_vals[-1], 300)
    axes[1].plot(aa, [pk.theory.vertical_stability_threshold(pk.Spheroid(x).A, pk.Spheroid(x).C, x) or np.nan for x in aa],
                 "r--", lw=1.2, label=r"$n_0=\sqrt{5a^3}$: $(a^2C-A)n_0^2=a^3(a^2-1)$")
    axes[1].set_ylim(n0_vals[0], n0_vals[-1])
    axes[0].plot(aa, [pk.theory.horizontal_stability_threshold(pk.Spheroid(x).A, pk.Spheroid(x).C, x) or np.nan for x in aa],
                 "r--", lw=1.2, label=r"$\Omega_0=\sqrt{5}$: $(a^2C-A)\Omega_0^2=a^2-1$")
    axes[0].legend(loc="upper left", fontsize=8)
    axes[1].legend(loc="upper left", fontsize=8)
    cb = fig.colorbar(im, ax=axes, ticks=[0, 1, 2])
    cb.set_label("dimension of the unstable subspace")
    fig.suptitle(f"Linear stability, viscous friction $\\mu={args.mu:g}$, uniform spheroids (exact CasADi Jacobians)", fontsize=10)
    png = st.save(fig, "stability_map.png", bbox_inches="tight")
    print(f"Figure {png.name}: {n}x{n} grids, mu = {args.mu:g}, {2 * n * n} linearisations in {wall:.1f} s.")
    print("criteria: horizontal unstable iff (a^2 C - A) Omega0^2 > a^2 - 1 (Omega0 = sqrt 5 for uniform bodies); "
          "vertical stable iff (a^2 C - A) n0^2 > a^3 (a^2 - 1) (n0 = sqrt(5 a^3))")
    print(f"the two criteria disagree with the computed maps at {disagree} of {2 * n * n} grid points")
    return {"disagree": disagree, "H": H, "V": V}


if __name__ == "__main__":
    pk.sweep.run_study(main)
