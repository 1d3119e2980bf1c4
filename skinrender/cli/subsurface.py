"""
``--physics subsurface`` and ``subsurface-volume`` on a chart (``render``, ``validate``, ``detect``)
====================================================================================================

The chart commands take ``--physics direct`` (the default), ``subsurface`` or
``subsurface-volume`` (the chart's registry of effects,
:mod:`skinrender.rendering.chart_effects`, whose subsurface levels refuse what
does not go with them where the request is built): the chart's skin patches
as the skin model's layers, lit by a uniform sky, their flat slab's angular
reflectance as a BSDF (:mod:`skinrender.rendering.slab_chart`) or media under
a dielectric boundary, path traced
(:mod:`skinrender.rendering.subsurface_chart`), each checked by ``validate``
against Eq. 4 of its slab's adding-doubling reflectance.

-   :func:`subsurface_keys`: what the JSON of a subsurface chart adds (:mod:`skinrender.rendering.chart_document`).
-   :func:`subsurface_lines`: the text lines it adds.
"""

from __future__ import annotations

__all__ = ["subsurface_keys", "subsurface_lines"]

from ..rendering.chart_document import subsurface_keys  # noqa: E402 - moved to the rendering layer (re-exported)


def subsurface_lines(rendering) -> list[str]:
    """The text lines a subsurface chart adds (none at ``direct``): its skin patches' layers and their fits."""
    if "skin_model" not in rendering.info:
        return []
    rows = [row for row in rendering.info["skin_model"] if row is not None]
    fits = [row["fit_rms"] for row in rows if row["fit_rms"] is not None]
    fitted = f", {len(fits)} fitted to their measured reflectance (RMS ≤ {max(fits):.4f})" if fits else ""
    physics, how = rendering.info["physics"], rendering.info["slabs_as"]
    return [f"{physics}: {len(rows)} skin patches as the skin model's layers{fitted}, {how}, under a uniform sky; "
            f"analytic: each slab's adding-doubling reflectance through Eq. 4"]
