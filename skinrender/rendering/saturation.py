"""
Saturated patches are not evidence
==================================

A pixel whose charge reaches the full well, or whose code reaches the top of the ADC's range, records the
sensor's ceiling, not the light: Eq. 4 is linear and says nothing there. A patch channel that saturates is
therefore left out of the sensor validation's tests
(:func:`~skinrender.rendering.sensor_validation.validate_imaged`): a chart that saturates entirely would
otherwise pass whatever the light (every saturated value equals its saturated prediction), and one that saturates
in part fails where the render's spread meets the ceiling (the model's mean at the analytic electrons is not the
mean of the clipped pixels). Its verdict is at best inconclusive, with the reason and the exposure that would
not saturate.

-   :data:`SATURATION_SIGMAS`, :func:`saturated_values`: which patch channels reach the ceiling.
-   :func:`unsaturated_exposure`: the longest exposure at which none does.
-   :func:`saturation_verdict`: the check in words (``not_applicable`` where nothing saturates).

Units: electrons e⁻, DN, exposure s, illuminance lx.
"""

from __future__ import annotations

import math

import numpy as np

from ..evaluation.verdict import Verdict
from ..hints import NDArrayFloat
from ..model.imager import Imager

__all__ = ["SATURATION_SIGMAS", "saturated_values", "unsaturated_exposure", "saturation_verdict"]

SATURATION_SIGMAS = 5.0
"""A pixel counts as saturating where its expected charge plus this many standard deviations of its noise (shot and
read, e⁻) reaches the ceiling (a one-sided normal tail of 3e-7 per pixel: over a 24-patch chart's 8 000 pixels and
three channels, a saturated pixel in an unflagged patch channel less than once in a hundred charts)."""


def _ceiling_e(im: Imager) -> float:
    """The charge, e⁻, at which a pixel stops following the light: the full well, or the ADC's top code."""
    adc = (im.max_dn - im.black_level_dn) / im.gain_dn_per_e
    return float(min(im.full_well_e, adc))


def _reach(electrons: NDArrayFloat, im: Imager) -> NDArrayFloat:
    """Each charge (e⁻) plus :data:`SATURATION_SIGMAS` of its shot and read noise, e⁻."""
    e = np.maximum(np.asarray(electrons, dtype=np.float64), 0.0)
    return e + SATURATION_SIGMAS * np.sqrt(e + im.read_noise_e**2)


def saturated_values(im: Imager, pixel_electrons: list[NDArrayFloat], expected: NDArrayFloat) -> NDArrayFloat:
    """
    Which patch channels saturate, ``(patches, 3)`` booleans.

    Parameters
    ----------
    im
        The imager (its full well, e⁻, and ADC range).
    pixel_electrons
        Per patch, its pixels' expected charges ``(pixels, 3)``, e⁻ (the render's, noise-free: photo plus dark).
    expected
        Each patch channel's analytic charge (Eq. 4's), e⁻, ``(patches, 3)``.

    Examples
    --------
    >>> from skinrender.model.imager import imager
    >>> im = imager("sony-imx174")  # full well 32 691 e⁻
    >>> saturated_values(im, [np.array([[1e3, 3.2e4, 3.3e4]])], np.array([[1e3, 3e4, 3.3e4]])).tolist()
    [[False, True, True]]
    """
    ceiling = _ceiling_e(im)
    brightest = np.array([np.max(_reach(p, im), axis=0) for p in pixel_electrons])
    return (brightest >= ceiling) | (_reach(expected, im) >= ceiling)


def unsaturated_exposure(im: Imager, brightest_e: float, exposure_s: float) -> float:
    """
    The longest exposure, s, at which a pixel expecting ``brightest_e`` e⁻ at ``exposure_s`` stays
    :data:`SATURATION_SIGMAS` below the ceiling (the charge scales with the exposure; rounded down to 3 digits).

    >>> from skinrender.model.imager import imager
    >>> unsaturated_exposure(imager("sony-imx174"), 4e4, 0.02)
    0.0159
    """
    ceiling, read = _ceiling_e(im), im.read_noise_e
    root = (-SATURATION_SIGMAS + math.sqrt(SATURATION_SIGMAS**2 + 4 * (ceiling + read**2))) / 2
    allowed = root**2 - read**2  # x + k·√(x + r²) = ceiling
    return _round_down(exposure_s * allowed / brightest_e)


def _round_down(value: float) -> float:
    """``value`` > 0 rounded down to three significant digits."""
    digits = 2 - math.floor(math.log10(value))
    return math.floor(value * 10**digits) / 10**digits


def saturation_verdict(saturated: NDArrayFloat, names: list[str], channels: list[str], im: Imager,
                       brightest_e: float, exposure_s: float, illuminance_lux: float, auto: bool) -> Verdict:
    """
    The check that no tested value saturates: ``not_applicable`` where none does, else ``inconclusive`` naming the
    patch channels left out and the ``--exposure`` (and, with a fixed exposure, the ``--illuminance``) at which
    none would; ``details``: ``saturated`` (``["patch channel", …]``), ``exposure_max_s``,
    ``illuminance_max_lux`` (``None`` with an ``auto`` exposure, which follows the light).
    """
    test = (f"no patch channel's pixels within {SATURATION_SIGMAS:g} standard deviations of the full well "
            f"({im.full_well_e:g} e⁻) or the ADC's top code ({im.max_dn:g} DN): a saturated pixel records the "
            "sensor's ceiling, not the light")
    which = [f"{names[i]} {channels[k]}" for i, k in zip(*np.nonzero(saturated))]
    if not which:
        return Verdict("saturation", "not_applicable", 0.0, test, reason="no patch channel saturates",
                       details={"saturated": []})
    t_max = unsaturated_exposure(im, brightest_e, exposure_s)
    lux_max = None if auto else _round_down(illuminance_lux * t_max / exposure_s)
    shown = ", ".join(which[:4]) + (f" and {len(which) - 4} more" if len(which) > 4 else "")
    advice = f"--exposure {t_max:g}" + ("" if lux_max is None else f" or --illuminance {lux_max:g}")
    reason = (f"{len(which)} patch channel{'s saturate' if len(which) > 1 else ' saturates'} ({shown}): a saturated pixel is not "
              f"evidence about Eq. 4, so they are left out of the tests; {advice} would not saturate")
    return Verdict("saturation", "inconclusive", 0.0, test, reason=reason,
                   details={"saturated": which, "exposure_max_s": t_max, "illuminance_max_lux": lux_max})
