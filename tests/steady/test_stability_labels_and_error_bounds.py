"""Stability labels backed by error bounds (phasekit.steady.linearisation.FixedPoint): each eigenvalue's
real part is classified against a first-order bound (condition number x error of the
Jacobian); labels agree with closed-form criteria, and a state labelled unstable grows at the
rate of its eigenvalue."""

import phasekit as pk

import numpy as np
import pytest

from ..helpers import run_cli, strict_json


@pytest.mark.parametrize("a", [1.2, 1.5, 3.0])
def test_horizontal_state_labels_follow_the_closed_form_threshold(a):
    body = pk.Spheroid(a)
    crit = pk.theory.horizontal_stability_threshold(body.A, body.C, a)
    model = pk.Model(body, pk.Viscous(0.1))
    for factor in (0.99, 0.999, 1.001, 1.01):
        fp = pk.steady.find_fixed_point(model, pk.steady.horizontal_state(factor * crit), kind="horizontal", value=factor * crit)
        assert (fp.n_unstable > 0) == (factor > 1) and fp.n_undecided == 0
        # the deciding eigenvalue is small, but far outside its bound
        nonzero = np.flatnonzero(np.abs(fp.eigenvalues) > fp.bounds)
        k = nonzero[int(np.argmax(fp.eigenvalues.real[nonzero]))]
        assert abs(fp.eigenvalues[k].real) > 100 * fp.bounds[k]


@pytest.mark.parametrize("alpha,A,C", [(0.3, 0.38, 0.4), (0.2, 0.45, 0.4)])
def test_pole_labels_follow_the_pole_criterion(alpha, A, C):
    body = pk.EccentricSphere(alpha, A=A, C=C)
    model = pk.Model(body, pk.Viscous(0.3), "vector")
    for pole, state in (("upright", pk.steady.vertical_state), ("inverted", pk.steady.inverted_state)):
        crit = pk.theory.pole_stability_threshold(body, pole)
        for n0 in (0.9 * crit.threshold, 1.1 * crit.threshold):
            x = state(n0)
            fp = pk.steady.find_fixed_point(model, x, kind="vertical", value=n0) if pole == "upright" else pk.steady.linearise(model, x)
            assert fp.stable == crit.stable(n0)


def test_the_slip_eps_case_is_labelled_unstable_with_its_bound():
    code, out, _ = run_cli("fixed-points", "--a", "1.5", "--mu", "0.1", "--slip-eps", "1e-5", "--omega0", "2", "--json")
    d = strict_json(out)
    [h] = [p for p in d["fixed_points"] if p["kind"] == "horizontal"]
    re = np.array([e[0] for e in h["eigenvalues"]])
    bounds = np.array([np.inf if b is None else b for b in h["error_bounds"]])
    assert code == 0 and not h["stable"] and h["classification"] == "unstable: 1 oscillatory unstable pair"
    assert re[0] > 1e3 * bounds[0]  # +3.2e-6 against a bound of a few 1e-9: not rounding
    assert h["eigenvalue_classes"][:2] == ["unstable", "unstable"]


def _horizontal(eps):
    model = pk.Model(pk.Spheroid(1.5), pk.RegularisedCoulomb(0.1, eps))
    fp = pk.steady.find_fixed_point(model, pk.steady.horizontal_state(2.0), kind="horizontal", value=2.0)
    return model, fp


def test_the_unstable_label_is_the_growth_of_the_linearised_dynamics():
    """eps = 1e-5: the pair grows at 3.2e-6 (e-folding 3e5) next to slip modes at -3.5e4: the
    linearised dynamics advanced exactly (its propagator expm(J dt), 400 steps to t = 4e5)
    grow at that rate."""
    from scipy.linalg import expm

    model, fp = _horizontal(1e-5)
    J = model.jacobian(fp.x, pk.core.Mode.SLIDING)
    lam = fp.eigenvalues[0]
    step = expm(J * 1000.0)
    y = fp.eigenvectors[:, 0].real.copy()
    norms = []
    for _ in range(400):
        y = step @ y
        norms.append(np.linalg.norm(y))
    rate = np.log(np.max(norms[-50:]) / np.max(norms[50:100])) / (300 * 1000.0)  # windows 3e5 apart
    assert rate == pytest.approx(lam.real, rel=0.05)


def test_a_state_labelled_unstable_grows_in_a_simulation():
    """eps = 1e-3: the pair grows at 3.2e-4; the full nonlinear equations started on the
    unstable eigenvector grow at that rate (the amplitude of Lambda over windows)."""
    model, fp = _horizontal(1e-3)
    lam = fp.eigenvalues[0]
    assert fp.n_unstable == 2 and lam.real > 1e3 * fp.bounds[0]
    v = fp.eigenvectors[:, 0].real
    x0 = fp.x + 1e-7 * v / np.linalg.norm(v)
    T = 1000.0
    traj = pk.simulate(model, x0, T, rtol=1e-11, stop_at="none", track_minima=False)
    assert traj.status is pk.Status.COMPLETED
    period = 2 * np.pi / abs(lam.imag)
    early = traj.sample(np.linspace(0.0, 5 * period, 800))["Lambda"].abs().max()
    late = traj.sample(np.linspace(T - 5 * period, T, 800))["Lambda"].abs().max()
    rate = np.log(late / early) / (T - 5 * period)
    assert rate == pytest.approx(lam.real, rel=0.02)


def test_rolling_spectra_stay_neutral_and_zero_eigenvalues_are_not_counted():
    model = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))
    fp = pk.steady.find_fixed_point(model, pk.steady.horizontal_state(2.0), kind="horizontal", value=2.0)
    assert fp.law == "coulomb-rolling" and fp.stable and fp.n_unstable == 0
    assert fp.classification == "neutral (spectrally stable)"
    # every real part lies within its bound (a reversible, energy-conserving field), and two
    # eigenvalues are zero within theirs: the family in Omega0 and its conjugate
    assert np.all(np.abs(fp.eigenvalues.real) <= fp.bounds)
    assert int(np.sum(np.abs(fp.eigenvalues) <= fp.bounds)) == 2 and np.max(np.abs(fp.eigenvalues.imag)) > 1.0
