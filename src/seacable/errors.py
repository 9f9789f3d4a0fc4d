"""The exception family of seacable: every error a user can meet derives from SeacableError."""


class SeacableError(Exception):
    """Base class of every seacable error."""


class CaseError(SeacableError, ValueError):
    """A case file or case object is invalid; the message names the field, value and fix."""


class OutputError(SeacableError, OSError):
    """The results cannot be written where asked (another run writes that file); the message
    names the file and what to do."""


class SimulationDiverged(SeacableError, RuntimeError):
    """The integration produced a non-finite or singular state.

    ``results`` holds what was computed before the failure (status ``diverged``).
    """

    def __init__(self, message: str, results=None):
        super().__init__(message)
        self.results = results


class SimulationInterrupted(SeacableError, KeyboardInterrupt):
    """The run was interrupted (Ctrl-C, SIGINT, or SIGTERM: ``signal``); ``results`` holds
    what was computed."""

    def __init__(self, message: str, results=None, signal: int = 2):
        super().__init__(message)
        self.results = results
        self.signal = signal


class HydroDBError(SeacableError, ValueError):
    """A hydrodynamic database that cannot be read or used (seacable.hydrodb): the message
    names the file, what is wrong (the section, the line) and the fix."""


class InputError(SeacableError, ValueError):
    """A file a command reads (results, a database, a table, a mesh) that cannot be used: the
    message names the file, what is wrong and the fix."""


MEMORY_BUDGET = 1e9  # [bytes] a computation estimated to hold more is refused unless allowed


def memory_check(what: str, needed: float, fix: str, allowed: bool = False) -> None:
    """Refuse (CaseError) a computation estimated to hold ``needed`` bytes, beyond
    MEMORY_BUDGET, unless ``allowed`` (the commands' ``--yes``): ``what`` says what grows and
    how, ``fix`` what to do."""
    if needed > MEMORY_BUDGET and not allowed:
        raise CaseError(
            f"{what}: about {needed / 1e9:.2g} GB of memory, more than the "
            f"{MEMORY_BUDGET / 1e9:g} GB budget; {fix}, or give --yes to compute it anyway"
        )
