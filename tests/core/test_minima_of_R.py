"""The minima of R of a default run (``track_minima=True``): found from the Taylor expansion of the
integral of R that the integrator carries (phasekit/core/engines/roots.py), which must leave the
run exactly as it is without them, and be the minima of R along the run's own dense output."""

import phasekit as pk

import numpy as np
import pytest


@pytest.fixture(scope="module")
def model():
    return pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))


def _runs(model, x0, t_end, **kw):
    tracked = pk.simulate(model, x0, t_end, **kw)
    bare = pk.simulate(model, x0, t_end, dense=False, track_minima=False, **kw)
    return tracked, bare


@pytest.mark.parametrize("label", ["sliding", "5.2"])
def test_tracking_the_minima_leaves_the_run_as_it_is(model, label):
    """The same steps, events and end state to the last bit as the sweep path's run (the
    integral of R is scaled out of heyoka's choice of step): sliding to the jump, and the
    paper's start (5.2), which sticks at t = 0.011 and rolls."""
    if label == "sliding":
        run_model, x0 = model, pk.gyroscopic_start(model.body, np.pi / 2 - 0.01, omega0=10.5)
    else:
        run_model, x0 = pk.paper_start(label)
    tracked, bare = _runs(run_model, x0, 60.0)
    assert len(tracked.minima) > 20
    assert tracked.n_steps == bare.n_steps and tracked.t == bare.t
    assert [(e.name, e.t) for e in tracked.events] == [(e.name, e.t) for e in bare.events]
    np.testing.assert_array_equal(tracked.x, bare.x)


def test_the_minima_are_the_minima_of_R_along_the_dense_output(model):
    """Every local minimum of R sampled on a fine grid of the run's own dense output is a located
    minimum, within the grid spacing, and there are no others; at each, dR/dt = 0 to 1e-9 of its
    largest value along the run, and R is below the dense output's R either side."""
    run = pk.simulate(model, pk.gyroscopic_start(model.body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    mins = run.minima
    ts = np.linspace(0.0, run.t_jump, 200_001)
    samples = run.sample(ts)
    R = samples["R"].to_numpy()
    inner = np.flatnonzero((R[1:-1] < R[:-2]) & (R[1:-1] < R[2:])) + 1
    assert len(mins) == len(inner) > 40
    np.testing.assert_allclose(mins[:, 0], ts[inner], rtol=0, atol=ts[1] - ts[0])
    assert np.all(mins[:, 1] <= R[inner] + 1e-12)
    for side in (-1e-4, 1e-4):
        assert np.all(run.sample(mins[:, 0] + side)["R"].to_numpy() > mins[:, 1])
    rdot = model.guard_function("Rdot", "sliding")
    along = samples[list(model.state_names)].to_numpy()[::100]
    scale = max(abs(float(rdot(x, model.p, 0.0))) for x in along)
    at_minima = [abs(float(rdot(x, model.p, 0.0))) for s in run.segments for _, x in s.monitored]
    assert len(at_minima) == len(mins) and max(at_minima) <= 1e-9 * scale
