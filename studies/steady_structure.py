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
from dataclasses import dataclass
from pathlib import Path

import phasekit as pk
from phasekit.viz import pyplot, render_structure, save_figure

import numpy as np

STEM = "steady_structure"
LAW = pk.Viscous(0.1)  # stability of the representatives (the signature does not depend on the law)
C_SCALE = 0.05  # C of the free-moment bodies, times min(1, a)^2: small enough for every A/C <= 4
#: panel: (title, x label, y label, x range, y range, log x, log y)
PANELS = {
    "tippe-top": ("tippe top (eccentric sphere)", r"offset $\alpha$ = OG / radius", "A / C", (0.02, 0.9), (0.5, 2.0),
                  False, False),
    "spheroid-default": ("spheroid, default moments", "aspect ratio a", "offset / a", (0.2, 5.0), (0.005, 0.445),
                         True, False),
    "spheroid-a0.9": ("spheroid, a = 0.9", "offset / a", "A / C", (0.005, 0.95), (0.5, 4.0), False, True),
    "spheroid-a1.5": ("spheroid, a = 1.5", "offset / a", "A / C", (0.005, 0.95), (0.5, 4.0), False, True),
}
FULL = dict(n=56, cube=(20, 14, 16), xtol=1e-4, chunk=150)
QUICK = dict(n=14, cube=(6, 5, 6), xtol=1e-3, chunk=60)
EGG = dict(a=57.0 / 43.0, w=0.05, mu=0.1, theta0=math.pi / 2 - 0.05, omegas=(6.0, 10.0), t_end=300.0)
SCENE = dict(a=1.5, offset=0.2, seed_delta=0.01, t_end=400.0)


@dataclass(frozen=True)
class AtlasRow:
    key: str
    panel: str
    x: float
    y: float
    z: float
    signature: str
    status: str


@dataclass(frozen=True)
class BoundaryRow:
    key: str
    panel: str
    x: float
    y: float
    width: float
    below: str
    above: str
    bifurcation: str


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
        out.append(AtlasRow(point_key(panel, x, y, z), panel, x, y, z, s.signature, s.status.value))
    return out


def trace(prev, edges, xtol):
    """Task: bisect the signature along each edge of a 2-D panel to ``xtol`` (a fraction of the
    panel's span along the edge) and name the bifurcation there."""
    out = []
    for panel, p, q, span in edges:
        lo, hi = 0.0, 1.0
        s_lo, s_hi = structure_at(panel, *p), structure_at(panel, *q)
        length = abs(q[0] - p[0]) + abs(q[1] - p[1])  # edges run along x or along y
        while (hi - lo) * length / span > xtol:
            mid = 0.5 * (lo + hi)
            s_mid = structure_at(panel, p[0] + mid * (q[0] - p[0]), p[1] + mid * (q[1] - p[1]))
            if s_mid.signature == s_lo.signature:
                lo, s_lo = mid, s_mid
            else:
                hi, s_hi = mid, s_mid
        t = 0.5 * (lo + hi)
        width = (hi - lo) * length
        out.append(BoundaryRow(edge_key(panel, p, q, span), panel, p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]),
                               width, s_lo.signature, s_hi.signature, pk.bifurcation_between(s_lo, s_hi)))
    return out


def axis_values(rng, n, log):
    u = (np.arange(n) + 0.5) / n  # half a cell in: never on A/C = 1 exactly
    return np.exp(np.log(rng[0]) + u * np.log(rng[1] / rng[0])) if log else rng[0] + u * (rng[1] - rng[0])


def grid_points(g) -> list[tuple]:
    pts = []
    for panel, (_, _, _, xr, yr, logx, logy) in PANELS.items():
        pts += [(panel, float(x), float(y), 0.0) for x in axis_values(xr, g["n"], logx) for y in axis_values(yr, g["n"], logy)]
    na, nr, ng = g["cube"]
    for a, r, gam in itertools.product(axis_values((0.2, 5.0), na, True), axis_values((0.0, 0.95), nr, False),
                                       axis_values((0.5, 4.0), ng, True)):
        pts.append(("cube", float(a), float(r), float(gam)))
    return pts


