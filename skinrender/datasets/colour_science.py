"""
colour-science datasets
=======================

Data that the colour-science package ships, read from the installed package
(nothing copied): BSD-3-Clause, data from the cited measurements.

-   ``macbeth``: the 24 ColorChecker patches measured by N. Ohta
    (``SDS_COLOURCHECKERS["ColorChecker N Ohta"]``), 380–780 nm / 5 nm.
-   cameras ``Nikon 5100 (NPL)`` and ``Sigma SDMerill (NPL)`` (Darrodi et al.
    2015) and ``Canon EOS 5D Mark II`` (rawtoaces, AMPAS).

References
----------
-   :cite:`Ohta1997` : Ohta, N. (1997). The basis of color reproduction
    engineering (ColorChecker spectral data as shipped by colour-science).
-   :cite:`Darrodi2015a` : Darrodi, M. M., Finlayson, G., Goodman, T., &
    Mackiewicz, M. (2015). Reference data set for camera spectral sensitivity
    estimation. JOSA A, 32(3), 381.
-   :cite:`Mansencal2024` : colour-science developers. Colour (Python package).
"""

from __future__ import annotations

import os

import numpy as np

from .registry import REGISTRY_CAMERAS, REGISTRY_REFLECTANCES, SpectralSet, register

__all__ = ["sds_macbeth", "msds_camera_canon"]

LICENCE_COLOUR = "BSD-3-Clause (colour-science package data)"
SOURCE_MACBETH = "ColorChecker 24 patches measured by N. Ohta, colour-science SDS_COLOURCHECKERS['ColorChecker N Ohta']"


@register(REGISTRY_REFLECTANCES, "macbeth", SOURCE_MACBETH, LICENCE_COLOUR)
def sds_macbeth() -> SpectralSet:
    """The 24 ColorChecker (Macbeth) patches, 380–780 nm every 5 nm."""
    import colour

    patches = colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"]
    names = tuple(patches.keys())
    first = patches[names[0]]
    values = np.array([patches[name].values for name in names])
    return SpectralSet("macbeth", np.asarray(first.wavelengths, float), values, names, SOURCE_MACBETH, LICENCE_COLOUR)


def _camera_loader(name: str):
    def load() -> SpectralSet:
        from colour.characterisation import MSDS_CAMERA_SENSITIVITIES

        msds = MSDS_CAMERA_SENSITIVITIES[name]
        return SpectralSet(
            name, np.asarray(msds.wavelengths, float), np.asarray(msds.values, float).T,
            ("R", "G", "B"), REGISTRY_CAMERAS[name].source, LICENCE_COLOUR,
            extrapolation="zero", kind="sensitivity",
        )

    return load


for _name in ("Nikon 5100 (NPL)", "Sigma SDMerill (NPL)"):
    register(
        REGISTRY_CAMERAS, _name,
        f"{_name}: Darrodi et al. 2015 (JOSA A 32:381), colour-science MSDS_CAMERA_SENSITIVITIES",
        LICENCE_COLOUR,
    )(_camera_loader(_name))

SOURCE_CANON = "Canon EOS 5D Mark II: AMPAS rawtoaces, colour-science CANON_EOS_5DMark_II_RGB_Sensitivities.csv"


@register(REGISTRY_CAMERAS, "Canon EOS 5D Mark II", SOURCE_CANON, LICENCE_COLOUR + " / AMPAS rawtoaces")
def msds_camera_canon() -> SpectralSet:
    """Canon EOS 5D Mark II sensitivities from rawtoaces, 380–780 nm every 5 nm."""
    from colour.characterisation.aces_it import ROOT_RESOURCES_RAWTOACES

    from ..spectral_csv import read_spectra_csv

    table = read_spectra_csv(
        os.path.join(ROOT_RESOURCES_RAWTOACES, "CANON_EOS_5DMark_II_RGB_Sensitivities.csv"),
        kind="sensitivity", expected_columns=3,
    )
    return SpectralSet(
        "Canon EOS 5D Mark II", table.wavelengths, table.values, ("R", "G", "B"), SOURCE_CANON,
        LICENCE_COLOUR + " / AMPAS rawtoaces", extrapolation="zero", kind="sensitivity",
    )

