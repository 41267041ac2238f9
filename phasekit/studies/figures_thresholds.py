"""Figures of the jump thresholds and of linear stability: jump-threshold curves against the
aspect ratio (:func:`plot_threshold_curves`, drawn in :data:`DEFINITION_STYLES`) and over (a, mu)
(:func:`plot_threshold_map`), the linear-stability map of the steady states with its closed-form thresholds
(:func:`plot_stability_map`), and the paper's printed (no jump, jump) pairs against the
regularisation of Coulomb friction (:func:`plot_pair_scan`).

Each takes the stored rows of its study (:class:`phasekit.studies.ThresholdRow`,
:class:`phasekit.studies.SearchRow`, :func:`phasekit.studies.stability_grid`'s grids) and returns a
matplotlib figure for :meth:`phasekit.scaffold.Study.save`. matplotlib is imported by the functions
that draw.
"""

from __future__ import annotations

import numpy as np

from ..viz.mpl import plain_log_ticks
from ..viz.output import pyplot

#: the line style of each threshold definition of :data:`phasekit.thresholds.DEFAULT_DEFINITIONS` (the
#: default, "sliding", bold black), for :func:`phasekit.studies.plot_threshold_curves`
DEFINITION_STYLES = {"sliding": dict(color="k", lw=2.2, marker="o", ms=4, zorder=5),
                     "literal-eps1e-3": dict(color="C0", lw=1, marker="s", ms=3),
                     "literal-eps1e-4": dict(color="C1", lw=1, marker="^", ms=3),
                     "literal-exact": dict(color="C3", lw=1, marker="v", ms=3),
                     "viscous": dict(color="C2", lw=1, marker="x", ms=3)}


# -- jump thresholds against the aspect ratio ------------------------------------------------------


def plot_threshold_curves(rows, definitions, *, default: str, styles: dict, hi: float, brackets: dict, title: str):
    """Jump thresholds against the aspect ratio (Figure 6b,c): Omega0*(a) prolate (left), n0*(a)
    oblate (right), one curve per definition (``rows``: :class:`phasekit.studies.ThresholdRow` of
    group "main"; ``styles``: the plot keywords per definition name; ``default``: the name of
    the default definition). A definition that does not jump up to ``hi`` is an arrow at ``hi``;
    ``brackets`` maps an aspect ratio to the paper's (no jump, jump) pair of single runs. A point
    whose self-consistency check failed (:func:`phasekit.studies.threshold_task`) is ringed; one
    searched again in the vector chart is boxed, the paper's chart's threshold there a cross.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> d = pk.Definition('sliding', 'sliding')
    >>> row = ps.threshold_task(None, asdict(d), 1.5, 'main', True, dict(hi=120.0, tol=0.05))
    >>> fig = ps.plot_threshold_curves([row], [d], default='sliding', styles={'sliding': {}}, hi=120.0,
    ...                                    brackets={1.5: (10.2, 10.5)}, title='demo')
    >>> len(fig.axes)
    2
    """
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.6))
    main = [r for r in rows if r.group == "main"]
    for ax, branch in zip(axes, ("prolate", "oblate")):
        for defn in definitions:
            pts = sorted(((r.a, r) for r in main if r.name == defn.name and r.branch == branch), key=lambda q: q[0])
            if not pts:
                continue
            ok = [(a, r.threshold) for a, r in pts if r.threshold is not None]
            label = defn.label + (" [default]" if defn.name == default else "")
            none = [a for a, r in pts if r.status == "no_jump_in_range"]
            if ok:
                ax.plot(*zip(*ok), label=label, **styles.get(defn.name, {}))
            failed = [(a, r.threshold) for a, r in pts if r.threshold is not None and r.consistent is False]
            if failed:  # set by the integration error, not the body (the library's check)
                ax.plot(*zip(*failed), ls="none", marker="o", ms=11, mfc="none", mec="k", mew=1.2,
                        label="not verified: a bracket end changes its outcome at rtol / 10")
            again = [(a, r.threshold, r.first_threshold) for a, r in pts if getattr(r, "first_threshold", None) is not None]
            if again:  # the first search failed its check; the search at rtol / 10 is the point
                ax.plot([q[0] for q in again], [q[1] for q in again], ls="none", marker="s", ms=10, mfc="none", mec="0.3",
                        label="searched again at rtol / 10: the first search failed its check")
                ax.plot([q[0] for q in again], [q[2] for q in again], ls="none", marker="x", ms=7, color="0.3",
                        label="the first search's threshold there")
            if none:
                ax.plot(none, [hi] * len(none), ls="none", marker=r"$\uparrow$", ms=10, color=styles[defn.name]["color"],
                        label=(label + f": no jump up to {hi:g}") if not ok else None)
        for a, (lo, up) in brackets.items():
            if (a > 1) == (branch == "prolate"):
                ax.errorbar([a], [0.5 * (lo + up)], yerr=[[0.5 * (up - lo)]], fmt="D", color="m", ms=5, capsize=3,
                            label="paper Fig. %s: bracket from two runs" % ("4" if a > 1 else "3"))
        ax.set_yscale("log")
        ax.axvline(1.0, color="0.7", ls=":")
        ax.set_xlabel(r"aspect ratio $a$")
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel(r"threshold precession rate $\Omega_0$ (units $\sqrt{g/b}$)")
    axes[1].set_ylabel(r"threshold spin $n_0$ (units $\sqrt{g/b}$)")
    axes[0].set_title(r"prolate, from the horizontal precession (cf. Fig. 6b)", fontsize=10)
    axes[1].set_title(r"oblate, from the vertical spin (cf. Fig. 6c)", fontsize=10)
    for ax in axes:
        ax.set_ylim(4.0, 1.6 * hi)
    handles = {}
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    fig.legend(list(handles.values()), list(handles.keys()), loc="lower center", ncol=2, fontsize=8, frameon=False)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0.17, 1, 1))
    return fig


