"""The exact boundary R = 0 at a given Lambda, by root finding on the model's normal reaction:
checked against the closed form (6.3) of the jump surface (:func:`phasekit.theory.surface_n`), with
which it coincides at Lambda = 0."""

from __future__ import annotations

import numpy as np

from .._runtime.validate import check_finite, check_instance, check_nonnegative
from ..core.model import Model
from ..friction.laws import Coulomb, FrictionLaw
from ..theory.jump_surface import check_body, check_grid, surface_n_unchecked


def exact_boundary(body, mu: float, Omega, theta, Lambda: float = 0.0, *, friction: FrictionLaw | None = None):
    """n at which the model's normal reaction (6.1) vanishes, for U = V = 0 and the given Lambda.

    Found by Brent's method on R(n) from the compiled model (Coulomb friction with ``mu``,
    or the law ``friction``; slip direction of that state), independently of the closed
    form (6.3).

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    mu : float or None
        Coulomb friction coefficient, finite >= 0; may be None when ``friction`` is given.
    Omega : float or array_like
        Precession rate, units sqrt(g/b), as for :func:`phasekit.theory.surface_n`: finite, nonzero.
    theta : float or array_like
        Inclination, radians, as for :func:`phasekit.theory.surface_n`: in (0, pi) where
        h_theta sin(theta) != 0, of a shape that broadcasts with that of ``Omega``.
    Lambda : float, optional
        The rate Lambda = dtheta/dt of the section, units sqrt(g/b): finite (default 0).
    friction : FrictionLaw, optional
        The friction law of the model; default Coulomb(mu).

    Returns
    -------
    numpy.ndarray
        The spin n at which R = 0, units sqrt(g/b): an array of the broadcast shape of
        ``Omega`` and ``theta`` (at least 1-d), NaN where no sign change of R(n) was found.

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``friction`` is not a FrictionLaw, ``mu`` is not a finite
        number >= 0 (when it is used), ``Omega`` or ``theta`` is invalid as for
        :func:`surface_n`, or ``Lambda`` is not finite.

    See Also
    --------
    phasekit.theory.surface_n
        the closed form (6.3) it is checked against

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.scenes.exact_boundary(pk.Spheroid(1.5), 0.1, [10.0, 12.0], [1.0, 1.0]).round(6)
    array([ 8.382922, 10.20507 ])
    """
    body = check_body(body)
    if friction is not None:
        check_instance("friction", friction, FrictionLaw, "Coulomb(0.1)")
    if mu is not None or friction is None:
        check_nonnegative("mu", mu)
    Om, Th = check_grid(body, Omega, theta)
    Lambda = check_finite("Lambda", Lambda)
    return exact_boundary_unchecked(body, mu, Om, Th, Lambda, friction=friction)


def exact_boundary_unchecked(body, mu, Omega, theta, Lambda=0.0, *, friction=None):
    from scipy.optimize import brentq

    model = Model(body, Coulomb(mu) if friction is None else friction)
    Rf = model.function("R_sliding")
    Om = np.atleast_1d(np.asarray(Omega, dtype=float))
    Th = np.atleast_1d(np.asarray(theta, dtype=float))
    Om, Th = np.broadcast_arrays(Om, Th)
    out = np.full(Om.shape, np.nan)
    for idx in np.ndindex(Om.shape):
        om, th = Om[idx], Th[idx]
        guess = surface_n_unchecked(body, om, th)
        f = lambda n: float(Rf(np.array([0.0, 0.0, om, Lambda, th, n]), model.p))  # noqa: E731
        span = 1e-3 + 0.2 * abs(guess) + abs(Lambda) * 10
        lo, hi = guess - span, guess + span
        for _ in range(40):
            if f(lo) * f(hi) < 0:
                break
            lo, hi = lo - span, hi + span
            span *= 2
        else:
            continue
        out[idx] = brentq(f, lo, hi, xtol=1e-14, rtol=1e-15)
    return out if out.ndim else float(out)
