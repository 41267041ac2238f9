"""The tippe top's figures: the inversion map (measured outcomes over the theory's predicted
ones), the history of a top that hops while inverting, and a 3-D view of one inversion.

Units: radius of the ball R = 1, mass 1, g = 1 (time sqrt(R/g)); alpha = OG / radius and
gamma = A/C (moments about G), as in :mod:`phasekit.theory.tippetop`. matplotlib and PyVista
are imported by the functions that draw.
"""

from __future__ import annotations

import math

import numpy as np

from ..viz.output import pyplot

#: colour and marker of each measured outcome of an inversion
OUTCOME_STYLE = {"full": ("#1a9850", "o"), "partial": ("#fdae61", "s"), "never": ("#d73027", "x"), "failed": ("k", "?")}
#: background colours of the predicted outcomes never, partial, full
PREDICTED_COLORS = ("#f4a582", "#fee090", "#a6dba0")
ALPHA_LIM, GAMMA_LIM = (0.0, 0.55), (0.5, 1.6)


def _predicted(ax, cmap, C: float, n0: float, theta0: float) -> None:
    """The background of one panel: the outcome :func:`phasekit.theory.tippetop.ueda_group`
    predicts over (alpha, gamma), and the classical bounds gamma = 1 -+ alpha."""
    from ..theory.tippetop import ueda_group

    code = {"never": 0, "partial": 1, "full": 2}
    al = np.linspace(0.0, 0.55, 200)
    ag, gg = np.meshgrid(np.linspace(0.02, 0.55, 160), np.linspace(0.5, 1.6, 160))
    pred = np.vectorize(lambda a, g: code[ueda_group(a, g * C, C, n0, theta0=theta0)])(ag, gg)
    ax.contourf(ag, gg, pred, levels=[-0.5, 0.5, 1.5, 2.5], cmap=cmap, alpha=0.8)
    ax.plot(al, 1 - al, "k--", lw=1)
    ax.plot(al, 1 + al, "k--", lw=1)


def _measured(ax, r) -> None:
    """One run: its outcome's marker, a magenta ring if it disagrees with the prediction, "h" if
    it hopped, theta reached if partial."""
    color, marker = OUTCOME_STYLE[r.outcome]
    ax.scatter(r.alpha, r.gamma, c=color, marker=marker, s=46, edgecolors="k" if marker != "x" else None, linewidths=0.6,
               zorder=3)
    if r.outcome != r.predicted and r.outcome != "failed":
        ax.scatter(r.alpha, r.gamma, facecolors="none", edgecolors="m", s=150, linewidths=1.4, zorder=4)
    if r.n_liftoff:
        ax.annotate("h", (r.alpha, r.gamma), xytext=(4, 4), textcoords="offset points", fontsize=7, color="b")
    if r.outcome == "partial":
        ax.annotate(f"{r.theta_end:.2f}", (r.alpha, r.gamma), xytext=(-9, -11), textcoords="offset points", fontsize=5.5,
                    color="0.25")


def _map_legend(fig, colors) -> None:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles = [Patch(color=c, label=f"predicted {k}") for k, c in zip(("never", "partial", "full"), colors)]
    handles += [Line2D([], [], color=OUTCOME_STYLE[k][0], marker=OUTCOME_STYLE[k][1], ls="none", label=f"phasekit: {k}")
                for k in ("full", "partial", "never")]
    handles += [Line2D([], [], color="k", ls="--", label=r"classical $\gamma = 1 \pm \alpha$"),
                Line2D([], [], color="m", marker="o", mfc="none", ls="none", ms=10, label="disagrees with prediction"),
                Line2D([], [], color="b", marker="$h$", ls="none", label="hopped (lost contact)"),
                Line2D([], [], color="0.25", marker="$0.0$", ls="none", ms=12, label=r"$\theta$ reached (partial)")]
    fig.legend(handles=handles, loc="lower center", ncol=4, fontsize=8, frameon=False)


