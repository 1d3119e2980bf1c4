"""
skinrender
==========

Design and validate three-channel cameras for skin detection under changing
light: the analytic camera model of Martinkauppi et al. (Eqs. 1–11), its
datasets, Stage 1 illuminant selection, gamut evaluation and the Stage 3
sensor search, the skin locus and detection, continuous camera design, and
spectral rendering with Mitsuba 3 validated against the analytic model.

The package is built in layers, each importing only from those below it
(import-linter contracts in ``pyproject.toml`` keep it so):

1.  :mod:`~skinrender.spectra`, :mod:`~skinrender.constants`,
    :mod:`~skinrender.errors`, :mod:`~skinrender.hints`,
    :mod:`~skinrender.methods`, :mod:`~skinrender.extras`;
2.  :mod:`~skinrender.datasets`;
3.  :mod:`~skinrender.model`: illuminants, camera, Eqs. 1–11, Stage 1;
4.  :mod:`~skinrender.evaluation`: gamut, locus, detection;
5.  :mod:`~skinrender.design` (bank, criteria, search, optimisation) and,
    independent of it, :mod:`~skinrender.rendering`;
6.  :mod:`~skinrender.studies`: tables, figures, reproduction, benchmarks;
7.  :mod:`~skinrender.cli`.

A name ``skinrender.<name>`` is either one of these layer modules or a public
function, class or constant (below); never both.

Units throughout: wavelength in nm, temperature in K, spectral radiance in
W·m⁻²·sr⁻¹·nm⁻¹, reflectance as a fraction in [0, 1], responses in output
units (255 for white at p = c).

A render's validation (:func:`validate`) returns a :class:`Validation` whose
``verdict`` (a :class:`Verdict`: pass, fail or inconclusive) says whether every
patch is shown within a relative tolerance of the analytic model, with the
``bound`` it reached and the ``spp_needed`` to pass.

Examples
--------
>>> import skinrender as sr
>>> cam = sr.camera("gbell:9@450,540,610")
>>> rgb = sr.response(cam, sr.reflectances("macbeth"), prevailing=2856, calibration=2300)
>>> rgb.shape
(24, 3)
"""

from __future__ import annotations

from ._interrupt import quiet_while_starting as _quiet_while_starting

_quiet_while_starting()  # the command line only: Ctrl-C while it imports is one line and status 130, no traceback

from .constants import TEMPERATURES_PAPER  # noqa: E402 - after the Ctrl-C guard
from .datasets import SpectralSet, list_cameras, list_reflectances, reflectances
from .design.optimise import Design, optimise_camera
from .design.search import SearchResult, search
from .errors import SkinrenderError
from .evaluation.detection import Detection, detect
from .evaluation.gamut import Gamut, gamut, gamut_all_calibrations, gamut_calibration, gamut_volume
from .evaluation.locus import SkinLocus, skin_locus
from .evaluation.verdict import Verdict
from .model.camera import CHANNELS, Camera, camera
from .model.illuminant import Illuminant, illuminant
from .model.chromaticity import measure, ncc
from .model.response import (
    NORMALISATIONS,
    gain,
    knee,
    normalisation_factor,
    response,
    response_raw,
    white_coefficient,
)
from .model.stage1 import illuminant_selection, illuminant_set, illuminant_track, select_illuminants
from .rendering.balance import Rendering
from .rendering.dispatch import load_scene, render, render_cameras, validate
from .rendering.scene import ChartScene
from .rendering.settings import RenderSettings
from .rendering.spectral_files import read_spectral
from .rendering.spectral_image import SpectralImage
from .rendering.validation import Validation, validate_gamut
from .spectra import GRID_DEFAULT, WavelengthGrid, gbell, impulse, planck, resample
from .studies import labelled as _labelled  # noqa: F401 (registers the figures of Rendering and FaceRendering)
from .studies.paper.tables import table1

__version__ = "0.1.0"

__all__ = [
    "CHANNELS",
    "GRID_DEFAULT",
    "NORMALISATIONS",
    "TEMPERATURES_PAPER",
    "Camera",
    "ChartScene",
    "Design",
    "Detection",
    "Gamut",
    "Illuminant",
    "RenderSettings",
    "Rendering",
    "SearchResult",
    "SkinLocus",
    "SkinrenderError",
    "SpectralImage",
    "SpectralSet",
    "Validation",
    "Verdict",
    "WavelengthGrid",
    "camera",
    "detect",
    "gain",
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
    "load_scene",
    "measure",
    "ncc",
    "normalisation_factor",
    "optimise_camera",
    "planck",
    "read_spectral",
    "reflectances",
    "render",
    "render_cameras",
    "resample",
    "response",
    "response_raw",
    "search",
    "select_illuminants",
    "skin_locus",
    "table1",
    "validate",
    "validate_gamut",
    "white_coefficient",
]
