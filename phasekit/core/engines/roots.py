"""Zeros of the Taylor steps' polynomials: where the derivative of a recorded quantity crosses zero
(:func:`derivative_zeros`), e.g. the minima of R from the Taylor coefficients of its integral.

heyoka finds a non-terminal event's zeros on the Taylor expansion of the event's expression, which
costs a second expansion of the field's size (dR/dt: 232 elementary terms against the field's 112
on a spheroid, 2.3x the run, measured). The minima of R need less: the integrator carries
z' = s R, whose expansion shares R with the field (3 more terms), and d^2z/dt^2 = s dR/dt is the
expansion of dR/dt to one order less. Its zeros on each step are isolated the way heyoka isolates
an event's: the polynomial on [0, 1] in Bernstein form, whose sign changes bound the number of its
zeros there (Descartes' rule): none, no zero; one, exactly one; more, the step is halved (de
Casteljau) until each piece has at most one. Each zero is then found by Newton's steps from the
control polygon's crossing, on the expansion whose centre is nearer (a bracketed bisection where
they fail); tests/core/test_polynomial_zeros.py checks them against closed forms and numpy.
"""

from __future__ import annotations

from functools import lru_cache
from math import comb

import numpy as np

#: halvings of a step before a piece with several sign changes is taken as its end-point signs
MAX_DEPTH = 40


@lru_cache(maxsize=None)
def _to_bernstein(m: int) -> np.ndarray:
    """M with B = M b: Bernstein coefficients on [0, 1] of sum b_j u^j (degree m)."""
    return np.array([[comb(i, j) / comb(m, j) if j <= i else 0.0 for j in range(m + 1)] for i in range(m + 1)])


@lru_cache(maxsize=None)
def _falling(p: int, order: int) -> np.ndarray:
    """j (j - 1) ... (j - order + 1) for j = order ... p: the factors of the order-th derivative."""
    j = np.arange(order, p + 1)
    return np.prod([j - i for i in range(order)], axis=0).astype(float)


