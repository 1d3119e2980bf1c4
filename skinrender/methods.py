"""
Method tables
=============

Every family of named methods (normalisations, extrapolations, locus
boundaries, design objectives, emitters, samplers, …) is a mapping from the
name a user types to what it means; :func:`validate_method` checks a name
against its table and words the error the same way everywhere, and the
command line takes its choices from the same tables. :func:`parse_range`
reads the ``START:END:STEP`` ranges (nm) of grids and sensor positions.

-   :func:`validate_method`: a name of a method table, or a one-line error.
-   :func:`parse_range`: ``START:END:STEP`` as three finite numbers.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from .errors import SkinrenderError

__all__ = ["validate_method", "parse_range"]


def validate_method(name: object, methods: Mapping[str, object], what: str, role: str | None = None) -> str:
    """
    ``name`` if it is a key of ``methods``, else a :class:`SkinrenderError`
    naming ``what`` and listing the choices (its ``role``: ``role``, the
    argument at fault, for the command line to name its flag).

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
        raise SkinrenderError(f"{what} must be one of {', '.join(methods)}, got {name!r}", role=role)
    return name


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
        raise SkinrenderError(f"{what} must be START:END:STEP in nm (e.g. {example}), got {text!r}") from None
    if not all(math.isfinite(value) for value in values):
        raise SkinrenderError(f"{what} must be finite numbers of nm, got {text!r}")
    return values  # type: ignore[return-value]
