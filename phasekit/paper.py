"""The paper's printed cases as data: the starts (5.1) and (5.2) with their models.

Shimomura, Branicki & Moffatt, section 5: Coulomb friction mu = 0.1;
(5.1) oblate uniform spheroid a = 2/3, "perturbation applied along the vector in phase space
with components (approximately)" U = 8e-7, V = 4e-6, Omega = C n0 / A, Lambda = 1e-5
(printed "A = 10^-5", a misprint for Lambda), theta = 4e-6, n0 (Fig. 3: n0 = 10 rises
without jumping, 10.5 jumps at t* ~ 91);
(5.2) prolate uniform spheroid a = 3/2: U = 7e-5, V = 2e-6, Omega0, Lambda = -1e-4
(printed "A"), theta = pi/2 - 1e-3, n = 2e-2 (Fig. 4: Omega0 = 10.2 rises without jumping,
10.5 jumps at t* ~ 111).
The printed components have one significant figure; see the README's reproduction table
for what these starts do under exact and regularised Coulomb friction.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .body import Spheroid
from .errors import ParameterError
from .friction import Coulomb, FrictionLaw
from .model import Model
from .starts import to_chart

__all__ = ["PaperCase", "PAPER_CASES", "paper_start"]


@dataclass(frozen=True)
class PaperCase:
    """A printed start: the body, the family parameter it takes, and the figure's values."""

    label: str
    a: float
    parameter: str  # "n0" or "omega0"
    figure: str
    no_jump: float  # the value printed as rising without a jump
    jump: float  # the value printed as jumping
    t_jump: float  # the printed (approximate) jump time of the jumping value

    def state(self, value: float) -> np.ndarray:
        """(U, V, Omega, Lambda, theta, n) for the family parameter ``value``."""
        body = Spheroid(self.a)
        if self.label == "5.1":
            return np.array([8e-7, 4e-6, body.C * value / body.A, 1e-5, 4e-6, value])
        return np.array([7e-5, 2e-6, value, -1e-4, np.pi / 2 - 1e-3, 2e-2])


PAPER_CASES = {
    "5.1": PaperCase("5.1", 2.0 / 3.0, "n0", "Fig. 3", 10.0, 10.5, 91.0),
    "5.2": PaperCase("5.2", 1.5, "omega0", "Fig. 4", 10.2, 10.5, 111.0),
}


def paper_start(label: str, *, n0: float | None = None, omega0: float | None = None,
                friction: FrictionLaw | None = None) -> tuple[Model, np.ndarray]:
    """The printed start (5.1) or (5.2) with its model: (model, x0).

    ``n0`` ((5.1)) or ``omega0`` ((5.2)) defaults to the value printed as jumping (10.5);
    ``friction`` defaults to exact Coulomb with mu = 0.1. (5.1) starts 4e-6 from the
    vertical, so its model is in the vector chart; (5.2) in the Euler chart.
    """
    if label not in PAPER_CASES:
        raise ParameterError("label", f"must be one of {', '.join(PAPER_CASES)}", label)
    case = PAPER_CASES[label]
    other = "omega0" if case.parameter == "n0" else "n0"
    if (omega0 if other == "omega0" else n0) is not None:
        raise ParameterError(other, f"does not apply to ({label}), which takes {case.parameter}", show_value=False)
    value = n0 if case.parameter == "n0" else omega0
    value = case.jump if value is None else value
    law = Coulomb(0.1) if friction is None else friction
    chart = "vector" if label == "5.1" else "euler"
    return Model(Spheroid(case.a), law, chart), to_chart(chart, case.state(value))
