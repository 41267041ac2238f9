"""CasADi's if_else (its comparisons and if_else_zero) translates to heyoka's select: the translated
field equals CasADi's on both sides of the switch, for every comparison and logical operation; a
Taylor integration that reaches the switch with the switch as an event stops there and goes on
with the other branch; the other non-smooth operations stay refused; the operations a body may use
(phasekit.bodies.operations) are exactly those the translator rebuilds."""

import math

import phasekit as pk
from phasekit.bodies.operations import NON_SMOOTH, PIECEWISE, SMOOTH, operations
from phasekit.core.engines.translate import binary, to_heyoka, unary

import casadi as ca
import heyoka as hy
import numpy as np
import pytest


def _cfunc(f: ca.Function, n_par: int):
    x = hy.make_vars("x")
    out = to_heyoka(f, [[x], [hy.par[i] for i in range(n_par)]])
    return hy.cfunc([e for o in out for e in o], [x])


def test_the_stemmed_tops_support_and_its_derivatives_translate_exactly_on_both_sides():
    top = pk.bodies.TippeTop(0.3, 0.375, 0.2, A=0.38, C=0.4)
    c, sh = ca.SX.sym("c"), ca.SX.sym("shape", 3)
    H = top.height(c, sh)
    dH = ca.jacobian(H, c)
    f = ca.Function("H", [c, sh], [ca.vertcat(H, dH, ca.jacobian(dH, c))])
    assert {"if_else_zero", "lt", "not"} <= operations(f)["non_smooth"]  # still reported as a kink ...
    cf = _cfunc(f, 3)  # ... and translated
    c_switch = math.cos(top.theta_switch)
    for cc in np.concatenate([np.linspace(-1, 1, 41), c_switch + np.array([-1e-9, -1e-13, 1e-13, 1e-9])]):
        want = np.asarray(f(cc, top.shape_params)).ravel()
        got = cf([cc], pars=list(top.shape_params))
        assert np.max(np.abs(got - want)) <= 1e-15 * max(1.0, np.max(np.abs(want))), cc
        # the ball's below the switch (c above c*), the stem's above it
        ball = cc > c_switch
        slope = -top.offset if ball else -top.tip_centre
        assert got[1] == pytest.approx(slope, rel=1e-15) and got[2] == 0.0


def test_every_comparison_and_logical_operation_translates():
    c, s = ca.SX.sym("c"), ca.SX.sym("s", 2)
    exprs = [ca.if_else(c < s[0], c, -c), ca.if_else(c <= s[0], 1.0, 2.0), ca.if_else(c == s[1], 3.0, 4.0),
             ca.if_else(c != s[1], ca.sin(c), ca.cos(c)), ca.if_else(ca.logic_not(c > s[0]), c * c, 1.0),
             ca.if_else(ca.logic_and(c > s[0], c < s[1]), c, 0.5), ca.if_else(ca.logic_or(c < s[0], c > s[1]), c, 0.5)]
    f = ca.Function("f", [c, s], [ca.vertcat(*exprs)])
    ops = {ca.OP_LT, ca.OP_LE, ca.OP_EQ, ca.OP_NE, ca.OP_NOT, ca.OP_AND, ca.OP_OR, ca.OP_IF_ELSE_ZERO}
    assert ops <= {f.instruction_id(k) for k in range(f.n_instructions())} and ops == PIECEWISE
    cf = _cfunc(f, 2)
    for cc in (-0.7, -0.2, -0.1999, 0.0, 0.3, 0.5, 0.9):
        want = np.asarray(f(cc, [-0.2, 0.5])).ravel()
        assert np.array_equal(cf([cc], pars=[-0.2, 0.5]), want), cc


@pytest.mark.parametrize("op", ["fabs", "fmax", "sign", "floor"])
def test_the_other_non_smooth_operations_stay_refused(op):
    c = ca.SX.sym("c")
    expr = {"fabs": ca.fabs(c), "fmax": ca.fmax(c, 0.1), "sign": ca.sign(c), "floor": ca.floor(c)}[op]
    f = ca.Function("f", [c], [expr])
    assert {f.instruction_id(k) for k in range(f.n_instructions())} & (NON_SMOOTH - PIECEWISE)
    with pytest.raises(NotImplementedError):
        to_heyoka(f, [[hy.make_vars("x")]])


def test_a_run_that_reaches_the_switch_stops_there_and_goes_on_with_the_other_branch():
    # x' = 1 above the switch s, 2 below it, from x = 0: the switch is reached at t = s/2 exactly
    c, s = ca.SX.sym("c"), ca.SX.sym("s")
    f = ca.Function("f", [c, s], [ca.if_else(c > s, 1.0, 2.0)])
    x = hy.make_vars("x")
    rhs = to_heyoka(f, [[x], [hy.par[0]]])[0][0]
    ta = hy.taylor_adaptive([(x, rhs)], [0.0], pars=[0.7], t_events=[hy.t_event(x - hy.par[0])])
    outcome = ta.propagate_until(10.0)[0]
    assert int(outcome.value) == -1  # the switch event (index 0) stopped the step
    assert ta.time == pytest.approx(0.35, rel=1e-15) and ta.state[0] == pytest.approx(0.7, rel=1e-15)
    ta.state[0] = 0.7 + 1e-12  # a reset puts the state just past the switch (core.resets.Transfer)
    ta.propagate_until(1.35)
    assert ta.state[0] == pytest.approx(1.7 + 1e-12, rel=1e-14)


def test_the_smooth_operations_a_body_may_use_are_the_ones_the_translator_rebuilds():
    assert SMOOTH == set(unary(hy)) | set(binary(hy))
