"""
The band basis of a multispectral render
========================================

A spectral render records, instead of a camera's three channels, one
channel per band of a uniform wavelength grid (the *bands*): band ``j`` is
the piecewise-linear "hat" ``h_j(λ)``, 1 at ``λ_j`` and falling linearly to 0
at its neighbours ``λ_j ± Δ`` (the end bands are half hats). Its ``specfilm``
channel holds ``B_j = ∫ L(λ) h_j(λ) dλ`` (W·m⁻²·sr⁻¹).

Why hats: a sensitivity ``s_k`` given on the band grid and linearly
interpolated between its samples *is* ``Σ_j s_k(λ_j) h_j(λ)``, so
``∫ L s_k dλ = Σ_j s_k(λ_j) B_j`` exactly: a camera on the band grid is
represented without error, and Eq. 4 being linear in the camera's curves,
every camera's image is the bands times its ``(3, N)`` matrix
(:func:`projection`). A curve not on the grid (a gbell every 1 nm against
5 nm bands) is represented by its samples on the bands, linearly
interpolated; the error this makes is measured (``docs/spectral.md``).

The hats sum to 1 everywhere on the grid, so ``specfilm``, which samples
wavelengths in proportion to the sum of its channels' curves, samples them
uniformly over the bands: a narrow camera channel gets fewer wavelength
samples than in a render of that camera alone (``bench render --spectral``
measures what that costs).

-   :data:`BANDS_DEFAULT`, :data:`BANDS_MAX`, :func:`parse_bands`,
    :func:`check_bands`: the band grid, its cap and its range.
-   :func:`band_names`, :func:`hats`, :func:`film_channels`: the channels.
-   :func:`band_integrals`: ``∫ f h_j dλ`` of a tabulated spectrum (the analytic
    whites).
-   :func:`projection`: a camera's ``(3, N)`` matrix, the camera checked
    against the bands.
-   :func:`estimate`, :data:`SPECTRAL_BYTES_MAX`: a spectral render's memory
    and time, refused beyond their caps.

Units: wavelengths nm; band values W·m⁻²·sr⁻¹ (radiance integrated over a
hat); sensitivities as the camera gives them.
"""

from __future__ import annotations

import functools

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from ..model.camera import Camera
from ..spectra import WavelengthGrid

__all__ = ["BANDS_DEFAULT", "BANDS_MAX", "SPECTRAL_BYTES_MAX", "BAND_COST", "BAND_COMPILE_S", "parse_bands",
           "bands_text", "check_bands", "band_names", "hats", "film_channels", "band_integrals", "projection", "estimate"]

BANDS_DEFAULT = WavelengthGrid(400.0, 700.0, 5.0)
"""The default bands: 400–700 nm every 5 nm (61 bands)."""

BANDS_MAX = 401
"""Most bands one spectral render may record (1 nm over 380–780 nm): Mitsuba sets no limit on a ``specfilm``'s
channels, but its kernel grows with them: the first render of the face compiled for 13.6 s at 301 bands against
2.0 s at 61 (measured, ``docs/spectral.md``)."""

SPECTRAL_BYTES_MAX = 4 * 2**30
"""Most memory a spectral render's image may take (:func:`estimate`), bytes."""

BAND_COST = (0.083, 0.66)
"""A spectral render's time per sample is ``1 + a · N^b`` times a three-channel render's (``N`` bands, ``(a,
b)`` these): fitted to the face at 128 px, 64 spp, direct (2.25× at 61 bands, 4.6× at 301, measured on one
core, ``docs/spectral.md``)."""

BAND_COMPILE_S = 0.045
"""Seconds of kernel compilation per band of a spectral render's first render (13.6 s at 301 bands, measured)."""

BYTES_PER_PIXEL_BAND = 24
"""Bytes a spectral render holds per pixel and band: Mitsuba's film block and developed image (float32 each),
the image returned (float32) and a float64 projection's operand."""


