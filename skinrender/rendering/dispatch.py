"""
One render for charts and faces
===============================

:func:`load_scene` (``skinrender.load_scene``) makes any scene the command
line takes an object, once: a :class:`~skinrender.rendering.scene.ChartScene`
or a :class:`~skinrender.rendering.face.scene.FaceScene`; the commands and
the renderers below them pass that object on.

:func:`render` (``skinrender.render``) renders any scene the command line's
``render`` takes: a chart (``macbeth``, ``skin_patches``, ``face_chart``, a
chart TOML, a :class:`~skinrender.rendering.scene.ChartScene`) through
:func:`skinrender.rendering.balance.render`, a face (``face``, a TOML with
``[camera]`` and ``[mesh]``, a :class:`~skinrender.rendering.face.scene.FaceScene`)
through :func:`skinrender.rendering.face.render.render_face`. Both results
save themselves (``.save(exr, png=…, figure=…)``) and draw their labelled
figure (``.figure(path)``).

:func:`validate` (``skinrender.validate``) checks any scene the command
line's ``validate`` takes: a chart against Eq. 4 patch by patch
(:func:`skinrender.rendering.validation.validate`), a face against its
level's analytic limits and Eq. 4's detection budget
(:func:`skinrender.rendering.face.validation.validate_face`). Both results
give ``verdict`` (pass, fail or inconclusive), ``bound`` and ``spp_needed``.

Units: temperatures K; images in Eq. 4 output units (255 for white at p = c).
"""

from __future__ import annotations

import inspect

from ..errors import SkinrenderError
from .bands import BANDS_DEFAULT

__all__ = ["load_scene", "render", "validate", "render_spectral", "render_cameras"]


def load_scene(spec):
    """
    A chart or a face scene, parsed and checked once: a bundled name (``macbeth``, ``skin_patches``,
    ``face_chart``, ``face``), a TOML path (a face's has ``[camera]`` and ``[mesh]``), or a scene object (returned
    as it is).

    Returns
    -------
    :class:`~skinrender.rendering.scene.ChartScene` or :class:`~skinrender.rendering.face.scene.FaceScene`

    Raises
    ------
    SkinrenderError
        An unknown name (every bundled scene listed), a file that is not valid TOML, a missing or bad field
        (the file and the field named).

    Examples
    --------
    >>> type(load_scene("macbeth")).__name__, type(load_scene("face")).__name__
    ('ChartScene', 'FaceScene')
    """
    from .face.scene import is_face_scene, load_face_scene  # here: importing skinrender need not load the face
    from .scene import load_chart_scene

    return load_face_scene(spec) if is_face_scene(spec) else load_chart_scene(spec)


def _options(function) -> list[str]:
    """The names a renderer takes: its parameters, ``settings`` led by the render settings' fields (which its
    ``**options`` take one by one)."""
    from dataclasses import fields

    from .settings import RenderSettings

    names = []
    for name, parameter in inspect.signature(function).parameters.items():
        if name == "settings":
            names += [field.name for field in fields(RenderSettings)]
        if parameter.kind is not parameter.VAR_KEYWORD:
            names.append(name)
    return names


def _camera_of(camera, options: dict, what: str):
    """The camera given as ``camera`` or (the chart functions' name) ``camera_``, once."""
    if "camera_" in options:
        if camera is not None:
            raise SkinrenderError(f"{what}: give the camera once (camera or camera_)")
        camera = options.pop("camera_")
    if camera is None:
        raise SkinrenderError("camera: name the camera (a Camera or a spec such as gbell:9@450,540,610)")
    return camera


def _check_options(function, arguments: dict, options: dict, kind: str, what: str, forwards_to=None) -> None:
    """Refuse, naming them, options that ``function`` (of a ``kind`` scene) does not take, nor ``forwards_to`` (the
    function its ``**options`` go to)."""
    names = ([] if forwards_to is None else _options(forwards_to)) + _options(function)  # the render's first
    known = [name for name in dict.fromkeys(names) if name not in arguments]
    unknown = sorted(set(options) - set(known))
    if unknown:
        verb = "is not an option" if len(unknown) == 1 else "are not options"
        raise SkinrenderError(f"{what}: {', '.join(unknown)} {verb} of a {kind} scene; its options: "
                              f"{', '.join(known)}")


def _chart_lights(prevailing, calibration, what: str) -> None:
    for name, value in (("prevailing", prevailing), ("calibration", calibration)):
        if value is None:
            raise SkinrenderError(f"{name}: a chart {what} needs the {name} light (kelvin, A or H)")