def plot_inversion_map(rows, laws, spins, *, C: float, theta0: float, title: str = ""):
    """A figure of inversion outcomes over (alpha, gamma): one panel per friction law (rows of
    panels, ``laws`` as (name, mu) pairs) and spin n0 (columns). Background: the outcome
    :func:`phasekit.theory.tippetop.ueda_group` predicts for the vertical-spin start at
    ``theta0`` (axial moment ``C``), with the classical bounds gamma = 1 -+ alpha; markers: the
    measured outcomes (:data:`OUTCOME_STYLE`), ringed where they disagree, "h" where the top
    hopped, theta reached where it inverted partly. ``rows`` have the attributes ``law``,
    ``mu``, ``n0``, ``alpha``, ``gamma``, ``outcome``, ``predicted``, ``n_liftoff`` and
    ``theta_end``.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> import phasekit as pk, phasekit.studies as ps
    >>> row = SimpleNamespace(law="viscous", mu=0.3, n0=8.0, alpha=0.3, gamma=0.95, outcome="full", predicted="full",
    ...                       n_liftoff=0, theta_end=3.1)
    >>> fig = ps.plot_inversion_map([row], [("viscous", 0.3)], [8.0], C=0.4, theta0=0.1, title="one run")
    >>> len(fig.axes)
    1
    """
    from matplotlib.colors import ListedColormap

    plt = pyplot()
    fig, axes = plt.subplots(len(laws), len(spins), figsize=(max(4.4 * len(spins) + 1.0, 10.0), 4.0 * len(laws) + 1.2),
                             squeeze=False, sharex=True, sharey=True)
    cmap = ListedColormap(list(PREDICTED_COLORS))
    for i, (law, mu) in enumerate(laws):
        for j, n0 in enumerate(spins):
            ax = axes[i, j]
            _predicted(ax, cmap, C, n0, theta0)
            for r in rows:
                if r.law == law and r.mu == mu and r.n0 == n0:
                    _measured(ax, r)
            ax.set_title(f"{law} $\\mu$={mu:g}, $n_0$={n0:g}", fontsize=10)
            ax.set_xlim(*ALPHA_LIM)
            ax.set_ylim(*GAMMA_LIM)
            if i == len(laws) - 1:
                ax.set_xlabel(r"$\alpha$ = OG / radius")
            if j == 0:
                ax.set_ylabel(r"$\gamma = A/C$ (moments about G)")
    _map_legend(fig, cmap.colors)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0.1, 1, 0.95))
    return fig


def plot_hopping(traj, *, n: int = 20001, title: str = ""):
    """A figure of a tippe top's run through its hops: theta(t) (pi dotted), the normal reaction
    R(t) in contact with every lift-off marked (red), and the gap in flight (log scale),
    sampled at ``n`` times.

    Examples
    --------
    >>> import math, phasekit as pk, phasekit.studies as ps
    >>> top = pk.EccentricSphere(0.3, A=0.38, C=0.4)
    >>> traj = pk.simulate(pk.Model(top, pk.Coulomb(0.3), "vector"), pk.core.to_chart("vector", pk.core.vertical_spin_start(0.1, 15.0)),
    ...                    20.0, rtol=1e-10, stop_at="none")
    >>> len(ps.plot_hopping(traj, n=2001, title="first hops").axes)
    3
    """
    plt = pyplot()
    ts = np.linspace(traj.t0, traj.t, n)
    df = traj.sample(ts)
    fig, axes = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True)
    axes[0].plot(ts, df["theta"], "k", lw=1)
    axes[0].axhline(math.pi, color="0.6", ls=":")
    axes[0].set_ylabel(r"$\theta$ (rad)")
    R = np.where(df["mode"] == "flight", np.nan, df["R"])
    axes[1].plot(ts, R, "C0", lw=0.8)
    axes[1].axhline(0.0, color="r", lw=0.8)
    axes[1].set_ylabel(r"$R$ (units $Mg$)")
    axes[2].semilogy(ts, np.where(df["gap"] > 0, df["gap"], np.nan), "C3", lw=1)
    axes[2].set_ylabel("gap (units b)")
    axes[2].set_xlabel(r"$t$ (units $\sqrt{b/g}$)")
    for e in traj.events_named("lift-off"):
        axes[1].axvline(e.t, color="r", alpha=0.15, lw=0.6)
    axes[0].set_title(title, fontsize=10)
    fig.tight_layout()
    return fig


