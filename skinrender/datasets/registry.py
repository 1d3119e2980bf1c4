"""
Dataset registry
================

The types every dataset module builds, and the two registries users reach by
name: :data:`REGISTRY_REFLECTANCES` and :data:`REGISTRY_CAMERAS`.

-   :class:`SpectralSet`: named spectra on their measured wavelengths.
-   :class:`DatasetEntry`: a registry row; the set is built lazily, on first use.
-   :func:`lookup`: find an entry by name, case-insensitively, or raise an error
    that lists the known names.

Each entry states its source, its licence and its extrapolation rule (what a
grid outside the measured range gets: see :data:`skinrender.spectra.EXTRAPOLATIONS`).
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..spectra import GRID_DEFAULT, WavelengthGrid, resample
from ..spectral_csv import read_spectra_csv, validate_spectra

__all__ = [
    "ROOT_RESOURCES",
    "SpectralSet",
    "DatasetEntry",
    "REGISTRY_REFLECTANCES",
    "REGISTRY_CAMERAS",
    "register",
    "lookup",
    "is_bundled",
    "unknown",
    "read_bundled_csv",
]

ROOT_RESOURCES = Path(__file__).parent / "resources"
"""Folder of the CSVs bundled with the package."""


@dataclass(frozen=True, eq=False)
class SpectralSet:
    """
    Named spectra on their measured wavelengths.

    Parameters
    ----------
    name
        Set name (``macbeth``, a camera name, a file path).
    wavelengths
        Measured wavelengths, nm, strictly increasing, shape ``(n_wl,)``.
    values
        Spectra, shape ``(n_spectra, n_wl)``: reflectance fractions in [0, 1]
        or relative sensitivities.
    names
        One name per spectrum (a sample name, or a channel name R, G, B).
    source, licence
        Where the data come from and under which licence.
    extrapolation
        Rule for grid wavelengths outside the measured range.
    """

    name: str
    wavelengths: NDArrayFloat
    values: NDArrayFloat
    names: tuple[str, ...]
    source: str = ""
    licence: str = ""
    extrapolation: str = "refuse"
    kind: str = "reflectance"

    def __post_init__(self) -> None:
        if self.values.shape != (len(self.names), self.wavelengths.size):
            raise SkinrenderError(
                f"{self.name}: {len(self.names)} names and {self.wavelengths.size} wavelengths "
                f"do not match values of shape {self.values.shape}"
            )
        validate_spectra(self.wavelengths, self.values, self.name, self.kind)

    @property
    def count(self) -> int:
        """Number of spectra."""
        return len(self.names)

    @property
    def range(self) -> tuple[float, float, float | None]:
        """``(min, max, step)`` of the wavelengths, nm; step ``None`` if not uniform."""
        steps = np.diff(self.wavelengths)
        uniform = steps.size and np.allclose(steps, steps[0])
        step = float(steps[0]) if uniform else None
        return float(self.wavelengths[0]), float(self.wavelengths[-1]), step

    def on(self, grid: WavelengthGrid = GRID_DEFAULT, extrapolation: str | None = None) -> NDArrayFloat:
        """
        The spectra resampled onto ``grid`` (linear), shape ``(n_spectra, grid.size)``.

        ``extrapolation`` overrides the set's own rule.
        """
        return _resample_cached(self, grid, extrapolation or self.extrapolation)

    def subset(self, indices, name: str | None = None) -> SpectralSet:
        """The spectra at ``indices`` (integers or a boolean mask) as a new set."""
        indices = np.arange(self.count)[np.asarray(indices)]
        return SpectralSet(
            name or self.name,
            self.wavelengths,
            self.values[indices],
            tuple(self.names[i] for i in indices),
            self.source,
            self.licence,
            self.extrapolation,
            self.kind,
        )

    @cached_property
    def _cache(self) -> dict:
        return {}


def _resample_cached(spectra: SpectralSet, grid: WavelengthGrid, extrapolation: str) -> NDArrayFloat:
    key = (grid, extrapolation)
    cache = spectra._cache
    if key not in cache:
        values = resample(spectra.wavelengths, spectra.values, grid, extrapolation, spectra.name)
        values.setflags(write=False)
        cache[key] = values
    return cache[key]


@dataclass
class DatasetEntry:
    """A registry row: a name, a loader building the set on first use, and its description."""

    name: str
    loader: Callable[[], SpectralSet]
    source: str
    licence: str
    _loaded: SpectralSet | None = field(default=None, repr=False)

    def load(self) -> SpectralSet:
        """Build (once) and return the set."""
        if self._loaded is None:
            self._loaded = self.loader()
        return self._loaded


REGISTRY_REFLECTANCES: dict[str, DatasetEntry] = {}
"""Reflectance sets by name (``macbeth``, ``munsell``, ``skin``, …)."""

REGISTRY_CAMERAS: dict[str, DatasetEntry] = {}
"""Measured camera sensitivities by name (``Nikon 5100 (NPL)``, …)."""


def register(registry: dict[str, DatasetEntry], name: str, source: str, licence: str):
    """Decorator registering a loader under ``name`` in ``registry``."""

    def decorate(loader: Callable[[], SpectralSet]) -> Callable[[], SpectralSet]:
        registry[name] = DatasetEntry(name, loader, source, licence)
        return loader

    return decorate


def is_bundled(name: str) -> bool:
    """Whether ``name`` is a bundled reflectance set's or camera's (not a user's file)."""
    name = str(name).strip()
    return lookup(REGISTRY_REFLECTANCES, name) is not None or lookup(REGISTRY_CAMERAS, name) is not None


def lookup(registry: dict[str, DatasetEntry], name: str) -> DatasetEntry | None:
    """
    The entry called ``name`` (case and spacing insensitive), or ``None``.

    A miss is not an error here; callers raise :func:`unknown` for it.
    """

    def key(text: str) -> str:
        return " ".join(text.lower().split())

    for entry_name, entry in registry.items():
        if key(entry_name) == key(name):
            return entry
    return None


def unknown(registry: dict[str, DatasetEntry], name: str, what: str, hint: str) -> SkinrenderError:
    """The error for an unknown name: it lists the names that exist."""
    known = ", ".join(f"'{n}'" for n in registry)
    return SkinrenderError(f"unknown {what} {name!r}; known: {known}; {hint}")


def read_bundled_csv(filename: str, sha256: str, kind: str = "reflectance"):
    """
    Read a CSV bundled in :data:`ROOT_RESOURCES`, checking its SHA-256 first.

    An accidental edit of a bundled table is caught here rather than giving
    silently different results.
    """

    path = ROOT_RESOURCES / filename
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    if digest != sha256:
        raise SkinrenderError(
            f"bundled dataset {path} has SHA-256 {digest}, expected {sha256}: the file was "
            f"modified; rebuild it with the script under tools/"
        )
    return read_spectra_csv(path, kind=kind)
