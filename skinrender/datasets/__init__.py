"""
Datasets
========

Reflectance sets and camera sensitivities, one module per source, reached by
name through the registries. Nothing is loaded at import: each set is built on
first use.

-   :func:`reflectances`: a named set or a CSV path to a :class:`SpectralSet`.
-   :func:`camera_sensitivities`: a named camera to a :class:`SpectralSet`.
-   :func:`list_reflectances`, :func:`list_cameras`: what exists, with source,
    licence, count and wavelength range.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import SkinrenderError
from ..files import exists
from ..methods import validate_method
from ..spectra import EXTRAPOLATIONS
from ..spectral_csv import read_spectra_csv
from . import colour_science, luxpy_munsell, psychtoolbox, skin_model, skin_tones  # noqa: F401  (registration)
from .registry import REGISTRY_CAMERAS, REGISTRY_REFLECTANCES, SpectralSet, lookup, unknown

__all__ = [
    "SpectralSet",
    "REGISTRY_CAMERAS",
    "REGISTRY_REFLECTANCES",
    "reflectances",
    "camera_sensitivities",
    "list_reflectances",
    "list_cameras",
    "looks_like_path",
]


def looks_like_path(spec: str) -> bool:
    """
    Whether a spec names a file rather than a registry entry: a ``.csv`` path, or an existing file whose name
    is no registered set or camera (a file named ``macbeth`` in the working folder does not hide the set).
    """
    text = str(spec)
    if text.lower().endswith(".csv"):
        return True
    if not exists(text):  # a pipe, a device or a folder too: the CSV reader says what it is
        return False
    return lookup(REGISTRY_REFLECTANCES, text) is None and lookup(REGISTRY_CAMERAS, text) is None


def reflectances(spec: str | SpectralSet, extrapolation: str = "refuse") -> SpectralSet:
    """
    A reflectance set by name or CSV path.

    Parameters
    ----------
    spec
        A name from :data:`REGISTRY_REFLECTANCES` (``macbeth``, ``munsell``,
        ``munsell-nickerson``, ``skin``, ``vrhel``, ``vrhel-nonskin``) or the path of
        a CSV: first column wavelength in nm, one column per sample, a header row
        with the sample names, reflectance as a fraction in [0, 1].
    extrapolation
        For a CSV: the rule for grid wavelengths outside its range
        (``refuse``, the default, ``zero`` or ``constant``).

    Returns
    -------
    :class:`SpectralSet`
        One row per sample (``names``), reflectance fractions on the set's own wavelengths (nm);
        ``on(grid)`` resamples them with the set's ``extrapolation``.

    Raises
    ------
    SkinrenderError
        An unknown name (the message lists the sets), a CSV that cannot be read, or an
        ``extrapolation`` other than ``refuse``, ``zero`` or ``constant``.

    Examples
    --------
    >>> reflectances("macbeth").count
    24

    A CSV measured over 450–650 nm put on a 400–700 nm grid: with ``extrapolation="zero"`` the
    reflectance is 0 outside the data (with the default, ``refuse``, this resampling is an error):

    >>> import tempfile
    >>> from skinrender.spectra import WavelengthGrid
    >>> path = Path(tempfile.mkdtemp()) / "two.csv"
    >>> _ = path.write_text("wavelength,pale,dark\\n450,0.40,0.20\\n550,0.50,0.25\\n650,0.60,0.30\\n")
    >>> samples = reflectances(str(path), extrapolation="zero")
    >>> samples.names
    ('pale', 'dark')
    >>> samples.on(WavelengthGrid(400, 700, 50))[0].tolist()
    [0.0, 0.4, 0.45, 0.5, 0.55, 0.6, 0.0]
    """

    validate_method(extrapolation, EXTRAPOLATIONS, "extrapolation")  # a bundled set's own rule is its dataset's
    if isinstance(spec, SpectralSet):
        return spec
    spec = str(spec).strip()
    if looks_like_path(spec):
        validate_method(extrapolation, EXTRAPOLATIONS, "extrapolation")
        table = read_spectra_csv(spec, kind="reflectance")
        return SpectralSet(
            Path(spec).name, table.wavelengths, table.values, table.names, source=spec,
            licence="user data", extrapolation=extrapolation,
        )
    entry = lookup(REGISTRY_REFLECTANCES, spec)
    if entry is None:
        raise unknown(REGISTRY_REFLECTANCES, spec, "reflectance set", "or give a CSV path").reworded(role="reflectance")
    return entry.load()


def camera_sensitivities(name: str) -> SpectralSet:
    """Measured sensitivities of a camera in :data:`REGISTRY_CAMERAS`, channels R, G, B."""
    entry = lookup(REGISTRY_CAMERAS, name)
    if entry is None:
        raise unknown(
            REGISTRY_CAMERAS, name, "camera",
            "or use 'gbell:N@P1,P2,P3', 'impulse@P1,P2,P3' or a CSV path (wavelength nm, R, G, B)",
        )
    return entry.load()


def _describe(entry) -> dict:
    spectra = entry.load()
    return {
        "name": entry.name,
        "count": spectra.count,
        "source": entry.source,
        "licence": entry.licence,
        "wavelengths": list(spectra.range),
        "extrapolation": spectra.extrapolation,
    }


def list_reflectances() -> list[dict]:
    """Every reflectance set: ``name, count, source, licence, wavelengths [min, max, step]``."""
    rows = []
    for entry in REGISTRY_REFLECTANCES.values():
        try:
            rows.append(_describe(entry))
        except SkinrenderError:  # an optional source that is not installed (skin-model without skinoptics)
            continue
    return rows


def list_cameras() -> list[dict]:
    """Every bundled camera: ``name, source, wavelengths [min, max, step]`` (and licence)."""
    rows = []
    for entry in REGISTRY_CAMERAS.values():
        row = _describe(entry)
        del row["count"]
        rows.append(row)
    return rows