def _snapshots(pl, pv, ts, k, zG, theta, alpha: float, n_snap: int, dx: float) -> np.ndarray:
    """The top at ``n_snap`` instants side by side on the table: ball, stem along +k, G in black."""
    picks = np.linspace(0, len(ts) - 1, n_snap).astype(int)
    for j, i in enumerate(picks):
        ball = np.array([j * dx, 0.0, zG[i]]) + alpha * k[i] * np.array([0.0, 0.0, 1.0])  # the ball's centre O
        G = ball - alpha * k[i]
        pl.add_mesh(pv.Sphere(radius=1.0, center=ball, theta_resolution=48, phi_resolution=48), color="#fdae6b", opacity=0.45)
        pl.add_mesh(pv.Cylinder(center=ball + 1.12 * k[i], direction=k[i], radius=0.13, height=0.3), color="#8c2d04")
        pl.add_mesh(pv.Sphere(radius=0.08, center=G), color="k")
        pl.add_point_labels([np.array([j * dx, 0.0, 2.75])], [f"t={ts[i]:.1f}, theta={theta[i]:.2f}"], font_size=14,
                            text_color="k", shape=None, show_points=False)
    return picks


def render_inversion(traj, path, *, title: str = "", n: int = 12000) -> dict:
    """A 3-D scene of one inversion (PyVista, off-screen; a tippe top's run, an
    :class:`phasekit.EccentricSphere` in the vector chart). Left: the path of the axis k(t)
    drawn on a sphere of radius 1.3 around the ball's centre (the stem's direction, from the
    north pole to the south pole), coloured by time. Right: the top at six instants side by
    side on the table (ball, stem along +k, centre of mass G in black), each at its computed
    height (h(theta) + gap). Writes ``path`` (PNG); returns the image's standard deviation (a
    blank image has 0) and theta at the six instants.

    Examples
    --------
    >>> import tempfile, pathlib, phasekit as pk, phasekit.studies as ps
    >>> top = pk.EccentricSphere(0.3, A=0.38, C=0.4)
    >>> traj = pk.simulate(pk.Model(top, pk.Coulomb(0.3), "vector"), pk.core.to_chart("vector", pk.core.vertical_spin_start(0.1, 15.0)),
    ...                    5.0, rtol=1e-10, stop_at="none")
    >>> info = ps.render_inversion(traj, pathlib.Path(tempfile.mkdtemp()) / "scene.png", n=500)
    >>> info["image_std"] > 0, len(info["theta_snapshots"])
    (True, 6)
    """
    import pyvista as pv

    pv.OFF_SCREEN = True
    alpha = traj.model.body.offset
    ts = np.linspace(traj.t0, traj.t, n)
    X = traj.states(ts)
    k = X[:, 0:3] / np.linalg.norm(X[:, 0:3], axis=1)[:, None]
    df = traj.sample(ts)
    zG = (df["h"] + df["gap"]).to_numpy()
    pl = pv.Plotter(off_screen=True, window_size=[1500, 820])
    pl.set_background("white")
    n_snap, dx, x_left = 6, 2.7, -3.4
    pl.add_mesh(pv.Plane(center=(0.5 * (x_left + (n_snap - 1) * dx), 0.0, 0.0), direction=(0, 0, 1),
                         i_size=(n_snap - 1) * dx - x_left + 3.0, j_size=3.4), color="#e0e0e0")
    centre = np.array([x_left, 0.0, 1.0 + 0.3])
    line = pv.lines_from_points(centre + 1.3 * k)
    line["t"] = ts
    pl.add_mesh(line, scalars="t", cmap="viridis", line_width=2.5, scalar_bar_args=dict(title="t (units sqrt(b/g))",
                color="k", vertical=False, position_x=0.05, position_y=0.08, width=0.3, title_font_size=14,
                label_font_size=12))
    pl.add_mesh(pv.Sphere(radius=1.0, center=centre, theta_resolution=48, phi_resolution=48), color="#9ecae1", opacity=0.3)
    pl.add_point_labels([centre + np.array([0.0, 0.0, 1.75])], ["axis k(t)"], font_size=16, text_color="k", shape=None,
                        show_points=False)
    theta = df["theta"].to_numpy()
    picks = _snapshots(pl, pv, ts, k, zG, theta, alpha, n_snap, dx)
    pl.add_text(title, font_size=12, color="k", position="upper_left")
    pl.enable_parallel_projection()
    mid = 0.5 * (x_left + (n_snap - 1) * dx)
    pl.camera_position = [(mid, -30.0, 9.0), (mid, 0.0, 1.0), (0, 0, 1)]
    pl.camera.parallel_scale = 5.6
    img = pl.screenshot(str(path), return_img=True)
    pl.close()
    return {"image_std": float(img.std()), "theta_snapshots": [float(theta[i]) for i in picks]}