def parse_bands(text) -> WavelengthGrid:
    """
    ``START:END:STEP`` (nm) as the band grid, at most :data:`BANDS_MAX` bands; a one-line error naming
    ``bands`` otherwise.

    >>> parse_bands("400:700:5").size
    61
    """
    if isinstance(text, WavelengthGrid):
        bands = text
    else:
        try:
            bands = WavelengthGrid.parse(str(text))
        except SkinrenderError as error:
            raise error.reworded(f"bands: {error.message}", role="bands") from None
    if bands.size > BANDS_MAX:
        raise SkinrenderError(f"bands {bands} give {bands.size} bands, more than {BANDS_MAX} (each band is a film "
                              "channel: the kernel and its compilation grow with them); use a larger step",
                              role="bands")
    return bands


def bands_text(bands: WavelengthGrid) -> str:
    """
    The bands as ``START:END:STEP`` (nm), as ``--bands`` takes them.

    >>> bands_text(BANDS_DEFAULT)
    '400:700:5'
    """
    return f"{bands.start:g}:{bands.end:g}:{bands.step:g}"


def check_bands(bands: WavelengthGrid, grid: WavelengthGrid, what: str = "the lights and reflectances") -> None:
    """
    Refuse bands beyond ``grid``, the range over which the scene's lights and reflectances are tabulated
    (they are zero outside it: those bands would record nothing), naming both ranges.

    >>> check_bands(WavelengthGrid(400, 700, 5), WavelengthGrid(400, 700, 1))
    >>> check_bands(WavelengthGrid(380, 700, 5), WavelengthGrid(400, 700, 1))
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: bands 380–700 nm reach beyond 400–700 nm, the range of the lights and reflectances (zero outside it); choose bands inside it
    """
    if bands.start < grid.start - 1e-9 or bands.end > grid.end + 1e-9:
        raise SkinrenderError(f"bands {bands.start:g}–{bands.end:g} nm reach beyond {grid.start:g}–{grid.end:g} nm, "
                              f"the range of {what} (zero outside it); choose bands inside it", role="bands")


def band_names(bands: WavelengthGrid) -> tuple[str, ...]:
    """
    The EXR channel of each band, named by its wavelength.

    >>> band_names(WavelengthGrid(400, 410, 2.5))
    ('400nm', '402.5nm', '405nm', '407.5nm', '410nm')
    """
    return tuple(f"{value:g}nm" for value in np.round(bands.wavelengths, 6))


def hats(bands: WavelengthGrid) -> list[tuple[NDArrayFloat, NDArrayFloat]]:
    """
    Each band's hat as ``(wavelengths, values)``: 1 at the band, 0 at its neighbours (half hats at the ends).

    >>> [w.tolist() for w, v in hats(WavelengthGrid(400, 410, 5))]
    [[400.0, 405.0], [400.0, 405.0, 410.0], [405.0, 410.0]]
    """
    lam = bands.wavelengths
    out = []
    for j in range(lam.size):
        low, high = max(j - 1, 0), min(j + 1, lam.size - 1)
        wavelengths = lam[low:high + 1]
        out.append((wavelengths, (np.arange(low, high + 1) == j).astype(np.float64)))
    return out


def film_channels(bands: WavelengthGrid) -> dict:
    """
    The ``specfilm`` channels of the bands: name → Mitsuba ``regular`` spectrum of its hat (2 or 3 values over
    its support: evaluated without the search an ``irregular`` one needs; the same hat, measured to the float32
    rounding).

    >>> film_channels(WavelengthGrid(400, 410, 5))["405nm"]
    {'type': 'regular', 'wavelength_min': 400.0, 'wavelength_max': 410.0, 'values': '0,1,0'}
    """
    return {name: {"type": "regular", "wavelength_min": float(wavelengths[0]), "wavelength_max": float(wavelengths[-1]),
                   "values": ",".join(f"{value:g}" for value in values)}
            for name, (wavelengths, values) in zip(band_names(bands), hats(bands))}


def hat_matrix(bands: WavelengthGrid, wavelengths: NDArrayFloat) -> NDArrayFloat:
    """Every hat at ``wavelengths`` (nm), shape ``(bands, wavelengths)``; 0 outside the bands (cached: every
    camera seen through a render integrates its whites on the same wavelengths)."""
    return _hat_matrix(bands, np.asarray(wavelengths, dtype=np.float64).tobytes())


@functools.lru_cache(maxsize=8)
def _hat_matrix(bands: WavelengthGrid, data: bytes) -> NDArrayFloat:
    wavelengths, lam = np.frombuffer(data, dtype=np.float64), bands.wavelengths
    matrix = np.array([np.interp(wavelengths, lam, np.eye(lam.size)[j], left=0.0, right=0.0)
                       for j in range(lam.size)])
    matrix.setflags(write=False)
    return matrix


