"""
Spectral CSV files
==================

The validating reader of every spectral table a user can give (cameras,
reflectance sets, illuminants): a CSV whose first column is wavelength in nm
and whose other columns are spectra, checked line by line so that a bad file
is refused with the file, line and column named.

-   :class:`SpectraTable`, :func:`read_spectra_csv`: a CSV of spectra.
-   :func:`validate_spectra`: the checks on wavelengths and values.
-   :func:`measured_spectrum`: one spectrum given as arrays, checked alike.

Units: wavelength in nm; values in the file's unit (unitless reflectances and
sensitivities, W·m⁻²·sr⁻¹·nm⁻¹ for illuminants).
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import SkinrenderError
from .files import read_input
from .hints import Literal, NDArrayFloat
from .spectra import float_array

__all__ = ["CSV_BYTES_MAX", "SpectraTable", "measured_spectrum", "read_spectra_csv", "validate_spectra"]

CSV_BYTES_MAX = 64_000_000
"""Largest spectral CSV read, bytes: a 1 nm table of 10 000 spectra is ~30 MB."""


@dataclass(frozen=True)
class SpectraTable:
    """Spectra read from a table: wavelengths (nm), names and values ``(n_spectra, n_wl)``."""

    wavelengths: NDArrayFloat
    names: tuple[str, ...]
    values: NDArrayFloat
    source: str


def measured_spectrum(wavelength, reflectance, least: int = 2) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    A measured reflectance spectrum as arrays, in increasing wavelength: at least ``least`` finite fractions in
    [0, 1.5] (as :func:`validate_spectra` takes reflectances: a table in percent is refused, not rescaled) on as
    many finite, strictly monotonic ``wavelength`` (nm); else an error naming ``wavelength`` or ``reflectance``.

    >>> measured_spectrum([400, 500], [0.2, 40.0])
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: reflectance must be fractions in [0, 1.5], got 0.2 to 40 (percent? divide by 100)
    """
    lam, values = float_array(wavelength, "wavelength"), float_array(reflectance, "reflectance")
    if lam.ndim != 1 or lam.shape != values.shape or lam.size < least or not np.all(np.isfinite(values)):
        raise SkinrenderError(f"reflectance must be finite on at least {least} wavelengths, one per wavelength, got "
                              f"shapes {values.shape} and {lam.shape}", role="reflectance")
    if np.all(np.diff(lam) < 0):  # decreasing: the same spectrum, read the other way
        lam, values = lam[::-1], values[::-1]
    if not (np.all(np.isfinite(lam)) and np.all(np.diff(lam) > 0)):
        raise SkinrenderError("wavelength must be finite nm, strictly monotonic", role="wavelength")
    if np.any((values < 0) | (values > 1.5)):
        percent = " (percent? divide by 100)" if 1.5 < values.max() <= 100 else ""
        raise SkinrenderError(f"reflectance must be fractions in [0, 1.5], got {values.min():.4g} to "
                              f"{values.max():.4g}{percent}", role="reflectance")
    return lam, values


def validate_spectra(
    wavelengths: NDArrayFloat,
    values: NDArrayFloat,
    source: str,
    kind: Literal["reflectance", "sensitivity", "spd"] = "reflectance",
    lines: "list[int] | None" = None,
) -> None:
    """
    Refuse NaN, infinite or negative values and non-monotonic wavelengths.

    Parameters
    ----------
    wavelengths
        Shape ``(n,)``, nm.
    values
        Shape ``(n_spectra, n)``.
    source
        File or dataset name for the message.
    kind
        What the values are (named in the message). Reflectances must also be
        at most 1.5 — a table in percent is refused rather than rescaled.
    lines
        The file line number of each wavelength row, for the message; with
        ``None`` messages give the row index.
    """

    def where(row: int) -> str:
        return f"{source}, line {lines[row]}" if lines is not None else f"{source}, row {row}"

    if not np.all(np.isfinite(wavelengths)):
        row = int(np.flatnonzero(~np.isfinite(wavelengths))[0])
        raise SkinrenderError(f"{where(row)}: wavelength is not a finite number")
    steps = np.diff(wavelengths)
    if np.any(steps <= 0):
        row = int(np.flatnonzero(steps <= 0)[0]) + 1
        raise SkinrenderError(
            f"{where(row)}: wavelength {wavelengths[row]:g} nm does not increase on the "
            f"previous {wavelengths[row - 1]:g} nm (the wavelength column must be strictly increasing)"
        )
    if np.any(wavelengths <= 0):
        row = int(np.flatnonzero(wavelengths <= 0)[0])
        raise SkinrenderError(f"{where(row)}: wavelength must be > 0 nm")
    bad = ~np.isfinite(values)
    if np.any(bad):
        spectrum, row = (int(i[0]) for i in np.nonzero(bad))
        raise SkinrenderError(f"{where(row)}: {kind} in column {spectrum + 2} is not a finite number")
    negative = values < 0
    if np.any(negative):
        spectrum, row = (int(i[0]) for i in np.nonzero(negative))
        raise SkinrenderError(
            f"{where(row)}: negative {kind} {values[spectrum, row]:g} in column {spectrum + 2}"
        )
    if kind == "reflectance" and values.size and values.max() > 1.5:
        spectrum, row = np.unravel_index(int(np.argmax(values)), values.shape)
        raise SkinrenderError(
            f"{where(int(row))}: reflectance {values[spectrum, row]:g} in column {spectrum + 2} "
            f"is above 1.5; reflectances are fractions in [0, 1], not percent"
        )


