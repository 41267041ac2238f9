"""The report of the work-precision study (studies/work_precision.py): what a comparison of
phasekit's integrators with the baselines (:func:`phasekit.baseline.work_precision`) found, as
text (:func:`work_precision_summary`; its figures are :mod:`phasekit.studies.figures_work_precision`').
"""

from __future__ import annotations

import numpy as np

from ..baseline import JUMP_METHODS


def work_precision_summary(rows, refs: dict, targets=(1e-6, 1e-9)) -> str:
    """What a work-precision comparison (:func:`phasekit.baseline.work_precision`) found, as text: each
    workload's reference and its check by scipy, the cheapest run of each method reaching each
    error level in ``targets``, and the log-log slope of the error against rtol of CVODES and
    phasekit's Taylor integrator on the first workload.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> rows = [dict(workload="w", method=m, rtol=r, error=r, wall_s=r * 1e4, status="ok")
    ...         for m in pk.baseline.JUMP_METHODS for r in (1e-4, 1e-7, 1e-10)]
    >>> print(ps.work_precision_summary(rows, {"w": (45.256, 1e-12, 1e-10)}).splitlines()[-1])
    error against rtol, phasekit Taylor/heyoka (sweep path): log-log slope 1.00
    """
    out = [f"{wl}: reference t* = {t_ref:.12f} (Taylor tol 1e-15); scipy DOP853 rtol 1e-13 on the NumPy rhs differs by "
           f"{chk:.1e} relative in t*, {schk:.1e} in the state" for wl, (t_ref, chk, schk) in refs.items()]
    for wl in refs:
        out += [f"\n{wl}: cheapest run reaching each error level",
                f"{'method':<42s} " + " ".join(f"{'error <= ' + f'{t:.0e}'.replace('e-0', 'e-'):>22s}" for t in targets)]
        for name in JUMP_METHODS:
            cells = []
            for target in targets:
                ok = [r for r in rows if r["workload"] == wl and r["method"] == name and r["error"] is not None and r["error"] <= target]
                best = min(ok, key=lambda r: r["wall_s"]) if ok else None
                cells.append(f"{best['wall_s'] * 1e3:9.2f} ms @ {best['rtol']:.0e}" if best else "not reached")
            out.append(f"{name:<42s} " + " ".join(f"{c:>22s}" for c in cells))
    for name in ("CVODES BDF (CasADi)", "CVODES Adams (CasADi)", JUMP_METHODS[0]):
        pts = [(r["rtol"], r["error"]) for r in rows if r["workload"] == next(iter(refs)) and r["method"] == name and r["error"]]
        if len(pts) > 2:
            slope = np.polyfit(np.log10([p[0] for p in pts]), np.log10([max(p[1], 1e-16) for p in pts]), 1)[0]
            out.append(f"error against rtol, {name}: log-log slope {slope:.2f}")
    return "\n".join(out)
