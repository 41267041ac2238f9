"""The Taylor engine on heyoka's SIMD batch mode (:class:`TaylorBatchEngine`, used by
:func:`phasekit.core.simulate_batch`): ``lanes`` starts at once, each propagated to a time or its own
first event, built by the same code as the scalar :class:`~phasekit.core.engines.taylor.TaylorEngine`.
"""

from __future__ import annotations

from functools import partial

from ..hybrid import CompiledFlow
from .cache import compiled
from .protocol import End
from .taylor_build import build_taylor, load_heyoka, taylor_end


class TaylorBatchEngine:
    """The Taylor integrator on heyoka's batch mode: ``lanes`` starts of one flow (different states,
    parameters and times) propagated at once, each to its time limit or its own first event.

    Built by the same code as :class:`~phasekit.core.engines.taylor.TaylorEngine` (same expressions,
    tolerance, compact mode and event cooldown); segments it integrates record the name "taylor",
    as they are the same steps.

    Parameters
    ----------
    rtol : float
        heyoka's tolerance, as for the scalar engine.
    lanes : int
        Starts per integrator (the SIMD batch size).

    Examples
    --------
    >>> import phasekit as pk
    >>> e = pk.core.engines.batch.TaylorBatchEngine(1e-9, lanes=8)
    >>> e.name, e.pointwise, e.lanes
    ('taylor', False, 8)
    """

    name = "taylor"
    pointwise = False

    def __init__(self, rtol: float, lanes: int):
        self.rtol, self.lanes = float(rtol), int(lanes)

    def integrator(self, flow: CompiledFlow, n_params: int):
        """(heyoka batch integrator, number of parameters), compiled once.

        Parameters
        ----------
        flow : CompiledFlow
            The flow integrated.
        n_params : int
            The number of model parameters.

        Returns
        -------
        tuple
            (batch integrator, number of parameters).
        """
        return compiled(("batch", flow.signature, self.rtol, self.lanes),
                        partial(build_taylor, flow, n_params, self.rtol, self.lanes), disk="taylor-batch")

    def propagate(self, ta, limits, max_steps: int) -> list[tuple[End | None, int | None, int, str]]:
        """One call of heyoka's propagate on every lane (to ``limits``, at most ``max_steps``
        steps): per lane (End or None while under way, event index, steps taken, heyoka's
        outcome in words). A terminal event in one lane stops the call for every lane; the
        others end their current step and are under way (heyoka's batch-mode documentation,
        and measured here).

        Parameters
        ----------
        ta : heyoka.taylor_adaptive_batch
            The batch integrator, with the lanes' states, parameters and times set.
        limits : array_like
            The time limit of each lane.
        max_steps : int
            Steps allowed in this call.

        Returns
        -------
        list of tuple
            Per lane: (End or None, event index or None, steps taken, heyoka's outcome in words).
        """
        hy = load_heyoka()
        ta.propagate_until(limits, max_steps=max_steps)
        out = []
        for k, res in enumerate(ta.propagate_res):
            end, event = taylor_end(hy, res[0])
            if end is None and float(ta.time[k]) >= limits[k]:
                end = End.TIME  # the call ended on the lane's last step
            out.append((end, event, int(res[3]), str(res[0])))
        return out
