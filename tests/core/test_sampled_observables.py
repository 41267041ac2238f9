"""Observables along a trajectory (``Trajectory.sample``, ``at``, ``Model.evaluate``) in the mode in
force: R against the vertical acceleration and an independent transcription, energy, the samples'
bounds and modes; results are frozen."""

from __future__ import annotations

import dataclasses

import phasekit as pk
from phasekit import ParameterError

import numpy as np
import pytest

DT = 1e-4  # central-difference step for R = 1 + d^2 z/dt^2 (error ~ DT^2 z'''' ~ 1e-6, rounding ~ 1e-8)


@pytest.fixture(scope="module")
def model(prolate):
    return pk.Model(prolate, pk.Coulomb(0.1))


@pytest.fixture(scope="module")
def bouncing(model, prolate):
    """Through lift-off, flights, impacts and contact again (e = 0.5)."""
    x0 = pk.gyroscopic_start(prolate, np.pi / 2 - 0.01, omega0=11.0)
    return pk.simulate(model, x0, 43.0, stop_at="none", restitution=0.5)


@pytest.fixture(scope="module")
def sticking():
    """(5.2) under exact Coulomb friction: slides, sticks at t = 0.011, rolls."""
    return pk.simulate(*pk.paper_start("5.2"), 3.0)


def _interior(traj, ts):
    """Times at least 2 DT away from every segment end (R jumps at a mode switch)."""
    ends = np.array([s.t1 for s in traj.segments] + [s.t0 for s in traj.segments])
    return ts[np.min(np.abs(ts[:, None] - ends[None, :]), axis=1) > 2 * DT]


@pytest.mark.parametrize("which", ["bouncing", "sticking"])
def test_sampled_R_is_one_plus_vertical_acceleration_in_the_mode_in_force(which, request):
    """(2.8) R = 1 + d^2 z_G/dt^2, with z_G = h + gap from the dense output, independently of
    the mode's formula for R: checks that each row uses the mode in force (sliding, rolling,
    flight, where R = 0)."""
    traj = request.getfixturevalue(which)
    ts = _interior(traj, np.linspace(traj.t0 + 3 * DT, traj.t - 3 * DT, 1500 if which == "bouncing" else 300))
    mid, lo, hi = traj.sample(ts), traj.sample(ts - DT), traj.sample(ts + DT)
    z = lambda d: (d["h"] + d["gap"]).to_numpy()  # noqa: E731
    accel = (z(hi) - 2 * z(mid) + z(lo)) / DT**2
    modes = set(mid["mode"])
    assert modes == ({"sliding", "flight"} if which == "bouncing" else {"sliding", "rolling"})
    np.testing.assert_allclose(mid["R"].to_numpy(), 1.0 + accel, atol=2e-5)
    if which == "bouncing":
        assert np.all(mid.loc[mid["mode"] == "flight", "R"] == 0.0)
        assert np.all(mid.loc[mid["mode"] == "flight", "gap"] > 0.0)
    else:
        assert np.all(mid.loc[mid["mode"] == "rolling", "slip"] < 1e-12)


def test_sampled_R_matches_the_numpy_transcription_while_sliding(model, prolate, standard_start):
    """The sampled R against (6.1) written independently in NumPy (pk.baseline.numpy_normal_reaction),
    at the sampled states."""
    traj = pk.simulate(model, standard_start, 100.0)
    df = traj.sample(np.linspace(0.0, traj.t, 400))
    Y = df[list(pk.core.PAPER_NAMES)].to_numpy()
    R_np = np.array([pk.baseline.numpy_normal_reaction(y, 1.5, prolate.A, prolate.C, 0.1) for y in Y])
    np.testing.assert_allclose(df["R"], R_np, rtol=1e-11, atol=1e-12)


