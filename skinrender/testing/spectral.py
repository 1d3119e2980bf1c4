"""
Several cameras, one render: a regression check's spectral measurements
========================================================================

``render_regression.check(scene, camera=[A, B, …])`` renders the scene once
with the bands of :mod:`skinrender.rendering.bands` as its film and measures
each camera through it (:meth:`~skinrender.rendering.spectral.SpectralImage.through`),
reduced as one camera's render is (:mod:`skinrender.testing.regression`): a
chart's patch means (its whites' noise carried: at p ≠ c the calibration white
is computed, exact), a face's region means and skin NCC from
:data:`~skinrender.testing.replicates.REPLICATES` replicates, each replicate
one spectral render. The settings add ``spectral_bands_nm``, so that a
reference made one render per camera is told apart in a failure's notes.

-   :func:`measure_spectral`.

Units: output units (Eq. 4), NCC fractions; temperatures K; bands nm.
"""

from __future__ import annotations

from ..errors import SkinrenderError
from ..rendering.bands import BANDS_DEFAULT, bands_text

__all__ = ["measure_spectral"]


def measure_spectral(kind: str, scene, cameras: list, prevailing: float, calibration: float, spp: int, seed: int,
                     physics: str | None, skin: str | None, imager: str | None, illuminance: float | None, size: int,
                     variant: str | None) -> list:
    """
    One :class:`~skinrender.testing.regression.Measurement` per camera of ``cameras`` from one spectral render
    of ``scene`` (a loaded chart, or a face spec) with :data:`~skinrender.rendering.bands.BANDS_DEFAULT`
    (arguments as :func:`~skinrender.testing.regression.measure`; a chart through an ``imager`` is refused: its
    sensor records a camera's channels).
    """
    from .regression import Measurement, _chart_values, _white_relative_variance

    bands = {"spectral_bands_nm": bands_text(BANDS_DEFAULT)}
    if kind == "chart":
        if imager is not None:
            raise SkinrenderError("imager: a chart's image sensor records one camera's render; check several cameras "
                                  "without it, or one camera at a time")
        from ..rendering.spectral_chart import render_chart_spectral

        image = render_chart_spectral(scene, prevailing, BANDS_DEFAULT, spp=spp, seed=seed, variant=variant)
        out = []
        for cam in cameras:
            rendering = image.through(cam, calibration)
            out.append(_chart_values(scene, cam, rendering, _white_relative_variance(rendering), bands))
        return out
    from ..rendering.face.spectral import render_face_spectral
    from .replicates import REPLICATES, face_effects, reduce_face, replicate_seeds

    effects = face_effects(spp, physics, imager, illuminance)
    images = [render_face_spectral(scene, prevailing, skin, effects, spp // REPLICATES, s, size, variant=variant,
                                   bands=BANDS_DEFAULT, imager=imager, illuminance=illuminance)
              for s in replicate_seeds(seed)]
    out = []
    for cam in cameras:
        found = Measurement("face", *reduce_face([image.through(cam, calibration) for image in images], cam))
        out.append(Measurement(found.kind, found.image, found.labels, found.channels, found.regions, found.items,
                               found.mean, found.standard_error, found.dof, {**found.settings, **bands}))
    return out
