"""The case file's ``sweep:`` block: the load cases ``seacable sweep`` runs from one case (its
dimensions, seeds and table of load cases; seacable.sweep runs them)."""

import math
import re
from typing import Annotated, Any

from pydantic import Field, field_validator, model_validator

from seacable.case.base import NonNeg, Pos, _Model

# the weather's short paths, as seacable continuation names them (seacable.sweep sets them):
# the uniform current's and the constant wind's speed and direction, the waves scaled to a
# significant height and turned to a mean direction
WEATHER = ("current.speed", "current.towards_deg", "wind.speed", "wind.towards_deg",
           "waves.height", "waves.towards_deg")  # fmt: skip
RANGE = re.compile(r"^\s*([^:]+):([^:]+):([^:]+)\s*$")  # first:stop:step (stop excluded)


def range_values(text: str, where: str) -> list[float]:
    """The numbers of ``first:stop:step`` (stop excluded, as Python's ranges), e.g. 0:360:45
    gives 0, 45, ..., 315; ValueError naming ``where`` when it is not such a range."""
    found = RANGE.match(text)
    try:
        if found is None:
            raise ValueError
        first, stop, step = (float(v) for v in found.groups())
    except ValueError:
        raise ValueError(f"{where} '{text}': write first:stop:step (stop excluded, e.g. "
                         "0:360:45) or a list of values ([2, 4, 6])") from None  # fmt: skip
    if not all(math.isfinite(v) for v in (first, stop, step)):
        raise ValueError(f"{where} '{text}': give finite numbers (first:stop:step, stop "
                         "excluded)")  # fmt: skip
    if not step > 0.0 or not stop > first:
        raise ValueError(f"{where} '{text}': the step must be positive and stop beyond first "
                         "(first:stop:step, stop excluded)")  # fmt: skip
    count = int((stop - first) / step - 1e-9) + 1
    if count > 100_000:
        raise ValueError(f"{where} '{text}': {count} values; a sweep takes at most 100,000")
    return [first + k * step for k in range(count)]


class Variation(_Model):
    """One case key a sweep varies: a dimension of the sweep's summary, or a key that moves
    with another dimension (``along``)."""

    path: str = Field(min_length=1)
    """The key, written as ``--set`` writes it: ``environment.waves[0].significant_height``,
    ``bodies.buoy.mass``, ``lines.line_1.sections[0].length`` (a list's item by its index or
    its ``name``); or the weather as ``seacable continuation`` names it: ``waves.height`` [m]
    (every wave scaled to that significant height), ``waves.towards_deg`` (every wave turned
    to that mean direction), ``current.speed`` [m/s] and ``current.towards_deg`` (a uniform
    current), ``wind.speed`` [m/s] and ``wind.towards_deg`` (a constant wind)."""
    values: list[Any] | str
    """The values the key takes, in order: a list (``[2, 4, 6]``, words or lists allowed) or
    ``first:stop:step`` (stop excluded: ``0:360:45`` is 0, 45, ..., 315)."""
    name: Annotated[str, Field(pattern=r"^[A-Za-z_][A-Za-z0-9_]*$")] | None = None
    """The dimension's name in the summary. Omitted: the path's last key
    (``significant_height``)."""
    along: str | None = None
    """The name of another variation this one moves with, value by value (a zipped list: the
    same number of values; no dimension of its own). Omitted: a dimension of its own, crossed
    with the others."""
    probabilities: list[NonNeg] | None = None
    """[-] Each value's share of the time (a scatter diagram's marginal), one per value; the
    sweep's load cases then carry the product of their dimensions' shares (a probability for
    the fatigue damage summed over the sweep)."""

    @field_validator("values")
    @classmethod
    def _some(cls, values):
        found = range_values(values, "values") if isinstance(values, str) else values
        if not found:
            raise ValueError("give at least one value")
        return values

    def listed(self) -> list[Any]:
        """The values, a range written out."""
        if isinstance(self.values, str):
            return range_values(self.values, f"sweep.vary '{self.path}' values")
        return list(self.values)

    @property
    def label(self) -> str:
        """The dimension's name: ``name``, else the path's last key (``position[2]`` as
        ``position_2``; a weather path whole: ``waves_height``)."""
        if self.name:
            return self.name
        if self.path in WEATHER:
            return self.path.replace(".", "_")
        last = self.path.split(".")[-1]
        return re.sub(r"\W+", "_", last).strip("_") or "value"

    @model_validator(mode="after")
    def _shares(self):
        if self.probabilities is not None and len(self.probabilities) != len(self.listed()):
            raise ValueError(f"{len(self.probabilities)} probabilities for "
                             f"{len(self.listed())} values; give one per value")  # fmt: skip
        return self


class Sweep(_Model):
    """Load cases run from this case by ``seacable sweep``: each key of ``vary`` a dimension
    (crossed with the others: every combination runs), ``seeds`` irregular seas of each, and
    the rows of a table of load cases. ``seacable run`` runs the case as written, without
    them."""

    vary: list[Variation] = []
    """The keys varied: each a dimension of the summary, or moving along another one."""
    seeds: Annotated[int, Field(ge=1, le=10_000)] = 1
    """[-] Sea realisations of each load case: every irregular wave spectrum's ``seed`` plus 0,
    1, ..., seeds - 1 (a dimension ``seed``)."""
    load_cases: str | None = None
    """A CSV table of load cases (relative to the case file): a header of keys written as
    ``path`` is, optionally ``name`` (the row's label) and ``probability`` (its share of the
    time); one row per load case, a dimension ``load_case`` crossed with ``vary``."""
    storm: Pos = 10800.0
    """[s] Duration of the storm whose most probable largest tension the summary gives
    (Rayleigh's law of the peaks, seacable.stats), 3 hours as mooring design checks take it."""

    @model_validator(mode="after")
    def _dimensions(self):
        names = [v.label for v in self.vary]
        own = [v.label for v in self.vary if v.along is None]
        for k, variation in enumerate(self.vary):
            if names.count(variation.label) > 1:
                raise ValueError(f"vary[{k}]: the name '{variation.label}' is taken twice; "
                                 "give each variation its own 'name'")  # fmt: skip
            if variation.label in ("seed", "load_case", "line", "body", "dof"):
                raise ValueError(f"vary[{k}]: the name '{variation.label}' is the summary's "
                                 "own dimension; give the variation another 'name'")  # fmt: skip
            if variation.along is None:
                continue
            if variation.along not in own:
                raise ValueError(
                    f"vary[{k}].along: '{variation.along}' is not the name of "
                    f"a variation with a dimension of its own ({', '.join(own)})"
                )
            leader = self.vary[names.index(variation.along)]
            if len(leader.listed()) != len(variation.listed()):
                raise ValueError(f"vary[{k}]: {len(variation.listed())} values along "
                                 f"'{variation.along}', which has {len(leader.listed())}; "
                                 "give as many")  # fmt: skip
            if variation.probabilities is not None:
                raise ValueError(f"vary[{k}].probabilities: a variation along another takes "
                                 f"its shares; give them to '{variation.along}'")  # fmt: skip
        paths = [v.path for v in self.vary]
        for path in paths:
            if paths.count(path) > 1:
                raise ValueError(f"vary: the key '{path}' is varied twice; vary it once")
        return self
