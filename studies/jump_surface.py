"""Figure 6a: the jump surface (6.3) with trajectories in (Omega, theta, n), rendered off-screen.

Prolate a = 1.5 and oblate a = 2/3, Coulomb mu = 0.1: trajectories started next to the
horizontal steady precession (prolate) or the vertical spin (oblate), on the sliding branch at
distance 0.01 (the default threshold definition; the literal eigenvector seed sticks, see
README), ending where R = 0 (black points). Surface: (6.3) coloured by n; green wireframe: the
exact boundary R = 0 of (6.1) at the median |Lambda| of the crossings (at Lambda = 0 it is (6.3)).

Also tabulates, for more Omega0 values, the relative error in n of (6.3) at each crossing
(crossings only: no dense output). Writes figures/jump_surface.png (prolate),
figures/jump_surface_oblate.png, figures/jump_surface.csv, and with --gltf / --html an
interactive export of the prolate scene.

    python studies/jump_surface.py [--quick] [--gltf] [--html]
"""

from __future__ import annotations

import argparse
import csv
import time
from pathlib import Path

import numpy as np

from phasekit.surface import Scene, compute_scene

FIGURES = Path(__file__).resolve().parents[1] / "figures"
ALL = frozenset({"surface", "exact_boundary", "trajectories", "crossings", "fixed_points", "axes", "colorbar"})


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--gltf", action="store_true", help="also write figures/jump_surface.gltf")
    ap.add_argument("--html", action="store_true", help="also write figures/jump_surface.html (needs trame)")
    args = ap.parse_args(argv)
    from phasekit.viz import render_scene  # the only place pyvista is needed

    t0 = time.perf_counter()
    res = 60 if args.quick else 140
    scenes = {
        "jump_surface": Scene("prolate", 1.5, values=(10.0, 12.0, 15.0, 20.0, 30.0), show=ALL, resolution=res),
        "jump_surface_oblate": Scene("oblate", 2 / 3, values=(9.0, 10.0, 12.0, 15.0, 20.0), show=ALL, resolution=res),
    }
    infos = {}
    for stem, sc in scenes.items():
        data = compute_scene(sc)
        what = "horizontal precession, Omega0" if sc.branch == "prolate" else "vertical spin, n0"
        title = (f"Fig. 6a, {sc.branch} a = {sc.a:.4g}, mu = {sc.mu:g}: surface (6.3) (colour), exact R = 0 at "
                 f"Lambda = +-{data.exact_lambda:.3f} (green),\ntrajectories from the {what} = "
                 + ", ".join(f"{v:g}" for v in sc.values) + " (lines), R = 0 crossings (black), fixed points (red)")
        extra = {}
        if stem == "jump_surface":
            if args.gltf:
                extra["gltf"] = str(FIGURES / "jump_surface.gltf")
            if args.html:
                extra["html"] = str(FIGURES / "jump_surface.html")
        infos[stem] = (data, render_scene(data, FIGURES / f"{stem}.png", title=title, **extra))
    # the error of (6.3) at the crossings, over more starts
    table = []
    for branch, a, vals in (("prolate", 1.5, (10.0, 11.0, 12.5, 15.0, 17.5, 20.0, 25.0, 30.0, 40.0)),
                            ("oblate", 2 / 3, (9.0, 10.0, 12.5, 15.0, 17.5, 20.0, 25.0, 30.0, 40.0))):
        if args.quick:
            vals = vals[::2]
        d = compute_scene(Scene(branch, a, values=vals, show=frozenset({"crossings"})))
        for c in d.crossings:
            table.append((branch, a, c.value, c.t, c.Omega, c.theta, c.n, c.Lambda, c.n_surface, c.rel_error))
    with open(FIGURES / "jump_surface.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["branch", "a", "start", "t_cross", "Omega", "theta", "n", "Lambda", "n_63", "rel_error_n"])
        w.writerows(table)
    for stem, (data, info) in infos.items():
        print(f"Figure {stem}.png: {data.scene.branch} a = {data.scene.a:g}; {data.n_simulations} trajectories; "
              f"points drawn {info.n_points}")
    print("\nrelative error in n of (6.3) at the simulated crossing (R = 0, dR/dt < 0):")
    print(f"{'branch':<8s} {'start':>6s} {'t_cross':>8s} {'theta*':>7s} {'n*':>8s} {'Lambda*':>8s} {'rel err':>9s}")
    for row in table:
        print(f"{row[0]:<8s} {row[2]:6.1f} {row[3]:8.2f} {row[5]:7.4f} {row[6]:8.4f} {row[7]:8.4f} {row[9]:9.2e}")
    for branch in ("prolate", "oblate"):
        rows = [r for r in table if r[0] == branch]
        slope = np.polyfit(np.log([r[2] for r in rows]), np.log([r[9] for r in rows]), 1)[0]
        print(f"{branch}: log-log trend of the error against the start value: slope {slope:.2f}")
    print(f"{time.perf_counter() - t0:.1f} s")
    return {"infos": infos, "table": table}


if __name__ == "__main__":
    main()
