"""Steady-state structure of convex bodies (parts III and IV of the series): classes and atlases.

The structure of a body (pk.steady_structure) is its branches of steady precessions over
0 <= theta <= pi with their two ends (pole, static, infinite-spin); its signature is the
sequence of ends. This study

* colours parameter space by signature (atlases): the tippe top over (offset, A/C); the
  spheroid with displaced centre of mass over (a, offset/a) with the default moments
  (A = (1 + a^2)/5 - offset^2, C = 2/5) and over (offset/a, A/C) at a = 0.9 and a = 1.5; and
  counts the classes on a 3-D grid over (a, offset/a, A/C), a in [0.2, 5], offset/a in
  (0, 0.95), A/C in [0.5, 4] (C <= 2A bounds A/C below; the signature depends on A/C only);
* traces the boundaries between classes by bisection on the signature along every grid edge
  whose ends differ (to 1e-4 of the panel's span) and names the bifurcation at each;
* draws Omega(theta) and n(theta) of a representative body of every class found, stability
  under viscous friction (mu = 0.1, part I's law) marked, ends and changes of stability
  labelled; and a 3-D scene of one structure with trajectories on the unstable manifold;
* finds where the rise of a uniform egg (w = 0.05) that settles tilted ends (part IV's question).

Grids are offset by half a cell so that no point lies on the measure-zero boundary A = C.
Runs on the sweep engine (Dask LocalCluster, or --serial / --scheduler), resumable: finished
rows are appended to steady_structure_atlas.csv and _boundaries.csv at once.
"""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import plot_atlas, plot_branch_planes, plot_classes, render_structure
from phasekit.viz import save_figure

import numpy as np

STEM = "steady_structure"
LAW = pk.Viscous(0.1)  # stability of the representatives (the signature does not depend on the law)
C_SCALE = 0.05  # C of the free-moment bodies, times min(1, a)^2: small enough for every A/C <= 4
PANELS = {k: ps.AtlasPanel(*v) for k, v in {
    "tippe-top": ("tippe top (eccentric sphere)", r"offset $\alpha$ = OG / radius", "A / C", (0.02, 0.9), (0.5, 2.0),
                  False, False),
    "spheroid-default": ("spheroid, default moments", "aspect ratio a", "offset / a", (0.2, 5.0), (0.005, 0.445),
                         True, False),
    "spheroid-a0.9": ("spheroid, a = 0.9", "offset / a", "A / C", (0.005, 0.95), (0.5, 4.0), False, True),
    "spheroid-a1.5": ("spheroid, a = 1.5", "offset / a", "A / C", (0.005, 0.95), (0.5, 4.0), False, True),
}.items()}
FULL = dict(n=56, cube=(20, 14, 16), xtol=1e-4, chunk=150)
QUICK = dict(n=14, cube=(6, 5, 6), xtol=1e-3, chunk=60)
EGG = dict(a=57.0 / 43.0, w=0.05, mu=0.1, theta0=math.pi / 2 - 0.05, omegas=(6.0, 10.0), t_end=300.0)
SCENE = dict(a=1.5, offset=0.2, seed_delta=0.01, t_end=400.0)


# -- the atlas points --------------------------------------------------------------------------


def body_at(panel: str, x: float, y: float, z: float = 0.0):
    """The body of one atlas point (cube: a = x, offset/a = y, A/C = z)."""
    if panel == "tippe-top":
        return pk.EccentricSphere(x, A=y * 0.4, C=0.4)
    if panel == "spheroid-default":
        return pk.Spheroid(x, offset=y * x)
    a, r, g = (x, y, z) if panel == "cube" else (float(panel.split("-a")[1]), x, y)
    c = C_SCALE * min(1.0, a) ** 2
    return pk.Spheroid(a, A=g * c, C=c, offset=r * a)


def structure_at(panel, x, y, z=0.0):
    return pk.steady_structure(body_at(panel, x, y, z), LAW, samples=False)


def signatures(prev, points):
    """Task: the signatures of a chunk of atlas points."""
    out = []
    for panel, x, y, z in points:
        s = structure_at(panel, x, y, z)
        out.append(ps.AtlasRow(ps.atlas_point_key(panel, x, y, z), panel, x, y, z, s.signature, s.status.value))
    return out


def trace(prev, edges, xtol):
    """Task: the boundary along each edge of a 2-D panel, bisected to ``xtol`` of the panel's span."""
    return [ps.trace_boundary(structure_at, *e, xtol=xtol, key=ps.atlas_edge_key(*e)) for e in edges]


