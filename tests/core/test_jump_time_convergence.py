"""The standard prolate workload jumps, and its jump time converges in eps and rtol."""

import phasekit as pk

import numpy as np
import pytest


@pytest.fixture(scope="module")
def runs(prolate, standard_start):
    out = {}
    for label, law in [("exact", pk.Coulomb(0.1)), ("eps1e-6", pk.RegularisedCoulomb(0.1, 1e-6)), ("eps1e-8", pk.RegularisedCoulomb(0.1, 1e-8))]:
        m = pk.Model(prolate, law)
        for rtol in (1e-9, 1e-11):
            out[label, rtol] = pk.simulate(m, standard_start, 200.0, rtol=rtol)
    return out


def test_standard_workload_jumps(runs):
    r = runs["exact", 1e-9]
    assert r.status is pk.Status.JUMPED
    assert 40 < r.t_jump < 50
    assert r.Rdot_jump < 0  # R crosses zero downwards
    assert not r.stuck  # slides throughout (slip stays >= 0.03)
    # the recorded lift-off state satisfies the guard: R = 0 there, evaluated afresh from the model
    m = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))
    assert abs(m.normal_reaction(r.x_jump)) < 1e-9


def test_t_jump_converges_in_eps_and_rtol(runs):
    ref = runs["exact", 1e-11].t_jump
    for key, r in runs.items():
        assert r.status is pk.Status.JUMPED, key
        assert abs(r.t_jump - ref) / ref < 1e-7, (key, r.t_jump, ref)
    # eps 1e-6 -> 1e-8 at fixed rtol
    for rtol in (1e-9, 1e-11):
        a, b = runs["eps1e-6", rtol].t_jump, runs["eps1e-8", rtol].t_jump
        assert abs(a - b) / b < 1e-7
    # the exact stick-slip law agrees with the regularised one
    assert abs(runs["exact", 1e-11].t_jump - runs["eps1e-8", 1e-11].t_jump) / ref < 1e-9


# the vector chart's integrator (~13 s cold): the full run only (the charts agree on the oblate spheroid's
# jump in tests/core/test_euler_and_vector_charts.py, CVODES gives t* to 1e-7 in test_cvodes_error_falls_with_rtol)
@pytest.mark.slow
def test_euler_and_vector_and_cvodes_agree_on_t_jump(prolate, standard_start):
    ref = pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), standard_start, 200.0, rtol=1e-12).t_jump
    rv = pk.simulate(pk.Model(prolate, pk.Coulomb(0.1), "vector"), pk.core.to_chart("vector", standard_start), 200.0, rtol=1e-12)
    rc = pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), standard_start, 200.0, rtol=1e-11, backend="cvodes")
    assert abs(rv.t_jump - ref) / ref < 1e-9
    assert abs(rc.t_jump - ref) / ref < 1e-7
    assert rc.backend == "cvodes"


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
