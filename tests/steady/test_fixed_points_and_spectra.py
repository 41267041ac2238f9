"""Fixed points found by Newton at every scale, their exact linearisation and spectra: residuals and
Jacobians, the rising mode, the oscillation frequencies, and the regularised spectrum's rolling
limit."""


import phasekit as pk
from phasekit.steady import find_fixed_point, fixed_points, horizontal_state, linearise, precessions, vertical_state
from phasekit.steady.fixedpoints import continue_family
from phasekit.steady.precessions import intermediate_state

import numpy as np
import pytest

from ..helpers import central_jacobian


@pytest.mark.parametrize("a", [1.5, 0.6])
@pytest.mark.parametrize("law", [pk.Viscous(0.1), pk.RegularisedCoulomb(0.1, 1e-4), pk.Coulomb(0.1)], ids=["viscous", "reg", "exact"])
def test_residuals_and_jacobians_at_fixed_points(a, law):
    body = pk.Spheroid(a)
    me, mv = pk.Model(body, law), pk.Model(body, law, "vector")
    pts = fixed_points(me, omega0=2.3) + fixed_points(me, mv, n0=6.0)
    assert {p.kind for p in pts} >= {"horizontal", "vertical"}
    for p in pts:
        assert p.residual < 1e-12, p
        if law.name == "viscous":  # the sliding field is smooth there: compare with differences
            m = mv if p.chart == "vector" else me
            J = m.jacobian(p.x)
            np.testing.assert_allclose(J, central_jacobian(m.rhs, p.x), atol=1e-6 * max(1, np.abs(J).max()))


def test_newton_from_a_rough_guess_and_intermediate_family_formula(prolate):
    m = pk.Model(prolate, pk.Viscous(0.1))
    exact = intermediate_state(prolate, 0.8)
    guess = exact + np.array([0.01, -0.01, 0.0, 0.02, 0.05, 0.1])
    fp = find_fixed_point(m, guess, kind="intermediate", value=exact[2])
    np.testing.assert_allclose(fp.x, exact, atol=1e-10)
    assert fp.residual < 1e-13
    # the family: Omega^2 = h_t / (sin [(A - C) cos + C h_t / x_P]) at every theta*
    br = continue_family(m, "intermediate", np.linspace(exact[2], exact[2] * 1.05, 6), start=exact)
    for p in br.points:
        np.testing.assert_allclose(p.x, intermediate_state(prolate, p.x[4]), atol=1e-9)


def test_intermediate_states_found_by_newton_satisfy_the_closed_form_balance():
    body = pk.Spheroid(0.3)
    [inter] = [p for p in pk.fixed_points(pk.Model(body, pk.Viscous(0.1)), omega0=3.0) if p.kind == "intermediate"]
    assert precessions.intermediate_omega(body, inter.y[4]) == pytest.approx(3.0, rel=1e-12)
    assert inter.residual < 1e-14


def test_convergence_error_states_the_tolerance_and_reads_an_intermediate():
    model = pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1))
    guess = precessions.intermediate_state(model.body, 0.8)  # Omega* ~ 2.0 here; ask for Omega = 1: no such state
    with pytest.raises(pk.ConvergenceError) as info:
        pk.steady.find_fixed_point(model, guess, kind="intermediate", value=1.0)
    msg = str(info.value)
    assert msg.startswith("Newton did not converge to an intermediate fixed point with Omega = 1")
    assert "above the tolerance 1e-10" in msg


def test_fixed_points_without_a_vector_model_returns_the_vertical_state():
    pts = pk.fixed_points(pk.Model(pk.Spheroid(0.6), pk.Coulomb(0.1)), n0=10.0)
    [v] = [p for p in pts if p.kind == "vertical"]
    assert v.y[4] == 0.0 and v.y[5] == pytest.approx(10.0, rel=1e-14)


def test_prolate_horizontal_rising_mode_is_real_and_linear_in_mu(prolate):
    rates = []
    mus = np.array([1e-3, 3e-3, 1e-2, 3e-2, 0.1])
    for mu in mus:
        fp = linearise(pk.Model(prolate, pk.Viscous(mu)), horizontal_state(10.0), kind="horizontal")
        assert fp.n_unstable == 1 and fp.classification == "unstable: 1 real unstable"
        assert fp.eigenvalues[0].imag == 0.0
        rates.append(fp.eigenvalues[0].real)
    slope = np.polyfit(np.log(mus), np.log(rates), 1)[0]
    assert slope == pytest.approx(1.0, abs=0.01)
    assert 0.5 < rates[0] / mus[0] < 2  # O(mu), not just proportional


def test_oscillatory_frequencies_approach_3_30(prolate):
    """At theta = pi/2 (3.30) gives omega^2 = Omega0^2 + h_tt / A; the pairs approach it."""
    errs = []
    for om in (5.0, 10.0, 20.0, 40.0):
        fp = linearise(pk.Model(prolate, pk.Viscous(0.1)), horizontal_state(om))
        freqs = np.abs(fp.eigenvalues.imag[fp.eigenvalues.imag > 0])
        assert freqs.size == 2
        w = np.sqrt(om**2 + prolate.h(np.pi / 2)[2] / prolate.A)
        errs.append(np.max(np.abs(freqs - w)) / w)
    assert all(e2 < e1 / 3 for e1, e2 in zip(errs, errs[1:]))  # ~Omega0^-2
    assert errs[-1] < 1e-3


def test_roles_swap_between_prolate_and_oblate():
    for a, vertical_stable, horizontal_unstable in [(1.5, True, True), (0.6, False, False)]:
        body = pk.Spheroid(a)
        h = linearise(pk.Model(body, pk.Viscous(0.1)), horizontal_state(10.0))
        v = linearise(pk.Model(body, pk.Viscous(0.1), "vector"), vertical_state(10.0))
        assert v.stable is vertical_stable and (h.n_unstable > 0) is horizontal_unstable


def test_regularised_coulomb_spectrum_tends_to_rolling(prolate):
    roll = linearise(pk.Model(prolate, pk.Coulomb(0.1)), horizontal_state(10.0))
    assert roll.law == "coulomb-rolling" and roll.n_unstable == 0
    w_roll = roll.eigenvalues.imag.max()
    for eps in (1e-4, 1e-6):
        reg = linearise(pk.Model(prolate, pk.RegularisedCoulomb(0.1, eps)), horizontal_state(10.0))
        slow = reg.eigenvalues[np.abs(reg.eigenvalues) < 1 / eps * 1e-2]
        fast = reg.eigenvalues[np.abs(reg.eigenvalues) > 1 / eps * 1e-2]
        assert fast.size == 2 and np.all(fast.real < -0.1 / eps)  # slip relaxes at ~mu/eps
        assert abs(slow.imag.max() - w_roll) < 1e-6
        assert np.max(np.abs(slow.real)) < 200 * eps  # real parts -> 0 like eps