def point_key(panel, x, y, z) -> str:
    return f"{panel}|{x:.12g}|{y:.12g}|{z:.12g}"


def edge_key(panel, p, q, span) -> str:
    return f"edge|{panel}|{p[0]:.12g}|{p[1]:.12g}|{q[0]:.12g}|{q[1]:.12g}"


def boundary_edges(rows) -> list[tuple]:
    """Neighbouring points (along x and along y) of a 2-D panel whose signatures differ."""
    edges = []
    for panel, (_, _, _, xr, yr, _, _) in PANELS.items():
        sig = {(r.x, r.y): r.signature for r in rows if r.panel == panel and r.status == "completed"}
        xs, ys = sorted({x for x, _ in sig}), sorted({y for _, y in sig})
        for i, x in enumerate(xs):
            for j, y in enumerate(ys):
                nbrs = ([((xs[i + 1], y), xr[1] - xr[0])] if i + 1 < len(xs) else []) + \
                       ([((x, ys[j + 1]), yr[1] - yr[0])] if j + 1 < len(ys) else [])
                for q, span in nbrs:
                    if (x, y) in sig and q in sig and sig[x, y] != sig[q]:
                        edges.append((panel, (x, y), q, span))
    return edges


# -- classes ------------------------------------------------------------------------------------


def generic(sig: str) -> bool:
    """A class, not a boundary: no family crossed (that needs A = C or a side static exactly)."""
    return "cross" not in sig and sig != "none"


def class_counts(rows) -> dict:
    tops = sorted({r.signature for r in rows if r.panel == "tippe-top" and generic(r.signature)})
    spheroid = [r for r in rows if r.panel != "tippe-top" and r.status == "completed"]
    classes = sorted({r.signature for r in spheroid if generic(r.signature)})
    cube = [r for r in spheroid if r.panel == "cube"]
    per_cube = {s: sum(r.signature == s for r in cube) for s in sorted({r.signature for r in cube})}
    return {"tippe_top": tops, "spheroid": classes, "cube_counts": per_cube,
            "failed": sum(r.status != "completed" for r in rows)}


def representatives(rows, classes) -> dict:
    """For each class: the point of a 2-D panel (else of the cube) nearest the median of the
    class's points in that panel's unit square (inside its region, away from its edges)."""
    out = {}
    for sig in classes:
        for panel in [*PANELS, "cube"]:
            pts = [r for r in rows if r.panel == panel and r.signature == sig]
            if not pts:
                continue
            P = np.array([[r.x, r.y, r.z] for r in pts])
            lo, hi = P.min(axis=0), P.max(axis=0)
            U = (P - lo) / np.where(hi > lo, hi - lo, 1.0)
            k = int(np.argmin(np.sum((U - np.median(U, axis=0)) ** 2, axis=1)))
            out[sig] = pts[k]
            break
    return out


# -- figures ------------------------------------------------------------------------------------

BIFURCATION_MARKERS = ("o", "s", "^", "D", "v", "P", "X")


def _edges(rng, n, log):
    return np.geomspace(rng[0], rng[1], n + 1) if log else np.linspace(rng[0], rng[1], n + 1)


