"""The linearisation of a steady state and its stability (part I of the series), for any body:
:func:`linearise` and the :class:`FixedPoint` it returns, with an error bound on every
eigenvalue. The states themselves are in phasekit.steady.precessions, the Newton searches for
them in phasekit.steady.fixedpoints.

Linearisation
-------------
CasADi's exact Jacobian of the mode's vector field. For viscous friction the field is
smooth at zero slip. The Coulomb law is not differentiable at u = 0, so "the linearisation
of Coulomb friction" needs a meaning:
* regularised Coulomb (eps > 0): the smooth field, whose slip modes relax at rates ~mu/eps;
* exact Coulomb: near a zero-slip state that static friction can hold (|F_req| <= mu R,
  here F_req = 0), any small slip dies in a finite time ~|u|/(mu g) and the motion is the
  rolling mode's, so stability is that of the ROLLING field restricted to the no-slip
  manifold (velocity of O slaved to u = 0). Rolling does no work: the rolling spectrum has
  no friction-induced decay or growth of the kind viscous friction gives, and the
  regularised spectrum tends to it, plus two fast slip modes, as eps -> 0 (tested).
  Closed-form criteria for sliding friction (phasekit.theory.criteria) are then reported beside
  the rolling spectrum in ``FixedPoint.parameter``.

Families have a structural zero eigenvalue (the family parameter), and in the vector chart
a second one (|k|, which the field leaves invariant); these count as neutral.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from .._runtime.validate import check_vector
from ..core.charts import PAPER_NAMES, VECTOR
from ..core.hybrid import Mode
from ..core.model import Model
from ..errors import ConvergenceError, ParameterError

#: the rounding of one evaluation of a compiled Jacobian, in units of eps * ||J||_F: CasADi's
#: entries are sums of many products (measured below 10 on the spheroid, egg and tippe top;
#: 64 leaves room), and LAPACK's eigensolver adds a backward error of a few eps * ||J||
JACOBIAN_ROUNDING = 64.0


@dataclass(frozen=True)
class FixedPoint:
    """A steady state with its linearisation.

    Attributes
    ----------
    kind : "vertical", "inverted", "horizontal", "horizontal-like" or "intermediate"
    chart : the chart of ``x`` ("euler" or "vector")
    x : chart state; ``y`` the same in the paper's variables (Omega is NaN at theta = 0)
    eigenvalues : complex, sorted by descending real part
    eigenvectors : columns in the coordinates of ``space`` (the chart's state, or for
        exact Coulomb the no-slip manifold coordinates, lifted to the chart state)
    residual : max |f(x)| of the mode's vector field at x
    law : the linearised law ("viscous", "coulomb-regularised", "coulomb-rolling")
    parameter : the family parameter (Omega0 or n0), and for the poles the closed-form
        stability criterion under sliding friction (phasekit.theory.criteria.pole_stability_threshold)
    error_bounds : a bound on the error of each eigenvalue (same order): its condition number
        (1 / |y^H x| for unit left and right eigenvectors) times the size of the error in the
        Jacobian (the rounding of its evaluation and of the eigensolver, JACOBIAN_ROUNDING
        eps ||J||, plus the change of J over the state's own error, estimated from the
        residual). First order in the error; infinite for a defective eigenvalue.

    Each eigenvalue is classified against its bound: Re > bound ``unstable``, Re < -bound
    ``stable``; |lambda| <= bound is a zero eigenvalue (families and invariants make them:
    ``neutral``); otherwise (|Re| within the bound, Im not) ``undecided`` for a dissipative
    law and ``neutral`` for the rolling field, which conserves energy and is reversible, so
    that its spectrum is symmetric about the imaginary axis and a real part within the bound
    is zero.

    Examples
    --------
    >>> import phasekit as pk
    >>> fp = pk.steady.linearise(pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1)), pk.steady.horizontal_state(10.0), kind='horizontal')
    >>> isinstance(fp, pk.steady.FixedPoint), fp.n_unstable, len(fp.unstable_directions())
    (True, 1, 1)
    """

    kind: str
    chart: str
    x: np.ndarray
    y: np.ndarray
    eigenvalues: np.ndarray
    eigenvectors: np.ndarray
    residual: float
    law: str
    parameter: dict = field(default_factory=dict)
    error_bounds: np.ndarray | None = field(default=None, repr=False)

    @property
    def scale(self) -> float:
        return max(1.0, float(np.max(np.abs(self.eigenvalues)))) if self.eigenvalues.size else 1.0

    @property
    def bounds(self) -> np.ndarray:
        if self.error_bounds is None:  # built by hand without bounds: rounding of the eigensolver only
            return JACOBIAN_ROUNDING * np.finfo(float).eps * self.scale * np.ones(self.eigenvalues.size)
        return self.error_bounds

    @property
    def eigenvalue_classes(self) -> tuple[str, ...]:
        """Per eigenvalue: "unstable", "stable", "neutral" or "undecided" (see the class notes)."""
        out = []
        for lam, b in zip(self.eigenvalues, self.bounds):
            if lam.real > b:
                out.append("unstable")
            elif lam.real < -b:
                out.append("stable")
            elif abs(lam) <= b or self.law == "coulomb-rolling":
                out.append("neutral")
            else:
                out.append("undecided")
        return tuple(out)

    def _unstable_mask(self) -> np.ndarray:
        return np.array([c == "unstable" for c in self.eigenvalue_classes], dtype=bool)

    @property
    def n_unstable(self) -> int:
        """Dimension of the unstable subspace (a complex pair counts 2)."""
        return int(np.sum(self._unstable_mask()))

    @property
    def n_neutral(self) -> int:
        return sum(c == "neutral" for c in self.eigenvalue_classes)

    @property
    def n_undecided(self) -> int:
        """Eigenvalues whose real part lies within its error bound although they are not zero:
        double precision cannot tell their sign."""
        return sum(c == "undecided" for c in self.eigenvalue_classes)

    @property
    def stable(self) -> bool:
        """Linearly (spectrally) stable: no eigenvalue whose real part is positive beyond its
        error bound, and none undecided."""
        return self.n_unstable == 0 and self.n_undecided == 0

    @property
    def classification(self) -> str:
        lam = self.eigenvalues[self._unstable_mask()]
        bounds = self.bounds[self._unstable_mask()]
        n_real = int(np.sum(np.abs(lam.imag) <= bounds))
        n_osc = (lam.size - n_real) // 2
        if lam.size == 0:
            if self.n_undecided:
                k = self.n_undecided
                return f"undecided: {k} eigenvalue{'s' if k > 1 else ''} with real part within {'their' if k > 1 else 'its'} error bound"
            return "stable" if self.n_neutral <= 2 else "neutral (spectrally stable)"
        parts = []
        if n_real:
            parts.append(f"{n_real} real unstable")
        if n_osc:
            parts.append(f"{n_osc} oscillatory unstable pair" + ("s" if n_osc > 1 else ""))
        return "unstable: " + ", ".join(parts)

    def unstable_directions(self) -> list[np.ndarray]:
        """Real unit vectors spanning the unstable subspace (Re and Im of complex ones),
        normalised in the Euclidean norm of the chart state."""
        out = []
        for k in np.flatnonzero(self._unstable_mask()):
            lam, v = self.eigenvalues[k], self.eigenvectors[:, k]
            if abs(lam.imag) <= self.bounds[k]:
                vecs = [v.real]
            elif lam.imag > 0:
                vecs = [v.real, v.imag]
            else:
                continue
            for w in vecs:
                if np.linalg.norm(w) > 0:
                    out.append(w / np.linalg.norm(w))
        return out

    def to_dict(self) -> dict:
        y = self.y
        state = {k: (None if not np.isfinite(v) else float(v)) for k, v in zip(PAPER_NAMES, y)}
        return {
            "kind": self.kind,
            "state": state,
            "residual": float(self.residual),
            "eigenvalues": [[float(ev.real), float(ev.imag)] for ev in self.eigenvalues],
            "error_bounds": [float(b) if np.isfinite(b) else None for b in self.bounds],
            "eigenvalue_classes": list(self.eigenvalue_classes),
            "n_unstable": self.n_unstable,
            "n_neutral": self.n_neutral,
            "n_undecided": self.n_undecided,
            "stable": self.stable,
            "classification": self.classification,
            "linearised_law": self.law,
            "chart": self.chart,
            **({"parameter": self.parameter} if self.parameter else {}),
        }

    def __repr__(self) -> str:
        return f"FixedPoint({self.kind}, {self.classification}, residual={self.residual:.1e})"


def mode_for(model: Model) -> Mode:
    return Mode.ROLLING if model.friction.has_rolling_mode else Mode.SLIDING


def check_model(model) -> Model:
    if not isinstance(model, Model):
        raise ParameterError("model", "must be a phasekit Model such as Model(Spheroid(1.5), Coulomb(0.1))", model)
    return model


# -- linearisation -------------------------------------------------------------------------


_REDUCED: dict = {}


def _rolling_reduced_jacobian(model: Model, x: np.ndarray):
    """Jacobian of the rolling field on the no-slip manifold, in coordinates that omit the
    velocity of O (it is slaved to u = 0), and the map lifting tangent vectors back.
    The CasADi function is built once per compiled model."""
    n = model.n_states
    i, j = model.chart.velocity_slots
    keep = [k for k in range(n) if k not in (i, j)]
    key = model.compiled.key
    if key not in _REDUCED:
        r = ca.SX.sym("r", len(keep))
        p = ca.SX.sym("p", len(model.p))
        base = [None] * n
        for k, kk in enumerate(keep):
            base[kk] = r[k]
        base[i] = ca.SX(0)
        base[j] = ca.SX(0)
        u = model.function("slip")(ca.vertcat(*base), p)  # the slip is (velocity slots) + u(rest)
        full = list(base)
        full[i], full[j] = -u[0], -u[1]
        xr = ca.vertcat(*full)
        fr = model.function("rhs_rolling")(xr, p)
        red = ca.vertcat(*[fr[k] for k in keep])
        _REDUCED[key] = ca.Function("Jr", [r, p], [ca.jacobian(red, r), ca.jacobian(xr, r)])
    Jr, L = _REDUCED[key](x[keep], model.p)
    return np.asarray(Jr), np.asarray(L)


def linearise(model: Model, x, *, kind: str = "state") -> FixedPoint:
    """Eigen-decomposition of the exact Jacobian at ``x`` (see the module notes for Coulomb),
    with an error bound on every eigenvalue (:class:`FixedPoint`).

    Parameters
    ----------
    model : Model
        The model; its friction law decides the field linearised (the rolling field for exact Coulomb).
    x : array_like
        The state, ``model.n_states`` numbers in the model's chart.
    kind : str, optional
        A label for the state, kept as ``FixedPoint.kind`` (e.g. "horizontal").

    Returns
    -------
    FixedPoint
        The state, its residual, eigenvalues, eigenvectors and eigenvalue error bounds.

    Raises
    ------
    ParameterError
        For a model that is not a Model, an empty or non-string ``kind``, a state of the wrong length or
        with non-finite entries, or a state where the field or Jacobian is not finite.
    ConvergenceError
        If the eigenvalue iteration does not converge.

    Examples
    --------
    >>> import phasekit as pk
    >>> fp = pk.steady.linearise(pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1)), pk.steady.horizontal_state(10.0), kind='horizontal')
    >>> fp.n_unstable, round(float(fp.eigenvalues[0].real), 6)
    (1, 0.089489)
    """
    model = check_model(model)
    if not isinstance(kind, str) or not kind:
        raise ParameterError("kind", "must be a label such as 'horizontal' or 'state'", kind)
    x = check_vector("x", x, model.n_states)
    mode = mode_for(model)
    f = model._rhs(x, mode)
    residual = float(np.max(np.abs(f)))
    jac = law_jacobian(model, mode)
    Jr, L = jac(x)
    law = "coulomb-rolling" if mode is Mode.ROLLING else model.friction.name
    if not (np.all(np.isfinite(Jr)) and np.isfinite(residual)):
        raise ParameterError("x", "gives a non-finite field or Jacobian (a state beyond double precision, or where "
                                  "the contact equations are singular)", x)
    try:
        lam, V, bounds = eigen_with_bounds(Jr, jacobian_error(model, mode, jac, x, f, Jr))
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ConvergenceError(f"the eigenvalues of the Jacobian at the {kind} state did not converge ({exc})") from None
    if L is not None:
        V = L @ V  # tangent vectors of the no-slip manifold, in chart coordinates
    y = model.chart.to_paper(x)
    if model.chart is VECTOR and np.hypot(x[0], x[1]) == 0.0:
        y[2] = np.nan  # Omega is undefined at theta = 0
    return FixedPoint(kind, model.chart.name, x, y, lam, V, residual, law, error_bounds=bounds)


def law_jacobian(model: Model, mode: Mode):
    """x -> (J, L): the Jacobian the law is linearised with, and for the rolling field the
    map lifting its reduced coordinates to the chart state (None otherwise)."""
    if mode is Mode.ROLLING:
        return lambda x: _rolling_reduced_jacobian(model, x)
    return lambda x: (model._jacobian(x, mode), None)


def jacobian_error(model: Model, mode: Mode, jac, x: np.ndarray, f: np.ndarray, J: np.ndarray) -> float:
    """A size (Frobenius norm) for the error of the computed Jacobian J at the computed state x:
    rounding (JACOBIAN_ROUNDING eps ||J||) plus the change of J across the state's own error
    dx, the least-squares Newton correction -J_full^+ f(x) of the residual f."""
    rounding = JACOBIAN_ROUNDING * np.finfo(float).eps * float(np.linalg.norm(J))
    if not np.any(f):
        return rounding
    J_full = model._jacobian(x, mode)
    dx = np.linalg.lstsq(J_full, -f, rcond=None)[0]
    if not np.all(np.isfinite(dx)):
        return float("inf")
    J2 = jac(x + dx)[0]
    return rounding + float(np.linalg.norm(J2 - J)) if np.all(np.isfinite(J2)) else float("inf")


def eigen_with_bounds(J: np.ndarray, error: float):
    """Eigenvalues (sorted by descending real part, then imaginary part), right eigenvectors
    and first-order error bounds kappa_i * error, kappa_i = 1/|y_i^H x_i| (unit vectors)."""
    import scipy.linalg

    lam, VL, VR = scipy.linalg.eig(J, left=True, right=True)
    nl, nr = np.linalg.norm(VL, axis=0), np.linalg.norm(VR, axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = (nl * nr) / np.abs(np.sum(VL.conj() * VR, axis=0))
    bounds = np.where(np.isfinite(kappa), kappa * error, np.inf)
    order = np.lexsort((-lam.imag, -lam.real))
    return lam[order], VR[:, order], bounds[order]
