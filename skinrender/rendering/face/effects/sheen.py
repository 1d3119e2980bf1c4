"""
Sheen
=====

The skin under a rough dielectric coat (``roughplastic``, GGX) over the same
diffuse spectrum: the oily surface's highlights in the light's colour.

-   :data:`SHEEN`: the effect; :data:`SHEEN_ALPHA`, :data:`SHEEN_IOR`,
    :data:`SHEEN_NONLINEAR`: the coat.
-   :func:`dichromatic_colours`: the body and light colours its check tests
    against.

Its limit, the dichromatic model :cite:`Shafer1985`: under one light each
skin pixel is a non-negative mix of the body colour ``∫ ρ E x_k`` and the
light's colour ``∫ E x_k`` (a spectrally flat Fresnel term), so it lies in
their plane (:func:`~skinrender.rendering.face.limits.check_dichromatic`).
It replaces ``direct``'s shading check in a level with a sheen.

References
----------
-   :cite:`Weyrich2006` : T. Weyrich, W. Matusik, H. Pfister, B. Bickel,
    C. Donner, C. Tu, J. McAndless, J. Lee, A. Ngan, H. W. Jensen and
    M. Gross (2006). Analysis of human faces using a measurement-based skin
    reflectance model. ACM Transactions on Graphics 25(3), 1013–1024.
-   :cite:`Donner2006` : C. Donner and H. W. Jensen (2006). A spectral BSSRDF
    for shading human skin. Eurographics Symposium on Rendering, 409–417.
-   :cite:`Shafer1985` : S. A. Shafer (1985). Using color to separate
    reflection components. Color Research & Application 10(4), 210–218.
"""

from __future__ import annotations

import numpy as np

from ....constants import CONSTANT_OUTPUT_SCALE
from ....hints import NDArrayFloat
from ....model.response import gain
from ....spectra import GRID_DEFAULT
from ..document import channel_integral, light_irradiance
from ..limits import check_dichromatic
from ..scene import Light, skin_reflectance_of
from .base import Effect, Limits, Replicates, Setup, spectrum, twosided

__all__ = ["SHEEN", "SHEEN_ALPHA", "SHEEN_IOR", "SHEEN_NONLINEAR", "dichromatic_colours"]

SHEEN_ALPHA = 0.35
"""GGX roughness α of the skin's coat: :cite:`Weyrich2006` fit Torrance–Sparrow roughness 0.3–0.45 to faces."""

SHEEN_IOR = 1.4
"""Refractive index of the skin's surface (:cite:`Donner2006` use 1.4)."""

SHEEN_NONLINEAR = False
"""``roughplastic``'s ``nonlinear``: whether the coat's internal scattering is on (it is not: the diffuse
spectrum is the skin's reflectance as it is)."""


def _coated(material: dict, reflectance: NDArrayFloat, setup: Setup) -> dict:
    return {"bsdf": twosided({"type": "roughplastic", "distribution": "ggx", "alpha": SHEEN_ALPHA,
                              "int_ior": SHEEN_IOR, "ext_ior": 1.0, "nonlinear": SHEEN_NONLINEAR,
                              "diffuse_reflectance": spectrum(setup.grid, reflectance)})}


def dichromatic_colours(rendering, light: Light) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    The body colour ``∫ ρ E x_k`` of the rendering's skin and the colour ``∫ E x_k`` of ``light``,
    balanced with the rendering's Eq. 4 gain (of its noise-free whites), output units, ``(3,)`` each.
    """
    lam, irradiance = light_irradiance(light, GRID_DEFAULT)
    rho = np.interp(lam, GRID_DEFAULT.wavelengths, skin_reflectance_of(rendering.skin, GRID_DEFAULT, "skin"))
    g = gain(rendering.white_prevailing, rendering.white_calibration, scale=CONSTANT_OUTPUT_SCALE)
    cam = rendering.camera
    return (g * channel_integral(cam, GRID_DEFAULT, lam, rho * irradiance),
            g * channel_integral(cam, GRID_DEFAULT, lam, irradiance))


def _check(replicates: Replicates):
    r = replicates
    (light,) = r.lights.values()
    return check_dichromatic(r.images, r.labels, *dichromatic_colours(r.first, light), r.usable, r.bias, r.floor)


SHEEN = Effect(
    "sheen",
    "the skin under a rough dielectric coat (roughplastic, GGX) over the same diffuse spectrum: the oily "
    "surface's highlights in the light's colour (the dichromatic model)",
    skin=_coated,
    limits=Limits(check=_check, why="the coat adds the light's colour at highlights: the dichromatic plane is the "
                                    "test"),
)
