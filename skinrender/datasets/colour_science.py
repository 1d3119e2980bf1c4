"""
colour-science datasets
=======================

Data that the colour-science package ships (BSD-3-Clause, data from the cited
measurements), read without importing colour (its import takes over a second):

-   ``macbeth``: the 24 ColorChecker patches measured by N. Ohta
    (``SDS_COLOURCHECKERS["ColorChecker N Ohta"]``), 380–780 nm / 5 nm.
-   cameras ``Nikon 5100 (NPL)`` and ``Sigma SDMerill (NPL)`` (Darrodi et al.
    2015; ``MSDS_CAMERA_SENSITIVITIES``).
-   the CIE 1924 photopic V(λ) (``SDS_LEFS_PHOTOPIC``), 360–830 nm / 1 nm, for lux.

These are bundled as CSV, written from colour-science 0.4.7 by
``tools/build_colour_data.py`` with every float64 exact; see
``resources/LICENCE-colour-science.txt``.

-   camera ``Canon EOS 5D Mark II`` (rawtoaces, AMPAS): read in place from the CSV
    in the installed colour-science package, found without importing it.

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

import importlib.util
from pathlib import Path

from .registry import REGISTRY_CAMERAS, REGISTRY_REFLECTANCES, SpectralSet, read_bundled_csv, register

__all__ = ["sds_macbeth", "msds_camera_canon", "path_colour_rawtoaces", "photopic_v_cie1924"]

LICENCE_COLOUR = "BSD-3-Clause (colour-science package data)"
SOURCE_MACBETH = "ColorChecker 24 patches measured by N. Ohta, colour-science SDS_COLOURCHECKERS['ColorChecker N Ohta']"
VERSION_COLOUR = "0.4.7"
"""The colour-science version the bundled CSVs were written from (``tools/build_colour_data.py``)."""
SHA256_MACBETH = "480703adf5b1c024a0108bf4a5b8cbd2642a2d1988ce5bad3584011be6c04347"
BUNDLED_CAMERAS = {
    "Nikon 5100 (NPL)": ("camera_nikon_5100_npl.csv", "6c654c7b6b9a1d49caf078ff31827a680c17da6c02d62721e6e590568013b6a1"),
    "Sigma SDMerill (NPL)": (
        "camera_sigma_sdmerill_npl.csv", "6b1925bfddce9941cca6cde80e118d1004306ffeec206330e6ad3299732c3b3a",
    ),
}
"""Camera name → (bundled CSV, its SHA-256)."""
SHA256_PHOTOPIC = "6e71d5d2c0ecb319416f713a09d525b3ffa6add006367397690a8069d764c4ce"
SOURCE_PHOTOPIC = ("CIE 1924 photopic luminous efficiency V(λ), colour-science "
                   "SDS_LEFS_PHOTOPIC['CIE 1924 Photopic Standard Observer']")


@register(REGISTRY_REFLECTANCES, "macbeth", SOURCE_MACBETH, LICENCE_COLOUR)
def sds_macbeth() -> SpectralSet:
    """The 24 ColorChecker (Macbeth) patches, 380–780 nm every 5 nm."""
    table = read_bundled_csv("colourchecker_n_ohta.csv", SHA256_MACBETH)
    return SpectralSet("macbeth", table.wavelengths, table.values, table.names, SOURCE_MACBETH, LICENCE_COLOUR)


def photopic_v_cie1924() -> SpectralSet:
    """
    The CIE 1924 photopic luminous efficiency V(λ), unitless, 360–830 nm every 1 nm (one spectrum, ``V``).

    Bundled from colour-science (``tools/build_colour_data.py``) so that working in lux does not import colour.

    Examples
    --------
    >>> v = photopic_v_cie1924()
    >>> float(v.wavelengths[v.values[0].argmax()]), float(v.values.max())
    (555.0, 1.0)
    """
    table = read_bundled_csv("cie1924_photopic.csv", SHA256_PHOTOPIC, kind="sensitivity")
    return SpectralSet("CIE 1924 V", table.wavelengths, table.values, table.names, SOURCE_PHOTOPIC, LICENCE_COLOUR,
                       kind="sensitivity")


def _camera_loader(name: str):
    def load() -> SpectralSet:
        table = read_bundled_csv(*BUNDLED_CAMERAS[name], kind="sensitivity")
        return SpectralSet(
            name, table.wavelengths, table.values, ("R", "G", "B"), REGISTRY_CAMERAS[name].source, LICENCE_COLOUR,
            extrapolation="zero", kind="sensitivity",
        )

    return load


for _name in BUNDLED_CAMERAS:
    register(
        REGISTRY_CAMERAS, _name,
        f"{_name}: Darrodi et al. 2015 (JOSA A 32:381), colour-science MSDS_CAMERA_SENSITIVITIES",
        LICENCE_COLOUR,
    )(_camera_loader(_name))

def path_colour_rawtoaces() -> Path:
    """Folder of the rawtoaces CSVs in the installed colour-science package, found without importing colour
    (the folder ``colour.characterisation.aces_it.ROOT_RESOURCES_RAWTOACES`` names)."""
    spec = importlib.util.find_spec("colour")
    return Path(spec.origin).parent / "characterisation" / "datasets" / "rawtoaces"


SOURCE_CANON = "Canon EOS 5D Mark II: AMPAS rawtoaces, colour-science CANON_EOS_5DMark_II_RGB_Sensitivities.csv"


@register(REGISTRY_CAMERAS, "Canon EOS 5D Mark II", SOURCE_CANON, LICENCE_COLOUR + " / AMPAS rawtoaces")
def msds_camera_canon() -> SpectralSet:
    """Canon EOS 5D Mark II sensitivities from rawtoaces, 380–780 nm every 5 nm."""
    from ..spectral_csv import read_spectra_csv

    table = read_spectra_csv(
        path_colour_rawtoaces() / "CANON_EOS_5DMark_II_RGB_Sensitivities.csv",
        kind="sensitivity", expected_columns=3,
    )
    return SpectralSet(
        "Canon EOS 5D Mark II", table.wavelengths, table.values, ("R", "G", "B"), SOURCE_CANON,
        LICENCE_COLOUR + " / AMPAS rawtoaces", extrapolation="zero", kind="sensitivity",
    )

