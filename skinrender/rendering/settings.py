"""
Render settings
===============

How a render samples, as one frozen object: samples per pixel, the sampler,
its seed, the Mitsuba variant and the channel passes. The command line makes
it once from ``--quality``, ``--spp``, ``--sampler``, ``--seed``,
``--variant`` and ``--channels``; the chart renderers take it whole
(:func:`~skinrender.rendering.balance.render`,
:func:`~skinrender.rendering.validation.validate`,
:func:`~skinrender.rendering.renderer.render_raw`, …), and from Python their
keyword arguments ``spp=``, ``seed=`` … make one (:meth:`RenderSettings.of`).

-   :class:`RenderSettings`: the five settings, checked.
-   :data:`SEED_MAX`, :data:`SPP_MAX`, :func:`check_seed`, :func:`seed_at`: the
    bounds of a seed and of spp, the same through every front door (the command
    line, ``skinrender.render``/``validate``, the pytest plugin), and the one
    rule for the seeds a render derives from its seed.
-   :data:`SAMPLERS`, :data:`CHANNEL_GROUPINGS`, :data:`QUALITY_PRESETS`: the
    method tables their names come from.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from ..errors import SkinrenderError
from ..methods import validate_method
from ..model.imager import is_integer

__all__ = ["SAMPLERS", "CHANNEL_GROUPINGS", "QUALITY_PRESETS", "sampler_independent", "sampler_stratified",
           "sampler_multijitter", "sampler_orthogonal", "sampler_ldsampler", "passes_auto", "passes_together",
           "passes_separate", "CHANNELS_DEFAULT", "FWHM_SEPARATE", "CHANNEL_AREA_RATIO_SEPARATE", "SEED_MAX", "SPP_MAX", "check_seed", "seed_at",
           "RenderSettings"]

SEED_MAX = 2**32 - 2
"""Largest seed a render takes, through every front door: Mitsuba's seeds are 32-bit and a chart's calibration
render takes ``seed + 1`` (:func:`seed_at`)."""

SPP_MAX = 1 << 20
"""Most samples per pixel a render may ask for (the reference preset uses 4096)."""


def check_seed(seed, name: str = "seed") -> int:
    """
    ``seed`` as an int if it is an integer in [0, :data:`SEED_MAX`], else a one-line error naming ``name`` (its
    ``role``: ``seed``).

    >>> check_seed(7)
    7
    """
    if not (is_integer(seed) and 0 <= seed <= SEED_MAX):
        raise SkinrenderError(f"{name} must be an integer in [0, 2^32) and at most {SEED_MAX} (Mitsuba's seeds are "
                              f"32-bit, and a chart's calibration render uses seed + 1), got {seed!r}", role="seed")
    return int(seed)


def seed_at(seed: int, offset: int) -> int:
    """
    The seed of a render ``offset`` after one at ``seed``: ``seed + offset`` modulo 2³² (a chart's calibration
    render: offset 1; replicates and the gamut's lights: 0, 1, 2, …), the one rule for derived seeds.

    >>> seed_at(5, 1), seed_at(2**32 - 2, 3)
    (6, 1)
    """
    return (int(seed) + int(offset)) % 2**32

def _at_least(spp: float) -> int:
    return max(1, math.ceil(spp))


def sampler_independent(spp: float) -> tuple[int, str]:
    """independent uniform samples

    ``(count, how)``: the samples per pixel to ask for at least ``spp`` (rounded up), and how it was rounded, in
    words for a reason (``""``: to an integer)."""
    return _at_least(spp), ""


def sampler_stratified(spp: float) -> tuple[int, str]:
    """stratified samples

    ``(count, how)`` as :func:`sampler_independent`."""
    return _at_least(spp), ""


def sampler_multijitter(spp: float) -> tuple[int, str]:
    """correlated multi-jittered samples (default; far better on flat patches)

    ``(count, how)`` as :func:`sampler_independent`, the count rounded up to the square of an even number: the
    counts multijitter samples exactly, whose bounds fall alike (:mod:`~skinrender.rendering.spp_choice`)."""
    count = _at_least(spp)
    side = math.isqrt(count - 1) + 1  # the smallest side with side² ≥ count
    side += side % 2
    return side * side, ", up to an even square"


def sampler_orthogonal(spp: float) -> tuple[int, str]:
    """orthogonal-array samples

    ``(count, how)`` as :func:`sampler_independent`."""
    return _at_least(spp), ""


def sampler_ldsampler(spp: float) -> tuple[int, str]:
    """low-discrepancy (Sobol-type) samples

    ``(count, how)`` as :func:`sampler_independent`."""
    return _at_least(spp), ""


SAMPLERS = {"independent": sampler_independent, "stratified": sampler_stratified,
            "multijitter": sampler_multijitter, "orthogonal": sampler_orthogonal, "ldsampler": sampler_ldsampler}
"""Mitsuba samplers (the name is Mitsuba's plugin), name → the function ``(spp) → (count, how)`` of the samples
per pixel to ask it for (:func:`~skinrender.rendering.spp_choice.square_spp` dispatches)."""

CHANNEL_AREA_RATIO_SEPARATE = 4.0
"""With ``channels="auto"``, render channels separately when the largest
channel area ∫ s_k dλ exceeds the smallest by this factor."""

FWHM_SEPARATE = 50.0
"""With ``channels="auto"``, render gbell channels of at most this FWHM (nm)
separately: three narrow, disjoint channels in one pass share the wavelength
samples three ways and their patch means get heavy-tailed at low spp
(measured: 5σ excursions at 64 spp for sensor 3)."""


def passes_auto(cam, grid) -> bool:
    """separate passes for the impulse, narrow gbell or very unequal channels, else one

    Whether ``cam``'s channels are rendered in separate passes on ``grid``: the impulse, a gbell of at most
    :data:`FWHM_SEPARATE` nm, or channel areas more than :data:`CHANNEL_AREA_RATIO_SEPARATE` apart."""
    if cam.kind == "impulse" or (cam.kind == "gbell" and cam.fwhm <= FWHM_SEPARATE):
        return True
    areas = cam.sensitivities(grid).sum(axis=1)
    return bool(areas.max() > CHANNEL_AREA_RATIO_SEPARATE * areas.min())


def passes_together(cam, grid) -> bool:
    """the three channels in one pass"""
    return False


def passes_separate(cam, grid) -> bool:
    """one pass per channel"""
    return True


CHANNEL_GROUPINGS = {"auto": passes_auto, "together": passes_together, "separate": passes_separate}
CHANNELS_DEFAULT = "auto"
"""The channel grouping unless one is named (a spectral render, one pass of bands, takes no other)."""
"""How the three channels are rendered, name → the function ``(camera, grid) → bool``: whether each channel has
a pass of its own (:func:`~skinrender.rendering.renderer.channels_separate` dispatches)."""

QUALITY_PRESETS = {
    "draft": {"spp": 16, "sampler": "multijitter"},
    "standard": {"spp": 256, "sampler": "multijitter"},
    "reference": {"spp": 4096, "sampler": "multijitter"},
}
"""Named settings; their expected error and time are measured by
``skinrender bench render`` (docs/speed.md)."""

@dataclass(frozen=True)
class RenderSettings:
    """How a render samples: what every render takes beside its scene, camera and lights.

    Parameters
    ----------
    spp
        Samples per pixel, an integer in [1, :data:`SPP_MAX`] (multijitter rounds it up to a product of two integers; a render
        reports the count it used).
    seed
        Sampler seed, an integer in [0, :data:`SEED_MAX`] (Mitsuba's seeds are 32-bit): the same seed gives the
        same image. A chart's calibration render takes ``seed + 1`` (:func:`seed_at`).
    sampler
        One of :data:`SAMPLERS`.
    variant
        A Mitsuba variant (``llvm_ad_spectral``, ``cuda_ad_spectral``, ``scalar_spectral``), or ``None`` for
        the fastest that works here (chosen when the render starts).
    channels
        One of :data:`CHANNEL_GROUPINGS`.

    Raises
    ------
    SkinrenderError
        A setting out of its range, its ``role`` the setting's name.

    Examples
    --------
    >>> RenderSettings(spp=16, seed=3)
    RenderSettings(spp=16, seed=3, sampler='multijitter', variant=None, channels='auto')
    >>> RenderSettings.preset("draft", seed=2).spp
    16
    >>> RenderSettings.of(RenderSettings(spp=16), seed=5)
    RenderSettings(spp=16, seed=5, sampler='multijitter', variant=None, channels='auto')
    """

    spp: int = 256
    seed: int = 0
    sampler: str = "multijitter"
    variant: str | None = None
    channels: str = CHANNELS_DEFAULT

    def __post_init__(self) -> None:
        if not (is_integer(self.spp) and 1 <= self.spp <= SPP_MAX):
            raise SkinrenderError(f"spp must be a positive integer (at most {SPP_MAX}), got {self.spp!r}", role="spp")
        check_seed(self.seed)
        validate_method(self.sampler, SAMPLERS, "sampler", role="sampler")
        validate_method(self.channels, CHANNEL_GROUPINGS, "channels", role="channels")
        if self.variant is not None and not isinstance(self.variant, str):
            raise SkinrenderError(f"variant must be a Mitsuba variant's name or None, got {self.variant!r}",
                                  role="variant")
        object.__setattr__(self, "spp", int(self.spp))
        object.__setattr__(self, "seed", int(self.seed))

    @classmethod
    def preset(cls, quality: str = "standard", **changes) -> RenderSettings:
        """The settings of a :data:`QUALITY_PRESETS` name (its spp and sampler), with ``changes``."""
        validate_method(quality, QUALITY_PRESETS, "quality", role="quality")
        return cls(**{**QUALITY_PRESETS[quality], **changes})

    @classmethod
    def of(cls, settings: RenderSettings | None = None, **fields) -> RenderSettings:
        """
        ``settings`` (the defaults where ``None``) with ``fields`` (``spp``, ``seed``, ``sampler``, ``variant``,
        ``channels``) replaced: what a function that takes ``settings`` and the settings' keyword arguments
        renders with. Any other keyword is refused, naming it.
        """
        names = [field.name for field in dataclasses.fields(cls)]
        unknown = sorted(set(fields) - set(names))
        if unknown:
            raise SkinrenderError(f"{', '.join(unknown)}: not a render setting; the settings: {', '.join(names)}")
        if settings is None:
            return cls(**fields)
        if not isinstance(settings, cls):
            raise SkinrenderError(f"settings must be a RenderSettings, got {settings!r}", role="settings")
        return dataclasses.replace(settings, **fields) if fields else settings

    def replace(self, **changes) -> RenderSettings:
        """A copy with ``changes`` (checked again)."""
        return dataclasses.replace(self, **changes)

    @property
    def key(self) -> tuple:
        """What a loaded renderer depends on (all but the seed, which each render takes)."""
        return self.spp, self.sampler, self.variant, self.channels
