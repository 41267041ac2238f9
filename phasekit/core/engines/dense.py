"""Dense output of the engines: callables t -> states over a propagation's span. The Taylor method's
steps recorded as their Taylor polynomials (:class:`TaylorSteps`, evaluated by :class:`_TaylorDense`),
cubic Hermite interpolation on a pointwise engine's output grid (:class:`HermiteDense`), and the
restriction of either to its span (:class:`Span`).
"""

from __future__ import annotations

import numpy as np

from .roots import derivative_zeros


class TaylorSteps:
    """Dense output of the Taylor method: the Taylor coefficients of every step (heyoka's
    ``tc``, the expansion at the step's start), recorded by a step callback and evaluated
    here by Horner's rule. heyoka's own continuous output costs ~1.4 ms per propagate call
    whatever its length (measured), which dominates runs of many short segments; this costs
    ~0.4 us per step. ``tc`` is the integrator's ``ta.tc``, read once: it is a view of heyoka's
    buffer (reading the property costs 1 us a step). Each step keeps its bytes (half the cost
    of an array copy), joined into one array at the end. ``callback`` is what heyoka calls.
    ``scale``: the integrator's scales of its states from the first step on, :meth:`rescale` the
    new ones from the next step on (:mod:`.scaling`): one record spans a whole propagation, so
    what is computed per record (the monitor's zeros) is paid once, not once per renewal."""

    def __init__(self, t0: float, tc: np.ndarray, scale=None):
        self.t0, self.shape, self.ends, self.coefs = float(t0), tc.shape, [], []
        self.scale = None if scale is None else np.asarray(scale, dtype=float)[:, None]
        self._marks = []  # (index of the first step, scales) of each renewal
        self._arrays = None
        keep, end, raw = self.coefs.append, self.ends.append, tc.tobytes

        def callback(ta) -> bool:  # after every step (heyoka may deep-copy it: a function copies as itself)
            keep(raw())
            end(ta.time)
            return True

        self.callback = callback

    @property
    def t_last(self) -> float:
        return self.ends[-1] if self.ends else self.t0

    def rescale(self, scale) -> None:
        """The steps recorded from now on are in the integrator's new scaled variables."""
        self._marks.append((len(self.coefs), np.asarray(scale, dtype=float)[:, None]))
        self._arrays = None

    def finish(self, ta) -> None:
        """Record the last, event-truncated step when the callback did not see it."""
        if float(ta.time) != self.t_last:
            self.callback(ta)

    def arrays(self):
        """(starts, ends, coefficients (steps, states, order + 1)) of the recorded steps."""
        if self._arrays is None:
            ends = np.array(self.ends)
            coefs = np.frombuffer(b"".join(self.coefs)).reshape(len(self.coefs), *self.shape)
            if self.scale is not None:  # the integrator's scaled variables back to the flow's (scaling.py)
                firsts = [0, *(k for k, _ in self._marks), len(coefs)]
                scales = np.stack([self.scale, *(sc for _, sc in self._marks)])  # one multiply, each step by its scales
                coefs = coefs * scales[np.repeat(np.arange(len(scales)), np.diff(firsts))]
            self._arrays = np.concatenate([[self.t0], ends[:-1]]), ends, coefs
        return self._arrays

    def span(self, n: int):
        """The first ``n`` states' dense output over the recorded steps."""
        if not self.coefs:
            return None
        starts, ends, coefs = self.arrays()
        return Span(_TaylorDense(starts, ends, coefs[:, :n]), starts[0], ends[-1])

    def zeros(self, n: int, direction: int) -> list:
        """[(t, x)] where the second derivative of the last state (z, with z' = s P, see
        :func:`phasekit.core.engines.taylor_build.build_taylor`) crosses zero in ``direction``, x
        the first ``n`` states there: the monitor's zeros."""
        if not self.coefs:
            return []
        starts, ends, coefs = self.arrays()
        k, tau = derivative_zeros(ends - starts, coefs[:, -1], 2, direction)
        x = (coefs[k, :n] * np.vander(tau, coefs.shape[2], increasing=True)[:, None, :]).sum(axis=2)
        return list(zip((starts[k] + tau).tolist(), x))


#: times evaluated together by :class:`_TaylorDense` (the energy budget asks for 13 per step)
HORNER_BLOCK = 2048