def plot_atlas(rows, bounds, colours, png: Path, n: int, note: str) -> None:
    """Each panel's grid as coloured cells (one colour per signature, the same in every panel),
    the traced boundary points on top (marker: the bifurcation)."""
    plt = pyplot()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
    from matplotlib.ticker import ScalarFormatter

    fig, axes = plt.subplots(2, 2, figsize=(13.5, 12))
    names = sorted({b.bifurcation for b in bounds})
    order = sorted(colours)
    cmap = ListedColormap([colours[s] for s in order])
    for ax, (panel, (title, xl, yl, xr, yr, logx, logy)) in zip(axes.ravel(), PANELS.items()):
        pts = [r for r in rows if r.panel == panel]
        xs, ys = axis_values(xr, n, logx), axis_values(yr, n, logy)
        ix = {float(x): i for i, x in enumerate(xs)}
        iy = {float(y): j for j, y in enumerate(ys)}
        grid = np.full((n, n), np.nan)
        for r in pts:
            if r.x in ix and r.y in iy:
                grid[iy[r.y], ix[r.x]] = order.index(r.signature)
        ax.pcolormesh(_edges(xr, n, logx), _edges(yr, n, logy), grid, cmap=cmap, vmin=-0.5, vmax=len(order) - 0.5)
        for k, name in enumerate(names):
            sel = np.array([[b.x, b.y] for b in bounds if b.panel == panel and b.bifurcation == name]).reshape(-1, 2)
            if len(sel):
                ax.scatter(sel[:, 0], sel[:, 1], s=10, marker=BIFURCATION_MARKERS[k % len(BIFURCATION_MARKERS)],
                           color="black", edgecolors="none")
        if panel == "tippe-top":
            al = np.linspace(*xr, 50)
            ax.plot(al, 1 - al, "w--", lw=1.4)
            ax.plot(al, 1 + al, "w--", lw=1.4)
            ax.annotate(r"white dashes: A/C = 1 $\pm$ $\alpha$ (closed form)", (0.03, 0.03), xycoords="axes fraction",
                        fontsize=8, color="white")
        present = sorted({r.signature for r in pts})
        ax.legend(handles=[Patch(color=colours[s], label=s) for s in present], fontsize=7, loc="upper right", framealpha=0.9)
        ax.set(xlabel=xl, ylabel=yl, xlim=xr, ylim=yr,
               title=f"{title}: {len([s for s in present if generic(s)])} classes")
        ax.set_xscale("log" if logx else "linear")
        ax.set_yscale("log" if logy else "linear")
        for axis in ((ax.xaxis,) if logx else ()) + ((ax.yaxis,) if logy else ()):
            axis.set_major_formatter(ScalarFormatter())
            axis.set_minor_formatter(ScalarFormatter())
            ax.tick_params(which="minor", labelsize=7)
    handles = [plt.Line2D([], [], ls="none", marker=BIFURCATION_MARKERS[k % len(BIFURCATION_MARKERS)], color="black",
                          label=name) for k, name in enumerate(names)]
    fig.legend(handles=handles, loc="lower center", fontsize=8, ncol=1, frameon=False,
               title="boundaries between classes, traced by bisection on the signature")
    fig.suptitle("Classes of steady-state structure (signature: the branches' ends in theta order)\n" + note, fontsize=11)
    fig.tight_layout(rect=(0, 0.05 + 0.018 * len(names), 1, 0.95))
    save_figure(fig, png)


