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

from ..errors import SkinrenderError, given_role
from .bands import BANDS_DEFAULT

__all__ = ["load_scene", "render", "validate", "render_spectral", "render_cameras", "SPECTRAL_OMITTED"]


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
    from .kinds import scene_kind  # here: importing skinrender need not load the face

    return given_role("scene", lambda: scene_kind(spec).load(spec))  # a file's or a name's fault: the scene's


def _camera_of(camera, options: dict, what: str):
    """The camera given as ``camera`` or (the chart functions' name) ``camera_``, once."""
    if "camera_" in options:
        if camera is not None:
            raise SkinrenderError(f"{what}: give the camera once (camera or camera_)", role="camera")
        camera = options.pop("camera_")
    if camera is None:
        raise SkinrenderError("camera: name the camera (a Camera or a spec such as gbell:9@450,540,610)",
                              role="camera")
    return camera


def _check_options(names: tuple[str, ...], arguments: dict, options: dict, kind: str, what: str) -> None:
    """Refuse, naming them, options not among a ``kind`` scene's ``names`` (nor given as ``arguments``)."""
    known = [name for name in dict.fromkeys(names) if name not in arguments]
    unknown = sorted(set(options) - set(known))
    if unknown:
        verb = "is not an option" if len(unknown) == 1 else "are not options"
        raise SkinrenderError(f"{what}: {', '.join(unknown)} {verb} of a {kind} scene; its options: "
                              f"{', '.join(known)}")


def _lights(kind, prevailing, calibration, what: str) -> None:
    """The lights a kind's request cannot do without: a chart needs both (a face keeps its scene's)."""
    if not kind.lights_required:
        return
    for name, value in (("prevailing", prevailing), ("calibration", calibration)):
        if value is None:
            raise SkinrenderError(f"{name}: a chart {what} needs the {name} light (kelvin, A or H)", role=name)


def render(scene, camera=None, prevailing=None, calibration=None, spectral: bool = False, **options):
    """
    Render a chart or a face scene through a camera, white balanced to the calibration light (Eq. 4); with
    ``spectral=True``, once for every camera: a :class:`~skinrender.rendering.spectral_image.SpectralImage` (no
    camera, no calibration: ``.through(camera, calibration=K)`` gives each camera's result).

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
        chart's ``normalization``, ``knee``, ``cache``, a sensor's, and ``channels`` (applied by ``.through``, or
        meaningless).
    spectral
        Render the bands of :mod:`~skinrender.rendering.bands` instead of a camera's channels
        (:func:`render_spectral`; the request's ``bands``).

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
        from .request import spectral_only

        spectral_only(camera if camera is not None else options.get("camera_"), calibration)
        return render_spectral(scene, prevailing, **options)
    camera = _camera_of(camera, options, "render")
    from .kinds import scene_kind

    kind = scene_kind(scene)
    scene = kind.load(scene)
    _lights(kind, prevailing, calibration, "render")
    _check_options(kind.render_options, {}, options, kind.name, "render")
    after = {name: options.pop(name) for name in ("cache",) if name in options}  # the render's, not the request's
    return kind.render(kind.request(scene, camera, prevailing, calibration, **options), **after)


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
    from .kinds import scene_kind

    kind = scene_kind(scene)
    scene = kind.load(scene)
    _lights(kind, prevailing, calibration, "validation")
    _check_options(kind.validate_options, {}, options, kind.name, "validate")
    return kind.validate_of(scene, camera, prevailing, calibration, **options)


SPECTRAL_OMITTED = ("normalization", "knee", "cache", "channels", "imager", "exposure", "illuminance")
"""A chart's render options a spectral render does not take (a face's sensor options it does: ``noise``)."""


def render_spectral(scene, prevailing=None, bands=BANDS_DEFAULT, **options):
    """
    Render a chart or a face once with the bands as its film (no camera, no calibration: both applied by
    :meth:`~skinrender.rendering.spectral_image.SpectralImage.through`): the kind's request with ``bands``,
    rendered by the kind.

    Parameters
    ----------
    scene
        A chart or a face: a bundled name, a TOML path or a parsed scene.
    prevailing
        The light: kelvin, ``A`` or ``H`` (a chart needs it; a face keeps its scene's key light where ``None``).
    bands
        ``START:END:STEP`` nm or a :class:`~skinrender.spectra.WavelengthGrid` (default 400:700:5).
    **options
        A chart's: ``spp``, ``seed``, ``sampler``, ``variant`` (or ``settings``), ``grid``, ``emitter``,
        ``physics`` (``direct``). A face's: ``skin``, ``physics``, ``spp``, ``seed``, ``size``, ``sampler``,
        ``variant``, ``grid``, ``imager``, ``exposure``, ``illuminance`` (the ``noise`` sensor, applied per camera).
    """
    from .kinds import scene_kind

    kind = scene_kind(scene)
    scene = kind.load(scene)
    names = tuple(name for name in kind.render_options
                  if not (kind.lights_required and name in SPECTRAL_OMITTED) and name != "channels")
    _check_options(names, {}, options, kind.name, "spectral render")
    if kind.lights_required and prevailing is None:
        raise SkinrenderError(f"prevailing: a {kind.name}'s spectral render needs its light (kelvin, A or H)",
                              role="prevailing")
    return kind.render(kind.request(scene, None, prevailing, None, bands=bands, **options))


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
        The white balance's light (kelvin, ``A``, ``H``); ``None``: the prevailing light. A chart's
        ``normalization`` and ``knee`` go in ``options`` too (applied by each ``through``).

    Examples
    --------
    >>> import skinrender as sr
    >>> faces = sr.render_cameras("face", ["gbell:9@450,540,610", "Nikon 5100 (NPL)"], 2856, 5900,
    ...                           spp=4, size=16)  # doctest: +SKIP
    >>> [face.camera.name for face in faces]  # doctest: +SKIP
    ['gbell:9@450,540,610', 'Nikon 5100 (NPL)']
    """
    from ..model.camera import camera
    from ..spectra import GRID_DEFAULT, as_grid
    from .bands import parse_bands, projection
    from .request import planckian

    cams = [camera(cam) for cam in cameras] if not isinstance(cameras, (str, bytes)) else [camera(cameras)]
    if not cams:
        raise SkinrenderError("cameras: name at least one camera", role="cameras")
    bands = parse_bands(bands)
    if "grid" in options:
        options["grid"] = as_grid(options["grid"])  # its text too, as --grid
    for cam in cams:  # every camera checked against the bands before the render
        projection(cam, bands, options.get("grid", GRID_DEFAULT))
    if calibration is not None:
        planckian(calibration, "calibration")
    balance = {key: options.pop(key) for key in ("normalization", "knee") if key in options}
    spectral = render_spectral(scene, prevailing, bands, **options)
    return [spectral.through(cam, calibration, **balance) for cam in cams]