def render(scene, camera=None, prevailing=None, calibration=None, spectral: bool = False, **options):
    """
    Render a chart or a face scene through a camera, white balanced to the calibration light (Eq. 4); with
    ``spectral=True``, once for every camera: a :class:`~skinrender.rendering.spectral_image.SpectralImage` (no camera,
    no calibration: ``.through(camera, calibration=K)`` gives each camera's result).

    Parameters
    ----------
    scene
        A chart or a face scene: a bundled name, a TOML path, or a parsed scene.
    camera
        A :class:`~skinrender.model.camera.Camera` or a camera spec (``gbell:9@450,540,610``, a CSV path).
    prevailing, calibration
        Planckian lights: kelvin, ``A`` (2856 K) or ``H`` (2300 K). A chart needs both; a face keeps its
        scene's key light where ``prevailing`` is ``None``, and is balanced to the prevailing light where
        ``calibration`` is ``None``.
    **options
        A chart's: ``normalization``, ``knee``, ``spp`` (default 256), ``seed``, ``sampler``, ``variant``,
        ``channels`` (or all five as ``settings``, a :class:`~skinrender.rendering.settings.RenderSettings`),
        ``grid``, ``cache``, ``emitter`` (:func:`skinrender.rendering.balance.render`).
        A face's: ``skin``, ``physics`` (``direct``, effects joined by ``+``), ``spp`` (default 64), ``seed``,
        ``size`` (pixels), ``sampler``, ``variant``, ``grid``, ``channels``, ``imager``, ``exposure`` (s or
        ``auto``), ``illuminance`` (lx) (:func:`skinrender.rendering.face.render.render_face`).
        A spectral render's: ``bands`` (``START:END:STEP`` nm, default 400:700:5) and the options above but a
        chart's ``normalization``, ``knee``, ``cache`` and ``channels`` (applied by ``.through``, or meaningless).
    spectral
        Render the bands of :mod:`~skinrender.rendering.bands` instead of a camera's channels
        (:func:`~skinrender.rendering.spectral_image.render_spectral`).

    Returns
    -------
    :class:`~skinrender.rendering.balance.Rendering`, :class:`~skinrender.rendering.face.render.FaceRendering`
    or, spectral, :class:`~skinrender.rendering.spectral_image.SpectralImage`

    Raises
    ------
    SkinrenderError
        A bad scene, camera, light or option, each named; an option of the other kind of scene (``physics``
        for a chart, ``normalization`` for a face).

    Examples
    --------
    >>> import skinrender as sr
    >>> face = sr.render("face", camera="gbell:9@450,540,610", prevailing=2856, calibration=5900,
    ...                  physics="sheen", spp=4, size=16)  # doctest: +SKIP
    >>> face.physics, face.image.shape  # doctest: +SKIP
    ('sheen', (16, 16, 3))
    """

    if spectral:
        return _render_spectral(scene, camera, prevailing, calibration, options)
    camera = _camera_of(camera, options, "render")
    from .face.scene import FaceScene

    scene = load_scene(scene)
    if isinstance(scene, FaceScene):
        from .face.render import render_face

        kind, function = "face", render_face
        arguments = {"camera_": camera, "scene": scene, "prevailing": prevailing, "calibration": calibration}
    else:
        from .balance import render as render_chart

        _chart_lights(prevailing, calibration, "render")
        kind, function = "chart", render_chart
        arguments = {"scene": scene, "camera_": camera, "prevailing": prevailing, "calibration": calibration}
    _check_options(function, arguments, options, kind, "render")
    return function(**arguments, **options)


def _render_spectral(scene, camera, prevailing, calibration, options: dict):
    """``render(…, spectral=True)``: no camera, no calibration (both applied by ``.through``), the options
    checked against the spectral renderer of the scene's kind."""
    for name, value in (("camera", camera if camera is not None else options.get("camera_")),
                        ("calibration", calibration)):
        if value is not None:
            raise SkinrenderError(f"{name}: a spectral render takes no {name}; see it through one afterwards: "
                                  "SpectralImage.through(camera, calibration=K)")
    from .face.scene import FaceScene

    scene = load_scene(scene)
    if isinstance(scene, FaceScene):
        from .face.spectral_face import render_face_spectral as function

        kind = "face"
    else:
        from .spectral_chart import render_chart_spectral as function

        kind = "chart"
        _chart_lights(prevailing, 0, "spectral render")
    _check_options(function, {"scene": scene, "prevailing": prevailing}, options, kind, "render")
    return render_spectral(scene, prevailing, **options)