def grid_points(g) -> list[tuple]:
    """The 2-D panels' points, then the 3-D grid's (a, offset/a, A/C)."""
    axis = ps.axis_values
    cube = itertools.product(axis((0.2, 5.0), g["cube"][0], True), axis((0.0, 0.95), g["cube"][1], False),
                             axis((0.5, 4.0), g["cube"][2], True))
    return ps.atlas_grid(PANELS, g["n"]) + [("cube", float(a), float(r), float(gam)) for a, r, gam in cube]


def boundary_edges(rows) -> list[tuple]:
    return ps.atlas_edges(rows, PANELS)


# -- classes ------------------------------------------------------------------------------------


def class_counts(rows) -> dict:
    tops = sorted({r.signature for r in rows if r.panel == "tippe-top" and ps.is_class(r.signature)})
    spheroid = [r for r in rows if r.panel != "tippe-top" and r.status == "completed"]
    classes = sorted({r.signature for r in spheroid if ps.is_class(r.signature)})
    cube = [r for r in spheroid if r.panel == "cube"]
    per_cube = {s: sum(r.signature == s for r in cube) for s in sorted({r.signature for r in cube})}
    return {"tippe_top": tops, "spheroid": classes, "cube_counts": per_cube,
            "failed": sum(r.status != "completed" for r in rows)}


def scene(png: Path, quick: bool) -> dict:
    """The displaced spheroid's structure in (Omega, theta, n) with trajectories from the
    unstable manifold of its most unstable branch state at moderate spin."""
    body = pk.Spheroid(SCENE["a"], offset=SCENE["offset"])
    s = pk.steady_structure(body, LAW)
    runs = ps.manifold_runs(s, omega_range=(2.0, 6.0), seed_delta=SCENE["seed_delta"], t_end=SCENE["t_end"])
    trs = runs["trajectories"]
    info = render_structure(s, png, trajectories=trs, omega_max=8.0,
                            title=f"{body!r}, viscous mu = {LAW.mu:g}: its branches coloured by stability and\n"
                                  f"{len(trs)} trajectories from the unstable manifold of the branch state at theta = "
                                  f"{runs['state']['theta']:.3f}, run to the poles" + (" (quick run)" if quick else ""),
                            camera=[(2.9, -2.6, 1.4), (0.7, 0.5, 0.45), (0.0, 0.0, 1.0)])
    return {"body": repr(body), "seed_state": runs["state"], "points": info.n_points}


# -- where the egg's rise ends --------------------------------------------------------------------


def egg_rise_end(png: Path) -> dict:
    """Simulate the egg from near its side at two spins (exact Coulomb), then compare the motion
    it settles into with the branch state at the same theta (G at rest) and with the steady
    rolling motion at the same theta and Omega (G on a circle)."""
    egg = pk.Egg(EGG["a"], EGG["w"])
    law = pk.Coulomb(EGG["mu"])
    s = pk.steady_structure(egg, law)
    out = {"egg": repr(egg), "signature": s.signature, "runs": []}
    drawn = []
    for om0, colour in zip(EGG["omegas"], ("#4575b4", "#d73027")):
        r = pk.simulate(pk.Model(egg, law), pk.gyroscopic_start(egg, EGG["theta0"], omega0=om0), EGG["t_end"],
                        stop_at="none", track_minima=False)
        run = {"omega0": om0, **ps.settled_motion(r, s)}
        drawn.append(dict(path=r.sample(np.linspace(0.0, r.t, 3000)), colour=colour, label=f"egg, $\\Omega_0$ = {om0:g}",
                          star=(run["late_mean"]["theta"], run["late_mean"]["Omega"], run["rolling_motion"]["n"])))
        out["runs"].append(run)
    save_figure(plot_branch_planes(s, drawn, omega_max=14, caption="stars: the late mean state; its n is that of the steady "
                                   "rolling motion (G on a circle)", title=f"Where the rise of {egg!r} ends (exact Coulomb mu = "
                                   f"{EGG['mu']:g}, start theta0 = pi/2 - 0.05, gyroscopic)"), png)
    return out


