"""The public API refuses bad input with a ParameterError naming the argument (scenes and
rendering, plots, the jump surface, impacts, units, the paper's starts), and the valid calls
still give the known values (closed forms, not values recorded from the code)."""

import math
import os

import phasekit as pk
from phasekit.core import units
from phasekit.core.impact import collision_matrix, contact_point
from phasekit.theory.surface import Scene, compute_scene

import numpy as np
import pytest

os.environ.setdefault("MPLBACKEND", "Agg")
NAN, INF = float("nan"), float("inf")
B = pk.Spheroid(1.5)
A_UNIFORM = (1 + 1.5**2) / 5  # the uniform spheroid's A (C = 2/5)


def _raises(name, call):
    with pytest.raises(pk.ParameterError, match=f"`{name}`") as info:
        call()
    assert info.value.param == name
    return info.value


# ---------------------------------------------------------------------------------------------
# the jump surface (6.3) and the exact boundary


def _closed_form_6_3(a, Om, th):
    """(6.3) for the uniform spheroid written out: h_t = (1 - a^2) cos sin / h."""
    A, C = (1 + a * a) / 5, 0.4
    h = np.sqrt(a * a * np.cos(th) ** 2 + np.sin(th) ** 2)
    ht = (1 - a * a) * np.cos(th) * np.sin(th) / h
    return A / C * (Om * np.cos(th) + 1 / (Om * ht * np.sin(th)))


@pytest.mark.parametrize("name, args", [
    ("theta", (12.0, NAN)),
    ("theta", (12.0, 0.0)),
    ("theta", (12.0, -0.3)),
    ("theta", (12.0, math.pi)),
    ("theta", (12.0, INF)),
    ("theta", (12.0, math.pi / 2)),  # h_theta = 0: (6.3) infinite
    ("theta", (12.0, "1.0")),
    ("theta", ([8.0, 9.0, 10.0], [1.0, 1.1])),  # shapes that do not broadcast
    ("Omega", (NAN, 1.0)),
    ("Omega", (0.0, 1.0)),
    ("Omega", ([8.0, INF], 1.0)),
    ("Omega", (None, 1.0)),
    ("Omega", (1e-320, 1.0)),  # overflows
])
def test_surface_n_rejects(name, args):
    _raises(name, lambda: pk.theory.surface_n(B, *args))


def test_surface_n_rejects_a_non_body_and_a_sphere():
    _raises("body", lambda: pk.theory.surface_n("spheroid", 12.0, 1.0))
    _raises("theta", lambda: pk.theory.surface_n(pk.Spheroid(1.0), 12.0, 1.0))  # h_theta = 0 everywhere


def test_surface_n_valid_matches_closed_form():
    OM, TH = np.meshgrid([8.0, 12.0, 20.0], [0.4, 0.9, 1.3])
    np.testing.assert_allclose(pk.theory.surface_n(B, OM, TH), _closed_form_6_3(1.5, OM, TH), rtol=1e-13)
    assert float(pk.theory.surface_n(B, 12.0, 1.0)) == pytest.approx(float(_closed_form_6_3(1.5, 12.0, 1.0)), rel=1e-13)


@pytest.mark.parametrize("name, kwargs", [
    ("mu", dict(mu=NAN)),
    ("mu", dict(mu=-0.1)),
    ("theta", dict(theta=NAN)),
    ("theta", dict(theta=[0.5, 0.0])),
    ("Omega", dict(Omega=0.0)),
    ("Lambda", dict(Lambda=NAN)),
    ("Lambda", dict(Lambda="0")),
    ("friction", dict(friction="coulomb")),
    ("body", dict(body=None)),
])
def test_exact_boundary_rejects(name, kwargs):
    args = dict(body=B, mu=0.1, Omega=12.0, theta=1.0, Lambda=0.0) | kwargs
    _raises(name, lambda: pk.theory.exact_boundary(args.pop("body"), args.pop("mu"), args.pop("Omega"), args.pop("theta"),
                                            **args))


def test_exact_boundary_valid_is_6_3_at_lambda_zero():
    th = np.array([0.5, 1.0, 1.3])
    np.testing.assert_allclose(pk.theory.exact_boundary(B, 0.1, 12.0, th), _closed_form_6_3(1.5, 12.0, th), rtol=1e-10)


