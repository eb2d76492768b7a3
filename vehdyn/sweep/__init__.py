"""Parameter sweeps, Monte Carlo and sensitivity (DESIGN §7).

:func:`sweep` runs every variant of a :class:`~vehdyn.Scene` or of a function of named parameters
(a full-factorial ``grid`` and/or ``samples`` drawn from distributions), reduces each run to named
metrics (:mod:`vehdyn.sweep.metrics`) and returns one row per variant; an invalid variant keeps
its row with the message in ``error``. Engines (:mod:`vehdyn.sweep.engines`): in-process, a
process pool or any :class:`concurrent.futures.Executor`, or a Dask cluster. ``out=`` writes
Parquet chunks atomically and ``resume=True`` finishes an interrupted sweep
(:mod:`vehdyn.sweep.storage`). :func:`sensitivity` gives Sobol' or Morris indices through SALib.

Pointing a study at a cluster changes only the executor::

    from dask.distributed import Client
    client = Client("tcp://scheduler:8786")      # or dask_jobqueue.SLURMCluster(...).get_client()
    table = vehdyn.sweep(scene, samples=..., n=100_000, executor=client, out="mc.parquet")
"""

from vehdyn.sweep.api import sweep, variants
from vehdyn.sweep.metrics import Run, metric_names, register_metric
from vehdyn.sweep.sensitivity import plot_sensitivity, sensitivity  # binds the function over the submodule's name
from vehdyn.sweep.targets import vectorized

__all__ = ["sweep", "variants", "vectorized", "register_metric", "metric_names", "Run", "sensitivity",
           "plot_sensitivity"]


class _CallableModule(__import__("types").ModuleType):
    """``vehdyn.sweep`` is this package and the function: ``vehdyn.sweep(scene, grid=...)`` calls
    :func:`vehdyn.sweep.api.sweep` (importing a submodule rebinds the package attribute, so a
    function of the same name could not stay there)."""

    def __call__(self, *args, **kwargs):
        return sweep(*args, **kwargs)


__import__("sys").modules[__name__].__class__ = _CallableModule
