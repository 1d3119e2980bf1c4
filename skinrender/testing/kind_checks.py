"""
What a render regression check renders, by kind of scene
========================================================

:func:`skinrender.testing.regression.measure` takes the road of the scene's kind
(:func:`skinrender.rendering.kinds.by_kind`): :class:`ChartChecks` (a chart at its base level, through a camera or an
image sensor; several cameras through one spectral render) or :class:`FaceChecks` (replicates at any level).

-   :func:`chart_measurement`, :func:`chart_values`: a chart's patch means with their standard errors;
    :func:`white_relative_variance`: what the rendered whites add to them.
-   :func:`beyond_base`: whether a physics spec names more than a registry's base level.

Units: means and standard errors in Eq. 4 output units (255 for white at p = c); temperatures K.
"""

from __future__ import annotations

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat
from .measurement import Measurement, named_argument
from .replicates import measure_face

__all__ = ["SPP_CHART", "SPP_FACE", "ChartChecks", "FaceChecks", "chart_measurement", "chart_values",
           "white_relative_variance", "beyond_base"]

SPP_CHART = 64
"""Samples per pixel of a chart check unless given (a check ~0.2 s after the first; a 2 nm shift at z > 10)."""

SPP_FACE = 64
"""Samples per pixel of a face check unless given, over all :data:`~skinrender.testing.replicates.REPLICATES` (16 each)."""


def white_relative_variance(rendering) -> NDArrayFloat:
    """
    Per channel ``k``, the relative variance every patch of a chart render takes from its rendered whites.

    The image is ``v · WP · P_k / C_k`` with ``WP = 3 / Σ_j r_j``, ``r_j = W_j / C_j`` (the white reference's
    means under the prevailing and the calibration light), so ``δ ln image_k = δ ln P_k − Σ_j w_j δ ln W_j +
    Σ_j (w_j − [j = k]) δ ln C_j`` with ``w_j = r_j / Σ r``: ``wᵀ Σ_W w + a_kᵀ Σ_C a_k``, ``a_k = w − e_k``, where
    ``Σ_W``, ``Σ_C`` are the relative covariances of the whites' channel means (from their pixels: the channels
    of a pixel share its wavelength samples and are correlated, and the calibration white enters twice and partly
    cancels). At p = c (one render, ``WP = 1`` exactly) and for the other normalisations (a fixed ``F_p / F_c``)
    it is ``Σ_C[k, k]``. Measured: adding the terms in quadrature without the covariances, as
    :mod:`~skinrender.rendering.validation` does for its 5 σ, overstated the G channel's standard errors by ~16 %.
    """
    from ..model.response import uses_whites


    def relative_covariance(raw) -> NDArrayFloat:
        rows, columns = rendering.scene.patch_pixels(rendering.scene.white_index)
        pixels = raw.radiance[rows, columns].reshape(-1, 3)
        mean = pixels.mean(axis=0)
        return np.cov(pixels, rowvar=False) / len(pixels) / np.outer(mean, mean)

    analytic = rendering.info.get("white_calibration") == "analytic"  # a spectral render's: computed, exact
    sigma_c = 0.0 * relative_covariance(rendering.raw[-1]) if analytic else relative_covariance(rendering.raw[-1])
    if not uses_whites(rendering.normalization) or rendering.prevailing == rendering.calibration:
        return np.diagonal(sigma_c).copy()
    sigma_w = relative_covariance(rendering.raw[0])
    ratio = rendering.info["white_ratio"]
    w = ratio / ratio.sum()
    a = w[None, :] - np.eye(3)
    return w @ sigma_w @ w + np.einsum("ki,ij,kj->k", a, sigma_c, a)


def chart_measurement(chart, cam, prevailing, calibration, spp, seed, imager, illuminance, variant) -> Measurement:
    """A chart check's :class:`Measurement`: its request, as every front door builds it, rendered (through an image
    sensor with ``imager``) and reduced to its patch means (:func:`chart_values`)."""
    from ..rendering.kinds import CHART

    request = CHART.request(chart, cam, prevailing, calibration, spp=spp, seed=seed, variant=variant, imager=imager,
                            illuminance=illuminance)  # the one request of every door
    rendering, imaged = CHART.render_imaged(request)
    # through a sensor the balance's whites are noise-free; else the rendered whites' noise adds to every patch
    relative = np.zeros(3) if imaged is not None else white_relative_variance(rendering)
    settings = {} if imaged is None else {"imager": imaged.imager.name, "illuminance_lux": imaged.illuminance_lux}
    return chart_values(chart, cam, rendering, relative, settings)


