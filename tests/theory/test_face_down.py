"""A disk sliding and spinning on its face (phasekit.theory.face_down): the terminal ratio
eps* = v/(r omega) against Farkas et al. and an independent high-precision computation, reached by
integrating the ratio's equation; both motions stopping together; the annulus' eps*(r_i/r) growing
towards 1; the energy balance along a run."""

import math

import phasekit as pk
from phasekit.theory.face_down import (
    annulus_resultant,
    inertia_factor,
    ratio_rate,
    slide_to_rest,
    stop_time,
    terminal_ratio,
)

import mpmath
import numpy as np
import pytest
from scipy.integrate import solve_ivp

#: Farkas, Bartels, Unger & Wolf, Phys. Rev. Lett. 90, 248302 (2003), for the uniform disk, as
#: quoted by Weidman & Malhotra (2007): "the terminal value of the speed ratio eps_0 = v/R omega is
#: always 1.0 for the ring and 0.653 for the uniform disk" (abstract).
FARKAS_EPS = 0.653
#: the ratios beta = r_i/r of the annuli checked
RATIOS = (0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999)


def _mp_terminal_ratio(beta):
    """eps* of a washer from mpmath's 2F1, K and E at 30 digits: the closed forms of the uniform
    patch (module notes of phasekit.friction.patch), nothing of phasekit's numerics."""
    mpmath.mp.dps = 30

    def f(e):
        return e * mpmath.hyp2f1(-0.5, 0.5, 2, e * e) if e <= 1 else mpmath.hyp2f1(-0.5, 0.5, 2, 1 / (e * e))

    def g(e):
        if e <= 1:
            m = e * e
            return 4 / (9 * mpmath.pi) * ((4 - 2 * m) * mpmath.ellipe(m) - (1 - m) * mpmath.ellipk(m))
        return mpmath.hyp2f1(0.5, 0.5, 3, 1 / (e * e)) / (4 * e)

    b = mpmath.mpf(beta)
    kappa = (1 + b * b) / 2

    def h(e):
        if b == 0:
            return kappa * f(e) - e * g(e)
        return kappa * (f(e) - b * b * f(e / b)) - e * (g(e) - b**3 * g(e / b))

    return float(mpmath.findroot(h, 0.7 if beta < 0.9 else 0.99))


def test_full_disk_terminal_ratio_matches_farkas_et_al():
    eps = terminal_ratio().eps
    assert abs(eps - FARKAS_EPS) < 1e-3
    assert eps == pytest.approx(0.6530018, abs=1e-6)


@pytest.mark.parametrize("beta", [0.0, 0.5, 0.9])
def test_terminal_ratio_agrees_with_an_independent_30_digit_computation(beta):
    result = terminal_ratio(beta)
    assert result.status == "converged" and result.attracting
    assert result.eps == pytest.approx(_mp_terminal_ratio(beta), abs=1e-10)


@pytest.mark.parametrize("beta", [0.0, 0.5, 0.9])
@pytest.mark.parametrize("eps0", [0.02, 30.0])
def test_terminal_ratio_is_reached_by_integrating_the_ratio_equation(beta, eps0):
    """d eps/d tau = -h(eps), tau = ln(omega0/omega): from far below and far above, to tau = 60."""
    sol = solve_ivp(lambda tau, y: [-float(ratio_rate(y[0], beta))], (0.0, 60.0), [eps0], method="DOP853",
                    rtol=1e-12, atol=1e-14)
    assert sol.y[0, -1] == pytest.approx(terminal_ratio(beta).eps, abs=1e-9)


@pytest.mark.parametrize("v0, omega0", [(1.0, 3.0), (2.0, 0.5), (0.05, 10.0)])
def test_sliding_and_spinning_stop_at_the_same_instant(v0, omega0):
    run = slide_to_rest(v0, omega0, mu=0.3)
    T = stop_time(v0, omega0, mu=0.3)  # another clock (ln omega), another integration
    assert run.status == "at_rest"
    assert abs(run.t_stop_slide - run.t_stop_spin) < 1e-8 * T
    assert run.t_stop_spin == pytest.approx(T, rel=1e-8)


