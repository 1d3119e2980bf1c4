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
-   :data:`SAMPLERS`, :data:`CHANNEL_GROUPINGS`, :data:`QUALITY_PRESETS`: the
    method tables their names come from.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from ..errors import SkinrenderError
from ..methods import validate_method
from ..model.imager import is_integer

__all__ = ["SAMPLERS", "CHANNEL_GROUPINGS", "QUALITY_PRESETS", "RenderSettings"]

SAMPLERS = {
    "independent": "independent uniform samples",
    "stratified": "stratified samples",
    "multijitter": "correlated multi-jittered samples (default; far better on flat patches)",
    "orthogonal": "orthogonal-array samples",
    "ldsampler": "low-discrepancy (Sobol-type) samples",
}
"""Mitsuba samplers, name → meaning."""

CHANNEL_GROUPINGS = {
    "auto": "separate passes for the impulse, narrow gbell or very unequal channels, else one",
    "together": "the three channels in one pass",
    "separate": "one pass per channel",
}
"""How the three channels are rendered, name → meaning."""

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
        Samples per pixel, an integer ≥ 1 (multijitter rounds it up to a product of two integers; a render
        reports the count it used).
    seed
        Sampler seed, an integer in [0, 2³²) (Mitsuba's seeds are 32-bit): the same seed gives the same image. A chart's
        calibration render takes ``seed + 1``.
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
    channels: str = "auto"

    def __post_init__(self) -> None:
        if not (is_integer(self.spp) and self.spp >= 1):
            raise SkinrenderError(f"spp must be a positive integer, got {self.spp!r}", role="spp")
        if not (is_integer(self.seed) and 0 <= self.seed < 2**32):
            raise SkinrenderError(f"seed must be an integer in [0, 2^32) (Mitsuba's seeds are 32-bit), got "
                                  f"{self.seed!r}", role="seed")
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
