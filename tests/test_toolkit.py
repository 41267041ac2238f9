"""Issue 18: observables along trajectories, sections, ensembles, rerun, extension points."""

import json

import phasekit as pk
from phasekit._runtime.errors import ParameterError
from phasekit.core import trajectory

import casadi as ca
import numpy as np
import pytest

from .helpers import UserSpheroid

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


# -- sections ----------------------------------------------------------------------------------


def test_poincare_matches_an_independent_integration_refined_by_brent(prolate, standard_start):
    """Lambda = 0 upward crossings of a long sliding run: phasekit's events (Taylor polynomial
    roots) against scipy's DOP853 on the NumPy transcription, sign changes on a fine t_eval
    grid refined by Brent's method on that integration's dense output."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    model = pk.Model(prolate, pk.Coulomb(0.1))
    df = pk.core.poincare(model, standard_start, 40.0, on="Lambda", value=0.0, direction=+1, rtol=1e-13)
    sol = solve_ivp(pk.baseline.numpy_rhs, (0.0, 40.0), standard_start, method="DOP853", rtol=1e-12, atol=1e-14,
                    args=(1.5, prolate.A, prolate.C, 0.1), dense_output=True)
    grid = np.linspace(0.0, 40.0, 40001)
    L = sol.sol(grid)[3]
    k = np.flatnonzero((L[:-1] < 0) & (L[1:] >= 0))
    t_ref = np.array([brentq(lambda s: sol.sol(s)[3], grid[i], grid[i + 1], xtol=1e-14) for i in k])
    assert df["t"].iloc[0] == 0.0  # the start lies on the section (Lambda = 0, rising)
    crossings = df.iloc[1:]
    assert len(crossings) == len(t_ref) >= 5
    np.testing.assert_allclose(crossings["t"], t_ref, rtol=0, atol=1e-8)
    np.testing.assert_allclose(crossings["theta"], sol.sol(t_ref)[4], atol=1e-8)
    assert np.max(np.abs(df["Lambda"])) < 1e-12
    assert list(df.columns) == ["t", "mode", *trajectory.SAMPLE_COLUMNS]


def test_poincare_on_any_observable_and_direction(model, standard_start):
    up = pk.core.poincare(model, standard_start, 45.0, on="R", value=0.9, direction=-1)
    assert len(up) >= 3 and np.all(np.abs(up["R"] - 0.9) < 1e-10)
    both = pk.core.poincare(model, standard_start, 45.0, on="R", value=0.9, direction=0)
    assert len(both) == 2 * len(up) or len(both) == 2 * len(up) - 1
    with pytest.raises(ParameterError, match="`dense`"):
        pk.core.poincare(model, standard_start, 10.0, dense=False)


def test_non_terminal_events_fire_after_a_tangential_start(model, standard_start):
    """Regression: heyoka's automatic cooldown after an event at a start with dLambda/dt ~ 1e-16
    was 8.6e8, which silenced the event for the rest of the run."""
    traj = pk.simulate(model, standard_start, 40.0, events=[pk.Event("Lambda", 0.0, direction=+1, terminal=False)])
    assert len(traj.events_named("Lambda=0")) >= 8


# -- ensembles and rerun ---------------------------------------------------------------------------


@pytest.fixture(scope="module")
def ten_starts(prolate):
    return [pk.gyroscopic_start(prolate, np.pi / 2 - 0.01, omega0=w) for w in np.linspace(9.0, 14.0, 10)]


def test_ensemble_equals_single_runs_row_by_row(model, ten_starts):
    ev = pk.Event("theta", 1.0, direction=-1, terminal=False, name="theta1")
    df = pk.ensemble(model, ten_starts, 200.0, events=[ev], processes=2, progress=False)
    assert list(df["i"]) == list(range(10))
    for i, x0 in enumerate(ten_starts):
        tr = pk.simulate(model, x0, 200.0, events=[ev])
        row = df.iloc[i]
        assert row["status"] == tr.status.value and row["stuck"] == tr.stuck and row["n_events"] == len(tr.events)
        assert row["t_end"] == tr.t and row["R_min"] == tr.R_min and row["n_steps"] == tr.n_steps
        assert (np.isnan(row["t_jump"]) if tr.t_jump is None else row["t_jump"] == tr.t_jump)
        first = tr.events_named("theta1")
        assert row["t_theta1"] == first[0].t if first else np.isnan(row["t_theta1"])
        np.testing.assert_array_equal(row[list(pk.core.PAPER_NAMES)].to_numpy(float), x0)
    assert set(df["status"]) == {"jumped", "completed"}  # both outcomes occur in this range


def test_ensemble_takes_a_table_of_starts_and_reports_failures(model, ten_starts):
    import pandas as pd

    table = pd.DataFrame(ten_starts[:3], columns=list(pk.core.PAPER_NAMES))
    df = pk.ensemble(model, table, 200.0, processes=1, progress=False, max_steps=50)
    assert list(df["status"]) == ["failed"] * 3 and all("step limit" in r for r in df["reason"])
    with pytest.raises(ParameterError, match="`starts`"):
        pk.ensemble(model, [[1.0, 2.0]], 10.0, progress=False)
    with pytest.raises(ParameterError, match="`t_eval`"):
        pk.ensemble(model, ten_starts[:1], 10.0, t_eval=[1.0], progress=False)
    with pytest.raises(ParameterError, match="`rtoll`"):
        pk.ensemble(model, ten_starts[:1], 10.0, rtoll=1e-9, progress=False)


def test_rerun_reproduces_a_result_from_its_json_and_an_ensemble_row(model, ten_starts):
    tr = pk.simulate(model, ten_starts[5], 200.0, events=[pk.Event("theta", 1.2, terminal=False)], rtol=1e-10)
    d = json.loads(json.dumps(tr.to_dict()))  # what the CLI prints, read back
    again = pk.rerun(d)
    assert again.t_jump == tr.t_jump and again.options == tr.options and len(again.events) == len(tr.events)
    df = pk.ensemble(model, ten_starts[4:7], 200.0, processes=1, progress=False)
    assert pk.rerun(df, 2).t_jump == df["t_jump"].iloc[2]
    with pytest.raises(ParameterError, match="`index`"):
        pk.rerun(df)
    # one row, taken out of a filtered table: its position there is not its start's
    row = df.iloc[1:].iloc[1]
    again = pk.rerun(row)
    assert row["i"] == 2 and again.t_jump == df["t_jump"].iloc[2] and again.R_min == df["R_min"].iloc[2]
    with pytest.raises(ParameterError, match="`source`"):
        pk.rerun(df.iloc[2].drop("i"))


# -- extension points ------------------------------------------------------------------------------


class LoadViscous(pk.friction.FrictionLaw):
    """A user's law, F = -mu R u (viscous, scaled by the load)."""

    name = "load-viscous"

    @staticmethod
    def sliding_force(u, mu, eps):
        return ca.SX.zeros(3), ca.vertcat(-mu * u[0], -mu * u[1], 1)