def test_pure_sliding_and_pure_spin_stop_times_are_the_coulomb_ones():
    """omega -> 0: v0/(mu g); v -> 0: the couple is mu R (2/3) r, so omega0 r/2 / (2 mu/3) = 3 r omega0/(4 mu)."""
    assert stop_time(1.0, 1e-9, mu=0.5) == pytest.approx(2.0, rel=1e-6)
    assert stop_time(1e-9, 2.0, mu=0.5) == pytest.approx(3 * 2.0 / (4 * 0.5), rel=1e-6)


def test_annular_terminal_ratio_grows_monotonically_towards_one():
    eps = np.array([terminal_ratio(b).eps for b in RATIOS])
    assert np.all(np.diff(eps) > 0)
    assert eps[0] == pytest.approx(terminal_ratio().eps, rel=1e-14)
    assert 1 - eps[-1] < 1e-3 and 1 - eps[-2] < 1e-2
    assert np.all(eps < 1)


@pytest.mark.parametrize("beta", [0.5, 0.9])
def test_annular_terminal_ratio_is_where_a_time_integration_ends(beta):
    run = slide_to_rest(1.0, 0.4, mu=0.2, ratio=beta)
    assert run.status == "at_rest"
    assert run.eps_end == pytest.approx(terminal_ratio(beta).eps, abs=1e-5)


def test_thin_ring_meets_force_and_couple_at_eps_one():
    """The ring's f(1) = g(1) = 2/pi with kappa = 1: eps* = 1 is the ring's fixed point. The annulus
    approaches it like (1 - beta) log(1 - beta) (both of its circles sit at the kink s = 1)."""
    gaps = np.array([[abs(x - 2 / math.pi) for x in annulus_resultant(1.0, b)[:2]] for b in (0.99, 0.999, 0.9999)])
    assert np.all(np.diff(gaps, axis=0) < 0)
    assert np.all(gaps[-1] < 3e-4)


@pytest.mark.parametrize("beta", [0.0, 0.5])
def test_energy_balance_holds_along_an_integration(beta):
    run = slide_to_rest(1.5, 2.0, mu=0.25, r=0.7, ratio=beta)
    assert run.energy_error < 1e-8
    assert run.ys[-1, 2] < 0 and np.all(np.diff(run.ys[:, 2]) <= 0)  # the patch only takes energy


def test_a_narrow_hole_barely_changes_the_disk_and_a_washers_inertia_is_its_integral():
    eps = np.array([0.2, 1.0, 3.0])
    full = np.array(pk.friction.patch.patch_resultant(eps))
    holed = np.array(annulus_resultant(eps, 1e-3)[:2])
    np.testing.assert_allclose(holed, full, rtol=1e-5)  # beta^2 (f(eps) - 1)/f(eps) and beta^4/(4 eps g(eps))
    assert np.max(np.abs(holed - full) / full) > 1e-8
    r = np.linspace(0.6, 1.0, 20001)  # I/(M r^2) of a washer 0.6 < r < 1 by the trapezoidal rule
    kappa = np.trapezoid(r**3, r) / np.trapezoid(r, r)
    assert inertia_factor(0.6) == pytest.approx(kappa, rel=1e-8)
    assert inertia_factor(0.6, "disk") == 0.5


@pytest.mark.parametrize("kappa", [0.2, 0.9])
def test_inertia_outside_the_finite_ratio_regime_has_no_terminal_ratio(kappa):
    """kappa < 1/4: the spin stops first (eps -> oo); kappa > 2/3: the slide does (eps -> 0)."""
    with pytest.raises(pk.ParameterError) as err:
        terminal_ratio(0.0, kappa)
    assert err.value.param == "kappa"
