"""The tippe top (an eccentric sphere) in phasekit's full model: Jellett's
integral is an exact invariant under every friction law, energy never increases, both charts
agree on event times, the README example converges in rtol and eps, and phasekit's model
agrees with an independent Newton-Euler model and with phasekit.theory.tippetop's closed forms."""

import json
import math
import subprocess
import sys

import phasekit as pk
from phasekit.steady import fixed_points, inverted_state, linearise, vertical_state
from phasekit.theory import tippetop as tt

import numpy as np
import pytest

from .newton_euler_tippe_top import jellett_of_state
from .newton_euler_tippe_top import rhs as reference_rhs

ALPHA, A, C, MU = 0.3, 0.38, 0.4, 0.3
THETA0, N0 = 0.1, 15.0
#: the README example, word for word
EXAMPLE = ["simulate", "--body", "tippe-top", "--offset", "0.3", "--A", "0.38", "--C", "0.4", "--mu", "0.3", "--friction", "coulomb", "--slip-eps", "1e-8", "--theta0", "0.1", "--spin-about-vertical", "15", "--stop-at", "theta=0.4", "--t-end", "30", "--rtol", "1e-10", "--json"]
LAWS = [pk.Coulomb(MU), pk.RegularisedCoulomb(MU, 1e-6), pk.Viscous(MU)]


@pytest.fixture(scope="module")
def top():
    return pk.EccentricSphere(ALPHA, A=A, C=C)


def run(top, law, chart="euler", t_end=12.2, **kw):
    m = pk.Model(top, law, chart)
    y0 = pk.core.vertical_spin_start(THETA0, N0)
    return pk.simulate(m, pk.core.to_chart(chart, y0), t_end, rtol=1e-12, dense=True, **kw)


# -- Jellett and the energy law --------------------------------------------------------------
@pytest.mark.parametrize("law", LAWS, ids=lambda law: law.name)
def test_jellett_is_exact_and_energy_never_increases_while_sliding(top, law):
    """Up to just before the first lift-off (t = 12.285 for Coulomb friction), sampled on the
    dense output: lambda = -L.GP stays at its start value to 1e-10 while friction removes energy."""
    r = run(top, law)
    assert r.status is pk.Status.COMPLETED and not r.stuck and len(r.flights) == 0
    df = r.sample(np.linspace(0.0, r.t, 3001))
    J, E = df["jellett"].to_numpy(), df["energy"].to_numpy()
    lam0 = tt.jellett_of_vertical_start(ALPHA, A, C, THETA0, N0)
    assert J[0] == pytest.approx(lam0, rel=1e-14)
    assert np.max(np.abs(J - lam0)) < 1e-10
    assert np.max(np.diff(E)) < 1e-12  # never increases (to rounding)
    assert E[0] - E[-1] > 1e-2  # and friction did work
    assert df["slip"].min() > 1e-3  # sliding throughout


def test_jellett_survives_flights_and_impacts(top):
    """Contact is lost during the inversion (the top hops): across lift-off, free flight and
    impacts (impulses act at P, so their torque about G is perpendicular to GP) lambda is
    still conserved, and each impact only removes energy."""
    r = run(top, pk.Coulomb(MU), t_end=14.0, stop_at="none", restitution=0.5)
    kinds = [e.name for e in r.events]
    assert kinds.count("lift-off") >= 2 and kinds.count("impact") >= 2
    t_first = r.events_named("lift-off")[0].t
    assert t_first == pytest.approx(12.285172, abs=1e-5)
    df = r.sample(np.linspace(0.0, r.t, 4001))
    lam0 = tt.jellett_of_vertical_start(ALPHA, A, C, THETA0, N0)
    assert np.max(np.abs(df["jellett"].to_numpy() - lam0)) < 1e-10
    assert np.max(np.diff(df["energy"].to_numpy())) < 1e-12
    assert set(df["mode"]) >= {"sliding", "flight"}