def _log_thresholds(ax) -> None:
    ax.set_yscale("log")
    plain_log_ticks(ax, "y", subs=(2, 3, 4, 5, 6, 7, 8))


def plot_threshold_map(rows, mus, collapse: dict, *, d0: float, d_lines: dict, d_mu, title: str):
    """Jump thresholds over (a, mu) (``rows``: :class:`phasekit.studies.SearchRow`, one colour per
    mu in ``mus``): top, threshold(a) per branch at the seed distance ``d0``; bottom left, the
    collapse test (each curve divided by the fitted f(mu) of ``collapse``, as
    :func:`phasekit.studies.threshold_collapse` gives it); bottom right, threshold against d at the
    aspect ratios ``d_lines["a"]`` (solid, dashed) for the mu in ``d_mu``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> fig = ps.plot_threshold_map([], [0.1], {}, d0=0.01, d_lines={"a": [1.5], "d": [0.005, 0.01]}, d_mu=[0.1],
    ...                                 title="demo")
    >>> len(fig.axes)
    4
    """
    plt = pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    cmap = plt.get_cmap("viridis")
    colour = {mu: cmap(i / max(1, len(mus) - 1)) for i, mu in enumerate(mus)}
    main = [r for r in rows if r.d == d0]
    for ax, branch in zip(axes[0], ("prolate", "oblate")):
        for mu in mus:
            pts = sorted((r.a, r.threshold) for r in main if r.branch == branch and r.mu == mu and r.threshold)
            if pts:
                ax.plot(*zip(*pts), "o-", color=colour[mu], ms=4, label=fr"$\mu$ = {mu:.3g}")
        _log_thresholds(ax)
        ax.set_xlabel(r"aspect ratio $a$")
        ax.grid(alpha=0.3, which="both")
    axes[0, 0].set_ylabel(r"threshold $\Omega_0^*$ (units $\sqrt{g/b}$)")
    axes[0, 1].set_ylabel(r"threshold $n_0^*$ (units $\sqrt{g/b}$)")
    axes[0, 0].set_title(r"prolate, from the horizontal precession ($\mu \leq 0.1$: curves nearly coincide)", fontsize=10)
    axes[0, 1].set_title("oblate, from the vertical spin", fontsize=10)
    if axes[0, 0].get_legend_handles_labels()[0]:  # an empty map has no curves to name
        axes[0, 0].legend(fontsize=8, ncol=2)
    _collapse_panel(axes[1, 0], main, mus, collapse, colour)
    ax = axes[1, 1]
    for a, ls in zip(d_lines["a"], ("-", "--")):
        for mu in d_mu:
            pts = sorted((r.d, r.threshold) for r in rows if abs(r.a - a) < 1e-12 and r.mu == mu and r.threshold)
            if len(pts) > 1:
                ax.plot(*zip(*pts), marker="o", ls=ls, color=colour.get(mu, "k"), ms=4)
        ax.plot([], [], ls=ls, color="0.3", label=f"a = {a:.3g}")  # line style only: colours are mu, as above
    ds = np.array([2.5e-3, 1e-2])
    ax.plot(ds, 30.0 * (ds / ds[0]) ** -0.5, "k:", lw=1, label=r"slope $-1/2$ ($d\,\Omega_0^2$ = const: the sticking boundary)")
    ax.set_xscale("log")
    _log_thresholds(ax)
    plain_log_ticks(ax, "x", subs=())
    ax.set_xticks(d_lines["d"], [f"{d:g}" for d in d_lines["d"]])
    ax.set_xlabel(r"seed distance $d$ from the fixed point (rad)")
    ax.set_ylabel(r"threshold $\Omega_0^*$ or $n_0^*$ (units $\sqrt{g/b}$)")
    ax.set_title(r"threshold against $d$ (one colour per $\mu$; solid a = 1.5, dashed a = 2/3)", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    return fig


def _collapse_panel(ax, main, mus, coll, colour) -> None:
    for branch, marker in (("prolate", "o"), ("oblate", "s")):
        for mu in mus:
            f = coll.get(branch, {}).get(mu, {}).get("f")
            if f is None:
                continue
            pts = sorted((r.a, r.threshold / f) for r in main if r.branch == branch and r.mu == mu and r.threshold)
            ax.plot(*zip(*pts), marker=marker, ls="-", color=colour[mu], ms=3, lw=0.8)
    _log_thresholds(ax)
    ax.set_xlabel(r"aspect ratio $a$")
    ax.set_ylabel(r"threshold / $f(\mu)$ (units $\sqrt{g/b}$)")
    spread = coll.get("max_spread")
    ax.set_title(r"collapse test: threshold / $f(\mu)$, $f$ fitted per $\mu$ and branch" + "\n"
                 + (f"remaining spread max |ln| = {spread:.3f} (raw, f = 1: {coll['max_raw_spread']:.3f})" if spread else ""),
                 fontsize=9)
    ax.grid(alpha=0.3, which="both")


# -- linear stability of the steady states ---------------------------------------------------------


def plot_stability_map(a_values, omegas, spins, horizontal, vertical, *, mu: float):
    """The dimension of the unstable subspace of the horizontal steady precession over (a, Omega0)
    (``horizontal``, rows: ``omegas``) and of the vertical spin over (a, n0) (``vertical``, rows:
    ``spins``), as :func:`phasekit.studies.stability_grid` gives them for uniform spheroids under
    viscous friction ``mu``, with the closed-form criteria drawn over them.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> a, s = np.linspace(0.5, 2.0, 3), np.linspace(1.0, 10.0, 3)
    >>> fig = ps.plot_stability_map(a, s, s, np.zeros((3, 3), int), np.zeros((3, 3), int), mu=0.1)
    >>> len(fig.axes)
    3
    """
    from ..bodies.spheroid import Spheroid
    from ..theory.criteria import horizontal_stability_threshold, vertical_stability_threshold

    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6), sharey=True)
    cmap = plt.get_cmap("viridis", 3)
    for ax, M, ys, title, ylabel in [
        (axes[0], horizontal, omegas, "horizontal steady precession", r"precession rate $\Omega_0$ (units $\sqrt{g/b}$)"),
        (axes[1], vertical, spins, "vertical spin", r"spin $n_0$ (units $\sqrt{g/b}$)"),
    ]:
        im = ax.pcolormesh(a_values, ys, M, cmap=cmap, vmin=-0.5, vmax=2.5, shading="nearest")
        ax.axvline(1.0, color="w", lw=0.8, ls=":")
        ax.set_xlabel(r"aspect ratio $a$")
        ax.set_title(title, fontsize=10)
        ax.set_ylabel(ylabel)
    aa = np.linspace(a_values[0], a_values[-1], 300)
    axes[1].plot(aa, [vertical_stability_threshold(Spheroid(x).A, Spheroid(x).C, x) or np.nan for x in aa],
                 "r--", lw=1.2, label=r"$n_0=\sqrt{5a^3}$: $(a^2C-A)n_0^2=a^3(a^2-1)$")
    axes[1].set_ylim(spins[0], spins[-1])
    axes[0].plot(aa, [horizontal_stability_threshold(Spheroid(x).A, Spheroid(x).C, x) or np.nan for x in aa],
                 "r--", lw=1.2, label=r"$\Omega_0=\sqrt{5}$: $(a^2C-A)\Omega_0^2=a^2-1$")
    axes[0].legend(loc="upper left", fontsize=8)
    axes[1].legend(loc="upper left", fontsize=8)
    cb = fig.colorbar(im, ax=axes, ticks=[0, 1, 2])
    cb.set_label("dimension of the unstable subspace")
    fig.suptitle(f"Linear stability, viscous friction $\\mu={mu:g}$, uniform spheroids (exact CasADi Jacobians)", fontsize=10)
    return fig


