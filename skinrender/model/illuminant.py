"""
Illuminant
==========

One light source: a Planckian radiator at a colour temperature, or a measured
SPD from a CSV file, and the parsing of the illuminant specs users type.

-   :class:`Illuminant`: ``spd(wavelengths)`` in W·m⁻²·sr⁻¹·nm⁻¹ (Planck) or the
    file's relative units.
-   :func:`illuminant`: ``3300``, ``"3300K"``, ``"A"``, ``"H"`` or a CSV path.
-   :func:`illuminants_array`: any of those, or an array of kelvin, as a flat
    list plus its shape (for broadcasting).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..constants import TEMPERATURE_A, TEMPERATURE_HORIZON, TEMPERATURE_MAX
from ..errors import SkinrenderError
from ..files import exists
from ..hints import ArrayLike, NDArrayFloat
from ..spectra import planck, resample
from ..spectral_csv import read_spectra_csv

__all__ = ["Illuminant", "illuminant", "illuminants_array", "NAMED_TEMPERATURES"]

NAMED_TEMPERATURES = {"A": TEMPERATURE_A, "H": TEMPERATURE_HORIZON, "HORIZON": TEMPERATURE_HORIZON}
"""Named Planckian illuminants, K: CIE A (2856 K) and the paper's Horizon (2300 K)."""


@dataclass(frozen=True)
class Illuminant:
    """
    A light source: a Planckian radiator when ``temperature`` is set, else a measured SPD; made from a
    user's spec by :func:`illuminant`, evaluated by :meth:`spd`.

    Parameters
    ----------
    name
        ``3300K``, ``A``, ``H`` or a file name.
    temperature
        Planckian colour temperature, K, or ``None`` for a measured SPD.
    wavelengths, values
        The measured SPD (nm, relative units) when ``temperature`` is ``None``.
    """

    name: str
    temperature: float | None = None
    wavelengths: tuple[float, ...] | None = None
    values: tuple[float, ...] | None = None

    def spd(self, wavelengths: ArrayLike) -> NDArrayFloat:
        """
        Spectral power distribution at ``wavelengths`` (nm).

        Planck radiance in W·m⁻²·sr⁻¹·nm⁻¹ (the paper's ``I_0``), or the
        measured SPD linearly interpolated; a wavelength outside the measured
        range is an error (no extrapolation).
        """
        wavelengths = np.asarray(wavelengths, dtype=np.float64)
        if self.temperature is not None:
            return planck(wavelengths, self.temperature)
        return resample(
            np.asarray(self.wavelengths), np.asarray(self.values), wavelengths, "refuse", f"illuminant {self.name}"
        )

    def __str__(self) -> str:
        return self.name


def _planckian(temperature: float, name: str | None = None) -> Illuminant:
    if not (np.isfinite(temperature) and 0 < temperature <= TEMPERATURE_MAX):
        raise SkinrenderError(f"illuminant temperature must be a finite number of kelvin in (0, {TEMPERATURE_MAX:g}], "
                              f"got {temperature:g}", role="illuminant")
    return Illuminant(name or f"{temperature:g}K", float(temperature))


def illuminant(spec: Illuminant | float | str) -> Illuminant:
    """
    An illuminant from its spec.

    Parameters
    ----------
    spec
        A colour temperature in kelvin (``3300``, ``"3300K"``), meaning a
        Planckian radiator; ``A`` (Planckian 2856 K) or ``H`` (Horizon,
        Planckian 2300 K); or a CSV path (wavelength nm, one SPD column).

    Returns
    -------
    :class:`Illuminant`
        ``temperature`` in K for a Planckian radiator, ``None`` for a measured SPD.

    Raises
    ------
    SkinrenderError
        A temperature outside (0, :data:`~skinrender.constants.TEMPERATURE_MAX`] K, a CSV that cannot
        be read or has other than one SPD column, or a spec that is none of these.

    Examples
    --------
    >>> illuminant("3300K").temperature
    3300.0
    >>> illuminant("a").name, illuminant("a").temperature  # CIE A: Planck at 2856 K
    ('A', 2856.0)

    Planck radiance at 560 nm, W·m⁻²·sr⁻¹·nm⁻¹:

    >>> illuminant(3300).spd([560.0]).round(1).tolist()
    [899.4]

    A measured SPD (relative units) from a CSV, linearly interpolated between its wavelengths:

    >>> import tempfile
    >>> path = Path(tempfile.mkdtemp()) / "led.csv"
    >>> _ = path.write_text("wavelength,spd\\n400,0.5\\n550,1.0\\n700,0.8\\n")
    >>> led = illuminant(str(path))
    >>> led.name, led.temperature, led.spd([475.0, 625.0]).tolist()
    ('led.csv', None, [0.75, 0.9])
    """

    if isinstance(spec, Illuminant):
        return spec
    if isinstance(spec, (bool, np.bool_)) or spec is None or isinstance(spec, (dict, set)):
        raise SkinrenderError(f"illuminant must be kelvin, A, H, a CSV path or an Illuminant, got {spec!r}",
                              role="illuminant")
    if isinstance(spec, (int, float, np.integer, np.floating)):
        return _planckian(float(spec))
    text = str(spec).strip()
    if text.upper() in NAMED_TEMPERATURES:
        return _planckian(NAMED_TEMPERATURES[text.upper()], text.upper())
    number = text[:-1] if text.upper().endswith("K") else text
    try:
        value = float(number)
    except ValueError:
        value = None
    if value is not None:
        return _planckian(value)
    if text.lower().endswith(".csv") or exists(text):
        table = read_spectra_csv(text, kind="spd", expected_columns=1)
        return Illuminant(Path(text).name, None, tuple(table.wavelengths), tuple(table.values[0]))
    raise SkinrenderError(
        f"illuminant {text!r} not understood: expected kelvin (3300 or 3300K), A, H or a CSV path", role="illuminant"
    )


def illuminants_array(spec, role: str = "illuminant") -> tuple[list[Illuminant], tuple[int, ...]]:
    """
    Any illuminant spec, list or array of kelvin, as a flat list and its shape; a refusal's role is ``role``
    (the caller's argument: ``prevailing``, ``calibration`` …).

    A single spec has shape ``()``.
    """
    try:
        return _illuminants_array(spec)
    except SkinrenderError as error:
        raise (error if error.role not in (None, "illuminant") else error.reworded(role=role)) from None


def _illuminants_array(spec) -> tuple[list[Illuminant], tuple[int, ...]]:
    if isinstance(spec, (str, Illuminant)) or np.isscalar(spec) or spec is None or isinstance(spec, (dict, set)):
        return [illuminant(spec)], ()
    if isinstance(spec, (list, tuple)) and spec and all(isinstance(s, (str, Illuminant)) or np.isscalar(s)
                                                        for s in spec):
        return [illuminant(s) for s in spec], (len(spec),)
    try:
        values = np.asarray(spec, dtype=np.float64)
    except (TypeError, ValueError):
        raise SkinrenderError(f"illuminant must be kelvin, A, H, a CSV path, an Illuminant or an array of kelvin, "
                              f"got {spec!r}"[:200], role="illuminant") from None
    if values.size == 0:
        raise SkinrenderError("illuminants: expected at least one temperature (K), got none")
    return [_planckian(float(t)) for t in values.ravel()], values.shape
