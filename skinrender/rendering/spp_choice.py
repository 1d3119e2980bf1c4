"""
The samples a tolerance takes
=============================

``validate --spp auto --tolerance T``: the smallest samples per pixel at which a
chart's validation is expected to pass, from two cheap pilot renders.

-   :data:`PILOT_SPP`, :data:`SPP_AUTO_MARGIN`, :data:`EXPONENT_RANGE`, :data:`EXPONENT_RANGES`.
-   :func:`bound_exponent`: how fast the bound falls between two spp.
-   :func:`spp_for_tolerance`: the pilots, the fit and the spp chosen; :func:`is_auto`: ``spp`` asks for it
    (``validate --spp auto``, ``skinrender.validate(…, spp="auto", tolerance=T)``: both through
    :meth:`~skinrender.rendering.kinds.ChartKind.choose_spp`).

Notes
-----
The equivalence bound (the smallest tolerance that would pass,
:mod:`skinrender.rendering.agreement`) of a Monte Carlo render falls as
``spp^-a``: ``a = ½`` for independent samples, more for the stratified
``multijitter`` sampler (measured 1.2–1.4 on the Macbeth chart between 16 and
1024 spp, docs/verdicts.md). The exponent is fitted to the two pilots and held
within :data:`EXPONENT_RANGE`; the spp where the fitted bound meets the
tolerance is multiplied by :data:`SPP_AUTO_MARGIN` (the bound of one render
scatters about its expectation). The ``independent`` sampler's exponent is ½,
not fitted (:data:`EXPONENT_RANGES`): its standard error falls as ``spp^-½``
exactly, and what falls faster between two pilots (the widening for a skewed
mean, noise) is not to be extrapolated — measured on the ``skin_patches``
chart at ``subsurface-volume``: pilots 16 and 64 spp fall as ``spp^-0.60``, whose
choice (286 spp) was inconclusive at 0.05 (bound 0.0524). ``multijitter`` (which Mitsuba rounds to a
product of two integers) stratifies a count that is a multiple of 4 far better
(measured on the Macbeth chart, gbell:9, 3300 K / 4800 K, two seeds each:
bounds 0.8–1.4e-3 at 132, 144, 156, 168, 196 spp, against 3–6e-3 at 121, 143,
169, 182, 195, 225 spp; why is not established — Mitsuba's spectral variants
draw four wavelengths per sample), so its counts are rounded up to the square
of an even number (:func:`square_spp`), as the pilots' are. Through an image
sensor the bound has a floor
(the sensor's noise, which spp leaves alone): there the pilot's own
``spp_needed`` (:func:`~skinrender.rendering.sensor_validation.validate_imaged`)
is used, and a tolerance below the floor is refused.

Units: spp (samples per pixel), tolerances and bounds relative, seconds s.
"""

from __future__ import annotations

import math

from ..errors import SkinrenderError
from ..methods import method_of
from .settings import SAMPLERS

__all__ = ["PILOT_SPP", "SPP_AUTO_MARGIN", "EXPONENT_RANGE", "EXPONENT_RANGES", "is_auto", "square_spp",
           "bound_exponent", "spp_for_tolerance"]

PILOT_SPP = (16, 64)
"""The pilot renders' samples per pixel (the draft preset and 4 × it: ~0.2 and ~0.5 s on the Macbeth chart)."""

SPP_AUTO_MARGIN = 1.25
"""The spp where the fitted bound meets the tolerance is multiplied by this (the bound scatters by ~10–20 %
between seeds)."""

EXPONENT_RANGE = (0.5, 1.5)
"""The fitted exponent ``a`` of ``bound ∝ spp^-a`` is held within this range (½: independent samples)."""

EXPONENT_RANGES = {"independent": (0.5, 0.5)}
"""Sampler → the range its fitted exponent is held within, where not :data:`EXPONENT_RANGE`: independent samples'
standard error falls as ``spp^-½`` (module notes)."""


def is_auto(spp) -> bool:
    """
    Whether ``spp`` asks for the smallest spp expected to pass (``auto``, any case), not a number.

    >>> is_auto("auto"), is_auto(" AUTO "), is_auto(64), is_auto(None)
    (True, True, False, False)
    """
    return isinstance(spp, str) and spp.strip().lower() == "auto"


def square_spp(spp: float, sampler: str = "multijitter") -> int:
    """
    ``spp`` rounded up to an integer, and for ``multijitter`` up to the square of an even number (module notes).

    >>> square_spp(127.3), square_spp(127.3, "independent"), square_spp(0.2), square_spp(200)
    (144, 128, 4, 256)
    """
    return _count(spp, sampler)[0]


def _count(spp: float, sampler: str) -> tuple[int, str]:
    """The sampler's ``(count, how)`` for ``spp`` (:data:`~skinrender.rendering.settings.SAMPLERS`)."""
    return method_of(sampler, SAMPLERS, "sampler")(spp)


