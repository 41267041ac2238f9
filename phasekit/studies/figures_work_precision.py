"""Figures of accuracy and cost, drawn with matplotlib on the axes given: the work-precision
diagram of the jump time (:func:`phasekit.baseline.work_precision`), the jump time against the
regularisation eps of Coulomb's law, and the growth of the cost with the simulated time and
the spin. Each returns the artists it drew.
"""

from __future__ import annotations

import math

#: the runs drawn at the bottom of a work-precision panel when they hit the wall-time cap
CAPPED_ERROR = 1e-1


def _styles(methods) -> dict:
    """phasekit's two Taylor rows in black (solid: sweep path, dashed: default options), the rest
    in the colour cycle."""
    styles = {name: dict(color=f"C{k}", lw=1) for k, name in enumerate(m for m in methods if not m.startswith("phasekit"))}
    styles["phasekit Taylor/heyoka (sweep path)"] = dict(color="k", lw=2.5)
    styles["phasekit Taylor/heyoka (default options)"] = dict(color="k", lw=1.5, ls="--")
    return styles


def plot_work_precision(axes, rows, refs: dict, cap: float) -> list:
    """One work-precision panel per workload (``axes`` in the order of ``refs``): the relative
    error of the jump time against the wall time per run, one line per method of
    :data:`phasekit.baseline.JUMP_METHODS` (phasekit's as its sweeps run it bold black, with
    simulate's default options dashed black), runs stopped at the ``cap`` as red ticks.
    ``rows`` and ``refs``: what :func:`phasekit.baseline.work_precision` returns.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> rows = [dict(workload="w", method="scipy DOP853, NumPy rhs", rtol=r, error=r, wall_s=r * 1e4, status="ok")
    ...         for r in (1e-6, 1e-8)]
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(ps.plot_work_precision([ax], rows, {"w": (45.256, 0.0, 0.0)}, 5.0))
    1
    """
    from ..baseline import JUMP_METHODS

    markers = "os^vD<>phX*P"
    styles = _styles(JUMP_METHODS)
    any_capped = any(r["status"] == "capped" for r in rows)
    lines = []
    for ax, wl in zip(axes, refs):
        for k, name in enumerate(JUMP_METHODS):
            mine = [r for r in rows if r["workload"] == wl and r["method"] == name]
            pts = [(r["wall_s"], max(r["error"], 1e-16)) for r in mine if r["error"] is not None]
            capped = [r for r in mine if r["status"] == "capped"]
            if pts:
                lines += ax.loglog(*zip(*pts), marker=markers[k % len(markers)], ms=4, label=name, **styles[name])
            if capped:
                lines += ax.loglog([cap] * len(capped), [CAPPED_ERROR] * len(capped), "r|", ms=12)
        ax.set_xlabel("wall time per run (s)")
        ax.set_ylabel(r"relative error of the jump time $t_*$")
        ax.set_title(f"{wl}: t* = {refs[wl][0]:.6f}" + ("; red ticks: capped runs" if any_capped else ""), fontsize=9)
        ax.grid(alpha=0.3, which="both")
    return lines


def plot_regularisation(ax, runs: dict, *, t_max: float, exact_at: float = 1e-10, title: str = "") -> list:
    """The jump time against the regularisation eps of Coulomb's law, one line per start:
    ``runs`` maps a label to rows (eps, t_jump, status, t_stick, wall) (eps None: the exact
    stick-slip law, drawn at ``exact_at``, a power of 10; t_jump None: no jump by ``t_max``,
    drawn there); "stick" marks a run that stuck (``t_stick`` not None).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> runs = {"sliding": [(1e-3, 45.3, "jumped", None, 0.1), (None, 45.256, "jumped", None, 0.1)]}
    >>> len(ps.plot_regularisation(ax, runs, t_max=400.0, title="t_jump against eps"))
    1
    """
    lines = []
    for label, erows in runs.items():
        xs = [e if e is not None else exact_at for e, *_ in erows]
        ys = [tj if tj is not None else t_max for _, tj, *_ in erows]
        lines += ax.semilogx(xs, ys, "o-", label=label)
        for (e, tj, st, tstick, w), x, y in zip(erows, xs, ys):
            if tstick is not None:
                ax.annotate("stick", (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.axhline(t_max, color="0.6", ls=":", lw=0.8)
    ax.set_xlabel(r"regularisation $\epsilon$ (units $\sqrt{gb}$; the exact stick-slip law plotted at "
                  rf"$10^{{{round(math.log10(exact_at))}}}$)")
    ax.set_ylabel(rf"jump time $t_*$ (units $\sqrt{{b/g}}$; {t_max:g} = no jump by $t = {t_max:g}$)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8, loc="center left")
    return lines


def plot_cost_growth(ax, by_T, by_omega, *, omega0: float = 10.0, T: float = 100.0, title: str = "") -> list:
    """Wall time per run against the simulated time T (``by_T``: rows (T, wall, steps), at
    ``omega0``) and, on a second x axis, against the initial precession rate Omega0
    (``by_omega``: rows (Omega0, wall, steps), at ``T``), on log scales labelled with the
    values measured.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(ps.plot_cost_growth(ax, [(10, 1e-3, 50), (100, 5e-3, 400)], [(5, 1e-3, 80), (40, 9e-3, 900)]))
    2
    """
    from matplotlib.ticker import NullFormatter

    Ts, oms = [T for T, *_ in by_T], [o for o, *_ in by_omega]
    lines = ax.loglog(Ts, [w for _, w, _ in by_T], "o-", label=rf"against simulated time $T$ ($\Omega_0={omega0:g}$)")
    ax2 = ax.twiny()
    lines += ax2.loglog(oms, [w for _, w, _ in by_omega], "s--", color="C1", label=rf"against $\Omega_0$ ($T={T:g}$)")
    for a, ticks in ((ax, Ts), (ax2, oms)):  # label the measured values, plainly
        a.set_xticks(ticks, [f"{v:g}" for v in ticks])
        a.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel(r"simulated time $T$ (units $\sqrt{b/g}$)")
    ax2.set_xlabel(r"initial precession rate $\Omega_0$ (units $\sqrt{g/b}$)", color="C1")
    ax.set_ylabel("wall time per run (s)")
    ax.set_title(title, fontsize=9)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="upper left")
    return lines