# -- main -----------------------------------------------------------------------------------------


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="coarse grids", dask=True)
    st.parser.add_argument("--no-scene", action="store_true", help="skip the 3-D scene and the egg")
    args = st.parse(argv)
    g = QUICK if args.quick else FULL
    meta = {"panels": {k: list(v[:5]) for k, v in PANELS.items()}, "grid": g, "law_for_stability": repr(LAW),
            "moments": "tippe top: C = 0.4, A = (A/C) C; spheroid-default: A = (1 + a^2)/5 - offset^2, C = 2/5; "
                       "others: C = 0.05 min(1, a)^2, A = (A/C) C"}
    atlas = st.store(ps.AtlasRow, meta, name=f"{STEM}_atlas")
    borders = st.store(ps.BoundaryRow, meta, name=f"{STEM}_boundaries")
    points = grid_points(g)
    specs, members = pk.sweep.chunked(points, ps.atlas_point_key, signatures, size=g["chunk"], prefix="atlas")
    rows, ran = st.sweep(specs, atlas, members=members, desc="atlas")
    edges = boundary_edges(rows)
    specs, members = pk.sweep.chunked(edges, ps.atlas_edge_key, trace, size=40, args=(g["xtol"],), prefix="boundaries")
    bounds, ran_b = st.sweep(specs, borders, members=members, desc="boundaries")
    how = f"{ran}; boundaries: {ran_b}"
    counts = class_counts(rows)
    colours = ps.signature_colours({r.signature for r in rows})
    note = (f"{len(rows)} bodies ({g['n']}x{g['n']} per panel, {'x'.join(map(str, g['cube']))} on the 3-D grid), "
            f"{len(bounds)} boundary points bisected to {g['xtol']:g} of the span" + (" (quick run)" if args.quick else ""))
    al = np.linspace(*PANELS["tippe-top"].xrange, 50)
    st.save(plot_atlas(rows, bounds, PANELS, colours, n=g["n"], note=note, closed_forms={"tippe-top": (
        [(al, 1 - al), (al, 1 + al)], r"white dashes: A/C = 1 $\pm$ $\alpha$ (closed form)")}), f"{STEM}_atlas.png")
    reps = ps.atlas_representatives(rows, sorted(set(counts["spheroid"]) | set(counts["tippe_top"])), [*PANELS, "cube"])
    structures = {sig: pk.steady_structure(body_at(r.panel, r.x, r.y, r.z), LAW) for sig, r in reps.items()}
    st.save(plot_classes(structures, note=f"representatives of the {len(reps)} classes found; stability: exact Jacobian, "
                                          "bounded eigenvalues"), f"{STEM}_classes.png")
    rep_info = {sig: {"body": repr(s.body), "panel": reps[sig].panel, "changes": sum(len(b.changes) for b in s.branches)}
                for sig, s in structures.items()}
    extra = {}
    if not args.no_scene:
        extra["scene"] = scene(st.path(f"{STEM}_scene.png"), args.quick)
        extra["egg"] = egg_rise_end(st.path(f"{STEM}_egg.png"))
    tops = [b for b in bounds if b.panel == "tippe-top"]
    closed = {"max_distance": max((min(abs(b.y - (1 - b.x)), abs(b.y - (1 + b.x))) for b in tops), default=None),
              "max_half_width": max((b.width / 2 for b in tops), default=None), "points": len(tops)}
    summary = {"classes": counts, "part_iii": {"spheroid": 9, "tippe_top": 3}, "tippe_top_boundary_vs_1_pm_alpha": closed,
               "bifurcations": ps.bifurcation_pairs(bounds),
               "boundary_width_max": max((b.width for b in bounds), default=None), "representatives": rep_info, **extra}
    atlas.annotate(summary=summary)
    wall = st.wall
    print(f"\n{STEM}: {len(rows)} bodies, {len(bounds)} traced boundary points; {how}; {wall:.1f} s wall")
    print(f"  tippe top: {len(counts['tippe_top'])} classes (part III: 3): {', '.join(counts['tippe_top'])}")
    print(f"  displaced spheroid: {len(counts['spheroid'])} classes (part III: 9): {', '.join(counts['spheroid'])}")
    print(f"  tippe-top boundary points against A/C = 1 +- alpha: largest distance {closed['max_distance']}, largest "
          f"half-width of a bracket {closed['max_half_width']} ({closed['points']} points)")
    print(f"  3-D grid counts: {counts['cube_counts']}; failed: {counts['failed']}")
    for name, pairs in summary["bifurcations"].items():
        print(f"  boundary: {name}: {len(pairs)} class pairs")
    if "egg" in extra:
        for run in extra["egg"]["runs"]:
            print(f"  egg Omega0 = {run['omega0']:g}: settles at theta {run['late_mean']['theta']:.4f}, Omega "
                  f"{run['late_mean']['Omega']:.4f} (branch at that theta: {run['branch_at_theta']['Omega']:.4f}); rolling "
                  f"motion n differs by {run['rolling_motion']['n_rel_difference']:.1e}, radius {run['rolling_motion']['radius']:.4f} b,"
                  f" needs mu >= {run['rolling_motion']['needs_mu']:.4f}; {run['stick_slip_cycles']} slip events")
    print(json.dumps({"wall_s": wall, "n_bodies": len(rows), "n_boundary_points": len(bounds),
                      "classes_spheroid": len(counts["spheroid"]), "classes_tippe_top": len(counts["tippe_top"])}))
    return {"rows": rows, "bounds": bounds, "summary": summary, "wall_s": wall}


if __name__ == "__main__":
    pk.scaffold.run_study(main)
