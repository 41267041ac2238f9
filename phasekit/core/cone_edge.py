"""The EDGE mode of exact Coulomb friction: the contact slides on the edge of the friction cone.

Where rolling needs a friction force at the cone's edge, |F| = mu R, the slip stays tiny (1e-6 -
1e-3) for a long time while the force needed hovers about mu R. Sliding's field -mu R u/|u| is then
stiff: the slip's direction u/|u| relaxes at a rate ~ mu R |K|/|u| (K the contact's mobility), so
the Taylor steps shrink with |u|, and a run can spend its whole step budget stick-slipping there.

EDGE integrates the reduced system instead (Tikhonov; Filippov's convex combination of the rolling
and the sliding fields, the combination chosen by the dynamics). Write the slip u = r e. Sliding along
a fixed direction e (F = -mu R e, R from the contact constraint) gives a slip acceleration a(e); as
r -> 0 the direction is slaved to e*(x) with a(e*) = lambda e*, the condition
:func:`phasekit.core.zero_slip.sliding_direction` solves numerically at a slip onset. With the slip
acceleration c0 + C Fc and the constraint g0 + G Fc (both affine in Fc), multiplying by
D(e) = G.(-mu e, 1) turns it into

    b + M e = lambda' e,   b = c0 G_3 - g0 C_3,   M = mu (g0 C_12 - c0 G_12),   lambda' = lambda D,

so e(lambda') = -(M - lambda' I)^-1 b with |e| = 1, a scalar secular equation in lambda'. At
lambda' = 0, e = -M^-1 b is the direction of minus the rolling force over mu R (its length is 1
exactly on the cone's edge); NEWTON_STEPS Newton steps from there, unrolled symbolically, give e*.
The friction is F = -mu R e* + f e*_perp, (R, f) fixed by the contact constraint and by
d(e*_perp.u)/dt = -EDGE_PULL e*_perp.u (de*/dt along the field with F = -mu R e*): the slip stays
along e*, f = O(r), so the cone holds to O(r^2); no u/|u| appears, and nothing is stiff as r -> 0.
The slip grows (lambda > 0: the force needed lies beyond the cone) or vanishes (lambda < 0) at the
slow rate lambda.

Entry: from ROLLING at its slip event (u = 0 exactly, no nudge); from OFF_EDGE (SLIDING's field, after
an exit) when |u| falls below EDGE_IN while the force rolling would need is within EDGE_BAND of the cone's
edge (``edge_in``). Exit: u.e* falls to -EDGE_STICK (``edge_stick``): the slip vanished, roll (the rest
of u taken out by a contact impulse, ``edge_landing``); |u| rises past EDGE_OUT (``edge_out``): the
reduction's first-order error would grow with r, slide (OFF_EDGE). docs/physics.md, "Sliding on the
edge of the friction cone (exact Coulomb's EDGE mode)", gives what was checked.
"""

from __future__ import annotations

import casadi as ca

from .hybrid import Mode

#: the slip speed (units sqrt(g b)) above which EDGE hands over to SLIDING; the reduction's error is
#: first order in |u| (measured on the inverted tippe top: 1.7e-5 at 1e-3 against 1.5e-4 at 1e-2)
EDGE_OUT = 1e-3
#: the slip speed below which OFF_EDGE enters EDGE (hysteresis: half of EDGE_OUT) ...
EDGE_IN = 0.5 * EDGE_OUT
#: ... where the force rolling would need is this close to the cone's edge: |1 - |F|^2/(mu R)^2| below it
EDGE_BAND = 0.02
#: the rate (units sqrt(g/b)) at which the slip across e* is pulled to zero
EDGE_PULL = 20.0
#: the slip along e* (units sqrt(g b)) at which EDGE's stick fires, just past its zero: the slip is exactly 0
#: on entry from ROLLING, where a guard at 0 would fire at once; the slip then set to 0 changes the energy by
#: about |v| EDGE_STICK, far below the balance's tolerance
EDGE_STICK = 1e-12
#: Newton steps on the secular equation from the rolling force's direction (1 and 3 give the same run
#: to 9 digits on the inverted tippe top: the mode lives near the edge, where lambda' is small)
NEWTON_STEPS = 1


def slaved_direction(M, b, steps: int = NEWTON_STEPS):
    """e* with M e + b = lambda' e, |e*| = 1: Newton on |(M - lambda' I)^-1 b|^2 = 1 from lambda' = 0."""
    lam, eye = ca.SX(0), ca.DM.eye(2)
    for _ in range(steps):
        K = M - lam * eye
        y = ca.solve(K, b)
        z = ca.solve(K, y)
        lam = lam - (ca.dot(y, y) - 1) / (2 * ca.dot(y, z))
    e = -ca.solve(M - lam * eye, b)
    return e / ca.norm_2(e)


