"""
Scene kinds
===========

A chart and a face are two kinds of scene, each an object of one protocol,
:class:`SceneKind`: it knows its scenes (``owns``, ``load``), builds its
:mod:`request <skinrender.rendering.request>` from specs or objects
(``request``), renders it (``render``), validates it against the analytic
model (``validate``), estimates its time (``estimate_seconds``) and draws its
labelled figure (``figure``); its ``registry`` is its effects of physics
(:class:`~skinrender.rendering.registry.Registry`). :data:`SCENE_KINDS` is the
one table of kinds and :func:`scene_kind` the one place a scene (or a spec) is
told to be a chart or a face: nothing else tests a scene's type or a kind's
name.

-   :class:`SceneKind`: the protocol; :data:`CHART`, :data:`FACE`: the kinds.
-   :data:`SCENE_KINDS`, :func:`scene_kind`.

Units: temperatures K, times s.
"""

from __future__ import annotations

from pathlib import Path
from typing import Protocol

from ..errors import SkinrenderError
from .physics import SECONDS_PER_RENDER

__all__ = ["SceneKind", "ChartKind", "FaceKind", "CHART", "FACE", "SCENE_KINDS", "scene_kind", "by_kind"]


class SceneKind(Protocol):
    """
    What a kind of scene does (a chart, a face).

    Attributes
    ----------
    name
        ``chart`` or ``face`` (the figures' and the pytest plugin's word for it).
    registry
        Its effects of physics (:class:`~skinrender.rendering.registry.Registry`).
    render_options, validate_options
        The keywords ``skinrender.render`` and ``skinrender.validate`` take for it (beside scene, camera and the
        two lights), in the order a refusal lists them.
    lights_required
        Whether a request needs both lights (a chart); a face keeps its scene's key light where none is given.
    """

    name: str
    render_options: tuple[str, ...]
    validate_options: tuple[str, ...]
    lights_required: bool

    @property
    def registry(self): ...

    def owns(self, spec) -> bool:
        """Whether ``spec`` (a scene object, a bundled name, a TOML path) is a scene of this kind."""

    def load(self, spec):
        """The scene of ``spec``, parsed and checked once (an object of this kind returned as it is)."""

    def request(self, scene, camera, prevailing, calibration, **options):
        """Its request (:mod:`skinrender.rendering.request`), each argument parsed and checked once."""

    def render(self, request, **options):
        """The render of a request."""

    def validate(self, request, **options):
        """The render of a request checked against the analytic model (a result with ``verdict``, ``bound``,
        ``spp_needed``)."""

    def validate_of(self, scene, camera, prevailing, calibration, **options):
        """:meth:`validate` from specs (``skinrender.validate``'s keywords)."""

    def estimate_seconds(self, request, renders: int = 1, cores: int = 1) -> float:
        """Seconds ``renders`` renders of a request should take on ``cores`` cores."""

    def workload(self, request, renders: int = 1, cores: int = 1) -> tuple[float, str]:
        """``(seconds, what)``: :meth:`estimate_seconds` and what is estimated, in words (for a refusal)."""

    def figure(self, result, path, **options) -> Path:
        """Its render drawn with its labels into a PNG at ``path``."""


def _workload(request, renders: int, cores: int) -> tuple[float, str]:
    """
    ``renders`` renders of ``request`` on ``cores`` cores: ``(seconds, what)`` (what they are, in words, for a
    refusal): its level's own estimate where an effect gives one (:attr:`~skinrender.rendering.physics.Effect.estimate`),
    else a render's fixed cost and its pixels × spp at the level's rate, and the level's one-off work once
    (:attr:`~skinrender.rendering.physics.Level.setup_seconds`: the fast subsurface's table).
    """
    cores = max(1, int(cores))
    estimate = request.level.estimate
    if estimate is not None:
        seconds, what = estimate(request, cores)
        return renders * seconds, what
    spp, pixels, level = request.settings.spp, request.pixels, request.level
    seconds = (renders * (SECONDS_PER_RENDER + pixels * spp / level.samples_per_s) + level.setup_seconds) / cores
    return seconds, f"{f'{renders} renders' if renders > 1 else 'a render'} of {pixels} pixels at {spp} spp"


