"""A run that says how far it can be trusted (phasekit/core/verify.py, approximations.py): repeated at
rtol / 10 in the other chart, and the approximations it used listed, each with its bound."""

import json

import phasekit as pk
from phasekit.core import RunCheck

import numpy as np
import pytest


@pytest.fixture(scope="module")
def standard():
    body = pk.Spheroid(1.5)
    return pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)


def test_the_standard_run_to_t_40_is_converged_in_position_and_orientation(standard):
    """The issue's bar: position and orientation within 1e-7 relative (or 1e-8 b) of a converged run."""
    model, x0 = standard
    traj = pk.simulate(model, x0, 40.0, verify=True)
    v = traj.verification
    assert isinstance(v, RunCheck) and v.verdict == "converged" and v.chart == "vector" and v.rtol == 1e-10
    assert v.position < 1e-8 and v.orientation < 1e-7 and v.end_state < 1e-7 and v.worst < 1e-7
    # an independent measure of the same: the position of G at rtol 1e-9 against 1e-13 in the same chart
    tight = pk.simulate(model, x0, 40.0, rtol=1e-13)
    g9, g13 = (np.array(r.pose([40.0]).iloc[0][["X", "Y"]], dtype=float) for r in (traj, tight))
    assert np.linalg.norm(g9 - g13) < 1e-8


def test_a_hopping_run_says_it_is_not_converged():
    """After its jump a fast spheroid hops (e = 0.5): hundreds of lift-offs and impacts whose sequence
    a ten times tighter tolerance changes (449 events to t = 40 at rtol 1e-9, 472 at 1e-10)."""
    body = pk.Spheroid(1.5)
    x0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=30.0)
    traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), x0, 40.0, stop_at="none", restitution=0.5, verify=True)
    check = traj.verification
    assert len(traj.events) > 100 and check.verdict == "not converged" and check.worst is None
    assert check.detail.startswith("not converged: events differ")


def test_a_trajectory_verifies_itself_on_request_and_reports_it_in_json(standard):
    model, x0 = standard
    traj = pk.simulate(model, x0, 30.0)
    assert traj.verification is None
    check = traj.verify()
    assert check.converged and check.worst < 1e-7
    d = pk.simulate(model, x0, 30.0, verify=True).to_dict()
    assert d["verification"]["verdict"] == "converged" and json.loads(json.dumps(d))["verification"]["chart"] == "vector"


def test_a_regularised_run_lists_its_regularisation_and_its_creep():
    body = pk.Spheroid(1.5)
    law = pk.RegularisedCoulomb(0.1, 1e-4)
    x0 = pk.gyroscopic_start(body, 1.5, omega0=3.0)
    traj = pk.simulate(pk.Model(body, law), x0, 5.0)
    names = [a.name for a in traj.approximations]
    assert names[:2] == ["regularised friction", "creep"] and traj.approximations[0].bound == 1e-4
    assert traj.approximations[1].bound == pytest.approx(1e-2)
    assert [a["name"] for a in traj.to_dict()["approximations"]] == names


def test_with_the_creep_off_the_run_follows_the_laws_own_field():
    """The same start with SolverOptions(creep=False): no creep in the list, the law rebuilt without
    it, and its rolling stretch agrees with a Radau run of the law's own field (scipy, rtol 1e-11)."""
    from scipy.integrate import solve_ivp

    body = pk.Spheroid(1.5)
    law = pk.RegularisedCoulomb(0.1, 1e-4)
    x0 = pk.gyroscopic_start(body, 1.5, omega0=3.0)
    traj = pk.simulate(pk.Model(body, law), x0, 5.0, creep=False, rtol=1e-11)
    assert "creep" not in [a.name for a in traj.approximations]
    assert not traj.model.friction.creeps and traj.model.friction.describe().endswith("no creep)")
    assert pk.Model.from_dict(traj.to_dict()["model"]).friction == traj.model.friction
    own = pk.Model(body, law)
    ref = solve_ivp(lambda t, y: own.rhs(y, pk.core.Mode.SLIDING), (0.0, 5.0), x0, method="Radau", rtol=1e-11, atol=1e-14,
                    jac=lambda t, y: own.jacobian(y, pk.core.Mode.SLIDING))
    assert np.abs(traj.x - ref.y[:, -1]).max() < 1e-7