def _horner(coefs, k, h) -> np.ndarray:
    """The steps ``k``'s polynomials at h past their starts (h a column), by Horner's rule."""
    c = coefs[k]  # (n, states, order + 1)
    out = c[:, :, -1].copy()
    for j in range(c.shape[2] - 2, -1, -1):
        out = out * h + c[:, :, j]
    return out


class _TaylorDense:
    """x(t) = sum_j tc[:, j] (t - t_start)^j on the step containing t."""

    def __init__(self, starts, ends, coefs):
        self.starts, self.ends, self.coefs = starts, ends, coefs

    def __call__(self, ts) -> np.ndarray:
        ts = np.atleast_1d(np.asarray(ts, dtype=float))
        k = np.clip(np.searchsorted(self.ends, ts, side="left"), 0, len(self.starts) - 1)
        h = (ts - self.starts[k])[:, None]
        if ts.size <= HORNER_BLOCK:
            return _horner(self.coefs, k, h)
        out = np.empty((ts.size, self.coefs.shape[1]))
        for a in range(0, ts.size, HORNER_BLOCK):  # blocks that stay in the cache: the same sums, ~3x faster
            out[a:a + HORNER_BLOCK] = _horner(self.coefs, k[a:a + HORNER_BLOCK], h[a:a + HORNER_BLOCK])
        return out

    def pieces(self):
        """(starts, ends, coefficients (steps, states, order + 1)): the steps' polynomials in
        powers of t - start, for quadratures along the run (:mod:`phasekit.core.pose`)."""
        return self.starts, self.ends, self.coefs


class Span:
    """A dense-output callable restricted to [t0, t1]."""

    def __init__(self, f, t0: float, t1: float):
        self.f, self.t0, self.t1 = f, float(t0), float(t1)

    def __call__(self, ts) -> np.ndarray:
        ts = np.asarray(ts, dtype=float)
        return np.asarray(self.f(ts)).reshape(ts.size, -1)

    def pieces(self):
        """The piecewise polynomials behind this span (see :meth:`_TaylorDense.pieces`)."""
        return self.f.pieces()


def linear_span(t0: float, t1: float, x0, x1) -> Span:
    """The straight line from (t0, x0) to (t1, x1) as a dense-output span (a one-step polynomial)."""
    x0, x1 = np.asarray(x0, dtype=float), np.asarray(x1, dtype=float)
    coefs = np.stack([x0, (x1 - x0) / (t1 - t0)], axis=-1)[None]
    return Span(_TaylorDense(np.array([t0]), np.array([t1]), coefs), t0, t1)


class HermiteDense:
    """Cubic Hermite interpolation on an integrator's output grid (for output only)."""

    def __init__(self, ts, xs, field, p):
        self.ts, self.xs = np.asarray(ts, float), np.asarray(xs, float)
        self.field, self.p = field, np.asarray(p, float)

    def __call__(self, tt) -> np.ndarray:
        tt = np.atleast_1d(np.asarray(tt, dtype=float))
        out = np.empty((tt.size, self.xs.shape[1]))
        for i, t in enumerate(tt):
            j = int(min(max(np.searchsorted(self.ts, t), 1), len(self.ts) - 1))
            t0, t1 = self.ts[j - 1], self.ts[j]
            if t == t1:
                out[i] = self.xs[j]
                continue
            h = t1 - t0
            s = (t - t0) / h
            f0 = np.asarray(self.field(self.xs[j - 1], self.p)).ravel()
            f1 = np.asarray(self.field(self.xs[j], self.p)).ravel()
            out[i] = ((2 * s**3 - 3 * s**2 + 1) * self.xs[j - 1] + (s**3 - 2 * s**2 + s) * h * f0
                      + (-2 * s**3 + 3 * s**2) * self.xs[j] + (s**3 - s**2) * h * f1)
        return out

    def pieces(self):
        """The same cubics in powers of t - t_j, one per grid interval: (starts, ends,
        coefficients (intervals, states, 4))."""
        F = np.array([np.asarray(self.field(x, self.p)).ravel() for x in self.xs])
        keep = np.diff(self.ts) > 0  # an event appended on a grid point makes an empty interval
        h = np.diff(self.ts)[keep][:, None]
        x0, x1, f0, f1 = self.xs[:-1][keep], self.xs[1:][keep], F[:-1][keep], F[1:][keep]
        slope = (x1 - x0) / h
        c2 = (3 * slope - 2 * f0 - f1) / h
        c3 = (f0 + f1 - 2 * slope) / h**2
        return self.ts[:-1][keep], self.ts[1:][keep], np.stack([x0, f0, c2, c3], axis=2)
