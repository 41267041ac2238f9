"""Every number and table of the results pages, computed from the committed data when the docs
build (``{pk}`group.name``` inline, ``{pk-table} group.name`` as a block).

A *group* is a function of :class:`~sources.Sources` returning a dict of named values: strings
(inline numbers, short phrases) or Markdown blocks (tables). Nothing here is typed from a
previous run: change a number in ``figures/`` and the page changes with it (tests/contracts/test_docs_site.py
does exactly that on a copy).
"""

from __future__ import annotations

from collections import Counter
from typing import Callable

import numpy as np
import pandas as pd

from .fmt import a_label, fixed, pct, rng, sci, sig, table
from .sources import Sources

GROUPS: dict[str, Callable[[Sources], dict]] = {}


def group(name: str):
    def deco(fn):
        GROUPS[name] = fn
        return fn

    return deco


def values(src: Sources, name: str) -> dict:
    if name not in GROUPS:
        raise KeyError(f"no group of generated values named {name!r} (known: {', '.join(sorted(GROUPS))})")
    return src.memo(("group", name), lambda: GROUPS[name](src))


def lookup(src: Sources, key: str) -> str:
    """``"steady.spheroid_classes"`` -> its value as text."""
    name, _, item = key.partition(".")
    vals = values(src, name)
    if item not in vals:
        raise KeyError(f"group {name!r} has no value {item!r} (it has: {', '.join(sorted(vals))})")
    return str(vals[item])


# -- the steady-state structure (studies/steady_structure.py) ----------------------------------------

#: the atlas's panels as the page names them
PANEL_NAMES = {
    "tippe-top": "tippe top",
    "spheroid-default": "default moments",
    "spheroid-a0.9": "a = 0.9",
    "spheroid-a1.5": "a = 1.5",
    "cube": "3-D grid",
}


@group("steady")
def steady(src: Sources) -> dict:
    meta = src.json("steady_structure_atlas.json")
    s = meta["summary"]
    atlas = src.csv("steady_structure_atlas.csv")
    bounds = src.csv("steady_structure_boundaries.csv")
    classes = s["classes"]
    egg = s["egg"]
    r6, r10 = (next(r for r in egg["runs"] if r["omega0"] == w) for w in (6.0, 10.0))
    tt = s["tippe_top_boundary_vs_1_pm_alpha"]
    n = meta["grid"]["n"]
    cube = "x".join(str(k) for k in meta["grid"]["cube"])
    out = {
        "spheroid_classes": len(classes["spheroid"]),
        "tippe_classes": len(classes["tippe_top"]),
        "part_iii_spheroid": s["part_iii"]["spheroid"],
        "part_iii_tippe": s["part_iii"]["tippe_top"],
        "panel_grid": f"{n}x{n}",
        "cube_grid": cube,
        "n_panels": len(meta["panels"]),
        "n_bodies": len(atlas),
        "n_boundary_points": len(bounds),
        "failed": classes["failed"],
        "boundary_width_max": sci(s["boundary_width_max"], 1),
        "tippe_boundary_distance": sci(tt["max_distance"], 1),
        "tippe_boundary_half_width": sci(tt["max_half_width"], 1),
        "tippe_boundary_points": tt["points"],
        "law": meta["law_for_stability"],
        "moments": meta["moments"],
        "egg": egg["egg"],
        "egg_signature": f"`{egg['signature']}`",
        "egg6_theta": fixed(r6["late_mean"]["theta"], 3),
        "egg6_Omega": fixed(r6["late_mean"]["Omega"], 3),
        "egg6_branch_Omega": fixed(r6["branch_at_theta"]["Omega"], 3),
        "egg6_radius": sig(r6["rolling_motion"]["radius"], 2),
        "egg6_needs_mu": fixed(r6["rolling_motion"]["needs_mu"], 3),
        "egg6_n_difference": sci(r6["rolling_motion"]["n_rel_difference"], 1),
        "egg10_theta": fixed(r10["late_mean"]["theta"], 3),
        "egg10_slips": r10["stick_slip_cycles"],
        "egg10_t_end": f"{r10['t_end']:g}",
        "egg10_needs_mu": fixed(r10["rolling_motion"]["needs_mu"], 3),
        "egg10_Omega": fixed(r10["late_mean"]["Omega"], 3),
        "egg10_branch_Omega": fixed(r10["branch_at_theta"]["Omega"], 3),
        "scene_body": s["scene"]["body"],
    }
    # which class where: the atlas rows per panel
    where = atlas.groupby(["signature", "panel"]).size()
    rows = []
    for sig_ in sorted(set(classes["spheroid"]) | set(classes["tippe_top"])):
        panels = [f"{PANEL_NAMES.get(p, p)}: {k}" for (sg, p), k in where.items() if sg == sig_]
        rep = s["representatives"].get(sig_, {})
        rows.append(
            [
                f"`{sig_}`",
                "yes" if sig_ in classes["spheroid"] else "",
                "yes" if sig_ in classes["tippe_top"] else "",
                "; ".join(panels),
                f"`{rep.get('body', '')}`",
                rep.get("changes", ""),
            ]
        )
    out["classes_table"] = table(
        [
            "signature (branch ends, theta from 0 to pi)",
            "spheroid",
            "tippe top",
            "found in (panel: bodies)",
            "representative",
            "stability changes along it",
        ],
        rows,
    )
    brows = []
    for name, pairs in s["bifurcations"].items():
        pts = bounds[bounds["bifurcation"] == name]
        brows.append(
            [name, "; ".join(f"`{p}`" for p in pairs), len(pts), sci(pts["width"].max(), 1) if len(pts) else ""]
        )
    out["bifurcations_table"] = table(
        ["at the boundary", "classes on either side", "traced points", "widest bracket"], brows
    )
    out["n_bifurcation_kinds"] = len(s["bifurcations"])
    return out


# -- jump thresholds (studies/threshold_vs_aspect.py, threshold_vs_mu.py, outcome_map.py) ------------

ASPECT_COLUMNS = [
    ("sliding", "(2) sliding, exact Coulomb [default]"),
    ("literal-eps1e-3", "(3) literal, eps 1e-3"),
    ("literal-eps1e-4", "(3) literal, eps 1e-4"),
    ("literal-exact", "(3) literal, exact"),
    ("viscous", "(1) viscous"),
]


def _threshold_cell(r) -> str:
    if r["status"] == "converged":
        return fixed(r["threshold"], 4)
    if r["status"] == "no_jump_in_range":
        return f"no jump <= {r['bracket_lo']:g}"
    return str(r["status"])


def _aspect(src: Sources) -> pd.DataFrame:
    return src.csv("threshold_vs_aspect.csv")


def _at(df: pd.DataFrame, name: str, a: float) -> float:
    row = df[(df["name"] == name) & np.isclose(df["a"], a)]
    if len(row) != 1 or row["status"].iloc[0] != "converged":
        raise ValueError(f"threshold_vs_aspect.csv: no converged {name!r} at a = {a:g}")
    return float(row["threshold"].iloc[0])


