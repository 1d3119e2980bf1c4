"""
A design's inputs as the command line takes them
================================================

:func:`design_inputs`: the skin and Munsell sets of a search (:func:`~skinrender.design.search.search`) or a
design (:func:`~skinrender.design.optimise.optimise_camera`) by name, CSV path or ``SpectralSet`` as well as
arrays, the illuminant set as ``--illuminants`` text as well as kelvin, and the noisy setting checked, each
refusal naming its argument: what ``skinrender search`` and ``design`` take, from Python.
"""

from __future__ import annotations

from ..datasets import reflectances
from ..datasets.registry import SpectralSet
from ..errors import SkinrenderError
from ..evaluation.gamut import illuminant_temperatures
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .noise_aware import NoisySetting

__all__ = ["design_inputs"]


def design_inputs(skin, munsell, illuminants, grid: WavelengthGrid = GRID_DEFAULT, noisy=None) -> tuple:
    """
    A search's or a design's inputs as the CLI takes them: ``skin`` and ``munsell`` as reflectance sets (a name, a
    CSV path, a ``SpectralSet``: resampled onto ``grid``) or arrays on ``grid`` (as they are); ``illuminants`` as
    numbers (K) or ``--illuminants`` text (``paper``, ``2000,3300,A``); ``noisy`` ``None`` or a
    :class:`~skinrender.design.noise_aware.NoisySetting`. Each refusal names its argument.
    """
    def on_grid(reflectance, name):
        if not isinstance(reflectance, (str, SpectralSet)):
            return reflectance
        try:
            return reflectances(reflectance).on(grid)
        except SkinrenderError as error:
            raise (error.reworded(role=name) if error.role == "reflectance" else error if error.role
                   else error.reworded(f"{name}: {error.message}", role=name)) from None

    if noisy is not None and not isinstance(noisy, NoisySetting):
        raise SkinrenderError(f"noisy must be a NoisySetting (skinrender.design.noise_aware) or None, got {noisy!r}",
                              role="noisy")
    temperatures = illuminant_temperatures(illuminants)
    return on_grid(skin, "skin"), on_grid(munsell, "munsell"), temperatures
