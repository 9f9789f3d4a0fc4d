"""The kinds of value the command line's options take, each checked as a case key is: a number
that must be finite and within its bounds, a count within its own, a list of numbers. Every
refusal is click's ``BadParameter``, which the command line's error boundary (``seacable.cli``)
writes as one line naming the option, the value, what is allowed and an example."""

import math

import click


class Number(click.ParamType):
    """A finite real number (``inf`` too where ``infinite`` says what it means) in bounds:
    above ``low`` (or at least, ``low_open`` False), at most ``high``; ``example``: a value the
    message suggests."""

    name = "number"

    def __init__(self, low: float | None = None, high: float | None = None,
                 low_open: bool = False, infinite: str | None = None,
                 example: str = "1.5"):  # fmt: skip
        self.low, self.high, self.low_open = low, high, low_open
        self.infinite, self.example = infinite, example

    def allowed(self) -> str:
        parts = []
        if self.low is not None:
            parts.append(f"{'above' if self.low_open else 'at least'} {self.low:g}")
        if self.high is not None:
            parts.append(f"at most {self.high:g}")
        finite = "a finite number" if self.infinite is None else "a number"
        tail = "" if self.infinite is None else f", or inf ({self.infinite})"
        return f"{finite}{' ' + ' and '.join(parts) if parts else ''}{tail}"

    def convert(self, value, param, ctx) -> float:
        if isinstance(value, bool):
            self.fail(f"{value!r}: give {self.allowed()}, e.g. {self.example}", param, ctx)
        try:
            number = float(value)
        except (TypeError, ValueError, OverflowError):
            self.fail(f"'{value}' is not a number; give {self.allowed()}, e.g. {self.example}",
                      param, ctx)  # fmt: skip
        if math.isnan(number) or (math.isinf(number) and (self.infinite is None or number < 0)):
            self.fail(f"{value}: give {self.allowed()}, e.g. {self.example}", param, ctx)
        below = self.low is not None and (
            number < self.low or (self.low_open and number == self.low)
        )
        if below or (self.high is not None and number > self.high):
            self.fail(f"{number:g}: give {self.allowed()}, e.g. {self.example}", param, ctx)
        return number


def count(low: int, high: int) -> click.IntRange:
    """A whole number from ``low`` to ``high``."""
    return click.IntRange(min=low, max=high)


ANGLE = Number(example="45")
SPEED = Number(low=0.0, example="1.2")
POSITIVE = Number(low=0.0, low_open=True)
NONNEGATIVE = Number(low=0.0)
DURATION = Number(low=0.0, low_open=True, example="600")
ANY = Number(example="0")


def numbers(text: str, option: str, low: float | None = None) -> list[float]:
    """The finite numbers of a comma-separated list (at least ``low`` each, when given), or
    click's BadParameter naming ``option``."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if not values or not all(math.isfinite(v) for v in values):
        raise click.BadParameter(
            f"'{text}': give finite numbers separated by commas, e.g. 0,90,180",
            param_hint=f"'{option}'",
        )
    if low is not None and min(values) < low:
        raise click.BadParameter(f"'{text}': every value at least {low:g}",
                                 param_hint=f"'{option}'")  # fmt: skip
    return values