def build_edge(fn, add_mode, function, x, p, Fc, xdot, slip, constraint, mu, Fc_roll, frame_rate) -> None:
    """Add the EDGE mode's field (through ``add_mode``) and its guards ``edge_stick``, ``edge_out``,
    ``edge_in``, ``edge_landing`` and ``edge_check`` (R, lambda and the secular residual
    |a(e*) - lambda e*|) to ``fn``. The slip acceleration a(e) is taken in fixed axes (the chart's
    turn at ``frame_rate`` about the vertical), so that e* is the same direction in every chart."""
    zero = ca.SX.zeros(3)
    G = ca.jacobian(constraint, Fc)
    g0 = ca.substitute(constraint, Fc, zero)
    acc = ca.jtimes(slip, x, xdot)
    fixed = acc + frame_rate * ca.vertcat(-slip[1], slip[0])  # du/dt in fixed axes
    C = ca.jacobian(fixed, Fc)
    c0 = ca.substitute(fixed, Fc, zero)
    b = c0 * G[2] - g0 * C[:, 2]
    M = mu * (g0 * C[:, 0:2] - ca.mtimes(c0, G[0, 0:2]))
    e = slaved_direction(M, b)
    ep = ca.vertcat(-e[1], e[0])

    def along(ee):
        return ca.vertcat(-mu * ee[0], -mu * ee[1], 1)

    R_nom = -g0 / ca.mtimes(G, along(e))
    Fc_nom = R_nom * along(e)
    acc_nom = ca.substitute(fixed, Fc, Fc_nom)
    lam = ca.dot(e, acc_nom)
    de = ca.jtimes(e, x, ca.substitute(xdot, Fc, Fc_nom))
    # the unknowns (R, f): Fc = R (-mu e, 1) + f (e_perp, 0)
    Rs, f = ca.SX.sym("R"), ca.SX.sym("f")
    unknowns = ca.vertcat(Rs, f)
    Fc_e = Rs * along(e) + f * ca.vertcat(ep, 0)
    rows = ca.vertcat(ca.substitute(constraint, Fc, Fc_e),
                      ca.dot(ep, ca.substitute(acc, Fc, Fc_e)) + ca.dot(ca.vertcat(-de[1], de[0]), slip)
                      + EDGE_PULL * ca.dot(ep, slip))
    sol = -ca.solve(ca.jacobian(rows, unknowns), ca.substitute(rows, unknowns, ca.SX.zeros(2)))
    add_mode(Mode.EDGE, ca.substitute(Fc_e, unknowns, sol))
    speed2 = ca.sumsqr(slip)
    fn["edge_stick"] = function("edge_stick", x, p, ca.dot(slip, e))
    fn["edge_out"] = function("edge_out", x, p, speed2 - EDGE_OUT ** 2)
    # |u|^2 - EDGE_IN^2 (1 - (room/EDGE_BAND)^2), room = 1 - |F_roll|^2/(mu R_roll)^2 (0 on the cone's
    # edge), times (mu R_roll)^4 >= 0: the same zeros, and no pole where R_roll = 0 (a pole in a guard
    # shrinks the Taylor method's steps, measured: 30 000 steps in 0.08 s of the tippe top's inversion)
    cone = (mu * Fc_roll[2]) ** 2
    margin = cone - ca.sumsqr(Fc_roll[0:2])
    fn["edge_in"] = function("edge_in", x, p, cone ** 2 * (speed2 - EDGE_IN ** 2) + (EDGE_IN * margin / EDGE_BAND) ** 2)
    # the stick: the slip left (|u| ~ EDGE_STICK) taken out by a contact impulse, as the slip's own fast
    # transient would (M the contact's mobility, as in the rolling mode): it loses -u.K^-1 u/2 <= 0 of energy
    mobility = ca.jacobian(ca.vertcat(constraint, acc), Fc)
    impulse = ca.solve(mobility, ca.vertcat(0, -slip))
    fn["edge_landing"] = function("edge_landing", x, p, x + ca.mtimes(ca.jacobian(xdot, Fc), impulse))
    fn["edge_check"] = function("edge_check", x, p, ca.vertcat(R_nom, lam, ca.norm_2(acc_nom - lam * e)))