def test_user_body_agrees_with_the_built_in_spheroid_everywhere(standard_start):
    body = UserSpheroid(1.5)
    built_in = pk.Spheroid(1.5)
    mine = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), standard_start, 100.0)
    ref = pk.simulate(pk.Model(built_in, pk.Coulomb(0.1)), standard_start, 100.0)
    assert mine.t_jump == pytest.approx(ref.t_jump, rel=1e-10)
    fp = pk.fixed_points(pk.Model(body, pk.Viscous(0.1)), omega0=10.0)
    fp_ref = pk.fixed_points(pk.Model(built_in, pk.Viscous(0.1)), omega0=10.0)
    assert [f.kind for f in fp] == [f.kind for f in fp_ref]
    np.testing.assert_allclose(fp[0].eigenvalues, fp_ref[0].eigenvalues, rtol=1e-9)
    defn = pk.Definition("sliding", "sliding")
    th, th_ref = (pk.find_threshold(defn, b, lo=9.0, hi=11.0, n_coarse=3, tol=1e-2) for b in (body, built_in))
    assert th.status is pk.SearchStatus.CONVERGED and th.bracket == th_ref.bracket


def test_user_friction_law_runs_and_keeps_its_name(prolate, standard_start):
    law = LoadViscous(0.1)
    assert repr(law) == "LoadViscous(mu=0.1)" and law.describe() == "load-viscous(mu=0.1)"
    model = pk.Model(prolate, law)
    traj = pk.simulate(model, standard_start, 20.0)
    assert traj.status is pk.Status.COMPLETED
    # F = -mu R u: dissipative, and equal to the sampled friction force at a sampled state
    x = traj.states([10.0])[0]
    u = model.evaluate("slip", x)
    np.testing.assert_allclose(model.evaluate("friction", x), -0.1 * model.evaluate("R", x) * u, rtol=1e-12)
    E = traj.sample(np.linspace(0, 20, 500))["energy"].to_numpy()
    assert np.all(np.diff(E) <= 1e-9 * E[0])
    fp = pk.fixed_points(pk.Model(prolate, law), omega0=10.0)
    assert fp[0].kind == "horizontal" and fp[0].residual < 1e-10
    assert pk.Model(prolate, law).to_dict()["law"] == "load-viscous"


def test_base_classes_document_what_a_subclass_must_provide():
    for name in ("shape_params", "height(c, shape)"):
        assert name in pk.bodies.Body.__doc__
    assert "sliding_force(u, mu, eps)" in pk.friction.FrictionLaw.__doc__
    with pytest.raises(NotImplementedError, match="must define `shape_params`"):
        pk.bodies.Body(1.0, 1.0).shape_params


def test_scene_validation_names_the_argument():
    with pytest.raises(ParameterError, match="`dt`"):
        pk.Scene(dt=0)
    with pytest.raises(ParameterError, match="`resolution`"):
        pk.Scene(resolution=1)
    with pytest.raises(ParameterError, match="`omega_range`"):
        pk.Scene(omega_range=(20.0, 10.0))
    with pytest.raises(ParameterError, match="`branch`"):
        pk.Scene("oblate", 1.5)
    with pytest.raises(ParameterError, match="`values`"):
        pk.Scene(values=(10.0, -1.0))
    with pytest.raises(ParameterError, match="`traj`"):
        pk.Scene().add_trajectory("not a trajectory")


def test_ensemble_on_a_dask_client_equals_the_local_run(model, ten_starts):
    from dask.distributed import Client

    with Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=None) as client:
        on_dask = pk.ensemble(model, ten_starts[:4], 200.0, scheduler=client, progress=False)
    here = pk.ensemble(model, ten_starts[:4], 200.0, processes=1, progress=False)
    cols = [c for c in here.columns if c != "wall_s"]
    assert on_dask[cols].equals(here[cols])
    with pytest.raises(ParameterError, match="`scheduler`"):
        pk.ensemble(model, ten_starts[:1], 10.0, scheduler=3.0, progress=False)
