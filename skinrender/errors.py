"""
Errors
======

:class:`SkinrenderError` is raised for every bad input a user can give: an
unknown name, a malformed spec, a CSV with bad values, a temperature that is not
positive. The command line turns it into a one-line message and exit status 2.
"""

from __future__ import annotations

__all__ = ["SkinrenderError"]


class SkinrenderError(ValueError):
    """A user-facing error whose message names the argument and what was expected."""
