"""The steady-state structure's values (studies/steady_structure.py), for pkdocs.facts."""

from __future__ import annotations

import pandas as pd

from .fmt import fixed, sci, sig, table
from .registry import group
from .sources import Sources

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
        **_egg_runs(s["egg"]),
        "scene_body": s["scene"]["body"],
    }
    out["classes_table"] = _classes_table(s, classes, atlas)
    out["bifurcations_table"] = _bifurcations_table(s, bounds)
    out["n_bifurcation_kinds"] = len(s["bifurcations"])
    return out


def _egg_runs(egg: dict) -> dict:
    """The egg's two runs (Omega0 = 6 and 10) set beside the structure."""
    r6, r10 = (next(r for r in egg["runs"] if r["omega0"] == w) for w in (6.0, 10.0))
    return {
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
    }


def _classes_table(s: dict, classes: dict, atlas: pd.DataFrame) -> str:
    """Which class where: the atlas rows per panel."""
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
    return table(
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


def _bifurcations_table(s: dict, bounds: pd.DataFrame) -> str:
    brows = []
    for name, pairs in s["bifurcations"].items():
        pts = bounds[bounds["bifurcation"] == name]
        brows.append(
            [name, "; ".join(f"`{p}`" for p in pairs), len(pts), sci(pts["width"].max(), 1) if len(pts) else ""]
        )
    return table(
        ["at the boundary", "classes on either side", "traced points", "widest bracket"], brows
    )
