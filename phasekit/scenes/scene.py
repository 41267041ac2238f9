"""3-D scenes of the jump surface in (Omega, theta, n): which elements to draw, and their data.

A :class:`Scene` says which elements to draw (the surface (6.3) and the exact boundary R = 0 of
:mod:`phasekit.theory.jump_surface` and :mod:`phasekit.scenes.boundary`, trajectories, their crossings of R = 0, fixed points, axes);
:func:`compute_scene` computes only the data those elements need (no simulation unless
trajectories or crossings are asked for), and :func:`phasekit.viz.render_scene` draws it
off-screen with PyVista (imported there only).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np

from .._runtime.validate import (
    check_array,
    check_instance,
    check_int,
    check_nonnegative,
    check_positive,
    check_range,
)
from ..bodies.body import Body
from ..bodies.spheroid import Spheroid
from ..core.model import Model
from ..errors import ParameterError
from ..friction.laws import Coulomb, FrictionLaw
from ..theory.jump_surface import surface_n_unchecked
from .boundary import exact_boundary_unchecked

ELEMENTS = frozenset({"surface", "exact_boundary", "trajectories", "crossings", "fixed_points", "axes", "colorbar"})

#: the scene's axes: (Omega, theta, n) with the paper's units (time unit sqrt(b/g))
AXES = (("Omega", "sqrt(g/b)"), ("theta", "rad"), ("n", "sqrt(g/b)"))


def _pair(name: str, value) -> tuple[float, float] | None:
    if value is None:
        return None
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ParameterError(name, "must be a pair (lo, hi) of numbers", value) from None
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ParameterError(name, "must be a pair (lo, hi) of finite numbers with lo < hi", value)
    return lo, hi


@dataclass(frozen=True)
class Scene:
    """What to draw in (Omega, theta, n): the branch, the family values of the simulated
    trajectories, the user's own trajectories, and the elements.

    Parameters
    ----------
    branch : {"prolate", "oblate"}
        prolate: trajectories start next to the horizontal steady precession (``values`` are
        Omega0); oblate: next to the vertical spin (``values`` are n0).
    a : float
        Aspect ratio of the uniform spheroid (ignored when ``body`` is given).
    mu : float
        Coulomb friction coefficient (ignored when ``friction`` is given).
    values : tuple of float
        Family parameter of each simulated trajectory (may be empty).
    seed_distance : float in (0, pi/2)
        Distance of the sliding-branch seeds from the fixed point.
    show : frozenset
        A subset of :data:`ELEMENTS`.
    omega_range, theta_range, n_clip : (lo, hi), optional
        The drawn box. By default it holds every drawn point; given ranges clip the
        trajectories (nothing is drawn outside the axes box).
    resolution : int >= 2
        Grid points per direction of the surface.
    exact_lambda : float, optional
        Lambda of the exact-boundary section (None: the median of abs(Lambda) over the
        computed crossings, or 0 without them).
    dt : float > 0
        Output spacing of the drawn trajectories.
    body : Body, optional
        Any body (a user-defined :class:`phasekit.bodies.Body` subclass too); default Spheroid(a).
    friction : FrictionLaw, optional
        Any friction law; default Coulomb(mu).

    Raises
    ------
    ParameterError
        If ``show`` is not a subset of :data:`ELEMENTS`; ``branch`` is not "prolate" or
        "oblate", or does not match the body (prolate: ``a`` > 1, or h(0) > h(pi/2) for a
        given ``body``); ``body`` is not a Body or ``friction`` not a FrictionLaw; ``a`` is
        outside [1e-4, 1e4] (without ``body``); ``mu`` is not a finite number >= 0; ``values``
        is not a sequence of finite numbers > 0;
        ``seed_distance`` is outside (0, pi/2); a range is not a pair (lo, hi) of finite
        numbers with lo < hi (``theta_range`` inside [0, pi]); ``resolution`` is not an integer
        in [2, 4000]; ``dt`` is not a finite number > 0; or ``exact_lambda`` is outside
        (-1000, 1000).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> scene = pk.Scene("prolate", 1.5, values=(), show=frozenset({"trajectories", "axes"}))
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.5, omega0=12.0), 100.0)
    >>> scene.add_trajectory(traj).n_trajectories
    1
    """

    branch: str = "prolate"
    a: float = 1.5
    mu: float = 0.1
    values: tuple[float, ...] = (10.0, 12.0, 15.0, 20.0, 30.0)
    seed_distance: float = 0.01  # sliding-branch seeds, the default threshold definition
    show: frozenset = field(default_factory=lambda: frozenset({"surface", "trajectories", "crossings", "fixed_points",
                                                               "axes", "colorbar"}))
    omega_range: tuple[float, float] | None = None
    theta_range: tuple[float, float] | None = None
    n_clip: tuple[float, float] | None = None
    resolution: int = 120
    exact_lambda: float | None = None
    dt: float = 0.02  # output spacing of the drawn trajectories
    body: Body | None = None
    friction: FrictionLaw | None = None
    extra: list = field(default_factory=list, compare=False, hash=False, repr=False)

    def __post_init__(self):
        if isinstance(self.show, (str, bytes)) or not isinstance(self.show, (set, frozenset, list, tuple)):
            raise ParameterError("show", f"must be a set of element names, a subset of {', '.join(sorted(ELEMENTS))}",
                                 self.show)
        unknown = set(self.show) - ELEMENTS
        if unknown:
            raise ParameterError("show", f"must be a subset of {', '.join(sorted(ELEMENTS))} (unknown: "
                                         f"{', '.join(sorted(map(str, unknown)))})", show_value=False)
        if self.branch not in ("prolate", "oblate"):
            raise ParameterError("branch", "must be prolate or oblate", self.branch)
        if self.body is not None and not isinstance(self.body, Body):
            raise ParameterError("body", "must be a phasekit Body", self.body)
        if self.friction is not None and not isinstance(self.friction, FrictionLaw):
            raise ParameterError("friction", "must be a phasekit FrictionLaw", self.friction)
        body = self.make_body()
        if body.is_prolate != (self.branch == "prolate"):
            what = "`a` must be > 1" if self.body is None else "the body must be prolate (h(0) > h(pi/2))"
            raise ParameterError("branch", f"{self.branch} does not match the body ({what} for the prolate branch, "
                                           "the reverse for the oblate one)", self.branch)
        object.__setattr__(self, "show", frozenset(self.show))
        check_nonnegative("mu", self.mu)
        if isinstance(self.values, (str, bytes, dict, set, frozenset)) or not np.iterable(self.values):
            raise ParameterError("values", "must be a sequence of finite numbers > 0", self.values)
        vals = tuple(check_positive("values", v) for v in self.values)
        object.__setattr__(self, "values", vals)
        check_range("seed_distance", self.seed_distance, 0.0, np.pi / 2, label="(0, pi/2)")
        for name in ("omega_range", "theta_range", "n_clip"):
            object.__setattr__(self, name, _pair(name, getattr(self, name)))
        if self.theta_range is not None and not (0.0 <= self.theta_range[0] and self.theta_range[1] <= np.pi):
            raise ParameterError("theta_range", "must be a pair (lo, hi) with 0 <= lo < hi <= pi", self.theta_range)
        object.__setattr__(self, "resolution", check_int("resolution", self.resolution, minimum=2, maximum=4000))
        check_positive("dt", self.dt)
        if self.exact_lambda is not None:
            check_range("exact_lambda", self.exact_lambda, -1e3, 1e3)

    def make_body(self) -> Body:
        return self.body if self.body is not None else Spheroid(self.a)

    def make_friction(self) -> FrictionLaw:
        return self.friction if self.friction is not None else Coulomb(self.mu)

    def add_trajectory(self, traj, label: str | None = None, *, bodies=()) -> "Scene":
        """Draw ``traj`` (any :class:`phasekit.core.Trajectory` with dense output) too, and its
        lift-off point as a crossing.

        Parameters
        ----------
        traj : Trajectory
            A run of :func:`phasekit.simulate` that kept its dense output (``dense=True``, the
            default).
        label : str, optional
            Its label (None: "trajectory k", k its number among the drawn trajectories).
        bodies : array_like, optional
            Times of the run, inside [traj.t0, traj.t], at which the body itself is drawn on
            the trajectory, turned as it is then (its pose: psi, theta, phi). Default: none.

        Returns
        -------
        Scene
            The scene, so calls chain.

        Raises
        ------
        ParameterError
            If ``traj`` is not a Trajectory or has no dense output, ``label`` is neither a
            string nor None, or ``bodies`` is not finite times inside the run.
        """
        from ..core.trajectory import Trajectory

        if not isinstance(traj, Trajectory):
            raise ParameterError("traj", "must be a phasekit Trajectory (from pk.simulate)", traj)
        if not traj.segments or not all(s.dense for s in traj.segments):
            raise ParameterError("traj", "must keep its dense output (simulate with dense=True, the default)"
                                 + _dropped(traj), show_value=False)
        if label is not None and not isinstance(label, str):
            raise ParameterError("label", "must be a string or None", label)
        times = check_array("bodies", bodies, allow_empty=True).ravel()
        if np.any((times < traj.t0) | (times > traj.t)):
            raise ParameterError("bodies", f"must be times inside the run [{traj.t0:.10g}, {traj.t:.10g}]", times)
        self.extra.append((traj, label, tuple(float(t) for t in times)))
        return self

    @property
    def n_trajectories(self) -> int:
        """Trajectories drawn: the simulated ones and the user's."""
        return len(self.values) + len(self.extra)