@group("aspect")
def aspect(src: Sources) -> dict:
    d = _aspect(src)
    main = d[d["group"] == "main"]
    out = {}
    rows = []
    for branch in ("prolate", "oblate"):
        for a in sorted(main.loc[main["branch"] == branch, "a"].unique()):
            cells = []
            for name, _ in ASPECT_COLUMNS:
                r = main[(main["name"] == name) & np.isclose(main["a"], a)]
                cells.append(_threshold_cell(r.iloc[0]) if len(r) else "")
            dflt = main[(main["name"] == "sliding") & np.isclose(main["a"], a)].iloc[0]
            rows.append(
                [
                    branch,
                    a_label(a) if abs(a - 2 / 3) > 1e-9 else "0.6667",
                    *cells,
                    int(dflt["n_sims"]) + int(dflt["n_check_sims"]),
                ]
            )
    out["table"] = table(["branch", "a", *(c for _, c in ASPECT_COLUMNS), "sims (default)"], rows)
    conv = main[main["status"] == "converged"]
    out["n_converged"] = len(conv)
    out["n_checked_ok"] = int(conv["consistent"].astype(str).eq("True").sum())
    vis = main[main["name"] == "viscous"]
    nj = vis[vis["status"] == "no_jump_in_range"]
    out["viscous_no_jump"] = (
        f"no jump up to {sig(nj['bracket_lo'].min(), 3)} at {len(nj)} of {len(vis)} aspect ratios"
        if len(nj)
        else f"jumps at {len(vis)} aspect ratios"
    )
    out["n_thresholds"] = len(d)
    out["n_sims"] = int(d["n_sims"].sum() + d["n_check_sims"].fillna(0).sum())
    out["task_time_s"] = f"{d['wall_s'].sum():.0f}"
    dflt = main[main["name"] == "sliding"].set_index("a")["threshold"]
    out["a15"] = fixed(_at(d, "sliding", 1.5), 3)
    out["a23"] = fixed(_at(d, "sliding", 2 / 3), 3)
    for k in ("literal-eps1e-3", "literal-eps1e-4", "literal-exact"):
        out[f"a15_{k}"] = sig(_at(d, k, 1.5), 4 if k != "literal-exact" else 3)
        out[f"a23_{k}"] = sig(_at(d, k, 2 / 3), 3)
    out["a15_literal_eps1e-6"] = sig(_at(d, "literal-eps1e-6", 1.5), 3)
    out["a15_literal_eps1e-8"] = sig(_at(d, "literal-eps1e-8", 1.5), 2)
    pro, obl = (dflt[main[main["name"] == "sliding"].set_index("a")["branch"] == b] for b in ("prolate", "oblate"))
    out["prolate_near1"] = f"{sig(pro.loc[pro.index.min()], 3)} (a = {pro.index.min():g})"
    out["prolate_at2"] = f"{sig(pro.loc[2.0], 3)} (a = 2)"
    out["oblate_near1"] = f"{sig(obl.loc[obl.index.max()], 3)} (a = {obl.index.max():g})"
    out["oblate_far"] = f"{sig(obl.loc[0.4], 3)} (a = 0.4)"
    amin = pro.idxmin()
    out["prolate_min"] = f"{sig(pro.min(), 3)} at a = {amin:g}"
    out["oblate_min"] = f"{sig(obl.min(), 3)} at a = {obl.idxmin():g}"
    # sensitivity: relative change against the default (and the literal recipe against eps 1e-4)
    srows = []
    for name, ref, what in [
        ("sliding-d0.005", "sliding", "seed distance d = 0.005"),
        ("sliding-d0.02", "sliding", "seed distance d = 0.02"),
        ("sliding-eps0.0001", "sliding", "regularised, eps = 1e-4"),
        ("sliding-eps1e-06", "sliding", "regularised, eps = 1e-6"),
        ("sliding-eps1e-08", "sliding", "regularised, eps = 1e-8"),
        ("sliding-rtol1e-8", "sliding", "rtol 1e-8"),
        ("sliding-rtol1e-10", "sliding", "rtol 1e-10"),
        ("literal-eps1e-4-delta0.005", "literal-eps1e-4", "literal, delta = 0.005"),
        ("literal-eps1e-4-delta0.02", "literal-eps1e-4", "literal, delta = 0.02"),
        ("literal-eps1e-4-rtol1e-8", "literal-eps1e-4", "literal, rtol 1e-8"),
        ("literal-eps1e-4-rtol1e-10", "literal-eps1e-4", "literal, rtol 1e-10"),
        ("literal-eps1e-6", "literal-eps1e-4", "literal, eps = 1e-6"),
        ("literal-eps1e-8", "literal-eps1e-4", "literal, eps = 1e-8"),
    ]:
        cells = []
        for a in (1.5, 2 / 3):
            try:
                cells.append(pct(_at(d, name, a) / _at(d, ref, a) - 1, 2, sign=True))
            except ValueError:
                cells.append("")
        srows.append([what, "default" if ref == "sliding" else "literal, eps = 1e-4", *cells])
    out["sensitivity_table"] = table(["change", "relative to", "a = 1.5", "a = 2/3"], srows)
    lo, hi = (_at(d, f"sliding-d{x}", 1.5) for x in ("0.005", "0.02"))
    out["d_spread_a15"] = f"{sig(lo, 4)} / {out['a15']} / {sig(hi, 4)}"
    return out


MU_LABEL = {0.02: "0.02", 0.0342: "0.0342", 0.0585: "0.0585", 0.1: "0.1", 0.171: "0.171", 0.292: "0.292", 0.5: "0.5"}


def _mu_label(mu: float) -> str:
    return f"{mu:.3g}"


@group("mu")
def mu(src: Sources) -> dict:
    d = src.csv("threshold_vs_mu.csv")
    meta = src.json("threshold_vs_mu.json")
    base = d[np.isclose(d["d"], 0.01)]
    mus = sorted(base["mu"].unique())
    rows = []
    for branch in ("prolate", "oblate"):
        for a in sorted(base.loc[base["branch"] == branch, "a"].unique()):
            cells = []
            for m in mus:
                r = base[(base["branch"] == branch) & np.isclose(base["a"], a) & np.isclose(base["mu"], m)]
                cells.append(
                    sig(r["threshold"].iloc[0], 4)
                    if len(r) and r["status"].iloc[0] == "converged"
                    else (r["status"].iloc[0] if len(r) else "")
                )
            rows.append([branch, a_label(a), *cells])
    out = {"table": table(["branch", "a", *(f"mu = {_mu_label(m)}" for m in mus)], rows)}
    out["n"] = len(d)
    out["n_converged"] = int((d["status"] == "converged").sum())
    out["n_sims"] = int(d["n_sims"].sum())
    out["n_mu"] = len(mus)
    out["mu_range"] = f"{_mu_label(mus[0])} ... {_mu_label(mus[-1])}"
    # relative to mu = 0.1, per (branch, a)
    ref = base[np.isclose(base["mu"], 0.1)].set_index(["branch", "a"])["threshold"]
    rel = base.assign(rel=[r.threshold / ref.loc[(r.branch, r.a)] - 1 for r in base.itertuples()])

    def band(lo, hi):
        sel = rel[(rel["mu"] >= lo * 0.999) & (rel["mu"] <= hi * 1.001)]
        return sel["rel"].abs().max()

    out["within_mid"] = pct(band(0.0585, 0.171), 1)
    out["mid_range"] = f"{_mu_label(mus[2])}-{_mu_label(mus[4])}"
    low = rel[np.isclose(rel["mu"], mus[0])]
    out["within_low"] = pct(low["rel"].abs().max(), 0)
    for m, key in ((mus[-2], "rise_292"), (mus[-1], "rise_500")):
        sel = rel[np.isclose(rel["mu"], m)]
        k = sel["rel"].idxmax()
        out[key] = f"{pct(sel.loc[k, 'rel'], 0, sign=True)} (a = {a_label(sel.loc[k, 'a'])})"
    out["rise_500_pct"] = pct(rel[np.isclose(rel["mu"], mus[-1])]["rel"].max(), 0, sign=True)
    coll = meta["summary"]["collapse"]
    small = [v["spread"] for b in coll.values() for m, v in b.items() if float(m) <= 0.171 and float(m) != 0.1]
    out["collapse_small"] = rng(min(small), max(small), lambda x: fixed(x, 2))
    big = {b: [coll[b][k]["spread"] for k in sorted(coll[b], key=float)[-2:]] for b in coll}
    out["collapse_big"] = "; ".join(f"{b}: {fixed(v[0], 2)} / {fixed(v[1], 2)}" for b, v in big.items())
    # d-lines: the threshold as the seed distance shrinks
    dl = meta["summary"]["d_lines"]
    lines = []
    for key, v in dl.items():
        ch = [c for c in v["change_per_halving"] if c is not None]
        lines.append(
            [
                key,
                ", ".join(sig(x, 3) for x in v["d"]),
                ", ".join(sig(x, 4) for x in v["threshold"]),
                ", ".join(pct(c, 0, sign=True) for c in ch),
            ]
        )
    out["d_lines_table"] = table(["line", "d", "threshold", "change per halving of d"], lines)
    return out


