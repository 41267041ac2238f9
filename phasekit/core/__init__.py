"""The hybrid system and its integration (``phasekit.core``): the two charts of the state, the
:class:`Model` (CasADi fields per mode), the modes, events and resets declared as data, the
engines (:mod:`phasekit.core.engines`), :func:`simulate` and its :class:`Trajectory`, the
starts, the pose of the body in space and real units.

Examples
--------
>>> import numpy as np, phasekit as pk
>>> body = pk.Spheroid(1.5)
>>> traj = pk.core.simulate(pk.core.Model(body, pk.Coulomb(0.1)), pk.core.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
>>> traj.status.value
'jumped'
"""

from .approximations import Approximation
from .batch import simulate_batch
from .charts import PAPER_NAMES, choose_chart
from .hybrid import Event, Mode
from .impact import impact
from .model import Model
from .observables import OBSERVABLES
from .options import SolverOptions
from .pose import Pose
from .records import EventRecord, Flight, Segment
from .sections import poincare
from .settle import Settle
from .simulate import simulate
from .sizes import egg_of_size
from .starts import gyroscopic_start, paper_start, to_chart, to_paper, vertical_spin_start
from .trajectory import Trajectory
from .units import Scale
from .verify import RunCheck

__all__ = [
    "Model", "OBSERVABLES", "Mode", "Event", "SolverOptions", "Settle",
    "simulate", "simulate_batch", "Trajectory", "Segment", "EventRecord", "Flight", "poincare",
    "gyroscopic_start", "vertical_spin_start", "paper_start", "to_chart", "to_paper", "choose_chart", "PAPER_NAMES",
    "impact", "Pose", "Scale", "egg_of_size", "RunCheck", "Approximation",
]