@dataclass(frozen=True)
class Crossing:
    """Where a trajectory reached R = 0: its family value (None for a user's trajectory),
    time and state, and n on (6.3) at the same (Omega, theta).

    Attributes
    ----------
    value : float or None
        Omega0 or n0 of the trajectory (None for a user's trajectory).
    t : float
        Time of the crossing (the lift-off), units sqrt(b/g).
    Omega, theta, n, Lambda : float
        The state there: precession rate, inclination (radians), spin and dtheta/dt.
    n_surface : float
        n on (6.3) at the crossing's (Omega, theta).
    """

    value: float | None  # Omega0 or n0 of the trajectory
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


@dataclass(frozen=True)
class SceneData:
    """What :func:`compute_scene` computed: the grids, the trajectories' (Omega, theta, n)
    points, the crossings, the fixed points and the box ``bounds`` (Omega, theta, n pairs).

    Attributes
    ----------
    scene : Scene
        The scene computed.
    surface : tuple of numpy.ndarray or None
        The Omega, theta and n grids of (6.3) (element "surface").
    exact : tuple of numpy.ndarray or None
        The Omega, theta and n grids of the exact boundary (element "exact_boundary"; NaN where
        none was found).
    exact_lambda : float or None
        The Lambda of that section.
    trajectories : list of numpy.ndarray
        The drawn trajectories, each an (N, 3) array of (Omega, theta, n).
    crossings : list of Crossing
        Where the trajectories reached R = 0.
    fixed_points : numpy.ndarray or None
        The family's fixed points, rows (Omega, theta, n).
    n_simulations : int
        Simulations run for the scene.
    bounds : tuple of float
        The axes box (Omega lo, hi, theta lo, hi, n lo, hi).
    labels : list
        One label per trajectory (None for a simulated one).
    bodies : list
        The bodies to draw, each (body, (Omega, theta, n), rotation matrix).
    """

    scene: Scene
    surface: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None  # Omega, theta, n grids
    exact: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
    exact_lambda: float | None = None
    trajectories: list = field(default_factory=list)  # (N, 3) arrays of (Omega, theta, n)
    crossings: list = field(default_factory=list)
    fixed_points: np.ndarray | None = None
    n_simulations: int = 0
    bounds: tuple | None = None
    labels: list = field(default_factory=list)  # one per trajectory (None: a simulated one)
    bodies: list = field(default_factory=list)  # (body, (Omega, theta, n), rotation matrix) to draw


