"""Driver models: controllers that steer a vehicle model along a path.

:class:`PreviewDriver` (pure pursuit with a lag, optional speed control), :class:`CrossoverDriver`
(McRuer) and :class:`OptimalPreviewDriver` (MacAdam 1981) are controller :class:`~vehdyn.Model`
objects with named parameters (gain, preview time, delay as a Padé approximant, lag): their
inputs are the plant signals they read, their outputs the plant inputs they command, and
``driver.close(plant)`` puts them in the loop, a :class:`vehdyn.interconnect.ClosedLoop` that
simulates, linearizes, nests (a driver around ESC around ABS around the car) and compiles with
the plant. :func:`driver_loop`, :func:`driver_loop_response`, :func:`driver_loop_margins`: the
driver-vehicle loop analysed with python-control.

The lane-change procedures that use them are in :mod:`vehdyn.procedures.iso3888`.
"""

from vehdyn.driver.base import preview_offsets
from vehdyn.driver.crossover import CrossoverDriver
from vehdyn.driver.loop_analysis import driver_loop, driver_loop_margins, driver_loop_response
from vehdyn.driver.optimal_preview import OptimalPreviewDriver, preview_gains
from vehdyn.driver.preview import PreviewDriver

__all__ = ["PreviewDriver", "CrossoverDriver", "OptimalPreviewDriver", "preview_gains", "preview_offsets",
           "driver_loop", "driver_loop_response", "driver_loop_margins"]