# -- two charts ---------------------------------------------------------------------------------
# its own integrators (~10 s cold): the full run only (the charts agree on the tippe top with its stem in
# tests/core/test_piece_transfer.py, and on spheroids in tests/core/test_euler_and_vector_charts.py)
@pytest.mark.slow
def test_both_charts_agree_on_event_times(top):
    """Euler and vector charts (independent formulations): every event to 1e-9 in time, here the
    crossings of theta = 0.4 (a non-terminal user event) and the lift-off."""
    ev = [pk.Event("theta", 0.4, direction=0, terminal=False, name="theta=0.4")]
    out = {c: run(top, pk.Coulomb(MU), c, t_end=13.0, events=ev) for c in ("euler", "vector")}
    e, v = (out[c].events for c in ("euler", "vector"))
    assert [x.name for x in e] == [x.name for x in v]
    assert [x.name for x in e].count("theta=0.4") >= 3 and e[-1].name == "lift-off"
    np.testing.assert_allclose([x.t for x in v], [x.t for x in e], rtol=0, atol=1e-9)
    assert out["vector"].status is out["euler"].status is pk.Status.JUMPED


# -- the README example ----------------------------------------------------------------------------
def example_t_stop(top, eps, rtol):
    law = pk.Coulomb(MU) if eps is None else pk.RegularisedCoulomb(MU, eps)
    r = pk.simulate(pk.Model(top, law), pk.core.vertical_spin_start(THETA0, N0), 30.0, rtol=rtol,
                    events=[pk.Event("theta", 0.4, name="theta=0.4")], dense=False)
    assert r.status is pk.Status.STOPPED
    return r.events[-1].t


def test_example_converges_in_rtol_and_eps(top):
    """t_stop of the example: the error against rtol = 1e-12 falls with rtol (4e-10 at 1e-8,
    below 1e-11 from 1e-10 on, measured); the regularisation changes it by < 1e-11 at eps 1e-6
    and < 1e-13 from eps 1e-8 on (the slip stays large before theta = 0.4)."""
    ref = example_t_stop(top, None, 1e-12)
    errs = [abs(example_t_stop(top, None, rtol) - ref) for rtol in (1e-8, 1e-9, 1e-10, 1e-11)]
    assert errs[0] > errs[2] and errs[1] > errs[2] and errs[2] < 2e-11 and errs[3] < 2e-11 and errs[0] < 1e-8
    for eps, tol in ((1e-6, 1e-11), (1e-8, 1e-13), (1e-10, 1e-13)):
        assert abs(example_t_stop(top, eps, 1e-12) - ref) < tol


