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
differ: see :func:`phasekit.paper_start` and ``examples/paper_start_rounding.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._runtime.validate import check_finite
from ..bodies.spheroid import Spheroid


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
    >>> isinstance(case, pk.theory.paper.PaperCase), case.figure, case.a, case.t_jump
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
