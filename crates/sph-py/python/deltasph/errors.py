"""Exceptions raised by deltasph.

Bad configuration values raise :class:`ConfigError` (a ``ValueError``); unknown or
missing keys raise :class:`ConfigKeyError`, which is also a ``KeyError``. The first
line of each message names the key, the value and what was expected, exactly as
the command line reports it. A run that blows up raises :class:`InstabilityError`.
"""


class ConfigError(ValueError):
    """A case the solver cannot accept: a value out of range, a wrong type, bad geometry."""


class ConfigKeyError(ConfigError, KeyError):
    """A key the case schema does not know, or a required key that is missing."""

    # KeyError would print the message in quotes; keep it readable.
    __str__ = ValueError.__str__


class InstabilityError(RuntimeError):
    """The run went unstable (non-finite values or runaway density).

    The simulation keeps the state at which it stopped, so it can still be written
    with ``Simulation.write_snapshot`` for inspection.

    Attributes:
        time: simulated time at which the guard fired [s].
        step: step count at that moment.
        particle: id of the offending particle (its row in the state arrays).
        position: that particle's position, as text.
        reason: what the guard saw (e.g. ``"density variation 0.35 > 0.2"``).
    """

    def __init__(self, message: str, time: float, step: int, particle: int, position: str,
                 reason: str) -> None:
        super().__init__(message)
        self.time = time
        self.step = step
        self.particle = particle
        self.position = position
        self.reason = reason
