"""Componentwise error control for the Taylor method: the integrators run in scaled variables.

heyoka has one tolerance, applied to the infinity norm of the whole state: absolute where the
largest component is below 1, relative to that component above it. In the paper's variables a
body precessing fast carries Omega ~ 40 and n ~ 20 beside U, V and Lambda ~ 1e-3 to 1e-2, the
velocities that set the slip, so those got an absolute error of ~40 rtol per step: ~1e4 rtol
relative, in the quantities that decide the friction. Measured on the literal recipe near
a = 1 (a = 1.1, Omega0 = 40, eps = 1e-4): theta at t = 150 was off by 1.1e-6, 1.1e-6 and 2.1e-7
at rtol 1e-10, 1e-11 and 1e-12 (no convergence, and outcomes that changed with the tolerance);
the same field with every component scaled to its own size (floor 1e-2) is off by 1.1e-8,
5.8e-10, 3.4e-10 for 2-10% more steps. Checked two more ways: CVODES (componentwise weights) on the same Euler
field converges to the same reference as rtol and atol fall (5.5e-8 at t = 160 at rtol 1e-13,
atol 1e-17), and the vector chart at rtol 1e-14 and 1e-15 agrees with it to 2.7e-8 there
(docs/physics.md, "Tolerance per component").

So every Taylor integrator integrates xs = x / S, with S a run-time parameter per state
(nothing is recompiled), S_i = max(|x_i|, SCALE_FLOOR): the error per step is <= rtol S_i, a test
relative to each component as CVODES's (rtol |x_i| + atol) with atol = rtol SCALE_FLOOR.
The scales are set at the start of each propagation and again on a fixed grid of times
(every RESCALE_EVERY time units, the same for the scalar and the batch integrators, so that
both take the same steps), never falling faster than by half per interval so that a
component that passes through zero keeps the scale of its oscillation.
"""

from __future__ import annotations

import math

import numpy as np

#: the smallest scale of a component (units of b, sqrt(g b), sqrt(g/b)): the absolute part of the
#: error test. Measured at rtol 1e-9 (docs/physics.md): on the literal run a = 1.05, Omega0 = 51.74,
#: eps = 1e-4, whose slow start creeps with U, V < 1e-5, t* is 306.619, 306.123, 305.495 and 305.370
#: with floors 1e-2, 1e-3, 1e-4 and 1e-6 (converged 305.368); on the standard workload t* is off by
#: 8.9e-10, 1.2e-10, 5.9e-11 and 5.7e-11, for 613, 684, 714 and 715 steps
SCALE_FLOOR = 1e-6
#: the scales are renewed at every multiple of this time (units sqrt(b/g)): the propagation is cut
#: there (one short step more per interval); fast changes of size happen at events, which renew them
#: too. Measured (rtol 1e-9): every 1, 4, 10 time units leave the standard t* off by 5.6e-11, 1.1e-10,
#: 4.8e-10 and the literal run a = 1.05, Omega0 = 51.74, eps = 1e-4 at t* = 305.370, 305.494,
#: 305.620 (converged 305.368, both charts at rtol 1e-11 and 1e-12): a longer interval is cheaper
#: for the batch integrator (16 threshold runs: 71, 41, 42 ms; its lanes wait for each other at
#: every renewal) but less accurate, so it is 1
RESCALE_EVERY = 1.0


def initial_scales(x) -> np.ndarray:
    """The scales of a propagation that starts at ``x``."""
    return np.maximum(np.abs(np.asarray(x, dtype=float)), SCALE_FLOOR)


def next_scales(x, previous) -> np.ndarray:
    """The scales after a grid time at which the state is ``x``: its sizes, not below the floor and
    not below half the ``previous`` scales (a component passing through zero keeps its scale)."""
    new = np.abs(np.asarray(x, dtype=float))  # one new array, the rest in place (~45 renewals a run)
    np.maximum(new, SCALE_FLOOR, out=new)
    return np.maximum(new, 0.5 * np.asarray(previous), out=new)


def next_rescale(t: float) -> float:
    """The first grid time (a multiple of RESCALE_EVERY) after ``t``."""
    k = math.floor(t / RESCALE_EVERY) + 1
    out = k * RESCALE_EVERY
    return out if out > t else (k + 1) * RESCALE_EVERY
