"""Jump thresholds and the paper's printed pairs (studies/threshold_vs_aspect.py, threshold_vs_mu.py,
outcome_map.py, paper_pairs.py), for pkdocs.facts."""

from __future__ import annotations

import numpy as np
import pandas as pd

from .fmt import a_label, fixed, pct, rng, sci, sig, table
from .registry import group
from .sources import Sources

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
    _aspect_sensitivity(src, out)
    return out


def _aspect_sensitivity(src: Sources, out: dict) -> None:
    """The thresholds' sensitivity: relative change against the default (and the literal recipe against eps 1e-4)."""
    d = _aspect(src)
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
