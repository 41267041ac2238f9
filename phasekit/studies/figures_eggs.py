"""Figures of the egg studies (studies/egg.py, egg_jumps.py): which end rises over
(asymmetry, start) (:func:`plot_which_end`), thresholds against a body parameter
(:func:`plot_threshold_against`), and flights in real units against experiment
(:func:`plot_flights`).

Each returns a matplotlib figure for :meth:`phasekit.scaffold.Study.save`; matplotlib is imported
by the functions that draw.
"""

from __future__ import annotations

import math

import numpy as np

from ..viz.mpl import plain_log_ticks
from ..viz.output import pyplot


def plot_which_end(rows, omegas, *, risen, theta_2, title: str):
    """Which end an egg rises onto, over (asymmetry w, theta0 - pi/2), one panel per Omega0 in
    ``omegas``: each start (``rows``, with ``w``, ``omega0``, ``theta0``, ``theta_h`` and
    ``predicted``) coloured by ``risen(row)`` ("fat" blue, "thin" red, "none" grey: stuck at
    once, "failed" black), a cross where it is not as predicted; the predicted separatrix
    theta_h(Omega0) and its Omega0 -> infinity limit ``theta_2(w)``.

    Examples
    --------
    >>> import math, phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> rows = [Row(w=w, omega0=6.0, theta0=1.5, theta_h=math.pi / 2, predicted="fat", end="fat") for w in (0.0, 0.05)]
    >>> fig = ps.plot_which_end(rows, [6.0], risen=lambda r: r.end, theta_2=lambda w: math.pi / 2, title="demo")
    >>> len(fig.axes)
    1
    """
    plt = pyplot()
    fig, axes = plt.subplots(1, len(omegas), figsize=(6.2 * len(omegas), 5.0), squeeze=False)
    for ax, om in zip(axes[0], omegas):
        sub = [r for r in rows if r.omega0 == om]
        for r in sub:
            end = risen(r)
            c = {"fat": "#2166ac", "thin": "#b2182b", "none": "0.6", "failed": "k"}[end]
            ax.scatter(r.w, r.theta0 - math.pi / 2, c=c, marker="o" if end in (r.predicted, "none") else "X", s=50, zorder=3)
        ws = sorted({r.w for r in sub})
        th_h = [next(r.theta_h for r in sub if r.w == w) for w in ws]
        ax.plot(ws, np.array(th_h) - math.pi / 2, "k-", lw=1.5, label=r"$\theta_h(\Omega_0)$: horizontal-like state (predicted separatrix)")
        wf = np.linspace(0.0, max(ws), 30)
        ax.plot(wf, [theta_2(w) - math.pi / 2 if w > 0 else 0.0 for w in wf], "k:", lw=1,
                label=r"$\theta_2$: its $\Omega_0\to\infty$ limit")
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.set_xlabel(r"asymmetry $w$ (shift of the widest section / length)")
        ax.set_ylabel(r"$\theta_0 - \pi/2$ (rad; > 0: thin end lower)")
        ax.set_title(rf"$\Omega_0$ = {om:g}: blue = rises onto the fat end, red = thin end, grey = stuck at once"
                     "\n(X: not as predicted)", fontsize=9)
        ax.legend(fontsize=8, loc="lower right")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def plot_threshold_against(rows, x: str, curves: dict, *, xlabel: str, title: str, rev_scale=None, rev_label: str = ""):
    """Jump thresholds against a body parameter ``x`` (``rows``: dicts with ``x``, "threshold"
    and "start"), one curve per start (``curves``: start -> (format, label)); with ``rev_scale``
    (a :class:`phasekit.Scale`), a right axis in revolutions per second of that body
    (``rev_label``).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> rows = [{"w": w, "threshold": 12.0 + w, "start": "s"} for w in (0.0, 0.05)]
    >>> fig = ps.plot_threshold_against(rows, "w", {"s": ("ko-", "start s")}, xlabel="w", title="demo",
    ...                                     rev_scale=pk.Scale("21.5 mm"), rev_label="rev/s")
    >>> [line.get_label() for line in fig.axes[0].lines]
    ['start s']
    """
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.2, 4.8))
    for start, (style, label) in curves.items():
        pts = [(r[x], r["threshold"]) for r in rows if r["threshold"] is not None and r["start"] == start]
        ax.plot(*zip(*pts), style, label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"threshold precession rate $\Omega_0$ (units $\sqrt{g/b}$)")
    if rev_scale is not None:
        per_rev = rev_scale.dimensionless("1 rev/s")  # Omega0 of one revolution per second
        sec = ax.secondary_yaxis("right", functions=(lambda v: v / per_rev, lambda v: v * per_rev))
        sec.set_ylabel(rev_label)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    return fig


def plot_flights(rows, *, experiment: dict, title: str):
    """Flights of runs in real units, one marker per lever (``rows``: dicts with "lever",
    "value", "e" (restitution) and, for runs that flew, "first_flight_ms", "first_gap_mm",
    "longest_flight_ms", "largest_gap_mm"): the longest flight and largest gap of each run
    (black without rebounds, e = 0; labelled with the lever's value), the first flight hollow,
    and a box for the experiment (``experiment``: "flight_ms" and "gap_mm" ranges, and "label":
    whose numbers they are; a published text's words turned into numbers are our reading of
    it, and the label says so).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> rows = [dict(lever="spin", value=50.0, e=0.5, first_flight_ms=2.0, first_gap_mm=0.01, longest_flight_ms=5.0,
    ...              largest_gap_mm=0.1)]
    >>> fig = ps.plot_flights(rows, experiment=dict(gap_mm=(0.05, 0.5), flight_ms=(5.0, 30.0)), title="demo")
    >>> len(fig.axes)
    1
    """
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8.6, 6.0))
    g, f = experiment["gap_mm"], experiment["flight_ms"]
    ax.fill_between(f, g[0], g[1], color="#fdd0a2", alpha=0.6,
                    label=experiment.get("label", "our reading of a published range (not its numbers)"))
    markers = dict(zip(sorted({r["lever"] for r in rows}), "osD^vP*X"))
    for r in rows:
        if r.get("largest_gap_mm") is None:
            continue
        m = markers[r["lever"]]
        ax.scatter(r["first_flight_ms"], r["first_gap_mm"], marker=m, s=30, facecolors="none", edgecolors="grey")
        ax.scatter(r["longest_flight_ms"], r["largest_gap_mm"], marker=m, s=40, color="k" if r["e"] == 0 else "C0",
                   zorder=3)
        ax.annotate(f"{r['value']:.3g}", (r["longest_flight_ms"], r["largest_gap_mm"]), fontsize=7,
                    xytext=(3, 3), textcoords="offset points")
    for lever, m in markers.items():
        ax.scatter([], [], marker=m, color="C0", label=f"{lever}: longest flight, largest gap of the run")
    ax.scatter([], [], marker="o", facecolors="none", edgecolors="grey", label="the first flight alone (hollow)")
    ax.scatter([], [], marker="s", color="k", label="restitution 0 (no rebound)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log_ticks(ax)
    ax.set_xlabel("flight duration (ms)")
    ax.set_ylabel("gap (mm)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="lower right")  # the box and the longest flights are at the top
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    return fig
