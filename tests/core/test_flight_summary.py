"""Trajectory.flight_summary sums up every flight of a run: it agrees with the run's Flight
records (an independent route: touchdown minus lift-off of each) and with its hop statistics,
and is None where nothing is defined."""

import phasekit as pk

import numpy as np
import pytest

BODY = pk.Spheroid(1.5)


@pytest.fixture(scope="module")
def hopping():
    """A prolate spheroid that hops: many flights before t = 80."""
    return pk.simulate(pk.Model(BODY, pk.Coulomb(0.1)), pk.gyroscopic_start(BODY, 1.5607963, omega0=11.0), 80.0,
                       stop_at="none")


def test_the_summary_agrees_with_the_flight_records(hopping):
    fs, flights = hopping.flight_summary(), hopping.flights
    assert fs["n_flights"] == len(flights) > 5
    assert all(f.t_touchdown is not None for f in flights)  # every flight touched down before the end
    durations = [f.t_touchdown - f.t_liftoff for f in flights]
    assert fs["t_airborne"] == pytest.approx(sum(durations), rel=1e-12)
    assert fs["longest_flight"] == pytest.approx(max(durations), rel=1e-12)
    assert fs["t_longest_flight"] == flights[durations.index(max(durations))].t_liftoff
    assert fs["airborne_fraction"] == pytest.approx(fs["t_airborne"] / (hopping.t - hopping.t0), rel=1e-14)
    assert 0 < fs["airborne_fraction"] < 1
    best = max(flights, key=lambda f: f.gap_max)
    assert (fs["gap_max"], fs["t_gap_max"]) == (best.gap_max, best.t_gap_max)
    assert best.t_liftoff <= fs["t_gap_max"] <= best.t_touchdown
    assert fs["t_first_liftoff"] == flights[0].t_liftoff == hopping.t_jump


def test_the_summary_and_the_hop_statistics_agree(hopping):
    fs, hops = hopping.flight_summary(), hopping.hops
    assert fs["n_flights"] == hops["n_flights"]
    assert fs["gap_max"] == hops["gap_max"] and fs["longest_flight"] == hops["longest_flight"]
    assert fs["t_airborne"] == pytest.approx(hops["t_flight"], rel=1e-14)


def test_a_run_without_flights():
    traj = pk.simulate(pk.Model(BODY, pk.Coulomb(0.1)), pk.gyroscopic_start(BODY, 1.0, omega0=3.0), 5.0)
    fs = traj.flight_summary()
    assert fs["n_flights"] == 0 and fs["t_airborne"] == 0.0 and fs["airborne_fraction"] == 0.0
    assert all(fs[k] is None for k in ("t_first_liftoff", "gap_max", "t_gap_max", "longest_flight",
                                       "t_longest_flight"))
    assert np.isfinite(traj.t) and traj.flights == ()
