"""
Psychtoolbox-3 datasets
=======================

Reflectances and a camera from Psychtoolbox-3's colorimetric MAT files, bundled
as CSV (``tools/build_psychtoolbox_data.py`` rebuilds them from Debian's
``psychtoolbox-3-common``); MIT (Expat) licence, see
``resources/LICENCE-psychtoolbox.txt``.

-   ``vrhel``: the 170 surfaces of Vrhel et al. (1994), 390–730 nm / 2 nm.
-   ``skin``: the 30 of them labelled human skin (labels starting "skin").
-   ``vrhel-nonskin``: the other 140.
-   ``munsell-nickerson``: 462 Munsell papers, 380–780 nm / 5 nm.
-   camera ``Kodak DCS-200``: RGB sensitivities, 380–780 nm / 5 nm.

References
----------
-   :cite:`Vrhel1994` : Vrhel, M. J., Gershon, R., & Iwan, L. S. (1994).
    Measurement and analysis of object reflectance spectra. Color Research and
    Application, 19(1), 4–9.
-   :cite:`Brainard1997` : Brainard, D. H. (1997). The Psychophysics Toolbox.
    Spatial Vision, 10, 433–436.
"""

from __future__ import annotations

import numpy as np

from .registry import REGISTRY_CAMERAS, REGISTRY_REFLECTANCES, SpectralSet, read_bundled_csv, register

__all__ = ["sds_vrhel", "sds_skin_vrhel", "sds_vrhel_nonskin", "sds_munsell_nickerson", "msds_kodak_dcs200"]

LICENCE_PSYCHTOOLBOX = "MIT (Expat), Psychtoolbox-3; see resources/LICENCE-psychtoolbox.txt"
SOURCE_VRHEL = (
    "Vrhel, Gershon & Iwan 1994 (Color Res. Appl. 19:4), sur_vrhel.mat of Psychtoolbox-3 "
    "(Debian psychtoolbox-3-common)"
)
SHA256_VRHEL = "a92939ffcb13fc73dfbf5b128b14f5471c7663250745d7f8c4e0e7edec664877"
SHA256_NICKERSON = "28b32a98675f9091a92c4a45d05696f55d15692d3d6ad7e8be4baf098c32e2ef"
SHA256_DCS200 = "618af85bda8e11d475fef10ff622d6fe127b97907f1c57094b460ca75a9f94a9"


@register(REGISTRY_REFLECTANCES, "vrhel", SOURCE_VRHEL, LICENCE_PSYCHTOOLBOX)
def sds_vrhel() -> SpectralSet:
    """The 170 Vrhel surfaces (natural, man-made, skin, hair), 390–730 nm every 2 nm."""
    table = read_bundled_csv("vrhel_surfaces.csv", SHA256_VRHEL)
    return SpectralSet(
        "vrhel", table.wavelengths, table.values, table.names, SOURCE_VRHEL, LICENCE_PSYCHTOOLBOX
    )


def _is_skin(name: str) -> bool:
    # names are "<index> <label>"; skin labels start with "skin" (not "peach skin")
    return name.split(" ", 1)[1].lower().startswith("skin")


@register(REGISTRY_REFLECTANCES, "skin", SOURCE_VRHEL + ", the 30 surfaces labelled skin", LICENCE_PSYCHTOOLBOX)
def sds_skin_vrhel() -> SpectralSet:
    """The 30 human skin spectra among the Vrhel surfaces."""
    vrhel = sds_vrhel()
    mask = np.array([_is_skin(name) for name in vrhel.names])
    return vrhel.subset(mask, "skin")


@register(
    REGISTRY_REFLECTANCES, "vrhel-nonskin", SOURCE_VRHEL + ", the 140 surfaces not labelled skin",
    LICENCE_PSYCHTOOLBOX,
)
def sds_vrhel_nonskin() -> SpectralSet:
    """The 140 Vrhel surfaces that are not skin (hair, wood, food, fabrics, plants …)."""
    vrhel = sds_vrhel()
    mask = np.array([not _is_skin(name) for name in vrhel.names])
    return vrhel.subset(mask, "vrhel-nonskin")


SOURCE_NICKERSON = "Nickerson's 462 Munsell papers, sur_nickerson.mat of Psychtoolbox-3 (Debian psychtoolbox-3-common)"


@register(REGISTRY_REFLECTANCES, "munsell-nickerson", SOURCE_NICKERSON, LICENCE_PSYCHTOOLBOX)
def sds_munsell_nickerson() -> SpectralSet:
    """Nickerson's 462 Munsell papers, 380–780 nm every 5 nm."""
    table = read_bundled_csv("nickerson_munsell.csv", SHA256_NICKERSON)
    return SpectralSet(
        "munsell-nickerson", table.wavelengths, table.values, table.names, SOURCE_NICKERSON,
        LICENCE_PSYCHTOOLBOX,
    )


SOURCE_DCS200 = "Kodak DCS-200 sensitivities, T_DCS200.mat of Psychtoolbox-3 (Debian psychtoolbox-3-common)"


@register(REGISTRY_CAMERAS, "Kodak DCS-200", SOURCE_DCS200, LICENCE_PSYCHTOOLBOX)
def msds_kodak_dcs200() -> SpectralSet:
    """Kodak DCS-200 RGB sensitivities, relative units, 380–780 nm every 5 nm."""
    table = read_bundled_csv("camera_kodak_dcs200.csv", SHA256_DCS200, kind="sensitivity")
    return SpectralSet(
        "Kodak DCS-200", table.wavelengths, table.values, ("R", "G", "B"), SOURCE_DCS200,
        LICENCE_PSYCHTOOLBOX, extrapolation="zero", kind="sensitivity",
    )