def bound_exponent(spps: tuple[int, int], bounds: tuple[float, float], sampler: str = "multijitter") -> float:
    """
    The exponent ``a`` of ``bound ∝ spp^-a`` through two points, held within the ``sampler``'s range
    (:data:`EXPONENT_RANGES`, else :data:`EXPONENT_RANGE`).

    >>> bound_exponent((16, 64), (0.017, 0.0031))
    1.2...
    >>> bound_exponent((16, 64), (0.01, 0.02))  # the bound rose: noise; taken as ½
    0.5
    >>> bound_exponent((16, 64), (0.247, 0.107), "independent")  # 0.60 between the pilots; independent: ½
    0.5
    """
    low, high = EXPONENT_RANGES.get(sampler, EXPONENT_RANGE)
    (s1, s2), (b1, b2) = spps, bounds
    if not (b1 > 0 and b2 > 0 and s2 > s1):
        return low
    a = math.log(b1 / b2) / math.log(s2 / s1)
    return min(max(a, low), high)


def _named(name: str) -> dict:
    """A refusal's fields naming the tolerance: its ``role``, and the flag where ``name`` is one."""
    return {"role": "tolerance", "flag": name if name.startswith("--") else None}


def spp_for_tolerance(validate_at, tolerance: float, seed: int = 0, pilots: tuple[int, int] = PILOT_SPP,
                      spp_max: int | None = None, sampler: str = "multijitter", name: str = "--tolerance") -> dict:
    """
    The smallest spp expected to pass ``tolerance``.

    Parameters
    ----------
    validate_at
        ``validate_at(spp, seed)`` → a validation (``.bound``, ``.verdict``, ``.rendering.raw[0].spp`` and
        ``.rendering.seconds``; with ``.spp_reason`` and ``.spp_needed``, a validation through a sensor).
    tolerance
        The relative tolerance.
    seed
        The pilots use ``seed + 2`` and ``seed + 4`` (the validation itself ``seed`` and ``seed + 1``), so the
        choice does not pick the validation's own noise.
    spp_max
        Refuse (naming ``name``) a choice above this.
    sampler
        The sampler (``multijitter``: the count rounded up to a square, :func:`square_spp`).
    name
        How a refusal names the tolerance: ``--tolerance`` (the CLI's flag) or ``tolerance`` (the Python
        argument); its ``role`` is ``tolerance`` either way.

    Returns
    -------
    dict
        ``spp`` (chosen: never below the first pilot's, where nothing below was measured), ``pilots`` (``[{spp,
        bound, seconds}]``), ``exponent``, ``margin``, ``why`` (one line).
    """

    rows, runs = [], []
    for j, spp in enumerate(pilots):
        run = validate_at(spp, (seed + 2 + 2 * j) % (2**31))
        runs.append(run)
        rows.append({"spp": int(run.rendering.raw[0].spp), "bound": run.bound, "seconds": run.rendering.seconds})
    last = runs[-1]
    if hasattr(last, "spp_reason"):  # through a sensor: the bound has the sensor's floor
        if last.spp_needed is None:
            bound = " has no bound" if last.bound is None else f"'s bound is {last.bound:.3g}"  # None: saturated
            raise SkinrenderError(f"{name} {tolerance:g}: no spp is expected to pass it: {last.spp_reason} "
                                  f"(the {rows[-1]['spp']}-spp pilot{bound})", **_named(name))
        chosen = square_spp(last.spp_needed * SPP_AUTO_MARGIN, sampler)
        exponent = None
        why = (f"the {rows[-1]['spp']}-spp pilot's bound {last.bound:.3g} (sensor and render noise) is expected to "
               f"meet {tolerance:g} at {last.spp_needed} spp; × {SPP_AUTO_MARGIN:g} margin")
    else:
        exponent = bound_exponent((rows[0]["spp"], rows[1]["spp"]), (rows[0]["bound"], rows[1]["bound"]), sampler)
        at = rows[1]["spp"] * (rows[1]["bound"] / tolerance) ** (1 / exponent)
        chosen, how = _count(at * SPP_AUTO_MARGIN, sampler)
        why = (f"pilots at {rows[0]['spp']} and {rows[1]['spp']} spp gave bounds {rows[0]['bound']:.3g} and "
               f"{rows[1]['bound']:.3g} (falling as spp^-{exponent:.2f}); the bound is expected to meet {tolerance:g} "
               f"at {at:.0f} spp; × {SPP_AUTO_MARGIN:g} margin{how}")
    if chosen < rows[0]["spp"]:  # below the pilots nothing was measured: multijitter's variance rises faster
        chosen = rows[0]["spp"]   # than 1/spp there (a sensor's 64-spp pilot asked for 2 spp, which failed)
        why += f"; held at the first pilot's {chosen} spp (nothing below it measured)"
    if spp_max is not None and chosen > spp_max:
        raise SkinrenderError(f"{name} {tolerance:g}: about {chosen} spp would be needed ({why}), more than "
                              f"{spp_max} a render may take; ask for a larger tolerance", **_named(name))
    return {"spp": int(chosen), "pilots": rows, "exponent": exponent, "margin": SPP_AUTO_MARGIN, "why": why}
