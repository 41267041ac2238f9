"""What the threshold studies read off their stored rows (:class:`phasekit.studies.ThresholdRow`,
:class:`phasekit.studies.SearchRow`) and print (a study-support module).

* :func:`threshold_collapse` and :func:`threshold_against_d`: thresholds over (a, mu) and against
  the seed distance.
* The stored rows as text tables (the studies' reports): :func:`threshold_table`,
  :func:`definition_sensitivity_table`, :func:`threshold_grid_table`, :func:`seed_sensitivity_table`.
* :func:`threshold_map_report`: what ``studies/threshold_vs_mu.py`` prints of its (a, mu) map:
  the table, the collapse test and the thresholds against the seed distance d, as lines of text.
"""

from __future__ import annotations

import math

import numpy as np


def threshold_collapse(rows, mus, ref_mu: float) -> dict:
    """The collapse test of thresholds over (a, mu) (``rows``: :class:`SearchRow` at one seed
    distance): are the thresholds at every mu one factor f(mu) times those at ``ref_mu``? Per
    branch and mu: f, the geometric mean over a of T(a, mu)/T(a, ref_mu); ``spread``, the
    largest ``|ln(T / (f T_ref))|`` that remains; ``raw_spread``, the same with f = 1; ``n``, the
    aspect ratios compared. Also the largest of each over everything (``max_spread``,
    ``max_raw_spread``; None without two aspect ratios to compare).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> rows = [Row(branch='prolate', a=a, mu=mu, threshold=t * (2 if mu == 0.5 else 1)) for a, t in ((1.5, 10.0), (2.0, 8.0))
    ...         for mu in (0.1, 0.5)]
    >>> c = ps.threshold_collapse(rows, [0.1, 0.5], 0.1)
    >>> round(c['prolate'][0.5]['f'], 6), round(c['max_spread'], 6)
    (2.0, 0.0)
    """
    out = {}
    for branch in ("prolate", "oblate"):
        ref = {r.a: r.threshold for r in rows if r.branch == branch and r.mu == ref_mu and r.threshold}
        per_mu = {}
        for mu in mus:
            ratios = [math.log(r.threshold / ref[r.a]) for r in rows
                      if r.branch == branch and r.mu == mu and r.threshold and r.a in ref]
            if len(ratios) < 2:
                continue
            lnf = float(np.mean(ratios))
            per_mu[mu] = {"f": math.exp(lnf), "spread": float(max(abs(x - lnf) for x in ratios)),
                          "raw_spread": float(max(abs(x) for x in ratios)), "n": len(ratios)}
        out[branch] = per_mu
    spreads = [v["spread"] for b in out.values() for v in b.values()]
    raw = [v["raw_spread"] for b in out.values() for v in b.values()]
    out["max_spread"] = max(spreads) if spreads else None
    out["max_raw_spread"] = max(raw) if raw else None
    return out


def threshold_against_d(rows, a_values, mus) -> dict:
    """Thresholds against the seed distance d (``rows``: :class:`SearchRow`), per aspect ratio
    in ``a_values`` and mu in ``mus`` with at least two d: the d, thresholds and statuses in the
    order of d, and the relative change per halving of d (None where a threshold is missing:
    a start that sticks has none). Keyed ``"a=1.5 mu=0.1"``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> rows = [Row(a=1.5, mu=0.1, d=d, threshold=t, status='converged') for d, t in ((0.01, 10.0), (0.02, 8.0))]
    >>> ps.threshold_against_d(rows, [1.5], [0.1])['a=1.5 mu=0.1']['change_per_halving']
    [0.25]
    """
    out = {}
    for a in a_values:
        for mu in mus:
            pts = sorted(((r.d, r) for r in rows if abs(r.a - a) < 1e-12 and r.mu == mu and r.d is not None),
                         key=lambda q: q[0])
            if len(pts) < 2:
                continue
            ds = [d for d, _ in pts]
            th = [r.threshold for _, r in pts]
            steps = [(th[i] / th[i + 1] - 1) if th[i] and th[i + 1] else None for i in range(len(th) - 1)]
            out[f"a={a:.4g} mu={mu:.4g}"] = {"d": ds, "threshold": th, "status": [r.status for _, r in pts],
                                            "change_per_halving": steps}
    return out


# -- the stored rows as text tables (the studies' reports) -------------------------------------------


