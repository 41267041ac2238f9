"""Every run ends with a status and a finite state: extreme and stiff cases, step and wall budgets,
a diverging integration; never a crash, a hang or a NaN."""


import phasekit as pk
from phasekit.core.engines.taylor import TaylorEngine

import numpy as np
import pytest


@pytest.mark.parametrize(
    "a, law, start",
    [
        (0.2, pk.Coulomb(0.1), dict(theta0=0.05, n0=10.0)),
        (5.0, pk.Coulomb(0.1), dict(theta0=np.pi / 2 - 0.01, omega0=100.0)),
        (1.01, pk.Coulomb(0.1), dict(theta0=1.2, omega0=10.0)),
        (2 / 3, pk.Coulomb(1.0), dict(theta0=0.05, n0=10.5)),
        (1.5, pk.Viscous(1.0), dict(theta0=np.pi / 2 - 1e-8, omega0=10.5)),
    ],
)
def test_extreme_cases_end_with_a_status_and_finite_state(a, law, start):
    body = pk.Spheroid(a)
    y0 = pk.gyroscopic_start(body, start["theta0"], omega0=start.get("omega0"), n0=start.get("n0"))
    rise = pk.Event("theta", 0.05, direction=-1) if a > 1 else pk.Event("theta", np.pi / 2 - 0.05, direction=+1)
    r = pk.simulate(pk.Model(body, law), y0, 2000.0, events=[rise])
    assert r.status in (pk.Status.JUMPED, pk.Status.STOPPED, pk.Status.COMPLETED)
    assert np.all(np.isfinite(r.x)) and np.isfinite(r.R_min)


def test_hopelessly_stiff_law_creeps_as_exact_coulomb_rolls():
    """eps = 1e-12 on a sticking start: relaxation rate mu/eps = 1e11, beyond any integrator of the
    law's own field (CVODES ran out of steps here). Its creep (core.fields) is not stiff, and it
    is exact Coulomb's rolling up to O(eps): the two runs agree to their integration error, at
    rtol 1e-11 (measured 4.3e-8 relative, 2.7e-10 absolute, the same at 1e-13; at rtol 1e-9 exact
    Coulomb's own error is 1.2e-5 of U at t = 100, the creep's, integrated at a hundredth of the
    tolerance, 4e-8)."""
    y = [7e-5, 2e-6, 10.5, -1e-4, np.pi / 2 - 1e-3, 2e-2]
    runs = [pk.simulate(pk.Model(pk.Spheroid(1.5), law), y, 100.0, rtol=1e-11, max_steps=300_000, progress=False)
            for law in (pk.RegularisedCoulomb(0.1, 1e-12), pk.Coulomb(0.1))]
    creep, rolling = runs
    assert creep.status is rolling.status is pk.Status.COMPLETED
    assert creep.segments[-1].mode is pk.core.Mode.ROLLING and creep.segments[-1].engine == "taylor"
    assert creep.events[0].t == pytest.approx(rolling.events[0].t, abs=1e-9)  # the stick (slip 1e-10 + 10 eps, or 0)
    assert np.allclose(creep.euler_end, rolling.euler_end, rtol=1e-7, atol=1e-9)


def test_step_and_wall_budgets_end_the_run_with_a_reason(prolate, standard_start):
    m = pk.Model(prolate, pk.Coulomb(0.1))
    r = pk.simulate(m, standard_start, 200.0, max_steps=50)
    assert r.status is pk.Status.FAILED and "step limit" in r.reason and r.t < 200.0
    assert np.all(np.isfinite(r.x))
    r = pk.simulate(m, standard_start, 1e4, max_wall=1e-3, stop_at="none")
    assert r.status is pk.Status.FAILED and "wall-time limit" in r.reason


def test_a_diverging_integration_ends_failed_at_its_last_finite_state(monkeypatch):
    """A run whose integrator returns a non-finite time or state used to keep a NaN segment
    (t = nan in the result); it now ends "failed" where the state was last finite."""

    real = TaylorEngine.propagate

    def diverging(self, *args, **kwargs):
        prop = real(self, *args, **kwargs)
        prop.t, prop.x = float("nan"), prop.x * np.nan
        return prop

    monkeypatch.setattr(TaylorEngine, "propagate", diverging)
    model = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))
    x0 = pk.gyroscopic_start(model.body, 1.5, omega0=10.0)
    r = pk.simulate(model, x0, 5.0)
    assert r.status is pk.Status.FAILED and r.reason == "the integration diverged after t = 0 (non-finite state)"
    assert r.t == 0.0 and np.array_equal(r.x, x0)
    d = r.to_dict()
    assert d["t_end"] == 0.0 and all(np.isfinite(list(d["state_end"].values())))


def test_api_simulate_refuses_rates_beyond_double_precision():
    model = pk.Model(pk.Spheroid(0.6), pk.Coulomb(0.1))
    with pytest.raises(pk.ParameterError, match="^`x0` must have entries of at most 100000"):
        pk.simulate(model, [0.0, 0.0, 10.0, 76523426.0, 3.0, 5.0], 1.0)