@pytest.mark.parametrize("name, kwargs", [
    ("show", dict(show="surface")),
    ("show", dict(show=None)),
    ("values", dict(values=12.0)),
    ("values", dict(values=(12.0, NAN))),
    ("theta_range", dict(theta_range=(-1.0, 1.0))),
    ("theta_range", dict(theta_range=(0.5, 4.0))),
    ("resolution", dict(resolution=1)),
    ("mu", dict(mu=NAN)),
])
def test_scene_rejects(name, kwargs):
    _raises(name, lambda: Scene("prolate", 1.5, **({"show": frozenset({"surface"})} | kwargs)))


def test_compute_scene_and_add_trajectory_reject():
    _raises("scene", lambda: compute_scene("prolate"))
    _raises("traj", lambda: Scene("prolate", 1.5, values=()).add_trajectory(None))


def test_scene_surface_unchanged_by_the_checks():
    """A box that touches theta = 0 is still drawn (the grid is not checked point by point)."""
    d = compute_scene(Scene("prolate", 1.5, values=(), show=frozenset({"surface"}), resolution=12,
                            omega_range=(8.0, 20.0), theta_range=(0.3, 1.4), n_clip=(-5.0, 40.0)))
    OM, TH, N = d.surface
    np.testing.assert_allclose(N, _closed_form_6_3(1.5, OM, TH), rtol=1e-12)


# ---------------------------------------------------------------------------------------------
# impacts

GOOD_IMPACT = dict(k=[0.0, 0.0, 1.0], w=[0.0, 0.0, 0.0], v=[0.0, 0.0, -1.0], e=0.5, mu=0.1)


@pytest.mark.parametrize("name, bad", [
    ("k", [0.0, 0.0, NAN]),
    ("k", [0.0, 0.0, 2.0]),  # not a unit vector
    ("k", [1.0, 1.0, 1.0]),
    ("k", [0.0, 1.0]),
    ("k", "up"),
    ("w", [0.0, INF, 0.0]),
    ("w", [1.0, 2.0]),
    ("v", [0.0, 0.0, NAN]),
    ("v", None),
    ("e", 1.5),
    ("e", NAN),
    ("e", -0.1),
    ("mu", NAN),
    ("mu", -1.0),
    ("body", "spheroid"),
])
def test_impact_rejects(name, bad):
    args = dict(GOOD_IMPACT, body=B) | {name: bad}
    _raises(name, lambda: pk.core.impact(args["body"], args["k"], args["w"], args["v"], e=args["e"], mu=args["mu"]))


@pytest.mark.parametrize("fn", [contact_point, collision_matrix])
def test_impact_geometry_rejects(fn):
    _raises("k", lambda: fn(B, [0.0, 0.0, 3.0]))
    _raises("k", lambda: fn(B, [NAN, 0.0, 1.0]))
    _raises("body", lambda: fn(None, [0.0, 0.0, 1.0]))