@dataclass
class _SceneBuilder:
    """SceneData while :func:`compute_scene` fills it in."""

    scene: Scene
    surface: tuple | None = None
    exact: tuple | None = None
    exact_lambda: float | None = None
    trajectories: list = field(default_factory=list)
    crossings: list = field(default_factory=list)
    fixed_points: np.ndarray | None = None
    n_simulations: int = 0
    bounds: tuple | None = None
    labels: list = field(default_factory=list)
    bodies: list = field(default_factory=list)


def _simulate(scene: Scene, value: float, dense: bool):
    from ..core.hybrid import Event
    from ..core.simulate import simulate
    from ..core.starts import gyroscopic_start

    body = scene.make_body()
    model = Model(body, scene.make_friction())
    if scene.branch == "prolate":
        y0 = gyroscopic_start(body, math.pi / 2 - scene.seed_distance, omega0=value)
        rise = Event("theta", 0.05, direction=-1, name="rise-complete")
    else:
        y0 = gyroscopic_start(body, scene.seed_distance, n0=value)
        rise = Event("theta", math.pi / 2 - 0.05, direction=+1, name="rise-complete")
    return body, simulate(model, y0, 1000.0, events=[rise], track_minima=False, dense=dense)


def _add_run(data: _SceneBuilder, body, r, value, label, show) -> None:
    """The drawn points and the crossing of one trajectory."""
    if "trajectories" in show:
        ts = np.arange(r.t0, r.t, data.scene.dt)
        pts = r.sample(ts)[["Omega", "theta", "n"]].to_numpy()
        if r.x_jump is not None:
            pts = np.vstack([pts, r.model.chart.to_paper(r.x_jump)[[2, 4, 5]]])
        data.trajectories.append(pts)
        data.labels.append(label)
    if r.x_jump is not None:
        U, V, Om, Lam, th, n = r.model.chart.to_paper(r.x_jump)
        data.crossings.append(Crossing(value, r.t_jump, Om, th, n, Lam, float(surface_n_unchecked(body, Om, th))))


