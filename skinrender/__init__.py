"""
skinrender
==========

Design and validate three-channel cameras for skin detection under changing
light: the analytic camera model of Martinkauppi et al. (Eqs. 1–11), its
datasets, Stage 1 illuminant selection, and (in later modules) gamut
evaluation, spectral rendering and skin detection.

Units throughout: wavelength in nm, temperature in K, spectral radiance in
W·m⁻²·sr⁻¹·nm⁻¹, reflectance as a fraction in [0, 1], responses in output
units (255 for white at p = c).

Examples
--------
>>> import skinrender as sr
>>> cam = sr.camera("gbell:9@450,540,610")
>>> rgb = sr.response(cam, sr.reflectances("macbeth"), prevailing=2856, calibration=2300)
>>> rgb.shape
(24, 3)
"""

from __future__ import annotations

from .camera import (
    CHANNELS,
    NORMALISATIONS,
    Camera,
    camera,
    knee,
    measure,
    ncc,
    normalisation_factor,
    response,
    response_raw,
    white_coefficient,
)
from .constants import TEMPERATURES_PAPER
from .datasets import SpectralSet, list_cameras, list_reflectances, reflectances
from .errors import SkinrenderError
from .gamut import Gamut, gamut, gamut_all_calibrations, gamut_calibration, gamut_volume
from .illuminant import Illuminant, illuminant
from .illuminants import (
    illuminant_selection,
    illuminant_set,
    illuminant_track,
    select_illuminants,
)
from .spectra import GRID_DEFAULT, WavelengthGrid, gbell, impulse, planck, resample
# Submodules search, render and validate keep their names: their main
# functions are imported from them (from skinrender.render import render).
from .search import SearchResult
from .scene import ChartScene, load_scene
from .render import Rendering
from .validate import table1, validate_gamut
from .locus import SkinLocus, detect, skin_locus

__version__ = "0.1.0"

__all__ = [
    "CHANNELS",
    "GRID_DEFAULT",
    "NORMALISATIONS",
    "TEMPERATURES_PAPER",
    "Camera",
    "Illuminant",
    "SkinrenderError",
    "SpectralSet",
    "WavelengthGrid",
    "Gamut",
    "camera",
    "gamut",
    "gamut_all_calibrations",
    "gamut_calibration",
    "gamut_volume",
    "gbell",
    "illuminant",
    "illuminant_selection",
    "illuminant_set",
    "illuminant_track",
    "impulse",
    "knee",
    "list_cameras",
    "list_reflectances",
    "measure",
    "ncc",
    "normalisation_factor",
    "planck",
    "reflectances",
    "resample",
    "response",
    "response_raw",
    "select_illuminants",
    "white_coefficient",
    "SearchResult",
    "ChartScene",
    "load_scene",
    "Rendering",
    "validate_gamut",
    "table1",
    "SkinLocus",
    "skin_locus",
    "detect",
]
