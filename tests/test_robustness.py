"""Issue 9: stiff and extreme cases end with a status (never a crash or a NaN); CVODES converges."""

import phasekit as pk
from phasekit.core import charts

import numpy as np
import pytest


def test_vector_to_euler_is_finite_next_to_the_pole():
    for th in (1e-8, 1e-12):
        y = charts.vector_to_euler(charts.euler_to_vector([0.0, 0.0, 14.0, 0.0, th, 10.0]))
        assert np.all(np.isfinite(y)) and y[2] == pytest.approx(14.0, rel=1e-6)


@pytest.mark.parametrize(
    "a, law, start",
    [
        (0.2, pk.Coulomb(0.1), dict(theta0=0.05, n0=10.0)),
        (5.0, pk.Coulomb(0.1), dict(theta0=np.pi / 2 - 0.01, omega0=100.0)),
        (1.01, pk.Coulomb(0.1), dict(theta0=1.2, omega0=10.0)),
        (2 / 3, pk.Coulomb(1.0), dict(theta0=0.05, n0=10.5)),
        (1.5, pk.Viscous(1.0), dict(theta0=np.pi / 2 - 1e-8, omega0=10.5)),
    ],
)
def test_extreme_cases_end_with_a_status_and_finite_state(a, law, start):
    body = pk.Spheroid(a)
    y0 = pk.gyroscopic_start(body, start["theta0"], omega0=start.get("omega0"), n0=start.get("n0"))
    rise = pk.Event("theta", 0.05, direction=-1) if a > 1 else pk.Event("theta", np.pi / 2 - 0.05, direction=+1)
    r = pk.simulate(pk.Model(body, law), y0, 2000.0, events=[rise])
    assert r.status in (pk.Status.JUMPED, pk.Status.STOPPED, pk.Status.COMPLETED)
    assert np.all(np.isfinite(r.x)) and np.isfinite(r.R_min)


def test_hopelessly_stiff_case_fails_with_a_reason_and_bounded_work():
    """eps = 1e-12 on a sticking start: relaxation rate mu/eps = 1e11. It must end, as failed,
    with a readable reason, not hang and not return NaNs."""
    m = pk.Model(pk.Spheroid(1.5), pk.RegularisedCoulomb(0.1, 1e-12))
    y = [7e-5, 2e-6, 10.5, -1e-4, np.pi / 2 - 1e-3, 2e-2]
    r = pk.simulate(m, y, 100.0, max_steps=300_000)
    assert r.status is pk.Status.FAILED and "CV_TOO_MUCH_WORK" in r.reason
    assert ".cpp" not in r.reason and np.all(np.isfinite(r.x))
    assert r.stuck  # the stick that made it stiff is on record


def test_cvodes_error_falls_with_rtol(prolate, standard_start):
    m = pk.Model(prolate, pk.Coulomb(0.1))
    ref = pk.simulate(m, standard_start, 200.0, rtol=1e-14, track_minima=False).t_jump
    rtols = [1e-6, 1e-8, 1e-10]
    errs = [abs(pk.simulate(m, standard_start, 200.0, rtol=rt, backend="cvodes", track_minima=False).t_jump - ref) for rt in rtols]
    slope = np.polyfit(np.log10(rtols), np.log10(errs), 1)[0]
    assert slope > 0.7 and errs[-1] / ref < 1e-7  # relative error of t*


def test_idas_backend_agrees(prolate, standard_start):
    m = pk.Model(prolate, pk.Coulomb(0.1))
    ref = pk.simulate(m, standard_start, 200.0, rtol=1e-13, track_minima=False).t_jump
    r = pk.simulate(m, standard_start, 200.0, rtol=1e-11, backend="idas", track_minima=False)
    assert r.backend == "idas" and abs(r.t_jump - ref) / ref < 1e-7
