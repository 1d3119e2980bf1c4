"""
The Mitsuba scenes kept loaded between renders, and their release.

Chart renderers (:data:`~skinrender.rendering.renderer.RENDERERS_KEPT`), subsurface chart renderers and face
documents (:data:`~skinrender.rendering.face.render.LOADED_KEPT`) stay loaded so that renders sharing them
(seeds, replicates, levels of a ladder) skip the scene load and the kernel's compilation. Every loaded scene
has a cost for the renders of *other* scenes too (as we read it, Dr.Jit dispatches a render's calls to BSDFs,
emitters and media over every instance alive in the process, so each scene kept makes later kernels larger and
changes them, so that they are traced and compiled again). Measured on a 2-core
machine (``llvm_ad_spectral``; a 32 × 32 px face at 16 spp after six chart renders that stay loaded): a repeated
face render took 0.17 s instead of 0.015 s, the first at a new size 0.55 s instead of 0.044 s.

A long-lived process that moves on to other work (a notebook, a test session, a service) calls
:func:`release_scenes` between tasks; the next render of a released scene loads it again and, with the same seed,
draws the same samples (its kernel, compiled again, may round a pixel differently in float32's last bits: within
:data:`~skinrender.rendering.validation.FLOAT32_FLOOR`).
"""

from __future__ import annotations

__all__ = ["release_scenes"]


def release_scenes() -> int:
    """
    Release every Mitsuba scene the rendering caches keep loaded (charts, subsurface charts, faces).

    Results already returned are unaffected (they hold arrays, not scenes), and the next render loads what it
    needs again; nothing else is cleared (skin-model fits, datasets).

    Returns
    -------
    int
        How many cached renderers and documents were released.

    Examples
    --------
    >>> release_scenes() >= 0
    True
    """
    from . import renderer, spectral_chart, subsurface_chart
    from .face import render as face_render, revalue

    caches = (renderer._renderer, subsurface_chart._renderer, spectral_chart._renderer, face_render.load_document)
    released = sum(cache.cache_info().currsize for cache in caches)
    for cache in caches:
        cache.cache_clear()  # the scenes go with their last reference (no gc.collect: a full one costs ~0.1 s)
    return released + revalue.release()
