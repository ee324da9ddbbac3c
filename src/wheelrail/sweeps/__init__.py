"""Parameter sweeps at scale: specification, executors, resumable stores.

=====================  =======================================================
:func:`sweep`          run a sweep (serial, local processes or Dask), return
                       an ``xarray.Dataset`` stored in Zarr or NetCDF
:class:`SweepSpec`     what to evaluate over which axes (or explicit points)
:func:`load_sweep`     read a ``[sweep]`` TOML case
:func:`open_sweep`     open a stored result
:data:`EVALUATORS`     what can be evaluated at each point (``"creep"``)
=====================  =======================================================
"""

from .evaluators import EVALUATORS, STATUS_CODES
from .executors import DaskExecutor, ProcessExecutor, SerialExecutor
from .run import SweepSummary, evaluate_chunk, sweep
from .spec import SweepSpec, load_sweep, sweep_from_dict
from .store import open_sweep

__all__ = ["sweep", "SweepSpec", "SweepSummary", "load_sweep", "sweep_from_dict", "open_sweep",
           "EVALUATORS", "STATUS_CODES", "SerialExecutor", "ProcessExecutor", "DaskExecutor",
           "evaluate_chunk"]
