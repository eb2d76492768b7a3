"""Parameter sweeps, Monte Carlo and sensitivity (DESIGN §7).

:func:`run` runs every variant of a :class:`~vehdyn.Scene` or of a function of named parameters
(a full-factorial ``grid`` and/or ``samples`` drawn from distributions), reduces each run to named
metrics (:mod:`vehdyn.sweep.metrics`: the registry, the :class:`~vehdyn.sweep.metrics.Run` a
metric reduces) and returns one row per variant; an invalid variant keeps
its row with the message in ``error``. Engines (:mod:`vehdyn.sweep.engines`): in-process, a
process pool or any :class:`concurrent.futures.Executor`, or a Dask cluster. ``out=`` writes
Parquet chunks atomically beside a manifest of what produced them, and ``resume=True`` finishes
an interrupted sweep - that sweep's, never another's (:mod:`vehdyn.sweep.storage`,
:mod:`vehdyn.sweep.manifest`). :func:`sensitivity` gives Sobol' or Morris indices through SALib
(:mod:`vehdyn.sweep.indices`).

Pointing a study at a cluster changes only the executor::

    from dask.distributed import Client
    client = Client("tcp://scheduler:8786")      # or dask_jobqueue.SLURMCluster(...).get_client()
    table = vehdyn.sweep.run(scene, samples=..., n=100_000, executor=client, out="mc.parquet")
"""

from vehdyn.sweep.api import run, variants
from vehdyn.sweep.indices import plot_sensitivity, sensitivity
from vehdyn.sweep.metrics import metric_names, register_metric
from vehdyn.sweep.targets import vectorized

__all__ = ["run", "variants", "vectorized", "register_metric", "metric_names", "sensitivity", "plot_sensitivity"]