def test_impact_valid_upright_drop():
    """Upright (k = e_Z) and falling straight: the impulse passes through G, so it only reverses
    the fall by Newton's law and spins nothing: v = (0, 0, e), w = 0, P = (0, 0, 1 + e)."""
    r = pk.core.impact(B, **GOOD_IMPACT)
    np.testing.assert_allclose(r.v, [0.0, 0.0, 0.5], atol=1e-15)
    np.testing.assert_allclose(r.w, [0.0, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(r.impulse, [0.0, 0.0, 1.5], atol=1e-15)
    assert r.energy_after == pytest.approx(0.5 * 0.25, rel=1e-15)
    # the contact point is the end of the axis (h(0) = a), K = diag(1 + a^2/A, 1 + a^2/A, 1)
    np.testing.assert_allclose(contact_point(B, [0, 0, 1]), [0.0, 0.0, -1.5], atol=1e-15)
    k11 = 1 + 1.5**2 / A_UNIFORM
    np.testing.assert_allclose(collision_matrix(B, [0, 0, 1]), np.diag([k11, k11, 1.0]), rtol=1e-14, atol=1e-15)


# ---------------------------------------------------------------------------------------------
# units


@pytest.mark.parametrize("name, call", [
    ("length", lambda: pk.core.egg_of_size("57 s", "43 mm")),
    ("breadth", lambda: pk.core.egg_of_size("57 mm", "43 rev/s")),
    ("breadth", lambda: pk.core.egg_of_size("57 mm", "-43 mm")),
    ("length", lambda: pk.core.egg_of_size("nan mm", "43 mm")),
    ("length", lambda: pk.core.egg_of_size(57, "43 mm")),
    ("length", lambda: pk.core.egg_of_size("570 mm", "43 mm")),  # aspect ratio out of range
    ("mass", lambda: pk.core.egg_of_size("57 mm", "43 mm", mass="57 mm")),
    ("g", lambda: pk.core.egg_of_size("57 mm", "43 mm", g="9.81 m/s")),
    ("w", lambda: pk.core.egg_of_size("57 mm", "43 mm", w=NAN)),
    ("radius", lambda: pk.core.tippe_top_of_size("15 s", "3 mm")),
    ("offset", lambda: pk.core.tippe_top_of_size("15 mm", "3 s")),
    ("offset", lambda: pk.core.tippe_top_of_size("15 mm", "30 mm")),
    ("A", lambda: pk.core.tippe_top_of_size("15 mm", "3 mm", A="2 g")),
    ("A", lambda: pk.core.tippe_top_of_size("15 mm", "3 mm", A=True)),
    ("C", lambda: pk.core.tippe_top_of_size("15 mm", "3 mm", C=NAN)),
    ("b", lambda: pk.Scale("21.5 s")),
    ("b", lambda: pk.Scale(21.5)),
    ("b", lambda: pk.Scale("0 mm")),
    ("g", lambda: pk.Scale("21.5 mm", g="9.81 m")),
    ("mass", lambda: pk.Scale("21.5 mm", mass="inf g")),
    ("kind", lambda: pk.Scale("21.5 mm").unit("foo")),
    ("kind", lambda: pk.Scale("21.5 mm").unit(["rate"])),
    ("kind", lambda: pk.Scale("21.5 mm").dimensionless("30 rev/s", "foo")),
    ("value", lambda: pk.Scale("21.5 mm").dimensionless("30 rev/s", "speed")),
    ("value", lambda: pk.Scale("21.5 mm").dimensionless("3")),
    ("value", lambda: pk.Scale("21.5 mm").dimensionless("30 Hz")),
    ("value", lambda: pk.Scale("21.5 mm").quantity(NAN, "rate")),
    ("value", lambda: pk.Scale("21.5 mm").quantity("x", "rate")),
    ("default_unit", lambda: units.as_quantity(3, "x", "foo")),
    ("x", lambda: units.as_quantity("3j mm", "x")),
    ("name", lambda: units.as_quantity("3 mm", 5)),
])
def test_units_reject(name, call):
    _raises(name, call)


def test_units_valid_by_hand():
    sc = pk.Scale("21.5 mm")
    # 30 rev/s in units sqrt(g/b): 30 * 2 pi * sqrt(b/g)
    assert sc.dimensionless("30 rev/s") == pytest.approx(30 * 2 * math.pi * math.sqrt(0.0215 / 9.81), rel=1e-12)
    assert sc.dimensionless("30 rev/s", "rate") == pytest.approx(30 * 2 * math.pi * math.sqrt(0.0215 / 9.81), rel=1e-12)
    assert sc.quantity(1.0, "time").to("s").magnitude == pytest.approx(math.sqrt(0.0215 / 9.81), rel=1e-12)
    egg, sc2 = pk.core.egg_of_size("57 mm", "43 mm", w=0.05, mass="57 g")
    assert egg.a == pytest.approx(57 / 43, rel=1e-14) and sc2.b.to("mm").magnitude == pytest.approx(21.5, rel=1e-14)
    top, sc3 = pk.core.tippe_top_of_size("15 mm", "3 mm")
    assert top.offset == pytest.approx(0.2, rel=1e-14) and top.A == pytest.approx(0.4 - 0.2**2, rel=1e-14)


# ---------------------------------------------------------------------------------------------
# the paper's starts


@pytest.mark.parametrize("name, call", [
    ("label", lambda: pk.paper_start(["5.2"])),
    ("label", lambda: pk.paper_start("5.3")),
    ("label", lambda: pk.paper_start(5.2)),
    ("label", lambda: pk.paper_start(None)),
    ("foo", lambda: pk.paper_start("5.2", foo=1)),
    ("omega0", lambda: pk.paper_start("5.2", omega0=NAN)),
    ("n0", lambda: pk.paper_start("5.2", n0=10.0)),
    ("n0", lambda: pk.paper_start("5.1", n0="10")),
    ("friction", lambda: pk.paper_start("5.1", friction="coulomb")),
    ("value", lambda: pk.theory.PAPER_CASES["5.2"].state(NAN)),
])
def test_paper_start_rejects(name, call):
    err = _raises(name, call)
    if name == "label":
        assert "5.1, 5.2" in str(err)
    if name == "foo":
        assert "n0, omega0, friction" in str(err)


def test_paper_start_valid_is_the_printed_5_2():
    model, x0 = pk.paper_start("(5.2)")
    assert model.chart.name == "euler"
    np.testing.assert_array_equal(x0, [7e-5, 2e-6, 10.5, -1e-4, math.pi / 2 - 1e-3, 2e-2])


# ---------------------------------------------------------------------------------------------
# matplotlib helpers


@pytest.fixture(scope="module")
def traj():
    return pk.simulate(pk.Model(B, pk.Coulomb(0.1)), pk.gyroscopic_start(B, 1.5, omega0=12.0), 20.0)


@pytest.fixture()
def ax():
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    yield ax
    plt.close(fig)


def _mpl_bad_calls():
    from phasekit.viz import plain_log_ticks, plot_events, plot_minima, plot_phase, plot_section, plot_timeseries

    return [
        ("names", lambda ax, tr: plot_timeseries(ax, tr, ["RR"])),
        ("names", lambda ax, tr: plot_timeseries(ax, tr, [])),
        ("names", lambda ax, tr: plot_timeseries(ax, tr, 5)),
        ("ax", lambda ax, tr: plot_timeseries(None, tr, ["R"])),
        ("traj", lambda ax, tr: plot_timeseries(ax, "traj", ["R"])),
        ("n", lambda ax, tr: plot_timeseries(ax, tr, "R", n=0)),
        ("times", lambda ax, tr: plot_timeseries(ax, tr, "R", times=[NAN])),
        ("set_labels", lambda ax, tr: plot_timeseries(ax, tr, "R", set_labels="yes")),
        ("style", lambda ax, tr: plot_timeseries(ax, tr, "R", colr="r")),
        ("x", lambda ax, tr: plot_phase(ax, tr, "Theta", "Lambda")),
        ("y", lambda ax, tr: plot_phase(ax, tr, "theta", ["Lambda"])),
        ("ax", lambda ax, tr: plot_phase(object(), tr, "theta", "Lambda")),
        ("traj", lambda ax, tr: plot_phase(ax, None, "theta", "Lambda")),
        ("df", lambda ax, tr: plot_section(ax, tr, "theta", "Lambda")),
        ("x", lambda ax, tr: plot_section(ax, tr.sample([0.0, 1.0]), "thta", "Lambda")),
        ("c", lambda ax, tr: plot_section(ax, tr.sample([0.0, 1.0]), "theta", "Lambda", c="time")),
        ("ax", lambda ax, tr: plot_section(None, tr.sample([0.0, 1.0]), "theta", "Lambda")),
        ("ax", lambda ax, tr: plot_events(None, tr)),
        ("traj", lambda ax, tr: plot_events(ax, [])),
        ("names", lambda ax, tr: plot_events(ax, tr, 5)),
        ("ax", lambda ax, tr: plot_minima(None, tr)),
        ("traj", lambda ax, tr: plot_minima(ax, None)),
        ("axis", lambda ax, tr: plain_log_ticks(ax, "z")),
        ("ax", lambda ax, tr: plain_log_ticks(None)),
    ]


@pytest.mark.parametrize("k", range(24))
def test_plots_reject(k, ax, traj):
    calls = _mpl_bad_calls()
    assert len(calls) == 24
    name, call = calls[k]
    _raises(name, lambda: call(ax, traj))


def test_plots_valid_draw_the_sampled_data(ax, traj):
    from phasekit.viz import plot_phase, plot_section, plot_timeseries

    ts = np.linspace(0.0, 20.0, 11)
    df = traj.sample(ts)
    (line,) = plot_timeseries(ax, traj, "R", times=ts)
    np.testing.assert_array_equal(line.get_xdata(), ts)
    np.testing.assert_array_equal(line.get_ydata(), df["R"])
    assert ax.get_ylabel() == "R [M g]"
    (curve,) = plot_phase(ax, traj, "theta", "Lambda", times=ts)
    np.testing.assert_array_equal(curve.get_ydata(), df["Lambda"])
    art = plot_section(ax, df, "theta", "Omega")
    np.testing.assert_array_equal(art.get_offsets(), df[["theta", "Omega"]].to_numpy())
    # the first point of the curve is the start: theta0 = 1.5 given to gyroscopic_start
    assert curve.get_xdata()[0] == pytest.approx(1.5, abs=1e-12)


# ---------------------------------------------------------------------------------------------
# 3-D scenes


@pytest.fixture(scope="module")
def scene_data():
    return compute_scene(Scene("prolate", 1.5, values=(), show=frozenset({"surface", "axes"}), resolution=12))


@pytest.mark.parametrize("name, kwargs", [
    ("path", dict(path="/proc/x/a.png")),
    ("path", dict(path="{tmp}/a.txt")),
    ("path", dict(path="{tmp}")),
    ("path", dict(path=5)),
    ("window_size", dict(window_size="big")),
    ("window_size", dict(window_size=(0, -5))),
    ("window_size", dict(window_size=(300,))),
    ("window_size", dict(window_size=(300.5, 200))),
    ("window_size", dict(window_size=(100_000, 200))),
    ("camera", dict(camera="top")),
    ("camera", dict(camera=[[0, 0, 0], [0, 0, 0], [0, 0, 1]])),
    ("camera", dict(camera=[[1, 0, 0], [0, 0, 0], [1, 0, 0]])),  # view up along the line of sight
    ("camera", dict(camera=[0, 0, NAN])),
    ("camera", dict(camera=5)),
    ("title", dict(title=123)),
    ("gltf", dict(gltf="/proc/x/a.gltf")),
    ("gltf", dict(gltf="{tmp}/a.png")),
    ("gltf", dict(gltf="{tmp}/missing/a.gltf")),
    ("html", dict(html="{tmp}/a.gltf")),
    ("off_screen", dict(off_screen="yes")),
])
def test_render_scene_rejects_before_drawing(name, kwargs, tmp_path, scene_data):
    from phasekit.viz import render_scene

    kwargs = {k: v.format(tmp=tmp_path) if isinstance(v, str) else v for k, v in kwargs.items()}
    path = kwargs.pop("path", tmp_path / "x.png")
    _raises(name, lambda: render_scene(scene_data, path, **kwargs))
    assert list(tmp_path.iterdir()) == []  # nothing written


def test_render_scene_rejects_bad_data_and_exports_without_path(tmp_path, scene_data):
    from phasekit.viz import render_scene

    _raises("data", lambda: render_scene("scene", tmp_path / "x.png"))
    _raises("gltf", lambda: render_scene(scene_data, None, gltf=str(tmp_path / "x.gltf")))
    err = _raises("gltf", lambda: render_scene(scene_data, tmp_path / "x.png", gltf=str(tmp_path / "m" / "x.gltf")))
    assert isinstance(err, pk.PhasekitError)  # an unwritable target is a PhasekitError too, as before


@pytest.mark.render
def test_render_scene_valid_writes_the_asked_size(tmp_path, scene_data):
    from phasekit.viz import render_scene

    info = render_scene(scene_data, tmp_path / "new" / "s.png", window_size=(120, 90), camera="iso", title="t")
    assert info.image_shape[:2] == (90, 120) and (tmp_path / "new" / "s.png").is_file()
    assert info.bounds[:4] == (8.0, 30.0, 0.35, math.pi / 2 - 0.03)  # the prolate default box without data