def _split(B: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """de Casteljau at u = 1/2: the Bernstein coefficients of the left and right halves."""
    left, right, row = [B[0]], [B[-1]], B
    while len(row) > 1:
        row = 0.5 * (row[:-1] + row[1:])
        left.append(row[0])
        right.append(row[-1])
    return np.array(left), np.array(right[::-1])


def _changes(B: np.ndarray) -> np.ndarray:
    """Sign changes along the last axis (zero counted as positive)."""
    s = B >= 0
    return np.count_nonzero(s[..., 1:] != s[..., :-1], axis=-1)


def _slopes(c: np.ndarray) -> np.ndarray:
    """The coefficients of each row's derivative (the last column zero)."""
    dc = np.zeros_like(c)
    dc[:, :-1] = c[:, 1:] * np.arange(1, c.shape[1])
    return dc


def _newton(c: np.ndarray, dc: np.ndarray, t: np.ndarray) -> np.ndarray:
    """One Newton step on each row's polynomial sum c_j t^j, dc its derivative's (a zero slope
    leaves t where it is)."""
    P = np.vander(t, c.shape[1], increasing=True)
    q, dq = np.einsum("ij,ij->i", c, P), np.einsum("ij,ij->i", dc, P)
    return t - np.divide(q, dq, out=np.zeros_like(q), where=dq != 0)


def _crossing(B: np.ndarray) -> np.ndarray:
    """Where each row's Bernstein control polygon (one sign change) crosses zero, in [0, 1]: a
    start for Newton's steps within a few of them of the curve's zero."""
    m = B.shape[1] - 1
    s = B >= 0
    i = np.argmax(s[:, 1:] != s[:, :-1], axis=1)
    r = np.arange(len(B))
    return (i + B[r, i] / (B[r, i] - B[r, i + 1])) / m


def _polish(b: np.ndarray, lo: np.ndarray, hi: np.ndarray, u: np.ndarray) -> np.ndarray:
    """The zero in [lo, hi] of each row's polynomial sum b_j u^j, which changes sign there once,
    from the start u: Newton's steps, a bisection whenever one leaves the bracket, to a step of
    1e-7 (the caller's last two Newton steps take it to rounding). The fallback of
    :func:`_nearer_centre`."""
    rising = (b * np.vander(hi, b.shape[1], increasing=True)).sum(axis=1) >= 0
    db = _slopes(b)
    for _ in range(60):
        q = (b * np.vander(u, b.shape[1], increasing=True)).sum(axis=1)
        below = (q < 0) == rising
        lo, hi = np.where(below, u, lo), np.where(below, hi, u)
        nxt = _newton(b, db, u)
        nxt = np.where((nxt >= lo) & (nxt <= hi), nxt, 0.5 * (lo + hi))
        done = np.abs(nxt - u) <= 1e-7
        u = nxt
        if done.all():
            break
    return u


def derivative_zeros(h: np.ndarray, coefs: np.ndarray, order: int, direction: int) -> tuple[np.ndarray, np.ndarray]:
    """Zeros of the ``order``-th derivative of each step's polynomial, crossing in ``direction``.

    Parameters
    ----------
    h : numpy.ndarray
        The steps' lengths, shape (k,).
    coefs : numpy.ndarray
        Each step's Taylor coefficients in powers of the time since its start, shape (k, p + 1).
    order : int
        Which derivative (2: the minima of R from its integral's coefficients).
    direction : int
        +1 rising through zero, -1 falling, 0 either.

    Returns
    -------
    tuple of numpy.ndarray
        (step index, time since that step's start) of each zero in (0, h], in time order (a zero
        in a step's second half is located on the next step's expansion, see
        :func:`_nearer_centre`).
    """
    p = coefs.shape[1] - 1
    d = coefs[:, order:] * _falling(p, order)
    b = d * np.vander(h, p + 1 - order, increasing=True)  # in u = tau / h on [0, 1]
    B = b @ _to_bernstein(p - order).T
    n = _changes(B)
    one = np.flatnonzero(n == 1)  # nearly every candidate: exactly one zero in the step
    found = [(one, np.zeros(len(one)), np.ones(len(one)), B[one, 0] < 0, _crossing(B[one]))]
    work, depth = [(k, 0.0, 1.0, B[k]) for k in np.flatnonzero(n > 1)], 0
    while work:  # rare: a step with several sign changes, halved until each piece has one or none
        rest = []
        for k, u0, u1, Bk in work:
            m = _changes(Bk)
            if m == 1 or (m > 1 and depth >= MAX_DEPTH):
                if (Bk[0] >= 0) != (Bk[-1] >= 0):
                    guess = u0 + (u1 - u0) * _crossing(Bk[None])
                    found.append((np.array([k]), np.array([u0]), np.array([u1]), np.array([Bk[0] < 0]), guess))
            elif m > 1:
                left, right = _split(Bk)
                mid = 0.5 * (u0 + u1)
                rest += [(k, u0, mid, left), (k, mid, u1, right)]
        work, depth = rest, depth + 1
    k, lo, hi, rising, guess = (np.concatenate(c) for c in zip(*found))
    keep = np.ones(len(k), bool) if direction == 0 else rising == (direction > 0)
    k, lo, hi, guess = k[keep], lo[keep], hi[keep], guess[keep]
    if len(found) > 1:  # zeros of halved steps: put them in time order
        order_ = np.lexsort((guess, k))
        k, lo, hi, guess = k[order_], lo[order_], hi[order_], guess[order_]
    j, t, ok = _nearer_centre(k, guess * h[k], h, lo * h[k], hi * h[k], d)
    if not ok.all():  # Newton's steps left the bracket: bisect there, then polish on the step itself
        bad = np.flatnonzero(~ok)
        u = _polish(b[k[bad]], lo[bad], hi[bad], guess[bad])
        c = d[k[bad]]
        dc = _slopes(c)
        j[bad], t[bad] = k[bad], _newton(c, dc, _newton(c, dc, u * h[k[bad]]))
    back = j > k  # found on the next step's expansion: given in the step that holds it
    t[back] += h[k[back]]
    return k, t


def _nearer_centre(k, tau, h, lo, hi, d):
    """Newton's steps from ``tau`` (a zero of step k's polynomial in [lo, hi]) on the expansion
    whose centre is nearer: a zero in a step's second half on the next step's (tau <= 0 there),
    because a truncated derivative is least accurate at the end of its step (measured: |dR/dt| 1e-8
    at such zeros at tol 1e-9, 4e-10 at heyoka's; 1e-10 on the nearer centre). Returns (step, tau,
    converged within [lo, hi])."""
    j = np.where((tau > 0.5 * h[k]) & (k + 1 < len(h)), k + 1, k)
    shift = np.where(j > k, h[k], 0.0)
    t, c = tau - shift, d[j]
    dc, small = _slopes(c), 1e-12 * h[k]
    for i in range(8):  # from the control polygon's crossing: 3 or 4 steps (measured)
        t, last = _newton(c, dc, t), t
        if i >= 2 and (np.abs(t - last) <= small).all():
            break
    ok = np.isfinite(t) & (np.abs(t - last) <= small) & (t + shift >= lo) & (t + shift <= hi)
    return j, t, ok