def validate(scene, camera=None, prevailing=None, calibration=None, **options):
    """
    Render a chart or a face scene and check it against the analytic model: a three-way verdict.

    Parameters
    ----------
    scene
        A chart or a face scene: a bundled name, a TOML path, or a parsed scene.
    camera
        A :class:`~skinrender.model.camera.Camera` or a camera spec (``camera_`` is taken too).
    prevailing, calibration
        Planckian lights (kelvin, ``A``, ``H``), as :func:`render`.
    **options
        A chart's: ``tolerance`` (relative), ``alpha``, ``alpha_difference``, ``rendering``, ``normalization``,
        ``knee``, ``grid`` and the render settings (:func:`skinrender.rendering.validation.validate`).
        A face's: ``skin``, ``physics``, ``spp`` (in all, over the replicates), ``seed``, ``size`` (pixels),
        ``replicates``, ``limits``, ``budget_fraction``, ``imager``, ``exposure`` (s or ``auto``),
        ``illuminance`` (lx) … (:func:`skinrender.rendering.face.validation.validate_face`).

    Returns
    -------
    :class:`~skinrender.rendering.validation.Validation` or :class:`~skinrender.rendering.face.validation.FaceValidation`
        Both with ``verdict`` (a :class:`~skinrender.evaluation.verdict.Verdict`), ``bound`` (a chart's: the
        smallest relative tolerance that would pass; a face's: the upper bound of Eq. 4's NCC error, the
        smallest detection budget that would pass) and ``spp_needed`` (the spp expected to pass, or ``None``).

    Raises
    ------
    SkinrenderError
        A bad scene, camera, light or option, each named; an option of the other kind of scene.

    Examples
    --------
    >>> import skinrender as sr
    >>> v = sr.validate("face", "gbell:9@450,540,610", 2856, 2856, physics="direct", spp=48,
    ...                 size=24)  # doctest: +SKIP
    >>> v.verdict.outcome, v.spp_needed  # doctest: +SKIP
    ('pass', 192)
    """

    camera = _camera_of(camera, options, "validate")
    from .face.scene import FaceScene

    scene = load_scene(scene)
    if isinstance(scene, FaceScene):
        from .face.validation import validate_face

        from .face.render import render_face

        kind, function, forwards_to = "face", validate_face, render_face
    else:
        from .balance import render as render_chart
        from .validation import validate as validate_chart

        _chart_lights(prevailing, calibration, "validation")
        kind, function, forwards_to = "chart", validate_chart, render_chart
    arguments = {"scene": scene, "camera_": camera, "prevailing": prevailing, "calibration": calibration}
    _check_options(function, arguments, options, kind, "validate", forwards_to)
    return function(**arguments, **options)


def render_spectral(scene, prevailing=None, bands=BANDS_DEFAULT, **options):
    """
    Render a chart or a face once with the bands as its film (no camera, no calibration: both applied by
    :meth:`~skinrender.rendering.spectral_image.SpectralImage.through`).

    Parameters
    ----------
    scene
        A chart or a face: a bundled name, a TOML path or a parsed scene.
    prevailing
        The light: kelvin, ``A`` or ``H`` (a chart needs it; a face keeps its scene's key light where
        ``None``).
    bands
        ``START:END:STEP`` nm or a :class:`~skinrender.spectra.WavelengthGrid` (default 400:700:5).
    **options
        A chart's: ``spp``, ``seed``, ``sampler``, ``variant`` (or ``settings``), ``grid``, ``emitter``,
        ``physics`` (``direct``) (:func:`~skinrender.rendering.spectral_chart.render_chart_spectral`). A face's:
        ``skin``, ``physics``, ``spp``, ``seed``, ``size``, ``sampler``, ``variant``, ``grid``, ``imager``,
        ``exposure``, ``illuminance`` (:func:`~skinrender.rendering.face.spectral_face.render_face_spectral`).
    """
    from .face.scene import FaceScene

    scene = load_scene(scene)
    if isinstance(scene, FaceScene):
        from .face.spectral_face import render_face_spectral

        return render_face_spectral(scene, prevailing, bands=bands, **options)
    from .spectral_chart import render_chart_spectral

    if prevailing is None:
        raise SkinrenderError("prevailing: a chart's spectral render needs its light (kelvin, A or H)")
    return render_chart_spectral(scene, prevailing, bands, **options)


def render_cameras(scene, cameras, prevailing=None, calibration=None, bands=BANDS_DEFAULT, **options) -> list:
    """
    Render ``scene`` once spectrally, then return each camera's result: what ``sr.render(scene, camera,
    prevailing, calibration, …)`` returns for every camera of ``cameras``, in their order, from one render
    (their images share its light paths).

    Parameters
    ----------
    scene, prevailing, bands, options
        As :func:`render_spectral`.
    cameras
        Cameras or specs (at least one).
    calibration
        The white balance's light (kelvin, ``A``, ``H``); ``None``: the prevailing light. The chart's
        ``normalization`` and ``knee`` go in ``options`` too.

    Examples
    --------
    >>> import skinrender as sr
    >>> faces = sr.render_cameras("face", ["gbell:9@450,540,610", "Nikon 5100 (NPL)"], 2856, 5900,
    ...                           spp=4, size=16)  # doctest: +SKIP
    >>> [face.camera.name for face in faces]  # doctest: +SKIP
    ['gbell:9@450,540,610', 'Nikon 5100 (NPL)']
    """
    from ..model.camera import camera
    from ..model.illuminant import illuminant
    from ..spectra import GRID_DEFAULT
    from .bands import parse_bands, projection

    cams = [camera(cam) for cam in cameras] if not isinstance(cameras, (str, bytes)) else [camera(cameras)]
    if not cams:
        raise SkinrenderError("cameras: name at least one camera")
    bands = parse_bands(bands)
    for cam in cams:  # every camera checked against the bands before the render
        projection(cam, bands, options.get("grid", GRID_DEFAULT))
    if calibration is not None and illuminant(calibration).temperature is None:
        raise SkinrenderError(f"calibration: a Planckian light (kelvin, A or H), got {calibration!r}")
    balance = {key: options.pop(key) for key in ("normalization", "knee") if key in options}
    spectral = render_spectral(scene, prevailing, bands, **options)
    return [spectral.through(cam, calibration, **balance) for cam in cams]
