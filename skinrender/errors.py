"""
Errors
======

:class:`SkinrenderError` is raised for every bad input a user can give: an
unknown name, a malformed spec, a CSV with bad values, a temperature that is not
positive. The command line turns it into a one-line message and exit status 2.

An error carries, beside its message, what the command line needs to word it
without reading its text: ``role`` (which argument of the function was at
fault: ``camera``, ``illuminant``, ``spp`` …), ``flag`` (the command-line flag
once known), ``cause`` (a kind of failure with its own advice, e.g.
``coverage``: spectra that do not cover the grid), ``hint`` (the advice, kept
apart from the message) and ``status`` (the exit status).
"""

from __future__ import annotations

import copy

__all__ = ["SkinrenderError", "naming", "naming_role", "given_role", "flag_of", "check_flag"]


class SkinrenderError(ValueError):
    """
    A user-facing error whose message names the argument and what was expected.

    Parameters
    ----------
    message
        What is wrong, one line.
    role, flag, cause, hint
        Optional fields (see the module's notes); ``str(error)`` is ``message`` followed by ``; hint``.

    Examples
    --------
    >>> error = SkinrenderError("x.csv: measured over 420–680 nm", hint="choose another grid", cause="coverage")
    >>> str(error), error.message, error.cause
    ('x.csv: measured over 420–680 nm; choose another grid', 'x.csv: measured over 420–680 nm', 'coverage')
    """

    status = 2
    """Exit status of the command line."""

    def __init__(self, message: str = "", *, role: str | None = None, flag: str | None = None,
                 cause: str | None = None, hint: str | None = None):
        super().__init__(message)
        self.message, self.role, self.flag, self.cause, self.hint = str(message), role, flag, cause, hint

    def __str__(self) -> str:
        return f"{self.message}; {self.hint}" if self.hint else self.message

    def reworded(self, message: str | None = None, **fields) -> SkinrenderError:
        """A copy with another ``message`` and ``fields`` (the others kept, the class too)."""
        new = copy.copy(self)
        new.message = self.message if message is None else message
        new.args = (new.message,)
        for key, value in fields.items():
            setattr(new, key, value)
        return new


def check_flag(value, name: str) -> bool:
    """
    ``value`` as a bool where it is one (Python's or numpy's), else an error naming ``name``: a text such as
    ``"no"`` is not taken as true.

    >>> check_flag(True, "knee")
    True
    >>> check_flag("no", "knee")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: knee must be True or False, got 'no'
    """
    if isinstance(value, bool) or (type(value).__module__ == "numpy" and type(value).__name__ in ("bool", "bool_")):
        return bool(value)
    raise SkinrenderError(f"{name} must be True or False, got {value!r}", role=name)


def given_role(role: str, function, *args, **kwargs):
    """
    ``function(*args, **kwargs)``, its :class:`SkinrenderError` given the ``role`` where it has none (a file's or a
    name's fault, found below the argument's caller: ``camera``, ``scene``, ``grid`` …).

    >>> def read(path):
    ...     raise SkinrenderError(f"{path}: no such file")
    >>> try:
    ...     given_role("camera", read, "cam.csv")
    ... except SkinrenderError as error:
    ...     error.role, error.message
    ('camera', 'cam.csv: no such file')
    """
    try:
        return function(*args, **kwargs)
    except SkinrenderError as error:
        raise (error if error.role else error.reworded(role=role)) from None


def naming_role(role: str, function, *args, **kwargs):
    """
    ``function(*args, **kwargs)``, its :class:`SkinrenderError` about a reflectance (role ``reflectance``) given the
    caller's argument ``role`` (``skin``, ``munsell``): which of two sets is at fault; any other error as it is.
    """
    try:
        return function(*args, **kwargs)
    except SkinrenderError as error:
        if error.role != "reflectance":
            raise
        raise error.reworded(error.message if error.message.startswith(role) else f"{role}: {error.message}",
                             role=role) from None


def flag_of(name: str) -> str | None:
    """
    ``name`` where it is a command-line flag (``--spp``), else ``None``: the ``flag`` of an error worded with a
    name its caller gave, which is a flag from the command line and an argument's name from Python.

    >>> flag_of("--tolerance"), flag_of("tolerance")
    ('--tolerance', None)
    """
    return name if str(name).startswith("--") else None


def naming(name: str | dict, function, *args, **kwargs):
    """
    ``function(*args, **kwargs)``, its :class:`SkinrenderError` reworded to start with the flag it came from,
    unless the error names its flag already (its ``flag`` field: the one at fault was named where it was found).

    ``name`` is a flag, or a mapping from the error's ``role`` to a flag with the key ``None`` for any other
    role: ``{"camera": "--camera", None: "--count"}`` blames the camera's errors on ``--camera``.

    >>> naming("--count", int, "7")
    7
    >>> def light(kelvin):
    ...     raise SkinrenderError(f"{kelvin} K gives no light", role="illuminant")
    >>> naming({"illuminant": "--range", None: "--count"}, light, 1)
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: --range: 1 K gives no light
    """
    try:
        return function(*args, **kwargs)
    except SkinrenderError as error:
        flag = name.get(error.role, name.get(None)) if isinstance(name, dict) else name
        if error.flag is not None or flag is None:
            raise
        raise error.reworded(f"{flag}: {error.message}", flag=flag) from None
