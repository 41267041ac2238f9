"""Coulomb friction over a contact patch in the simulator (pk.Contensou): the power the run loses
is the exact dissipation of the patch integrals (closed forms, not the approximant the field uses),
the two charts agree, the 60 x 45 mm egg rises from its side under dry friction (where a point
contact sticks and rolls, tests/friction/test_an_egg_spun_on_a_table.py) as fast as the regularised
law the patch is at small slip, and the law round-trips through its description and the CLI."""

from __future__ import annotations

import json
import subprocess
import sys

import phasekit as pk
from phasekit.errors import ParameterError
from phasekit.friction.patch import PATCH_LIMITS, patch_resultant

import numpy as np
import pytest
from scipy.integrate import simpson

EGG = pk.Egg(1.33333, 0.0)
SCALE = pk.Scale("22.5 mm")
A_PATCH = SCALE.dimensionless("0.1 mm", "length")


def _start():
    return pk.gyroscopic_start(EGG, float(np.radians(89.4)), omega0=SCALE.dimensionless("25 rev/s"))


def _run(law, t_end, chart="euler"):
    model = pk.Model(EGG, law, chart)
    traj = pk.simulate(model, model.chart.from_paper(_start()), t_end, stop_at="none", rtol=1e-10, max_wall=300,
                       max_steps=500_000)
    assert traj.success, traj.reason
    return traj


def _rise_time(traj, degrees=10.0):
    ts = np.linspace(traj.t0, traj.t, 8001)
    theta = np.degrees(traj.sample(ts).theta.to_numpy())
    below = np.flatnonzero(theta < degrees)
    assert below.size, f"theta stayed above {degrees} deg (least {theta.min():.3g})"
    i = below[0]  # linear interpolation between the two samples around the crossing
    return ts[i - 1] + (ts[i] - ts[i - 1]) * (theta[i - 1] - degrees) / (theta[i - 1] - theta[i])


@pytest.fixture(scope="module")
def egg_run():
    return _run(pk.Contensou(0.2, A_PATCH), 40.0)


def test_the_egg_rises_from_its_side_under_dry_friction_over_a_patch(egg_run):
    t_rise = _rise_time(egg_run)
    assert SCALE.to_real(t_rise, "time").to("s").magnitude < 1.5  # from 89.4 deg below 10 deg within 1.5 s
    assert np.degrees(egg_run.euler_end[4]) < 2.0  # and goes on towards its end (upright)


def test_the_energy_lost_is_the_exact_dissipation_of_the_patch_integrals(egg_run):
    # D = mu R a |w_n| d(s), s = |u|/(a |w_n|), d from the exact ring sums (Hertz pressure): an independent
    # evaluation of what the field's rational approximant (error <= 8.2e-6) and the chart's slip give
    ts = np.linspace(egg_run.t0, egg_run.t, 4001)
    df = egg_run.sample(ts)
    c, s = np.cos(df.theta.to_numpy()), np.sin(df.theta.to_numpy())
    w_n = df.Omega.to_numpy() * s * s + df.n.to_numpy() * c  # w.e_Z in the paper's variables
    spin = A_PATCH * np.abs(w_n)
    d = patch_resultant(df.slip.to_numpy() / spin, "hertz", dissipation=True)[2]
    lost = simpson(0.2 * df.R.to_numpy() * spin * d, x=ts)
    budget = egg_run.energy_budget()
    patch = dict(zip(budget.laws, budget.dissipated))["patch"]
    assert patch == pytest.approx(lost, rel=2e-6)  # measured 4.2e-7
    assert budget.residual_max < 1e-9 * budget.energy_start
    assert dict(zip(budget.laws, budget.dissipated))["sliding friction"] == 0.0  # the point carries no force


def test_the_euler_and_vector_charts_agree(egg_run):
    other = _run(pk.Contensou(0.2, A_PATCH), 40.0, chart="vector")
    assert other.euler_end[4] == pytest.approx(egg_run.euler_end[4], abs=1e-7)
    assert other.energy_budget().energy_end == pytest.approx(egg_run.energy_budget().energy_end, rel=1e-9)


