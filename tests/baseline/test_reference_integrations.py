"""The reference implementations phasekit is measured against (phasekit.baseline) agree with it:
the right-hand side and the normal reaction written by hand in NumPy equal the CasADi fields,
scipy's integration of that NumPy field finds the same jump time, and the bare heyoka integrator
stops at the same lift-off as the hybrid loop."""

import phasekit as pk

import numpy as np
import pytest


@pytest.fixture(scope="module")
def coulomb(prolate):
    return pk.Model(prolate, pk.Coulomb(0.1))


def _states(body, n=20, seed=3):
    """Sliding states away from the poles, with a slip large enough for Coulomb's law to be smooth."""
    rng = np.random.default_rng(seed)
    ys = []
    for _ in range(n):
        theta = rng.uniform(0.3, 2.8)
        y = pk.gyroscopic_start(body, theta, omega0=rng.uniform(4.0, 12.0))
        y[:2] += rng.uniform(-0.3, 0.3, 2)  # slip
        y[3] = rng.uniform(-0.5, 0.5)        # Lambda
        ys.append(y)
    return ys


def test_the_numpy_field_equals_the_casadi_field(prolate, coulomb):
    for y in _states(prolate):
        f_np = pk.baseline.numpy_rhs(0.0, y, prolate.a, prolate.A, prolate.C, 0.1)
        f_ca = np.asarray(coulomb.rhs(y)).ravel()
        np.testing.assert_allclose(f_np, f_ca, rtol=1e-11, atol=1e-12)


def test_the_numpy_normal_reaction_equals_the_model_s(prolate, coulomb):
    for y in _states(prolate, seed=5):
        R_np = pk.baseline.numpy_normal_reaction(y, prolate.a, prolate.A, prolate.C, 0.1)
        assert float(R_np) == pytest.approx(float(coulomb.evaluate("R", y)), rel=1e-11)


def test_scipy_on_the_numpy_field_finds_phasekit_s_jump_time(prolate, coulomb, standard_start):
    t_star = pk.simulate(coulomb, standard_start, 200.0, rtol=1e-12).t_jump
    run = pk.baseline.solve_ivp_to_jump(standard_start, 200.0, a=prolate.a, A=prolate.A, C=prolate.C, mu=0.1,
                                        method="DOP853", rtol=1e-11)
    assert run.status == "ok"
    assert run.t_jump == pytest.approx(t_star, abs=1e-6)


def test_the_bare_taylor_integrator_stops_at_the_hybrid_loop_s_lift_off(coulomb, standard_start):
    sweep = pk.simulate(coulomb, standard_start, 200.0, dense=False, track_minima=False)
    converged = pk.simulate(coulomb, standard_start, 200.0, rtol=1e-13, dense=False, track_minima=False).t_jump
    ta, pars = pk.baseline.taylor_integrator(coulomb, rtol=1e-9, track_minima=False, x0=standard_start)
    ta.propagate_until(200.0)
    # the loop renews the scales every time unit, the bare integrator keeps its first ones (set for
    # U, V ~ 1e-6 and n ~ 0.02, which grow): different steps, the loop's error 1.1e-10, the bare one's 1.4e-9
    assert sweep.t_jump == pytest.approx(converged, abs=5e-10)
    assert ta.time == pytest.approx(converged, abs=3e-9)
    assert ta.state * pars[-6:] == pytest.approx(sweep.x_jump, rel=1e-7, abs=1e-9)


def test_the_bare_integrator_is_the_caller_s_own(coulomb, standard_start):
    """A simulate between two propagations of the bare integrator leaves it as it was: the
    benchmark's "bare heyoka" once shared simulate's integrator, and after a simulate its runs
    stopped at t = 1.38 (another segment's parameters), 29 steps instead of 601."""
    ta, pars = pk.baseline.taylor_integrator(coulomb, rtol=1e-9, track_minima=False, x0=standard_start)
    start = np.array(ta.state)

    def run():
        ta.time = 0.0
        ta.state[:] = start
        ta.reset_cooldowns()
        outcome = ta.propagate_until(200.0)
        return ta.time, outcome[3]

    first = run()
    sim = pk.simulate(coulomb, standard_start, 200.0, rtol=1e-9, dense=False, track_minima=False)
    assert run() == first
    assert first[0] == pytest.approx(sim.t_jump, abs=3e-9)  # the same lift-off, not an early stop
