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
(:func:`~skinrender.testing.kind_checks.white_relative_variance`): ``SE² = SE_patch² + mean² ·
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

from dataclasses import dataclass

import numpy as np

from ..errors import SkinrenderError
from ..evaluation.verdict import ALPHA_DIFFERENCE, Verdict, difference, sidak
from ..hints import NDArrayFloat
from .kind_checks import SPP_CHART, SPP_FACE, ChartChecks, FaceChecks, white_relative_variance  # noqa: F401
from .measurement import Measurement, named_argument
from .replicates import region_values

__all__ = ["REFERENCE_SPP_FACTOR", "SPP_CHART", "SPP_FACE", "SIZE_FACE",
           "ILLUMINANCE_DEFAULT_LUX", "Measurement", "Comparison", "scene_kind", "measure", "measure_spectral",
           "values_of", "setting_notes", "compare"]

REFERENCE_SPP_FACTOR = 4
"""A reference is rendered at this many times the check's spp (with its own seed,
:func:`~skinrender.testing.reference.reference_seed`): its
own noise then moves every later check's z by at most ``1/√5`` of its deviation (``1/√2`` at equal spp), so that
one unlucky reference does not raise the false-alarm rate of all the checks against it, as Mitsuba's high-spp
references do not."""

SIZE_FACE = 64
"""Image side of a face check unless given, pixels: a reference of ~60 kB."""

ILLUMINANCE_DEFAULT_LUX = 500.0
"""A chart's illuminance through an ``imager`` unless given, lx (every door's:
:data:`skinrender.rendering.request.ILLUMINANCE_DEFAULT`)."""


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


def _planckian(spec, name: str) -> float:
    from ..model.illuminant import illuminant

    light = named_argument(name, illuminant, spec)
    if light.temperature is None:
        raise SkinrenderError(f"{name}: rendering needs a Planckian illuminant (kelvin, A or H), got {light}")
    return float(light.temperature)


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
    from ..rendering.kinds import by_kind, scene_kind
    from ..rendering.settings import SEED_MAX, SPP_MAX

    kind = scene_kind(scene).name
    checks = by_kind(scene, chart=ChartChecks, face=FaceChecks)(scene, physics, skin, size, imager, illuminance)
    several = isinstance(camera, (list, tuple))
    cams = [named_argument("camera", camera_of, one) for one in (camera if several else [camera])]
    if not cams:
        raise SkinrenderError("camera: name at least one camera")
    for cam in cams:
        named_argument("camera", cam.sensitivities)
    p, c = _planckian(prevailing, "prevailing"), _planckian(calibration, "calibration")
    spp = _integer(checks.spp_default if spp is None else spp, "spp", 1, SPP_MAX + 1)
    seed = _integer(seed, "seed", 0, SEED_MAX + 1)  # the bound of every front door
    renders = seed if render_seed is None else _integer(render_seed, "render_seed", 0, SEED_MAX + 1)
    size = SIZE_FACE if size is None else size
    if several:
        found = checks.spectral(cams, p, c, spp * factor, renders, physics, skin, imager, illuminance, size, variant)
    else:
        found = [checks.one(cams[0], p, c, spp * factor, renders, physics, skin, imager, illuminance, size, variant)]
    from .. import __version__

    out = []
    for cam, one in zip(cams, found):
        settings = {"kind": kind, "scene": checks.name(one), **camera_attributes(cam), "prevailing_K": p,
                    "calibration_K": c, "spp_requested": spp, "seed": seed,
                    **({} if render_seed is None else {"reference_seed": renders}), **one.settings,
                    "skinrender_version": __version__}
        out.append(Measurement(one.kind, one.image, one.labels, one.channels, one.regions, one.items, one.mean,
                               one.standard_error, one.dof, settings, checks.chart))
    return out if several else out[0]


def measure_spectral(kind: str, scene, cameras: list, prevailing: float, calibration: float, spp: int, seed: int,
                     physics: str | None, skin: str | None, imager: str | None, illuminance: float | None, size: int,
                     variant: str | None) -> list:
    """
    One :class:`Measurement` per camera of ``cameras`` from one spectral render of ``scene`` (a chart, or a face
    spec; a face: one per replicate seed) with :data:`~skinrender.rendering.bands.BANDS_DEFAULT` (arguments as
    :func:`measure`; a chart through an ``imager`` is refused: its sensor records a camera's channels). The
    settings add ``spectral_bands_nm``, so that a reference made one render per camera is told apart in a
    failure's notes. ``kind``: the scene's (its checks are the kind's; kept for callers that name it).
    """
    from ..rendering.kinds import by_kind

    checks = by_kind(scene, chart=ChartChecks, face=FaceChecks)(scene, physics, skin, None, imager, illuminance)
    return checks.spectral(cameras, prevailing, calibration, spp, seed, physics, skin, imager, illuminance, size,
                           variant)


def values_of(kind: str, image: NDArrayFloat, labels: NDArrayFloat | None, regions, scene=None) -> NDArrayFloat:
    """The compared means of a stored image: a chart's patch means (``scene`` its chart) or a face's region means
    and skin NCC (``regions`` ``{name: label}``), in :attr:`Measurement.items` order."""
    if labels is None:  # a chart's (a face's image has its labels)
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