def threshold_table(rows, *, first: str) -> str:
    """The main rows of a threshold sweep (:class:`ThresholdRow` of group "main") as a text
    table, the definition named ``first`` first: definition, branch, a, threshold, status,
    simulations and the library's check (:mod:`phasekit.thresholds.verify`: the bracket's ends keep
    their outcomes at a ten times tighter tolerance); then how many of the checked points pass it.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> r = Row(group="main", name="sliding", definition="sliding", branch="prolate", a=1.5, threshold=9.75,
    ...         status="converged", n_sims=30, consistent=True)
    >>> print(ps.threshold_table([r], first="sliding").splitlines()[-1])
    verified (the bracket's ends keep their outcomes at rtol / 10): 1 of 1 points
    """
    main = [r for r in rows if r.group == "main"]
    lines = [f"{'definition':<58s} {'branch':<8s} {'a':>6s} {'threshold':>10s} {'status':<17s} {'sims':>4s} {'check':>5s}"]
    for r in sorted(main, key=lambda r: (r.name != first, r.name, r.branch, r.a)):
        check = "ok" if r.consistent else "FAIL" if r.consistent is False else "-"
        th = f"{r.threshold:.4f}" if r.threshold else "-"
        lines.append(f"{r.definition[:58]:<58s} {r.branch:<8s} {r.a:6.3f} {th:>10s} {r.status:<17s} {r.n_sims:>4d} {check:>5s}")
    bad = [r for r in main if r.consistent is False]
    checked = [r for r in main if r.consistent is not None]
    lines.append(f"verified (the bracket's ends keep their outcomes at rtol / 10): {len(checked) - len(bad)} of {len(checked)} "
                 "points")
    return "\n".join(lines)


def definition_sensitivity_table(rows, *, parent) -> str:
    """The sensitivity rows of a threshold sweep (:class:`ThresholdRow` of group "sensitivity")
    against the main row of their parent definition at the same a (``parent(row)``: its name):
    the threshold (or the status), its relative change, and whether the search stuck near it.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> rows = [Row(group="main", name="sliding", a=1.5, threshold=10.0),
    ...         Row(group="sensitivity", name="sliding-d0.02", a=1.5, threshold=10.1, status="converged", stuck_near=False)]
    >>> print(ps.definition_sensitivity_table(rows, parent=lambda r: "sliding"))
      sliding-d0.02                  a=1.5000 threshold=10.1000            vs sliding: +1.00e-02  stuck near threshold: False
    """
    ref = {(r.name, r.a): r.threshold for r in rows if r.group == "main"}
    lines = []
    for r in sorted((r for r in rows if r.group == "sensitivity"), key=lambda r: (r.name, r.a)):
        base = ref.get((parent(r), r.a))
        rel = f"{(r.threshold / base - 1):+.2e}" if r.threshold and base else "-"
        th = f"{r.threshold:.4f}" if r.threshold else r.status
        lines.append(f"  {r.name:<30s} a={r.a:.4f} threshold={th:<18s} vs {parent(r)}: {rel}  stuck near threshold: {r.stuck_near}")
    return "\n".join(lines)


def threshold_grid_table(rows, mus) -> str:
    """Thresholds over (a, mu) (:class:`SearchRow` at one seed distance) as a text table: a row
    per branch and aspect ratio, a column per mu in ``mus`` (the status where there is no
    threshold, "-" where there is no row).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> print(ps.threshold_grid_table([Row(branch="prolate", a=1.5, mu=0.1, threshold=9.75, status="converged")], [0.1, 0.5]))
    branch        a     mu=0.1     mu=0.5
    prolate   1.500     9.7500          -
    """
    lines = [f"{'branch':<8s} {'a':>6s} " + " ".join(f"{'mu=' + format(mu, '.3g'):>10s}" for mu in mus)]
    for branch in ("prolate", "oblate"):
        for a in sorted({r.a for r in rows if r.branch == branch}):
            cells = []
            for mu in mus:
                r = next((r for r in rows if r.a == a and r.mu == mu), None)
                cells.append(f"{r.threshold:10.4f}" if r and r.threshold else f"{(r.status if r else '-'):>10s}")
            lines.append(f"{branch:<8s} {a:6.3f} " + " ".join(cells))
    return "\n".join(lines)


def seed_sensitivity_table(rows) -> str:
    """The searches that measured their sensitivity to the seed distance (:class:`SearchRow`
    with ``sens_*``) as text lines, by branch and a: the threshold T*, T* at d/2 and 2d, the
    slope d ln T*/d ln d, the largest shift, the bracket's relative width, and what dominates.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> r = Row(branch="prolate", a=1.5, threshold=10.0, bracket_lo=9.995, bracket_hi=10.005, sens_half=10.2, sens_double=9.8,
    ...         sens_slope=-0.03, sens_shift=0.02, sens_dominant="seed distance")
    >>> print(ps.seed_sensitivity_table([r]))  # doctest: +NORMALIZE_WHITESPACE
      prolate  a= 1.500 T*= 10.0000 T*(d/2)= 10.2000 T*(2d)=  9.8000 slope=-0.030 max shift=2.000% bracket=1.0e-03
      -> seed distance
    """
    lines = []
    for r in sorted((r for r in rows if r.sens_dominant), key=lambda r: (r.branch, r.a)):
        width = r.bracket_hi / r.bracket_lo - 1
        lines.append(f"  {r.branch:<8s} a={r.a:6.3f} T*={r.threshold:8.4f} T*(d/2)={r.sens_half or float('nan'):8.4f} "
                     f"T*(2d)={r.sens_double or float('nan'):8.4f} slope={r.sens_slope if r.sens_slope is not None else float('nan'):+.3f} "
                     f"max shift={r.sens_shift if r.sens_shift is not None else float('nan'):.3%} bracket={width:.1e} -> {r.sens_dominant}")
    return "\n".join(lines)


# -- the report of an (a, mu) threshold map ----------------------------------------------------------


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