def _ranges(scene: Scene, data: SceneData, body) -> tuple:
    """(Omega, theta) ranges of the surface grid: given, or from the values and the data."""
    vals = np.asarray(scene.values, dtype=float)
    pts = np.vstack(data.trajectories) if data.trajectories else np.empty((0, 3))
    if scene.omega_range is not None:
        om_rng = scene.omega_range
    elif vals.size:
        om_rng = ((0.75 * vals.min(), 1.05 * vals.max()) if scene.branch == "prolate"
                  else (0.6 * body.C * vals.min() / body.A, 1.1 * body.C * vals.max() / body.A))
    elif pts.size:
        om_rng = (0.9 * pts[:, 0].min(), 1.1 * pts[:, 0].max())
    else:
        om_rng = (8.0, 30.0)
    if pts.size and scene.omega_range is None:  # hold every drawn point
        om_rng = (min(om_rng[0], pts[:, 0].min()), max(om_rng[1], pts[:, 0].max()))
    default_th = (0.35, math.pi / 2 - 0.03) if scene.branch == "prolate" else (0.05, math.pi / 2 - 0.35)
    th_rng = scene.theta_range or default_th
    if data.crossings and scene.theta_range is None:
        th_c = [c.theta for c in data.crossings]
        th_rng = ((min(th_rng[0], min(th_c) - 0.1), th_rng[1]) if scene.branch == "prolate"
                  else (th_rng[0], max(th_rng[1], max(th_c) + 0.1)))
    return om_rng, th_rng


