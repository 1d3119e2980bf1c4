"""
Faces rendered once for every camera
====================================

The face rendered with the bands of :mod:`skinrender.rendering.bands` as its
film (one render per light, skin and level, no camera: a
:class:`~skinrender.rendering.face.request.FaceRequest` with ``bands``), and
then seen through any camera: its bands projected on the camera's curves
(:func:`~skinrender.rendering.bands.projection`), the whites computed as a
spectral render sees that camera, the level's post-processing applied per
camera (``noise``: one frame through the image sensor, as
:func:`~skinrender.rendering.face.render.render_face_request` does), and Eq. 4's
white balance. The result is the :class:`~skinrender.rendering.face.render.FaceRendering`
a render of that camera returns.

-   :func:`render_face_spectral`: the render from specs; :func:`render_face_spectral_request`: from a request
    (the face kind's ``render`` of a spectral request).
-   :func:`face_through`: one camera's render from it.
-   :class:`FacePlan`: what a spectral render loads and renders (the request, its lights, scale, variant).

Every level works so: its effects change the scene's document and the
integrator, never the film, and ``noise`` acts after the render. Two
cameras seen through one spectral render share its light paths: their
difference is estimated with common random numbers.

Units: band values W·m⁻²·sr⁻¹ (``∫ L h_j dλ``); images in Eq. 4 output units;
temperatures K; illuminance lx.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ...errors import SkinrenderError
from ...hints import NDArrayFloat
from ...model.camera import Camera, camera
from ...spectra import GRID_DEFAULT, WavelengthGrid
from ..bands import BANDS_DEFAULT, bands_text, estimate, projection
from ..variants import mitsuba
from .document import light_irradiance
from .labels import label_names, render_labels, shape_labels
from .render import FaceRendering, finish_face, loaded_document, planckian_temperature, white_references

__all__ = ["FacePlan", "render_face_spectral", "render_face_spectral_request", "face_through"]


@dataclass(frozen=True)
class FacePlan:
    """
    What a face render loads and renders: its ``request``'s scene (resized, relit), level, skin, settings and
    grid, with the level's ``lights``, the emitters' ``scale`` (W·m⁻²·nm⁻¹), the Mitsuba ``variant`` and the
    ``seed`` rendered with.
    """

    request: object
    lights: dict
    scale: float
    variant: str
    seed: int

    @classmethod
    def of(cls, request, seed: int | None = None) -> FacePlan:
        """The plan of a face request (``seed``: a derived seed, else the request's)."""
        lights = request.level.lights(request.scene)
        scale = max(float(np.max(light_irradiance(light, request.grid)[1])) for light in lights.values())
        seed = request.settings.seed if seed is None else int(seed)
        if not 0 <= seed < 2**32:
            raise SkinrenderError(f"seed must be a 32-bit integer, got {seed}", role="seed")
        return cls(request, lights, scale, request.level.choose_variant(request.settings.variant), seed)

    scene = property(lambda self: self.request.scene, doc="The face as rendered.")
    level = property(lambda self: self.request.level, doc="The level of physics.")
    skin = property(lambda self: self.request.skin, doc="The skin spec.")
    grid = property(lambda self: self.request.grid, doc="The wavelength grid, nm.")
    spp = property(lambda self: self.request.settings.spp, doc="Samples per pixel asked.")
    sampler = property(lambda self: self.request.settings.sampler, doc="The sampler.")

    def loaded(self, bands: WavelengthGrid):
        """The plan's document with ``bands`` as its film (the face renderer's cache)."""
        return loaded_document(self.scene, None, self.grid, self.level, self.skin, (), self.spp, self.sampler,
                               self.variant, self.lights, self.scale, bands)

    def render(self, loaded) -> tuple[NDArrayFloat, int]:
        """One render of ``loaded`` with the plan's seed: ``(height, width, n)`` float64 in absolute units (the
        emitters' ``scale`` restored), and the spp the sampler used."""
        mi = mitsuba(self.variant)
        width, height = self.scene.camera.width, self.scene.camera.height
        values = np.array(mi.render(loaded, seed=self.seed), dtype=np.float64)
        spp = int(loaded.sensors()[0].sampler().sample_count())
        return values.reshape(height, width, -1) * self.scale, spp

    def labels(self, loaded) -> NDArrayFloat:
        """The label image (:func:`~skinrender.rendering.face.labels.render_labels`) through ``loaded``."""
        mi = mitsuba(self.variant)
        return render_labels(mi, loaded, self.scene.camera.width, self.scene.camera.height, shape_labels(self.scene))


def render_face_spectral(scene="face", prevailing=None, skin: str | None = None, physics="direct", spp: int = 64,
                         seed: int = 0, size=None, sampler: str | None = None, variant: str | None = None,
                         grid: WavelengthGrid = GRID_DEFAULT, bands: WavelengthGrid | str = BANDS_DEFAULT,
                         imager: str | None = None, exposure=None, illuminance: float | None = None):
    """
    Render a face scene once with the bands as its film, for any camera afterwards.

    Parameters
    ----------
    scene, prevailing, skin, physics, spp, seed, size, sampler, variant, grid
        As :func:`~skinrender.rendering.face.render.render_face` (temperatures K, size pixels).
    bands
        The band grid (``START:END:STEP`` nm or a :class:`~skinrender.spectra.WavelengthGrid`), inside ``grid``;
        default :data:`~skinrender.rendering.bands.BANDS_DEFAULT`.
    imager, exposure, illuminance
        The ``noise`` effect's options: the image sensor every camera's frame is taken with (it acts after the
        projection, per camera), its exposure, and the key light's illuminance, lx.

    Returns
    -------
    :class:`~skinrender.rendering.spectral_image.SpectralImage`
    """
    from .request import face_request

    request = face_request(scene, None, prevailing, None, skin=skin, physics=physics, size=size, spp=spp,
                           seed=seed, sampler=sampler, variant=variant, grid=grid, imager=imager,
                           exposure=exposure, illuminance=illuminance, bands=bands)
    return render_face_spectral_request(request)


def render_face_spectral_request(request, seed: int | None = None):
    """
    The :class:`~skinrender.rendering.spectral_image.SpectralImage` of a spectral face request (its ``bands``
    set; ``seed``: a derived seed, else the request's): one render, one kernel per structure
    (:mod:`~skinrender.rendering.face.revalue`), and its label image.
    """
    from ..spectral_image import SpectralImage
    from .revalue import spectral_loaded

    start = time.perf_counter()
    if not request.spectral:
        raise SkinrenderError("bands: this request renders a camera's channels; a spectral render needs bands",
                              role="bands")
    bands, plan = request.bands, FacePlan.of(request, seed)
    estimate(bands, request.pixels, 0.0)  # refused beyond the memory cap
    loaded, labels = spectral_loaded(plan, bands)
    radiance, spp_used = plan.render(loaded)
    info = {"lights": {k: {"temperature_K": v.temperature, "illuminance_lx": v.illuminance}
                       for k, v in plan.lights.items()}}
    return SpectralImage("face", request.scene, bands, (radiance / plan.scale).astype(np.float32), plan.scale,
                         float(request.prevailing), request.level.name, spp_used, request.settings.spp, plan.seed,
                         request.settings.sampler, plan.variant, time.perf_counter() - start, request.grid, labels,
                         label_names(request.scene), request.skin, info, request, face_through)


def face_through(spectral, camera_: Camera | str, calibration=None) -> FaceRendering:
    """
    The face render ``camera_`` would give, from a spectral render: its bands projected on the camera's
    curves, the whites as the spectral render sees the camera, the level's post-processing (``noise``: one
    frame through the request's image sensor, seeded from the render's seed), Eq. 4's gain to ``calibration``
    (K; ``None``: the prevailing light). Its ``info`` adds ``spectral``: the bands, and the seconds of the
    render it came from (``seconds`` is the projection's own).
    """
    start = time.perf_counter()
    cam = camera(camera_)
    request = spectral.request
    if request is None:
        raise SkinrenderError("this spectral image carries no face scene to see it through a camera (read from a "
                              "file whose scene could not be loaded)")
    matrix = projection(cam, spectral.bands, spectral.grid)
    c = request.prevailing if calibration is None else planckian_temperature(calibration, "calibration")
    white_p, white_c = white_references(request.scene, cam, c, spectral.grid, spectral.bands)
    radiance = spectral.radiance @ matrix.T
    info = {"spectral": {"bands_nm": bands_text(spectral.bands), "render_seconds": spectral.seconds}}
    return finish_face(request, cam, c, radiance, white_p, white_c, spectral.labels, spectral.spp, 1, spectral.seed,
                       spectral.variant, start, info)
