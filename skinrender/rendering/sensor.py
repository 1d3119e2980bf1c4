"""
What an image sensor records with
=================================

The options of the ``noise`` effect (a render recorded by an image sensor, on
a chart or a face), owned by the effect and checked once, where a request is
built (:mod:`skinrender.rendering.request`): :class:`NoiseOptions`, the
imager, the illuminance and the exposure.

-   :class:`NoiseOptions`; :data:`EXPOSURE_MAX`, :data:`ILLUMINANCE_MAX`:
    their bounds.

Units: illuminance lx, exposure s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError, given_role
from ..model.imager import Imager, imager as load_imager, is_integer

__all__ = ["EXPOSURE_MAX", "ILLUMINANCE_MAX", "NoiseOptions"]

EXPOSURE_MAX = 1e5
"""Longest exposure, s (about 28 h): far beyond it the electron counts overflow."""

ILLUMINANCE_MAX = 1e15
"""Largest illuminance, lx: ten orders of magnitude above direct sunlight (~1.2e5 lx); far beyond it the electron
counts overflow."""


def _number(value) -> float | None:
    """``value`` as a float where it is a real number (not a bool), else ``None``."""
    if isinstance(value, (bool, np.bool_)):
        return None
    if is_integer(value) or isinstance(value, (float, np.floating)):
        return float(value)
    try:
        return float(value) if isinstance(value, str) else None
    except ValueError:
        return None


@dataclass(frozen=True)
class NoiseOptions:
    """
    The options of the ``noise`` effect: how an image sensor records the render.

    Parameters
    ----------
    imager
        An :class:`~skinrender.model.imager.Imager`, a preset's name or a TOML path (loaded here, once), or
        ``None``: the effect's default (a face: :data:`~skinrender.rendering.face.effects.noise.IMAGER_DEFAULT`).
    illuminance
        The illuminance of the prevailing light at the target, lx, in (0, :data:`ILLUMINANCE_MAX`]; ``None``: the
        scene's (a face) or :data:`~skinrender.rendering.request.ILLUMINANCE_DEFAULT` (a chart).
    exposure
        ``auto`` (the calibration white's brightest channel at 0.7 of the full well) or seconds in
        (0, :data:`EXPOSURE_MAX`].

    Raises
    ------
    SkinrenderError
        An option out of its bounds (illuminance in lx, exposure in s), its ``role`` the option's name: the
        command line words it with the option's flag.

    Examples
    --------
    >>> options = NoiseOptions("sony-imx174", 300, "0.01")
    >>> options.imager.name, options.illuminance, options.exposure
    ('sony-imx174', 300.0, 0.01)
    >>> NoiseOptions(exposure=-1)
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: exposure must be auto or a finite number of seconds > 0 and ≤ 100000, got -1
    """

    imager: Imager | None = None
    illuminance: float | None = None
    exposure: float | str = "auto"

    def __post_init__(self) -> None:
        if self.imager is not None and not isinstance(self.imager, Imager):
            if not isinstance(self.imager, (str, Path)):
                raise SkinrenderError(f"imager must be a preset's name, a TOML path or an Imager, got {self.imager!r}",
                                      role="imager")
            object.__setattr__(self, "imager", given_role("imager", load_imager, self.imager))
        if self.illuminance is not None:
            lux = _number(self.illuminance)
            if lux is None or not (math.isfinite(lux) and 0 < lux <= ILLUMINANCE_MAX):
                raise SkinrenderError(f"illuminance must be a finite number of lux > 0 and ≤ {ILLUMINANCE_MAX:g}, got "
                                      f"{self.illuminance!r}", role="illuminance")
            object.__setattr__(self, "illuminance", lux)
        exposure = self.exposure
        if isinstance(exposure, str) and exposure.strip().lower() == "auto":
            object.__setattr__(self, "exposure", "auto")
            return
        seconds = _number(exposure)
        if seconds is None or not (math.isfinite(seconds) and 0 < seconds <= EXPOSURE_MAX):
            raise SkinrenderError(f"exposure must be auto or a finite number of seconds > 0 and ≤ {EXPOSURE_MAX:g}, "
                                  f"got {exposure!r}", role="exposure")
        object.__setattr__(self, "exposure", seconds)
