"""Text reports of the threshold maps: what ``studies/threshold_vs_mu.py`` prints of its
(a, mu) map (:class:`phasekit.studies.SearchRow`), the collapse test and the thresholds against
the seed distance d, as lines of text (the tables themselves are :mod:`phasekit.studies.maps`').
"""

from __future__ import annotations

from .maps import seed_sensitivity_table, threshold_grid_table

__all__ = ["threshold_map_report"]


def threshold_map_report(rows, mus, collapse: dict, against_d: dict, *, d0: float, mu_ref: float) -> list[str]:
    """The lines of the report of an (a, mu) threshold map: the thresholds at seed distance
    ``d0`` over a and ``mus`` (:func:`phasekit.studies.threshold_grid_table`), the searches that
    did not converge (the first ten), the ``collapse`` test (:func:`phasekit.studies.threshold_collapse`:
    f(mu) and the spread that remains), the thresholds ``against_d``
    (:func:`phasekit.studies.threshold_against_d`) and, where measured, their sensitivity to the
    seed distance at ``mu_ref`` (:func:`phasekit.studies.seed_sensitivity_table`).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> lines = ps.threshold_map_report([], [0.1], {"prolate": {}, "oblate": {}}, {}, d0=0.01, mu_ref=0.1)
    >>> len(lines), lines[1]
    (4, 'not converged: 0 ')
    """
    main = [r for r in rows if r.d == d0]
    lines = [threshold_grid_table(main, mus)]
    bad = [r for r in rows if r.status not in ("converged",)]
    lines.append(f"not converged: {len(bad)} " + ", ".join(f"(a={r.a:.3g}, mu={r.mu:.3g}, d={r.d:g}: {r.status})" for r in bad[:10]))
    lines.append("collapse test, f(mu) and remaining spread (max |ln T/(f T_ref)|):")
    for branch in ("prolate", "oblate"):
        for mu, v in sorted(collapse[branch].items()):
            lines.append(f"  {branch:<8s} mu={mu:<7.3g} f={v['f']:.4f} spread={v['spread']:.4f} (f = 1: {v['raw_spread']:.4f})")
    lines.append("threshold against d (relative change per halving of d, from the largest d down):")
    for k, v in against_d.items():
        th = ", ".join(f"{t:.4f}" if t else s for t, s in zip(v["threshold"], v["status"]))
        ch = ", ".join(f"{c:+.3f}" if c is not None else "-" for c in v["change_per_halving"])
        lines.append(f"  {k}: d = {v['d']}: {th}; change per halving: {ch}")
    if any(r.sens_dominant for r in main):
        lines.append(f"sensitivity to the seed distance at mu = {mu_ref:g} (thresholds at d/2 and 2d; slope = d ln T*/d ln d):")
        lines.append(seed_sensitivity_table(main))
    return lines