def band_integrals(wavelengths: NDArrayFloat, spectrum: NDArrayFloat, bands: WavelengthGrid) -> NDArrayFloat:
    """
    ``∫ f(λ) h_j(λ) dλ`` per band (trapezoid on ``wavelengths``, nm), as :func:`channel_integral
    <skinrender.rendering.face.document.channel_integral>` integrates a camera's channels: shape
    ``spectrum.shape[:-1] + (bands,)``, the unit of ``f`` times nm.

    >>> bands = WavelengthGrid(400, 700, 5)
    >>> fine = WavelengthGrid(400, 700, 0.1).wavelengths
    >>> round(float(band_integrals(fine, np.ones(fine.size), bands).sum()), 9)  # the hats sum to 1: 300 nm
    300.0
    """
    wavelengths = np.asarray(wavelengths, dtype=np.float64)
    weights = np.gradient(wavelengths) if wavelengths.size > 1 else np.ones(1)
    weights[[0, -1]] = np.diff(wavelengths)[[0, -1]] / 2
    return (np.asarray(spectrum, dtype=np.float64) * weights) @ hat_matrix(bands, wavelengths).T


def projection(cam: Camera, bands: WavelengthGrid, grid: WavelengthGrid) -> NDArrayFloat:
    """
    The camera's ``(3, bands)`` matrix: its sensitivities at the bands (with its CSV's extrapolation rule: a
    camera whose data do not cover the bands is refused, its range named). A camera sensitive on ``grid`` (the
    direct render's grid) outside the bands is refused too: a direct render of it would see light that the
    bands dropped.

    >>> from skinrender.model.camera import camera
    >>> projection(camera("gbell:9@450,540,610"), WavelengthGrid(400, 700, 5), WavelengthGrid(400, 700, 1)).shape
    (3, 61)
    """
    try:
        matrix = cam.sensitivities(bands)
    except SkinrenderError as error:
        raise error.reworded(f"camera {cam.name}: on the bands {bands}: {error.message}", role="camera") from None
    curves = cam.sensitivities(grid)
    outside = (grid.wavelengths < bands.start - 1e-9) | (grid.wavelengths > bands.end + 1e-9)
    seen = np.any(curves[:, outside] > 0, axis=0)
    if np.any(seen):
        where = grid.wavelengths[outside][seen]
        raise SkinrenderError(f"camera {cam.name} is sensitive at {where.min():g}–{where.max():g} nm, outside the bands "
                              f"{bands.start:g}–{bands.end:g} nm: a render of it on {grid.start:g}–{grid.end:g} nm "
                              "would see light the bands do not hold; render bands that cover its range",
                              role="camera")
    return np.asarray(matrix, dtype=np.float64)


def estimate(bands: WavelengthGrid, pixels: int, seconds_three: float) -> tuple[float, float]:
    """
    A spectral render's memory (bytes: :data:`BYTES_PER_PIXEL_BAND` per pixel and band) and time (s:
    ``seconds_three``, the time of a three-channel render of the same samples, times :data:`BAND_COST`'s
    factor, plus :data:`BAND_COMPILE_S` per band); refused beyond :data:`SPECTRAL_BYTES_MAX`, naming the bands,
    the pixels and the estimate.

    >>> memory, seconds = estimate(WavelengthGrid(400, 700, 5), 64 * 64, 0.1)
    >>> round(memory / 2**20, 1), round(seconds, 2)
    (5.7, 2.97)
    """
    memory = float(pixels) * bands.size * BYTES_PER_PIXEL_BAND
    if memory > SPECTRAL_BYTES_MAX:
        raise SkinrenderError(f"bands: {bands.size} bands × {pixels} pixels would take about {memory / 2**30:.3g} GiB "
                              f"(estimated, {BYTES_PER_PIXEL_BAND} bytes a pixel and band), more than the cap of "
                              f"{SPECTRAL_BYTES_MAX / 2**30:g} GiB; use fewer bands (a larger step) or a smaller image",
                              role="bands")
    a, b = BAND_COST
    return memory, seconds_three * (1.0 + a * bands.size**b) + BAND_COMPILE_S * bands.size