def test_the_rise_matches_the_regularised_law_the_patch_is_at_small_slip(egg_run):
    # near zero slip the Hertz patch is the regularised law with eps = a |w_n| / k_v, k_v = 3 pi / 8;
    # w_n at the start is Omega0 (theta0 ~ pi/2). The two differ where the slip is not small (s ~ 1)
    # and by the patch's couple, which brakes w_n: a few per cent (measured 0.7% here, at most 3.9% over
    # patches 0.05 - 0.2 mm and mu 0.2 - 0.3)
    eps = A_PATCH * abs(_start()[2]) / PATCH_LIMITS["hertz"].slip_slope
    regularised = _run(pk.RegularisedCoulomb(0.2, eps), 40.0)
    assert _rise_time(egg_run) == pytest.approx(_rise_time(regularised), rel=0.02)


def test_a_small_slip_over_a_spinning_patch_meets_a_viscous_force_not_the_full_coulomb_force():
    law = pk.Contensou(0.3, 0.01, pressure="uniform")
    u = np.array([1e-7, 0.0])
    F = law.force(u, 1.0, spin=2.0)
    # uniform pressure: F = -mu R u / (a |w_n|) for |u| << a |w_n|
    assert F[0] == pytest.approx(-0.3 * 1e-7 / (0.01 * 2.0), rel=1e-5)
    assert abs(F[0]) < 1e-4 * 0.3  # far below mu R, where a point contact would slide at full force
    assert law.force(np.array([1.0, 0.0]), 1.0, spin=0.0)[0] == pytest.approx(-0.3, rel=1e-6)


def test_the_law_round_trips_through_its_description():
    law = pk.Contensou(0.25, 0.003, pressure="uniform").with_dissipation(pk.RollingResistance(0.002))
    model = pk.Model(pk.Disk(0.1), law)
    again = pk.Model.from_dict(json.loads(json.dumps(model.to_dict())))
    assert again == model and again.friction.radius == 0.003 and again.friction.patch.pressure == "uniform"
    assert again.friction.describe() == "contensou(mu=0.25, radius=0.003, uniform) + rolling-resistance(delta=0.002)"


def test_spin_friction_beside_a_patch_is_refused():
    with pytest.raises(ParameterError) as err:
        pk.Contensou(0.2, 0.004).with_dissipation(pk.SpinFriction(0.01))
    assert err.value.param == "dissipation"


@pytest.mark.parametrize("extra, says", [(["--patch", "0.01", "--slip-eps", "1e-3"], "exact Coulomb"),
                                         (["--patch", "0.01", "--spin-friction", "0.01"], "not both"),
                                         (["--patch", "0.9"], "[0, 0.5]")])
def test_the_cli_refuses_a_patch_it_cannot_apply_in_one_line_naming_it(extra, says):
    args = ["simulate", "--a", "1.5", "--mu", "0.2", "--gyroscopic", "--theta0", "0.5", "--omega0", "5",
            "--t-end", "1", *extra]
    out = subprocess.run([sys.executable, "-m", "phasekit", *args], capture_output=True, text=True, timeout=120)
    lines = out.stderr.strip().splitlines()
    assert out.returncode == 2 and len(lines) == 1 and "--patch" in lines[0] and says in lines[0]


def test_the_contact_radii_in_the_field_are_the_principal_radii_of_the_support_function():
    # fields' c-derivative form against phasekit.friction.hertz.principal_radii's theta-derivative form
    from phasekit.core.fields import contact_point
    from phasekit.friction.hertz import principal_radii

    import casadi as ca

    for body in (pk.Spheroid(1.5), pk.Egg(1.33333, 0.1), pk.EccentricSphere(0.3)):
        shape = ca.DM(list(body.shape_params))
        k = ca.SX.sym("k", 3)
        radii = ca.Function("radii", [k], [contact_point(lambda c: body.height(c, shape), [pk.Contensou(0.2, 0.01).patch], k).radii])
        th = ca.SX.sym("th")
        h = body.height(ca.cos(th), shape)
        hs = ca.Function("h", [th], [h, ca.jacobian(h, th), ca.jacobian(ca.jacobian(h, th), th)])
        for theta in (0.3, 1.0, 1.5, 2.4):
            rho1, rho2 = principal_radii(*(float(x) for x in hs(theta)), theta)
            got = float(radii([np.sin(theta), 0.0, np.cos(theta)]))
            assert got == pytest.approx(rho1 * rho2, rel=1e-12)