class _Kind:
    """What the kinds share: their estimates (:func:`_workload`) and figures (by the kind's name)."""

    name = ""

    def __repr__(self) -> str:
        return self.name.upper()

    def estimate_seconds(self, request, renders: int = 1, cores: int = 1) -> float:  # noqa: D102
        return _workload(request, renders, cores)[0]

    def workload(self, request, renders: int = 1, cores: int = 1) -> tuple[float, str]:  # noqa: D102
        return _workload(request, renders, cores)

    def figure(self, result, path, **options) -> Path:  # noqa: D102
        from .outputs import draw_figure

        return draw_figure(self.name, result, path, **options)


class ChartKind(_Kind):
    """A chart (:class:`~skinrender.rendering.scene.ChartScene`): patches under a light, checked against Eq. 4."""

    name = "chart"
    render_options = ("normalization", "knee", "spp", "seed", "sampler", "variant", "channels", "settings", "grid",
                      "cache", "emitter", "physics", "imager", "illuminance", "exposure", "translate_mm", "quality")
    validate_options = (*render_options, "rendering", "tolerance", "alpha", "alpha_difference")
    lights_required = True

    @property
    def registry(self):
        """:data:`~skinrender.rendering.chart_effects.CHART_REGISTRY`."""
        from .chart_effects import CHART_REGISTRY

        return CHART_REGISTRY

    def owns(self, spec) -> bool:  # noqa: D102 - the protocol's
        from .scene import ChartScene

        return isinstance(spec, ChartScene) or not FACE.owns(spec)  # any other spec: the chart loader names it

    def load(self, spec):  # noqa: D102
        from .scene import load_chart_scene

        return load_chart_scene(spec)

    def request(self, scene, camera, prevailing, calibration, **options):  # noqa: D102
        from .request import chart_request

        return chart_request(scene, camera, prevailing, calibration, **options)

    def render(self, request, cache: dict | None = None):
        """The :class:`~skinrender.rendering.balance.Rendering` of a request (its level's raw renders balanced;
        through an image sensor: the Eq. 4 image of the noisy DN, the sensor's settings in ``info``); a spectral
        request's (``bands``) :class:`~skinrender.rendering.spectral_image.SpectralImage`."""
        if request.spectral:
            from .spectral_chart import render_chart_spectral_request

            return render_chart_spectral_request(request)
        return self.render_imaged(request, cache)[0]

    def render_imaged(self, request, cache: dict | None = None) -> tuple:
        """``(rendering, imaged)``: the render and, where the request records through an image sensor
        (:attr:`~skinrender.rendering.request.Request.sensor`), its
        :class:`~skinrender.rendering.imaging.ImagedRendering` (``None`` without). Through a sensor the request's
        ``knee`` (Eq. 10) is applied to the Eq. 4 image of its codes (it is the rendering's ``knee``)."""
        if request.sensor is not None:
            from .imaging import render_imaged_request

            imaged = render_imaged_request(request)
            rendering = imaged.rendering
            if request.knee and not rendering.knee:
                import dataclasses

                import numpy as np

                from ..model.response import knee

                rendering = dataclasses.replace(rendering, image=knee(rendering.image).astype(np.float32), knee=True)
            return rendering, imaged
        from .balance import render_balanced

        return render_balanced(request, request.level.chart(request), cache), None

    def validate(self, request, *, tolerance=None, alpha=None, alpha_difference=None, cache=None):
        """
        The chart checked patch by patch against Eq. 4: a :class:`~skinrender.rendering.validation.Validation`,
        or through an image sensor a :class:`~skinrender.rendering.sensor_validation.ImagedValidation` (the
        means, the variances and the means within ``tolerance``).
        """
        from ..evaluation.verdict import ALPHA_DIFFERENCE, ALPHA_EQUIVALENCE
        from .agreement import TOLERANCE_DEFAULT, check_tolerance
        from .validation import analytic_reference, validate_rendering

        tolerance = TOLERANCE_DEFAULT if tolerance is None else check_tolerance(tolerance, "tolerance")
        if request.sensor is not None and request.knee:  # before any render, as validate --imager --knee
            raise SkinrenderError("knee: a validation through an image sensor tests its linear codes (DN) against "
                                  "its model; drop knee", role="knee")
        rendering, imaged = self.render_imaged(request, cache)
        if imaged is None:
            return validate_rendering(rendering, tolerance, ALPHA_EQUIVALENCE if alpha is None else alpha,
                                      ALPHA_DIFFERENCE if alpha_difference is None else alpha_difference,
                                      request.grid)
        from .sensor_validation import validate_imaged

        grid = request.grid
        ratio = analytic_reference(rendering.camera, rendering.scene.reflectances(grid), rendering.prevailing,
                                   rendering.prevailing, grid=grid) / 255.0
        return validate_imaged(imaged, ratio, grid=grid, tolerance=tolerance)

    def choose_spp(self, request, tolerance: float, name: str = "--tolerance") -> dict:
        """
        ``spp="auto"`` (``validate --spp auto``): the smallest spp at which the request's validation is expected
        to pass ``tolerance`` (relative), from two pilot renders
        (:func:`~skinrender.rendering.spp_choice.spp_for_tolerance`, its dict: ``spp``, ``pilots``, ``exponent``,
        ``margin``, ``why``), held to ``SPP_MAX`` and to one pass's samples (Mitsuba's 32-bit wavefront); a
        refusal names the tolerance as ``name`` (the CLI's flag, or ``tolerance`` from Python).
        """
        import dataclasses

        from .renderer import SAMPLES_MAX
        from .settings import SPP_MAX
        from .spp_choice import spp_for_tolerance

        settings = request.settings

        def at(spp, seed):
            pilot = dataclasses.replace(request, settings=settings.replace(spp=spp, seed=seed))
            return self.validate(pilot, tolerance=tolerance)

        return spp_for_tolerance(at, tolerance, settings.seed, spp_max=min(SPP_MAX, SAMPLES_MAX // request.pixels),
                                 sampler=settings.sampler, name=name)

    def validate_of(self, scene, camera, prevailing, calibration, **options):  # noqa: D102
        import dataclasses

        from .spp_choice import PILOT_SPP, is_auto

        checks = {name: options.pop(name) for name in ("tolerance", "alpha", "alpha_difference", "cache")
                  if name in options}
        rendering = options.pop("rendering", None)
        auto = is_auto(options.get("spp"))
        if auto and rendering is not None:
            raise SkinrenderError("spp='auto' chooses the spp of a render to come: it does not go with rendering "
                                  "(a render given to check)", role="spp")
        if auto and checks.get("tolerance") is None:
            raise SkinrenderError("spp='auto' renders at the smallest spp expected to pass tolerance: give "
                                  "tolerance=REL", role="tolerance")
        if rendering is not None:  # a render given to check: the chart's own check of it
            from .validation import validate

            return validate(scene, camera, prevailing, calibration, rendering=rendering, **checks, **options)
        if auto:
            options["spp"] = PILOT_SPP[0]  # stands in until the pilots have chosen
        request = self.request(scene, camera, prevailing, calibration, **options)
        if not auto:
            return self.validate(request, **checks)
        refused = request.level.refused("spp_auto")
        if refused is not None:
            raise SkinrenderError(f"spp='auto' does not go with physics {refused[0].name!r}: {refused[1]}", role="spp")
        from .agreement import check_tolerance

        choice = self.choose_spp(request, check_tolerance(checks["tolerance"], "tolerance"), "tolerance")
        result = self.validate(dataclasses.replace(request, settings=request.settings.replace(spp=choice["spp"])),
                               **checks)
        return dataclasses.replace(result, spp_auto=choice)



class FaceKind(_Kind):
    """A face (:class:`~skinrender.rendering.face.scene.FaceScene`): a head in skin, props, lights; checked against
    the analytic limits of its level and Eq. 4's detection budget."""

    name = "face"
    render_options = ("skin", "physics", "spp", "seed", "size", "sampler", "variant", "grid", "channels", "imager",
                      "exposure", "illuminance", "translate_mm", "quality")
    validate_options = (*render_options, "replicates", "limits", "progress", "budget_fraction", "skin_set",
                        "detection_tolerance")
    lights_required = False

    @property
    def registry(self):
        """:data:`~skinrender.rendering.face.effects.PHYSICS_REGISTRY`."""
        from .face.effects import PHYSICS_REGISTRY

        return PHYSICS_REGISTRY

    def owns(self, spec) -> bool:  # noqa: D102
        from .face.scene import is_face_scene

        return is_face_scene(spec)

    def load(self, spec):  # noqa: D102
        from .face.scene import load_face_scene

        return load_face_scene(spec)

    def request(self, scene, camera, prevailing, calibration, **options):  # noqa: D102
        from .face.request import face_request

        return face_request(scene, camera, prevailing, calibration, **options)

    def render(self, request, seed: int | None = None):
        """The :class:`~skinrender.rendering.face.render.FaceRendering` of a request (``seed``: a derived seed); a
        spectral request's (``bands``) :class:`~skinrender.rendering.spectral_image.SpectralImage`."""
        if request.spectral:
            from .face.spectral_face import render_face_spectral_request

            return render_face_spectral_request(request, seed)
        from .face.render import render_face_request

        return render_face_request(request, seed)

    def validate(self, request, **options):
        """:func:`~skinrender.rendering.face.validation.validate_face_request`: a
        :class:`~skinrender.rendering.face.validation.FaceValidation`."""
        from .face.validation import validate_face_request

        return validate_face_request(request, **options)

    def validate_of(self, scene, camera, prevailing, calibration, **options):  # noqa: D102
        from .face.validation import validate_face
        from .spp_choice import is_auto

        if is_auto(options.get("spp")):  # as the CLI's --spp auto: a chart's
            raise SkinrenderError("spp='auto' goes with a chart's validation (tolerance=REL); a face's gives the "
                                  "spp it needs (spp_needed): give spp=N", role="spp")
        if options.get("quality") is not None:  # as --quality: its spp (in all) and sampler unless given
            from .settings import RenderSettings

            preset = RenderSettings.preset(options.pop("quality"))
            options.setdefault("spp", preset.spp)
            options.setdefault("sampler", preset.sampler)

        return validate_face(camera, scene, prevailing, calibration, **options)



CHART = ChartKind()
"""The chart kind."""

FACE = FaceKind()
"""The face kind."""

SCENE_KINDS: dict[str, SceneKind] = {"face": FACE, "chart": CHART}
"""The kinds of scene, name → kind, in the order a spec is tried (a face TOML has ``[camera]`` and ``[mesh]``;
anything else is a chart's, whose loader names what is wrong)."""


def by_kind(scene, **functions):
    """
    The function of ``scene``'s kind (a scene or a spec) among ``functions`` (kind name → function, every kind of
    :data:`SCENE_KINDS` given): the one way code outside the kinds takes a kind's road (the command line's
    commands, the pytest plugin's checks).

    >>> by_kind("face", chart="a chart's", face="a face's")
    "a face's"
    """
    missing = sorted(set(SCENE_KINDS) - set(functions))
    if missing:
        raise TypeError(f"by_kind: no function for {', '.join(missing)}")
    return functions[scene_kind(scene).name]


def scene_kind(spec) -> SceneKind:
    """
    The kind of a scene or a scene spec: the first of :data:`SCENE_KINDS` that owns it.

    >>> scene_kind("face").name, scene_kind("macbeth").name
    ('face', 'chart')
    """
    return next(kind for kind in SCENE_KINDS.values() if kind.owns(spec))
