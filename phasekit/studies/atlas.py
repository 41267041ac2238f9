"""Atlases of steady-state structure (parts III and IV of the series; a study-support module): the
signature of :func:`phasekit.steady_structure` (the sequence of its branches' ends) over a plane
of body parameters, and the boundaries between its classes.

* :class:`AtlasPanel`: one plane (its axes, ranges and scales); :func:`axis_values`, its grid,
  offset by half a cell (no point on a measure-zero boundary such as A = C).
* :class:`AtlasRow` (a body's signature) and :class:`BoundaryRow` (a traced boundary point), as
  stored by :class:`phasekit.sweep.ResultStore`.
* :func:`atlas_grid` (the points of the panels), keyed by :func:`atlas_point_key`.
* :func:`atlas_edges` (neighbours whose signatures differ), :func:`trace_boundary` (bisection on
  the signature along one of them, naming the bifurcation), :func:`is_class`,
  :func:`atlas_representatives` (one body per class), :func:`bifurcation_pairs` (the class pairs
  each bifurcation separates). A traced edge is keyed by :func:`atlas_edge_key`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..steady.structure import bifurcation_between


class AtlasPanel(NamedTuple):
    """One plane of an atlas: its title, axis labels, ranges and whether each axis is logarithmic.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> p = ps.AtlasPanel("tippe top", "offset", "A / C", (0.02, 0.9), (0.5, 2.0), False, False)
    >>> p.xrange, p.logy
    ((0.02, 0.9), False)
    """

    title: str
    xlabel: str
    ylabel: str
    xrange: tuple
    yrange: tuple
    logx: bool
    logy: bool


@dataclass(frozen=True)
class AtlasRow:
    """The signature of one body of an atlas (``panel``, at ``x``, ``y``; ``z``: the third
    parameter of a 3-D grid) and the status of its structure.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.AtlasRow("k", "tippe-top", 0.3, 1.2, 0.0, "pole-pole", "completed").signature
    'pole-pole'
    """

    key: str
    panel: str
    x: float
    y: float
    z: float
    signature: str
    status: str


@dataclass(frozen=True)
class BoundaryRow:
    """A traced boundary point between two classes of an atlas panel: where (``x``, ``y``),
    the width of its final bracket, the signatures on either side and the bifurcation there
    (:func:`phasekit.steady.structure.bifurcation_between`).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.BoundaryRow("k", "tippe-top", 0.3, 0.7, 1e-4, "a", "b", "saddle-node").bifurcation
    'saddle-node'
    """

    key: str
    panel: str
    x: float
    y: float
    width: float
    below: str
    above: str
    bifurcation: str


def axis_values(rng, n: int, log: bool) -> np.ndarray:
    """``n`` grid values over ``rng``, each half a cell in from its edge (so that none lies on
    A/C = 1 exactly); geometric with ``log``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.axis_values((0.0, 1.0), 4, False).tolist()
    [0.125, 0.375, 0.625, 0.875]
    """
    u = (np.arange(n) + 0.5) / n
    return np.exp(np.log(rng[0]) + u * np.log(rng[1] / rng[0])) if log else rng[0] + u * (rng[1] - rng[0])


def atlas_edges(rows, panels: dict) -> list[tuple]:
    """Neighbouring points (along x and along y) of each 2-D panel (``panels``: name ->
    :class:`AtlasPanel`) whose signatures differ, among the completed ``rows``
    (:class:`AtlasRow`): ``(panel, p, q, span)``, span being the panel's range along the edge.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> P = {"demo": ps.AtlasPanel("demo", "x", "y", (0.0, 1.0), (0.0, 1.0), False, False)}
    >>> rows = [ps.AtlasRow(str(x), "demo", x, 0.5, 0.0, "A" if x < 0.5 else "B", "completed") for x in (0.25, 0.75)]
    >>> ps.atlas_edges(rows, P)
    [('demo', (0.25, 0.5), (0.75, 0.5), 1.0)]
    """
    edges = []
    for panel, (_, _, _, xr, yr, _, _) in panels.items():
        sig = {(r.x, r.y): r.signature for r in rows if r.panel == panel and r.status == "completed"}
        xs, ys = sorted({x for x, _ in sig}), sorted({y for _, y in sig})
        for i, x in enumerate(xs):
            for j, y in enumerate(ys):
                nbrs = ([((xs[i + 1], y), xr[1] - xr[0])] if i + 1 < len(xs) else []) + \
                       ([((x, ys[j + 1]), yr[1] - yr[0])] if j + 1 < len(ys) else [])
                for q, span in nbrs:
                    if (x, y) in sig and q in sig and sig[x, y] != sig[q]:
                        edges.append((panel, (x, y), q, span))
    return edges


def trace_boundary(structure_at, panel: str, p, q, span: float, *, xtol: float, key: str) -> BoundaryRow:
    """Bisect the signature along the edge from ``p`` to ``q`` of a 2-D panel (along x or
    along y; ``structure_at(panel, x, y)``: the structure there) until the bracket is ``xtol``
    of the panel's ``span``, and name the bifurcation between the two sides.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> def at(panel, x, y):
    ...     return pk.steady_structure(pk.EccentricSphere(x, A=y * 0.4, C=0.4), pk.Viscous(0.1), samples=False)
    >>> b = ps.trace_boundary(at, "tippe-top", (0.3, 1.2), (0.3, 1.4), 1.5, xtol=1e-2, key="k")
    >>> abs(b.y - 1.3) < 0.02, b.below != b.above
    (True, True)
    """
    lo, hi = 0.0, 1.0
    s_lo, s_hi = structure_at(panel, *p), structure_at(panel, *q)
    length = abs(q[0] - p[0]) + abs(q[1] - p[1])  # edges run along x or along y
    while (hi - lo) * length / span > xtol:
        mid = 0.5 * (lo + hi)
        s_mid = structure_at(panel, p[0] + mid * (q[0] - p[0]), p[1] + mid * (q[1] - p[1]))
        if s_mid.signature == s_lo.signature:
            lo, s_lo = mid, s_mid
        else:
            hi, s_hi = mid, s_mid
    t = 0.5 * (lo + hi)
    return BoundaryRow(key, panel, p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), (hi - lo) * length, s_lo.signature,
                       s_hi.signature, bifurcation_between(s_lo, s_hi))


def is_class(signature: str) -> bool:
    """Whether a signature is a class, not a boundary: no family crossed (that needs A = C or a
    side static exactly).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.is_class("pole-pole"), ps.is_class("none")
    (True, False)
    """
    return "cross" not in signature and signature != "none"


def atlas_representatives(rows, classes, panels) -> dict:
    """For each signature in ``classes``: the row (:class:`AtlasRow`) of the first panel in
    ``panels`` (names) that has it, nearest the median of the class's points in that panel's
    unit box (inside its region, away from its edges).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> rows = [ps.AtlasRow(str(x), "demo", x, 0.5, 0.0, "A", "completed") for x in (0.1, 0.4, 0.9)]
    >>> ps.atlas_representatives(rows, ["A"], ["demo"])["A"].x
    0.4
    """
    out = {}
    for sig in classes:
        for panel in panels:
            pts = [r for r in rows if r.panel == panel and r.signature == sig]
            if not pts:
                continue
            P = np.array([[r.x, r.y, r.z] for r in pts])
            lo, hi = P.min(axis=0), P.max(axis=0)
            U = (P - lo) / np.where(hi > lo, hi - lo, 1.0)
            k = int(np.argmin(np.sum((U - np.median(U, axis=0)) ** 2, axis=1)))
            out[sig] = pts[k]
            break
    return out


def atlas_grid(panels: dict, n: int) -> list[tuple]:
    """The points ``(panel, x, y, 0.0)`` of an ``n`` x ``n`` grid (:func:`axis_values`) over
    each 2-D panel (``panels``: name -> :class:`AtlasPanel`), x the outer loop.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> P = {"demo": ps.AtlasPanel("demo", "x", "y", (0.0, 1.0), (0.0, 1.0), False, False)}
    >>> ps.atlas_grid(P, 2)
    [('demo', 0.25, 0.25, 0.0), ('demo', 0.25, 0.75, 0.0), ('demo', 0.75, 0.25, 0.0), ('demo', 0.75, 0.75, 0.0)]
    """
    pts = []
    for panel, (_, _, _, xr, yr, logx, logy) in panels.items():
        pts += [(panel, float(x), float(y), 0.0) for x in axis_values(xr, n, logx) for y in axis_values(yr, n, logy)]
    return pts


def atlas_point_key(panel: str, x: float, y: float, z: float) -> str:
    """The key of an :class:`AtlasRow`.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.atlas_point_key("tippe-top", 0.3, 1.2, 0.0)
    'tippe-top|0.3|1.2|0'
    """
    return f"{panel}|{x:.12g}|{y:.12g}|{z:.12g}"


def atlas_edge_key(panel: str, p, q, span: float | None = None) -> str:
    """The key of a :class:`BoundaryRow` traced along the edge from ``p`` to ``q`` (an
    :func:`atlas_edges` item; its span is not part of the key).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.atlas_edge_key("tippe-top", (0.3, 1.2), (0.3, 1.4), 1.5)
    'edge|tippe-top|0.3|1.2|0.3|1.4'
    """
    return f"edge|{panel}|{p[0]:.12g}|{p[1]:.12g}|{q[0]:.12g}|{q[1]:.12g}"


def bifurcation_pairs(bounds) -> dict:
    """The bifurcations found on traced boundaries (:class:`BoundaryRow`), in the order of their
    names, each with the sorted class pairs it separates (``"a <-> b"``, the pair's
    signatures in order).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> b = [ps.BoundaryRow("k", "demo", 0.3, 0.7, 1e-4, "b", "a", "saddle-node")]
    >>> ps.bifurcation_pairs(b)
    {'saddle-node': ['a <-> b']}
    """
    names = {}
    for b in bounds:
        names.setdefault(b.bifurcation, set()).add(tuple(sorted((b.below, b.above))))
    return {k: sorted(" <-> ".join(p) for p in v) for k, v in sorted(names.items())}
