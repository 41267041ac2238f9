"""The typed records of the steady-state analysis: where a branch may end (:class:`Edge`), an interval of
a branch between two edges (:class:`Interval`), how a branch ends (:class:`BranchEnd`), and a range of
theta the structure is computed on (:class:`Part`: a compound body's piece, an edged body's range, or
all of [0, pi]).

Words: a *branch* is a maximal interval of theta with Omega^2 > 0, joined across the families it
crosses (phasekit.steady.branches); a *piece* is only ever a part of a compound body
(phasekit.bodies.compound).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..bodies.body import Body

#: a limit's name (bodies.Limit) in a branch end's words
LIMIT_WORDS = {"face down": "the face comes down onto the table", "side down": "the side touches the table"}


@dataclass(frozen=True)
class Edge:
    """A point of theta where an interval of a branch may end: a root of q and/or D (``q``, ``D``:
    which vanish there), a ``pole`` ("0" or "pi"), a ``switch`` to the piece beyond (a compound
    body), or a ``limit`` of an edged body's range (its name)."""

    theta: float
    q: bool = False
    D: bool = False
    pole: str | None = None
    switch: str | None = None
    limit: str | None = None


#: the ends of the range of a one-piece body
POLE_EDGES = (Edge(0.0, pole="0"), Edge(math.pi, pole="pi"))


@dataclass(frozen=True)
class BranchEnd:
    """One end of a branch (module notes).

    Attributes
    ----------
    kind : str
        One of END_KINDS: "pole", "static", "infinite-spin", "switch" (a compound body's
        switch angle, where the contact passes to another piece) or "limit" (an end of an
        edged body's range of theta).
    theta : float
        Where the branch ends: located to ~1e-15 by Brent's method on q or D; exactly 0 or pi
        at a pole; the body's switch angle at a switch; the end of the body's range at a limit.
    pole : str or None
        "0" or "pi" at a pole, else None.
    n, Omega : float or None
        At a pole, the signed spin with which the branch (Omega > 0) meets the spin about the
        vertical, and the pole's rate limit; at a switch, the limits of the branch's spin and
        rate there on its own piece (the next piece's branch, if any, starts elsewhere in
        (Omega, n): H' jumps); at a limit, their limits there (``inf`` where Omega diverges,
        at a face coming down); else None.
    to_piece : str or None
        At a switch, the piece the contact passes to ("stem" at the tippe top's switch from the
        ball); else None.
    limit : str or None
        At a limit, its name as a run's event names it ("face down", "side down"); else None.
    """

    kind: str
    theta: float
    pole: str | None = None  # "0" or "pi"
    n: float | None = None
    Omega: float | None = None
    to_piece: str | None = None
    limit: str | None = None

    @property
    def label(self) -> str:
        if self.kind == "pole":
            return "pole0" if self.pole == "0" else "polePi"
        return "inf" if self.kind == "infinite-spin" else self.kind

    def describe(self) -> str:
        """The end in words, e.g. "the contact passes to the stem at theta = 2.31972".

        Returns
        -------
        str
        """
        if self.kind == "switch":
            return f"the contact passes to the {self.to_piece} at theta = {self.theta:.6g}"
        if self.kind == "limit":
            what = LIMIT_WORDS.get(self.limit, f"the body's range ends ({self.limit})")
            return f"{what} at theta = {self.theta:.6g}"
        if self.kind == "pole":
            return f"the spin about the vertical at theta = {'0' if self.pole == '0' else 'pi'}"
        return f"{'a static equilibrium' if self.kind == 'static' else 'an infinite-spin asymptote'} at theta = {self.theta:.6g}"

    def to_dict(self) -> dict:
        d = {"kind": self.kind, "theta": self.theta}
        if self.kind == "pole":
            d.update(pole=self.pole, n=self.n, spin=abs(self.n), Omega=self.Omega)
        elif self.kind == "switch":
            d.update(to_piece=self.to_piece, n=self.n, spin=abs(self.n), Omega=self.Omega, description=self.describe())
        elif self.kind == "limit":  # a value that diverges there (Omega as a face comes down): null, named in "diverges"
            fin = lambda v: v if math.isfinite(v) else None  # noqa: E731
            d.update(limit=self.limit, n=fin(self.n), spin=fin(abs(self.n)), Omega=fin(self.Omega),
                     diverges=[k for k, v in (("Omega", self.Omega), ("n", self.n)) if not math.isfinite(v)],
                     description=self.describe())
        return d


@dataclass(frozen=True)
class Interval:
    """An interval of a branch: between the edges ``lo`` and ``hi``, crossing the families at
    ``crossings`` (theta of each); ``ends`` the two :class:`BranchEnd` once classified."""

    lo: Edge
    hi: Edge
    crossings: tuple[float, ...] = ()
    ends: tuple[BranchEnd, BranchEnd] | None = None


@dataclass(frozen=True)
class Part:
    """A range of theta the structure is computed on: a compound body's piece (``name``, its
    ``support`` a :class:`phasekit.bodies.compound.PieceSupport`) between its two ``edges`` (a pole,
    or a switch to the piece beyond), or a one-piece body's whole range (``name`` None, ``support``
    the body)."""

    name: str | None
    support: Body
    edges: tuple[Edge, Edge]

    @property
    def lo(self) -> float:
        return float(self.edges[0].theta)

    @property
    def hi(self) -> float:
        return float(self.edges[1].theta)
