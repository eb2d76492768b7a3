"""Exceptions raised by vehdyn.

Every error names the parameter, signal or file position at fault and the value it found, so that
a bad input is reported where it enters and never surfaces later as a NaN inside a solver.
"""

from __future__ import annotations

__all__ = ["VehdynError", "ParameterError", "SimulationError", "TirFileError", "VehdynWarning"]


class VehdynError(Exception):
    """Base class of every exception raised on purpose by vehdyn."""


class ParameterError(VehdynError, ValueError):
    """A parameter is missing, unknown, of the wrong type, non-finite or out of range.

    Raise it through the shared checks of :mod:`vehdyn.params.checks` where one fits, so that
    every message reads alike.

    Parameters
    ----------
    message : str
        What is wrong; it names the parameter and the value.
    key : str, optional
        Dotted path of the offending parameter (``"suspension.front_spring_rate"``).
    value : object, optional
        The offending value.

    Examples
    --------
    >>> import vehdyn
    >>> try:
    ...     vehdyn.load_vehicle("sedan").replace(mass__mass=-1.0)
    ... except vehdyn.ParameterError as error:
    ...     print(error.key, error.value)
    mass.mass -1.0
    """

    def __init__(self, message: str, *, key: str | None = None, value: object = None):
        super().__init__(message)
        self.key = key
        self.value = value


class SimulationError(VehdynError, RuntimeError):
    """An integration failed or produced a non-finite state.

    Parameters
    ----------
    message : str
        What failed, with the solver's own message where there is one.
    time : float, optional
        Simulation time [s] at which the failure was detected.
    signal : str, optional
        Name of the state at fault (non-finite, or out of the model's domain), where there is one.

    Attributes
    ----------
    time : float or None
        Simulation time [s] at which the failure was detected.
    signal : str or None
        Name of the state that became non-finite, where one did.
    """

    def __init__(self, message: str, *, time: float | None = None, signal: str | None = None):
        super().__init__(message)
        self.time = time
        self.signal = signal


class TirFileError(VehdynError, ValueError):
    """A ``.tir`` tire property file cannot be read.

    Parameters
    ----------
    message : str
        What is wrong: the key, its value and the rule it breaks.
    path : str, optional
        The file; prefixed to the message with the line.
    line : int, optional
        1-based line number of the offending line.

    Attributes
    ----------
    path : str or None
        The file.
    line : int or None
        1-based line number of the offending line.
    """

    def __init__(self, message: str, *, path: str | None = None, line: int | None = None):
        where = ""
        if path is not None:
            where = f"{path}"
            if line is not None:
                where += f", line {line}"
            where += ": "
        super().__init__(where + message)
        self.path = path
        self.line = line


class VehdynWarning(UserWarning):
    """Something vehdyn did on the user's behalf that may change a result.

    Raised as a warning, not an error: e.g. a ``.tir`` file missing whole sections whose
    coefficients take MFeval's defaults, or a solver choice that will be slow. Turn it into an
    error with ``warnings.simplefilter("error", vehdyn.VehdynWarning)``.
    """
