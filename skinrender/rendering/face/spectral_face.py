"""
Faces rendered once for every camera
====================================

The face rendered with the bands of :mod:`skinrender.rendering.bands` as its
film (one render per light, skin and level, no camera), and then seen through
any camera: its bands projected on the camera's curves
(:func:`~skinrender.rendering.bands.projection`), the whites computed as a
spectral render sees that camera, the level's post-processing applied per
camera (``noise``: one frame through the image sensor, as
:func:`~skinrender.rendering.face.render.render_face` does), and Eq. 4's
white balance. The result is the :class:`~skinrender.rendering.face.render.FaceRendering`
a render of that camera returns.

-   :func:`render_face_spectral`: the render (a :class:`~skinrender.rendering.spectral_image.SpectralImage`).
-   :func:`face_through`: one camera's render from it.

Every level works so: its effects change the scene's document and the
integrator, never the film, and ``noise`` acts after the render. Two
cameras seen through one spectral render share its light paths: their
difference is estimated with common random numbers.

Units: band values W·m⁻²·sr⁻¹ (``∫ L h_j dλ``); images in Eq. 4 output units;
temperatures K; illuminance lx.
"""

from __future__ import annotations

import time

from ...errors import SkinrenderError
from ...model.camera import Camera, camera
from ...spectra import GRID_DEFAULT, WavelengthGrid
from ..bands import BANDS_DEFAULT, bands_text, check_bands, estimate, parse_bands, projection
from .effects import Level
from .render import FaceRendering, finish_face, plan_face, planckian_temperature, white_references
from .revalue import spectral_loaded

__all__ = ["render_face_spectral", "face_through"]


def render_face_spectral(
    scene="face",
    prevailing=None,
    skin: str | None = None,
    physics: str | Level = "direct",
    spp: int = 64,
    seed: int = 0,
    size=None,
    sampler: str = "multijitter",
    variant: str | None = None,
    grid: WavelengthGrid = GRID_DEFAULT,
    bands: WavelengthGrid | str = BANDS_DEFAULT,
    imager: str | None = None,
    exposure="auto",
    illuminance: float | None = None,
):
    """
    Render a face scene once with the bands as its film, for any camera afterwards.

    Parameters
    ----------
    scene, prevailing, skin, physics, spp, seed, size, sampler, variant, grid, illuminance
        As :func:`~skinrender.rendering.face.render.render_face` (temperatures K, size pixels, lx).
    bands
        The band grid (``START:END:STEP`` nm or a :class:`~skinrender.spectra.WavelengthGrid`), inside
        ``grid``; default :data:`~skinrender.rendering.bands.BANDS_DEFAULT`.
    imager, exposure
        For ``noise``: the image sensor and exposure every camera's frame is taken with (the sensor acts
        after the projection, per camera).

    Returns
    -------
    :class:`~skinrender.rendering.spectral_image.SpectralImage`
    """
    from ..spectral_image import SpectralImage

    start = time.perf_counter()
    bands = parse_bands(bands)
    check_bands(bands, grid, "the face's lights and reflectances")
    plan = plan_face(scene, prevailing, skin, physics, spp, seed, size, sampler, variant, grid, illuminance)
    if "noise" not in plan.level and (imager is not None or exposure != "auto"):
        raise SkinrenderError("imager and exposure are the noise level's: add noise to physics")
    estimate(bands, plan.scene.camera.width * plan.scene.camera.height, 0.0)  # refused beyond the memory cap
    loaded, labels = spectral_loaded(plan, bands)  # one kernel per structure (revalue)
    radiance, spp_used = plan.render(loaded)
    scale = plan.scale
    info = {"lights": {k: {"temperature_K": v.temperature, "illuminance_lx": v.illuminance}
                       for k, v in plan.lights.items()}, "imager": imager, "exposure": exposure}
    return SpectralImage("face", plan.scene, bands, (radiance / scale).astype("float32"), scale,
                         float(plan.prevailing), plan.level.name, spp_used, plan.spp, plan.seed, plan.sampler,
                         plan.variant, time.perf_counter() - start, grid, labels, _names(plan.scene), plan.skin,
                         info, plan, face_through)


def _names(scene) -> dict:
    from .labels import label_names

    return label_names(scene)


def face_through(spectral, camera_: Camera | str, calibration=None) -> FaceRendering:
    """
    The face render ``camera_`` would give, from a spectral render: its bands projected on the camera's
    curves, the whites as the spectral render sees the camera, the level's post-processing (``noise``: one
    frame through the render's image sensor, seeded from its seed), Eq. 4's gain to ``calibration`` (K;
    ``None``: the prevailing light). Its ``info`` adds ``spectral``: the bands, and the seconds of the
    render it came from (``seconds`` is the projection's own).
    """
    start = time.perf_counter()
    cam = camera(camera_)
    plan = spectral.plan
    if plan is None:
        raise SkinrenderError("this spectral image carries no face scene to see it through a camera (read from a "
                              "file whose scene could not be loaded)")
    matrix = projection(cam, spectral.bands, spectral.grid)
    c = plan.prevailing if calibration is None else planckian_temperature(calibration, "calibration")
    white_p, white_c = white_references(plan.scene, cam, c, spectral.grid, spectral.bands)
    radiance = spectral.radiance @ matrix.T
    info = {"spectral": {"bands_nm": bands_text(spectral.bands), "render_seconds": spectral.seconds}}
    return finish_face(plan, cam, c, radiance, white_p, white_c, spectral.labels, spectral.spp, 1, start,
                       spectral.info.get("imager"), spectral.info.get("exposure", "auto"), info)
