"""
Validating a spectral render against Eq. 4 and against a direct render
======================================================================

A chart rendered once spectrally (:mod:`skinrender.rendering.spectral_chart`)
and seen through a camera must give what Eq. 4 gives for that camera, and what
a render of that camera gives. :func:`validate_spectral` checks both:

-   **against Eq. 4** (:func:`skinrender.rendering.validation.validate` on the
    projected render): every patch channel shown within ``tolerance`` of Eq. 4
    of the camera's own curves (the verdict: pass, fail or inconclusive), and
    the difference test beside it, which allows, beside the float32 floor, the
    *basis error*: Eq. 4 of the camera as the bands see it (its curves at the
    bands, linearly interpolated) minus Eq. 4 of its curves, computed exactly
    per patch. For a camera given on the band grid it is 0; for a gbell every
    1 nm against 5 nm bands it is ~0.2 % (measured, ``docs/spectral.md``), far
    inside a 1 % tolerance, which holds the whole error.
-   **against a direct render** of the same camera at independent seeds
    (``seed + 2``, and ``seed + 3`` for its calibration white): the difference
    of the two renders' patch means over their combined standard error
    (:func:`~skinrender.rendering.patch_errors.error_law` of each), beyond the
    basis error and both float32 floors, at family-wise α (Šidák): it must not
    fire.

-   :func:`validate_spectral`, :class:`SpectralValidation`.

Units: output units (255 for white at p = c); temperatures K; bands nm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..evaluation.verdict import ALPHA_DIFFERENCE, ALPHA_EQUIVALENCE, Verdict
from ..hints import NDArrayFloat
from ..model.camera import camera
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .agreement import TOLERANCE_DEFAULT, agreement, check_tolerance
from .balance import Rendering, render
from .request import planckian
from .bands import BANDS_DEFAULT, bands_text
from .patch_errors import SKEW_MAX, error_law
from .scene import load_chart_scene
from .settings import RenderSettings
from .validation import Validation, analytic_reference, float32_floor, validate

__all__ = ["SpectralValidation", "validate_spectral"]


@dataclass(frozen=True)
class SpectralValidation:
    """
    A spectral render seen through a camera, checked against Eq. 4 and a direct render.

    Attributes
    ----------
    validation
        The projected render against Eq. 4 (:class:`~skinrender.rendering.validation.Validation`: ``verdict``,
        ``difference``, ``bound``…), its difference test allowing :attr:`basis_error`.
    basis_error
        Per patch and channel, Eq. 4 of the camera as the bands see it minus Eq. 4 of its curves, output units.
    spectral
        The :class:`~skinrender.rendering.spectral_image.SpectralImage` rendered.
    direct
        The direct render of the camera (``None`` when not asked).
    direct_difference
        The spectral − direct difference test (``None`` without a direct render).
    direct_z
        Per patch and channel, (spectral − direct) over their combined standard error.
    """

    validation: Validation
    basis_error: NDArrayFloat
    spectral: object
    direct: Rendering | None = None
    """Asked with ``direct=True`` (the default)."""
    direct_difference: Verdict | None = None
    direct_z: NDArrayFloat | None = None  # (patches, 3)

    @property
    def verdict(self) -> Verdict:
        """The verdict against Eq. 4 (:attr:`validation`'s)."""
        return self.validation.verdict

    @property
    def basis_relative(self) -> float:
        """The largest basis error relative to Eq. 4 of a lit patch channel (dark ones against 1 % of white)."""
        from .agreement import tolerance_scale

        return float(np.max(np.abs(self.basis_error) / tolerance_scale(self.validation.analytic)))

    def document(self) -> dict:
        """The JSON keys a spectral validation adds: ``spectral`` (bands, basis error, the direct comparison)."""
        out = {"bands_nm": bands_text(self.spectral.bands), "bands": int(self.spectral.bands.size), "basis": "hat",
               "render_s": self.spectral.seconds, "basis_rel_error": self.basis_relative,
               "direct": None}
        if self.direct is not None:
            out["direct"] = {"seed": self.direct.raw[0].seed, "spp": self.direct.raw[0].spp,
                             "elapsed_s": self.direct.seconds, "difference": self.direct_difference.document(),
                             "max_abs_z": float(np.max(np.abs(self.direct_z)))}
        return out


def validate_spectral(
    scene,
    camera_,
    prevailing,
    calibration,
    *,
    bands: WavelengthGrid | str = BANDS_DEFAULT,
    spectral=None,
    direct: bool = True,
    grid: WavelengthGrid = GRID_DEFAULT,
    normalization: str = "white", knee: bool = False, tolerance: float = TOLERANCE_DEFAULT,
    alpha: float = ALPHA_EQUIVALENCE, alpha_difference: float = ALPHA_DIFFERENCE,
    settings: RenderSettings | None = None,
    **options,
) -> SpectralValidation:
    """
    Render a chart spectrally (or take ``spectral``), see it through ``camera_`` and check it against Eq. 4
    and, with ``direct``, against a direct render of the camera (module docstring).

    Parameters
    ----------
    scene, camera_, prevailing, calibration
        A chart, a camera, the lights (kelvin, ``A``, ``H``).
    bands
        The band grid (``START:END:STEP`` nm; default 400:700:5).
    spectral
        A :class:`~skinrender.rendering.spectral_image.SpectralImage` of the chart at ``prevailing`` to check instead
        of rendering one.
    direct
        Also render the camera directly (seeds ``seed + 2``, ``seed + 3``) and test the difference.
    grid, normalization, knee, tolerance, alpha, alpha_difference
        As :func:`~skinrender.rendering.validation.validate`.
    settings, options
        :class:`~skinrender.rendering.settings.RenderSettings` or its fields (both renders take the same spp).

    Examples
    --------
    >>> v = validate_spectral("macbeth", "gbell:9@450,540,610", 2856, 5900, spp=64)  # doctest: +SKIP
    >>> v.verdict.outcome, v.direct_difference.outcome  # doctest: +SKIP
    ('pass', 'pass')
    """
    from .spectral_chart import render_chart_spectral

    tolerance = check_tolerance(tolerance, "tolerance")
    settings = RenderSettings.of(settings, **options)
    chart, cam = load_chart_scene(scene), camera(camera_)
    p, c = planckian(prevailing, "prevailing"), planckian(calibration, "calibration")
    if spectral is None:
        spectral = render_chart_spectral(chart, p, bands, settings, grid)
    rendering = spectral.through(cam, c, normalization=normalization, knee=knee)
    reflectance = chart.reflectances(grid)
    exact = analytic_reference(cam, reflectance, p, c, normalization, knee, grid)
    seen = analytic_reference(cam, reflectance, p, c, normalization, knee, grid, bands=spectral.bands)
    basis = seen - exact
    validation = validate(chart, cam, p, c, grid=grid, rendering=rendering, tolerance=tolerance, alpha=alpha,
                          alpha_difference=alpha_difference, allowance=basis)
    if not direct:
        return SpectralValidation(validation, basis, spectral)
    other = render(chart, cam, p, c, normalization, knee, settings.replace(seed=(settings.seed + 2) % 2**32), grid)
    sigma_direct, skew_direct = error_law(other, exact)
    sigma = np.sqrt(validation.sigma**2 + sigma_direct**2)
    skewness = np.maximum(np.abs(validation.skewness), np.abs(skew_direct))
    floor = 2 * float32_floor(cam, grid)[None, :] * np.abs(exact) + np.abs(basis)
    dof = float(np.min(rendering.patches.count) - 1)
    out = agreement(rendering.patches.mean, other.patches.mean, sigma, tolerance, other.raw[0].spp, dof, floor, alpha,
                    alpha_difference, "spectral − direct patch channel means", skewness=skewness, skew_max=SKEW_MAX)
    return SpectralValidation(validation, basis, spectral, other, out["difference"], out["z"])