def test_a_curvature_following_patch_on_a_sphere_is_the_fixed_patch():
    # an eccentric sphere's radii are both b everywhere: the factor (rho1 rho2)^(1/6) is 1 on the whole run
    top = pk.EccentricSphere(0.3, A=0.38, C=0.4)
    y0 = pk.core.vertical_spin_start(0.1, 8.0)
    ends = [pk.simulate(pk.Model(top, pk.Contensou(0.3, 0.005, curvature=c), "vector"),
                        pk.core.to_chart("vector", y0), 20.0, stop_at="none", rtol=1e-10).x for c in (False, True)]
    assert np.max(np.abs(ends[0] - ends[1])) < 1e-9


def test_a_patch_that_follows_the_curvature_is_refused_on_a_rim():
    with pytest.raises(ParameterError) as err:
        pk.Model(pk.Disk(0.1), pk.Contensou(0.3, 0.004, curvature=True))
    assert err.value.param == "friction"


def test_hertz_materials_on_the_cli_give_the_hand_computed_patch():
    # a 5.9 g maple tippe top (b = 12.5 mm) on a laminate table: a = (3 W b / (4 E*))^(1/3) at radii b
    from phasekit.friction.hertz import MATERIALS, effective_modulus

    m, t = MATERIALS["hardwood"], MATERIALS["laminate"]
    a_hand = (3 * 5.9e-3 * 9.81 * 0.0125 / (4 * effective_modulus(m.E, m.nu, t.E, t.nu))) ** (1 / 3) / 0.0125
    args = ["simulate", "--body", "tippe-top", "--offset", "0.3", "--size", "12.5 mm", "--mass", "5.9 g", "--mu", "0.3",
            "--spin-about-vertical", "20 rev/s", "--theta0", "5 deg", "--t-end", "10 ms", "--json"]
    out = subprocess.run([sys.executable, "-m", "phasekit", *args, "--hertz", "hardwood, laminate"], capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    patch = json.loads(out.stdout)["model"]["patch"]
    assert patch["curvature"] is True and patch["radius"] == pytest.approx(a_hand, rel=1e-12)
    for bad, says in ((["--hertz", "cheese, laminate"], "two materials"), (["--hertz", "hardwood, laminate", "--patch", "0.01"], "not both")):
        out = subprocess.run([sys.executable, "-m", "phasekit", *args, *bad], capture_output=True, text=True, timeout=300)
        lines = out.stderr.strip().splitlines()
        assert out.returncode == 2 and len(lines) == 1 and "--hertz" in lines[0] and says in lines[0], out.stderr
    no_mass = [a for a in args if a not in ("--mass", "5.9 g")]
    out = subprocess.run([sys.executable, "-m", "phasekit", *no_mass, "--hertz", "hardwood, laminate"], capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 2 and "--mass" in out.stderr and len(out.stderr.strip().splitlines()) == 1


def test_over_a_patch_only_rest_and_straight_rolling_survive():
    # every spin about the vertical meets the patch's couple, every slip its force: rest keeps its energy,
    # and so does the spheroid rolling straight on its equator (w horizontal: no pivot, no slip)
    bare = pk.steady_structure(pk.Spheroid(1.5), pk.Coulomb(0.3), samples=False)
    patch = pk.steady_structure(pk.Spheroid(1.5), pk.Contensou(0.3, 0.005), samples=False)
    assert bare.branches and len(bare.families) > 1
    assert patch.branches == ()
    assert [(f.kind, f.theta) for f in patch.families] == [("rolling", pytest.approx(np.pi / 2))]
    assert len(patch.static_equilibria) == len(bare.static_equilibria) > 0


def test_a_disk_on_its_face_under_the_patch_law_slides_under_coulomb_traction():
    # the face's traction is Coulomb's (R-proportional) under the patch law as under pk.Coulomb: the same
    # stop, at the terminal ratio 0.6530 of Farkas et al. (uniform pressure over the face)
    disk = pk.Disk(0.1)
    runs = [pk.simulate(pk.Model(disk, law), pk.core.vertical_spin_start(0.0, 3.0, v0=1.0), 100.0, mode="face")
            for law in (pk.Coulomb(0.3), pk.Contensou(0.3, 0.004))]
    faces = [r.to_dict()["face"] for r in runs]
    assert faces[1]["t_stop_slide"] == pytest.approx(faces[0]["t_stop_slide"], rel=1e-12)
    assert faces[1]["ratio_end"] == pytest.approx(0.6530017892, abs=1e-3)
