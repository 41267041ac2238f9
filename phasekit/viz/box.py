"""The drawn box of a 3-D scene: (Omega, theta, n) have very different spans, so each is mapped
to a box of fixed aspect for drawing (the axes are labelled in the true values), and polylines
are cut exactly at its faces so that nothing is drawn outside it.
"""

from __future__ import annotations

import numpy as np

#: drawn box in VTK coordinates: Omega, theta, n spans
ASPECT = (1.4, 1.0, 1.0)


def bounding_box(bounds, aspect=ASPECT):
    lo = np.array(bounds[0::2], dtype=float)
    hi = np.array(bounds[1::2], dtype=float)
    span = np.where(hi > lo, hi - lo, 1.0)

    def f(P):
        P = np.atleast_2d(np.asarray(P, dtype=float))
        return (P - lo) / span * np.asarray(aspect)

    return f


def inside_runs(P: np.ndarray, bounds) -> list[np.ndarray]:
    """The pieces of the polyline P (N, 3) inside the box, each cut exactly at the faces."""
    lo, hi = np.array(bounds[0::2]), np.array(bounds[1::2])
    tol = 1e-12 * (hi - lo)
    inside = np.all((P >= lo - tol) & (P <= hi + tol), axis=1)
    runs, cur = [], []
    for k in range(len(P)):
        if inside[k]:
            if not cur and k > 0:
                cur.append(_cut(P[k], P[k - 1], lo, hi))
            cur.append(P[k])
        elif cur:
            cur.append(_cut(P[k - 1], P[k], lo, hi))
            runs.append(np.array(cur))
            cur = []
    if cur:
        runs.append(np.array(cur))
    return [r for r in runs if len(r) >= 2]


def _cut(a: np.ndarray, b: np.ndarray, lo, hi) -> np.ndarray:
    """The point where the segment from ``a`` (inside) to ``b`` (outside) leaves the box."""
    s = 1.0
    d = b - a
    for j in range(3):
        if d[j] > 0 and b[j] > hi[j]:
            s = min(s, (hi[j] - a[j]) / d[j])
        elif d[j] < 0 and b[j] < lo[j]:
            s = min(s, (lo[j] - a[j]) / d[j])
    return a + max(0.0, s) * d