# -- the paper's printed pairs under regularisation --------------------------------------------------


def plot_pair_scan(rows, table, cases: dict, *, charts, t_end: float, t_tolerance: float, title: str):
    """The paper's single-trajectory pairs (``cases``: label -> :class:`phasekit.theory.paper.PaperCase`,
    one panel each) against the regularisation eps of Coulomb friction: the jump time t* of each
    start that jumps (per chart in ``charts``: solid, dashed), markers above the axis for a start
    whose rise completes or that sticks by ``t_end``, the printed t* band (+- ``t_tolerance``),
    and green lines at the eps where ``table`` says the pair comes out as printed. ``rows``: one
    per run, with ``label``, ``role`` ("no_jump" or "jump"), ``chart``, ``eps`` (None: exact
    Coulomb, not drawn), ``outcome`` and ``t_jump``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Run
    >>> rows = [Run(label="5.2", role="jump", chart="euler", eps=1e-3, outcome="jump", t_jump=110.0)]
    >>> fig = ps.plot_pair_scan(rows, [], pk.theory.PAPER_CASES, charts=("euler",), t_end=600.0, t_tolerance=0.15,
    ...                             title="demo")
    >>> len(fig.axes)
    2
    """
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.4))
    top = {"rise": 1.12 * t_end, "stuck": 1.22 * t_end, "slow": 1.22 * t_end, "failed": 1.3 * t_end}
    for ax, (label, case) in zip(axes, cases.items()):
        for chart, ls, dy in zip(charts, ("-", "--"), (1.0, 1.03)):
            for role, colour in (("no_jump", "C0"), ("jump", "C3")):
                value = case.no_jump if role == "no_jump" else case.jump
                pts = sorted(((r.eps, r) for r in rows if r.label == label and r.role == role and r.chart == chart
                              and r.eps is not None), key=lambda q: q[0])
                jumped = [(e, r.t_jump) for e, r in pts if r.outcome == "jump"]
                if jumped:
                    ax.plot(*zip(*jumped), marker="o", ls=ls, color=colour, ms=4,
                            label=f"{case.parameter} = {value:g} jumps at t* ({chart})")
                for kind, marker in (("rise", "o"), ("stuck", "x")):
                    sel = [e for e, r in pts if r.outcome == kind]
                    if sel:
                        y = top[kind] * dy + (0.0 if role == "no_jump" else 0.07 * t_end)
                        ax.plot(sel, [y] * len(sel), ls="none", marker=marker, mfc="none", color=colour, ms=6,
                                label=f"{case.parameter} = {value:g}: {'rises, no jump' if kind == 'rise' else 'sticks, no rise'}"
                                      f" by t = {t_end:g} ({chart})")
        for t in table:
            if t["label"] == label and t["as_printed"] and t["chart"] == "euler":
                ax.axvline(float(t["eps"]), color="g", lw=1.5, alpha=0.6, label="as printed (both charts)")
        ax.axhspan(case.t_jump * (1 - t_tolerance), case.t_jump * (1 + t_tolerance), color="m", alpha=0.15,
                   label=f"printed t* ~ {case.t_jump:g} (+-{t_tolerance:.0%})")
        ax.set_xscale("log")
        ax.set_ylim(0, 1.45 * t_end)
        ax.set_xlabel(r"regularisation $\epsilon$ of $|u_P|$ (units $\sqrt{gb}$); exact Coulomb: sticks in both")
        ax.set_ylabel(r"jump time $t^*$ (units $\sqrt{b/g}$)")
        ax.set_title(f"{case.figure}: start ({label}), a = {case.a:.4g}: {case.parameter} = {case.no_jump:g} and {case.jump:g}",
                     fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=6.5, loc="center left")
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return fig