def plot_classes(reps: dict, colours, png: Path, note: str) -> dict:
    """Omega(theta) and n(theta) of each representative: stable solid, unstable dotted."""
    plt = pyplot()
    n = len(reps)
    cols = 3
    rows_ = math.ceil(n / cols)
    fig, axes = plt.subplots(rows_, cols, figsize=(5.2 * cols, 3.9 * rows_), squeeze=False)
    info = {}
    for ax, (sig, row) in zip(axes.ravel(), reps.items()):
        body = body_at(row.panel, row.x, row.y, row.z)
        s = pk.steady_structure(body, LAW)
        top = 1.0
        for b in s.branches:
            for y, ls in ((b.Omega, "-"), (b.n, "--")):
                for seg, st in _runs(b.theta, y, b.stable):
                    ax.plot(seg[0], seg[1], ls, color="#1a9850" if st else "#d73027", lw=1.6)
            top = max(top, float(np.quantile(np.abs(b.Omega), 0.7)) * 1.8)
            for c in b.changes:
                ax.plot([c.theta] * 2, [c.Omega, c.n], "o", color="#fdae61", ms=4, zorder=5)
            for e in b.ends:
                if e.kind == "infinite-spin":
                    ax.axvline(e.theta, color="0.4", ls=":", lw=1)
                    ax.annotate(r"$\theta_\infty$", (e.theta, 0.93), xycoords=("data", "axes fraction"), fontsize=8)
                elif e.kind == "static":
                    ax.plot(e.theta, 0.0, "k^", ms=6)
                else:
                    ax.plot([e.theta] * 2, [e.Omega, e.n], "ko", ms=5)
                    ax.annotate(f"n = {e.n:.3g}", (e.theta, e.n), fontsize=7, xytext=(4, 4), textcoords="offset points")
        ax.axhline(0, color="0.7", lw=0.6)
        ax.set(xlim=(0, math.pi), ylim=(-top, top), xlabel=r"$\theta$ (rad)", ylabel=r"$\Omega$, $n$ ($\sqrt{g/b}$)")
        ax.set_title(f"{sig}\n{body!r}", fontsize=8)
        info[sig] = {"body": repr(body), "panel": row.panel, "changes": sum(len(b.changes) for b in s.branches)}
    for ax in axes.ravel()[n:]:
        ax.axis("off")
    handles = [plt.Line2D([], [], color="k", ls="-", label=r"$\Omega(\theta)$"),
               plt.Line2D([], [], color="k", ls="--", label=r"$n(\theta)$"),
               plt.Line2D([], [], color="#1a9850", label="stable (viscous $\\mu$ = 0.1)"),
               plt.Line2D([], [], color="#d73027", label="unstable"),
               plt.Line2D([], [], ls="none", marker="o", color="#fdae61", label="change of stability"),
               plt.Line2D([], [], ls="none", marker="o", color="k", label="pole end (spin n)"),
               plt.Line2D([], [], ls="none", marker="^", color="k", label="static end")]
    fig.legend(handles=handles, loc="lower center", ncol=7, fontsize=8, frameon=False)
    fig.suptitle("One body of every class: steady precessions " + r"$\Omega(\theta)$, $n(\theta)$" + "\n" + note, fontsize=10)
    fig.tight_layout(rect=(0, 0.03, 1, 0.95))
    save_figure(fig, png)
    return info


def _runs(x, y, flags):
    out, start = [], 0
    for k in range(1, len(x) + 1):
        if k == len(x) or flags[k] != flags[start]:
            out.append(((x[start:k + 1], y[start:k + 1]), bool(flags[start])))
            start = k
    return out


def scene(png: Path, quick: bool) -> dict:
    """The displaced spheroid's structure in (Omega, theta, n) with trajectories from the
    unstable manifold of its most unstable branch state at moderate spin."""
    body = pk.Spheroid(SCENE["a"], offset=SCENE["offset"])
    s = pk.steady_structure(body, LAW)
    cands = [(float(np.max(p.eigenvalues.real)), i, k) for i, b in enumerate(s.branches) for k, p in enumerate(b.points)
             if p.n_unstable and 2.0 < b.Omega[k] < 6.0]
    _, i, k = max(cands)
    fp = s.branches[i].points[k]
    trs = []
    for _, x0 in pk.unstable_seeds(fp, SCENE["seed_delta"]):
        r = pk.simulate(pk.Model(body, LAW), x0, SCENE["t_end"], stop_at="jump")
        df = r.sample(np.linspace(0.0, r.t, 4000))
        near = np.minimum(df["theta"], math.pi - df["theta"]) < 0.02  # Omega is undefined at the poles
        stop = int(np.argmax(near)) if near.any() else len(df)
        trs.append(df[["Omega", "theta", "n"]].to_numpy()[:stop])
    info = render_structure(s, png, trajectories=trs, omega_max=8.0,
                            title=f"{body!r}, viscous mu = {LAW.mu:g}: its branches (green stable, red unstable) and\n"
                                  f"{len(trs)} trajectories from the unstable manifold of the branch state at theta = "
                                  f"{s.branches[i].theta[k]:.3f}, run to the poles" + (" (quick run)" if quick else ""),
                            camera=[(2.9, -2.6, 1.4), (0.7, 0.5, 0.45), (0.0, 0.0, 1.0)])
    return {"body": repr(body), "seed_state": {"theta": float(s.branches[i].theta[k]), "Omega": float(s.branches[i].Omega[k]),
            "n": float(s.branches[i].n[k]), "classification": fp.classification}, "points": info.n_points}


