"""
Render regressions: measure a scene, compare two measurements
=============================================================

What :class:`~skinrender.testing.plugin.RenderRegression` renders and how it
tells a change from noise, without pytest (the plugin is the glue).

-   :func:`measure`, :class:`Measurement`: a chart or a face rendered through
    a camera, reduced to the values a regression compares, each with its
    standard error and degrees of freedom.
-   :func:`compare`, :class:`Comparison`: the new values against a
    reference's, ``z = (new − reference) / √(SE_new² + SE_ref²)``, one
    difference verdict (:func:`skinrender.evaluation.verdict.difference`) at a
    family-wise false-alarm rate α over all of them (Šidák), as Mitsuba's own
    render regression tests do with their z-test :cite:`Jakob2022`.

What is compared
----------------
**Charts** (:func:`skinrender.rendering.balance.render`, or through an
image sensor :func:`skinrender.rendering.imaging.render_imaged`): each patch's
mean per channel, output units. A flat patch under the directional light has
pixels that are independent samples of one mean (a ``box`` filter), so its
standard error is the pixel standard deviation over √n
(:func:`~skinrender.rendering.balance.patch_statistics`), with ``n − 1``
degrees of freedom. Every patch is divided by the rendered white reference
(Eq. 4 with WP, Eq. 8), so the whites' relative standard errors add
(:func:`_white_relative_variance`): ``SE² = SE_patch² + mean² ·
relative_k``.

**Faces** (:func:`skinrender.rendering.face.render.render_face`): each labelled
region's mean per channel (label 0 background, 1 skin, 2… props) and the skin
region's NCC ``r, g``, their standard errors from :data:`REPLICATES`
independent replicates (:mod:`skinrender.testing.replicates`: a region's
pixels are not samples of one mean, its shading varies, so the noise comes
from each pixel's Monte Carlo variance over the replicates).

Each difference is held to Student's t at its own (Welch's) degrees of
freedom, at the Šidák level of the family. Values that are exactly equal with
no noise (a black background) are exact and pass.

Units: means and standard errors in Eq. 4 output units (255 for white at
p = c), NCC fractions; temperatures K, illuminance lx.

References
----------
-   :cite:`Jakob2022` : W. Jakob, S. Speierer, N. Roussel, M. Nimier-David,
    D. Vicini, T. Zeltner, B. Nicolet, M. Crespo, V. Leroy, Z. Zhang (2022).
    Mitsuba 3 renderer, version 3.0. https://mitsuba-renderer.org
    (``python/mitsuba/testing``: render regression tests by a z-test on
    reference and variance images, Šidák-corrected).
-   :cite:`Sidak1967` (:mod:`skinrender.evaluation.verdict`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import SkinrenderError
from ..evaluation.verdict import ALPHA_DIFFERENCE, Verdict, difference, sidak
from ..hints import NDArrayFloat
from .replicates import measure_face, region_values

__all__ = ["REFERENCE_SPP_FACTOR", "SPP_CHART", "SPP_FACE", "SIZE_FACE",
           "ILLUMINANCE_DEFAULT_LUX", "Measurement", "Comparison", "scene_kind", "measure", "measure_spectral",
           "values_of", "setting_notes", "compare"]

REFERENCE_SPP_FACTOR = 4
"""A reference is rendered at this many times the check's spp (with its own seed,
:func:`~skinrender.testing.reference.reference_seed`): its
own noise then moves every later check's z by at most ``1/√5`` of its deviation (``1/√2`` at equal spp), so that
one unlucky reference does not raise the false-alarm rate of all the checks against it, as Mitsuba's high-spp
references do not."""

SPP_CHART = 64
"""Samples per pixel of a chart check unless given (a check ~0.2 s after the first; a 2 nm shift at z > 10)."""

SPP_FACE = 64
"""Samples per pixel of a face check unless given, over all :data:`REPLICATES` (16 each)."""

SIZE_FACE = 64
"""Image side of a face check unless given, pixels: a reference of ~60 kB."""

ILLUMINANCE_DEFAULT_LUX = 500.0
"""A chart's illuminance through an ``imager`` unless given, lx (every door's:
:data:`skinrender.rendering.request.ILLUMINANCE_DEFAULT`)."""


@dataclass(frozen=True)
class Measurement:
    """
    A render reduced to the values a regression compares.

    Attributes
    ----------
    kind
        ``chart`` or ``face``.
    image
        ``(height, width, 3)`` float32, output units (a face: the mean of its replicates).
    labels
        ``(height, width)`` int32 region labels of a face; ``None`` for a chart.
    channels
        The image's EXR channel names (by the camera).
    regions
        Patch names (chart) or ``{name: label}`` of the regions present (face).
    items
        One name per value: ``"<patch or region> / <channel>"``, ``"skin NCC / r"``.
    mean, standard_error, dof
        Per value (output units; NCC fractions); ``dof`` inf where the standard error is 0.
    settings
        What made it, JSON-ready: scene, camera and its curves' hash, temperatures, spp, seed, variant, …
    scene
        The :class:`~skinrender.rendering.scene.ChartScene` of a chart (its patch layout); ``None`` for a face.
    """

    kind: str
    image: NDArrayFloat
    labels: NDArrayFloat | None
    channels: tuple[str, ...]
    regions: tuple[str, ...] | dict
    items: tuple[str, ...]
    mean: NDArrayFloat
    standard_error: NDArrayFloat
    dof: NDArrayFloat
    settings: dict = field(default_factory=dict)
    scene: object = None


def scene_kind(spec) -> str:
    """
    The name of a scene's kind (:func:`skinrender.rendering.kinds.scene_kind`): ``face`` for a ``FaceScene``, a
    bundled face name, or a ``.toml`` with ``[camera]`` and ``[mesh]``, else ``chart`` (the chart loader then names
    any error).

    >>> scene_kind("macbeth"), scene_kind("face")
    ('chart', 'face')
    """
    from ..rendering.kinds import scene_kind as kind_of

    return kind_of(spec).name


def _named(name: str, function, *args, **kwargs):
    """``function(*args)``, its :class:`SkinrenderError` prefixed with the argument ``name`` unless it names it
    already (its ``role`` is ``name``: ``camera 'x': …``)."""
    try:
        return function(*args, **kwargs)
    except SkinrenderError as error:
        if error.role == name:
            raise
        raise error.reworded(f"{name}: {error.message}", role=name) from None


def _planckian(spec, name: str) -> float:
    from ..model.illuminant import illuminant

    light = _named(name, illuminant, spec)
    if light.temperature is None:
        raise SkinrenderError(f"{name}: rendering needs a Planckian illuminant (kelvin, A or H), got {light}")
    return float(light.temperature)


def _white_relative_variance(rendering) -> NDArrayFloat:
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

    def relative_covariance(raw) -> NDArrayFloat:
        rows, columns = rendering.scene.patch_pixels(rendering.scene.white_index)
        pixels = raw.radiance[rows, columns].reshape(-1, 3)
        mean = pixels.mean(axis=0)
        return np.cov(pixels, rowvar=False) / len(pixels) / np.outer(mean, mean)

    analytic = rendering.info.get("white_calibration") == "analytic"  # a spectral render's: computed, exact
    sigma_c = 0.0 * relative_covariance(rendering.raw[-1]) if analytic else relative_covariance(rendering.raw[-1])
    if rendering.normalization != "white" or rendering.prevailing == rendering.calibration:
        return np.diagonal(sigma_c).copy()
    sigma_w = relative_covariance(rendering.raw[0])
    ratio = rendering.info["white_ratio"]
    w = ratio / ratio.sum()
    a = w[None, :] - np.eye(3)
    return w @ sigma_w @ w + np.einsum("ki,ij,kj->k", a, sigma_c, a)


def _chart(chart, cam, prevailing, calibration, spp, seed, imager, illuminance, variant) -> Measurement:
    from ..rendering.kinds import CHART

    request = CHART.request(chart, cam, prevailing, calibration, spp=spp, seed=seed, variant=variant, imager=imager,
                            illuminance=illuminance)  # the one request of every door
    rendering, imaged = CHART.render_imaged(request)
    # through a sensor the balance's whites are noise-free; else the rendered whites' noise adds to every patch
    relative = np.zeros(3) if imaged is not None else _white_relative_variance(rendering)
    settings = {} if imaged is None else {"imager": imaged.imager.name, "illuminance_lux": imaged.illuminance_lux}
    return _chart_values(chart, cam, rendering, relative, settings)


def _chart_values(chart, cam, rendering, relative, settings: dict) -> Measurement:
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


def _integer(value, name: str, low: int, high: int) -> int:
    if not (isinstance(value, (int, np.integer)) and not isinstance(value, bool) and low <= value < high):
        raise SkinrenderError(f"{name} must be an integer in [{low}, {high}), got {value!r}")
    return int(value)


def measure(scene, camera, prevailing, calibration, spp: int | None = None, seed: int = 0, physics: str | None = None,
            skin: str | None = None, imager: str | None = None, illuminance: float | None = None,
            size: int | None = None, variant: str | None = None, factor: int = 1,
            render_seed: int | None = None) -> Measurement:
    """
    Render ``scene`` (a chart or a face) through ``camera`` under the Planckian ``prevailing`` light (K),
    white balanced to ``calibration`` (K), and reduce it to the values a regression compares (module
    docstring).

    ``camera`` may be a list of cameras: the scene is then rendered once spectrally (a face: once per replicate
    seed) and seen through each (:func:`measure_spectral`), and a list of measurements returned, one per camera,
    in their order.

    ``spp`` defaults to :data:`SPP_CHART` or :data:`SPP_FACE`; ``physics``, ``skin`` and ``size`` (pixels,
    default :data:`SIZE_FACE`) go with faces; ``imager`` (and ``illuminance``, lx) put the image sensor's
    noise in (a face: physics ``noise``). ``factor``: render at ``factor × spp`` (a reference,
    :data:`REFERENCE_SPP_FACTOR`); the settings keep ``spp_requested`` the check's. ``render_seed``: render with
    this seed rather than ``seed`` (a reference, :func:`~skinrender.testing.reference.reference_seed`); the settings
    keep ``seed`` the check's
    and add ``reference_seed``. Any bad argument raises a one-line :class:`SkinrenderError` naming it.
    """
    from ..model.camera import camera as camera_of
    from ..rendering.exr import camera_attributes
    from ..rendering.scene import load_chart_scene
    from ..rendering.settings import SEED_MAX, SPP_MAX

    kind = scene_kind(scene)
    if kind == "chart":  # the plugin's own refusals (it checks a chart at direct, a face at any level)
        chart = _named("scene", load_chart_scene, scene)
        given = [n for n, v in (("physics", physics not in (None, "direct")), ("skin", skin is not None),
                                ("size", size is not None)) if v]
        if given:
            raise SkinrenderError(f"{', '.join(given)}: {'goes' if len(given) == 1 else 'go'} with a face scene "
                                  "(e.g. 'face'), not a chart")
        if illuminance is not None and imager is None:
            raise SkinrenderError("illuminance sets the image sensor's exposure: it goes with imager")
    several = isinstance(camera, (list, tuple))
    cams = [_named("camera", camera_of, one) for one in (camera if several else [camera])]
    if not cams:
        raise SkinrenderError("camera: name at least one camera")
    for cam in cams:
        _named("camera", cam.sensitivities)
    cam = cams[0]
    p, c = _planckian(prevailing, "prevailing"), _planckian(calibration, "calibration")
    spp = _integer(SPP_CHART if kind == "chart" and spp is None else SPP_FACE if spp is None else spp, "spp", 1,
                   SPP_MAX + 1)
    seed = _integer(seed, "seed", 0, SEED_MAX + 1)  # the bound of every front door
    renders = seed if render_seed is None else _integer(render_seed, "render_seed", 0, SEED_MAX + 1)
    size = SIZE_FACE if size is None else size
    if several:
        found = measure_spectral(kind, chart if kind == "chart" else scene, cams, p, c, spp * factor, renders, physics,
                                 skin, imager, illuminance, size, variant)
    elif kind == "chart":
        found = [_chart(chart, cam, p, c, spp * factor, renders, imager, illuminance, variant)]
    else:
        found = [Measurement("face", *measure_face(scene, cam, p, c, spp * factor, renders, physics, skin, imager,
                                                   illuminance, size, variant))]
    from .. import __version__

    out = []
    for cam, one in zip(cams, found):
        name = chart.name if kind == "chart" else one.settings.pop("scene_name")
        settings = {"kind": kind, "scene": name, **camera_attributes(cam), "prevailing_K": p, "calibration_K": c,
                    "spp_requested": spp, "seed": seed,
                    **({} if render_seed is None else {"reference_seed": renders}), **one.settings,
                    "skinrender_version": __version__}
        out.append(Measurement(one.kind, one.image, one.labels, one.channels, one.regions, one.items, one.mean,
                               one.standard_error, one.dof, settings, chart if kind == "chart" else None))
    return out if several else out[0]


def measure_spectral(kind: str, scene, cameras: list, prevailing: float, calibration: float, spp: int, seed: int,
                     physics: str | None, skin: str | None, imager: str | None, illuminance: float | None, size: int,
                     variant: str | None) -> list:
    """
    One :class:`Measurement` per camera of ``cameras`` from one spectral render of ``scene`` (a loaded chart, or a
    face spec; a face: one per replicate seed) with :data:`~skinrender.rendering.bands.BANDS_DEFAULT` (arguments
    as :func:`measure`; a chart through an ``imager`` is refused: its sensor records a camera's channels). The
    settings add ``spectral_bands_nm``, so that a reference made one render per camera is told apart in a
    failure's notes.
    """
    from ..rendering.bands import BANDS_DEFAULT, bands_text
    from ..rendering.kinds import CHART, FACE
    from .replicates import face_check_request, reduce_face, replicate_seeds

    bands = {"spectral_bands_nm": bands_text(BANDS_DEFAULT)}
    if kind == "chart":
        if imager is not None:
            raise SkinrenderError("imager: a chart's image sensor records one camera's render; check several cameras "
                                  "without it, or one camera at a time")
        image = CHART.render(CHART.request(scene, None, prevailing, None, spp=spp, seed=seed, variant=variant,
                                           bands=BANDS_DEFAULT))
        out = []
        for cam in cameras:
            rendering = image.through(cam, calibration)
            out.append(_chart_values(scene, cam, rendering, _white_relative_variance(rendering), bands))
        return out
    request = face_check_request(scene, None, prevailing, None, spp, seed, physics, skin, imager, illuminance, size,
                                 variant, BANDS_DEFAULT)
    images = [FACE.render(request, s) for s in replicate_seeds(seed)]
    out = []
    for cam in cameras:
        found = Measurement("face", *reduce_face([image.through(cam, calibration) for image in images], cam))
        out.append(Measurement(found.kind, found.image, found.labels, found.channels, found.regions, found.items,
                               found.mean, found.standard_error, found.dof, {**found.settings, **bands}))
    return out


def values_of(kind: str, image: NDArrayFloat, labels: NDArrayFloat | None, regions, scene=None) -> NDArrayFloat:
    """The compared means of a stored image: a chart's patch means (``scene`` its chart) or a face's region means
    and skin NCC (``regions`` ``{name: label}``), in :attr:`Measurement.items` order."""
    if kind == "chart":
        from ..rendering.balance import patch_statistics

        return patch_statistics(image, scene).mean.ravel()
    return region_values(image, labels, dict(regions))[0]


@dataclass(frozen=True)
class Comparison:
    """
    A new measurement against a reference.

    ``z`` per value (``(new − reference) / combined SE``; 0 where both are exact and equal), each value's
    ``critical`` value (Student's t at its Welch degrees of freedom, Šidák level), the
    :class:`~skinrender.evaluation.verdict.Verdict`, and ``notes`` (settings that differ from the reference's:
    camera curves, variant, spp, …).
    """

    items: tuple[str, ...]
    new: NDArrayFloat
    reference: NDArrayFloat
    z: NDArrayFloat
    critical: NDArrayFloat
    verdict: Verdict
    notes: tuple[str, ...] = ()

    @property
    def beyond(self) -> list[int]:
        """Indices of the values beyond their critical value, furthest first."""
        ratio = np.abs(self.z) / self.critical
        return [int(i) for i in np.argsort(-ratio) if ratio[i] > 1]

    @property
    def passed(self) -> bool:
        """No difference detected."""
        return self.verdict.outcome == "pass"

    @property
    def worst(self) -> int:
        """Index of the value furthest beyond (or nearest to) its critical value."""
        return int(self.verdict.details.get("worst", np.argmax(np.abs(self.z))))

    def summary(self) -> str:
        """One line: the verdict and the worst value with its z and critical value."""
        i = self.worst
        return (f"worst {self.items[i]}: {self.new[i]:.6g} against {self.reference[i]:.6g}, z = {self.z[i]:+.3g} "
                f"(critical {self.verdict.threshold:.3g} for {len(self.items)} values at family-wise "
                f"α = {self.verdict.alpha:g}, Šidák)")


NOTED = {"camera_sha256": "the camera's curves", "variant": "the Mitsuba variant", "spp_requested": "spp",
         "seed": "the seed", "skinrender_version": "the skinrender version", "physics": "the physics",
         "skin": "the skin", "imager": "the imager", "prevailing_K": "the prevailing light (K)",
         "calibration_K": "the calibration light (K)", "size": "the image size",
         "spectral_bands_nm": "the spectral bands (nm; none: one render per camera)"}
"""Settings whose change against the reference is noted in a failure message, key → words."""


def setting_notes(new: dict, reference: dict) -> tuple[str, ...]:
    """
    What differs between two measurements' settings, one note each.

    >>> setting_notes({"spp_requested": 64, "variant": "a"}, {"spp_requested": 16, "variant": "a"})
    ('spp changed: 16 in the reference, 64 now',)
    """
    notes = []
    for key, words in NOTED.items():
        if new.get(key) != reference.get(key):
            old, now = reference.get(key), new.get(key)
            if key == "camera_sha256":
                old, now = f"{reference.get('camera')} {str(old)[:12]}…", f"{new.get('camera')} {str(now)[:12]}…"
            notes.append(f"{words} changed: {old} in the reference, {now} now")
    return tuple(notes)


def compare(new: Measurement, reference_mean: NDArrayFloat, reference_se: NDArrayFloat, reference_dof: NDArrayFloat,
            alpha: float = ALPHA_DIFFERENCE, notes: tuple[str, ...] = ()) -> Comparison:
    """
    ``new`` against a reference's means, standard errors and degrees of freedom (same items, same order):
    :func:`~skinrender.evaluation.verdict.difference` of the differences over their combined standard errors at
    family-wise ``alpha``, each held to Student's t at its own Welch degrees of freedom.

    >>> m = Measurement("chart", None, None, (), (), ("a / R", "b / R"), np.array([1.0, 2.0]),
    ...                 np.array([0.1, 0.1]), np.array([50.0, 50.0]))
    >>> compare(m, np.array([1.05, 2.0]), np.array([0.1, 0.1]), np.array([50.0, 50.0])).passed
    True
    >>> compare(m, np.array([3.0, 2.0]), np.array([0.1, 0.1]), np.array([50.0, 50.0])).summary().split(" (")[0]
    'worst a / R: 1 against 3, z = -14.1'
    """
    from scipy import stats

    variance_new, variance_ref = new.standard_error**2, np.asarray(reference_se, dtype=np.float64) ** 2
    combined = variance_new + variance_ref
    deviation = new.mean - np.asarray(reference_mean, dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        welch = combined**2 / (variance_new**2 / new.dof + variance_ref**2 / np.asarray(reference_dof, float))
        z = np.where(combined > 0, deviation / np.sqrt(np.where(combined > 0, combined, 1.0)),
                     np.where(deviation == 0, 0.0, np.sign(deviation) * np.inf))
    dof = np.where(np.isfinite(welch) & (combined > 0), np.maximum(welch, 1.0), np.inf)
    verdict = difference(deviation, np.sqrt(combined), alpha, dof=dof, name="render regression")
    critical = stats.t.isf(sidak(alpha, dof.size) / 2, dof)
    return Comparison(new.items, new.mean, np.asarray(reference_mean, dtype=np.float64), z, critical, verdict,
                      tuple(notes))
