"""
Method tables
=============

Every family of named methods (normalisations, extrapolations, locus
boundaries, design objectives, emitters, samplers, …) is a mapping from the
name a user types to the function that does it (as colour-science's
``CCT_TO_XY_METHODS``), with one dispatcher that checks the name
(:func:`validate_method`, which words the error the same way everywhere) and
calls the function: nothing else compares a value with a method's name. A
method's one-line description is its docstring's first paragraph
(:func:`describe`), from which the command line words its choices' help. :func:`parse_range`
reads the ``START:END:STEP`` ranges (nm) of grids and sensor positions, and
:func:`range_steps` checks every such range (wavelength grids, sensor
positions, Stage 1's candidate temperatures) in one place.

-   :func:`validate_method`: a name of a method table, or a one-line error.
-   :func:`method_of`: the method of a name, checked (what a dispatcher calls).
-   :func:`describe`: a method's one-line description.
-   :func:`takes`: whether a method takes an option (what it does not take, it refuses).
-   :func:`parse_range`: ``START:END:STEP`` as three finite numbers.
-   :func:`range_steps`, :class:`RangeWords`, :class:`Steps`: the steps of a
    range, END included, or a refusal worded for its kind of range.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import NamedTuple

from .errors import SkinrenderError

__all__ = ["validate_method", "method_of", "describe", "takes", "parse_range", "Steps", "RangeWords", "range_steps"]


def _argument(what: str) -> str | None:
    """A refusal's role from how it names the thing at fault: ``what`` where it is an argument's name
    (``extrapolation``), ``None`` for words or a flag (``--grid``)."""
    return what if what.isidentifier() else None


def validate_method(name: object, methods: Mapping[str, object], what: str, role: str | None = None) -> str:
    """
    ``name`` if it is a key of ``methods``, else a :class:`SkinrenderError`
    naming ``what`` and listing the choices (its ``role``: ``role``, the
    argument at fault, for the command line to name its flag; by default
    ``what`` where it is an argument's name, ``extrapolation``).

    Examples
    --------
    >>> validate_method("zero", {"refuse": 0, "zero": 1}, "extrapolation")
    'zero'
    >>> validate_method("one", {"refuse": 0, "zero": 1}, "extrapolation")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: extrapolation must be one of refuse, zero, got 'one'
    """

    if not isinstance(name, str) or name not in methods:
        role = role if role is not None else _argument(what)
        raise SkinrenderError(f"{what} must be one of {', '.join(methods)}, got {name!r}", role=role)
    return name


def method_of(name: object, methods: Mapping[str, Callable], what: str, role: str | None = None) -> Callable:
    """
    The method ``methods[name]``, ``name`` checked by :func:`validate_method` first: what a family's dispatcher
    calls.

    Examples
    --------
    >>> method_of("twice", {"twice": lambda x: 2 * x}, "rule")(4)
    8
    """
    return methods[validate_method(name, methods, what, role)]


def describe(method: object) -> str:
    """
    The one-line description of a method: the first paragraph of its docstring, on one line (a string is its own
    description).

    Examples
    --------
    >>> def zero(values):
    ...     \"\"\"0 outside the
    ...     measured range
    ...
    ...     The values, 0 where no sample is.\"\"\"
    >>> describe(zero), describe("an error")
    ('0 outside the measured range', 'an error')
    """
    if isinstance(method, str):
        return method
    text = (getattr(method, "__doc__", None) or "").strip()
    return " ".join(text.split("\n\n")[0].split()) if text else getattr(method, "__name__", str(method))


def takes(method: Callable, option: str) -> bool:
    """
    Whether ``method`` takes the keyword ``option``: the one question a caller asks of a method beside calling it
    (an option only some methods of a family take is a parameter of those, and the others are refused it).

    >>> takes(lambda banks, noisy=None: 0, "noisy"), takes(lambda banks: 0, "noisy")
    (True, False)
    """
    import inspect

    return option in inspect.signature(method).parameters


def parse_range(text: str, what: str, example: str = "400:700:10") -> tuple[float, float, float]:
    """
    ``START:END:STEP`` (an optional ``nm`` is ignored) as three finite floats.

    Only the form is checked here; what a range must satisfy (``END > START``,
    whole steps, …) is checked by whoever uses it.

    Examples
    --------
    >>> parse_range("400:700:5nm", "grid")
    (400.0, 700.0, 5.0)
    """

    parts = str(text).replace("nm", "").split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        values = tuple(float(part) for part in parts)
    except ValueError:
        raise SkinrenderError(f"{what} must be START:END:STEP in nm (e.g. {example}), got {text!r}",
                              role=_argument(what)) from None
    if not all(math.isfinite(value) for value in values):
        raise SkinrenderError(f"{what} must be finite numbers of nm, got {text!r}", role=_argument(what))
    return values  # type: ignore[return-value]


class Steps(NamedTuple):
    """A range being checked: ``start``, ``end``, ``step``, the ``values`` it holds (END included; a fraction
    where END is not a whole number of steps away) and ``text``, the range as the user gave it."""

    start: float
    end: float
    step: float
    values: float
    text: str


@dataclass(frozen=True)
class RangeWords:
    """
    How a kind of range words its three refusals: each a function of the :class:`Steps` checked.

    Attributes
    ----------
    order
        END not above START (or STEP not > 0, where the caller has not refused it already).
    count
        More values than the most the range may hold.
    whole
        END not START plus a whole number of STEPs.
    """

    order: Callable[[Steps], str]
    count: Callable[[Steps], str]
    whole: Callable[[Steps], str]


def range_steps(start: float, end: float, step: float, most: int, words: RangeWords, text: str = "",
                role: str | None = None) -> int:
    """
    The number of steps of the range ``start, start + step, …, end`` (``end`` included): ``end`` above
    ``start``, ``step`` > 0, at most ``most`` values and ``end`` a whole number of steps from ``start`` (to
    1e-9 relative); otherwise a :class:`SkinrenderError` worded by ``words``, its role ``role``.

    Examples
    --------
    >>> words = RangeWords(lambda r: f"{r.text}: END must be above START",
    ...                    lambda r: f"{r.text}: {r.values:.3g} values, too many",
    ...                    lambda r: f"{r.text}: {r.end:g} is not START + whole steps")
    >>> range_steps(400.0, 700.0, 10.0, 1000, words, "400:700:10")
    30
    >>> range_steps(400.0, 690.0, 50.0, 1000, words, "400:690:50")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: 400:690:50: 690 is not START + whole steps
    """
    if not (step > 0 and end > start):
        raise SkinrenderError(words.order(Steps(start, end, step, math.nan, text)), role=role)
    count = (end - start) / step
    steps = Steps(start, end, step, count + 1, text)
    if count + 1 > most:
        raise SkinrenderError(words.count(steps), role=role)
    if abs(count - round(count)) > 1e-9 * max(1.0, count):
        raise SkinrenderError(words.whole(steps), role=role)
    return int(round(count))
