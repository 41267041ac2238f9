"""The observables: the quantities every mode of a model provides (:data:`OBSERVABLES`, for
:meth:`phasekit.core.model.Model.evaluate`, events and trajectory samples), and the evaluation of
a compiled function of (x, p) at one state or at many."""

from __future__ import annotations

import casadi as ca
import numpy as np

from .charts import PAPER_NAMES

#: observables every mode provides, for :meth:`Model.evaluate`, events and trajectory samples
OBSERVABLES = {
    **{name: f"the paper's state variable {name}" for name in PAPER_NAMES},
    "R": "normal reaction of the mode in force (0 in flight), units M g",
    "Rdot": "dR/dt in the mode in force",
    "friction": "horizontal friction force (F_1, F_2) of the mode in force, units M g",
    "slip": "slip velocity of the contact point (2-vector)",
    "slip_speed": "|slip velocity| of the contact point",
    "energy": "total energy (kinetic + potential), units M g b",
    "jellett": "Jellett's integral -L.GP (angular momentum about G dotted with P->G; A Omega h in the gyroscopic limit (3.17))",
    "L_Z": "vertical angular momentum about G",
    "spin": "spin n = w.k",
    "h": "height of G above the table, units b (in flight: h(theta), the gap excluded)",
    "W": "vertical velocity of G",
    "cos_theta": "cos(theta)",
    "gap": "height of the lowest point above the table (0 in contact)",
    "gap_rate": "rate of the gap (0 in contact)",
}


def evaluate_function(f: ca.Function, p: np.ndarray, x):
    """f(x, p) for one state (d,) -> float or (k,), or for many states (m, d) -> (m,) or (m, k)."""
    X = np.asarray(x, dtype=float)
    if X.ndim == 1:
        r = np.asarray(f(X, p))
        return float(r.item()) if r.size == 1 else r.ravel()
    if X.shape[0] == 0:
        return np.empty((0,) if f.numel_out(0) == 1 else (0, f.numel_out(0)))
    if X.shape[0] <= MAP_BLOCK:
        r = np.asarray(f.map(X.shape[0])(X.T, np.tile(p[:, None], (1, X.shape[0]))))
    else:  # one map of MAP_BLOCK columns, built once per function (building a map costs ~5 ms)
        m, P = _mapped(f), np.tile(p[:, None], (1, MAP_BLOCK))
        pad = -X.shape[0] % MAP_BLOCK
        XT = np.concatenate([X, np.repeat(X[-1:], pad, axis=0)]).T if pad else X.T
        r = np.concatenate([np.asarray(m(XT[:, a:a + MAP_BLOCK], P)) for a in range(0, XT.shape[1], MAP_BLOCK)],
                           axis=1)[:, :X.shape[0]]
    return r.ravel() if r.shape[0] == 1 else r.T


#: states evaluated by one map of a compiled function (:func:`evaluate_function` on more of them)
MAP_BLOCK = 4096
_MAPS: dict = {}


def _mapped(f: ca.Function) -> ca.Function:
    key = id(f)
    hit = _MAPS.get(key)
    if hit is None or hit[0] is not f:
        hit = _MAPS[key] = (f, f.map(MAP_BLOCK))
    return hit[1]
