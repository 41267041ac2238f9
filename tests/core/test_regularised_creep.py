"""A stiff regularised law's creep (its ROLLING mode on the slow manifold of the slip) against the
law's own field integrated by an implicit method, and its dissipation against the closed form."""

import phasekit as pk

import numpy as np
import pytest
from scipy.integrate import solve_ivp

MU, EPS = 0.1, 1e-6


@pytest.fixture(scope="module")
def creep_run():
    model = pk.Model(pk.Spheroid(2 / 3), pk.RegularisedCoulomb(MU, EPS), chart="vector")
    # the oblate spheroid spun at n0 = 8.6 from the viscous unstable eigenvector (delta = 0.01), at
    # t = 1: it stuck at t = 0.122 and creeps until t = 101
    x0 = [-0.002208660010335989, -0.0017785479840995446, 0.9999996569262123, 0.017364557167837868,
          0.014009852765269235, 8.599976765670686, -0.003404585330662462, 0.004253289532674261]
    traj = pk.simulate(model, x0, 40.0, stop_at="none", dense=True, progress=False)
    return model, traj


def test_the_law_creeps_without_its_stiffness(creep_run):
    model, traj = creep_run
    assert model.friction.creeps
    rolling = [s for s in traj.segments if s.mode.value == "rolling"]
    assert rolling and rolling[0].t1 - rolling[0].t0 > 30.0
    # the law relaxes the slip at mu R/eps ~ 1e5: its own field needs ~1e5 steps per unit time
    assert rolling[0].n_steps < 100 * (rolling[0].t1 - rolling[0].t0)


def test_creep_follows_the_laws_own_field(creep_run):
    """Two formulations: the creep field (Taylor) and the regularised law's full field (Radau)."""
    model, traj = creep_run
    t0, t1 = 2.0, 4.0
    x0 = traj._chart_states(np.array([t0]))[0]
    f = model.function("rhs_sliding")
    jac = model.function("rhs_jac_sliding")
    ref = solve_ivp(lambda t, x: np.asarray(f(x, model.p)).ravel(), (t0, t1), x0, method="Radau", rtol=1e-10,
                    atol=1e-12, jac=lambda t, x: np.asarray(jac(x, model.p)))
    assert ref.success
    x1 = traj._chart_states(np.array([t1]))[0]
    scale = 1.0 + np.abs(x1)
    assert np.max(np.abs(ref.y[:, -1] - x1) / scale) < 2e-8  # measured 5.8e-9
    # the slip itself: the law's relaxed slip u*, of size eps, to first order in the creep (measured 2.4e-4)
    u_ref = np.asarray(model.function("slip")(ref.y[:, -1], model.p)).ravel()
    u = np.asarray(model.function("slip")(x1, model.p)).ravel()
    assert 1e-3 * EPS < np.linalg.norm(u_ref) < 10 * EPS
    assert np.linalg.norm(u - u_ref) < 1e-3 * np.linalg.norm(u_ref)


def test_creep_dissipates_as_the_law_does(creep_run):
    """dE/dt along the creep equals F.u = -eps |F|^2/sqrt(mu^2 R^2 - |F|^2), the law's power at
    the slip that gives the force F."""
    model, traj = creep_run
    for t in (5.0, 15.0, 25.0):
        h = 1e-3
        xs = traj._chart_states(np.array([t - h, t, t + h]))
        E = [float(model.function("energy")(x, model.p)) for x in xs]
        dEdt = (E[2] - E[0]) / (2 * h)
        Fc = np.asarray(model.function("Fc_rolling")(xs[1], model.p)).ravel()
        F2, R = Fc[0] ** 2 + Fc[1] ** 2, Fc[2]
        power = -EPS * F2 / np.sqrt((MU * R) ** 2 - F2)
        assert power < 0
        assert dEdt == pytest.approx(power, rel=1e-3)