def compute_scene(scene: Scene) -> SceneData:
    """Compute exactly the data the scene's elements need (no simulation for a scene
    without trajectories or crossings).

    Parameters
    ----------
    scene : Scene
        What to draw: the branch, the family values, the user's trajectories, the elements.

    Returns
    -------
    SceneData
        The surface and exact-boundary grids, the trajectories' (Omega, theta, n) points, the
        crossings of R = 0, the fixed points and the axes box, each computed only if an
        element of ``scene.show`` needs it.

    Raises
    ------
    ParameterError
        If ``scene`` is not a Scene.

    Examples
    --------
    >>> import phasekit as pk
    >>> data = pk.compute_scene(pk.Scene('prolate', 1.5, values=(12.0,), show={'crossings'}))
    >>> len(data.crossings), round(data.crossings[0].theta, 4)
    (1, np.float64(0.9774))
    """
    check_instance("scene", scene, Scene, 'Scene("prolate", 1.5)')
    show = scene.show
    data = _SceneBuilder(scene)
    body = scene.make_body()
    if {"trajectories", "crossings"} & show:
        for v in scene.values:
            _, r = _simulate(scene, v, dense="trajectories" in show)
            data.n_simulations += 1
            _add_run(data, body, r, v, None, show)
        for traj, label, times in scene.extra:
            _add_run(data, body, traj, None, label or f"trajectory {len(data.labels) + 1}", show)
            if times and "trajectories" in show:
                from ..core.pose import rotation_matrix

                df = traj.sample(list(times))
                for _, row in df.iterrows():
                    data.bodies.append((traj.model.body, (row["Omega"], row["theta"], row["n"]),
                                        rotation_matrix(row["psi"], row["theta"], row["phi"])))
    om_rng, th_rng = _ranges(scene, data, body)
    if "surface" in show or "exact_boundary" in show:
        _grids(scene, data, body, om_rng, th_rng)
    if "fixed_points" in show and scene.values:
        if scene.branch == "prolate":  # horizontal steady precessions (Omega0, pi/2, 0)
            data.fixed_points = np.array([[v, math.pi / 2, 0.0] for v in scene.values])
        else:  # vertical spins: theta = 0, plotted at the fast-branch limit Omega = C n0 / A
            data.fixed_points = np.array([[body.C * v / body.A, 0.0, v] for v in scene.values])
    data.bounds = _bounds(scene, data, om_rng, th_rng)
    return SceneData(**{f.name: getattr(data, f.name) for f in fields(data)})


def _grids(scene, data, body, om_rng, th_rng) -> None:
    om = np.linspace(*om_rng, scene.resolution)
    th = np.linspace(*th_rng, scene.resolution)
    OM, TH = np.meshgrid(om, th, indexing="ij")
    if "surface" in scene.show:
        with np.errstate(divide="ignore", invalid="ignore"):
            data.surface = (OM, TH, surface_n_unchecked(body, OM, TH))
    if "exact_boundary" in scene.show:
        lam = scene.exact_lambda
        if lam is None:
            lam = float(np.median([abs(c.Lambda) for c in data.crossings])) if data.crossings else 0.0
        data.exact_lambda = lam
        coarse = max(20, scene.resolution // 4)
        OMc, THc = np.meshgrid(np.linspace(*om_rng, coarse), np.linspace(*th_rng, coarse), indexing="ij")
        data.exact = (OMc, THc, exact_boundary_unchecked(body, scene.mu, OMc, THc, lam, friction=scene.friction))


def _bounds(scene, data, om_rng, th_rng) -> tuple:
    """The axes box (Omega lo, hi, theta lo, hi, n lo, hi)."""
    n_all = [tr[:, 2] for tr in data.trajectories]
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
    th_lo, th_hi = th_rng
    pts = [np.vstack(data.trajectories)] if data.trajectories else []
    if data.fixed_points is not None:
        pts.append(data.fixed_points)
    if pts and scene.theta_range is None:
        P = np.vstack(pts)
        th_lo, th_hi = min(th_lo, P[:, 1].min()), max(th_hi, P[:, 1].max())
    om_lo, om_hi = om_rng
    if data.fixed_points is not None and scene.omega_range is None:
        om_lo, om_hi = min(om_lo, data.fixed_points[:, 0].min()), max(om_hi, data.fixed_points[:, 0].max())
    return tuple(float(v) for v in (om_lo, om_hi, th_lo, th_hi, n_lo, n_hi))


def _dropped(traj) -> str:
    """The clause of a run that dropped its dense output under ``max_dense_mb`` (else empty)."""
    from ..core.energy import dropped_note

    note = dropped_note(traj)
    return f": {note}" if note else ""
