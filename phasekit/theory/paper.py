"""The paper's printed cases as data: the starts (5.1) and (5.2) with their models.

Shimomura, Branicki & Moffatt, section 5, Coulomb friction mu = 0.1:

(5.1) oblate uniform spheroid a = 2/3, "perturbation applied along the vector in phase space
    with components (approximately)" U = 8e-7, V = 4e-6, Omega = C n0 / A, Lambda = 1e-5
    (printed "A = 10^-5", a misprint for Lambda), theta = 4e-6, n = n0. Fig. 3: n0 = 10
    rises without jumping, n0 = 10.5 jumps at t* ~ 91.
(5.2) prolate uniform spheroid a = 3/2: U = 7e-5, V = 2e-6, Omega = Omega0, Lambda = -1e-4
    (printed "A"), theta = pi/2 - 1e-3, n = 2e-2. Fig. 4: Omega0 = 10.2 rises without
    jumping, 10.5 jumps at t* ~ 111.

Every component is printed with one significant figure. (5.2) is the horizontal steady
precession plus 0.02 x the viscous unstable eigenvector (:func:`phasekit.steady.unstable_manifold_start`
with ``delta=0.02``) to that digit, but the two starts are different states and their runs
differ: see :func:`paper_start` and ``examples/paper_start_rounding.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._runtime.errors import ParameterError
from .._runtime.validate import check_finite
from ..bodies.spheroid import Spheroid
from ..core.model import Model
from ..core.starts import to_chart
from ..friction.laws import Coulomb, FrictionLaw

__all__ = ["PaperCase", "PAPER_CASES", "paper_start"]


@dataclass(frozen=True)
class PaperCase:
    """A printed start: the body, the family parameter it takes, and the figure's values.

    Attributes
    ----------
    label : {"5.1", "5.2"}
        The equation number of the start.
    a : float
        Aspect ratio of the uniform spheroid (2/3 for (5.1), 3/2 for (5.2)).
    parameter : {"n0", "omega0"}
        The family parameter the start takes: the spin n0 (5.1) or the precession rate
        Omega0 (5.2).
    figure : str
        The paper's figure of the case ("Fig. 3", "Fig. 4").
    no_jump : float
        The value printed as rising without a jump.
    jump : float
        The value printed as jumping.
    t_jump : float
        The printed (approximate) jump time of the jumping value, units sqrt(b/g).

    Examples
    --------
    >>> import phasekit as pk
    >>> case = pk.theory.PAPER_CASES['5.2']
    >>> isinstance(case, pk.theory.PaperCase), case.figure, case.a, case.t_jump
    (True, 'Fig. 4', 1.5, 111.0)
    """

    label: str
    a: float
    parameter: str  # "n0" or "omega0"
    figure: str
    no_jump: float  # the value printed as rising without a jump
    jump: float  # the value printed as jumping
    t_jump: float  # the printed (approximate) jump time of the jumping value

    def state(self, value: float) -> np.ndarray:
        """(U, V, Omega, Lambda, theta, n) for the family parameter ``value``.

        Parameters
        ----------
        value : float
            The family parameter (n0 for (5.1), Omega0 for (5.2)), units sqrt(g/b): finite
            and nonzero.

        Returns
        -------
        numpy.ndarray
            Shape (6,): the printed start in the paper's variables.

        Raises
        ------
        ParameterError
            If ``value`` is 0 or not finite.
        """
        value = check_finite("value", value, nonzero=True)
        body = Spheroid(self.a)
        if self.label == "5.1":
            return np.array([8e-7, 4e-6, body.C * value / body.A, 1e-5, 4e-6, value])
        return np.array([7e-5, 2e-6, value, -1e-4, np.pi / 2 - 1e-3, 2e-2])


PAPER_CASES = {
    "5.1": PaperCase("5.1", 2.0 / 3.0, "n0", "Fig. 3", 10.0, 10.5, 91.0),
    "5.2": PaperCase("5.2", 1.5, "omega0", "Fig. 4", 10.2, 10.5, 111.0),
}


#: the keywords of :func:`paper_start`
KEYWORDS = ("n0", "omega0", "friction")


def paper_start(label: str, *, n0: float | None = None, omega0: float | None = None,
                friction: FrictionLaw | None = None, **unknown) -> tuple[Model, np.ndarray]:
    """The printed start (5.1) or (5.2) with its model, digit for digit.

    Parameters
    ----------
    label : {"5.1", "5.2"}
        The equation number (``"(5.2)"`` is accepted too).
    n0 : float, optional
        (5.1) only: the spin (default 10.5, printed as jumping); Omega = C n0 / A.
    omega0 : float, optional
        (5.2) only: the precession rate (default 10.5, printed as jumping).
    friction : FrictionLaw, optional
        Default: exact Coulomb friction with mu = 0.1 (the paper's law).
    **unknown
        None: any other keyword raises :class:`ParameterError` naming it.

    Returns
    -------
    (Model, ndarray)
        The model (uniform spheroid a = 2/3 in the vector chart for (5.1), which starts 4e-6
        from the vertical; a = 3/2 in the Euler chart for (5.2)) and the start in its chart.

    Notes
    -----
    Which start each number of the README uses:

    * "(5.2) sticks at t = 0.011 and never rises" (exact Coulomb) and "jumps at 42.25 / 52.34 /
      156.59 for eps = 1e-2 / 1e-3 / 1e-4" (``RegularisedCoulomb(0.1, eps)``): this start,
      ``paper_start("5.2", friction=...)``.
    * "(5.1) sticks at t = 1.1e-4": ``paper_start("5.1")``.
    * The *literal* threshold definition (10.22 at a = 1.5 with eps = 1e-3) and
      "64.16 (sticking at 0.022)": the unrounded eigenvector start
      ``unstable_manifold_start(..., delta=0.01 or 0.02)``, not this one.

    The eigenvector start at delta = 0.02 rounds to (5.2) component by component, but its
    theta offset is 1.15e-3 (printed 1e-3), and rounding that component alone moves the jump
    (eps = 1e-3) from t = 64.16 to 52.34; rounding U, V or Lambda moves it by < 0.02, n by
    0.9. What sets t_jump is the transverse slip of the contact point at the start, u_Y: the
    residue of terms of size 0.01-0.02 that nearly cancel, -0.0072 for the eigenvector and
    -0.0036 for (5.2) (both below 10 eps: the regularised law starts them stuck; exact
    Coulomb sticks at t = 0.022 and 0.011). t_jump is close to one curve of u_Y, peaked at
    u_Y ~ -0.007, so inside the rounding box t_jump spans 46.8-61.7 across theta's interval,
    46.8-67.2 across n's, and 44.9-67.8 over a 15 x 15 grid of (theta, n) (one of 225 runs
    does not jump by t = 300); the eigenvector start sits on the peak, (5.2) on its flank.
    The printed digits fix t_jump only to about +-10 (``examples/paper_start_rounding.py``).

    Examples
    --------
    >>> import phasekit as pk
    >>> model, x0 = pk.paper_start("5.2")
    >>> model
    Model(Spheroid(a=1.5), coulomb(mu=0.1), chart='euler')
    """
    if unknown:
        name = sorted(unknown)[0]
        raise ParameterError(name, f"is not a keyword of paper_start (valid keywords: {', '.join(KEYWORDS)})",
                             unknown[name])
    given = label
    if isinstance(label, str) and label.startswith("(") and label.endswith(")"):
        label = label[1:-1]
    if not isinstance(label, str) or label not in PAPER_CASES:
        raise ParameterError("label", f"must be one of {', '.join(PAPER_CASES)} (or in parentheses, \"(5.2)\")", given)
    case = PAPER_CASES[label]
    other = "omega0" if case.parameter == "n0" else "n0"
    if (omega0 if other == "omega0" else n0) is not None:
        raise ParameterError(other, f"does not apply to ({label}), which takes {case.parameter}", show_value=False)
    value = n0 if case.parameter == "n0" else omega0
    value = case.jump if value is None else check_finite(case.parameter, value, nonzero=True)
    if friction is not None and not isinstance(friction, FrictionLaw):
        raise ParameterError("friction", "must be a phasekit FrictionLaw such as Coulomb(0.1)", friction)
    law = Coulomb(0.1) if friction is None else friction
    chart = "vector" if label == "5.1" else "euler"
    return Model(Spheroid(case.a), law, chart), to_chart(chart, case.state(value))