def test_readme_example_on_the_command_line(top):
    proc = subprocess.run([sys.executable, "-m", "phasekit", *EXAMPLE], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["status"] == "stopped" and out["stopped_by"] == "theta=0.4"
    assert out["t_stop"] == pytest.approx(example_t_stop(top, None, 1e-12), abs=1e-10)
    assert out["state_end"]["theta"] == pytest.approx(0.4, abs=1e-12)


# -- an independent model ------------------------------------------------------------------------
def test_trajectory_matches_an_independent_newton_euler_model(top):
    """The NumPy model of newton_euler_tippe_top.py (vector Newton-Euler, its own contact
    geometry, no phasekit code), viscous friction: the axis and Jellett's integral at t = 8."""
    from scipy.integrate import solve_ivp

    law = pk.Viscous(MU)
    r = run(top, law, "vector", t_end=8.0)
    x0 = np.array([math.sin(THETA0), 0.0, math.cos(THETA0), 0.0, 0.0, N0, 0.0, 0.0])
    sol = solve_ivp(lambda t, x: reference_rhs(x, ALPHA, A, C, MU)[0], (0.0, 8.0), x0, method="DOP853",
                    rtol=1e-12, atol=1e-12)
    ref = sol.y[:, -1]
    np.testing.assert_allclose(r.x[:6], ref[:6], rtol=0, atol=1e-8)
    assert float(r.model.evaluate("jellett", r.x)) == pytest.approx(jellett_of_state(ref, ALPHA, A, C), abs=1e-9)


# -- closed forms against phasekit's linearisation ---------------------------------------------
def max_growth(fp) -> float:
    """Largest real part among the eigenvalues that are not structural zeros (|k| and the
    family parameter, exactly 0 to rounding)."""
    lam = fp.eigenvalues[np.abs(fp.eigenvalues) > 1e-10 * fp.scale]
    return float(np.max(lam.real))


@pytest.mark.parametrize("law", [pk.Viscous(0.05), pk.Viscous(3.0), pk.RegularisedCoulomb(MU, 1e-3)], ids=lambda law: f"{law.name}")
@pytest.mark.parametrize("A_", [0.31, 0.38])
def test_pole_criteria_of_tippetop_against_linearisation(law, A_):
    """tippetop.upright_unstable_spin and inverted_stable_spin (derived there from the energy
    and Jellett's integral, for any sliding law) are where phasekit's exact linearisation in
    the vector chart changes sign, for weak and strong viscous and regularised Coulomb friction."""
    body = pk.EccentricSphere(ALPHA, A=A_, C=C)
    m = pk.Model(body, law, "vector")
    n_up, n_inv = tt.upright_unstable_spin(ALPHA, A_, C), tt.inverted_stable_spin(ALPHA, A_, C)
    assert max_growth(linearise(m, vertical_state(0.98 * n_up))) < 0 < max_growth(linearise(m, vertical_state(1.02 * n_up)))
    assert max_growth(linearise(m, inverted_state(1.02 * n_inv))) < 0 < max_growth(linearise(m, inverted_state(0.98 * n_inv)))


def test_under_exact_coulomb_the_poles_roll_without_growth(top):
    """Exact Coulomb: the spinning poles have zero slip and roll; the rolling linearisation
    is neutral (no friction work), and the sliding-friction criterion is reported beside it."""
    pts = fixed_points(pk.Model(top, pk.Coulomb(MU)), n0=5.0)
    assert [p.kind for p in pts[:2]] == ["vertical", "inverted"]
    for p in pts[:2]:
        assert p.law == "coulomb-rolling" and np.max(np.abs(p.eigenvalues.real)) < 1e-8 * p.scale
    up, inv = pts[0].parameter, pts[1].parameter
    assert up["critical_spin"] == pytest.approx(tt.upright_unstable_spin(ALPHA, A, C), rel=1e-14)
    assert inv["critical_spin"] == pytest.approx(tt.inverted_stable_spin(ALPHA, A, C), rel=1e-14)
    assert not up["stable_under_sliding_friction"] and inv["stable_under_sliding_friction"]


@pytest.mark.parametrize("A_, n0", [(0.31, 1.5), (0.31, 2.0), (0.38, 1.5), (0.56, 3.0)])
def test_intermediate_states_are_tippetops_steady_precessions(A_, n0):
    """Every intermediate state phasekit finds for spin n0 is tippetop.steady.steady_precession at its
    angle (Omega, spin), and its stability under viscous friction is the energy criterion of
    tippetop (stable iff g'(z) < 0, g = steady_state_jellett_sq)."""
    body = pk.EccentricSphere(ALPHA, A=A_, C=C)
    pts = [p for p in fixed_points(pk.Model(body, pk.Viscous(0.3)), n0=n0) if p.kind == "intermediate"]
    # tippetop's states with spin n0: n^2 = alpha (z - alpha)^2 / D(z), solved here on a grid
    z = np.linspace(-0.999, 0.999, 200001)
    D = (A_ - C) * z + C * ALPHA
    F = ALPHA * (z - ALPHA) ** 2 - n0 * n0 * D
    expect = z[:-1][np.sign(F[:-1]) != np.sign(F[1:])]
    assert len(pts) == len(expect) >= 1
    for p, ze in zip(sorted(pts, key=lambda p: -math.cos(p.x[4])), sorted(expect, reverse=True)):
        th = p.x[4]
        assert math.cos(th) == pytest.approx(ze, abs=2e-5)
        sp = tt.steady.steady_precession(ALPHA, A_, C, th)
        assert abs(p.x[2]) == pytest.approx(sp["Omega"], rel=1e-10) and abs(p.x[5]) == pytest.approx(n0, rel=1e-12)
        h = 1e-6
        gp = (tt.steady.steady_state_jellett_sq(ALPHA, A_, C, math.cos(th) + h) - tt.steady.steady_state_jellett_sq(ALPHA, A_, C, math.cos(th) - h)) / (2 * h)
        assert (max_growth(p) < 1e-9) == (gp < 0)