def chart_values(chart, cam, rendering, relative, settings: dict) -> Measurement:
    """A chart render reduced to its patch means with their standard errors (``relative``: the whites' relative
    variance per channel)."""
    from ..rendering.renderer import channel_names

    stats = rendering.patches
    se = np.sqrt(stats.standard_error**2 + stats.mean**2 * relative[None, :])
    dof = np.broadcast_to(stats.count[:, None] - 1.0, se.shape)
    names = tuple(p.name for p in chart.patches)
    items = tuple(f"{n} / {c}" for n in names for c in cam.channels)
    settings = {"spp": int(rendering.raw[0].spp), "variant": rendering.variant, **settings}
    return Measurement("chart", rendering.image, None, channel_names(cam), names, items, stats.mean.ravel(),
                       se.ravel(), np.where(se.ravel() > 0, dof.ravel(), np.inf), settings)


class ChartChecks:
    """What a check of a chart renders and refuses (:func:`~skinrender.testing.regression.measure`'s by the scene's kind): the plugin checks a
    chart at its base level, through a camera or an image sensor."""

    spp_default = SPP_CHART

    def __init__(self, scene, physics, skin, size, imager, illuminance):
        from ..rendering.chart_effects import CHART_REGISTRY
        from ..rendering.scene import load_chart_scene

        self.chart = named_argument("scene", load_chart_scene, scene)
        given = [n for n, v in (("physics", beyond_base(CHART_REGISTRY, physics)), ("skin", skin is not None),
                                ("size", size is not None)) if v]
        if given:
            raise SkinrenderError(f"{', '.join(given)}: {'goes' if len(given) == 1 else 'go'} with a face scene "
                                  "(e.g. 'face'), not a chart")
        if illuminance is not None and imager is None:
            raise SkinrenderError("illuminance sets the image sensor's exposure: it goes with imager")

    def name(self, found) -> str:
        return self.chart.name

    def one(self, cam, p, c, spp, seed, physics, skin, imager, illuminance, size, variant) -> Measurement:
        return chart_measurement(self.chart, cam, p, c, spp, seed, imager, illuminance, variant)

    def spectral(self, cams, p, c, spp, seed, physics, skin, imager, illuminance, size, variant) -> list:
        """One measurement per camera from one spectral render (:func:`measure_spectral`)."""
        from ..rendering.bands import BANDS_DEFAULT, bands_text
        from ..rendering.kinds import CHART

        if imager is not None:
            raise SkinrenderError("imager: a chart's image sensor records one camera's render; check several cameras "
                                  "without it, or one camera at a time")
        image = CHART.render(CHART.request(self.chart, None, p, None, spp=spp, seed=seed, variant=variant,
                                           bands=BANDS_DEFAULT))
        bands = {"spectral_bands_nm": bands_text(BANDS_DEFAULT)}
        out = []
        for cam in cams:
            rendering = image.through(cam, c)
            out.append(chart_values(self.chart, cam, rendering, white_relative_variance(rendering), bands))
        return out


class FaceChecks:
    """What a check of a face renders (:func:`~skinrender.testing.regression.measure`'s by the scene's kind): replicates at any level."""

    spp_default = SPP_FACE
    chart = None

    def __init__(self, scene, physics, skin, size, imager, illuminance):
        self.scene = scene

    def name(self, found) -> str:
        return found.settings.pop("scene_name")

    def one(self, cam, p, c, spp, seed, physics, skin, imager, illuminance, size, variant) -> Measurement:
        return Measurement("face", *measure_face(self.scene, cam, p, c, spp, seed, physics, skin, imager,
                                                 illuminance, size, variant))

    def spectral(self, cams, p, c, spp, seed, physics, skin, imager, illuminance, size, variant) -> list:
        """One measurement per camera from one spectral render per replicate seed (:func:`measure_spectral`)."""
        from ..rendering.bands import BANDS_DEFAULT, bands_text
        from ..rendering.kinds import FACE
        from .replicates import face_check_request, reduce_face, replicate_seeds

        request = face_check_request(self.scene, None, p, None, spp, seed, physics, skin, imager, illuminance, size,
                                     variant, BANDS_DEFAULT)
        images = [FACE.render(request, s) for s in replicate_seeds(seed)]
        bands = {"spectral_bands_nm": bands_text(BANDS_DEFAULT)}
        out = []
        for cam in cams:
            found = Measurement("face", *reduce_face([image.through(cam, c) for image in images], cam))
            out.append(Measurement(found.kind, found.image, found.labels, found.channels, found.regions, found.items,
                                   found.mean, found.standard_error, found.dof, {**found.settings, **bands}))
        return out


def beyond_base(registry, physics) -> bool:
    """Whether ``physics`` names more than the registry's base level (a spec of another registry does)."""
    if physics is None:
        return False
    try:
        return bool(registry.names(physics))
    except SkinrenderError:
        return True