def test_R_vanishes_at_the_jump_and_the_end_state_matches_the_sample(model, standard_start):
    traj = pk.simulate(model, standard_start, 100.0)
    row = traj.at(traj.t_jump)
    assert abs(row["R"]) < 1e-9 and row["mode"] == "sliding"
    assert traj.at(traj.t_jump - 0.05)["R"] > 1e-3
    # the dense output at the end equals the integrator's own end state (no re-integration)
    end = traj.sample([traj.t])[list(pk.core.PAPER_NAMES)].to_numpy()[0]
    np.testing.assert_allclose(end, traj.euler_end, rtol=0, atol=1e-12)


def test_energy_is_non_increasing_under_friction_and_conserved_without(prolate, standard_start, bouncing):
    for traj in (pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), standard_start, 40.0), bouncing):
        E = traj.sample(np.linspace(traj.t0, traj.t, 3000))["energy"].to_numpy()
        assert np.all(np.diff(E) <= 1e-9 * E[0])  # rounding of the dense output only
        assert E[-1] < E[0] - 1e-3  # friction (and the impacts) did dissipate
    free = pk.simulate(pk.Model(prolate, pk.Coulomb(0.0)), standard_start, 40.0, rtol=1e-12)
    E = free.sample(np.linspace(0.0, free.t, 2000))["energy"].to_numpy()
    assert np.max(np.abs(E - E[0])) < 1e-10 * E[0]


def test_sample_refuses_times_outside_the_run_and_runs_without_dense_output(model, standard_start):
    traj = pk.simulate(model, standard_start, 10.0)
    with pytest.raises(ParameterError, match="`times` must lie in the simulated span"):
        traj.sample([1.0, 10.5])
    with pytest.raises(ParameterError, match="`times`"):
        traj.sample([-0.1])
    with pytest.raises(ParameterError, match="`t` must be one time"):
        traj.at([1.0, 2.0])
    bare = pk.simulate(model, standard_start, 10.0, dense=False)
    with pytest.raises(ParameterError, match="dense"):
        bare.sample([1.0])


def test_sample_across_flights_switches_at_the_recorded_events(bouncing):
    fl = bouncing.flights[0]
    inside = np.linspace(fl.t_liftoff, fl.t_touchdown, 9)[1:-1]
    df = bouncing.sample(inside)
    assert list(df["mode"]) == ["flight"] * 7
    # a time at an event belongs to the segment that ends there (before the reset)
    assert bouncing.at(fl.t_liftoff)["mode"] == "sliding"
    assert bouncing.at(fl.t_touchdown)["mode"] == "flight"
    ev = bouncing.events_table("lift-off")
    assert len(ev) == len(bouncing.events_named("lift-off")) and ev["t"].iloc[0] == fl.t_liftoff


def test_evaluate_lists_its_names(model, standard_start):
    with pytest.raises(ParameterError) as err:
        model.evaluate("normal_force", standard_start)
    assert all(name in str(err.value) for name in pk.core.OBSERVABLES)
    assert all(name in pk.Model.evaluate.__doc__ for name in ("R", "energy", "jellett", "slip_speed"))


def test_results_are_frozen():
    body = pk.Spheroid(1.5)
    traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0),
                       200.0, stop_at="touchdown", pose0=pk.core.Pose(psi=0.3))
    assert isinstance(traj.segments[0], pk.core.Segment) and isinstance(traj.events[0], pk.core.EventRecord)
    assert isinstance(traj.flights[0], pk.core.Flight) and traj.pose0 == pk.core.Pose(psi=0.3)
    for obj, field in ((traj, "status"), (traj, "segments"), (traj, "pose0"), (traj.segments[0], "t1"),
                       (traj.events[0], "t"), (traj.flights[0], "gap_max")):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(obj, field, None)
    r = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.0, omega0=10.0), 5.0, dense=False,
                    t_eval=[1.0, 2.0])
    assert r.ys.shape == (2, 6) and all(s.dense == () for s in r.segments)  # kept only to answer t_eval
