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
import phasekit.studies as ps
from phasekit.studies import plot_stability_map

import numpy as np


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="25x25 grids instead of 80x80")
    st.parser.add_argument("--mu", type=st.parser.real(), default=0.1, help="viscous friction coefficient (default 0.1)")
    args = st.parse(argv, check=lambda args: pk.Viscous(args.mu))  # mu checked before any work (named --mu)
    n = 25 if args.quick else 80
    a_vals = np.linspace(0.3, 3.0, n)
    om_vals = np.linspace(0.2, 15.0, n)
    n0_vals = np.linspace(0.2, 15.0, n)
    with st.progress(total=2 * n * n, desc="linearisations") as bar:
        H = ps.stability_grid("horizontal", a_vals, om_vals, mu=args.mu, progress=bar)
        V = ps.stability_grid("vertical", a_vals, n0_vals, mu=args.mu, progress=bar)
    wall = st.wall
    # agreement of the maps with the criteria
    bodies = [pk.Spheroid(a) for a in a_vals]
    crit_v = np.array([[ps.vertical_is_stable(b.A, b.C, b.a, s) for b in bodies] for s in n0_vals])
    crit_h = np.array([[ps.horizontal_is_unstable(b.A, b.C, b.a, s) for b in bodies] for s in om_vals])
    disagree = int(np.sum(crit_v != (V == 0))) + int(np.sum(crit_h != (H > 0)))
    png = st.save(plot_stability_map(a_vals, om_vals, n0_vals, H, V, mu=args.mu), "stability_map.png", bbox_inches="tight")
    print(f"Figure {png.name}: {n}x{n} grids, mu = {args.mu:g}, {2 * n * n} linearisations in {wall:.1f} s.")
    print("criteria: horizontal unstable iff (a^2 C - A) Omega0^2 > a^2 - 1 (Omega0 = sqrt 5 for uniform bodies); "
          "vertical stable iff (a^2 C - A) n0^2 > a^3 (a^2 - 1) (n0 = sqrt(5 a^3))")
    print(f"the two criteria disagree with the computed maps at {disagree} of {2 * n * n} grid points")
    return {"disagree": disagree, "H": H, "V": V}


if __name__ == "__main__":
    pk.scaffold.run_study(main)
