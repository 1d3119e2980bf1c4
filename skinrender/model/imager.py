"""
Imager
======

The image sensor and optics behind the three spectral channels (the paper's
"sensor N" stays the spectral channel; the imager turns its radiance into
electrons and digital numbers): the parameters of the EMVA 1288 linear camera
model, validated, and the bundled presets.

-   :class:`Imager`: the parameters (pixel, lens, quantum efficiency, full
    well, read noise, dark current, system gain, ADC bits, black level).
-   :func:`imager`: an :class:`Imager` from a preset name, a TOML file path or
    an :class:`Imager`; :func:`list_imagers`: the presets.
-   :data:`ROOT_RESOURCES_IMAGERS`: the preset folder
    (``datasets/resources/imagers/*.toml``, found from this file, read on
    first use).
-   :func:`checked_array`, :func:`checked_grid`: the input validation shared
    by :mod:`skinrender.model.exposure` and :mod:`skinrender.model.noise`.

Units: pixel pitch µm, charge e⁻ (electrons), dark current e⁻/s, output DN,
system gain K in DN/e⁻, wavelength nm.

References
----------
-   :cite:`EMVA1288` : European Machine Vision Association (2021). EMVA
    Standard 1288, Standard for Characterization of Image Sensors and Cameras,
    Release 4.0 Linear.
-   :cite:`SonyICX418` : Sony, ICX418AKB/ALB/AKL datasheets, diagonal 8 mm
    (type 1/2) interline CCD, 768 × 494 pixels, unit cell 8.4 µm × 9.8 µm
    (preset ``sony-icx418``).
-   :cite:`Herb2016` : F. Herb, "Sony Exmor Sensoren: Datenblattrekonstruktion
    IMX157", fhotolab.fherb.de, 2016: EMVA 1288 figures of the Sony IMX174
    (attributed to Point Grey's Grasshopper3 GS3-U3-23S6M data; preset
    ``sony-imx174``). Each preset file states its sources and which values
    are assumed.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..files import exists
from ..hints import ArrayLike, NDArrayFloat
from ..spectra import WavelengthGrid
from ..toml_tables import entry, from_table, read_toml

__all__ = ["ROOT_RESOURCES_IMAGERS", "Imager", "checked_array", "checked_grid", "imager", "is_integer", "list_imagers"]

ROOT_RESOURCES_IMAGERS: Path = Path(__file__).resolve().parents[1] / "datasets" / "resources" / "imagers"
"""The folder of the imager presets, one TOML file each."""

_NUMBER_FIELDS = {  # field: (unit, lower bound, lower bound allowed, upper bound)
    "pixel_um": ("µm", 0.0, False, math.inf), "f_number": ("(dimensionless)", 0.0, False, math.inf),
    "transmittance": ("(fraction)", 0.0, False, 1.0), "qe_peak": ("(fraction)", 0.0, False, 1.0),
    "full_well_e": ("e⁻", 0.0, False, math.inf), "read_noise_e": ("e⁻ rms", 0.0, True, math.inf),
    "dark_current_e_per_s": ("e⁻/s", 0.0, True, math.inf), "gain_dn_per_e": ("DN/e⁻", 0.0, False, math.inf),
    "black_level_dn": ("DN", 0.0, True, math.inf),
}

LIST_KEYS = ("name", "source", "pixel_um", "full_well_e", "read_noise_e", "gain_dn_per_e", "bits")
"""The keys of each :func:`list_imagers` row (``skinrender imagers --json``)."""


def is_integer(value: object) -> bool:
    """Whether ``value`` is an integer (Python or numpy), not a bool."""
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


_IN_FILE = entry("any", required=True)
"""An imager file gives every field (the :class:`Imager` checks their values)."""


@dataclass(frozen=True, kw_only=True)
class Imager:
    """
    An image sensor behind a lens: the parameters of the noise model, validated.

    Parameters
    ----------
    name, source : str
        Preset name and the citation of its values.
    pixel_um, f_number, transmittance : float
        Pixel pitch, µm (square pixel) > 0; lens f-number N > 0; optics
        transmittance τ in (0, 1].
    qe_peak : float
        Quantum efficiency at each channel's sensitivity peak, in (0, 1].
    full_well_e, read_noise_e, dark_current_e_per_s : float
        Saturation capacity, e⁻ > 0; temporal dark (read) noise, e⁻ rms ≥ 0;
        dark current, e⁻/s ≥ 0.
    gain_dn_per_e, bits, black_level_dn
        System gain K, DN/e⁻ > 0; ADC bits, an integer 1–32 (codes 0 …
        2^bits − 1, DN); offset, DN, in [0, 2^bits − 1].

    Raises
    ------
    SkinrenderError
        Naming the first field out of its range.

    Examples
    --------
    >>> Imager(pixel_um=5.0, f_number=2.8, transmittance=0.9, qe_peak=0.6, full_well_e=2e4,
    ...        read_noise_e=5.0, dark_current_e_per_s=1.0, gain_dn_per_e=0.2, bits=12,
    ...        black_level_dn=10.0).max_dn
    4095
    """

    name: str = field(default="custom", metadata=_IN_FILE)
    source: str = field(default="user-defined", metadata=_IN_FILE)
    pixel_um: float = field(metadata=_IN_FILE)
    f_number: float = field(metadata=_IN_FILE)
    transmittance: float = field(metadata=_IN_FILE)
    qe_peak: float = field(metadata=_IN_FILE)
    full_well_e: float = field(metadata=_IN_FILE)
    read_noise_e: float = field(metadata=_IN_FILE)
    dark_current_e_per_s: float = field(metadata=_IN_FILE)
    gain_dn_per_e: float = field(metadata=_IN_FILE)
    bits: int = field(metadata=_IN_FILE)
    black_level_dn: float = field(metadata=_IN_FILE)

    def __post_init__(self) -> None:
        for key in ("name", "source"):
            if not isinstance(getattr(self, key), str) or not getattr(self, key).strip():
                raise SkinrenderError(f"{key} must be a non-empty string, got {getattr(self, key)!r}")
        for key, (unit, low, closed, high) in _NUMBER_FIELDS.items():
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, numbers.Real):
                raise SkinrenderError(f"{key} must be a number, {unit}, got {value!r}")
            value = float(value)
            if not (math.isfinite(value) and (value >= low if closed else value > low) and value <= high):
                bounds = f"{'[' if closed else '('}{low:g}, {'∞)' if math.isinf(high) else f'{high:g}]'}"
                raise SkinrenderError(f"{key} must be a finite number in {bounds} {unit}, got {value!r}")
            object.__setattr__(self, key, value)
        if not is_integer(self.bits) or not 1 <= self.bits <= 32:
            raise SkinrenderError(f"bits must be an integer from 1 to 32, got {self.bits!r}")
        object.__setattr__(self, "bits", int(self.bits))
        if self.black_level_dn > self.max_dn:
            raise SkinrenderError(
                f"black_level_dn must be ≤ 2**bits - 1 = {self.max_dn} DN, got {self.black_level_dn:g}"
            )

    @property
    def max_dn(self) -> int:
        """The largest output code, 2^bits − 1, DN."""
        return 2**self.bits - 1


def _read_imager_toml(path: Path) -> Imager:
    """One imager file; every problem names the file and the field."""
    data = read_toml(path, "an imager TOML", where="imager file", role="imager")
    return from_table(Imager, data, f"imager file {path}", unknown="first", role="imager")


@lru_cache(maxsize=1)
def _presets() -> dict[str, Imager]:
    items = map(_read_imager_toml, sorted(ROOT_RESOURCES_IMAGERS.glob("*.toml")))
    return {item.name.lower(): item for item in items}


def imager(spec: str | Path | Imager) -> Imager:
    """
    An :class:`Imager` from a preset name (any case), a TOML file path or an :class:`Imager`.

    Parameters
    ----------
    spec
        A preset name (``skinrender imagers`` lists them), a path to a TOML
        file with every :class:`Imager` field (units as in the field names:
        µm, e⁻, e⁻/s, DN/e⁻, DN), or an :class:`Imager` (returned as is).

    Returns
    -------
    :class:`Imager`

    Raises
    ------
    SkinrenderError
        For an unknown name (the message lists the presets), a missing file or
        a bad field (the message names the file and the field).

    Examples
    --------
    >>> imager("SONY-IMX174").full_well_e  # e⁻
    32691.0
    """

    if isinstance(spec, Imager):
        return spec
    if not isinstance(spec, (str, Path)):
        raise SkinrenderError(f"imager must be a preset name, a TOML path or an Imager, got {spec!r}", role="imager")
    presets = _presets()
    if isinstance(spec, str) and spec.strip().lower() in presets:
        return presets[spec.strip().lower()]
    if exists(spec):  # a file: read if it is a regular one of a sensible size, else refused saying what it is
        return _read_imager_toml(Path(spec))
    names = ", ".join(item.name for item in presets.values())
    raise SkinrenderError(f"imager {str(spec)!r} is neither a preset ({names}) nor an existing TOML file",
                          role="imager")


def list_imagers() -> list[dict]:
    """
    The presets, one row each.

    Returns
    -------
    list of dict
        ``name``, ``source``, ``pixel_um`` (µm), ``full_well_e`` (e⁻),
        ``read_noise_e`` (e⁻ rms), ``gain_dn_per_e`` (DN/e⁻), ``bits``.

    Examples
    --------
    >>> [row["name"] for row in list_imagers()]
    ['sony-icx418', 'sony-imx174']
    """
    return [{key: getattr(item, key) for key in LIST_KEYS} for item in _presets().values()]


def checked_grid(grid: WavelengthGrid | str) -> WavelengthGrid:
    """
    A :class:`~skinrender.spectra.WavelengthGrid` (nm) from itself or ``START:END:STEP``.

    Examples
    --------
    >>> checked_grid("400:700:10").size
    31
    """
    if isinstance(grid, WavelengthGrid):
        return grid
    if isinstance(grid, str):
        return WavelengthGrid.parse(grid)
    raise SkinrenderError(f"grid must be a WavelengthGrid or START:END:STEP in nm, got {grid!r}")


def checked_array(
    values: ArrayLike, name: str, unit: str, low: float | None = 0.0, grid: WavelengthGrid | None = None
) -> NDArrayFloat:
    """
    A finite float64 array, checked.

    Parameters
    ----------
    values
        Any array-like of numbers.
    name, unit
        The argument's name and unit (nm, e⁻, DN, s, …) for the error message.
    low
        Smallest value allowed (default 0); ``None`` for no bound.
    grid
        When given, the last axis must have ``grid.size`` samples (nm grid).

    Raises
    ------
    SkinrenderError
        Naming ``name`` for a non-number, NaN, ±inf, a value below ``low`` or
        a wrong last axis.

    Examples
    --------
    >>> checked_array([1, 2], "exposure_s", "s").tolist()
    [1.0, 2.0]
    """
    try:
        out = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise SkinrenderError(f"{name} must be an array of numbers, {unit}, got {values!r}") from None
    if not np.all(np.isfinite(out)) or (low is not None and np.any(out < low)):
        raise SkinrenderError(f"{name} must be finite{'' if low is None else f' and ≥ {low:g}'}, {unit}")
    if grid is not None and (out.ndim == 0 or out.shape[-1] != grid.size):
        raise SkinrenderError(f"{name} must have {grid.size} samples (grid {grid}) last, got {out.shape}")
    return out
