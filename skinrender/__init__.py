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

import importlib as _importlib  # noqa: E402 - after the Ctrl-C guard
import importlib.util as _importlib_util
from typing import TYPE_CHECKING

_WHERE = {
    "TEMPERATURES_PAPER": "constants",
    **dict.fromkeys(("SpectralSet", "list_cameras", "list_reflectances", "reflectances"), "datasets"),
    **dict.fromkeys(("Design", "optimise_camera"), "design.optimise"),
    **dict.fromkeys(("SearchResult", "search"), "design.search"),
    "SkinrenderError": "errors",
    **dict.fromkeys(("Detection", "detect"), "evaluation.detection"),
    **dict.fromkeys(("Gamut", "gamut", "gamut_all_calibrations", "gamut_calibration", "gamut_volume"),
                    "evaluation.gamut"),
    **dict.fromkeys(("SkinLocus", "skin_locus"), "evaluation.locus"),
    "Verdict": "evaluation.verdict",
    **dict.fromkeys(("CHANNELS", "Camera", "camera"), "model.camera"),
    **dict.fromkeys(("Illuminant", "illuminant"), "model.illuminant"),
    **dict.fromkeys(("measure", "ncc"), "model.chromaticity"),
    "NORMALISATIONS": "model.factors",
    **dict.fromkeys(("gain", "knee", "normalisation_factor", "response", "response_raw",
                     "white_coefficient"), "model.response"),
    **dict.fromkeys(("illuminant_selection", "illuminant_set", "illuminant_track", "select_illuminants"),
                    "model.stage1"),
    "Rendering": "rendering.balance",
    **dict.fromkeys(("load_scene", "render", "render_cameras", "validate"), "rendering.dispatch"),
    "read_spectral": "rendering.spectral_files",
    "SpectralImage": "rendering.spectral_image",
    "ChartScene": "rendering.scene",
    "RenderSettings": "rendering.settings",
    **dict.fromkeys(("Validation", "validate_gamut"), "rendering.validation"),
    **dict.fromkeys(("GRID_DEFAULT", "WavelengthGrid", "gbell", "impulse", "planck", "resample"), "spectra"),
    "table1": "studies.paper.tables",
}
"""Each public name → the module (below ``skinrender``) that defines it: imported on first use (PEP 562), so
that ``import skinrender`` (and the pytest plugin, which every pytest session of a user loads) imports nothing
but this file; ``skinrender.NAME`` and ``from skinrender import NAME`` read as before."""


def __getattr__(name: str):
    """A public name (:data:`_WHERE`) or a layer module, imported on first use and kept."""
    if name in _WHERE:
        value = getattr(_importlib.import_module(f"{__name__}.{_WHERE[name]}"), name)
    elif not name.startswith("_") and _importlib_util.find_spec(f"{__name__}.{name}") is not None:
        value = _importlib.import_module(f"{__name__}.{name}")  # a layer module, as an import of it would set
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})


if TYPE_CHECKING:  # the names for type checkers and editors, as they are imported on first use
    from .constants import TEMPERATURES_PAPER  # noqa: F401
    from .datasets import SpectralSet, list_cameras, list_reflectances, reflectances  # noqa: F401
    from .design.optimise import Design, optimise_camera  # noqa: F401
    from .design.search import SearchResult, search  # noqa: F401
    from .errors import SkinrenderError  # noqa: F401
    from .evaluation.detection import Detection, detect  # noqa: F401
    from .evaluation.gamut import (Gamut, gamut, gamut_all_calibrations, gamut_calibration,  # noqa: F401
                                   gamut_volume)
    from .evaluation.locus import SkinLocus, skin_locus  # noqa: F401
    from .evaluation.verdict import Verdict  # noqa: F401
    from .model.camera import CHANNELS, Camera, camera  # noqa: F401
    from .model.chromaticity import measure, ncc  # noqa: F401
    from .model.illuminant import Illuminant, illuminant  # noqa: F401
    from .model.factors import NORMALISATIONS  # noqa: F401
    from .model.response import (gain, knee, normalisation_factor, response, response_raw,  # noqa: F401
                                 white_coefficient)
    from .model.stage1 import (illuminant_selection, illuminant_set, illuminant_track,  # noqa: F401
                               select_illuminants)
    from .rendering.balance import Rendering  # noqa: F401
    from .rendering.dispatch import load_scene, render, render_cameras, validate  # noqa: F401
    from .rendering.spectral_files import read_spectral  # noqa: F401
    from .rendering.spectral_image import SpectralImage  # noqa: F401
    from .rendering.scene import ChartScene  # noqa: F401
    from .rendering.settings import RenderSettings  # noqa: F401
    from .rendering.validation import Validation, validate_gamut  # noqa: F401
    from .spectra import GRID_DEFAULT, WavelengthGrid, gbell, impulse, planck, resample  # noqa: F401
    from .studies.paper.tables import table1  # noqa: F401

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
