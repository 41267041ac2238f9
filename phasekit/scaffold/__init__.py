"""The scaffold of a study script (``phasekit.scaffold``): its flags, output folder, resumable
stores, runs, figures, tables and progress bars (:class:`Study`), and the runner that turns
Ctrl-C and bad input into one line (:func:`run_study`). It sits above both
:mod:`phasekit.sweep` (the runs) and :mod:`phasekit.viz` (the figures). What single studies
share beyond this lives in ``phasekit.studies``, which is not API.

Examples
--------
>>> import phasekit as pk
>>> pk.scaffold.run_study(lambda argv: print("ran with", argv), ["--quick"])
ran with ['--quick']
"""

from .study import Study, run_study

__all__ = ["Study", "run_study"]