# -- where the egg's rise ends --------------------------------------------------------------------


def egg_rise_end(png: Path) -> dict:
    """Simulate the egg from near its side at two spins (exact Coulomb), then compare the motion
    it settles into with the branch state at the same theta (G at rest) and with the steady
    rolling motion at the same theta and Omega (G on a circle)."""
    egg = pk.Egg(EGG["a"], EGG["w"])
    law = pk.Coulomb(EGG["mu"])
    s = pk.steady_structure(egg, law)
    out = {"egg": repr(egg), "signature": s.signature, "runs": []}
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 5))
    for b in s.branches:
        keep = b.Omega < 14
        for ax, y in ((ax1, b.Omega), (ax2, b.n)):
            ax.plot(b.theta[keep], y[keep], color="0.2", lw=2,
                    label="branch (G at rest)" if b is s.branches[0] and ax is ax1 else None)
    for om0, colour in zip(EGG["omegas"], ("#4575b4", "#d73027")):
        r = pk.simulate(pk.Model(egg, law), pk.gyroscopic_start(egg, EGG["theta0"], omega0=om0), EGG["t_end"],
                        stop_at="none", track_minima=False)
        late = r.sample(np.linspace(0.5 * r.t, r.t, 6000))
        th, om, n = (float(late[c].mean()) for c in ("theta", "Omega", "n"))
        branch_om, branch_n = (float(v[0]) for v in s.precession(np.array([th])))
        roll = pk.theory.rolling_motion(egg, th, om)
        path = r.sample(np.linspace(0.0, r.t, 3000))
        ax1.plot(path["theta"], path["Omega"], color=colour, lw=0.7, alpha=0.7, label=f"egg, $\\Omega_0$ = {om0:g}")
        ax2.plot(path["theta"], path["n"], color=colour, lw=0.7, alpha=0.7)
        ax1.plot(th, om, "*", color=colour, ms=13, mec="k")
        ax2.plot(th, roll.n, "*", color=colour, ms=13, mec="k")
        out["runs"].append({
            "omega0": om0, "status": r.status.value, "t_end": r.t, "n_events": len(r.events),
            "stick_slip_cycles": sum(e.name == "slip" for e in r.events),
            "late_mean": {"theta": th, "Omega": om, "n": n, "V": float(late["V"].mean()),
                          "theta_spread": float(late["theta"].std()), "slip_max": float(late["slip"].max())},
            "branch_at_theta": {"Omega": branch_om, "n": branch_n},
            "rolling_motion": {"n": roll.n, "V": roll.V, "radius": roll.radius, "needs_mu": roll.needs_mu,
                               "n_rel_difference": abs(roll.n - n) / abs(n)}})
    for ax, yl in ((ax1, r"$\Omega$ ($\sqrt{g/b}$)"), (ax2, r"$n$ ($\sqrt{g/b}$)")):
        ax.set(xlabel=r"$\theta$ (rad)", ylabel=yl, xlim=(0, math.pi))
        ax.grid(alpha=0.3)
    ax1.set_ylim(0, 14)
    ax1.legend(fontsize=8)
    ax2.set_title("stars: the late mean state; its n is that of the steady rolling motion (G on a circle)", fontsize=9)
    fig.suptitle(f"Where the rise of {egg!r} ends (exact Coulomb mu = {EGG['mu']:g}, start theta0 = pi/2 - 0.05, "
                 "gyroscopic)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, png)
    return out


# -- main -----------------------------------------------------------------------------------------


def colours_for(signatures_) -> dict:
    cmap = pyplot().get_cmap("tab20")
    return {sig: cmap(k % 20) for k, sig in enumerate(sorted(signatures_))}


def main(argv=None) -> dict:
    st = pk.sweep.Study(__file__, __doc__, quick_help="coarse grids", dask=True)
    st.parser.add_argument("--no-scene", action="store_true", help="skip the 3-D scene and the egg")
    args = st.parse(argv)
    g = QUICK if args.quick else FULL
    meta = {"panels": {k: list(v[:5]) for k, v in PANELS.items()}, "grid": g, "law_for_stability": repr(LAW),
            "moments": "tippe top: C = 0.4, A = (A/C) C; spheroid-default: A = (1 + a^2)/5 - offset^2, C = 2/5; "
                       "others: C = 0.05 min(1, a)^2, A = (A/C) C"}
    atlas = st.store(AtlasRow, meta, name=f"{STEM}_atlas")
    borders = st.store(BoundaryRow, meta, name=f"{STEM}_boundaries")
    points = grid_points(g)
    specs, members = pk.sweep.chunked(points, point_key, signatures, size=g["chunk"], prefix="atlas")
    how = str(st.run(specs, atlas, members=members, desc="atlas"))
    keys = {point_key(*p) for p in points}
    rows = [r for r in atlas.rows() if r.key in keys]
    edges = boundary_edges(rows)
    specs, members = pk.sweep.chunked(edges, edge_key, trace, size=40, args=(g["xtol"],), prefix="boundaries")
    how += "; boundaries: " + str(st.run(specs, borders, members=members, desc="boundaries"))
    ekeys = {edge_key(*e) for e in edges}
    bounds = [b for b in borders.rows() if b.key in ekeys]
    counts = class_counts(rows)
    colours = colours_for({r.signature for r in rows})
    note = (f"{len(rows)} bodies ({g['n']}x{g['n']} per panel, {'x'.join(map(str, g['cube']))} on the 3-D grid), "
            f"{len(bounds)} boundary points bisected to {g['xtol']:g} of the span" + (" (quick run)" if args.quick else ""))
    plot_atlas(rows, bounds, colours, st.path(f"{STEM}_atlas.png"), g["n"], note)
    reps = representatives(rows, sorted(set(counts["spheroid"]) | set(counts["tippe_top"])))
    rep_info = plot_classes(reps, colours, st.path(f"{STEM}_classes.png"),
                            f"representatives of the {len(reps)} classes found; stability: exact Jacobian, bounded eigenvalues")
    extra = {}
    if not args.no_scene:
        extra["scene"] = scene(st.path(f"{STEM}_scene.png"), args.quick)
        extra["egg"] = egg_rise_end(st.path(f"{STEM}_egg.png"))
    names = {}
    for b in bounds:
        names.setdefault(b.bifurcation, set()).add(tuple(sorted((b.below, b.above))))
    tops = [b for b in bounds if b.panel == "tippe-top"]
    closed = {"max_distance": max((min(abs(b.y - (1 - b.x)), abs(b.y - (1 + b.x))) for b in tops), default=None),
              "max_half_width": max((b.width / 2 for b in tops), default=None), "points": len(tops)}
    summary = {"classes": counts, "part_iii": {"spheroid": 9, "tippe_top": 3}, "tippe_top_boundary_vs_1_pm_alpha": closed,
               "bifurcations": {k: sorted(" <-> ".join(p) for p in v) for k, v in sorted(names.items())},
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
    pk.sweep.run_study(main)
