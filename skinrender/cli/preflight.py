"""
Checks before the work
======================

What a command checks before any work beyond its flags' syntax, each refusal one line naming the flag: every
light gives the camera light on the grid (:func:`check_lights`, :func:`check_render_lights`), and a
``--dask`` address is a Dask scheduler with workers (:func:`check_dask`).

Units: temperatures K, wavelengths nm, times s.
"""

from __future__ import annotations

import argparse

from ..errors import naming as flag

__all__ = ["check_lights", "check_render_lights", "check_dask"]


def check_render_lights(cam, temperatures: dict, grid=None) -> None:
    """
    Each render light gives the camera light on ``grid`` (``temperatures``: ``{"prevailing": K, "calibration": K}``),
    else a one-line error naming its flag and the light by its role (``--calibration: calibration illuminant 1K
    gives no light …``).
    """
    from ..model.illuminant import illuminants_array
    from ..model.response import check_light, spds_on
    from ..spectra import GRID_DEFAULT

    grid = grid or GRID_DEFAULT
    for name, kelvin in temperatures.items():
        items, _ = illuminants_array([kelvin])
        flag({"camera": "--camera", None: f"--{name}"}, check_light, cam, items, spds_on(items, grid), grid,
             f"{name} illuminant")


def check_lights(args: argparse.Namespace, cam, temperatures, grid=None, name: str = "--illuminants") -> None:
    """Every illuminant of a set gives the camera light on the grid; otherwise a one-line error naming ``name``."""
    from ..model.illuminant import illuminants_array
    from ..model.response import check_light, spds_on
    from ..spectra import GRID_DEFAULT

    grid = grid or GRID_DEFAULT
    items, _ = illuminants_array(temperatures)
    flag({"camera": "--camera", None: name}, check_light, cam, items, spds_on(items, grid), grid, "illuminant")


def check_dask(args: argparse.Namespace) -> str | None:
    """
    ``--dask`` checked before any work: ``None`` where not given, else the address once a Dask scheduler answered
    there with Dask's handshake within :data:`~skinrender.execution.DASK_TIMEOUT_S` s
    (:func:`~skinrender.execution.check_dask_address`); an empty address, another kind of server (an HTTP one) or
    none at all is a one-line refusal naming ``--dask``.
    """
    address = getattr(args, "dask", None)
    if address is None:
        return None
    from ..execution import check_dask_address
    from ..extras import require

    require("dask", "--dask")
    return check_dask_address(address, "--dask")
