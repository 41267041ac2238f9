"""The jump surface (6.3) in (Omega, theta, n), the exact boundary R = 0, and 3-D scenes.

Section 6: in the gyroscopic region R = 0 is close to the 2-D surface (6.3),

    n = (A/C) (Omega cos(theta) + 1 / (Omega h_theta sin(theta))),

which is (6.1) with the Lambda^2 term dropped. The exact boundary is 5-dimensional; its section
at given Lambda (and the gyroscopic slip direction, which only enters the denominator of (6.1))
is n = (A/C) (Omega cos(theta) + (1 + h_tt Lambda^2) / (Omega h_theta sin(theta))).
:func:`exact_boundary` finds it independently, by root finding on the model's normal reaction;
at Lambda = 0 it coincides with (6.3), and trajectories cross R = 0 with Lambda != 0 (the fast
nutation), which is where (6.3) and the crossings differ.

A :class:`Scene` says which elements to draw; :func:`compute_scene` computes only the data
those elements need (no simulation unless trajectories or crossings are asked for), and
:func:`phasekit.viz.render_scene` draws it off-screen with PyVista (imported there only).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .body import Body, Spheroid
from .friction import Coulomb
from .model import Model

__all__ = ["surface_n", "exact_boundary", "Scene", "SceneData", "Crossing", "compute_scene", "ELEMENTS"]

ELEMENTS = frozenset({"surface", "exact_boundary", "trajectories", "crossings", "fixed_points", "axes", "colorbar"})


def surface_n(body, Omega, theta):
    """(6.3): the spin n on the approximate jump surface at (Omega, theta)."""
    h, ht, _ = body.h(theta)
    return body.A / body.C * (Omega * np.cos(theta) + 1.0 / (Omega * ht * np.sin(theta)))


def exact_boundary(body, mu: float, Omega, theta, Lambda: float = 0.0):
    """n at which the model's normal reaction (6.1) vanishes, for U = V = 0 and the given Lambda.

    Found by Brent's method on R(n) from the compiled model (Coulomb friction, slip direction
    of that state), independently of the closed form (6.3)."""
    from scipy.optimize import brentq

    model = Model(body, Coulomb(mu))
    Rf = model.function("R_sliding")
    Om = np.atleast_1d(np.asarray(Omega, dtype=float))
    Th = np.atleast_1d(np.asarray(theta, dtype=float))
    Om, Th = np.broadcast_arrays(Om, Th)
    out = np.full(Om.shape, np.nan)
    for idx in np.ndindex(Om.shape):
        om, th = Om[idx], Th[idx]
        guess = surface_n(body, om, th)
        f = lambda n: float(Rf(np.array([0.0, 0.0, om, Lambda, th, n]), model.p))  # noqa: E731
        span = 1e-3 + 0.2 * abs(guess) + abs(Lambda) * 10
        lo, hi = guess - span, guess + span
        for _ in range(40):
            if f(lo) * f(hi) < 0:
                break
            lo, hi = lo - span, hi + span
            span *= 2
        else:
            continue
        out[idx] = brentq(f, lo, hi, xtol=1e-14, rtol=1e-15)
    return out if out.ndim else float(out)


@dataclass(frozen=True)
class Scene:
    """What to draw: the branch, the trajectories' family parameter values, and the elements.

    ``show`` is a subset of ELEMENTS. ``exact_lambda`` is the Lambda of the exact-boundary
    section (None: the median |Lambda| of the computed crossings, or 0 without them).
    """

    branch: str = "prolate"  # prolate: from the horizontal state (Omega0); oblate: from the vertical (n0)
    a: float = 1.5
    mu: float = 0.1
    values: tuple[float, ...] = (10.0, 12.0, 15.0, 20.0, 30.0)
    seed_distance: float = 0.01  # sliding-branch seeds, the default threshold definition
    show: frozenset = field(default_factory=lambda: frozenset({"surface", "trajectories", "crossings", "fixed_points", "axes", "colorbar"}))
    omega_range: tuple[float, float] | None = None
    theta_range: tuple[float, float] | None = None
    n_clip: tuple[float, float] | None = None
    resolution: int = 120
    exact_lambda: float | None = None
    dt: float = 0.02  # output spacing of the drawn trajectories
    body: Body | None = None  # any body (overrides `a`); default: the uniform Spheroid(a)

    def __post_init__(self):
        unknown = set(self.show) - ELEMENTS
        if unknown:
            raise ValueError(f"`show` must be a subset of {sorted(ELEMENTS)}; unknown: {sorted(unknown)}.")
        if self.branch not in ("prolate", "oblate"):
            raise ValueError(f"`branch` must be prolate or oblate, got {self.branch!r}.")
        if self.body is not None and not isinstance(self.body, Body):
            raise ValueError(f"`body` must be a phasekit Body, got {self.body!r}.")
        if self.body is not None and self.body.is_prolate != (self.branch == "prolate"):
            raise ValueError(f"`body` must be prolate for the prolate branch and oblate for the oblate one, got {self.body!r}.")
        if self.body is None and (self.a > 1) != (self.branch == "prolate"):
            raise ValueError(f"`a` must be > 1 for the prolate branch and < 1 for the oblate one, got {self.a!r}.")

    def make_body(self) -> Body:
        return self.body if self.body is not None else Spheroid(self.a)


@dataclass(frozen=True)
class Crossing:
    value: float  # Omega0 or n0 of the trajectory
    t: float
    Omega: float
    theta: float
    n: float
    Lambda: float
    n_surface: float  # (6.3) at the crossing's (Omega, theta)

    @property
    def rel_error(self) -> float:
        """Relative error in n of (6.3) at the crossing."""
        return abs(self.n_surface - self.n) / abs(self.n)


@dataclass
class SceneData:
    scene: Scene
    surface: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None  # Omega, theta, n grids
    exact: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
    exact_lambda: float | None = None
    trajectories: list = field(default_factory=list)  # (N, 3) arrays of (Omega, theta, n)
    crossings: list = field(default_factory=list)
    fixed_points: np.ndarray | None = None
    n_simulations: int = 0
    bounds: tuple | None = None


def _simulate(scene: Scene, value: float, dense: bool):
    from .hybrid import Event
    from .simulate import simulate
    from .starts import gyroscopic_start

    body = scene.make_body()
    model = Model(body, Coulomb(scene.mu))
    if scene.branch == "prolate":
        y0 = gyroscopic_start(body, math.pi / 2 - scene.seed_distance, omega0=value)
        rise = Event("theta", 0.05, direction=-1, name="rise-complete")
    else:
        y0 = gyroscopic_start(body, scene.seed_distance, n0=value)
        rise = Event("theta", math.pi / 2 - 0.05, direction=+1, name="rise-complete")
    return body, simulate(model, y0, 1000.0, events=[rise], track_minima=False, dense=dense)


def compute_scene(scene: Scene) -> SceneData:
    """Compute exactly the data the scene's elements need."""
    show = scene.show
    data = SceneData(scene)
    body = scene.make_body()
    need_sims = bool({"trajectories", "crossings"} & show)
    if need_sims:
        for v in scene.values:
            _, r = _simulate(scene, v, dense="trajectories" in show)
            data.n_simulations += 1
            if "trajectories" in show:
                pts = r.states(np.arange(0.0, r.t, scene.dt))[:, [2, 4, 5]]
                if r.x_jump is not None:
                    pts = np.vstack([pts, r.x_jump[[2, 4, 5]]])
                data.trajectories.append(pts)
            if r.x_jump is not None:
                U, V, Om, Lam, th, n = r.x_jump
                data.crossings.append(Crossing(v, r.t_jump, Om, th, n, Lam, float(surface_n(body, Om, th))))
    # ranges: from the trajectories when there are any, else sensible defaults
    vals = np.asarray(scene.values, dtype=float)
    if scene.omega_range is not None:
        om_rng = scene.omega_range
    elif scene.branch == "prolate":
        om_rng = (0.75 * vals.min(), 1.05 * vals.max())
    else:
        lo = body.C * vals.min() / body.A
        om_rng = (0.6 * lo, 1.1 * body.C * vals.max() / body.A)
    th_rng = scene.theta_range or ((0.35, math.pi / 2 - 0.03) if scene.branch == "prolate" else (0.05, math.pi / 2 - 0.35))
    if need_sims and data.crossings:
        th_c = [c.theta for c in data.crossings]
        th_rng = (min(th_rng[0], min(th_c) - 0.1), th_rng[1]) if scene.branch == "prolate" else (th_rng[0], max(th_rng[1], max(th_c) + 0.1))
    if "surface" in show or "exact_boundary" in show:
        om = np.linspace(*om_rng, scene.resolution)
        th = np.linspace(*th_rng, scene.resolution)
        OM, TH = np.meshgrid(om, th, indexing="ij")
        if "surface" in show:
            data.surface = (OM, TH, surface_n(body, OM, TH))
        if "exact_boundary" in show:
            lam = scene.exact_lambda
            if lam is None:
                lam = float(np.median([abs(c.Lambda) for c in data.crossings])) if data.crossings else 0.0
            data.exact_lambda = lam
            coarse = max(20, scene.resolution // 4)
            om_c, th_c = np.linspace(*om_rng, coarse), np.linspace(*th_rng, coarse)
            OMc, THc = np.meshgrid(om_c, th_c, indexing="ij")
            data.exact = (OMc, THc, exact_boundary(body, scene.mu, OMc, THc, lam))
    if "fixed_points" in show:
        if scene.branch == "prolate":  # horizontal steady precessions (Omega0, pi/2, 0)
            data.fixed_points = np.array([[v, math.pi / 2, 0.0] for v in scene.values])
        else:  # vertical spins: theta = 0, plotted at the fast-branch limit Omega = C n0 / A
            data.fixed_points = np.array([[body.C * v / body.A, 0.0, v] for v in scene.values])
    n_all = []
    for tr in data.trajectories:
        n_all.append(tr[:, 2])
    if data.crossings:
        n_all.append(np.array([c.n for c in data.crossings]))
    if data.fixed_points is not None:
        n_all.append(data.fixed_points[:, 2])
    if scene.n_clip is not None:
        n_lo, n_hi = scene.n_clip
    elif n_all:
        n_cat = np.concatenate(n_all)
        span = max(n_cat.max() - n_cat.min(), 1.0)
        n_lo, n_hi = n_cat.min() - 0.3 * span, n_cat.max() + 0.3 * span
    else:
        n_lo, n_hi = (-5.0, 40.0)
    th_lo = min(th_rng[0], 0.0 if scene.branch == "oblate" and "fixed_points" in show else th_rng[0])
    th_hi = max(th_rng[1], math.pi / 2 if scene.branch == "prolate" and "fixed_points" in show else th_rng[1])
    data.bounds = (om_rng[0], om_rng[1], th_lo, th_hi, n_lo, n_hi)
    return data
