"""The paper's theory against the simulation, and the bodies (the tippe top, eggs), for pkdocs.facts."""

from __future__ import annotations

import numpy as np
import pandas as pd

from .fmt import eps_label, fixed, pct, rng, sci, sig, table
from .registry import group
from .sources import Sources

# -- the paper's theory against the simulation (sections 3, 4, 6, 7) -------------------------------


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
        sg = np.asarray(pk.theory.reaction_envelope(body, J, theta0, theta, c, form="closed"))
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
    _theory_jump_surface(src, out)
    _theory_bouncing_envelope(src, out)
    return out


def _theory_bouncing_envelope(src: Sources, out: dict) -> None:
    """Section 7: the effective friction with bouncing; Figs. 3, 4: the envelope against the simulated minima of R."""
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


def _theory_jump_surface(src: Sources, out: dict) -> None:
    """Section 6: the jump surface (6.3) at the crossings, and the trend of its error."""
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
    conv = conv.assign(eps_label=[eps_label(e, 0) for e in conv["eps"]])
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
    _egg_jumps(src, out)
    return out


def _egg_jumps(src: Sources, out: dict) -> None:
    """The egg's jumps against experiment (studies/egg_jumps.py)."""
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
