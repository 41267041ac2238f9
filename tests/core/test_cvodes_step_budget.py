"""The step budget holds for the CVODES and IDAS engines: they integrate in chunks of output
points, and a chunk that would pass the budget is not taken (shorter ones are tried), so a run
ends "failed" with at most ``max_steps`` steps, its reason giving that count (a budget of 2 was
run to 832 steps)."""

import phasekit as pk

import numpy as np
import pytest

BODY = pk.Spheroid(1.5)
X0 = pk.gyroscopic_start(BODY, np.pi / 2 - 0.01, omega0=10.5)


@pytest.mark.parametrize("backend", ["cvodes", "cvodes-adams", "idas"])
@pytest.mark.parametrize("max_steps", [1, 2, 50, 400, 3000])
def test_a_run_ends_within_its_step_budget(backend, max_steps):
    traj = pk.simulate(pk.Model(BODY, pk.Coulomb(0.1)), X0, 200.0, backend=backend, max_steps=max_steps)
    assert traj.status is pk.Status.FAILED and traj.n_steps <= max_steps
    assert traj.reason.startswith(f"step limit ({traj.n_steps} steps) reached at t = ")
    assert float(traj.reason.split("t = ")[1].split()[0]) == pytest.approx(traj.t, rel=1e-5, abs=1e-12)
    if max_steps >= 400:  # a budget that holds several chunks is used, not given up early
        assert traj.n_steps > max_steps / 2 and traj.t > 0


def test_a_budget_that_is_enough_changes_nothing():
    """Exactly the steps a run needs: the same run (a budget spent as the end is reached holds)."""
    model = pk.Model(BODY, pk.Coulomb(0.1))
    free = pk.simulate(model, X0, 30.0, backend="cvodes")
    tight = pk.simulate(model, X0, 30.0, backend="cvodes", max_steps=free.n_steps)
    assert free.status is tight.status is pk.Status.COMPLETED
    assert tight.n_steps == free.n_steps and np.array_equal(tight.x, free.x)
    short = pk.simulate(model, X0, 30.0, backend="cvodes", max_steps=free.n_steps - 1)
    assert short.status is pk.Status.FAILED and short.n_steps <= free.n_steps - 1 and short.t < 30.0