@group("outcome")
def outcome(src: Sources) -> dict:
    meta = src.json("outcome_map_boundaries.json")
    grid = src.json("outcome_map.json")["grid"]
    rows_csv = src.csv("outcome_map.csv")
    bnd = src.csv("outcome_map_boundaries.csv")
    out = {
        "n_value": grid["n_value"],
        "n_d": grid["n_d"],
        "n_starts": grid["n_value"] * grid["n_d"],
        "n_sims": int(len(rows_csv) + bnd["n_sims"].sum()),
    }
    for key, label in (("a=1.5", "p"), ("a=0.6667", "o")):
        s = meta["summary"][key]
        c = s["counts"]
        out[f"{label}_stuck"], out[f"{label}_rise"], out[f"{label}_jump"] = c["stuck"], c["rise"], c["jump"]
        conv = [(dd, v) for dd, v, st in s["threshold_vs_d"] if st == "converged"]
        out[f"{label}_threshold_vs_d"] = ", ".join(
            f"{sig(v, 4)} (d = {sig(dd, 2)})" for dd, v in conv[:: max(1, len(conv) // 6)]
        )
        dm = [(v, dmin) for v, dmin, st in s["d_min_vs_value"] if st == "converged" and dmin is not None]
        prod = [dmin * v * v for v, dmin in dm if dmin < 0.05]
        out[f"{label}_dmin_v2"] = f"{fixed(max(prod), 3)} ... {fixed(min(prod), 3)}" if prod else ""
        out[f"{label}_dmin_span"] = (
            f"{sig(min(v for v, dmin in dm if dmin < 0.05), 3)} ... {sig(max(v for v, _ in dm), 3)}"
        )
        out[f"{label}_rise_fraction"] = rng(*s["rise_fraction_range"], f=lambda x: fixed(x, 2))
        g = s["grid_disagreements"]
        out[f"{label}_checked"], out[f"{label}_contradicting"] = g["checked"], g["contradicting"]
    out["counts_table"] = table(
        ["map", "starts", "stuck (rolls)", "rise without a jump", "jump"],
        [
            [f"a = {a}", out["n_starts"], out[f"{k}_stuck"], out[f"{k}_rise"], out[f"{k}_jump"]]
            for a, k in (("1.5", "p"), ("2/3", "o"))
        ],
    )
    return out


# -- the paper's printed pairs (studies/paper_pairs.py) --------------------------------------------


def _eps(e, digits: int = 1) -> str:
    return "exact" if pd.isna(e) else sci(e, digits)


@group("pairs")
def pairs(src: Sources) -> dict:
    d = src.csv("paper_pairs.csv")
    meta = src.json("paper_pairs.json")
    out = {"t_end": f"{meta['t_end']:g}", "n_eps": len(meta["eps"])}
    e = d[d["chart"] == "euler"]

    def runs(label, value):
        return e[(e["label"] == label) & np.isclose(e["value"], value)].sort_values(
            "eps", ascending=False, na_position="last"
        )

    r52 = runs(5.2, 10.5)
    exact = r52[r52["eps"].isna()].iloc[0]
    out["p52_exact"] = f"{exact['outcome']} (theta = {fixed(exact['theta_end'], 4)} at t = {exact['t_end']:g})"
    for eps_ in (1e-2, 1e-3, 1e-4):
        r = r52[np.isclose(r52["eps"], eps_)].iloc[0]
        out[f"p52_eps{sci(eps_, 0)}"] = fixed(r["t_jump"], 2)
    jumped = r52[r52["outcome"] == "jump"]
    stuck = r52[(r52["outcome"] == "stuck") & r52["eps"].notna()]
    out["p52_last_jump"] = (
        f"eps = {sci(jumped['eps'].min(), 1)} jumps at {fixed(jumped.loc[jumped['eps'].idxmin(), 't_jump'], 1)}"
    )
    out["p52_stuck_below"] = sci(stuck["eps"].max(), 1)
    r51 = runs(5.1, 10.5)
    ex51 = r51[r51["eps"].isna()].iloc[0]
    out["p51_exact"] = f"{ex51['outcome']} at theta = {sci(ex51['theta_end'], 0)}"
    # as printed: Fig. 3's n0 = 10 rises and 10.5 jumps near 91; Fig. 4's 10.2 rises and 10.5 jumps near 111
    for fig, label, lo, hi in (("3", 5.1, 10.0, 10.5), ("4", 5.2, 10.2, 10.5)):
        keys = [k for k in meta["as_printed"] if k.startswith(f"{label}|")]
        printed = sorted({float(x) for k in keys for x in meta["as_printed"][k]})
        charts = [k.split("|")[1] for k in keys if meta["as_printed"][k]]
        a, b = runs(label, lo), runs(label, hi)
        if printed:
            ok = b[np.isclose(b["eps"], printed[0])].iloc[0]
            out[f"fig{fig}"] = (
                f"as printed only at eps = {', '.join(sci(x, 1) for x in printed)} "
                f"({' and '.join(charts)} chart{'s' if len(charts) > 1 else ''}; t* = {fixed(ok['t_jump'], 2)})"
            )
        else:
            both = a.merge(b, on="eps", suffixes=("_lo", "_hi"))
            jj = both[(both["outcome_lo"] == "jump") & (both["outcome_hi"] == "jump")]
            only_hi = both[(both["outcome_hi"] == "jump") & (both["outcome_lo"] != "jump")]
            near = jj.iloc[(jj["t_jump_hi"] - 111.0).abs().argsort()[:1]] if len(jj) else jj
            text = "for no eps in either chart"
            if len(only_hi) == 0 and len(jj):
                n = near.iloc[0]
                text += (
                    f": whenever {hi:g} jumps, {lo:g} jumps too (eps = {sci(n['eps'], 1)}: "
                    f"{fixed(n['t_jump_hi'], 2)} and {fixed(n['t_jump_lo'], 2)})"
                )
            out[f"fig{fig}"] = text
        st = b[(b["outcome"] == "stuck")]
        out[f"fig{fig}_stuck"] = f"eps <= {sci(st['eps'].max(), 1)}" if st["eps"].notna().any() else ""
        bad = d[(d["label"] == label)].pivot_table(
            index=["value", "eps"], columns="chart", values="outcome", aggfunc="first"
        )
        out[f"fig{fig}_chart_disagreements"] = int((bad["euler"] != bad["vector"]).sum())
    return out


# -- the paper's theory against the simulation (sections 3, 4, 6, 7) -------------------------------


def _pk(name: str):
    """A closed form of the paper, wherever phasekit keeps it (top level or phasekit.theory)."""
    import phasekit as pk

    if hasattr(pk, name):
        return getattr(pk, name)
    import importlib

    return getattr(importlib.import_module("phasekit.theory"), name)


@group("theory")
def theory(src: Sources) -> dict:
    out = {}
    # Fig. 2: where Sigma (3.64) first reaches zero, from the closed forms (computed, no simulation)
    import phasekit as pk

    body = pk.Spheroid(1.5)
    theta0, c = np.pi / 2 - 1e-4, -0.00054
    theta = np.linspace(theta0, 0.02, 1500)
    first = {}
    for J in (6.63, 6.83, 7.15, 8.45, 13.0):
        sg = np.asarray(_pk("Sigma")(body, J, theta0, theta, c, form="closed"))
        k = np.flatnonzero(sg <= 0)
        first[J] = None if k.size == 0 else float(theta[k[0]])
    neg = [J for J, z in first.items() if z is not None]
    pos = [J for J, z in first.items() if z is None]
    out["fig2"] = (
        f"first negative for J between {max(pos):g} and {min(neg):g}"
        if pos and neg
        else "; ".join(f"J = {J:g}: {'no zero' if z is None else fixed(z, 3)}" for J, z in first.items())
    )
    # J = A Omega h for Figs. 3 and 4
    obl, pro = pk.Spheroid(2 / 3), pk.Spheroid(1.5)
    out["J_fig3"] = ", ".join(fixed(obl.C * n0 * (2 / 3), 2) for n0 in (10.0, 10.5))
    out["J_fig3_Cn0"] = ", ".join(f"{obl.C * n0:g}" for n0 in (10.0, 10.5))
    out["J_fig4"] = ", ".join(fixed(pro.A * w * 1.0, 2) for w in (10.2, 10.5))
    # Fig. 5: the (4.23) estimate of the largest gap against the exact flight
    f5 = src.csv("figure5_gap.csv")
    flown = f5[f5["status"] == "touchdown"]
    out["fig5_n"] = len(flown)
    out["fig5_423_above"] = int((flown["gap_max_4_23"] > flown["bound"]).sum())
    out["fig5_exact_above"] = int((flown["gap_max_exact"] > flown["bound"]).sum())
    rel = (flown["gap_max_4_23"] / flown["gap_max_exact"] - 1).abs()
    med = rel.groupby(flown["omega0"]).median()
    out["fig5_median_error"] = (
        f"{pct(med.iloc[0], 0)} (Omega0 = {med.index[0]:g}) to {pct(med.iloc[-1], 0)} (Omega0 = {med.index[-1]:g})"
    )
    out["fig5_omega_range"] = f"{flown['omega0'].min():g}-{flown['omega0'].max():g}"
    out["fig5_members"] = int(f5.groupby("omega0").size().max())
    # section 6: the jump surface (6.3) at the crossings
    js = src.csv("jump_surface.csv")
    tr = src.csv("jump_surface_trend.csv")
    out["js_max_error"] = sci(js["rel_error_n"].max(), 1)
    out["js_trend_max_error"] = sci(tr["rel_error_n"].max(), 1)
    out["js_trend_n"] = len(tr)
    from scipy import stats

    slopes = {}
    for (b, dd), g in tr.groupby(["branch", "d"]):
        r = stats.linregress(np.log(g["start"]), np.log(g["rel_error_n"]))
        slopes[(b, dd)] = (r.slope, r.stderr, abs(r.rvalue))
    for b in ("prolate", "oblate"):
        s_ = slopes[(b, 0.01)]
        out[f"js_slope_{b}"] = f"{s_[0]:+.2f} +- {s_[1]:.2f}"
    out["js_max_r"] = fixed(max(v[2] for v in slopes.values()), 2)
    out["js_slopes_table"] = table(
        ["branch", "seed distance d", "starts", "slope of log error vs log start", "|r|"],
        [
            [
                b,
                f"{dd:g}",
                int(((tr["branch"] == b) & np.isclose(tr["d"], dd)).sum()),
                f"{v[0]:+.2f} +- {v[1]:.2f}",
                fixed(v[2], 2),
            ]
            for (b, dd), v in sorted(slopes.items())
        ],
    )
    for b, w in (("prolate", 10.0), ("oblate", 10.0)):
        r = js[(js["branch"] == b) & np.isclose(js["start"], w)]
        out[f"js_{b}_10"] = fixed(r["t_cross"].iloc[0], 2) if len(r) else ""
    # section 7: effective friction with bouncing
    bo = src.csv("bouncing.csv")
    mu0 = 0.1
    bounced = bo[bo["n_impact"] > 0]
    out["mu_e_range"] = rng(bounced["mu_e"].min() / mu0, bounced["mu_e"].max() / mu0, lambda x: fixed(x, 2))
    out["mu_e_by_omega"] = "; ".join(
        f"{rng(g['mu_e'].min() / mu0, g['mu_e'].max() / mu0, lambda x: fixed(x, 3))} (Omega0 = {w:g})"
        for w, g in bounced.groupby("omega0")
    )
    out["flight_fraction"] = rng(
        bounced["flight_fraction"].min(), bounced["flight_fraction"].max(), lambda x: pct(x, 0)
    )
    out["max_impacts"] = int(bounced["n_impact"].max())
    out["mu_e_naive"] = rng(
        1 - bounced["flight_fraction"].max(), 1 - bounced["flight_fraction"].min(), lambda x: fixed(x, 2)
    )
    # Figs. 3, 4: the envelope against the simulated minima of R
    env = src.csv("envelope_vs_simulation.csv")
    erows = []
    for case, g in env.groupby("case", sort=False):
        rms = float(np.sqrt(np.mean((g["sigma"] - g["r_min_sim"]) ** 2)))
        erows.append(
            [case, len(g), sig(g["c"].iloc[0], 2), fixed(g["c_eff"].iloc[0] / g["c"].iloc[0], 2), fixed(rms, 3)]
        )
    out["envelope_table"] = table(
        ["case", "minima of R", "c (3.46)", "c_eff / c", "RMS(Sigma - simulated minima)"], erows
    )
    return out


# -- bodies: the tippe top and eggs (studies/tippe_top.py, egg.py, egg_jumps.py) ----------------------


@group("tippe")
def tippe(src: Sources) -> dict:
    s = src.json("tippe_top_summary.json")
    m = src.csv("tippe_top_map.csv")
    conv = src.csv("tippe_top_convergence.csv")
    out = {"n_runs": s["n_runs"], "n_failed": s["n_failed"], "jellett_drift": sci(s["max_jellett_drift"], 1)}
    vis, cou = m[m["law"] == "viscous"], m[m["law"] != "viscous"]
    out["viscous_n"] = len(vis)
    out["viscous_agree"] = int((vis["outcome"] == vis["predicted"]).sum())
    part = vis[(vis["outcome"] == "partial") & (vis["predicted"] == "partial")]
    err = (part["theta_end"] - part["theta_f_predicted"]).abs()
    out["viscous_partial_n"] = len(part)
    out["viscous_partial_err_max"] = sci(err.max(), 0)
    out["viscous_partial_err_median"] = sci(err.median(), 0)
    out["viscous_R_min"] = sci(vis["R_min"].min(), 1)
    c = s["coulomb"]
    out["coulomb_n"], out["coulomb_agree"], out["coulomb_disagree"] = c["n"], c["agree"], c["disagree"]
    out["coulomb_hopped"], out["coulomb_full"] = c["hopped"], c["by_outcome"]["full"]
    less = cou[(cou["outcome"] != cou["predicted"])]
    order = {"never": 0, "partial": 1, "full": 2}
    out["coulomb_all_less"] = (
        "all" if all(order[o] <= order[p] for o, p in zip(less["outcome"], less["predicted"])) else "not all"
    )
    out["hop_by_n0"] = ", ".join(
        f"{int(((cou['n0'] == n0) & (cou['n_liftoff'] > 0)).sum())} of {int((cou['n0'] == n0).sum())} at n0 = {n0:g}"
        for n0 in sorted(cou["n0"].unique())
    )
    out["alphas"] = ", ".join(f"{x:g}" for x in sorted(m["alpha"].unique()))
    out["gammas"] = f"{m['gamma'].min():g} ... {m['gamma'].max():g}"
    out["n0s"] = ", ".join(f"{x:g}" for x in sorted(m["n0"].unique()))
    # the README example converges in rtol and eps
    conv = conv.assign(eps_label=[_eps(e, 0) for e in conv["eps"]])
    rt = sorted(conv["rtol"].unique(), reverse=True)
    rows = []
    for e in list(dict.fromkeys(conv["eps_label"])):
        g = conv[conv["eps_label"] == e].set_index("rtol")["t_stop"]
        rows.append([e, *(f"{g.loc[r]:.15f}" for r in rt)])
    out["convergence_table"] = table(["eps \\ rtol", *(sci(r, 0) for r in rt)], rows)
    tight = conv[conv["rtol"] <= 1e-10]["t_stop"]
    out["t_stop"] = f"{tight.mean():.11f} +- {sci(max(tight.max() - tight.mean(), tight.mean() - tight.min()), 0)}"
    return out


@group("egg")
def egg(src: Sources) -> dict:
    s = src.json("egg_summary.json")
    we = s["which_end"]
    out = {
        "n": we["n"],
        "rose": we["rose"],
        "as_predicted": we["as_predicted"],
        "stuck": len(we["stuck_at_start"]),
        "failed": len(we["failed"]),
    }
    ends = src.csv("egg_which_end.csv")
    h = ends.groupby(["w", "omega0"])["theta_h"].first()
    out["theta_h_w05"] = fixed(h.loc[(0.05, 6.0)] - np.pi / 2, 2)
    out["theta_h_table"] = ", ".join(
        f"{fixed(h.loc[(w, 6.0)] - np.pi / 2, 3)} (w = {w:g})"
        for w in sorted(ends["w"].unique())
        if w > 0 and (w, 6.0) in h.index
    )
    rose = ends[(ends["end"] == "fat") & ~ends["key"].isin(we["stuck_at_start"])]  # onto the fat end
    tilt = rose.groupby("w")["theta_reached"].agg(["min", "max"])
    out["settle_w05"] = rng(tilt.loc[0.05, "min"], tilt.loc[0.05, "max"], lambda x: fixed(x, 2))
    out["settle_w10"] = rng(tilt.loc[0.1, "min"], tilt.loc[0.1, "max"], lambda x: fixed(x, 2))
    up = tilt[tilt["max"] < 0.17]
    out["upright_w_max"] = f"{up.index.max():g}"
    thr = pd.DataFrame(s["threshold"])
    rows = []
    for start, g in thr.groupby("start", sort=False):
        rows.append([start, *(fixed(v, 2) if st == "converged" else st for v, st in zip(g["threshold"], g["status"]))])
    ws = thr.groupby("start", sort=False).first().index
    out["threshold_table"] = table(["start", *(f"w = {w:g}" for w in thr[thr["start"] == ws[0]]["w"])], rows)
    width = ((thr["bracket_hi"] - thr["bracket_lo"]) / thr["threshold"]).max()
    out["threshold_width"] = sci(width, 0)
    spread = thr.groupby("start")["threshold"].agg(lambda v: v.max() / v.min() - 1).max()
    out["threshold_spread"] = pct(spread, 0)
    chk = s["default_definition_check"]
    out["default_check"] = "; ".join(
        f"w = {c['w']:g}: {fixed(c['egg_definition'], 3)} vs {fixed(c['default_definition'], 3)}" for c in chk
    )
    ru = pd.DataFrame(s["real_units"])
    out["scale"] = s["scale"]
    for w in (0.0, 0.05):
        r = ru[(ru["w"] == w) & (ru["case"] == "1.02 x threshold")].iloc[0]
        out[f"thr_rev_w{w:g}"] = sig(r["spin_rev_per_s"] / 1.02, 3)  # the 1.02 x threshold row names it
    rrows = [
        [
            f"{r.w:g}",
            r.case,
            fixed(r.spin_rev_per_s, 1),
            r.status,
            fixed(r.flight_ms, 1) if pd.notna(r.flight_ms) else "",
            sig(r.gap_max_mm, 2) if pd.notna(r.gap_max_mm) else "",
        ]
        for r in ru.itertuples()
    ]
    out["real_units_table"] = table(["w", "spin", "rev/s", "outcome", "first flight (ms)", "largest gap (mm)"], rrows)
    # jumps against experiment
    j = src.csv("egg_jumps.csv")
    jm = src.json("egg_jumps.json")
    base = jm["base"]
    out["base_first"] = f"{fixed(base['first_flight_ms'], 1)} ms, {sig(base['first_gap_mm'], 2)} mm"
    out["base_longest"] = (
        f"{fixed(base['longest_flight_ms'], 1)} ms / {sig(base['largest_gap_mm'], 2)} mm "
        f"({base['n_flights']} flights, {base['n_gap_over_0.05mm']} above 0.05 mm)"
    )
    hi = jm["base_rtol_1e-12"]
    out["base_rtol_check"] = sci(abs(hi["largest_gap_mm"] / base["largest_gap_mm"] - 1), 0)
    out["base_rev"], out["base_mu"], out["base_e"] = f"{base['rev']:g}", f"{base['mu']:g}", f"{base['e']:g}"
    lrows = []
    for lever, g in j.groupby("lever", sort=False):
        if lever.startswith("base"):
            continue
        first = ", ".join(
            f"{fixed(r.first_flight_ms, 1)} ms / {sig(r.first_gap_mm * 1000, 2)} um"
            if pd.notna(r.first_flight_ms)
            else "no jump"
            for r in g.itertuples()
        )
        most = ", ".join(
            f"{fixed(r.longest_flight_ms, 1)} ms / {sig(r.largest_gap_mm, 2)} mm"
            if pd.notna(r.longest_flight_ms)
            else "no jump"
            for r in g.itertuples()
        )
        lrows.append([f"{lever} " + ", ".join(f"{v:g}" for v in g["value"]), first, most])
    out["levers_table"] = table(
        ["lever (values)", "first flight: duration / gap", "longest flight / largest gap of the run"], lrows
    )
    ok = j[~j["lever"].str.startswith("base") & j["largest_gap_mm"].notna()]
    mid = ok[(ok["lever"] != "friction mu") & ~((ok["lever"] == "restitution") & (ok["value"] > 0.5))]
    out["hop_gap_range"] = rng(mid["largest_gap_mm"].min(), mid["largest_gap_mm"].max(), lambda x: fixed(x, 2))
    out["hop_ms_range"] = rng(mid["longest_flight_ms"].min(), mid["longest_flight_ms"].max(), lambda x: fixed(x, 0))
    out["first_gap_range_um"] = rng(
        ok["first_gap_mm"].min() * 1000, ok["first_gap_mm"].max() * 1000, lambda x: f"{x:.2g}"
    )
    out["first_ms_range"] = rng(ok["first_flight_ms"].min(), ok["first_flight_ms"].max(), lambda x: fixed(x, 1))
    ff = pd.DataFrame(jm["first_flights"])
    out["first_flights"] = "; ".join(
        f"{fixed(r.rev, 1)} rev/s: {fixed(r.flight_ms, 1)} ms, {sig(r.gap_um, 2)} um" for r in ff.itertuples()
    )
    out["movie_gap"] = f"{sig(jm['movie']['gap_mm'], 2)} mm, {fixed(jm['movie']['flight_ms'], 1)} ms"
    return out


# -- performance (studies/work_precision.py, stiff_extreme.py, benchmarks/) ---------------------------

#: the integration benchmark's ratios, as its report names them: (key, what, its goal's key, the goal's sense)
BENCH_RATIOS = [
    ("ratio_scipy_bdf_sweep", "scipy BDF (NumPy rhs, rtol 1e-9) / phasekit's sweep path (rtol 1e-8)", "scipy_bdf", ">="),
    ("ratio_scipy_bdf_default", "scipy BDF / phasekit with the default options (dense output, every minimum of R)", None, ""),
    ("ratio_sweep_bare_heyoka", "phasekit's sweep path / bare heyoka `propagate_until` (rtol 1e-9)", "bare_heyoka", "<="),
    ("ratio_default_bare_heyoka", "phasekit's default options / bare heyoka (rtol 1e-9)", None, ""),
    ("ratio_default_sweep", "phasekit's default options / its sweep path (rtol 1e-9)", "default_sweep", "<="),
    ("ratio_rolling_sliding", "a rolling trajectory / a sliding one of the same length", "rolling_sliding", "<="),
]

NOT_MEASURED = "not measured"


def _bench(src: Sources, name: str) -> dict | None:
    """A benchmark's report in docs/data/, or None when it has not been measured (the page says so)."""
    try:
        return src.report(name)
    except LookupError:
        return None


def _bench_note(b: dict | None, name: str, extra: str = "") -> str:
    """Markdown: the command as code (a role's plain text would get its ``--`` turned into a dash)."""
    if b is None:
        return f"{NOT_MEASURED.capitalize()}: `docs/data/{name}` is not there (the benchmark writes it with `--report`)."
    return f"Measured by `{b['command']}` on {b['machine']}, {b['measured']} (commit {b['commit']}{extra}):"


def _bench_block(prefix: str, note: str, rows: list | None, header: list[str]) -> dict:
    """``<prefix>_note``, ``<prefix>_table`` and ``<prefix>_report`` (the note above the table, the page's block)."""
    t = table(header, rows) if rows is not None else ""
    return {f"{prefix}_note": note, f"{prefix}_table": t, f"{prefix}_report": f"{note}\n\n{t}".strip()}


def _goal_row(r: dict, what: str, shown: str, value: float, goal: str | None, sense: str, unit: str = "") -> list:
    """A table row: what, the measured value as shown, its goal and whether this run met it."""
    g = r.get("goals", {}).get(goal) if goal else None
    if g is None:
        return [what, shown, "", ""]
    met = r.get("goals_met", {}).get(goal)
    if met is None:  # a report from before the goal was checked by the benchmark
        met = value >= g if sense == ">=" else value <= g
    return [what, shown, f"{sense} {g:g}{unit}", "yes" if met else "**no**"]


def _bench_performance(src: Sources) -> dict:
    b = _bench(src, "bench_performance.json")
    if b is None:
        return _bench_block("bench", _bench_note(b, "bench_performance.json"), None, [])
    r = dict(b["result"])
    # the same two medians the benchmark divides (older reports have the times, not the ratio)
    r.setdefault("ratio_default_sweep", r["default_rtol1e-9_ms"] / r["sweep_rtol1e-9_ms"])
    rows = [[f"sweep path (rtol {sci(r['phasekit_rtol'], 0)}), one run to the jump", f"{sig(r['sweep_ms'], 2)} ms", "", ""],
            [f"default options (rtol {sci(r['phasekit_rtol'], 0)})", f"{sig(r['default_ms'], 2)} ms", "", ""],
            ["scipy BDF on a NumPy right-hand side (rtol 1e-9)", f"{sig(r['scipy_bdf_ms'], 3)} ms", "", ""]]
    rows += [_goal_row(r, what, sig(r[key], 3), r[key], goal, sense) for key, what, goal, sense in BENCH_RATIOS if key in r]
    return _bench_block("bench", _bench_note(b, "bench_performance.json", f"; median of {r['repeats']} interleaved runs"),
                        rows, ["standard prolate workload, to the jump", "measured", "goal", "met"])


def _bench_sweep(src: Sources) -> dict:
    b = _bench(src, "bench_threshold_sweep.json")
    if b is None:
        return _bench_block("sweep", _bench_note(b, "bench_threshold_sweep.json"), None, [])
    r = b["result"]
    rows = [["simulations", f"{r['simulations']} ({r['searches']} searches, {r['grid']} grid)", "", ""],
            ["critical path", f"{r['critical_path']} rounds", "", ""],
            _goal_row(r, "parallelism (simulations / critical path)", sig(r["parallelism"], 3), r["parallelism"],
                      "parallelism", ">="),
            ["wall time serial", f"{sig(r['wall_serial_s'], 3)} s", "", ""],
            ["wall time on 2 workers", f"{sig(r['wall_dask_s'], 3)} s (cluster start {sig(r['cluster_start_s'], 2)} s more)",
             "", ""],
            _goal_row(r, "efficiency: serial / (2 x 2 workers)", fixed(r["efficiency"], 2), r["efficiency"], "efficiency", ">="),
            ["same thresholds serial and on 2 workers", "yes" if r["same_thresholds_serial_and_dask"] else "**no**", "", ""],
            _goal_row(r, "default Fig. 6b,c curves on 2 workers", f"{sig(r['default_curve_wall_s'], 3)} s",
                      r["default_curve_wall_s"], "default_curve_wall_s", "<=", " s")]
    return _bench_block("sweep", _bench_note(b, "bench_threshold_sweep.json"), rows,
                        ["the (a, mu) map", "measured", "goal", "met"])


def _bench_structure(src: Sources) -> dict:
    b = _bench(src, "bench_steady_structure.json")
    if b is None:
        return _bench_block("structure", _bench_note(b, "bench_steady_structure.json"), None, [])
    r = b["result"]
    n = len(r["structure_wall_s"])
    rows = [[f"one body's structure (the slowest of {n} pairs of body and law, median of 5 calls)",
             f"{sig(r['structure_worst_s'] * 1e3, 3)} ms", "", ""],
            ["atlas", f"{r['bodies']} bodies, {r['boundary_points']} boundary points ({r['grid']} atlas)", "", ""],
            ["atlas wall time serial", f"{sig(r['atlas_wall_serial_s'], 3)} s", "", ""],
            ["atlas wall time on 2 workers", f"{sig(r['atlas_wall_dask_s'], 3)} s (cluster start "
             f"{sig(r['cluster_start_s'], 2)} s more)", "", ""],
            _goal_row(r, "efficiency: serial / (2 x 2 workers)", fixed(r["efficiency"], 2), r["efficiency"], "efficiency", ">="),
            ["same signatures serial and on 2 workers", "yes" if r["same_signatures_serial_and_dask"] else "**no**", "", ""]]
    return _bench_block("structure", _bench_note(b, "bench_steady_structure.json"), rows,
                        ["steady-state structure", "measured", "goal", "met"])


def _bench_first_run(src: Sources) -> dict:
    b = _bench(src, "bench_first_run.json")
    if b is None:
        return _bench_block("first_run", _bench_note(b, "bench_first_run.json"), None, [])
    r = b["result"]
    rows = [[f"{name}: `{v['command']}`", f"{fixed(v['first_s'], 1)} s", f"{fixed(v['second_s'], 1)} s", str(v["notices"]), ""]
            for name, v in r["bodies"].items()]
    what, shown, goal, met = _goal_row(r, "the slowest first run", f"{fixed(r['worst_first_s'], 1)} s", r["worst_first_s"],
                                       "first_s", "<=", " s")
    rows.append([what, shown, "", "", f"{goal}: {met}"])
    return _bench_block("first_run", _bench_note(b, "bench_first_run.json"), rows,
                        ["body: command", "first run (empty caches)", "second run", "compile notices on stderr", "goal: met"])


def _study_profile(t) -> dict:
    """Where the main study's task time goes, by threshold definition (its committed table keeps
    each search's simulations and wall time)."""
    t = t.assign(sims=t["n_sims"] + t["n_check_sims"])
    g = t.groupby("name", sort=False).agg(points=("a", "size"), sims=("sims", "sum"), task=("wall_s", "sum"),
                                          longest=("wall_s", "max"))
    g = g.sort_values("task", ascending=False)
    total = float(g["task"].sum())
    rows = [[name, int(r.points), int(r.sims), sig(r.task, 3), f"{100 * r.task / total:.0f}%", sig(r.longest, 3)]
            for name, r in g.iterrows()]
    return {"study_task_s": sig(total, 3), "study_sims": int(g["sims"].sum()),
            "study_table": table(["definition", "points", "simulations", "task time (s)", "share", "longest search (s)"], rows)}


@group("performance")
def performance(src: Sources) -> dict:
    w = src.csv("work_precision.csv")
    ok = w[w["status"] == "ok"]
    out = {}
    for wl, key in (("prolate", "prolate"), ("oblate", "oblate")):
        sel = ok[ok["workload"].str.startswith(wl)]
        rows = []
        for method in dict.fromkeys(w["method"]):
            cells = []
            for tol in (1e-6, 1e-9):
                m = sel[(sel["method"] == method) & (sel["error"] <= tol)]
                if len(m):
                    r = m.loc[m["wall_s"].idxmin()]
                    cells.append(f"{sig(r['wall_s'] * 1e3, 3)} ms (rtol {sci(r['rtol'], 0)})")
                else:
                    cells.append("not reached")
            rows.append([method, *cells])
        out[f"{key}_workload"] = sel["workload"].iloc[0] if len(sel) else ""
        out[f"{key}_table"] = table(["method", "error <= 1e-6", "error <= 1e-9"], rows)
    out["n_capped"] = int((w["status"] == "capped").sum())
    s = src.csv("stiff_extreme.csv")
    out["stiff_n"] = len(s)
    out["stiff_status"] = ", ".join(f"{k} {v}" for k, v in Counter(s["status"]).most_common())
    out["stiff_all_finite"] = "yes" if s["finite"].astype(str).eq("True").all() else "no"
    inv = s[s["case"].str.startswith("mu = 0")]
    out["stiff_drift"] = sci(inv["invariant_drift"].max(), 0)
    fail = s[s["status"] == "failed"]
    out["stiff_failed"] = "; ".join(f"{r.case}: {r.reason}" for r in fail.itertuples()) or "none"
    out.update(_study_profile(src.csv("threshold_vs_aspect.csv")))
    for bench in (_bench_performance, _bench_sweep, _bench_structure, _bench_first_run):
        out.update(bench(src))
    return out


# -- robustness (tests/cli/test_generated_command_lines.py, tests/contracts/test_generated_api_calls.py)

OUTCOMES = [("valid", "valid result"), ("failed", "failed, with a reason"), ("error", "clear error")]


def _fuzz_table(rep: dict) -> tuple[str, int, dict]:
    rows = []
    for name in sorted(rep["suites"]):
        c = rep["suites"][name]
        rows.append([name, *(c.get(k, 0) for k, _ in OUTCOMES)])
    total = rep["total"]
    n = sum(total.get(k, 0) for k, _ in OUTCOMES)
    extra = {k: v for k, v in total.items() if k not in dict(OUTCOMES)}
    rows.append([f"**total: {n} cases**", *(f"**{total.get(k, 0)}**" for k, _ in OUTCOMES)])
    return table(["cases", *(label for _, label in OUTCOMES)], rows), n, extra


@group("robustness")
def robustness(src: Sources) -> dict:
    out = {}
    for key, name in (("cli", "fuzz.json"), ("api", "fuzz.api.json")):
        rep = src.report(name)
        t, n, extra = _fuzz_table(rep)
        out[f"{key}_table"], out[f"{key}_n"] = t, n
        out[f"{key}_other"] = sum(extra.values())
        out[f"{key}_scale"] = f"{rep.get('scale', 1):g}"
    return out


# -- the reproduction table: the paper against phasekit, with the measurement where they differ ------


@group("repro")
def repro(src: Sources) -> dict:
    p, a, m, t, e = (values(src, g) for g in ("pairs", "aspect", "mu", "theory", "egg"))
    rows = [
        [
            "start (5.2), Omega0 = 10.5",
            "rises, jumps at t* ~ 111 (Fig. 4b)",
            f"exact Coulomb: {p['p52_exact']}; regularised: eps = 1e-2 jumps at {p['p52_eps1e-2']}, 1e-3 at "
            f"{p['p52_eps1e-3']}, 1e-4 at {p['p52_eps1e-4']}; {p['p52_last_jump']}; eps <= {p['p52_stuck_below']}: "
            f"sticks, no jump to t = {p['t_end']}",
            "paper_pairs.csv",
        ],
        [
            "start (5.2) vs the unstable eigenvector",
            '"approximately" the unstable direction',
            "rounds to the horizontal state + 0.02 x the viscous unstable eigenvector in every component, but the two "
            "starts jump at different times",
            "gallery: paper_start_rounding.py",
        ],
        [
            "Fig. 3 pair (5.1): n0 = 10 / 10.5, regularised",
            "10 rises, 10.5 jumps at t* ~ 91",
            f"{p['fig3']}; exact Coulomb and {p['fig3_stuck']}: both stick",
            "paper_pairs.csv",
        ],
        [
            "Fig. 4 pair (5.2): Omega0 = 10.2 / 10.5, regularised",
            "10.2 rises, 10.5 jumps at t* ~ 111",
            f"{p['fig4']}; exact Coulomb and {p['fig4_stuck']}: both stick",
            "paper_pairs.csv",
        ],
        ["start (5.1), n0 = 10.5", "jumps at t* ~ 91 (Fig. 3d)", f"exact Coulomb: {p['p51_exact']}", "paper_pairs.csv"],
        [
            "prolate a = 1.5 threshold",
            "10.2 < Omega0* < 10.5 (Fig. 4, delta ~ 0.02)",
            f"literal recipe, eps = 1e-3: {a['a15_literal-eps1e-3']}; eps = 1e-4: {a['a15_literal-eps1e-4']}; exact: "
            f"{a['a15_literal-exact']}; default (sliding branch, d = 0.01): {a['a15']}",
            "threshold_vs_aspect.csv",
        ],
        [
            "oblate a = 2/3 threshold",
            "10 < n0* < 10.5 (Fig. 3, delta ~ 1e-5)",
            f"literal recipe, eps = 1e-3: {a['a23_literal-eps1e-3']}; exact: {a['a23_literal-exact']}; "
            f"default: {a['a23']}",
            "threshold_vs_aspect.csv",
        ],
        [
            "Fig. 6b,c trend",
            "thresholds rise as a -> 1",
            f"rise toward a = 1 on both branches: {a['prolate_at2']} ... {a['prolate_near1']}; {a['oblate_far']} ... "
            f"{a['oblate_near1']}; shallow minima {a['prolate_min']} and {a['oblate_min']}; every value depends on the "
            f"seed distance d (a = 1.5, d = 0.005 / 0.01 / 0.02: {a['d_spread_a15']})",
            "threshold_vs_aspect.csv",
        ],
        [
            "threshold against friction",
            "mu = 0.1 only",
            f"within {m['within_mid']} of mu = 0.1 for mu = {m['mid_range']}, up to {m['rise_500']} at mu = 0.5 "
            "(starts stick); no collapse with one factor f(mu)",
            "threshold_vs_mu.csv",
        ],
        [
            "Fig. 2",
            "Sigma's minimum falls with J and turns negative",
            f"same; {t['fig2']} (theta-bar0 = pi/2 - 1e-4)",
            "closed forms, computed",
        ],
        [
            "Fig. 3 (a = 2/3, n0 = 10)",
            "rises without jumping",
            f"from the sliding branch (d = 0.01) it jumps, at t* = {t['js_oblate_10']} (a different start; the "
            "printed one "
            "sticks)",
            "jump_surface.csv",
        ],
        [
            "Fig. 4a (a = 1.5, Omega0 = 10.2)",
            "rises without jumping",
            f"from the sliding branch (d = 0.01) already Omega0 = 10 jumps, at t* = {t['js_prolate_10']} (threshold "
            f"{a['a15']})",
            "jump_surface.csv",
        ],
        [
            "J in Figs. 3, 4",
            "4, 4.2; 6.63, 6.83",
            f"A Omega h: {t['J_fig3']} (the quoted oblate values are C n0 = {t['J_fig3_Cn0']}); {t['J_fig4']}",
            "closed form (3.17)",
        ],
        [
            "(4.23) against the exact flight",
            "differences decrease with Omega0 (Fig. 5a-c)",
            f"median relative error of the largest gap {t['fig5_median_error']}, {t['fig5_members']} perturbed starts "
            "per Omega0",
            "figure5_gap.csv",
        ],
        [
            "Fig. 5d bound (4.65/Omega0)^5",
            "bounds the (4.23) points",
            f"{t['fig5_423_above']} of {t['fig5_n']} (4.23) points above it; {t['fig5_exact_above']} of {t['fig5_n']} "
            "exact maxima above it",
            "figure5_gap.csv",
        ],
        [
            "(6.3) detects the jump",
            '"very well", better with Omega0',
            f"relative error in n <= {t['js_max_error']} (<= {t['js_trend_max_error']} over {t['js_trend_n']} "
            "starts); no "
            f"trend in Omega0 (fitted slope {t['js_slope_prolate']} prolate, {t['js_slope_oblate']} oblate)",
            "jump_surface.csv, jump_surface_trend.csv",
        ],
        [
            "effective friction with bouncing (section 7)",
            "conjecture: mu_e somewhat below mu",
            f"mu_e / mu = {t['mu_e_range']}",
            "bouncing.csv",
        ],
        [
            "egg jumps (Mitsui et al. 2006, cited)",
            'abstract: "the durations of the first loss of contact are measured"; as Science News reported it: '
            '"a fraction of a millimeter off the surface for up to a few hundredths of a second" at up to 2,500 rpm '
            "(our reading: 0.05-0.5 mm, 5-30 ms)",
            f"hen's-egg-sized body (57 x 43 mm, uniform, mu = 0.1): thresholds {e['thr_rev_w0.05']}-{e['thr_rev_w0']} "
            f"rev/s; first flights {e['first_gap_range_um']} micrometres; the highest hops, late in the rise, "
            f"{e['hop_gap_range']} mm for {e['hop_ms_range']} ms",
            "egg_real_units.csv, egg_jumps.csv",
        ],
        _euler_disk_row(src.json("euler_disk.json")["runs"]["air-layer"]),
    ]
    header = ["quantity", 'paper (its words "in quotes"; the rest our reading)', "phasekit (measured)", "data"]
    return {"table": table(header, rows), "n_rows": len(rows)}


def _euler_disk_row(air: dict) -> list:
    """Moffatt's air layer under Euler's disk against studies/euler_disk.py's run."""
    th, om = air["fit_theta"], air["fit_omega"]
    return [
        "Euler's disk, air layer (Moffatt 2000, cited)",
        'as the encyclopaedias quote him: "Omega ~ (t0 - t)^-1/6"; the tilt alpha ~ (t0 - t)^(1/3) and '
        f"t0 = {sig(air['t0_quasi_static'], 5)} for this launch are our reading of the same quasi-static balance",
        f"thin disk from 30 deg, k = {air['coefficient']:g}: alpha ~ (t0 - t)^{th['exponent']:.4f} +- {th['ci95']:.4f}, "
        f"Omega ~ (t0 - t)^{om['exponent']:.4f} +- {om['ci95']:.4f} over {air['decades']:.2f} decades; "
        f"t0 = {sig(air['t0_fit'], 5)} (the disk drifts off spinning in place)",
        "euler_disk.json",
    ]


# -- blocks of the README (tests/contracts/test_readme.py checks that the README holds them as generated) ------


@group("readme")
def readme(src: Sources) -> dict:
    s, r, e = values(src, "steady"), values(src, "robustness"), values(src, "egg")
    out = {
        "steady_counts": table(
            ["body", "classes of steady-state structure found", "part III"],
            [
                [
                    "spheroid with its centre of mass displaced along the axis",
                    s["spheroid_classes"],
                    s["part_iii_spheroid"],
                ],
                ["tippe top", s["tippe_classes"], s["part_iii_tippe"]],
            ],
        )
    }
    rows = []
    for key, label in (
        ("cli", "`tests/cli/test_generated_command_lines.py` (command lines)"),
        ("api", "`tests/contracts/test_generated_api_calls.py` (API calls)"),
    ):
        rep = src.report("fuzz.json" if key == "cli" else "fuzz.api.json")["total"]
        rows.append([label, r[f"{key}_n"], *(rep.get(k, 0) for k, _ in OUTCOMES), r[f"{key}_other"]])
    out["robustness_counts"] = table(
        ["generated cases", "cases", *(label for _, label in OUTCOMES), "anything else"], rows
    )
    out["egg_jumps"] = (
        f"A hen's-egg-sized body (57 x 43 mm, uniform, exact Coulomb mu = 0.1) first jumps at {e['thr_rev_w0']} rev/s "
        f"(w = 0; {e['thr_rev_w0.05']} rev/s with the asymmetry w = 0.05). Its first flights are micrometres high "
        f"({e['first_gap_range_um']} um over every lever tried: spin, friction, asymmetry, start), but it keeps "
        "hopping "
        f"through the rise, and its highest hops, late in the rise, leave the table by {e['hop_gap_range']} mm for "
        f"{e['hop_ms_range']} ms at any spin, start or asymmetry, with or without rebounds: inside our reading "
        "(0.05-0.5 mm, 5-30 ms) of Science News's report that the egg-shaped bodies of Mitsui et al. 2006 "
        '(Proc. R. Soc. A 462, 2897) "leaped a fraction of a millimeter off the surface for up to a few hundredths '
        'of a second". The paper\'s abstract says it measured "the durations of the first loss of contact", and '
        "phasekit's first flights are below that reading; the real bodies' friction and restitution are not known "
        "here."
    )
    return out