def read_spectra_csv(
    path: str | Path,
    kind: Literal["reflectance", "sensitivity", "spd"] = "reflectance",
    expected_columns: int | None = None,
) -> SpectraTable:
    """
    Read a CSV of spectra: first column wavelength (nm), one column per spectrum.

    Parameters
    ----------
    path
        The CSV file. A header row (any first cell that is not a number) gives
        the spectrum names; without one, the names are ``column 2`` …
    kind
        ``reflectance`` (fractions in [0, 1]), ``sensitivity`` or ``spd``.
    expected_columns
        Number of spectrum columns required (3 for a camera), or ``None``.

    Returns
    -------
    :class:`SpectraTable`

    Raises
    ------
    SkinrenderError
        For a missing file, a non-numeric cell, a ragged row, NaN, negative
        values or a wavelength column that is not strictly increasing, naming
        the file and line.
    """

    path = Path(path)
    rows: list[list[float]] = []
    lines: list[int] = []
    names: list[str] | None = None
    data = read_input(path, CSV_BYTES_MAX, "a spectral CSV")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise SkinrenderError(f"{path}: not a UTF-8 text file (byte {error.start}); expected a CSV of numbers") from None
    if "\x00" in text:
        raise SkinrenderError(f"{path}: a binary file, not a CSV of numbers")
    try:
        handle = io.StringIO(text, newline="")
        for line_number, row in enumerate(csv.reader(handle), start=1):
            cells = [cell.strip() for cell in row]
            if not cells or all(cell == "" for cell in cells) or cells[0].startswith("#"):
                continue
            if names is None and not rows and not _is_number(cells[0]):
                names = cells[1:]
                continue
            try:
                numbers = [float(cell) if cell != "" else math.nan for cell in cells]
            except ValueError:
                bad = next(cell for cell in cells if cell != "" and not _is_number(cell))
                raise SkinrenderError(f"{path}, line {line_number}: {bad!r} is not a number") from None
            width = len(names) + 1 if names is not None else (len(rows[0]) if rows else len(numbers))
            if len(numbers) != width:
                raise SkinrenderError(
                    f"{path}, line {line_number}: {len(numbers)} columns, expected {width}"
                )
            rows.append(numbers)
            lines.append(line_number)
    except csv.Error as error:
        raise SkinrenderError(f"{path}: not a readable CSV ({error})") from None
    if not rows:
        raise SkinrenderError(f"{path}: no data rows")
    data = np.asarray(rows, dtype=np.float64)
    if data.shape[1] < 2:
        raise SkinrenderError(f"{path}: needs a wavelength column and at least one spectrum column")
    if names is None:
        names = [f"column {i}" for i in range(2, data.shape[1] + 1)]
    if expected_columns is not None and data.shape[1] - 1 != expected_columns:
        raise SkinrenderError(
            f"{path}: {data.shape[1] - 1} spectrum columns, expected {expected_columns} "
            f"(wavelength in nm, then {expected_columns} columns)"
        )
    wavelengths, values = data[:, 0], data[:, 1:].T.copy()
    validate_spectra(wavelengths, values, str(path), kind, lines=lines)
    return SpectraTable(wavelengths, tuple(names), values, str(path))


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
