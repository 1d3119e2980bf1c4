"""
Errors
======

:class:`SkinrenderError` is raised for every bad input a user can give: an
unknown name, a malformed spec, a CSV with bad values, a temperature that is not
positive. The command line turns it into a one-line message and exit status 2.
"""

from __future__ import annotations

__all__ = ["SkinrenderError", "naming"]


class SkinrenderError(ValueError):
    """A user-facing error whose message names the argument and what was expected."""


def naming(name: str, function, *args, **kwargs):
    """
    ``function(*args, **kwargs)``, its :class:`SkinrenderError` reworded to start with the flag ``name`` it came
    from, unless the message already starts with a flag (``--…``: the one at fault was named where it was found).

    >>> naming("--count", int, "7")
    7
    """
    try:
        return function(*args, **kwargs)
    except SkinrenderError as error:
        text = str(error)
        raise SkinrenderError(text if text.startswith("--") else f"{name}: {text}") from None
